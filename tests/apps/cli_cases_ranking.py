# Command-line cases of `plmap simplify --ranking` (exec'd into cli_test.py's namespace).


@case
def simplify_with_the_estimate_ranking():
    run("generate", "delaunay", "--points", 300, "--lift", "--seed", 21, "-o", "ranked.off")
    runs = {}
    for ranking in ("exact", "estimate"):
        j = run_json("simplify", "ranked.off", "-o", f"{ranking}.plmap", "--target-elements", 120,
                     "--feature-angle", 180, "--oracle", "hausdorff:1", "--oracle", "aspect-ratio:1",
                     "--ranking", ranking, "--json")
        expect_keys(j, ["ranking", "ranking_plans", "full_plans", "requeued"], "simplify --json")
        expect(j["ranking"] == ranking and j["target_reached"], j)
        run("check", "--parametrization", f"{ranking}.plmap")
        runs[ranking] = j
    # the point of the estimate: plans only for the vertices that come up
    expect(runs["estimate"]["ranking_plans"] < runs["exact"]["ranking_plans"], runs)
    expect(all(j["elements_after"] <= 120 for j in runs.values()), runs)
    expect_clean_error(["simplify", "ranked.off", "-o", "never.plmap", "--target-elements", 100,
                        "--ranking", "psychic"], code=64, mention="psychic")
    expect(not os.path.exists(os.path.join(WORK, "never.plmap")), "never.plmap was written")


@case
def simplify_with_the_deferred_cut():
    run("generate", "delaunay", "--points", 300, "--lift", "--seed", 21, "-o", "deferred.off")
    j = run_json("simplify", "deferred.off", "-o", "deferred.plmap", "--target-elements", 120,
                 "--feature-angle", 180, "--oracle", "hausdorff:1", "--oracle", "aspect-ratio:1",
                 "--ranking", "estimate", "--cut", "deferred", "--json")
    expect_keys(j, ["cut", "cut_fell_back"], "simplify --json")
    expect(j["cut"] == "deferred" and j["target_reached"], j)
    run("check", "--parametrization", "deferred.plmap")
    expect_clean_error(["simplify", "deferred.off", "-o", "never.plmap", "--target-elements", 100,
                        "--cut", "later"], code=64, mention="later")
