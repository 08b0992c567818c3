# Command-line cases of `plmap simplify` (exec'd into cli_test.py's namespace).


def hill(name="hill.off", points=150, seed=11):
    run("generate", "delaunay", "--points", points, "--lift", "--seed", seed, "-o", name)
    return name


@case
def simplify_to_target_and_check():
    fine = hill()
    before = run_json("info", fine, "--json")
    j = run_json("simplify", fine, "-o", "coarse.plmap", "--coarse", "coarse.off",
                 "--target-elements", 100, "--oracle", "hausdorff:1", "--oracle", "aspect-ratio:0.1",
                 "--json")
    expect_keys(j, ["elements_before", "elements_after", "vertices_before", "vertices_after",
                    "hausdorff_error", "hausdorff_error_relative", "quality", "feature_edges",
                    "skipped_by_reason", "oracles", "seconds", "seconds_by_phase"], "simplify --json")
    expect(j["elements_before"] == before["elements"], (j, before))
    expect(j["elements_after"] < j["elements_before"], j)
    expect(j["oracles"] == "hausdorff:1,aspect-ratio:0.1", j)
    expect(j["quality"]["kappa_max"] >= 1.0, j)
    coarse = run_json("info", "coarse.off", "--json")
    expect(coarse["elements"] == j["elements_after"], (coarse, j))
    # the map is a parametrization: every check passes, and S2 is covered completely
    run("check", "--parametrization", "coarse.plmap")


@case
def simplify_by_error_bound():
    fine = hill(points=120, seed=12)
    j = run_json("simplify", fine, "-o", "bounded.plmap", "--max-error", 0.002, "--json")
    expect(j["hausdorff_error"] <= 0.002 * (1 + 1e-9), j)
    expect(j["elements_after"] < j["elements_before"], j)
    run("check", "--parametrization", "bounded.plmap")


@case
def simplify_strategies_and_features():
    fine = hill(points=100, seed=13)
    j = run_json("simplify", fine, "-o", "s.plmap", "--target-elements", 80, "--flattening",
                 "plane-projection", "--hole-triangulation", "min-max-aspect", "--feature-angle", 30,
                 "--oracle", "long-edge", "--oracle", "self-intersection", "--json")
    expect(j["flattening"] == "plane-projection" and j["hole_triangulation"] == "min-max-aspect", j)
    expect(j["feature_edges"] > 0, j)  # at least the boundary of the square
    run("check", "--parametrization", "s.plmap")


@case
def simplify_bad_input_leaves_no_output():
    fine = hill(points=60, seed=14)
    info = run_json("info", fine, "--json")
    outputs = ["never.plmap", "never.off"]
    expect_clean_error(["simplify", fine, "-o", outputs[0], "--coarse", outputs[1], "--target-elements",
                        info["elements"] + 5], mention="not below")
    expect_clean_error(["simplify", fine, "-o", outputs[0], "--coarse", outputs[1], "--target-elements", 10,
                        "--oracle", "hausdorf"], mention="hausdorf")
    expect_clean_error(["simplify", fine, "-o", outputs[0], "--target-elements", 10, "--oracle",
                        "hausdorff:heavy"], mention="heavy")
    expect_clean_error(["simplify", fine, "-o", outputs[0], "--target-elements", 10, "--flattening",
                        "magic"], mention="magic")
    expect_clean_error(["simplify", fine, "-o", outputs[0]], code=64, mention="--target-elements")
    # zero is no count of elements, and the message says so in words (CLI11's own spelled out
    # the largest double)
    line = expect_clean_error(["simplify", fine, "-o", outputs[0], "--target-elements", 0], code=64,
                              mention="positive")
    expect("1797" not in line, line)
    write("flat.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n")
    # what simplify refuses about the input names the input file, as the loader's errors do
    expect_clean_error(["simplify", "flat.off", "-o", outputs[0], "--target-elements", 1], mention="flat.off")
    # a mesh that has nothing to remove: the target cannot be met, but the map is still valid
    write("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    out, err, _ = run("simplify", "quad.off", "-o", "quad.plmap", "--target-elements", 1, "--json")
    j = json.loads(out)
    expect(not j["target_reached"] and j["elements_after"] == 2, j)
    # ... and says why on stderr, one line, leaving stdout to the JSON
    expect(err.strip().splitlines() == [err.strip()] and err.startswith("note: stopped at 2 elements, above --target-elements 1")
           and "4 feature corners" in err, f"missed target should be explained on stderr: {err!r}")
    run("check", "quad.plmap")
    # a run that reaches its target says nothing on stderr
    _, err, _ = run("simplify", fine, "-o", "reached.plmap", "--target-elements", 10, "--json")
    expect(err == "", f"a run that reaches its target should print nothing on stderr: {err!r}")
    # curves are simplified too (cli_cases_simplify_features.py); an oracle for triangles is not
    expect_clean_error(["simplify", polyline(), "-o", outputs[0], "--target-elements", 1, "--oracle",
                        "aspect-ratio"], mention="curves")
    expect_clean_error(["simplify", "missing.off", "-o", outputs[0], "--target-elements", 1],
                       mention="missing.off")
    expect_clean_error(["simplify", fine, "-o", outputs[0], "--coarse", "no/such/dir/c.off",
                        "--target-elements", 10], mention="no/such/dir")
    for name in outputs:
        expect(not os.path.exists(os.path.join(WORK, name)), f"{name} was written")


@case
def refine_through_a_simplified_map():
    fine = hill(points=120, seed=15)
    s = run_json("simplify", fine, "-o", "p.plmap", "--target-elements", 60, "--json")
    j = run_json("refine", "p.plmap", "--levels", 2, "-o", "refined.off", "--json")
    expect_keys(j, ["levels", "vertices", "elements", "distance_max", "distance_mean",
                    "distance_max_relative", "aspect_ratio_refined", "aspect_ratio_coarse", "seconds"],
                "refine --json")
    expect(j["elements"] == 16 * s["elements_after"], (j, s))
    info = run_json("info", "refined.off", "--json")
    expect(info["elements"] == j["elements"], (info, j))
    coarse = run_json("refine", "p.plmap", "--levels", 0, "-o", "level0.off", "--json")
    expect(j["distance_max"] <= coarse["distance_max"], (j, coarse))
    expect_clean_error(["refine", "p.plmap", "--levels", 9, "-o", "never.off"], code=64)
    run("build", "identity", polyline(), "-o", "curve.plmap")
    expect_clean_error(["refine", "curve.plmap", "-o", "never.off"], mention="curves")
    expect_clean_error(["refine", "missing.plmap", "-o", "never.off"], mention="missing.plmap")
    # a map whose domain is part of S1 is no parametrization: refused, naming the map file
    run("generate", "grid", "--cells", 4, "-o", "unit.off")
    write("wide.off", "OFF\n4 2 0\n-0.5 -0.5 -0.2\n1.5 -0.5 -0.2\n1.5 1.5 -0.2\n-0.5 1.5 -0.2\n3 0 1 2\n3 0 2 3\n")
    run("project", "wide.off", "unit.off", "-o", "partial.plmap")
    expect_clean_error(["refine", "partial.plmap", "-o", "never.off"], mention="partial.plmap")
    expect(not os.path.exists(os.path.join(WORK, "never.off")), "never.off was written")


@case
def simplify_and_refine_refuse_outputs_that_are_inputs():
    fine = hill(points=60, seed=14)
    before = open(os.path.join(WORK, fine), "rb").read()
    expect_clean_error(["simplify", fine, "-o", "m.plmap", "--coarse", fine, "--target-elements", 40],
                       code=64, mention=fine)
    expect_clean_error(["simplify", fine, "-o", "m.off", "--target-elements", 40], code=64, mention="m.off")
    expect_clean_error(["simplify", fine, "-o", "m.plmap", "--coarse", "m.plmap", "--target-elements", 40],
                       code=64, mention="m.plmap")
    expect(open(os.path.join(WORK, fine), "rb").read() == before, "simplify replaced its input")
    run("simplify", fine, "-o", "m.plmap", "--target-elements", 40)
    expect_clean_error(["refine", "m.plmap", "--levels", 1, "-o", "m.plmap"], code=64, mention="m.plmap")
    expect_clean_error(["refine", "m.plmap", "--levels", 1, "-o", "r.plmap"], code=64, mention="r.plmap")
    run("refine", "m.plmap", "--levels", 1, "-o", "r.off")
