"""plmap.Map.inverse: Xi^-1 at points of S2, checked against Xi and against the closed form of a
projection along +z onto a tilted plane."""

import numpy as np
import pytest

import plmap
from conftest import grid, polyline, random_local_points
from test_map import tilted_plane_map, world_on


@pytest.fixture(scope="module")
def tilted():
    return tilted_plane_map()


def test_inverse_undoes_evaluate(tilted):
    s1, _, m = tilted
    elements, local = random_local_points(np.random.default_rng(11), s1.element_count, 20000, 2)
    forward = m.evaluate(elements, local)
    assert forward["in_domain"].all()
    back = m.inverse(forward["image_element"], forward["image_local"])
    assert back["in_image"].all()
    # The preimage is the starting point (in world coordinates: an S1 edge point has two names).
    assert np.abs(back["world"] - world_on(s1, elements, local)).max() < 1e-12
    assert np.abs(world_on(s1, back["preimage_element"], back["preimage_local"]) - back["world"]).max() < 1e-12


def test_inverse_is_the_vertical_projection_and_marks_points_outside_the_image(tilted):
    # S2 reaches over [-0.1, 1.1]^2, S1 covers [0, 1]^2: points of S2 outside it have no preimage.
    _, s2, m = tilted
    elements, local = random_local_points(np.random.default_rng(12), s2.element_count, 20000, 2)
    y = world_on(s2, elements, local)
    back = m.inverse(elements, local, threads=2)
    inside = (y[:, 0] > 1e-9) & (y[:, 0] < 1 - 1e-9) & (y[:, 1] > 1e-9) & (y[:, 1] < 1 - 1e-9)
    outside = (y[:, 0] < -1e-9) | (y[:, 0] > 1 + 1e-9) | (y[:, 1] < -1e-9) | (y[:, 1] > 1 + 1e-9)
    assert inside.any() and outside.any()
    assert back["in_image"][inside].all()
    assert not back["in_image"][outside].any()
    assert (back["preimage_element"][outside] == -1).all()
    assert np.isnan(back["world"][outside]).all()
    expected = np.column_stack([y[inside, 0], y[inside, 1], np.zeros(inside.sum())])
    assert np.abs(back["world"][inside] - expected).max() < 1e-12
    one = m.inverse(elements, local, threads=1)
    for key in one:
        assert np.array_equal(one[key], back[key], equal_nan=key in ("world", "preimage_local")), key


def test_curve_inverse_takes_flat_local_coordinates():
    s1 = plmap.Surface(*polyline(0.0, 1.0, 8, 0.0))
    s2 = plmap.Surface(*polyline(-0.5, 1.5, 5, -0.25))
    m = plmap.project(s1, s2)
    rng = np.random.default_rng(13)
    elements = rng.integers(0, s2.element_count, 1000)
    t = rng.random(1000)
    back = m.inverse(elements, t)
    x = -0.5 + (elements + t) * 2.0 / 5
    inside = (x > 1e-9) & (x < 1 - 1e-9)
    assert back["in_image"][inside].all()
    assert not back["in_image"][(x < -1e-9) | (x > 1 + 1e-9)].any()
    assert np.abs(back["world"][inside, 0] - x[inside]).max() < 1e-12


def test_bad_inverse_points_name_s2(tilted):
    _, s2, m = tilted
    n = s2.element_count
    with pytest.raises(IndexError, match=rf"inverse: elements\[0\] = {n} is not an S2 element \(S2 has {n}\)"):
        m.inverse([n], [[0.1, 0.1]])
    with pytest.raises(ValueError, match=r"inverse: local\[0\] is not a point of the reference element"):
        m.inverse([0], [[0.9, 0.9]])
