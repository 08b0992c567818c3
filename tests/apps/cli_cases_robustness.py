# Command-line robustness (issue 12): outputs never replace inputs, numbers are checked before
# they reach the library, messages name what the user typed, temporaries do not outlive a write.
# Exec'd into cli_test.py's namespace (case, run, expect, expect_clean_error, WORK, ...).

import re
import signal
import socket
import time


def _read(name):
    with open(os.path.join(WORK, name), "rb") as f:
        return f.read()


def _expect_unchanged(name, before, what):
    expect(_read(name) == before, f"{what}: {name} was changed")


@case
def output_that_is_an_input_is_refused():
    s = grid("v.off", cells=2)
    surface = _read(s)
    line = expect_clean_error(["build", "identity", "v.off", "-o", "v.off"], code=64, mention="v.off")
    expect("input" in line, f"should say the output is an input: {line}")
    _expect_unchanged("v.off", surface, "build identity -o INPUT")
    grid("b.off", cells=3)
    target = _read("b.off")
    # the same file under another spelling, a symbolic link and a hard link
    os.symlink("v.off", os.path.join(WORK, "link.plmap"))
    os.link(os.path.join(WORK, "b.off"), os.path.join(WORK, "hard.plmap"))
    for output in ("./v.off", os.path.join(WORK, "v.off"), "link.plmap", "hard.plmap"):
        expect_clean_error(["project", "v.off", "b.off", "-o", output], code=64, mention=output)
    expect_clean_error(["project", "v.off", "b.off", "-o", "b.off"], code=64, mention="S2")
    _expect_unchanged("b.off", target, "project -o S2")
    _expect_unchanged("v.off", surface, "project -o S1")
    expect_clean_error(["build", "overlay", "v.off", "b.off", "-o", "hard.plmap"], code=64)
    expect_clean_error(["convert", "v.off", "./v.off"], code=64, mention="IN")
    # a map read by regions, draw and export is not replaced either
    m = identity_map("v.off", "m.plmap")
    saved = _read(m)
    os.link(os.path.join(WORK, m), os.path.join(WORK, "m.csv"))
    expect_clean_error(["regions", m, "-o", "m.csv"], code=64, mention="MAP")
    os.link(os.path.join(WORK, m), os.path.join(WORK, "m.svg"))
    expect_clean_error(["draw", m, "--view3d", "-o", "m.svg"], code=64, mention="MAP")
    os.makedirs(os.path.join(WORK, "vtk"))
    shutil.copy(os.path.join(WORK, m), os.path.join(WORK, "vtk", "graph.vtu"))
    expect_clean_error(["export", "vtk/graph.vtu", "-o", "vtk"], code=64, mention="graph.vtu")
    _expect_unchanged(m, saved, "regions/draw -o a link to the map")
    # an experiment's config inside its output directory would be overwritten by the copy
    os.makedirs(os.path.join(WORK, "results"))
    # (a build without the experiment runner, such as the sanitizer build, refuses every run)
    write("results/config.toml", "[experiment]\nname = \"x\"\n")
    _, err, _ = run("experiment", "run", "results/config.toml", "-o", "results", expect_code=64)
    if "no experiment runner" not in err:
        expect_clean_error(["experiment", "run", "results/config.toml", "-o", "results"], code=64,
                           mention="config.toml")
    # different files with the same content are not the same file
    shutil.copy(os.path.join(WORK, "v.off"), os.path.join(WORK, "copy.off"))
    run("build", "identity", "copy.off", "-o", "copy.plmap")


@case
def output_extension_of_another_kind_is_refused():
    s = grid("v.off", cells=2)
    m = identity_map(s, "m.plmap")
    refused = [
        (["build", "identity", s, "-o", "out.off"], ".off"),
        (["build", "refine", s, "-o", "out.stl"], ".stl"),
        (["build", "overlay", s, s, "-o", "out.ply"], ".ply"),
        (["project", s, s, "-o", "out.obj"], ".obj"),
        (["project", s, s, "-o", "out"], "without extension"),
        (["convert", s, "out.plmap"], "map file"),
        (["generate", "grid", "-o", "out.plmap"], "map file"),
        (["generate", "polyline", "-o", "out.svg"], ".svg"),
        (["regions", m, "-o", "out.plmap"], "map file"),
        (["regions", m, "-o", "out.off"], "surface file"),
        (["draw", m, "--view3d", "-o", "out.csv"], ".csv"),
        (["draw", m, "--view3d", "-o", "out.plmap"], "map file"),
    ]
    for args, mention in refused:
        expect_clean_error(args, code=64, mention=mention)
    os.makedirs(os.path.join(WORK, "dir.plmap"))
    expect_clean_error(["build", "identity", s, "-o", "dir.plmap"], code=64, mention="directory")
    stray = sorted(f for f in os.listdir(WORK) if f.startswith("out"))
    expect(not stray, f"refused commands wrote {stray}")
    # upper-case extensions are still the right kind
    run("build", "identity", s, "-o", "UPPER.PLMAP")


# Every command line with its required arguments, for the sweep over its numeric options.
_COMMANDS = {
    ("info",): ["x.off"],
    ("check",): ["x.plmap"],
    ("eval",): ["x.plmap"],
    ("regions",): ["x.plmap", "-o", "r.csv"],
    ("export",): ["x.plmap", "-o", "dir"],
    ("convert",): ["x.off", "y.off"],
    ("build", "identity"): ["x.off", "-o", "m.plmap"],
    ("build", "refine"): ["x.off", "-o", "m.plmap"],
    ("build", "overlay"): ["x.off", "y.off", "-o", "m.plmap"],
    ("generate", "grid"): ["-o", "g.off"],
    ("generate", "delaunay"): ["-o", "g.off"],
    ("generate", "polyline"): ["-o", "g.curve"],
    ("draw",): ["x.plmap", "-o", "p.svg"],
    ("experiment", "run"): ["x.toml", "-o", "dir"],
    ("project",): ["x.off", "y.off", "-o", "m.plmap"],
}


def _numeric_options(command):
    """(option, type) for every option of `plmap COMMAND --help` taking INT, UINT or FLOAT."""
    out, _, _ = run(*command, "--help")
    found = []
    for match in re.finditer(r"^\s+(?:-\w,)?(--[\w-]+)(?:,-\w)?\s+(INT|UINT|FLOAT)\b", out, re.M):
        found.append((match.group(1), match.group(2)))
    return found


@case
def negative_counts_are_refused():
    # the reported ones first, then every integer option of every command
    for args, option in ((["eval", "m.plmap", "--random", "-5"], "--random"),
                         (["eval", "m.plmap", "--seed", "-1"], "--seed"),
                         (["project", "a.off", "b.off", "-o", "m.plmap", "--max-listed", "-1"], "--max-listed"),
                         (["check", "m.plmap", "--max-reported", "-1"], "--max-reported"),
                         (["eval", "m.plmap", "--threads", "-2"], "--threads"),
                         (["draw", "m.plmap", "--element", "-1", "-o", "p.svg"], "--element")):
        expect_clean_error(args, code=64, mention=option)
    swept = 0
    for command, required in _COMMANDS.items():
        for option, kind in _numeric_options(command):
            if kind == "FLOAT":
                continue
            args = list(command) + required + [option, "-1"]
            expect_clean_error(args, code=64, mention=option)
            swept += 1
    expect(swept >= 15, f"only {swept} integer options found in the help texts")


@case
def non_finite_numbers_are_refused():
    s = grid("v.off", cells=2)
    m = identity_map(s, "m.plmap")
    expect_clean_error(["draw", m, "--view3d", "--azimuth", "nan", "-o", "nan.svg"], code=64,
                       mention="--azimuth")
    expect(not os.path.exists(os.path.join(WORK, "nan.svg")), "an SVG was written for azimuth nan")
    swept = 0
    for command, required in _COMMANDS.items():
        for option, kind in _numeric_options(command):
            if kind != "FLOAT":
                continue
            for value in ("nan", "inf", "-inf", "1e400"):
                expect_clean_error(list(command) + required + [option, value], code=64, mention=option)
            swept += 1
    expect(swept >= 8, f"only {swept} floating-point options found in the help texts")
    # finite values are still accepted, also where the default is infinite
    run("check", m, "--max-condition", "1e300")


@case
def unknown_command_is_named():
    line = expect_clean_error(["frobnicate"], code=64, mention="'frobnicate'")
    for name in ("info", "build", "project", "draw"):
        expect(name in line, f"the valid commands should be listed: {line}")
    line = expect_clean_error(["build", "idenity", "v.off"], code=64, mention="'build idenity'")
    expect("identity" in line and "overlay" in line, f"build's commands should be listed: {line}")
    line = expect_clean_error(["generate"], code=64, mention="no command")
    expect("grid" in line and "polyline" in line, line)
    line = expect_clean_error([], code=64, mention="no command")
    expect("eval" in line, line)
    expect_clean_error(["--frobnicate"], code=64, mention="'--frobnicate'")
    expect_clean_error(["build", "--json", "identity", "v.off", "-o", "m.plmap"], code=64,
                       mention="'--json' for 'build'")
    # an unknown option is still CLI11's message, which names it
    expect_clean_error(["info", "x.off", "--frobnicate"], code=64, mention="--frobnicate")


@case
def write_failures_name_the_output():
    s = grid("v.off", cells=2)
    m = identity_map(s, "m.plmap")
    write("afile", "not a directory\n")
    # /proc takes no new files, even for root; afile/ and missing/ are not directories
    for where in ("/proc", "missing", "afile"):
        attempts = [(["regions", m, "-o", f"{where}/x.vtu"], f"{where}/x.vtu"),
                    (["regions", m, "-o", f"{where}/x.csv"], f"{where}/x.csv"),
                    (["convert", s, f"{where}/x.ply"], f"{where}/x.ply"),
                    (["build", "identity", s, "-o", f"{where}/x.plmap"], f"{where}/x.plmap"),
                    (["draw", m, "--view3d", "-o", f"{where}/x.svg"], f"{where}/x.svg"),
                    (["export", m, "-o", f"{where}/vtk"], f"{where}/vtk")]
        if where == "missing":
            attempts.pop()  # export creates the directory
        for args, output in attempts:
            line = expect_clean_error(args, code=2, mention=output)
            expect(".tmp" not in line and "plmap-tmp" not in line,
                   f"the message names a temporary file: {line}")
    stray = [f for f in os.listdir(WORK) if f.startswith(".")]
    expect(not stray, f"temporaries left behind: {stray}")


def _dead_pid():
    """A process id that no process has now."""
    for pid in range(4_000_000, 3_000_000, -7919):
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return pid
        except PermissionError:
            pass
    raise Failure("no free process id found")


@case
def stale_temporaries_are_removed():
    s = grid("v.off", cells=2)
    host = socket.gethostname()
    stale = f".m.plmap.plmap-tmp-{host}-{_dead_pid()}-0"
    live = f".m.plmap.plmap-tmp-{host}-{os.getpid()}-0"  # this test is alive: not stale
    other_host = f".m.plmap.plmap-tmp-elsewhere.example-{_dead_pid()}-0"
    unrelated = f".n.plmap.plmap-tmp-{host}-{_dead_pid()}-0"
    for name in (stale, live, other_host, unrelated):
        write(name, "half a map")
    run("build", "identity", s, "-o", "m.plmap")
    left = set(os.listdir(WORK))
    expect(stale not in left, "the temporary of a dead process was not removed")
    for name in (live, other_host, unrelated):
        expect(name in left, f"{name} was removed, but it is not a stale temporary of m.plmap")
    expect(not [f for f in left if ".m.plmap.plmap-tmp-" in f and f not in (live, other_host)],
           f"the write left its own temporary: {sorted(left)}")


@case
def interrupted_write_leaves_no_temporary():
    # A refinement big enough that writing the map takes a while: interrupt it while the
    # temporary exists, and check that the handler removed it.
    s = grid("v.off", cells=8)
    command = [PLMAP, "build", "refine", s, "--levels", "6", "-o", "big.plmap"]
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        process = subprocess.Popen(command, cwd=WORK, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        caught = False
        deadline = time.monotonic() + 120
        while process.poll() is None and time.monotonic() < deadline:
            if any(".plmap-tmp-" in f for f in os.listdir(WORK)):
                process.send_signal(signal_number)
                caught = True
                break
            time.sleep(0.001)
        process.wait(timeout=120)
        if not caught:
            raise Failure("the write finished before it could be interrupted; refine more")
        expect(process.returncode == -signal_number,
               f"plmap should end by the signal {signal_number}, exit {process.returncode}")
        left = [f for f in os.listdir(WORK) if f not in ("v.off", "big.plmap")]
        expect(not left, f"interrupted write left {left}")
        if os.path.exists(os.path.join(WORK, "big.plmap")):
            # the signal came after the rename: then the map is complete
            run("info", "big.plmap", "--no-quality")
            os.remove(os.path.join(WORK, "big.plmap"))


@case
def threads_default_to_all_cores():
    s = grid("v.off", cells=2)
    m = identity_map(s, "m.plmap")
    cores = len(os.sched_getaffinity(0))  # the CPUs this process may run on (all, unless restricted)
    j = run_json("eval", m, "--random", 100, "--json")
    expect(j["threads"] == cores, f"eval: threads {j['threads']}, cores {cores}")
    j = run_json("project", s, s, "-o", "p.plmap", "--json")
    expect(j["threads"] == cores, f"project: threads {j['threads']}, cores {cores}")
    out, _, _ = run("eval", "--help")
    expect("all hardware threads" in out, f"eval --help should say what 0 threads means: {out}")
    expect_clean_error(["eval", m, "--threads", "100000"], code=64, mention="--threads")


@case
def more_threads_than_cpus_run_quietly_on_the_cpus_there_are():
    # oneTBB printed "TBB Warning: The number of workers is currently limited to ..." for every
    # run that asked for more threads than the process may use (--threads 4 on two cores; any
    # run in a batch job or under taskset given one core, where the default counted the
    # machine's cores). The default is now the CPUs the process may run on, and more threads
    # than that are not asked of oneTBB; the map is the same for every count.
    s = grid("v.off", cells=6)
    run("project", s, s, "-o", "one.plmapb", "--threads", 1)
    _, err, _ = run("project", s, s, "-o", "many.plmapb", "--threads", 2 * os.cpu_count() + 2)
    expect("TBB" not in err and not err.strip(), f"--threads above the CPU count printed: {err}")
    expect(_read("many.plmapb") == _read("one.plmapb"), "--threads above the CPU count changed the map")
    cpu = min(os.sched_getaffinity(0))
    for extra in ([], ["--threads", 2]):
        done = subprocess.run([PLMAP, "project", s, s, "-o", "pinned.plmapb", "--json"] + [str(a) for a in extra],
                              cwd=WORK, capture_output=True, text=True, timeout=120,
                              preexec_fn=lambda: os.sched_setaffinity(0, {cpu}))
        expect(done.returncode == 0, f"project on one CPU {extra}: exit {done.returncode}: {done.stderr}")
        expect("TBB" not in done.stderr and not done.stderr.strip(), f"project on one CPU {extra} printed: {done.stderr}")
        if not extra:
            threads = json.loads(done.stdout)["threads"]
            expect(threads == 1, f"the default on one CPU should be 1 thread, got {threads}")
        expect(_read("pinned.plmapb") == _read("one.plmapb"), f"project on one CPU {extra} changed the map")


@case
def a_pipe_as_input_is_refused_at_once():
    # The commands that peek at an input to tell a map from a surface would consume what a pipe
    # delivers (the reader then saw the rest only), and opening a pipe nobody writes to would wait.
    s = grid("v.off", cells=2)
    os.mkfifo(os.path.join(WORK, "pipe.off"))
    for args in (["info", "pipe.off"], ["project", "pipe.off", s, "-o", "p.plmap"],
                 ["project", s, "pipe.off", "-o", "p.plmap"], ["convert", "pipe.off", "c.obj"]):
        expect_clean_error(args, code=2, mention="pipe")
    stray = [f for f in ("p.plmap", "c.obj") if os.path.exists(os.path.join(WORK, f))]
    expect(not stray, f"refused commands wrote {stray}")


@case
def unstitched_seams_are_counted_and_warned_about():
    # Two triangles of a unit square that share the diagonal's position but not its vertices:
    # `info` counts the coincident vertices, and `project` warns that the map may leave out
    # elements along such a seam (projected onto itself it covered half of the square until the
    # seam rule of construct/src/vertex_star_probe.hpp; other seams still cost elements).
    write("seam.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 3 4 5\n")
    expect(run_json("info", "seam.off", "--json")["coincident_vertices"] == 2, "coincident vertices")
    _, err, _ = run("project", "seam.off", "seam.off", "-o", "seam.plmap")
    expect(err.count("vertices at the position of another vertex") == 2, err)
    grid("no_seam.off", cells=3)
    expect(run_json("info", "no_seam.off", "--json")["coincident_vertices"] == 0, "no seam")
    _, err, _ = run("project", "no_seam.off", "no_seam.off", "-o", "no_seam.plmap")
    expect("position of another vertex" not in err, err)


@case
def convert_merges_coincident_vertices():
    # The seam above, merged by `convert --merge-coincident`: the diagonal's two copies become one
    # edge, `project` no longer warns, and the square projected onto itself is the identity on all
    # of it. A triangle listed twice is kept once; a map file is not a surface to merge.
    write("seam.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 3 4 5\n")
    out, _, _ = run("convert", "seam.off", "welded.off", "--merge-coincident")
    expect("merged 2 vertices" in out and "dropped 0 duplicate" in out, out)
    j = run_json("info", "welded.off", "--json")
    expect(j["vertices"] == 4 and j["elements"] == 2 and j["coincident_vertices"] == 0, j)
    expect(j["boundary_edges"] == 4, f"the diagonal is one interior edge: {j}")
    _, err, _ = run("project", "welded.off", "welded.off", "-o", "welded.plmap")
    expect("position of another vertex" not in err, err)
    p = run_json("project", "welded.off", "welded.off", "-o", "welded.plmap", "--json")
    expect(abs(p["covered_measure"] - 1.0) < 1e-12 and abs(p["domain_measure"] - 1.0) < 1e-12, p)
    run("check", "welded.plmap")
    # a soup listing one triangle twice (its own corners each time, the second reversed): merged,
    # the two have the same corners, which a surface refuses, so the second goes
    write("twice.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 5 4 3\n")
    out, _, _ = run("convert", "twice.off", "once.off", "--merge-coincident")
    expect("merged 3 vertices" in out and "dropped 1 duplicate" in out, out)
    expect(run_json("info", "once.off", "--json")["elements"] == 1, "duplicate kept once")
    expect_clean_error(["convert", "welded.plmap", "w2.plmap", "--merge-coincident"], code=64, mention="map file")


@case
def surfaces_that_cross_themselves_are_counted():
    # A unit square (two triangles) pierced by a vertical triangle through the inside of the first
    # one: `info` counts one pair of elements that meet without sharing a vertex; the square alone,
    # whose triangles share an edge, none. (The ray check names the area such a crossing costs a
    # projection: missed reason target_crosses_itself.)
    write("pierced.off", "OFF\n7 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.2 -0.1\n0.7 0.2 -0.1\n0.6 0.2 0.1\n"
          "3 0 1 2\n3 0 2 3\n3 4 5 6\n")
    j = run_json("info", "pierced.off", "--json")
    expect(j["self_intersecting_pairs"] == 1, j)
    out, _, _ = run("info", "pierced.off")
    expect("self_intersecting_pairs: 1" in out, out)
    write("square.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
    expect(run_json("info", "square.off", "--json")["self_intersecting_pairs"] == 0, "square")


def tilted_sheets_off(cells, slopes):
    """Sheets over [-0.1, 1.1]^2 at z = 1 + slope (x - 0.5), facing down (-z); two with opposite
    slopes cross along x = 0.5, z = 1."""
    n = cells + 1
    vertices, faces = [], []
    for sheet, slope in enumerate(slopes):
        for j in range(n):
            for i in range(n):
                x, y = -0.1 + 1.2 * i / cells, -0.1 + 1.2 * j / cells
                vertices.append(f"{x!r} {y!r} {1 + slope * (x - 0.5)!r}")
        base = sheet * n * n
        for j in range(cells):
            for i in range(cells):
                a, b, c, d = (base + j * n + i, base + j * n + i + 1, base + (j + 1) * n + i + 1,
                              base + (j + 1) * n + i)
                faces += [f"3 {a} {c} {b}", f"3 {a} {d} {c}"]
    return f"OFF\n{len(vertices)} {len(faces)} 0\n" + "\n".join(vertices + faces) + "\n"


@case
def projecting_onto_a_surface_that_crosses_itself_says_so():
    # S2 crosses itself above the middle of S1: the nearest hit jumps from one sheet to the other
    # there, the faces beside the crossing are left out, and `project` names the crossing (and
    # counts its pairs in the JSON). Onto one of the sheets alone it says nothing.
    flat = grid("crossed_flat.off", cells=10)
    write("crossing.off", tilted_sheets_off(13, (0.5, -0.5)))
    out, err, _ = run("project", flat, "crossing.off", "-o", "crossed.plmap", "--json")
    j = json.loads(out)
    expect(j.get("target_self_intersecting_pairs", 0) > 0, j)
    expect("S2 crosses itself" in err and "target_crosses_itself" in err, err)
    expect(j["covered_measure"] < j["domain_measure"], j)
    write("one_sheet.off", tilted_sheets_off(13, (0.5,)))
    out, err, _ = run("project", flat, "one_sheet.off", "-o", "one_sheet.plmap", "--json")
    expect("S2 crosses itself" not in err, err)
    expect(json.loads(out).get("target_self_intersecting_pairs", 0) == 0, out)
