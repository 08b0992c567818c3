"""Map.check_against_rays: the independent ray check from Python, under the rules the map records
unless the arguments change them (as `plmap check --against-rays`)."""

import warnings

import numpy as np
import pytest

import plmap
from conftest import grid


def square_under_tilted_plane():
    """The unit square, and a plane tilted about x = 0.5 over it: its half x < 0.5 lies behind S1."""
    s1 = plmap.Surface(*grid(8, 8, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(9, 9, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.3 * (x - 0.5)))
    return s1, s2


def test_the_recorded_rules_apply_unless_changed():
    s1, s2 = square_under_tilted_plane()
    m = plmap.project(s1, s2, allow_negative_distance=True, normal_check="aligned")
    assert m.report["covered_measure"] == pytest.approx(1.0, rel=1e-12)
    r = m.check_against_rays(2000)
    assert r["ok"] is True
    assert r["samples"] == 2000
    assert r["missed"]["samples"] == 0 and r["extra"]["samples"] == 0
    assert r["rules"] == {"from": "map", "max_distance": "inf", "max_distance_is_relative": False,
                          "allow_negative_distance": True, "normal_check": "aligned",
                          "directions": "averaged-normals"}
    # the recorded value given again changes nothing
    assert m.check_against_rays(500, allow_negative_distance=True)["rules"]["from"] == "map"
    # a changed rule: the half behind S1 is now area without an admissible hit
    strict = m.check_against_rays(2000, allow_negative_distance=False)
    assert strict["ok"] is False
    assert strict["rules"]["from"] == "map, with the arguments'"
    assert strict["rules"]["normal_check"] == "aligned"
    behind = strict["extra"]["by_reason"]["behind_domain"]["fraction"]
    assert behind == pytest.approx(0.5, abs=0.05)
    assert len(strict["extra"]["examples"]) == 20
    assert len(m.check_against_rays(2000, allow_negative_distance=False, max_listed=3)["extra"]["examples"]) == 3
    # the recorded rules ignored: the defaults
    ignored = m.check_against_rays(500, recorded_rules=False)
    assert ignored["rules"]["from"] == "arguments"
    assert ignored["rules"]["allow_negative_distance"] is False and ignored["ok"] is False
    # a looser tolerance passes what the default one fails
    assert m.check_against_rays(500, recorded_rules=False, tolerance=1.0)["ok"] is True


def test_a_map_projected_along_given_directions_needs_them_again():
    s1, s2 = square_under_tilted_plane()
    tilted = np.tile([0.1, 0.0, 1.0], (s1.vertex_count, 1))
    m = plmap.project(s1, s2, directions=tilted, allow_negative_distance=True)
    with pytest.raises(ValueError, match="directions given to project"):
        m.check_against_rays(500)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = m.check_against_rays(2000, directions=tilted)
    assert r["ok"] is True and r["rules"]["directions"] == "given"
    with pytest.warns(UserWarning, match="not those the map was projected along"):
        m.check_against_rays(200, directions=np.tile([0.2, 0.0, 1.0], (s1.vertex_count, 1)))
    # under other rules the recorded field is not needed
    assert m.check_against_rays(200, recorded_rules=False)["rules"]["from"] == "arguments"


def test_bad_arguments_are_clear_errors():
    s1, s2 = square_under_tilted_plane()
    m = plmap.project(s1, s2, allow_negative_distance=True)
    with pytest.raises(ValueError, match="normal_check must be"):
        m.check_against_rays(100, normal_check="sideways")
    with pytest.raises(ValueError, match="directions must have shape"):
        m.check_against_rays(100, directions=np.ones((3, 3)))
    with pytest.raises(ValueError, match="max_distance must be"):
        m.check_against_rays(100, max_distance=-1.0)
    with pytest.raises(TypeError):
        m.check_against_rays(100, allow_negative=True)


def test_a_surface_projected_onto_itself_passes_without_error():
    s1 = plmap.Surface(*grid(4, 4, 0.0, 0.0, 1.0, 1.0))
    r = plmap.project(s1, s1).check_against_rays(300)
    assert r["ok"] is True and r["rules"]["from"] == "map"
    assert r["in_domain_with_hit"] == 300
    assert r["image_error_relative_to_edge"]["max"] < 1e-9
