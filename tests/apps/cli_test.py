#!/usr/bin/env python3
"""Command-line tests of `plmap`: each case runs the built binary on small generated inputs
and checks exit codes, JSON output, the files written and the error messages.

    cli_test.py --list                                  the case names, one per line
    cli_test.py --plmap BIN --work DIR CASE             runs one case in DIR (emptied first)

Cases live here and in cli_cases_*.py beside this file (one file per topic).
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

PLMAP = None
WORK = None
CASES = {}


def case(function):
    CASES[function.__name__] = function
    return function


class Failure(Exception):
    pass


def expect(condition, message):
    if not condition:
        raise Failure(message)


def run(*args, expect_code=0, stdin=None):
    """Runs plmap, checks the exit code, returns (stdout, stderr)."""
    command = [PLMAP] + [str(a) for a in args]
    try:
        done = subprocess.run(command, cwd=WORK, capture_output=True, text=True, timeout=120,
                              stdin=subprocess.DEVNULL if stdin is None else stdin)
    except subprocess.TimeoutExpired:
        raise Failure(f"`{' '.join(command)}` hung (no exit within 120 s)")
    if expect_code is not None and done.returncode != expect_code:
        raise Failure(f"`{' '.join(command)}` exited with {done.returncode}, expected "
                      f"{expect_code}\nstdout:\n{done.stdout}\nstderr:\n{done.stderr}")
    return done.stdout, done.stderr, done.returncode


def run_json(*args, expect_code=0):
    out, _, _ = run(*args, expect_code=expect_code)
    try:
        return json.loads(out)
    except json.JSONDecodeError as e:
        raise Failure(f"`plmap {' '.join(map(str, args))}` printed invalid JSON ({e}):\n{out}")


def expect_keys(obj, keys, what):
    missing = [k for k in keys if k not in obj]
    expect(not missing, f"{what}: missing keys {missing} in {json.dumps(obj)[:500]}")


def expect_clean_error(args, code=2, mention=None):
    """The command fails with `code`, prints exactly one line on stderr starting with
    'plmap:' (mentioning `mention`), and shows no sign of a crash."""
    _, err, _ = run(*args, expect_code=code)
    lines = err.strip().splitlines()
    expect(len(lines) == 1, f"`plmap {' '.join(map(str, args))}`: expected one error line, "
                            f"got {len(lines)}:\n{err}")
    expect(lines[0].startswith("plmap: "), f"error line does not start with 'plmap: ': {err}")
    for crash in ("terminate called", "Aborted", "Segmentation", "AddressSanitizer",
                  "runtime error", "internal error"):
        expect(crash not in err, f"crash-like output: {err}")
    if mention is not None:
        expect(mention in lines[0], f"error line should mention '{mention}': {lines[0]}")
    return lines[0]


def close(a, b, tol=1e-9):
    return abs(a - b) <= tol * max(1.0, abs(a), abs(b))


def write(name, content):
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        f.write(content)
    return name


# ---- fixtures ----------------------------------------------------------------------------------

def grid(name="grid.off", cells=4, jitter=0.0, seed=1, extra=()):
    run("generate", "grid", "--cells", cells, "--jitter", jitter, "--seed", seed, *extra,
        "-o", name)
    return name


def delaunay(name="delaunay.off", points=12, seed=2):
    run("generate", "delaunay", "--points", points, "--seed", seed, "-o", name)
    return name


def polyline(name="line.curve", segments=6, seed=3, closed=False):
    run("generate", "polyline", "--segments", segments, "--seed", seed,
        *(["--closed"] if closed else []), "-o", name)
    return name


def identity_map(surface, name="identity.plmap"):
    run("build", "identity", surface, "-o", name)
    return name


# ---- cases -------------------------------------------------------------------------------------

@case
def help_texts():
    out, _, _ = run("--help")
    for command in ("info", "check", "eval", "regions", "export", "convert", "build", "generate",
                    "experiment"):
        expect(command in out, f"`plmap --help` does not mention {command}")
        sub, _, _ = run(command, "--help")
        expect("Usage" in sub or "usage" in sub.lower(), f"`plmap {command} --help`: {sub}")
    for sub in (("build", "identity"), ("build", "refine"), ("build", "overlay"),
                ("generate", "grid"), ("generate", "delaunay"), ("generate", "polyline")):
        out, _, _ = run(*sub, "--help")
        expect("--output" in out, f"`plmap {' '.join(sub)} --help` lacks --output: {out}")


@case
def usage_errors():
    expect_clean_error([], code=64)
    expect_clean_error(["frobnicate"], code=64)
    expect_clean_error(["info"], code=64)  # FILE missing
    expect_clean_error(["eval", "x.plmap", "--random", "many"], code=64)
    expect_clean_error(["build", "refine", "s.off", "-o", "m.plmap", "--levels", "99"], code=64)
    # A number that must be positive says so, in a line a person can read.
    for option, value in (("--max-distance", "-1"), ("--max-distance", "abc")):
        line = expect_clean_error(["project", "a.off", "b.off", "-o", "m.plmap", option, value], code=64,
                                  mention="must be a positive number")
        expect(len(line) < 200, f"error line too long: {line}")
    expect_clean_error(["eval", "x.plmap", "--random", "5", "--repeat", "0"], code=64,
                       mention="--repeat: must be a positive number")


@case
def info_surface():
    s = grid(cells=4)
    j = run_json("info", s, "--json")
    expect_keys(j, ["kind", "dimension", "vertices", "elements", "edges", "measure",
                    "bounding_box", "boundary_edges", "boundary_vertices", "non_manifold_edges",
                    "non_manifold_vertices", "coincident_vertices", "self_intersecting_pairs"], "info surface")
    expect(j["self_intersecting_pairs"] == 0, j)
    expect(j["kind"] == "surface" and j["dimension"] == 2, j)
    expect(j["vertices"] == 25 and j["elements"] == 32, f"4x4 grid counts: {j}")
    expect(j["edges"] == 25 + 32 - 1, f"Euler: V - E + F = 1 for a disc: {j}")
    expect(close(j["measure"], 1.0), f"unit square area: {j['measure']}")
    expect(j["boundary_edges"] == 16 and j["boundary_vertices"] == 16, j)
    expect(j["non_manifold_edges"] == 0 and j["non_manifold_vertices"] == 0, j)
    expect(j["bounding_box"]["min"][:2] == [0, 0] and j["bounding_box"]["max"][:2] == [1, 1], j)
    out, _, _ = run("info", s)
    expect("vertices: 25" in out, f"text output: {out}")


@case
def info_curve():
    c = polyline(segments=5, closed=True)
    j = run_json("info", c, "--json")
    expect(j["dimension"] == 1 and j["elements"] == 5 and j["vertices"] == 5, j)
    expect(j["boundary_vertices"] == 0, f"closed polyline has no boundary: {j}")


@case
def info_map():
    m = identity_map(grid(cells=2))
    j = run_json("info", m, "--json")
    expect_keys(j, ["kind", "dimension", "domain", "target", "nodes", "regions", "coverage",
                    "quality"], "info map")
    expect(j["kind"] == "map" and j["dimension"] == 2, j)
    expect(j["regions"] == 8, f"identity of 8 triangles has 8 regions: {j['regions']}")
    expect(j["nodes"]["by_type"]["corner"] == 24, f"3 corner copies per triangle: {j['nodes']}")
    expect(j["nodes"]["total"] == 24, j["nodes"])
    expect(close(j["coverage"]["domain_fraction"], 1.0), j["coverage"])
    expect(close(j["quality"]["kappa_max"], 1.0, 1e-6), f"identity: kappa = 1, {j['quality']}")


@case
def build_identity_and_check():
    for surface in (grid(cells=3, jitter=0.1, extra=["--lift"]), polyline(segments=7)):
        m = identity_map(surface, surface + ".plmap")
        out, _, _ = run("check", m)
        expect("valid" in out, out)
        report = run_json("check", m, "--json")
        expect_keys(report, ["ok", "violation_count", "checks"], "check --json")
        expect(report["ok"] is True and report["violation_count"] == 0, report)


@case
def build_refine():
    s = grid(cells=2)
    for levels, regions in ((0, 8), (1, 32), (2, 128)):
        m = f"refine{levels}.plmap"
        j = run_json("build", "refine", s, "--levels", levels, "-o", m, "--json")
        expect(j["regions"] == regions and j["target"]["elements"] == regions, j)
        run("check", m, "--parametrization")
    c = polyline(segments=3)
    j = run_json("build", "refine", c, "--levels", 3, "-o", "curve.plmap", "--json")
    expect(j["regions"] == 24 and j["dimension"] == 1, j)
    run("check", "curve.plmap", "--parametrization")
    # random refinement: reproducible from the seed
    run("build", "refine", s, "--random-points", 2, "--seed", 5, "-o", "r1.plmap")
    run("build", "refine", s, "--random-points", 2, "--seed", 5, "-o", "r2.plmap")
    run("check", "r1.plmap", "--parametrization")
    with open(os.path.join(WORK, "r1.plmap")) as a, open(os.path.join(WORK, "r2.plmap")) as b:
        expect(a.read() == b.read(), "same seed, different maps")


@case
def build_overlay():
    a, b = grid(cells=4, jitter=0.15, seed=4), delaunay(points=15, seed=6)
    j = run_json("build", "overlay", a, b, "-o", "overlay.plmap", "--json")
    expect(j["regions"] > 32, j)
    run("check", "overlay.plmap", "--parametrization")
    info = run_json("info", "overlay.plmap", "--json")
    expect(info["nodes"]["by_type"]["intersection"] > 0, f"edges cross: {info['nodes']}")
    expect(close(info["coverage"]["target_fraction"], 1.0, 1e-8), info["coverage"])


@case
def project_surfaces():
    flat = grid("flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "hill.off")
    j = run_json("project", flat, "hill.off", "-o", "projection.plmap", "--allow-negative", "--json")
    expect_keys(j, ["domain_measure", "target_measure", "covered_measure", "regions",
                    "edges_not_inserted", "seconds"], "project --json")
    expect(close(j["covered_measure"], j["domain_measure"], 1e-9), j)
    expect(close(j["covered_target_measure"], j["target_measure"], 1e-9), j)
    expect(j["edges_not_inserted"] == 0, j)
    run("check", "projection.plmap")
    # without negative distances the hill's part below the flat grid is out of reach: what D
    # leaves out is reported by why, and with what it covers adds up to S1's measure
    j = run_json("project", flat, "hill.off", "-o", "above.plmap", "--json")
    left_out = j["left_out_measure"]
    expect(set(left_out) == {"outside", "reversed", "unmapped", "enclosed", "folded", "unbacked", "occluded"},
           left_out)
    expect(j["covered_measure"] < j["domain_measure"], j)
    expect(close(j["covered_measure"] + sum(left_out.values()), j["domain_measure"], 1e-9), j)
    # a surface projected onto itself is the identity: one region per element
    ident = run_json("project", flat, flat, "-o", "self.plmap", "--json")
    info = run_json("info", flat, "--json")
    expect(ident["regions"] == info["elements"], (ident, info))
    expect_clean_error(["project", flat, "hill.off", "-o", "x.plmap", "--solver", "bogus"],
                       mention="bogus")
    expect_clean_error(["project", flat, polyline(), "-o", "x.plmap"])


@case
def check_detects_invalid_map():
    m = identity_map(grid(cells=2))
    with open(os.path.join(WORK, m)) as f:
        text = f.read()
    expect("orientation 1\n" in text, "map file has an orientation line")
    # Claiming the map reverses orientation contradicts every region: a parseable, invalid map.
    write("flipped.plmap", text.replace("orientation 1\n", "orientation -1\n", 1))
    out, _, _ = run("check", "flipped.plmap", expect_code=1)
    expect("INVALID" in out, out)
    report = run_json("check", "flipped.plmap", "--json", expect_code=1)
    expect(report["ok"] is False and report["violation_count"] > 0, report)


@case
def eval_random():
    m = identity_map(grid(cells=4, jitter=0.1))
    results = {}
    for locator in ("brown-faigle", "straight-walk", "brute-force"):
        j = run_json("eval", m, "--random", 2000, "--seed", 7, "--locator", locator,
                     "--threads", 2, "--json")
        expect_keys(j, ["points", "found", "fraction_found", "evaluations_per_second", "seconds",
                        "locator", "seed", "threads"], "eval --json")
        expect(j["points"] == 2000 and j["locator"] == locator, j)
        expect(j["fraction_found"] == 1.0, f"identity map covers S1: {j}")
        expect(j["evaluations_per_second"] > 0, j)
        results[locator] = j["found"]
    j = run_json("eval", m, "--json")  # defaults
    expect(j["locator"] == "brown-faigle", j)
    c = identity_map(polyline(segments=9), "curve.plmap")
    j = run_json("eval", c, "--random", 500, "--json")
    expect(j["locator"] == "bisection" and j["fraction_found"] == 1.0, j)
    line = expect_clean_error(["eval", m, "--locator", "psychic"], mention="psychic")
    expect("brown-faigle" in line, f"lists the valid names: {line}")
    expect_clean_error(["eval", c, "--locator", "straight-walk"], mention="straight-walk")


@case
def regions_csv_and_vtu():
    m = identity_map(grid(cells=2))
    run("build", "refine", "grid.off", "--levels", 1, "-o", "refined.plmap")
    run("regions", "refined.plmap", "-o", "regions.csv")
    with open(os.path.join(WORK, "regions.csv")) as f:
        rows = list(csv.DictReader(f))
    expect(len(rows) == 32, f"32 regions, got {len(rows)} rows")
    expect_keys(rows[0], ["region", "domain_element", "target_element", "domain_measure",
                          "target_measure"], "regions.csv header")
    total = sum(float(r["domain_measure"]) for r in rows)
    expect(close(total, 1.0, 1e-12), f"regions tile the unit square: {total}")
    run("regions", m, "-o", "regions.vtu")
    root = ElementTree.parse(os.path.join(WORK, "regions.vtu")).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    expect(piece is not None and piece.get("NumberOfCells") == "8", ElementTree.tostring(root)[:300])
    leftovers = [f for f in os.listdir(WORK) if f.startswith(".")]
    expect(not leftovers, f"scratch files left behind: {leftovers}")
    expect_clean_error(["regions", m, "-o", "regions.txt"], code=64, mention="regions.txt")


@case
def export_vtu_set():
    m = identity_map(grid(cells=2))
    out, _, _ = run("export", m, "-o", "vtk")
    files = sorted(os.listdir(os.path.join(WORK, "vtk")))
    expect("map.pvd" in files and "regions.vtu" in files and "domain.vtu" in files, files)
    for name in files:
        ElementTree.parse(os.path.join(WORK, "vtk", name))  # well-formed XML
    expect("map.pvd" in out, out)


@case
def convert_formats():
    s = grid(cells=3, jitter=0.1, extra=["--lift"])
    reference = run_json("info", s, "--json")
    for ext in ("ply", "obj", "msh", "stl", "off"):
        out = f"copy.{ext}"
        run("convert", s, out)
        j = run_json("info", out, "--json")
        expect(j["elements"] == reference["elements"], f"{ext}: {j}")
        expect(j["vertices"] == reference["vertices"], f"{ext}: {j}")
        tol = 1e-6 if ext == "stl" else 1e-12  # binary STL stores floats
        expect(close(j["measure"], reference["measure"], tol), f"{ext}: {j['measure']}")
    run("convert", s, "ascii.ply", "--encoding", "ascii")
    with open(os.path.join(WORK, "ascii.ply"), "rb") as f:
        expect(b"format ascii" in f.read(200), "ASCII PLY requested")
    c = polyline(segments=4)
    run("convert", c, "line.msh")
    j = run_json("info", "line.msh", "--json")
    expect(j["dimension"] == 1 and j["elements"] == 4, f"Gmsh curve: {j}")
    expect_clean_error(["convert", s, "out.xyz"], code=64, mention="out.xyz")
    expect_clean_error(["convert", c, "line.off"])  # OFF cannot hold a curve


@case
def bad_inputs():
    expect_clean_error(["info", "missing.off"], mention="missing.off")
    expect_clean_error(["check", "missing.plmap"], mention="missing.plmap")
    expect_clean_error(["eval", "missing.plmap"], mention="missing.plmap")
    expect_clean_error(["convert", "missing.off", "x.ply"], mention="missing.off")
    expect_clean_error(["build", "identity", "missing.off", "-o", "x.plmap"], mention="missing.off")
    os.mkdir(os.path.join(WORK, "adir"))
    expect_clean_error(["info", "adir"], mention="adir")
    write("garbage.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n")
    expect_clean_error(["info", "garbage.off"], mention="garbage.off")
    write("truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n")
    expect_clean_error(["info", "truncated.off"], mention="truncated.off")
    write("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n")
    expect_clean_error(["info", "nan.off"], mention="nan.off")
    write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    expect_clean_error(["info", "range.off"], mention="range.off")
    write("huge.off", "OFF\n2000000000 2000000000 0\n0 0 0\n")
    expect_clean_error(["info", "huge.off"], mention="huge.off")
    write("mystery.xyz", "just some words\n")
    expect_clean_error(["info", "mystery.xyz"], mention="mystery.xyz")
    expect_clean_error(["check", "garbage.off"], mention="garbage.off")  # not a map
    # a map file cut in the middle
    m = identity_map(grid(cells=2))
    with open(os.path.join(WORK, m)) as f:
        text = f.read()
    write("cut.plmap", text[: len(text) // 2])
    for command in ("info", "check", "eval", "export"):
        args = [command, "cut.plmap"] + (["-o", "cut-vtk"] if command == "export" else [])
        expect_clean_error(args, mention="cut.plmap")
    write("nan.plmap", text.replace("corner 0 0 0", "corner 0 nan 0", 1))
    expect_clean_error(["check", "nan.plmap"], mention="nan.plmap")
    # overlay of a non-planar surface is refused before anything is written
    lifted = grid("lifted.off", cells=2, extra=["--lift"])
    write("keep.plmap", "old content\n")
    expect_clean_error(["build", "overlay", lifted, "grid.off", "-o", "keep.plmap"])
    with open(os.path.join(WORK, "keep.plmap")) as f:
        expect(f.read() == "old content\n", "a failed build must not touch the output file")


@case
def outputs_are_atomic():
    s = grid(cells=2)
    write("existing.ply", "previous\n")
    # the input fails to parse: the existing output stays as it was, and no temporary is left
    write("broken.off", "OFF\n3 1 0\n0 0 0\n")
    expect_clean_error(["convert", "broken.off", "existing.ply"])
    with open(os.path.join(WORK, "existing.ply")) as f:
        expect(f.read() == "previous\n", "failed conversion overwrote its output")
    run("convert", s, "existing.ply")
    j = run_json("info", "existing.ply", "--json")
    expect(j["elements"] == 8, j)
    expect(sorted(os.listdir(WORK)) == ["broken.off", "existing.ply", "grid.off"],
           f"stray files: {sorted(os.listdir(WORK))}")
    expect_clean_error(["convert", s, "no-such-dir/out.off"], mention="no-such-dir")


@case
def generate_is_reproducible():
    grid("a.off", cells=4, jitter=0.2, seed=11)
    grid("b.off", cells=4, jitter=0.2, seed=11)
    grid("c.off", cells=4, jitter=0.2, seed=12)
    read = lambda n: open(os.path.join(WORK, n)).read()
    expect(read("a.off") == read("b.off"), "same seed, different files")
    expect(read("a.off") != read("c.off"), "different seeds, same file")
    grid("hole.off", cells=8, extra=["--hole"])
    j = run_json("info", "hole.off", "--json")
    expect(close(j["measure"], 1.0 - 0.25 * 0.25), f"square minus hole: {j['measure']}")
    expect_clean_error(["generate", "grid", "--cells", 3, "--hole", "-o", "h.off"], mention="4")


def load_case_files():
    """Runs every cli_cases_*.py beside this file in this module's namespace, so that each topic
    keeps its cases in a file of its own while sharing run(), expect() and the CASES registry."""
    here = os.path.dirname(os.path.abspath(__file__))
    for name in sorted(os.listdir(here)):
        if name.startswith("cli_cases_") and name.endswith(".py"):
            path = os.path.join(here, name)
            with open(path) as f:
                exec(compile(f.read(), path, "exec"), globals())


load_case_files()


def main():
    global PLMAP, WORK
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--plmap")
    parser.add_argument("--work")
    parser.add_argument("case", nargs="?")
    args = parser.parse_args()
    if args.list:
        print("\n".join(CASES))
        return 0
    if not (args.plmap and args.work and args.case in CASES):
        parser.error(f"need --plmap, --work and one of: {', '.join(CASES)}")
    PLMAP = os.path.abspath(args.plmap)
    WORK = os.path.abspath(args.work)
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    try:
        CASES[args.case]()
    except Failure as e:
        print(f"FAIL {args.case}: {e}", file=sys.stderr)
        return 1
    print(f"ok {args.case}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
