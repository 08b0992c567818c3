# `plmap check --against-rays`: the ray check of a projection map (verify/ray_check.hpp).
# Exec'd into cli_test.py's namespace.


@case
def check_against_rays():
    flat = grid("rays_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "rays_hill.off")
    run("project", flat, "rays_hill.off", "-o", "rays.plmap", "--allow-negative")
    j = run_json("check", "rays.plmap", "--against-rays", 3000, "--allow-negative", "--json")
    expect_keys(j, ["ok", "against_rays"], "check --against-rays --json")
    rays = j["against_rays"]
    expect_keys(rays, ["samples", "missed", "extra", "image_error_relative_to_edge"], "against_rays")
    expect(j["ok"] is True and rays["samples"] == 3000, rays)
    expect(rays["missed"]["samples"] == 0 and rays["extra"]["samples"] == 0, rays)
    expect(rays["in_domain_with_hit"] == 3000, rays)
    out, _, _ = run("check", "rays.plmap", "--against-rays", 500, "--allow-negative")
    expect("against rays (500 samples): ok" in out, out)

    # A map projected with a distance limit lacks the area beyond it: checked without the limit,
    # that area is missed (and not covered by any region), and the check fails.
    run("project", flat, "rays_hill.off", "-o", "rays_short.plmap", "--allow-negative",
        "--max-distance", "1e-9")
    j = run_json("check", "rays_short.plmap", "--against-rays", 2000, "--allow-negative", "--json",
                 expect_code=1)
    missed = j["against_rays"]["missed"]
    expect(j["ok"] is False and missed["fraction"] > 0.9, missed)
    expect(missed["by_reason"]["not_covered"]["samples"] == missed["samples"], missed)
    expect(missed["examples"] and missed["examples"][0]["reason"] == "not_covered", missed)
    # told the same limit, the check agrees with the map
    j = run_json("check", "rays_short.plmap", "--against-rays", 2000, "--allow-negative",
                 "--max-distance", "1e-9", "--json")
    expect(j["against_rays"]["missed"]["samples"] == 0, j["against_rays"])

    expect_clean_error(["check", "rays.plmap", "--against-rays", 10, "--normal-check", "bogus"],
                       mention="bogus")
    expect_clean_error(["check", "rays.plmap", "--against-rays", 0], code=64)
    # a negative tolerance would fail every map
    expect_clean_error(["check", "rays.plmap", "--against-rays", 10, "--ray-tolerance", -1], code=64,
                       mention=">= 0")
