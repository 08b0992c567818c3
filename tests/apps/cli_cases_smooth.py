# Command-line cases of `plmap smooth` (exec'd into cli_test.py's namespace).


def write_bumpy_icosphere(name, subdivisions=3, jitter=0.1, seed=5):
    """A subdivided icosahedron with radii drawn from [1 - jitter, 1 + jitter], as OFF."""
    import random
    rng = random.Random(seed)
    t = (1 + 5 ** 0.5) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                middle[key] = len(vertices)
                vertices.append(tuple((x + y) / 2 for x, y in zip(vertices[a], vertices[b])))
            return middle[key]
        next_faces = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            next_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = next_faces
    with open(os.path.join(WORK, name), "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        for v in vertices:
            r = (1 + rng.uniform(-jitter, jitter)) / sum(x * x for x in v) ** 0.5
            f.write(" ".join(repr(x * r) for x in v) + "\n")
        for face in faces:
            f.write("3 " + " ".join(map(str, face)) + "\n")
    return name


def simplified_sphere(name="sphere_coarse.plmap"):
    write_bumpy_icosphere("sphere_fine.off")
    run("simplify", "sphere_fine.off", "-o", name, "--target-elements", 160, "--feature-angle", 180)
    return name


@case
def smooth_passes_check_and_mean_value_lowers_kappa():
    coarse = simplified_sphere()
    for weights in ["floater", "mean-value", "uniform"]:
        out = f"smooth_{weights}.plmap"
        j = run_json("smooth", coarse, "-o", out, "--weights", weights, "--json")
        expect_keys(j, ["before", "after", "sweeps", "free_nodes", "skipped_by_reason", "seconds"], "smooth --json")
        expect(j["weights"] == weights, j)
        # The simplified sphere starts nearly isometric (kappa max 9.6, mean 1.24): mean-value
        # weights lower the mean and p99 (max 9.63 -> 9.71); floater and uniform raise them.
        if weights == "mean-value":
            expect(j["after"]["kappa_mean"] < j["before"]["kappa_mean"], j)
            expect(j["after"]["kappa_p99"] < j["before"]["kappa_p99"], j)
        expect("kappa_p99" in j["after"], j)
        expect(j["free_nodes"] > 0 and j["sweeps"][0]["nodes_moved"] > 0, j)
        run("check", "--parametrization", out)


@case
def smooth_bad_command_lines():
    coarse = simplified_sphere("sphere_coarse2.plmap")
    expect_clean_error(["smooth", coarse, "-o", "never.plmap", "--weights", "cotangent"], code=64,
                       mention="cotangent")
    expect_clean_error(["smooth", coarse, "-o", coarse], code=64)
    expect_clean_error(["smooth", coarse, "-o", "never.off"], code=64)
    expect(not os.path.exists(os.path.join(WORK, "never.plmap")), "no output after a refused command line")
