"""Shared helpers of the Python tests: planar grids made with numpy, and where the build put the
programs the tests compare with (set by CTest, see bindings/python/CMakeLists.txt)."""

import os
import pathlib

import numpy as np
import pytest


def grid(cells_x, cells_y, x0, y0, x1, y1, height=None):
    """A structured triangulation of [x0, x1] x [y0, y1]; z = height(x, y) (default 0).
    Triangles are counter-clockwise seen from +z."""
    xs, ys = np.meshgrid(np.linspace(x0, x1, cells_x + 1), np.linspace(y0, y1, cells_y + 1))
    x, y = xs.ravel(), ys.ravel()
    z = np.zeros_like(x) if height is None else height(x, y)
    vertices = np.column_stack([x, y, z])
    i, j = np.meshgrid(np.arange(cells_x), np.arange(cells_y))
    v00 = (j * (cells_x + 1) + i).ravel()
    v10, v01, v11 = v00 + 1, v00 + cells_x + 1, v00 + cells_x + 2
    triangles = np.concatenate([np.column_stack([v00, v10, v11]), np.column_stack([v00, v11, v01])])
    return vertices, triangles


def polyline(x0, x1, segments, y):
    """A straight polyline from (x0, y) to (x1, y)."""
    x = np.linspace(x0, x1, segments + 1)
    return np.column_stack([x, np.full_like(x, y)]), np.column_stack(
        [np.arange(segments), np.arange(1, segments + 1)])


def random_local_points(rng, element_count, n, d):
    """n uniformly random points of random elements, as (elements, local coordinates)."""
    elements = rng.integers(0, element_count, n)
    if d == 1:
        return elements, rng.random((n, 1))
    a, b = rng.random(n), rng.random(n)
    flip = a + b > 1
    a[flip], b[flip] = 1 - a[flip], 1 - b[flip]
    return elements, np.column_stack([a, b])


@pytest.fixture
def work_dir(tmp_path):
    return tmp_path


def built_program(variable):
    path = os.environ.get(variable)
    if not path or not pathlib.Path(path).exists():
        pytest.skip(f"{variable} not set (run through CTest)")
    return path


def source_dir():
    return pathlib.Path(os.environ.get("PLMAP_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[3]))
