"""The printed closed-form derivation: its formulas equal the executor's solutions, its LaTeX compiles.

The formulas are the printed SymPy expressions (intermediates written back in), evaluated at random poses made by
random configurations; the executor (``solve_plan``) calls the numeric subproblems, a separate route.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from ik_robots import CYLINDRICAL

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
from symjac.printing.ik_signs import assumed_signs, cancel_parameters, under_signs

BUILDERS = {
    "planar2r": planar_plan,
    "planar3r": planar_plan,
    "scara": scara_plan,
    "articulated3r": articulated_plan,
    "ur5": three_parallel_axes_plan,
    "ur5_poe": three_parallel_axes_plan,
}
PDFLATEX = shutil.which("pdflatex")


def _plan(name):
    robot = load_robot(name)
    return BUILDERS[name](arm_geometry(robot)) if name in BUILDERS else closed_form_plan(robot)


def _wrapped(angle):
    return float(np.angle(np.exp(1j * angle)))


def _negative_puma(tmp_path):
    """The PUMA 560 with a2 = -0.4318: the same arm with its upper arm's x axis reversed (a textbook keeps a2 > 0)."""
    text = (Path(__file__).parents[1] / "symjac" / "robots" / "puma560.toml").read_text()
    (tmp_path / "puma_negative.toml").write_text(re.sub(r"^a2 = 0\.4318$", "a2 = -0.4318", text, flags=re.MULTILINE))
    return tmp_path / "puma_negative.toml"


@pytest.mark.parametrize("name", [*sorted(BUILDERS), "puma560", "stanford", "irb140", "cylindrical", "puma_negative"])
def test_printed_formulas_equal_the_executor(name, tmp_path):
    if name == "cylindrical":
        (tmp_path / "cylindrical.toml").write_text(CYLINDRICAL)
        name = tmp_path / "cylindrical.toml"
    if name == "puma_negative":
        name = _negative_puma(tmp_path)
    plan = _plan(name)
    robot = plan.robot
    formulas = step_formulas(plan)
    signs = assumed_signs([e for f in formulas for b in substituted(f) for e in b], robot.defaults)
    fk = sp.lambdify([list(robot.joint_variables)], forward_kinematics(robot).subs(robot.defaults), "numpy")
    names = [*POSE_SYMBOLS, *(s for s, _ in plan.definitions), *robot.joint_variables]
    definitions = [sp.lambdify([names], e.subs(robot.defaults), "numpy") for _, e in plan.definitions]
    branches = [[sp.lambdify([names], [v.subs(robot.defaults) for v in values]
                             + [under_signs(v, signs).subs(robot.defaults) for v in values], "numpy")
                 for values in substituted(f)] for f in formulas]  # exact, then as printed for the defaults' signs
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
                values_out = functions[index](values)
                for joint, printed in zip(step.joints * 2, values_out, strict=True):
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


def _latex_without_math(latex):
    """The comment lines' words, every ``$...$`` taken out."""
    words = "\n".join(line for line in latex.splitlines() if line.startswith("%"))
    return re.sub(r"\$[^$]*\$", "", words)


@pytest.mark.parametrize("name", ["puma560", "ur5", "scara"])
def test_the_target_position_prints_with_subscripts(name):
    document = ik_derivation_document(_plan(name))
    latex = render(document, "latex")
    assert "p_{x}" in latex and "p_{z}" in latex
    assert not re.search(r"\bp[xyz]\b", latex), "px would read as the product p x"
    data = json.loads(render(document, "json"))
    assert any("px" in e for step in data["steps"] for branch in step["solutions"] for e in branch) or name == "ur5"
    assert not any(re.search(r"\bp[xyz]\b", e) for step in data["steps"] for e in step["intermediates_latex"].values())


@pytest.mark.parametrize("name", [*sorted(BUILDERS), "puma560", "stanford", "irb140"])
def test_no_intermediate_is_a_number_or_a_lone_symbol(name):
    for formulas in step_formulas(_plan(name)):
        for symbol, expr in formulas.intermediates:
            assert not (expr.is_number or expr.is_Symbol or (-expr).is_Symbol), (symbol, expr)


def test_the_puma_wrist_carries_no_zero_beta():
    plan = _plan("puma560")
    wrist = next(f for f in step_formulas(plan) if len(f.step.joints) == 2 and 3 in f.step.joints)
    named = dict(wrist.intermediates)
    alpha, square = (next(s for s in named if s.name == n) for n in ("alpha4", "G4"))
    assert "beta4" not in {s.name for s in named}
    assert sp.expand(named[square] - (1 - alpha**2)) == 0
    used = set().union(*(e.free_symbols for branch in wrist.solutions for e in branch))
    assert "beta4" not in {s.name for s in used}
    assert r"\beta_{4}" not in render(ik_derivation_document(plan), "latex")


def test_common_positive_numbers_leave_atan2_and_abs_squares_cancel():
    plan = _plan("ur5")
    first = dict(step_formulas(plan)[0].intermediates)
    d4 = next(s for s in plan.robot.defaults if s.name == "d4")
    wx, wy = (next(s for s, _ in plan.definitions if s.name == n) for n in ("w_x", "w_y"))
    phi, cosine = (next(e for s, e in first.items() if s.name == n) for n in ("phi1", "D1"))
    assert phi == sp.atan2(wx * sp.sign(d4), -wy * sp.sign(d4))  # the 2 of atan2(2 d4 wx, -2 d4 wy) cancelled, d4's
    # sign kept (exact for either sign of d4)
    assert sp.simplify(cosine - sp.Abs(d4) / sp.sqrt(wx**2 + wy**2)) == 0
    assert not any(isinstance(m, sp.Abs) and m.args[0] == d4 for m in sp.denom(cosine).atoms(sp.Abs))


def test_a_factor_of_unknown_sign_keeps_its_sign_and_is_printed_for_the_arms_sign(tmp_path):
    plan = _plan("puma560")
    a2, a3, d4 = (next(s for s in plan.robot.defaults if s.name == n) for n in ("a2", "a3", "d4"))
    assert a2.is_positive is None  # a length parameter may be negative in an arm file: a2 cannot just be cancelled
    phi = next(e for f in step_formulas(plan) for s, e in f.intermediates if s.name == "phi3")
    assert phi == sp.atan2(d4 * sp.sign(a2), -a3 * sp.sign(a2))
    for value in (0.4318, -0.4318):  # equal to the uncancelled atan2(a2 d4, -a2 a3) for either sign
        at = {a2: value, a3: 0.0203, d4: 0.4318}
        assert abs(float(phi.subs(at)) - float(sp.atan2(a2 * d4, -a2 * a3).subs(at))) < 1e-15
    positive = render(ik_derivation_document(plan), "latex")
    assert r"\phi_{3} = \operatorname{atan2}\left(d_{4}, - a_{3}\right)" in positive and "sign" not in positive
    assert "Written for a2 > 0, as in this arm (a2 = 0.4318)" in render(ik_derivation_document(plan), "pretty")
    negative = ik_derivation_document(closed_form_plan(load_robot(_negative_puma(tmp_path))))
    assert r"\phi_{3} = \operatorname{atan2}\left(- d_{4}, a_{3}\right)" in render(negative, "latex")
    assert "Written for a2 < 0, as in this arm (a2 = -0.4318)" in render(negative, "pretty")
    positive_symbol = sp.Symbol("L", positive=True)  # a sign SymPy knows is cancelled outright
    assert cancel_parameters(positive_symbol * d4, -positive_symbol * a3, [positive_symbol]) == sp.atan2(d4, -a3)
    assert cancel_parameters(-2 * a2 * d4, 2 * a2 * a3, [a2]) == sp.atan2(-2 * d4 * sp.sign(a2), 2 * a3 * sp.sign(a2))


@pytest.mark.parametrize("name", ["puma560", "stanford", "scara", "palletizer", "ur5"])
def test_the_prose_writes_its_math_as_math(name):
    latex = render(ik_derivation_document(_plan(name)), "latex")
    words = _latex_without_math(latex)
    assert "textgreater" not in latex and "textless" not in latex
    assert not re.search(r"\btheta\d|\bh\d x h\d|\b[a-z]\d \+ [a-z]\d|\bphi\b|\bpsi\b", words), words
    if name in ("puma560", "stanford"):
        assert r"$\theta_{5} \geq 0$" in latex
        assert r"$h_{1} \times h_{2}$" in latex
        assert latex.count("$h_i$: the unit vector along the axis of joint $i$") == 1


def test_the_puma_wrist_is_craigs_theta4():
    """theta4 (no flip) = atan2(-r13 s1 + r23 c1, -r13 c1 c23 - r23 s1 c23 + r33 s23) (Craig, eq. 4.80)."""
    plan = _plan("puma560")
    wrist = next(f for f in step_formulas(plan) if 3 in f.step.joints)
    theta4 = wrist.solutions[wrist.step.branches.index("no flip")][wrist.step.joints.index(3)]
    assert not any(s.name.startswith("gamma") for s in theta4.free_symbols)  # sqrt(G4) >= 0 left the atan2
    r13, r23, r33 = POSE_SYMBOLS[2], POSE_SYMBOLS[5], POSE_SYMBOLS[8]
    t1, t2, t3 = plan.robot.joint_variables[:3]
    s1, c1, s23, c23 = sp.sin(t1), sp.cos(t1), sp.sin(t2 + t3), sp.cos(t2 + t3)
    craig = sp.atan2(-r13 * s1 + r23 * c1, -r13 * c1 * c23 - r23 * s1 * c23 + r33 * s23)
    rng = np.random.default_rng(4)
    for _ in range(20):
        at = dict(zip([*POSE_SYMBOLS[:9], t1, t2, t3], rng.uniform(-1, 1, 12), strict=True))
        assert abs(float(theta4.subs(at)) - float(craig.subs(at))) < 1e-12


def test_a_quarter_turn_is_written_in_and_its_condition_stays():
    first = step_formulas(_plan("irb140"))[0]
    phi = next(s for s, _ in first.intermediates if s.name == "phi1")
    assert [s.name for s, _ in first.intermediates] == ["phi1"]  # psi1 = atan2(sqrt(w_x^2 + w_y^2), 0) = pi/2
    assert first.solutions == ((phi - sp.pi / 2,), (phi + sp.pi / 2,))
    (condition,) = first.conditions
    assert isinstance(condition, sp.GreaterThan) and {s.name for s in condition.free_symbols} == {"w_x", "w_y"}
