# `plmap check --against-rays`: the ray check of a projection map (verify/ray_check.hpp).
# Exec'd into cli_test.py's namespace.


def text_of(name):
    with open(os.path.join(WORK, name)) as f:
        return f.read()


@case
def check_against_rays():
    flat = grid("rays_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "rays_hill.off")
    # a plane below an upward-facing one lies behind its normals: without --allow-negative
    # nothing is mapped, and plmap says what to try (a hint on stderr; exit 0, since an empty
    # map is a valid answer)
    scaled_grid_off("rays_up.off", 1.0, cells=5)
    scaled_grid_off("rays_below.off", 1.0, cells=7, height=-0.5, down=True)
    out, err, _ = run("project", "rays_up.off", "rays_below.off", "-o", "rays_empty.plmap", "--json")
    expect(json.loads(out)["covered_measure"] == 0.0, out)
    expect("no part of S1 was mapped" in err and "--allow-negative" in err, err)
    out, err, _ = run("project", "rays_up.off", "rays_below.off", "-o", "rays_below.plmap", "--allow-negative",
                      "--json")
    expect(json.loads(out)["covered_measure"] > 0.99, out)
    expect("no part of S1 was mapped" not in err, err)
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

    # A map projected with a distance limit lacks the area beyond it: checked without the limit
    # (ignoring the one the map records), that area is missed (and not covered by any region), and
    # the check fails.
    run("project", flat, "rays_hill.off", "-o", "rays_short.plmap", "--allow-negative",
        "--max-distance", "1e-9")
    j = run_json("check", "rays_short.plmap", "--against-rays", 2000, "--allow-negative", "--no-recorded-rules",
                 "--json", expect_code=1)
    missed = j["against_rays"]["missed"]
    expect(j["ok"] is False and missed["fraction"] > 0.9, missed)
    expect(missed["by_reason"]["not_covered"]["samples"] == missed["samples"], missed)
    expect(missed["examples"] and missed["examples"][0]["reason"] == "not_covered", missed)
    # told the same limit, or under the rules the map records, the check agrees with the map
    j = run_json("check", "rays_short.plmap", "--against-rays", 2000, "--allow-negative", "--no-recorded-rules",
                 "--max-distance", "1e-9", "--json")
    expect(j["against_rays"]["missed"]["samples"] == 0, j["against_rays"])
    j = run_json("check", "rays_short.plmap", "--against-rays", 2000, "--json")
    expect(j["against_rays"]["missed"]["samples"] == 0 and j["ok"] is True, j["against_rays"])
    expect(j["against_rays"]["rules"]["from"] == "map" and j["against_rays"]["rules"]["max_distance"] == 1e-9,
           j["against_rays"]["rules"])

    expect_clean_error(["check", "rays.plmap", "--against-rays", 10, "--normal-check", "bogus"],
                       mention="bogus")
    expect_clean_error(["check", "rays.plmap", "--against-rays", 0], code=64)
    # a negative tolerance would fail every map
    expect_clean_error(["check", "rays.plmap", "--against-rays", 10, "--ray-tolerance", -1], code=64,
                       mention=">= 0")


@case
def check_against_rays_along_given_directions():
    # A map projected along a direction file is checked along the same field with --directions;
    # along the default field (S1's averaged normals, vertical here) the images lie a tenth of an
    # S2 edge and more from the rays' hits.
    flat = grid("rays_dir_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "rays_dir_hill.off")
    write("rays_dir.txt", "".join("0.25 -0.1 1  # tilted\n" for _ in range(49)))
    run("project", flat, "rays_dir_hill.off", "-o", "rays_dir.plmap", "--allow-negative",
        "--directions", "rays_dir.txt")
    j = run_json("check", "rays_dir.plmap", "--against-rays", 2000, "--allow-negative",
                 "--directions", "rays_dir.txt", "--json")
    rays = j["against_rays"]
    expect(j["ok"] is True and rays["extra"]["samples"] == 0, rays)
    expect(rays["missed"]["defect_fraction"] == 0.0, rays)
    expect(rays["image_error_relative_to_edge"]["max"] < 1e-6, rays)
    # the map records that it was projected along given directions: checked without them, the
    # check asks for them; told to ignore the map's rules, it runs along the averaged normals
    expect_clean_error(["check", "rays_dir.plmap", "--against-rays", 100], code=64,
                       mention="pass the same file with --directions")
    j = run_json("check", "rays_dir.plmap", "--against-rays", 2000, "--allow-negative", "--no-recorded-rules", "--json")
    expect(j["against_rays"]["image_error_relative_to_edge"]["max"] > 0.1, j["against_rays"])
    # other directions than the map's are checked, with a warning
    write("rays_dir_other.txt", "".join("0.2 -0.1 1\n" for _ in range(49)))
    _, err, _ = run("check", "rays_dir.plmap", "--against-rays", 200, "--directions", "rays_dir_other.txt",
                    expect_code=None)
    expect("are not those rays_dir.plmap was projected along (given:" in err, err)
    _, err, _ = run("check", "rays_dir.plmap", "--against-rays", 200, "--directions", "rays_dir.txt")
    expect("warning" not in err, err)
    write("rays_dir_short.txt", "0 0 1\n0 0 1\n")
    expect_clean_error(["check", "rays_dir.plmap", "--against-rays", 10, "--directions", "rays_dir_short.txt"],
                       mention="rays_dir_short.txt")
    expect_clean_error(["check", "rays_dir.plmap", "--directions", "rays_dir.txt"], code=64,
                       mention="--against-rays")


@case
def check_against_rays_under_the_recorded_rules():
    # `plmap project` records its acceptance rules in the map (both formats keep them, `info`
    # shows them), and the ray check applies them unasked: a map with area behind S1 passes
    # without --allow-negative, and fails when told to ignore the recorded rules.
    scaled_grid_off("rules_up.off", 1.0, cells=5)
    scaled_grid_off("rules_below.off", 1.0, cells=7, height=-0.5, down=True)
    run("project", "rules_up.off", "rules_below.off", "-o", "rules.plmapb", "--allow-negative",
        "--normal-check", "facing")
    info = run_json("info", "rules.plmapb", "--json", "--no-quality")
    expect(info["provenance"] == {"made_by": "project", "projection.allow_negative_distance": "true",
                                  "projection.directions": "averaged-normals", "projection.max_distance": "inf",
                                  "projection.max_distance_is_relative": "false",
                                  "projection.normal_check": "facing"}, info)
    run("convert", "rules.plmapb", "rules.plmap")
    expect(text_of("rules.plmap").startswith("plmap-map 2\n"), text_of("rules.plmap")[:40])
    expect(run_json("info", "rules.plmap", "--json", "--no-quality")["provenance"] == info["provenance"], "text")
    for m in ["rules.plmapb", "rules.plmap"]:
        j = run_json("check", m, "--against-rays", 1000, "--json")
        rays = j["against_rays"]
        expect(j["ok"] is True and rays["extra"]["samples"] == 0 and rays["missed"]["samples"] == 0, rays)
        expect(rays["rules"] == {"from": "map", "max_distance": "inf", "max_distance_is_relative": False,
                                 "allow_negative_distance": True, "normal_check": "facing",
                                 "directions": "averaged-normals"}, rays["rules"])
    out, _, _ = run("check", "rules.plmapb", "--against-rays", 500)
    expect("rules from the map: distance limit none, hits behind S1 too, normal check facing" in out, out)
    j = run_json("check", "rules.plmapb", "--against-rays", 1000, "--no-recorded-rules", "--json", expect_code=1)
    rays = j["against_rays"]
    expect(rays["extra"]["by_reason"]["behind_domain"]["samples"] > 900, rays["extra"])
    expect(rays["rules"]["from"] == "command line" and rays["rules"]["allow_negative_distance"] is False, rays)
    # the command line's rule replaces the recorded one, the others stay
    j = run_json("check", "rules.plmapb", "--against-rays", 1000, "--normal-check", "aligned", "--json",
                 expect_code=1)
    rays = j["against_rays"]
    expect(rays["rules"]["from"] == "map, with the command line's" and rays["rules"]["normal_check"] == "aligned"
           and rays["rules"]["allow_negative_distance"] is True, rays["rules"])
    expect(j["ok"] is False and rays["extra"]["samples"] == 1000, rays["extra"])
    expect(rays["extra"]["by_reason"]["against_normal_check"]["samples"] > 300, rays["extra"])
    # repeating a recorded rule on the command line changes nothing, and is not called an override
    j = run_json("check", "rules.plmapb", "--against-rays", 300, "--allow-negative", "--normal-check", "facing",
                 "--json")
    expect(j["ok"] is True and j["against_rays"]["rules"]["from"] == "map", j["against_rays"]["rules"])
    # a map made otherwise records nothing and is checked under the command line's rules
    run("build", "identity", "rules_up.off", "-o", "rules_id.plmap")
    expect(text_of("rules_id.plmap").startswith("plmap-map 1\n"), text_of("rules_id.plmap")[:40])
    j = run_json("check", "rules_id.plmap", "--against-rays", 300, "--json")
    expect(j["against_rays"]["rules"]["from"] == "command line (the map records none)", j["against_rays"]["rules"])
