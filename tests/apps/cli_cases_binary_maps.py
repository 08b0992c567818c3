# The binary map format (.plmapb, docs/map-format.md): every command that writes a map writes it
# when the output name says so, every command that reads maps reads it, `plmap convert` converts
# maps both ways byte for byte, and damaged binary files give one clear error line.
# exec'd into cli_test.py's namespace (case, run, run_json, expect, expect_clean_error, WORK, ...).


def file_bytes(name):
    with open(os.path.join(WORK, name), "rb") as f:
        return f.read()


@case
def binary_maps_written_read_and_converted():
    flat = grid("bin_flat.off", cells=6, jitter=0.1, seed=5)
    run("generate", "delaunay", "--points", 40, "--lift", "--seed", 9, "-o", "bin_hill.off")
    text = run_json("project", flat, "bin_hill.off", "-o", "bin.plmap", "--allow-negative", "--json")
    binary = run_json("project", flat, "bin_hill.off", "-o", "bin.plmapb", "--allow-negative", "--json")
    expect(file_bytes("bin.plmapb")[:8] == b"\x89PLMAPB\n", "project -o x.plmapb did not write the binary format")
    expect(text["regions"] == binary["regions"], (text, binary))
    # Readers take either format and say the same.
    info_binary, info_text = run_json("info", "bin.plmapb", "--json"), run_json("info", "bin.plmap", "--json")
    info_binary.pop("file")
    info_text.pop("file")
    expect(info_binary == info_text, ("info differs", info_binary, info_text))
    run("check", "bin.plmapb")
    run("regions", "bin.plmap", "-o", "bin_text.csv")
    run("regions", "bin.plmapb", "-o", "bin_binary.csv")
    expect(file_bytes("bin_text.csv") == file_bytes("bin_binary.csv"), "the regions differ between the formats")
    # convert: text -> binary -> text reproduces the text file byte for byte.
    run("convert", "bin.plmap", "conv.plmapb")
    run("convert", "conv.plmapb", "conv.plmap")
    expect(file_bytes("conv.plmapb") == file_bytes("bin.plmapb"), "convert wrote another binary file")
    expect(file_bytes("conv.plmap") == file_bytes("bin.plmap"), "text -> binary -> text changed the file")
    # A map is not converted to a surface format.
    expect_clean_error(["convert", "bin.plmapb", "x.off"], code=64, mention="x.off")


@case
def damaged_binary_maps_are_refused_in_one_line():
    flat = grid("dmg_flat.off", cells=4, jitter=0.1, seed=5)
    run("build", "identity", flat, "-o", "dmg.plmapb")
    data = file_bytes("dmg.plmapb")
    with open(os.path.join(WORK, "cut.plmapb"), "wb") as f:
        f.write(data[:len(data) // 2])
    expect_clean_error(["info", "cut.plmapb"], mention="truncated")
    flipped = bytearray(data)
    flipped[len(data) - 70] ^= 0x10  # inside the last array
    with open(os.path.join(WORK, "flip.plmapb"), "wb") as f:
        f.write(bytes(flipped))
    expect_clean_error(["check", "flip.plmapb"], mention="flip.plmapb")
    future = bytearray(data)
    future[8] = 9
    with open(os.path.join(WORK, "future.plmapb"), "wb") as f:
        f.write(bytes(future))
    expect_clean_error(["eval", "future.plmapb", "-n", 10], mention="version 9")
    # a map file cut to nothing or to its first bytes is a damaged map for `info` too (it said
    # "unknown surface format"): its name says it is a map
    for name, content in (("empty.plmapb", b""), ("stub.plmapb", data[:7]), ("stub.plmap", b"plmap 1\n")):
        with open(os.path.join(WORK, name), "wb") as f:
            f.write(content)
        line = expect_clean_error(["info", name], mention=name)
        expect("surface format" not in line, line)
