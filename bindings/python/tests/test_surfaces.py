"""plmap.Surface: from and to numpy arrays and files, and the errors of bad input."""

import numpy as np
import pytest

import plmap
from conftest import grid, polyline


def test_arrays_round_trip_exactly_for_both_dimensions():
    rng = np.random.default_rng(1)
    vertices, triangles = grid(4, 3, 0.0, 0.0, 1.0, 1.0)
    vertices[:, :2] += 0.01 * rng.random((len(vertices), 2))
    s = plmap.Surface(vertices, triangles)
    assert s.dimension == 2
    assert (s.vertex_count, s.element_count) == (20, 24)
    assert np.array_equal(s.vertices, vertices)
    assert np.array_equal(s.elements, triangles)
    assert s.elements.dtype == np.int32

    points, segments = polyline(0.0, 2.0, 5, 0.5)
    c = plmap.Surface(points, segments.astype(np.uint16))
    assert c.dimension == 1
    assert c.measure == pytest.approx(2.0, rel=1e-15)
    assert np.array_equal(c.vertices, points)


def test_self_intersections_are_the_pairs_that_meet_without_a_shared_vertex():
    # the unit square (two triangles sharing an edge) and a vertical triangle through the inside
    # of the first: one pair; without it, none
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                         [0.5, 0.2, -0.1], [0.7, 0.2, -0.1], [0.6, 0.2, 0.1]], dtype=float)
    triangles = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]])
    assert plmap.Surface(vertices, triangles).self_intersections() == [(0, 2)]
    assert plmap.Surface(vertices, triangles).self_intersections(threads=1) == [(0, 2)]
    assert plmap.Surface(vertices[:4], triangles[:2]).self_intersections() == []


def test_measure_is_the_area():
    s = plmap.Surface(*grid(3, 5, 0.0, 0.0, 2.0, 0.5))
    assert s.measure == pytest.approx(1.0, rel=1e-14)


@pytest.mark.parametrize("extension", [".off", ".ply", ".obj", ".msh"])
def test_file_round_trip_is_exact(work_dir, extension):
    rng = np.random.default_rng(2)
    vertices, triangles = grid(3, 3, 0.0, 0.0, 1.0, 1.0, height=lambda x, y: 0.1 * np.sin(3 * x) * y)
    vertices[:, :2] += 0.05 * rng.random((len(vertices), 2))
    path = work_dir / f"s{extension}"
    plmap.Surface(vertices, triangles).save(path)
    back = plmap.read_surface(path)
    assert back.dimension == 2
    assert np.array_equal(back.vertices, vertices)
    assert np.array_equal(back.elements, triangles)


def test_curves_are_recognised_by_extension(work_dir):
    points, segments = polyline(-1.0, 1.0, 4, 0.25)
    plmap.Surface(points, segments).save(str(work_dir / "c.curve"))
    back = plmap.read_surface(str(work_dir / "c.curve"))
    assert back.dimension == 1
    assert np.array_equal(back.vertices, points)


def test_errors_are_plmap_errors_and_value_errors():
    assert issubclass(plmap.Error, ValueError)
    for sub in (plmap.ParseError, plmap.InvalidSurfaceError, plmap.BuilderError, plmap.InvalidMapError):
        assert issubclass(sub, plmap.Error)


def test_missing_file_names_the_file(work_dir):
    with pytest.raises(plmap.ParseError, match="no_such.off"):
        plmap.read_surface(work_dir / "no_such.off")


def test_malformed_file_names_file_and_line(work_dir):
    path = work_dir / "bad.off"
    path.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 oops 0\n3 0 1 2\n")
    with pytest.raises(plmap.ParseError, match=r"bad\.off:line 5: expected a vertex coordinate"):
        plmap.read_surface(path)


def test_invalid_surfaces_name_the_vertex_or_element():
    vertices, triangles = grid(2, 2, 0.0, 0.0, 1.0, 1.0)
    with_nan = vertices.copy()
    with_nan[4, 1] = np.nan
    with pytest.raises(plmap.InvalidSurfaceError, match="vertex 4"):
        plmap.Surface(with_nan, triangles)
    repeated = triangles.copy()
    repeated[3] = [1, 1, 2]
    with pytest.raises(plmap.InvalidSurfaceError, match="element 3"):
        plmap.Surface(vertices, repeated)


def test_bad_arrays_are_type_value_and_index_errors():
    vertices, triangles = grid(2, 2, 0.0, 0.0, 1.0, 1.0)
    with pytest.raises(TypeError, match="elements: expected an integer array"):
        plmap.Surface(vertices, triangles.astype(float))
    with pytest.raises(ValueError, match=r"vertices: expected shape \(n, 3\).*got \(9, 4\)"):
        plmap.Surface(np.zeros((9, 4)), triangles)
    with pytest.raises(ValueError, match=r"elements: expected shape \(n, 3\), got \(8, 2\)"):
        plmap.Surface(vertices, triangles[:, :2])
    out_of_range = triangles.copy()
    out_of_range[5, 2] = 2**40  # would wrap to a valid index if narrowed unchecked
    with pytest.raises(IndexError, match=r"elements\[5, 2\] = 1099511627776 is not a vertex index"):
        plmap.Surface(vertices, out_of_range)
    with pytest.raises(TypeError, match="expected a plmap.Surface or a file path"):
        plmap.project(42, plmap.Surface(vertices, triangles))


def test_merge_coincident_vertices_welds_a_soup():
    # the unit square as two triangles with corners of their own: vertices 3 and 5 lie on 1 and 2
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    soup = plmap.Surface(vertices, np.array([[0, 1, 2], [3, 4, 5]]))
    welded, merged, duplicates = soup.merge_coincident_vertices()
    assert (merged, duplicates) == (2, 0)
    assert welded.vertex_count == 4
    assert welded.elements.tolist() == [[0, 1, 2], [1, 3, 2]]
    assert welded.vertices.tolist()[3] == [1.0, 1.0, 0.0]
    assert soup.vertex_count == 6  # the original is unchanged
