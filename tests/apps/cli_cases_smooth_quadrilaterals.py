# Command-line cases of `plmap smooth` over edge quadrilaterals and κ per sweep (exec'd into
# cli_test.py's namespace after cli_cases_smooth.py, whose simplified_sphere it uses).


@case
def smooth_quadrilaterals_cross_edges_and_report_kappa_per_sweep():
    coarse = simplified_sphere("sphere_quads.plmap")
    out = "sphere_quads_smooth.plmap"
    j = run_json("smooth", coarse, "-o", out, "--weights", "mean-value", "--sweeps", 3, "--json")
    expect(j["quadrilaterals"] is True and "quadrilaterals_not_applicable" not in j, j)
    expect(len(j["sweeps"]) == 3, j)
    for key in ["before", "after"] + [f"sweep {i}" for i in range(3)]:
        k = j["sweeps"][int(key[-1])] if key.startswith("sweep") else j[key]
        expect_keys(k, ["kappa_max", "kappa_mean", "kappa_p99", "kappa_quantiles", "log10_kappa_histogram"], key)
        counts = k["log10_kappa_histogram"]["counts"]
        expect(sum(counts) > 0 and k["kappa_quantiles"]["p50"] <= k["kappa_max"], k)
    first = j["sweeps"][0]
    expect(first["quadrilaterals_smoothed"] > 0 and first["nodes_crossed"] > 0, first)
    expect(not first["quadrilateral_pass_rejected"], first)
    expect(j["after"]["kappa_max"] < j["before"]["kappa_max"], j)
    expect(j["after"]["kappa_mean"] < j["before"]["kappa_mean"], j)
    run("check", "--parametrization", out)


@case
def smooth_without_quadrilaterals_never_crosses_an_edge():
    coarse = simplified_sphere("sphere_quads2.plmap")
    out = "sphere_elements_only.plmap"
    j = run_json("smooth", coarse, "-o", out, "--no-quadrilaterals", "--sweeps", 2, "--json")
    expect(j["quadrilaterals"] is False, j)
    for s in j["sweeps"]:
        expect(s["quadrilaterals_smoothed"] == 0 and s["nodes_crossed"] == 0, s)
    run("check", "--parametrization", out)
