"""The numpy snippet of docs/map-format.md ("Reading the binary format with numpy"), run exactly as
printed there on a binary map written by plmap, gives the regions that m.regions() gives."""

import pathlib
import re

import numpy as np

import plmap
from conftest import grid, polyline, source_dir


def snippet():
    """The first ```python block after the heading of the numpy section of docs/map-format.md."""
    text = (source_dir() / "docs" / "map-format.md").read_text()
    section = text[text.index("## Reading the binary format with numpy"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def regions_by_snippet(path):
    namespace = {"path": str(path)}
    code = snippet()
    assert len(code.strip().splitlines()) <= 10
    exec(code, namespace)
    return namespace


def check_snippet_matches(m, path):
    m.save(str(path))
    assert path.read_bytes()[:8] == b"\x89PLMAPB\n"
    r = regions_by_snippet(path)
    expected = m.regions()
    np.testing.assert_array_equal(r["domain_element"], expected["domain_element"])
    np.testing.assert_array_equal(r["target_element"], expected["target_element"])
    np.testing.assert_array_equal(r["domain_local"], expected["domain_local"])
    assert len(r["domain_element"]) == m.info()["regions"] > 0


def test_numpy_snippet_reads_the_regions_of_a_triangle_map(tmp_path):
    s1 = plmap.Surface(*grid(7, 5, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(6, 6, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.5 + 0.1 * x))
    check_snippet_matches(plmap.project(s1, s2), tmp_path / "planes.plmapb")


def test_numpy_snippet_reads_the_regions_of_a_curve_map(tmp_path):
    s1 = plmap.Surface(*polyline(0.0, 1.0, 9, 0.0))
    s2 = plmap.Surface(*polyline(-0.1, 1.1, 7, -0.3))
    check_snippet_matches(plmap.project(s1, s2), tmp_path / "curves.plmapb")


def test_loading_the_binary_file_gives_the_same_map(tmp_path):
    s1 = plmap.Surface(*grid(5, 5, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(4, 4, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.5 + 0.0 * x))
    m = plmap.project(s1, s2)
    m.save(str(tmp_path / "m.plmapb"))
    m.save(str(tmp_path / "m.plmap"))
    a, b = plmap.load(str(tmp_path / "m.plmapb")), plmap.load(str(tmp_path / "m.plmap"))
    for key, value in a.regions().items():
        np.testing.assert_array_equal(value, b.regions()[key])
