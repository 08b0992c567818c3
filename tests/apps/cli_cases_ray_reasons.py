# `plmap check --against-rays`: the reasons of the missed area (verify/ray_check.hpp, MissedReason).
# Exec'd into cli_test.py's namespace.


@case
def check_against_rays_reasons():
    # S1 a flat grid, S2 a hill above it, projected with a negligible distance limit: the map
    # covers nothing, every sample with a hit is missed, and on this single sheet without folds
    # none of the stated reasons applies, so all of it is a defect, in JSON and in the text.
    flat = grid("reasons_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "reasons_hill.off")
    run("project", flat, "reasons_hill.off", "-o", "reasons.plmap", "--allow-negative", "--max-distance", "1e-9")
    # (the check ignores the limit the map records: the area beyond it is then missed)
    j = run_json("check", "reasons.plmap", "--against-rays", 2000, "--allow-negative", "--no-recorded-rules", "--json",
                 expect_code=1)
    missed = j["against_rays"]["missed"]
    reasons = ["nearer_sheet", "farther_sheet", "not_covered", "domain_in_between", "target_seen_twice",
               "target_crosses_itself", "in_folding_element", "next_to_fold", "inside_target_boundary"]
    expect_keys(missed["by_reason"], reasons, "missed.by_reason")
    expect(sum(missed["by_reason"][r]["samples"] for r in reasons) == missed["samples"], missed)
    defects = sum(missed["by_reason"][r]["samples"] for r in ["farther_sheet", "not_covered", "in_folding_element", "next_to_fold"])
    expect(abs(missed["defect_fraction"] - defects / 2000) < 1e-12, missed)
    expect(missed["samples"] > 1000 and missed["by_reason"]["not_covered"]["samples"] == missed["samples"], missed)
    out, _, _ = run("check", "reasons.plmap", "--against-rays", 500, "--allow-negative", "--no-recorded-rules",
                    expect_code=1)
    expect("outside D for a reason: nearer sheet 0, S1 in between 0, S2 seen twice 0, S2 crossing itself 0, just inside S2's boundary 0" in out, out)
    expect("defects: farther sheet 0, in a folding element 0, next to a fold 0, not covered" in out, out)


@case
def project_fold_rim_switch():
    # `plmap project --no-fold-rim` (ProjectionOptions::fold_rim = false): the report's fold rim
    # counts are 0 with it, and present without it; on a single sheet without folds the two maps
    # cover the same measure.
    flat = grid("foldrim_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "foldrim_hill.off")
    met = run_json("project", flat, "foldrim_hill.off", "-o", "foldrim_met.plmap", "--allow-negative", "--json")
    apart = run_json("project", flat, "foldrim_hill.off", "-o", "foldrim_apart.plmap", "--allow-negative",
                     "--no-fold-rim", "--json")
    expect_keys(met, ["fold_rim_nodes", "fold_rim_edges"], "project --json")
    expect(apart["fold_rim_nodes"] == 0 and apart["fold_rim_edges"] == 0, apart)
    expect(met["covered_measure"] == apart["covered_measure"], (met["covered_measure"], apart["covered_measure"]))
