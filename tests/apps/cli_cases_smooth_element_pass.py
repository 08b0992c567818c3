# Command-line cases of `plmap smooth --no-element-pass` (the quadrilaterals alone), exec'd into
# cli_test.py's namespace after cli_cases_smooth.py, whose simplified_sphere it uses.


@case
def smooth_without_element_pass_runs_only_quadrilaterals():
    coarse = simplified_sphere("sphere_no_element_pass.plmap")
    out = "sphere_no_element_pass_smooth.plmap"
    j = run_json("smooth", coarse, "-o", out, "--no-element-pass", "--sweeps", 2, "--json")
    expect(j["element_pass"] is False and j["quadrilaterals"] is True, j)
    for s in j["sweeps"]:
        expect(s["elements_smoothed"] == 0 and s["elements_shortened"] == 0, s)
    expect(j["sweeps"][0]["quadrilaterals_smoothed"] > 0, j)
    expect(j["after"]["kappa_max"] <= max(j["before"]["kappa_max"], 3.0) * (1 + 1e-12), j)
    run("check", "--parametrization", out)
    full = run_json("smooth", coarse, "-o", "sphere_with_element_pass.plmap", "--json")
    expect(full["element_pass"] is True and full["sweeps"][0]["elements_smoothed"] > 0, full)


@case
def smooth_refuses_to_run_no_pass_at_all():
    coarse = simplified_sphere("sphere_no_pass.plmap")
    out = "sphere_no_pass_smooth.plmap"
    expect_clean_error(["smooth", coarse, "-o", out, "--no-element-pass", "--no-quadrilaterals"], code=64,
                       mention="--no-element-pass")
    expect(not os.path.exists(os.path.join(WORK, out)), "no output may be written")
