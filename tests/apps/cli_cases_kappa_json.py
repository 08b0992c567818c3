# κ_Ξ as `plmap simplify` and `plmap smooth` print it (exec'd into cli_test.py's namespace): both
# commands write it with one helper (apps/kappa_json.hpp), so a script reads it the same way.


@case
def simplify_and_smooth_print_kappa_in_one_form():
    run("generate", "delaunay", "--points", 200, "--lift", "--seed", 4, "-o", "kappa_fine.off")
    simplified = run_json("simplify", "kappa_fine.off", "-o", "kappa_coarse.plmap", "--target-elements", 80,
                          "--json")
    smoothed = run_json("smooth", "kappa_coarse.plmap", "-o", "kappa_smooth.plmap", "--json")
    quality, before = simplified["quality"], smoothed["before"]
    kappa_keys = ["kappa_max", "kappa_mean", "kappa_p99", "kappa_quantiles", "log10_kappa_histogram",
                  "degenerate_regions"]
    expect_keys(quality, kappa_keys + ["stretch_min", "stretch_max"], "simplify --json quality")
    expect_keys(before, kappa_keys, "smooth --json before")
    # the same map, measured and written the same way
    for key in kappa_keys:
        expect(quality[key] == before[key], (key, quality[key], before[key]))
    # quantile levels 0.999 and 1 have keys of their own (both were "p100" before)
    expect(list(quality["kappa_quantiles"]) == ["p50", "p90", "p99", "p99.9", "p100"], quality["kappa_quantiles"])
    expect(quality["kappa_quantiles"]["p100"] == quality["kappa_max"], quality)
