"""The printed closed-form derivation: its formulas equal the executor's solutions, its LaTeX compiles.

The formulas are the printed SymPy expressions (intermediates written back in), evaluated at random poses made by
random configurations; the executor (``solve_plan``) calls the numeric subproblems, a separate route.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan, solve_plan
from symjac.analysis.inverse_kinematics.geometry import arm_geometry
from symjac.analysis.inverse_kinematics.parallel_axes import three_parallel_axes_plan
from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS
from symjac.analysis.inverse_kinematics.planar import articulated_plan, planar_plan, scara_plan
from symjac.errors import ArgumentError
from symjac.kinematics.chain import forward_kinematics
from symjac.printing.document import render
from symjac.printing.ik_derivation import ik_derivation_document, step_formulas, substituted

BUILDERS = {
    "planar2r": planar_plan,
    "planar3r": planar_plan,
    "scara": scara_plan,
    "articulated3r": articulated_plan,
    "ur5": three_parallel_axes_plan,
    "ur5_poe": three_parallel_axes_plan,
}
PDFLATEX = shutil.which("pdflatex")


CYLINDRICAL = """
name = "cylindrical"
description = "Cylindrical arm: a waist, a vertical slide, a radial slide"
convention = "modified"

[parameters]
d1 = 0.3
c = 0.1

[[joints]]
type = "revolute"
alpha = 0
a = 0
d = "d1"
theta = 0

[[joints]]
type = "prismatic"
alpha = 0
a = 0
d = 0
theta = 0
limits = [0.0, 0.8]

[[joints]]
type = "prismatic"
alpha = "-pi/2"
a = "c"
d = 0
theta = 0
limits = [0.2, 0.9]
"""


def _plan(name):
    robot = load_robot(name)
    return BUILDERS[name](arm_geometry(robot)) if name in BUILDERS else closed_form_plan(robot)


def _wrapped(angle):
    return float(np.angle(np.exp(1j * angle)))


@pytest.mark.parametrize("name", [*sorted(BUILDERS), "puma560", "stanford", "irb140", "cylindrical"])
def test_printed_formulas_equal_the_executor(name, tmp_path):
    if name == "cylindrical":
        (tmp_path / "cylindrical.toml").write_text(CYLINDRICAL)
        name = tmp_path / "cylindrical.toml"
    plan = _plan(name)
    robot = plan.robot
    fk = sp.lambdify([list(robot.joint_variables)], forward_kinematics(robot).subs(robot.defaults), "numpy")
    names = [*POSE_SYMBOLS, *(s for s, _ in plan.definitions), *robot.joint_variables]
    definitions = [sp.lambdify([names], e.subs(robot.defaults), "numpy") for _, e in plan.definitions]
    branches = [[sp.lambdify([names], [v.subs(robot.defaults) for v in values], "numpy") for values in substituted(f)]
                for f in step_formulas(plan)]
    rng = np.random.default_rng(12)
    checked = 0
    for _ in range(40):
        q = rng.uniform(-np.pi, np.pi, len(robot.joints))
        for i, joint in enumerate(robot.joints):
            if not joint.is_revolute:
                q[i] = rng.uniform(*[float(v) for v in joint.limits])
        pose = np.asarray(fk(q), dtype=float)
        for solution in solve_plan(plan, pose).solutions:
            values = [*pose[:3, :3].ravel(), *pose[:3, 3], *([0.0] * len(definitions)), *solution.q]
            for k, f in enumerate(definitions):
                values[12 + k] = float(f(values))
            taken, choices = iter(solution.branch), []
            for step, functions in zip(plan.steps, branches, strict=True):
                index = step.branches.index(next(taken)) if step.branches else 0
                if step.swapped_by is not None and choices[step.swapped_by] == 1:  # the names swapped by the shoulder
                    index = 1 - index
                choices.append(index)
                for joint, printed in zip(step.joints, functions[index](values), strict=True):
                    if robot.joints[joint].is_revolute:
                        assert abs(_wrapped(printed - solution.q[joint])) < 1e-8, (step.statement, printed, solution.q)
                    else:
                        assert abs(printed - solution.q[joint]) < 1e-10
                checked += 1
    assert checked > 40 * len(plan.steps)


def test_planar_2r_reads_like_the_textbook():
    document = ik_derivation_document(_plan("planar2r"))
    text = render(document, "pretty")
    assert "Family: planar 2R, because the axes of joints 1 and 2 are parallel." in text
    assert "elbow down" in text and "elbow up" in text
    latex = render(document, "latex")
    assert r"\operatorname{atan2}" in latex and "s_{2}" in latex and "c_{2}" in latex
    assert "1 - D_{2}^{2} \\geq 0" in latex


def test_ur5_derivation_uses_the_shorthand_and_says_why():
    document = ik_derivation_document(_plan("ur5"))
    latex = render(document, "latex")
    assert "the axes of joints 2, 3 and 4 are parallel" in latex
    assert "s_{23}" in latex or "c_{23}" in latex
    data = json.loads(render(document, "json"))
    assert data["family"] == "three parallel axes"
    assert [s["joints"] for s in data["steps"]] == [[1], [5], [6], [3], [2], [4]]
    assert data["steps"][0]["branches"] == ["shoulder right", "shoulder left"]
    assert "D1" in data["steps"][0]["intermediates"]


def test_unknown_subproblem_is_a_clear_error():
    plan = _plan("planar2r")
    object.__setattr__(plan.steps[0], "subproblem", "three_rotations")  # past the plan's own check
    with pytest.raises(ArgumentError, match="joint 2 uses 'three_rotations'"):
        step_formulas(plan)


@pytest.mark.external
@pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed (Debian: texlive-latex-base); .ci/run has it")
@pytest.mark.parametrize("name", ["planar2r", "scara", "ur5", "palletizer", "puma560"])
def test_latex_compiles(name, tmp_path):
    source = render(ik_derivation_document(_plan(name)), "latex", standalone=True)
    (tmp_path / "derivation.tex").write_text(source)
    run = subprocess.run([PDFLATEX, "-interaction=nonstopmode", "-halt-on-error", "derivation.tex"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-3000:]
    assert (tmp_path / "derivation.pdf").stat().st_size > 1000
