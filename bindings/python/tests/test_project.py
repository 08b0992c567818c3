"""plmap.project: normal projection from Python, its keyword options, and the regions it gives on
generated planar grids and curves (where the answer is known in closed form)."""

import json
import subprocess

import numpy as np
import pytest

import plmap
from conftest import built_program, grid, polyline


def overlapping_grids():
    """Two coplanar grids whose overlap is [0.3, 1] x [0, 0.85] (area 0.595); no grid line of one
    lies on a grid line of the other."""
    s1 = plmap.Surface(*grid(7, 7, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(5, 5, 0.3, -0.15, 1.3, 0.85))
    return s1, s2


def test_regions_of_overlapping_grids_sum_to_the_overlap_area():
    s1, s2 = overlapping_grids()
    m = plmap.project(s1, s2)
    r = m.regions()
    assert m.dimension == 2
    assert len(r["domain_measure"]) == m.region_count > 0
    assert r["domain_measure"].sum() == pytest.approx(0.7 * 0.85, rel=1e-12)
    # The map is the identity of the plane: each region has the same measure on both sides.
    assert np.allclose(r["domain_measure"], r["target_measure"], rtol=1e-9, atol=0)
    assert m.report["covered_measure"] == pytest.approx(0.7 * 0.85, rel=1e-12)
    assert m.check()["ok"]


def test_the_report_says_why_the_rest_of_s1_is_outside_d():
    # S1 is the unit square, S2 covers [0.3, 1] x [0, 0.85] of it: the rest of S1 (1 - 0.595) has
    # no ray hit, and is reported as outside D's reach; with what D covers, S1's measure
    s1, s2 = overlapping_grids()
    report = plmap.project(s1, s2).report
    left_out = report["left_out_measure"]
    assert set(left_out) == {"outside", "reversed", "unmapped", "enclosed", "folded", "unbacked", "occluded"}
    assert left_out["outside"] == pytest.approx(1.0 - 0.7 * 0.85, rel=1e-12)
    assert report["covered_measure"] + sum(left_out.values()) == pytest.approx(1.0, rel=1e-12)
    assert report["rim_nodes"] == 0 and report["rim_edges"] == 0


def test_region_arrays_have_documented_shapes_and_parents():
    s1, s2 = overlapping_grids()
    r = plmap.project(s1, s2).regions()
    n = len(r["domain_element"])
    assert r["domain_local"].shape == (n, 3, 2) and r["target_local"].shape == (n, 3, 2)
    assert r["domain_element"].dtype == np.int32
    assert 0 <= r["domain_element"].min() and r["domain_element"].max() < s1.element_count
    assert 0 <= r["target_element"].min() and r["target_element"].max() < s2.element_count
    # Identity of the plane: the corners are the same world points on both sides.
    def world(surface, elements, local):
        corners = surface.vertices[surface.elements[elements]]  # (n, 3, 3)
        origin = corners[:, None, 0, :]
        return origin + local[..., 0:1] * (corners[:, None, 1] - origin) + local[..., 1:2] * (
            corners[:, None, 2] - origin)
    on_s1 = world(s1, r["domain_element"], r["domain_local"])
    on_s2 = world(s2, r["target_element"], r["target_local"])
    assert np.abs(on_s1 - on_s2).max() < 1e-12


def test_curves_project_and_their_regions_sum_to_the_overlap_length():
    s1 = plmap.Surface(*polyline(0.0, 1.0, 10, 0.0))
    s2 = plmap.Surface(*polyline(0.25, 1.5, 7, 0.3))
    m = plmap.project(s1, s2, allow_negative_distance=True)
    r = m.regions()
    assert m.dimension == 1
    assert r["domain_local"].shape[1:] == (2, 1)
    # the map records the rules it was projected with (docs/map-format.md, "Provenance")
    assert m.info(quality=False)["provenance"]["projection.allow_negative_distance"] == "true"
    assert m.info(quality=False)["provenance"]["made_by"] == "project"
    assert r["domain_measure"].sum() == pytest.approx(0.75, rel=1e-12)
    assert r["target_measure"].sum() == pytest.approx(0.75, rel=1e-12)


def test_options_reach_the_projection():
    s1, _ = overlapping_grids()
    lifted = plmap.Surface(*grid(6, 6, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.5 + 0 * x))
    assert plmap.project(s1, lifted).region_count > 0
    # Everything is 0.5 away: a smaller limit leaves D empty.
    far = plmap.project(s1, lifted, max_distance=0.4)
    assert far.region_count == 0
    assert far.report["covered_measure"] == 0
    assert plmap.project(s1, lifted, max_distance=0.6).report["covered_measure"] == pytest.approx(1.0, rel=1e-12)
    # grids come in rows: renumbered only when asked, with the same coverage
    assert plmap.project(s1, lifted).report["renumbered"] == {"S1": False, "S2": False}
    both = plmap.project(s1, lifted, renumbering="always")
    assert both.report["renumbered"] == {"S1": True, "S2": True}
    assert both.report["covered_measure"] == pytest.approx(1.0, rel=1e-12)


def test_tilted_directions_shift_the_image_by_the_closed_form():
    s1 = plmap.Surface(*grid(7, 7, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(6, 6, -0.1, -0.1, 1.3, 1.1, height=lambda x, y: 0.5 + 0 * x))
    direction = np.array([0.2, 0.0, 1.0])
    m = plmap.project(s1, s2, directions=np.tile(direction, (s1.vertex_count, 1)))
    rng = np.random.default_rng(3)
    elements = rng.integers(0, s1.element_count, 500)
    local = rng.random((500, 2)) * 0.5
    e = m.evaluate(elements, local)
    x = s1.vertices[s1.elements[elements]]
    points = x[:, 0] + local[:, 0:1] * (x[:, 1] - x[:, 0]) + local[:, 1:2] * (x[:, 2] - x[:, 0])
    assert e["in_domain"].all()
    assert np.abs(e["world"] - (points + 0.5 * direction)).max() < 1e-12


def test_unknown_and_mistyped_keywords_are_type_errors():
    s1, s2 = overlapping_grids()
    with pytest.raises(TypeError, match="unexpected keyword argument 'max_dist'"):
        plmap.project(s1, s2, max_dist=0.1)
    with pytest.raises(TypeError, match="'allow_negative_distance' expects a bool, got str"):
        plmap.project(s1, s2, allow_negative_distance="yes")
    with pytest.raises(TypeError, match="'threads' expects"):
        plmap.project(s1, s2, threads=-1)
    with pytest.raises(ValueError, match="normal_check must be 'none', 'facing' or 'aligned'"):
        plmap.project(s1, s2, normal_check="sideways")
    with pytest.raises(ValueError, match="renumbering must be 'auto', 'always', 'target' or 'never', got 'random'"):
        plmap.project(s1, s2, renumbering="random")
    with pytest.raises(ValueError, match=r"directions must have shape \(64, 3\)"):
        plmap.project(s1, s2, directions=np.ones((10, 3)))
    with pytest.raises(plmap.Error, match="solver"):
        plmap.project(s1, s2, solver="no-such-solver")
    curve = plmap.Surface(*polyline(0.0, 1.0, 3, 0.0))
    with pytest.raises(ValueError, match="s1 has dimension 2 but s2 has dimension 1"):
        plmap.project(s1, curve)


def test_same_map_as_the_command_line(work_dir):
    cli = built_program("PLMAP_CLI")
    s1 = plmap.Surface(*grid(6, 6, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(5, 4, -0.2, 0.1, 0.9, 1.2, height=lambda x, y: 0.2 * x * y - 0.1))
    s1.save(work_dir / "s1.off")
    s2.save(work_dir / "s2.off")
    run = subprocess.run([cli, "project", str(work_dir / "s1.off"), str(work_dir / "s2.off"),
                          "--allow-negative", "--max-distance", "0.3", "-o", str(work_dir / "cli.plmap"),
                          "--max-listed", "1000000", "--json"],
                         check=True, capture_output=True, text=True)
    m = plmap.project(work_dir / "s1.off", str(work_dir / "s2.off"), allow_negative_distance=True,
                      max_distance=0.3)
    m.save(work_dir / "python.plmap")
    assert m.region_count > 0
    assert (work_dir / "python.plmap").read_bytes() == (work_dir / "cli.plmap").read_bytes()
    # and the same report, key for key: what only the command line knows aside, and the seconds
    cli_report = json.loads(run.stdout)
    for key in ("map", "solver", "threads", "target_self_intersecting_pairs"):
        cli_report.pop(key, None)
    timed = ("seconds", "seconds_by_phase")
    assert set(cli_report) == set(m.report)
    assert {k: v for k, v in cli_report.items() if k not in timed} == \
        {k: v for k, v in m.report.items() if k not in timed}
    assert m.report["edges_not_inserted"] == len(m.report["edges_not_inserted_list"])
