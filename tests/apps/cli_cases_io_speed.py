# `plmap project` reads S1 and S2 side by side and writes binary maps on all cores (issue 15,
# item 1): the inputs must still be read by the rule of reading them one after the other (S2 in
# S1's dimension, S1's error first), and the file written must not depend on the thread count.
# Exec'd into cli_test.py's namespace (case, run, expect, expect_clean_error, WORK, ...).


def _bytes(name):
    with open(os.path.join(WORK, name), "rb") as f:
        return f.read()


@case
def project_reads_the_inputs_by_the_sequential_rule():
    polyline("s1.curve", segments=8, seed=4)
    polyline("s2.curve", segments=11, seed=4)
    run("convert", "s2.curve", "s2line.msh")  # a Gmsh file of line elements: S2 takes S1's dimension
    j = run_json("project", "s1.curve", "s2line.msh", "-o", "curves.plmapb", "--json")
    expect(j["dimension"] == 1 and j["regions"] > 0, f"curve onto Gmsh curve: {j}")
    grid("g.off", cells=3)
    write("bad1.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n")
    write("bad2.off", "OFF\n3 1 0\nx 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    # Both damaged: S1's error, as when S1 is read first.
    expect_clean_error(["project", "bad1.off", "bad2.off", "-o", "m.plmapb"], mention="bad1.off")
    expect_clean_error(["project", "g.off", "bad2.off", "-o", "m.plmapb"], mention="bad2.off:line 3")
    # A triangle surface as S2 of a curve: read as a curve (S1's dimension), which OFF is not
    # (not "1-dimensional but 2-dimensional", which reading both by their own format gives).
    expect_clean_error(["project", "s1.curve", "g.off", "-o", "m.plmapb"],
                       mention="g.off: the OFF format holds triangle surfaces, not curves")
    expect_clean_error(["project", "g.off", "s1.curve", "-o", "m.plmapb"],
                       mention="s1.curve: the plmap curve format holds curves, not triangle surfaces")
    identity_map("g.off", "g.plmap")
    expect_clean_error(["project", "g.off", "g.plmap", "-o", "m.plmapb"], mention="g.plmap")
    expect(not os.path.exists(os.path.join(WORK, "m.plmapb")), "a failed project left an output")


@case
def project_writes_the_same_binary_map_on_every_thread_count():
    grid("a.off", cells=12, jitter=0.15, seed=5)
    grid("b.off", cells=9, jitter=0.15, seed=6)
    outputs = []
    for threads in ("1", "2", "0"):
        name = f"t{threads}.plmapb"
        run("project", "a.off", "b.off", "-o", name, "--threads", threads)
        outputs.append(_bytes(name))
    expect(outputs[0] == outputs[1] == outputs[2], "the binary map differs between thread counts")
    j = run_json("info", "t0.plmapb", "--json")
    expect(j.get("regions", 0) > 0, f"info of the map written: {j}")
