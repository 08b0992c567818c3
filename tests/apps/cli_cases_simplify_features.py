# Command-line cases of `plmap simplify` on feature lines: boundaries and non-manifold spines are
# simplified along themselves (exec'd into cli_test.py's namespace).


def book_off(name="book.off", pages=3, n=6, m=2):
    """`pages` grids of n x m cells around a common spine on the x axis (non-manifold edges)."""
    import math
    vertices = [(i / n, 0.0, 0.0) for i in range(n + 1)]
    faces = []
    for p in range(pages):
        angle = 2 * math.pi * (p + 0.1) / pages
        first = len(vertices)
        for r in range(1, m + 1):
            for i in range(n + 1):
                vertices.append((i / n, math.cos(angle) * r / m, math.sin(angle) * r / m))
        vid = lambda i, r: i if r == 0 else first + (r - 1) * (n + 1) + i
        for r in range(m):
            for i in range(n):
                faces.append((vid(i, r), vid(i + 1, r), vid(i + 1, r + 1)))
                faces.append((vid(i, r), vid(i + 1, r + 1), vid(i, r + 1)))
    text = f"OFF\n{len(vertices)} {len(faces)} 0\n"
    text += "".join(f"{x} {y} {z}\n" for x, y, z in vertices)
    text += "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)
    return write(name, text)


@case
def simplify_removes_vertices_along_a_non_manifold_spine():
    book = book_off()
    j = run_json("simplify", book, "-o", "book.plmap", "--coarse", "book_coarse.off", "--target-elements", 12,
                 "--json")
    expect(j["removed_along_lines"] > 0, j)
    expect(j["feature_corners"] >= 2, j)  # the spine's ends
    expect(j["elements_after"] < 3 * 2 * 6 * 2, j)
    run("check", "--parametrization", "book.plmap")


@case
def simplify_removes_boundary_vertices_of_a_sheet():
    run("generate", "delaunay", "--points", 120, "--lift", "--seed", 21, "-o", "sheet.off")
    j = run_json("simplify", "sheet.off", "-o", "sheet.plmap", "--target-elements", 20, "--json")
    expect(j["removed_along_lines"] > 0, j)
    run("check", "--parametrization", "sheet.plmap")


@case
def simplify_rejects_faces_that_are_not_triangles_or_polygons():
    write("two.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n2 0 3\n")
    expect_clean_error(["simplify", "two.off", "-o", "two.plmap", "--target-elements", 1], mention="two.off")
    expect(not os.path.exists(os.path.join(WORK, "two.plmap")), "two.plmap was written")


@case
def simplify_curves_open_and_closed():
    run("generate", "polyline", "--segments", 120, "--seed", 5, "-o", "open.curve")
    j = run_json("simplify", "open.curve", "-o", "open.plmap", "--coarse", "open_coarse.curve",
                 "--target-elements", 10, "--feature-angle", 180, "--json")
    expect(j["target_reached"] and j["elements_after"] == 10, j)
    expect(j["feature_corners"] == 2, j)  # the two ends of the open curve
    run("check", "--parametrization", "open.plmap")
    info = run_json("info", "open_coarse.curve", "--json")
    expect(info["elements"] == 10, info)
    run("generate", "polyline", "--segments", 60, "--seed", 6, "--closed", "-o", "closed.curve")
    j = run_json("simplify", "closed.curve", "-o", "closed.plmap", "--max-error", 0.05, "--oracle",
                 "hausdorff", "--oracle", "long-edge:0.1", "--json")
    expect(j["elements_after"] < 60 and j["hausdorff_error"] <= 0.05, j)
    run("check", "--parametrization", "closed.plmap")
    expect_clean_error(["simplify", "closed.curve", "-o", "never.plmap", "--target-elements", 60],
                       mention="not below")
    expect(not os.path.exists(os.path.join(WORK, "never.plmap")), "never.plmap was written")
