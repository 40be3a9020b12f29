"""The benchmark scripts run: each quick one once, on a small robot and a small batch, as a user would start it.

A benchmark asserts nothing about speed (a timed test would flake on a shared machine), but a script that no longer
runs is a defect the suite can see: ``generated_code.py`` once failed on a target that writes C, not Python. The
slowest scripts (``drawing.py``, ``redundant.py``, ``sweep.py``, ``cpp_vs_pinocchio.py`` and
``dynamics_vs_pinocchio.py``, which build pinocchio, and ``before_after.py``, which needs a second checkout) are left
to their authors' runs.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parent.parent / "benchmarks"

pytestmark = pytest.mark.slow  # seconds per script


@pytest.mark.parametrize("command", [
    pytest.param("generated_code.py planar2r -n 64 --seconds 0.001", marks=pytest.mark.external),  # a C compiler
    pytest.param("numeric_model.py --quick", marks=pytest.mark.external),  # a C compiler; pin and rtb optional
    pytest.param("ik_numeric.py planar3r -n 5", marks=pytest.mark.external),  # numeric_model: a C compiler
    pytest.param("ik_closed_form.py puma560 -n 10 --seconds 0.01 --repeats 1",
                 marks=pytest.mark.external),  # g++ and Eigen for the C++ loop (skipped without), a C compiler
    pytest.param("jax_casadi.py planar2r -n 64", marks=pytest.mark.skipif(
        importlib.util.find_spec("jax") is None or importlib.util.find_spec("casadi") is None,
        reason="jax and casadi come with the test extra")),
    "acceleration.py planar2r",
    "derivation.py planar2r",
    "dynamics.py planar2r --planar 3 --limit 120",
    "generic_geometry.py --quick -n 1 --section puma --section numbers",  # 5 processes, a few seconds
    "growth.py --family planar --sizes 2 3 --limit 10",
    "poe.py",
    "regressor.py planar2r --limit 120",
    "base_parameters.py planar2r --limit 120",
    "identification.py planar2r -n 100 --targets python numpy",
    "urdf_vs_dh.py",
])
def test_a_benchmark_script_runs_and_prints_its_table(command, tmp_path):
    script, *arguments = command.split()
    environment = {**os.environ, "SYMJAC_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    result = subprocess.run([sys.executable, str(BENCHMARKS / script), *arguments], cwd=tmp_path, env=environment,
                            capture_output=True, text=True, timeout=600, check=False)
    assert result.returncode == 0, result.stderr[-2000:]
    assert len(result.stdout.splitlines()) >= 2, result.stdout  # a header and at least one row
