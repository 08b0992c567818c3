"""examples/python/mortar_mass_matrix.py assembles the same mortar matrix as the C++ example
examples/mortar_mass_matrix, on the maps the C++ example writes."""

import importlib.util
import subprocess
import sys

import numpy as np
import pytest

import plmap
from conftest import built_program, source_dir

EXAMPLE = source_dir() / "examples" / "python" / "mortar_mass_matrix.py"


def example_module():
    spec = importlib.util.spec_from_file_location("mortar_mass_matrix_example", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def read_triplets(path):
    lines = path.read_text().splitlines()
    rows, cols = map(int, lines[0].split())
    dense = np.zeros((rows, cols))
    for line in lines[1:]:
        i, j, value = line.split()
        dense[int(i), int(j)] = float(value)
    return dense


@pytest.mark.parametrize("case", ["grid_delaunay", "polylines"])
def test_python_and_cpp_examples_give_the_same_matrix(work_dir, case):
    cpp_example = built_program("PLMAP_MORTAR_EXAMPLE")
    subprocess.run([cpp_example, "--write", str(work_dir)], check=True, capture_output=True)
    expected = read_triplets(work_dir / f"{case}.mortar.txt")
    m = plmap.load(work_dir / f"{case}.plmap")
    actual = example_module().mortar_mass_matrix(m).toarray()
    assert actual.shape == expected.shape
    assert np.count_nonzero(expected) > 0
    # The same quadrature on the same regions; only the order of the sums differs.
    assert np.abs(actual - expected).max() <= 1e-14 * np.abs(expected).max()


def test_the_example_runs_as_a_script_and_its_identities_hold():
    result = subprocess.run([sys.executable, str(EXAMPLE)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "row sums - lumped mass of S1" in result.stdout
