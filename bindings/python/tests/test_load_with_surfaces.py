"""plmap.load(path, s1, s2): a map file checked against the surfaces the caller has, given as
plmap.Surface objects, (vertices, elements) arrays or surface files (issue 15)."""

import numpy as np
import pytest

import plmap
from conftest import grid, polyline

FORMATS = ["map.plmap", "map.plmapb"]


def plane_pair():
    s1_arrays = grid(5, 5, 0.0, 0.0, 1.0, 1.0)
    s2_arrays = grid(4, 4, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.5 + 0 * x)
    return s1_arrays, s2_arrays


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """Both formats of one map, and the surfaces' arrays and files."""
    folder = tmp_path_factory.mktemp("load")
    s1_arrays, s2_arrays = plane_pair()
    s1, s2 = plmap.Surface(*s1_arrays), plmap.Surface(*s2_arrays)
    m = plmap.project(s1, s2)
    for name in FORMATS:
        m.save(folder / name)
    s1.save(folder / "s1.off")
    s2.save(folder / "s2.off")
    return folder, m, s1_arrays, s2_arrays


@pytest.mark.parametrize("name", FORMATS)
def test_matching_surfaces_are_accepted_in_every_form(saved, name):
    folder, m, s1_arrays, s2_arrays = saved
    s1, s2 = plmap.Surface(*s1_arrays), plmap.Surface(*s2_arrays)
    forms = [
        (s1, s2),                                      # plmap.Surface
        (s1_arrays, s2_arrays),                        # (vertices, elements) tuples
        (list(s1_arrays), list(s2_arrays)),            # [vertices, elements] lists
        (folder / "s1.off", str(folder / "s2.off")),   # os.PathLike and str
    ]
    for a, b in forms:
        loaded = plmap.load(folder / name, a, b)
        assert loaded.region_count == m.region_count
        np.testing.assert_array_equal(loaded.regions()["domain_local"], m.regions()["domain_local"])
    # The loaded map holds the caller's surfaces, not copies read from the file.
    loaded = plmap.load(folder / name, s1=s1, s2=s2)
    np.testing.assert_array_equal(loaded.domain.vertices, s1.vertices)
    assert loaded.check()["ok"]


@pytest.mark.parametrize("name", FORMATS)
@pytest.mark.parametrize("which", ["s1", "s2"])
def test_a_different_surface_is_refused_naming_it(saved, name, which):
    folder, _, s1_arrays, s2_arrays = saved
    vertices, triangles = s1_arrays if which == "s1" else s2_arrays
    moved = vertices.copy()
    moved[7, 2] += 1e-9  # one coordinate of one vertex: another surface
    s1 = (moved, triangles) if which == "s1" else s1_arrays
    s2 = (moved, triangles) if which == "s2" else s2_arrays
    expected = "domain (S1)" if which == "s1" else "target (S2)"
    with pytest.raises(plmap.ParseError, match=r"built for another " + expected.replace("(", r"\(").replace(")", r"\)")) as error:
        plmap.load(folder / name, s1, s2)
    assert name in str(error.value)
    # The surfaces swapped are refused too (the domain is checked first).
    with pytest.raises(plmap.ParseError, match=r"domain \(S1\)"):
        plmap.load(folder / name, s2_arrays, s1_arrays)


def test_bad_surface_arguments_are_clear_errors(saved):
    folder, _, s1_arrays, s2_arrays = saved
    path = folder / "map.plmapb"
    with pytest.raises(TypeError, match="both surfaces"):
        plmap.load(path, s1_arrays)
    with pytest.raises(TypeError, match="both surfaces"):
        plmap.load(path, s2=s2_arrays)
    with pytest.raises(TypeError, match=r"load\(\): s2: expected a \(vertices, elements\) pair"):
        plmap.load(path, s1_arrays, (s2_arrays[0],))
    with pytest.raises(TypeError, match=r"load\(\): s1: expected a plmap.Surface"):
        plmap.load(path, 42, s2_arrays)
    curve = plmap.Surface(*polyline(0.0, 1.0, 4, 0.0))
    with pytest.raises(ValueError, match="dimension 2, but s1 has dimension 1"):
        plmap.load(path, curve, curve)
    # Without surfaces, load reads the file's own (unchanged behaviour).
    assert plmap.load(path).region_count > 0
