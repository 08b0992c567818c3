"""plmap.Map: files, the invariant report, evaluation (vectorised, threaded), kappa and info."""

import json
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import plmap
from conftest import built_program, grid, polyline, random_local_points

SLOPE = np.array([0.1, 0.2])


def tilted_plane_map():
    """S1 = a grid of the unit square at z = 0, S2 = a grid of the plane z = 0.5 + 0.1 x + 0.2 y
    over a larger square. Projection along +z: Xi(x, y, 0) = (x, y, 0.5 + 0.1 x + 0.2 y)."""
    s1 = plmap.Surface(*grid(7, 7, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(6, 6, -0.1, -0.1, 1.1, 1.1, height=lambda x, y: 0.5 + SLOPE[0] * x + SLOPE[1] * y))
    return s1, s2, plmap.project(s1, s2)


def world_on(surface, elements, local):
    x = surface.vertices[surface.elements[elements]]
    p = x[:, 0].copy()
    for k in range(local.shape[1]):
        p += local[:, k:k + 1] * (x[:, k + 1] - x[:, 0])
    return p


@pytest.fixture(scope="module")
def tilted():
    return tilted_plane_map()


def test_evaluation_matches_the_closed_form(tilted):
    s1, s2, m = tilted
    rng = np.random.default_rng(4)
    elements, local = random_local_points(rng, s1.element_count, 20000, 2)
    e = m.evaluate(elements, local)
    p = world_on(s1, elements, local)
    expected = np.column_stack([p[:, 0], p[:, 1], 0.5 + p[:, :2] @ SLOPE])
    assert e["in_domain"].all()
    assert np.abs(e["world"] - expected).max() < 1e-12
    # The image (element, local) on S2 gives the same world point.
    assert np.abs(world_on(s2, e["image_element"], e["image_local"]) - e["world"]).max() < 1e-12
    assert (e["region"] >= 0).all() and (e["region"] < m.region_count).all()


def test_evaluation_marks_points_outside_the_domain():
    s1 = plmap.Surface(*grid(4, 4, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(3, 3, 0.55, 0.55, 1.55, 1.55))
    m = plmap.project(s1, s2)
    rng = np.random.default_rng(5)
    elements, local = random_local_points(rng, s1.element_count, 5000, 2)
    e = m.evaluate(elements, local)
    p = world_on(s1, elements, local)
    clearly_in = (p[:, 0] > 0.56) & (p[:, 1] > 0.56)
    clearly_out = (p[:, 0] < 0.54) | (p[:, 1] < 0.54)
    assert e["in_domain"][clearly_in].all()
    assert not e["in_domain"][clearly_out].any()
    assert (e["image_element"][clearly_out] == -1).all()
    assert np.isnan(e["world"][clearly_out]).all()
    assert np.abs(e["world"][clearly_in] - p[clearly_in]).max() < 1e-12


def test_threads_and_locators_give_the_same_images(tilted):
    s1, _, m = tilted
    elements, local = random_local_points(np.random.default_rng(6), s1.element_count, 30000, 2)
    one = m.evaluate(elements, local, threads=1)
    two = m.evaluate(elements, local, threads=2)
    for key in one:
        assert np.array_equal(one[key], two[key]), key
    brute = m.evaluate(elements, local, locator="brute-force")
    assert np.abs(brute["world"] - one["world"]).max() < 1e-12


def test_evaluation_from_several_python_threads(tilted):
    # evaluate releases the GIL; concurrent calls must not disturb each other.
    s1, _, m = tilted
    elements, local = random_local_points(np.random.default_rng(7), s1.element_count, 20000, 2)
    expected = m.evaluate(elements, local, threads=1)["world"]
    results = [None] * 4

    def work(i):
        results[i] = m.evaluate(elements, local, threads=1)["world"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r, expected)


def test_curve_evaluation_takes_flat_local_coordinates():
    s1 = plmap.Surface(*polyline(0.0, 1.0, 8, 0.0))
    s2 = plmap.Surface(*polyline(-0.5, 1.5, 5, -0.25))
    m = plmap.project(s1, s2)
    rng = np.random.default_rng(8)
    elements = rng.integers(0, s1.element_count, 1000)
    t = rng.random(1000)
    e = m.evaluate(elements, t)
    x = (elements + t) / 8
    assert e["in_domain"].all()
    assert np.abs(e["world"] - np.column_stack([x, np.full_like(x, -0.25)])).max() < 1e-12


def test_bad_query_points_are_named(tilted):
    s1, _, m = tilted
    with pytest.raises(IndexError, match=r"elements\[1\] = 98 is not an S1 element \(S1 has 98\)"):
        m.evaluate([0, 98], [[0.1, 0.1], [0.1, 0.1]])
    with pytest.raises(ValueError, match=r"local\[0\] is not a point of the reference element"):
        m.evaluate([0], [[np.nan, 0.1]])
    with pytest.raises(ValueError, match=r"local\[1\] is not a point of the reference element"):
        m.evaluate([0, 0], [[0.1, 0.1], [0.8, 0.8]])
    with pytest.raises(ValueError, match=r"local: expected shape \(n, 2\)"):
        m.evaluate([0], [[0.1, 0.1, 0.1]])
    with pytest.raises(ValueError, match="2 elements but 1 rows"):
        m.evaluate([0, 1], [[0.1, 0.1]])
    with pytest.raises(plmap.Error, match="no-such-locator"):
        m.evaluate([0], [[0.1, 0.1]], locator="no-such-locator")


def test_kappa_is_the_stretch_of_the_tilted_plane(tilted):
    _, _, m = tilted
    kappa = m.kappa()
    assert kappa.shape == (m.region_count,)
    # Vertical projection onto z = f(x, y) stretches by sqrt(1 + |grad f|^2) along grad f only.
    assert np.abs(kappa - np.sqrt(1 + SLOPE @ SLOPE)).max() < 1e-9
    assert m.info()["quality"]["kappa_max"] == pytest.approx(kappa.max(), rel=1e-12)


def test_info_counts_agree_with_the_arrays(tilted):
    s1, s2, m = tilted
    info = m.info()
    assert info["dimension"] == 2
    assert info["domain"]["elements"] == s1.element_count
    assert info["target"]["vertices"] == s2.vertex_count
    assert info["regions"] == m.region_count == len(m.regions()["domain_measure"])
    assert sum(info["nodes"]["by_type"].values()) == info["nodes"]["total"] == m.node_count
    assert info["coverage"]["domain_measure"] == pytest.approx(1.0, rel=1e-12)
    assert info["coverage"]["domain_fraction"] == pytest.approx(1.0, rel=1e-12)
    assert "quality" not in m.info(quality=False)


def test_info_is_what_the_command_line_reports(tilted, work_dir):
    # one function writes both: the same keys in the same order, the same values
    cli = built_program("PLMAP_CLI")
    _, _, m = tilted
    m.save(work_dir / "m.plmapb")
    run = subprocess.run([cli, "info", str(work_dir / "m.plmapb"), "--json"], check=True, capture_output=True,
                         text=True)
    from_cli = json.loads(run.stdout)
    assert (from_cli.pop("file"), from_cli.pop("kind")) == (str(work_dir / "m.plmapb"), "map")
    assert list(from_cli) == list(m.info())
    assert from_cli == m.info()


def test_check_returns_the_report_and_takes_verify_options():
    s1 = plmap.Surface(*grid(4, 4, 0.0, 0.0, 1.0, 1.0))
    s2 = plmap.Surface(*grid(3, 3, 0.55, 0.55, 1.55, 1.55))
    m = plmap.project(s1, s2)
    report = m.check()
    assert report["ok"] and report["violation_count"] == 0
    assert {"structure", "plane_graph", "map", "coverage"} <= set(report["checks"])
    # Only a quarter of S1 is covered: not a parametrization, and check says where.
    strict = m.check(expect_parametrization=True)
    assert not strict["ok"]
    assert strict["checks"]["coverage"]["violation_count"] > 0
    with pytest.raises(TypeError, match="unexpected keyword argument 'parametrization'"):
        m.check(parametrization=True)


def test_save_and_load_round_trip_exactly(tilted, work_dir):
    _, _, m = tilted
    m.save(work_dir / "m.plmap")
    back = plmap.load(str(work_dir / "m.plmap"))
    assert back.report is None
    a, b = m.regions(), back.regions()
    for key in a:
        assert np.array_equal(a[key], b[key]), key
    back.save(work_dir / "again.plmap")
    assert (work_dir / "again.plmap").read_bytes() == (work_dir / "m.plmap").read_bytes()
    assert np.array_equal(back.domain.vertices, m.domain.vertices)


def test_corrupt_map_files_are_parse_errors_naming_the_file(tilted, work_dir):
    _, _, m = tilted
    m.save(work_dir / "m.plmap")
    content = (work_dir / "m.plmap").read_bytes()
    (work_dir / "cut.plmap").write_bytes(content[: len(content) // 2])
    with pytest.raises(plmap.ParseError, match=r"cut\.plmap"):
        plmap.load(work_dir / "cut.plmap")
    with pytest.raises(plmap.ParseError, match=r"missing\.plmap"):
        plmap.load(work_dir / "missing.plmap")


def test_evaluation_releases_the_gil(tilted):
    # While one thread evaluates a large batch, another counts in Python. Were the GIL held through
    # the C++ evaluation, the counter could only run in the moments around the call (a few switch
    # intervals, kept short here); with the GIL released it runs during the whole evaluation.
    s1, _, m = tilted
    elements, local = random_local_points(np.random.default_rng(9), s1.element_count, 3_000_000, 2)

    def count_while(busy):
        done = threading.Event()
        counted = []

        def count():
            n = 0
            while not done.is_set():
                n += 1
            counted.append(n)

        counter = threading.Thread(target=count)
        start = time.perf_counter()
        counter.start()
        try:
            busy()
        finally:
            done.set()
            counter.join()
        return counted[0], time.perf_counter() - start

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)
    try:
        alone, alone_seconds = count_while(lambda: time.sleep(0.2))
        during, seconds = count_while(lambda: m.evaluate(elements, local, threads=1))
    finally:
        sys.setswitchinterval(interval)
    rate = alone / alone_seconds
    # Measured: about 0.4 of the counter's own rate with the GIL released, 0.03 with it held.
    assert during > 0.15 * rate * seconds, (during, rate, seconds)
