# Command-line cases of issue 12: scale (defect 8) and isolated vertices (defect 2).
# Exec'd into cli_test.py's namespace (case, run, run_json, expect, expect_clean_error, WORK).


def scaled_grid_off(name, factor, cells=4, height=0.0, down=False, extra_vertices=()):
    """An OFF grid over [0, 1]^2 * factor at height * factor (counter-clockwise from +z unless
    `down`), with extra (isolated) vertices appended after the grid's."""
    vertices, faces = [], []
    for j in range(cells + 1):
        for i in range(cells + 1):
            x, y = i / cells, j / cells
            if 0 < i < cells and 0 < j < cells:  # a little jitter, so that grids do not match
                x += 0.1 / cells * ((i * 7 + j * 3) % 5 - 2) / 2
                y += 0.1 / cells * ((i * 5 + j * 11) % 5 - 2) / 2
            vertices.append((x * factor, y * factor, height * factor))
    vertices += [tuple(c * factor for c in v) for v in extra_vertices]
    n = cells + 1
    for j in range(cells):
        for i in range(cells):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            for tri in ((a, b, c), (a, c, d)):
                faces.append((tri[0], tri[2], tri[1]) if down else tri)
    lines = ["OFF", f"{len(vertices)} {len(faces)} 0"]
    lines += [" ".join(repr(c) for c in v) for v in vertices]
    lines += ["3 " + " ".join(str(i) for i in f) for f in faces]
    return write(name, "\n".join(lines) + "\n")


@case
def scale_measures_are_finite_at_1e78_and_accepted_at_1e_minus_150():
    for factor in (1e78, 1e-150, 1e100, 1e-100):
        s = scaled_grid_off(f"grid_{factor:g}.off", factor)
        j = run_json("info", s, "--json")
        expect(j["measure"] is not None and close(j["measure"], factor * factor, 1e-12),
               f"measure of the unit square scaled by {factor:g}: {j['measure']}")


@case
def scale_projection_at_1e78_maps_everything():
    unit = run_json("project", scaled_grid_off("a1.off", 1.0), scaled_grid_off("b1.off", 1.0, cells=5, height=0.2),
                    "-o", "unit.plmap", "--json")
    for factor in (1e78, 1e-150):
        a = scaled_grid_off(f"a_{factor:g}.off", factor)
        b = scaled_grid_off(f"b_{factor:g}.off", factor, cells=5, height=0.2)
        m = f"scaled_{factor:g}.plmap"
        j = run_json("project", a, b, "-o", m, "--json")
        expect(j["regions"] == unit["regions"] and j["regions"] > 0, (factor, j, unit))
        expect(close(j["covered_measure"], unit["covered_measure"] * factor * factor, 1e-9), (factor, j))
        out, _, _ = run("check", m)
        expect("valid" in out, out)


@case
def scale_outside_the_range_of_doubles_is_a_clear_error():
    for factor in (1e-160, 1e160):
        s = scaled_grid_off(f"out_{factor:g}.off", factor)
        line = expect_clean_error(["info", s], code=2, mention=s)
        expect("outside the range of doubles" in line and "1e-150 to 1e150" in line, line)


@case
def isolated_vertices_are_skipped_by_every_command():
    # one isolated vertex off the plane, one exactly on a boundary edge of the other surface
    s = scaled_grid_off("iso.off", 1.0, cells=3, extra_vertices=[(0.3, 0.3, 1.0), (0.25, 0.0, 0.0)])
    t = scaled_grid_off("iso_target.off", 1.0, cells=2, extra_vertices=[(0.45, 0.4, 0.0)])
    for args in (["build", "identity", s], ["build", "refine", s, "--random-points", 1],
                 ["build", "refine", s, "--levels", 1], ["build", "overlay", s, t]):
        m = args[1] + ".plmap"
        run(*args, "-o", m)
        run("check", m, "--parametrization")
    lifted = scaled_grid_off("iso_lifted.off", 1.0, cells=4, height=0.2, extra_vertices=[(0.5, 0.5, 0.2)])
    run("project", s, lifted, "-o", "iso_project.plmap")
    run("check", "iso_project.plmap")


@case
def project_with_random_direction_fields_writes_only_valid_maps():
    # Issue 12, defect 5: one unrelated random direction per S1 vertex. Before the fix seed 73
    # gave a region whose image collapsed onto an S2 edge (fold_over) and seed 46 an S2 edge
    # meeting one S1 element in two pieces (not_minimal), both with exit 0.
    import math
    import random
    flat = grid("rd_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "rd_hill.off")
    vertices = run_json("info", flat, "--json")["vertices"]
    for seed in range(150):
        rnd = random.Random(seed)
        rows = []
        for _ in range(vertices):
            z, a = rnd.uniform(-1, 1), rnd.uniform(0, 2 * math.pi)
            r = math.sqrt(1 - z * z)
            rows.append(f"{r * math.cos(a)!r} {r * math.sin(a)!r} {z!r}")
        write("rd_directions.txt", "\n".join(rows) + "\n")
        run("project", flat, "rd_hill.off", "-o", "rd.plmap", "--directions", "rd_directions.txt", "--allow-negative")
        out, _, code = run("check", "rd.plmap", expect_code=None)
        expect(code == 0, f"direction field seed {seed}: invalid map\n{out}")
    # Directions are directions whatever their length: rows scaled by about 1e200 or 1e-200 (whose
    # squared norms overflow or underflow; powers of two, so that the scaled rows are exact) give
    # the map of the unscaled rows.
    rows = [f"{0.1 * (i % 3)!r} {-0.05 * (i % 2)!r} 1.0" for i in range(vertices)]
    maps = []
    for scale in (1.0, 2.0 ** 664, 2.0 ** -664):
        write("rd_scaled.txt", "\n".join(" ".join(repr(float(x) * scale) for x in r.split()) for r in rows) + "\n")
        run("project", flat, "rd_hill.off", "-o", f"rd_scaled_{len(maps)}.plmapb", "--directions", "rd_scaled.txt",
            "--allow-negative")
        with open(os.path.join(WORK, f"rd_scaled_{len(maps)}.plmapb"), "rb") as f:
            maps.append(f.read())
    expect(maps[0] == maps[1] == maps[2], "scaled direction rows give other maps")
