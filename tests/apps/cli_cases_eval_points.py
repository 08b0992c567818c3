# `plmap eval MAP --points FILE` and `--inverse` (issue 15): evaluation at the user's points,
# local or world, from CSV/blank-separated text or .npy, written as CSV, JSON, .npy or raw
# float64; points outside D (or Xi(D)) marked, not dropped; malformed input named by file and line.
# exec'd into cli_test.py's namespace (case, run, run_json, expect, expect_clean_error, WORK, ...).

import struct


def read_csv_rows(name):
    with open(os.path.join(WORK, name)) as f:
        return list(csv.DictReader(f))


def write_npy(name, rows, dtype="<f8"):
    """A 2-D .npy (format 1.0) written by hand, as numpy.save would."""
    cols = len(rows[0])
    header = "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d), }" % (dtype, len(rows), cols)
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    fmt_char = {"<f8": "d", "<i8": "q"}[dtype]
    with open(os.path.join(WORK, name), "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
        for r in rows:
            f.write(struct.pack("<" + fmt_char * cols, *r))
    return name


def read_npy(name):
    with open(os.path.join(WORK, name), "rb") as f:
        data = f.read()
    expect(data[:8] == b"\x93NUMPY\x01\x00", f"{name}: not a .npy 1.0 file")
    (length,) = struct.unpack("<H", data[8:10])
    header = data[10:10 + length].decode()
    expect((10 + length) % 64 == 0, f"{name}: header not padded to 64 bytes")
    shape = header[header.index("(") + 1:header.index(")")].split(",")
    rows, cols = int(shape[0]), int(shape[1])
    values = struct.unpack("<%dd" % (rows * cols), data[10 + length:])
    return [list(values[i * cols:(i + 1) * cols]) for i in range(rows)]


def wide_square_off(name="wide.off", z=0.2):
    """[-0.5, 1.5]^2 at height z, 8 triangles, normals +z."""
    v = [(-0.5 + i, -0.5 + j, z) for j in range(3) for i in range(3)]
    f = []
    for j in range(2):
        for i in range(2):
            a = 3 * j + i
            f += [(a, a + 1, a + 4), (a, a + 4, a + 3)]
    text = "OFF\n%d %d 0\n" % (len(v), len(f))
    text += "".join("%g %g %g\n" % p for p in v) + "".join("3 %d %d %d\n" % t for t in f)
    return write(name, text)


WORLD_POINTS = [(0.3, 0.4, 0.0), (0.05, 0.95, 0.0), (0.5, 0.5, 0.0), (1.0, 0.25, 0.0), (0.7, 0.1, 0.0)]


@case
def eval_points_world_and_local():
    s = grid(cells=3, jitter=0.1, seed=4)
    run("build", "refine", s, "--levels", 1, "-o", "refine.plmap")  # Xi = identity of space
    write("world.csv", "x,y,z\n" + "".join("%r,%r,%r\n" % p for p in WORLD_POINTS))
    run("eval", "refine.plmap", "--points", "world.csv", "-o", "out.csv")
    rows = read_csv_rows("out.csv")
    expect(len(rows) == len(WORLD_POINTS), rows)
    expect(list(rows[0].keys()) == ["in_domain", "element", "u", "v", "x", "y", "z", "query_element", "query_u",
                                    "query_v", "query_distance"], list(rows[0].keys()))
    for p, r in zip(WORLD_POINTS, rows):
        expect(r["in_domain"] == "1", r)
        for axis, value in zip("xyz", p):
            expect(close(float(r[axis]), value, 1e-12), f"{p} evaluated to {r}")
        expect(float(r["query_distance"]) < 1e-12, r)
    # the same points as (element, u, v), in blank-separated text with a comment: same images
    local = "# element u v\n" + "".join("%s %s %s\n" % (r["query_element"], r["query_u"], r["query_v"]) for r in rows)
    write("local.txt", local)
    run("eval", "refine.plmap", "--points", "local.txt", "-o", "local_out.csv")
    for a, b in zip(rows, read_csv_rows("local_out.csv")):
        expect(a["element"] == b["element"] and close(float(a["x"]), float(b["x"]), 1e-12), (a, b))
    # stdout without -o, and the summary with -o --json
    out, _, _ = run("eval", "refine.plmap", "--points", "local.txt")
    expect(out.splitlines()[0].startswith("in_domain,element,u,v,x,y,z"), out)
    j = run_json("eval", "refine.plmap", "--points", "world.csv", "-o", "out.json", "--json")
    expect(j["points"] == len(WORLD_POINTS) and j["in_domain"] == len(WORLD_POINTS), j)
    with open(os.path.join(WORK, "out.json")) as f:
        doc = json.load(f)
    expect(doc["direction"] == "forward" and len(doc["points"]) == len(WORLD_POINTS), doc)
    expect(doc["points"][0]["in_domain"] is True and isinstance(doc["points"][0]["element"], int), doc["points"][0])


@case
def eval_points_npy_and_raw():
    s = grid(cells=3, seed=2)
    run("build", "refine", s, "--levels", 1, "-o", "refine.plmap")
    write_npy("world.npy", WORLD_POINTS)
    run("eval", "refine.plmap", "--points", "world.npy", "--points-kind", "world", "-o", "out.npy")
    table = read_npy("out.npy")
    expect(len(table) == len(WORLD_POINTS) and len(table[0]) == 11, table)
    for p, r in zip(WORLD_POINTS, table):
        expect(r[0] == 1.0 and all(close(r[4 + k], p[k], 1e-12) for k in range(3)), (p, r))
    # int64 element column is fine for local points given as a separate int array? No: one dtype
    # per array, so local points come as float64 (element as a whole number) or int64 (corners).
    write_npy("corners.npy", [(0, 0, 0), (1, 1, 0), (2, 0, 1)], dtype="<i8")
    run("eval", "refine.plmap", "--points", "corners.npy", "-o", "corners.bin")
    with open(os.path.join(WORK, "corners.bin"), "rb") as f:
        raw = f.read()
    expect(len(raw) == 3 * 7 * 8, f"raw output has {len(raw)} bytes, expected 3 rows x 7 float64")


@case
def eval_points_inverse_marks_points_outside_the_image():
    s1 = grid(cells=4, seed=3)
    s2 = wide_square_off()
    run("project", s1, s2, "-o", "proj.plmap")
    pts = [(0.3, 0.4, 0.2), (1.2, 0.5, 0.2), (0.5, 0.5, 0.2), (-0.3, -0.3, 0.2)]
    write("s2.csv", "x,y,z\n" + "".join("%r,%r,%r\n" % p for p in pts))
    run("eval", "proj.plmap", "--inverse", "--points", "s2.csv", "-o", "back.csv")
    rows = read_csv_rows("back.csv")
    expect(list(rows[0].keys())[0] == "in_image", rows[0])
    expect([r["in_image"] for r in rows] == ["1", "0", "1", "0"], rows)
    for p, r in zip(pts, rows):
        if r["in_image"] == "1":
            expect(close(float(r["x"]), p[0], 1e-9) and close(float(r["y"]), p[1], 1e-9) and abs(float(r["z"])) < 1e-9,
                   (p, r))
        else:
            expect(r["element"] == "-1" and r["x"] == "nan", f"outside the image, yet {r}")
    # random inverse evaluation reports its throughput
    j = run_json("eval", "proj.plmap", "--inverse", "--random", 1000, "--json")
    expect(j["direction"] == "inverse" and 0.1 < j["fraction_found"] < 0.5, j)


@case
def eval_points_bad_input():
    s = grid(cells=2, seed=1)
    run("build", "refine", s, "--levels", 1, "-o", "m.plmap")
    write("ragged.csv", "element,u,v\n0,0.1,0.1\n1,0.2\n")
    expect_clean_error(["eval", "m.plmap", "--points", "ragged.csv"], mention="ragged.csv:line 3")
    write("word.csv", "0 0.1 0.1\n0 zero 0.1\n")
    expect_clean_error(["eval", "m.plmap", "--points", "word.csv"], mention="word.csv:line 2")
    write("range.csv", "element,u,v\n8,0.1,0.1\n")
    line = expect_clean_error(["eval", "m.plmap", "--points", "range.csv"], mention="range.csv:line 2")
    expect("8 elements" in line, line)
    write("outside.csv", "0 0.9 0.9\n")
    expect_clean_error(["eval", "m.plmap", "--points", "outside.csv"], mention="outside.csv:line 1")
    write("cols.csv", "1 2\n")
    expect_clean_error(["eval", "m.plmap", "--points", "cols.csv"], mention="expected 3 values")
    write("nan.csv", "0 nan 0.1\n")
    expect_clean_error(["eval", "m.plmap", "--points", "nan.csv"], mention="not finite")
    with open(os.path.join(WORK, "bad.npy"), "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) + (b"{'descr': '<f8', 'fortran_order': False, 'shape': (4, 3), }").ljust(117) + b"\n" + b"\0" * 40)
    expect_clean_error(["eval", "m.plmap", "--points", "bad.npy"], mention="bad.npy")
    expect_clean_error(["eval", "m.plmap", "--points", "missing.csv"], mention="missing.csv")
    expect_clean_error(["eval", "m.plmap", "--points", "range.csv", "-o", "out.xyz"], code=64, mention="out.xyz")
    expect_clean_error(["eval", "m.plmap", "--points", "range.csv", "--random", 5], code=64)
    expect_clean_error(["eval", "m.plmap", "-o", "out.csv"], code=64)
    expect(not os.path.exists(os.path.join(WORK, "out.xyz")), "an output was written for a bad command line")


@case
def eval_of_many_random_points_runs_in_batches():
    # Random points are drawn and evaluated 2^20 at a time: -n 1e9 held them all at once and
    # ended in "out of memory". Every point of a batch past the first still counts.
    flat = grid("batches.off", cells=3)
    run("build", "identity", flat, "-o", "batches.plmapb")
    n = (1 << 20) + 7
    j = run_json("eval", "batches.plmapb", "-n", n, "--json")
    expect(j["points"] == n and j["found"] == n and j["fraction_found"] == 1.0, j)
    expect(j["seconds"] > 0 and j["evaluations_per_second"] > 0, j)
    # the inverse evaluation too
    j = run_json("eval", "batches.plmapb", "-n", n, "--inverse", "--json")
    expect(j["points"] == n and j["found"] == n, j)
