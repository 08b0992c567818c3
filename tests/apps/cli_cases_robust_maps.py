# Command-line cases of issue 12: a corrupt map that passes the index-range checks is refused on
# load by every command, with the element named (defect 1), and a surface file given where a map
# is expected is named as such (defect 9). Exec'd into cli_test.py's namespace.


def _sections(text):
    """The map file as a list of lines and, per section name, the index of its header line."""
    lines = text.split("\n")
    where = {}
    for i, line in enumerate(lines):
        fields = line.split()
        if len(fields) == 2 and fields[0].isidentifier() and fields[1].isdigit():
            where.setdefault(fields[0], i)
    return lines, where


@case
def corrupt_map_is_refused_on_load():
    refine = grid("fine.off", cells=4)
    coarse = grid("coarse.off", cells=2)
    run("build", "overlay", coarse, refine, "-o", "overlay.plmap")
    with open(os.path.join(WORK, "overlay.plmap")) as f:
        lines, at = _sections(f.read())
    # Region 0 (on S1 element 0) names as its neighbour the first region of the last element:
    # every index stays in range, only the element is wrong.
    region_begin = [int(v) for v in lines[at["region_begin"] + 1: at["regions"]]]
    elements = len(region_begin) - 1
    last_first = region_begin[elements - 1]
    expect(last_first > 0 and region_begin[1] > 0, f"unexpected region layout {region_begin}")
    record = lines[at["regions"] + 1].split()
    record[3] = str(last_first)  # corners are fields 0-2, neighbours 3-5
    lines[at["regions"] + 1] = " ".join(record)
    write("corrupt.plmap", "\n".join(lines))
    for args in (["eval", "corrupt.plmap", "--locator", "cell-grid", "--random", "1000"],
                 ["eval", "corrupt.plmap"], ["regions", "corrupt.plmap", "-o", "corrupt.csv"],
                 ["export", "corrupt.plmap", "-o", "corrupt-vtk"],
                 ["draw", "corrupt.plmap", "--view3d", "-o", "corrupt.svg"], ["check", "corrupt.plmap"],
                 ["info", "corrupt.plmap"]):
        message = expect_clean_error(args, mention="corrupt.plmap")
        expect("S1 element 0" in message and f"neighbour region {last_first}" in message, message)
    for output in ("corrupt.svg", "corrupt.csv", "corrupt-vtk"):
        expect(not os.path.exists(os.path.join(WORK, output)), f"{output} written for a corrupt map")


@case
def surface_file_given_as_map():
    surface = grid("s.off", cells=2)
    for args in (["eval", surface], ["check", surface], ["regions", surface, "-o", "r.csv"],
                 ["draw", surface, "--element", "0", "-o", "s.svg"]):
        message = expect_clean_error(args, mention="s.off")
        expect("this is a surface file (OFF), not a map" in message, message)
