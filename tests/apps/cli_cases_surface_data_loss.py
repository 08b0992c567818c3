# Surface files whose data a reader used to drop with exit 0 (issue 12, defect 7): every command
# that reads a surface now refuses them with exit 2 and one line naming the file and the place.
# Exec'd into cli_test.py's namespace (case, run, expect_clean_error, write, WORK).

import os
import struct


@case
def surface_data_is_never_dropped():
    # OFF: two faces where one is announced.
    write("short.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
    expect_clean_error(["info", "short.off"], mention="short.off:line 8")
    # PLY: a record after the announced ones.
    write("extra.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n")
    expect_clean_error(["info", "extra.ply"], mention="extra.ply:line 14")
    # Gmsh: seven triangles would be read and the second-order one dropped.
    nodes = "".join(f"{i + 1} {x} {y} 0\n" for i, (x, y) in
                    enumerate([(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)]))
    write("p2.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n" + nodes + "$EndNodes\n"
                    "$Elements\n2\n1 2 0 1 4 6\n2 9 0 1 2 3 4 5 6\n$EndElements\n")
    expect_clean_error(["info", "p2.msh"], mention="p2.msh:line 16")
    # Binary STL: two facets, one announced. convert must not write the output either.
    facet = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    with open(os.path.join(WORK, "short.stl"), "wb") as f:
        f.write(b"binary".ljust(80, b" ") + struct.pack("<I", 1) + facet + facet)
    expect_clean_error(["convert", "short.stl", "out.off"], mention="short.stl:byte 134")
    expect(not os.path.exists(os.path.join(WORK, "out.off")), "convert wrote out.off from a refused file")
    # The same surfaces with correct counts are read.
    write("ok.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
    j = run_json("info", "ok.off", "--json")
    expect(j["elements"] == 2, f"ok.off: unexpected info {j}")
