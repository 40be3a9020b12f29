"""Test configuration: hypothesis runs the same examples on every run unless asked to explore.

Symbolic examples vary a lot in cost (a chain whose every twist is 0.3 rad is far larger than a real arm), so a
random draw can double the suite's time, and a failure's shrinking can run for minutes. The default profile is
derandomized: reproducible examples and times. ``HYPOTHESIS_PROFILE=explore`` draws new random examples (run it
locally now and then; it found the regressions tested in test_urdf, test_codegen and test_representations).

OpenBLAS gets one thread per process. Two worker processes on two cores already keep every core busy, and a BLAS
that starts its own threads for 4 x 4 matrices then waits on them: SciPy's ``expm`` of a 4 x 4 took 20 ms instead of
7 us on the loaded development machine. The variables must be set before NumPy or SciPy is first imported, so they
are set here, at the top of the first conftest (the worker processes inherit them).
"""

from __future__ import annotations

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import json  # noqa: E402 (the thread counts above come before any import that could load a BLAS)

import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

settings.register_profile("symjac", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", derandomize=False, deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "symjac"))


# --- the order in which files reach the workers -----------------------------------------------------------------

LONGEST_FIRST = (
    # the whole suite's longest files (fresh virtual environments, pdflatex, the notebooks, mypy, the site, the
    # compiled targets, hypothesis over random chains)
    "test_packaging.py", "test_latex_compile.py", "test_notebooks.py", "test_quality.py", "test_docs.py",
    "test_properties.py", "test_codegen_c99.py", "test_codegen_cpp.py", "test_jacobian_numeric.py",
    "test_numeric_model.py", "test_dynamics_random.py", "test_dynamics_pinocchio.py", "test_benchmarks.py",
    # the fast loop's longest, measured (tests/marks.py, docs/testing.md)
    "test_acceleration.py", "test_codegen_jax.py", "test_codegen.py", "test_representations.py", "test_errata.py",
    "test_report.py", "test_codegen_acceleration.py", "test_redundant.py", "test_readme.py", "test_coordinates.py",
)
"""Files that run longest, longest first. ``--dist loadfile`` hands whole files to the workers in collection order,
so a long file collected last keeps one worker busy while the other idles; starting the longest first (the
longest-processing-time rule) lets both finish together. A file not listed keeps its place after these."""


def pytest_configure(config: pytest.Config) -> None:
    """Keep the collection order below: pytest-xdist (3.8 and later) otherwise hands out files by their number of
    tests, most first, which puts the long files with few tests (the installs, the notebooks, mypy) last."""
    if hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Move the tests of :data:`LONGEST_FIRST` to the front, file by file; within a file the order is unchanged."""
    rank = {name: index for index, name in enumerate(LONGEST_FIRST)}
    items.sort(key=lambda item: rank.get(item.path.name, len(rank)) if item.path.parent.name == "tests" else len(rank))


# A two-joint arm whose flange carries two fingers: two leaves, so a URDF command must be told --tip-link.
GRIPPER_URDF = """<?xml version="1.0"?>
<robot name="gripper_arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="flange"/>
  <link name="finger_a"/><link name="finger_b"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2"/></joint>
  <joint name="mount" type="fixed"><parent link="l2"/><child link="flange"/><origin xyz="0.3 0 0"/></joint>
  <joint name="fa" type="fixed"><parent link="flange"/><child link="finger_a"/><origin xyz="0 0.02 0.05"/></joint>
  <joint name="fb" type="fixed"><parent link="flange"/><child link="finger_b"/><origin xyz="0 -0.02 0.05"/></joint>
</robot>
"""


@pytest.fixture
def gripper(tmp_path) -> str:
    """:data:`GRIPPER_URDF` written to a file; its path."""
    path = tmp_path / "arm.urdf"
    path.write_text(GRIPPER_URDF, encoding="utf-8")
    return str(path)


# --- the command line, run in process -------------------------------------------------------------------------------


class Cli:
    """``symjac`` run in process (:func:`symjac.cli.main.main`), its stdout and stderr read through ``capsys``."""

    def __init__(self, capsys: pytest.CaptureFixture[str]):
        self.capsys = capsys

    def run(self, *argv: str) -> tuple[int, str, str]:
        """Run ``symjac *argv``; return (exit status, stdout, stderr)."""
        from symjac.cli.main import main

        status = main(list(argv))
        out, err = self.capsys.readouterr()
        return status, out, err

    def ok(self, *argv: str) -> str:
        """Run a command that must succeed silently on stderr; return its stdout."""
        status, out, err = self.run(*argv)
        assert status == 0, err
        assert err == ""
        assert out.endswith("\n")
        return out

    def latex_line(self, *argv: str) -> str:
        """The single LaTeX line a non-standalone ``jacobian``/``fk`` prints."""
        out = self.ok(*argv)
        lines = out.splitlines()
        assert len(lines) == 1, out
        return lines[0]

    def json(self, *argv: str) -> dict:
        """The JSON a command prints with ``--format json``, parsed."""
        status, out, err = self.run(*argv, "--format", "json")
        assert status == 0, err
        return json.loads(out)

    def one_line_error(self, *argv: str) -> str:
        """Run a command that must fail with one line on stderr and status 2; return that line."""
        status, out, err = self.run(*argv)
        assert (status, out) == (2, ""), err
        assert len(err.splitlines()) == 1 and err.startswith("symjac: error: "), err
        assert "Traceback" not in err
        return err.strip()


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str]) -> Cli:
    """:class:`Cli`: ``cli.run``, ``cli.ok``, ``cli.latex_line``, ``cli.json``, ``cli.one_line_error``."""
    return Cli(capsys)
