# `plmap project --renumber`: the projection on copies in spatial order (docs/projection.md,
# "The order of the input"). A mesh whose triangles come in a random order, as most meshes
# written by other tools do, is renumbered by default; the map is in the input's numbers either
# way and covers the same. Exec'd into cli_test.py's namespace.

import random


def shuffled_off(source, name, seed):
    """The OFF file `source` with its vertices and faces in a random order (each face keeps its
    corners in their order)."""
    with open(os.path.join(WORK, source)) as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    nv, nf = int(words[1]), int(words[2])
    at = 4
    points = [words[at + 3 * i: at + 3 * i + 3] for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[at])
        faces.append([int(w) for w in words[at + 1: at + 1 + k]])
        at += 1 + k
    rng = random.Random(seed)
    order = list(range(nv))
    rng.shuffle(order)  # order[new] = old
    new_of_old = {old: new for new, old in enumerate(order)}
    rng.shuffle(faces)
    lines = ["OFF", f"{nv} {nf} 0"] + [" ".join(points[old]) for old in order]
    lines += [f"{len(c)} " + " ".join(str(new_of_old[v]) for v in c) for c in faces]
    return write(name, "\n".join(lines) + "\n")


@case
def project_renumbers_a_shuffled_target():
    flat = grid("rn_flat.off", cells=12, jitter=0.1, seed=5)
    grid("rn_hill.off", cells=14, jitter=0.15, seed=6, extra=("--lift",))
    hill = shuffled_off("rn_hill.off", "rn_hill_shuffled.off", seed=7)
    default = run_json("project", flat, hill, "-o", "rn_default.plmap", "--allow-negative", "--json")
    expect(default["renumbered"] == {"S1": False, "S2": True}, default["renumbered"])
    expect(default["seconds_by_phase"]["renumbering"] > 0, default["seconds_by_phase"])
    kept = run_json("project", flat, hill, "-o", "rn_never.plmap", "--allow-negative", "--renumber", "never",
                    "--json")
    expect(kept["renumbered"] == {"S1": False, "S2": False}, kept["renumbered"])
    both = run_json("project", flat, hill, "-o", "rn_always.plmap", "--allow-negative", "--renumber", "always",
                    "--json")
    expect(both["renumbered"] == {"S1": True, "S2": True}, both["renumbered"])
    # the hill lies over all of the flat grid: every way covers all of S1, and every map is valid
    for j, m in ((default, "rn_default.plmap"), (kept, "rn_never.plmap"), (both, "rn_always.plmap")):
        expect(close(j["covered_measure"], j["domain_measure"], 1e-9), (m, j["covered_measure"]))
        run("check", m)
    # the target in rows is kept
    rows = run_json("project", flat, "rn_hill.off", "-o", "rn_rows.plmap", "--allow-negative", "--json")
    expect(rows["renumbered"] == {"S1": False, "S2": False}, rows["renumbered"])

    expect_clean_error(["project", flat, hill, "-o", "rn_bad.plmap", "--renumber", "bogus"], mention="bogus")
    # the names are checked before anything is read: a missing input is not what is reported
    for option, value in (("--renumber", "bogus"), ("--normal-check", "sideways"), ("--solver", "gauss")):
        expect_clean_error(["project", "rn_missing_s1.off", "rn_missing_s2.off", "-o", "rn_bad.plmap", option, value],
                           mention=value)
    expect(not os.path.exists(os.path.join(WORK, "rn_bad.plmap")), "a rejected run wrote its map")
