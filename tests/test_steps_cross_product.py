"""``--steps`` for the cross-product and differentiation methods: the steps assemble to the Jacobian.

Every column a step prints is compared with :func:`symjac.jacobian` of the same method, frame, point and link:
exactly (both are simplified to the one normal form) and at random configurations with the default parameters. The
parts of a column are checked on their own too: the cross product of the printed axis and lever, the axis against
the forward kinematics, the position against the forward kinematics and its derivative against central finite
differences. The command line prints the same steps in LaTeX, pretty text and JSON, and the standalone LaTeX
documents compile.
"""

from __future__ import annotations

import json
import random

import numpy as np
import pytest
import sympy as sp

from symjac import forward_kinematics, jacobian, load_robot
from symjac.cli.main import main
from symjac.kinematics.column_steps import cross_product_steps, differentiation_steps
from symjac.printing.steps import propagation_steps
from tests.test_latex_compile import PDFLATEX, compile_tex

CASES = [  # robot, frame, point, link
    ("planar3r", 0, None, None),
    ("planar3r", 2, "tool", None),
    ("puma560", 0, None, None),
    ("puma560", 3, None, None),
    ("scara", 0, None, None),
    ("stanford", 0, None, None),
    ("stanford", 4, None, None),
    ("planar3r", "tool", (1, 0, 0), 2),
    ("puma560", 0, (sp.Rational(1, 10), 0, 0), 3),
]
IDS = [f"{robot}-frame{frame}-{point}-link{link}" for robot, frame, point, link in CASES]


def _at(robot, matrix, q):
    values = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
    return np.array(sp.Matrix(matrix).xreplace(values).evalf(), dtype=float)


def _configurations(robot, count=3):
    rng = random.Random(7)
    return [[rng.uniform(-2.5, 2.5) for _ in robot.q] for _ in range(count)]


@pytest.mark.parametrize(("name", "frame", "point", "link"), CASES, ids=IDS)
def test_cross_product_columns_assemble_to_the_jacobian(name, frame, point, link):
    robot = load_robot(name)
    steps = cross_product_steps(robot, frame, point, link=link)
    J = jacobian(robot, frame=frame, point=point, method="cross_product", link=link)
    assert sp.Matrix(steps.jacobian()) == J
    assert len(steps.columns) == (link or robot.n_joints)
    for q in _configurations(robot):
        assert np.allclose(_at(robot, steps.jacobian(), q), _at(robot, J, q), atol=1e-9)
        for step in steps.columns:
            z, column = _at(robot, step.axis, q)[:, 0], _at(robot, step.column, q)[:, 0]
            assert np.isclose(np.linalg.norm(z), 1.0)
            if step.lever is None:
                assert np.allclose(column, [*z, 0, 0, 0])
            else:
                assert np.allclose(column, [*np.cross(z, _at(robot, step.lever, q)[:, 0]), *z])


@pytest.mark.parametrize(("name", "frame", "point", "link"), CASES, ids=IDS)
def test_differentiation_steps_assemble_to_the_jacobian(name, frame, point, link):
    robot = load_robot(name)
    steps = differentiation_steps(robot, frame, point, link=link)
    J = jacobian(robot, frame=frame, point=point, method="differentiation", link=link)
    assert (steps.rotation is None) == (frame == 0)
    for q in _configurations(robot):
        assert np.allclose(_at(robot, steps.jacobian(), q), _at(robot, J, q), atol=1e-9)


@pytest.mark.parametrize("name", ["planar3r", "stanford", "puma560"])
def test_the_differentiated_position_is_the_forward_kinematics(name):
    """Independently: p_P from the forward kinematics, its columns by central differences, z from the rotations."""
    robot = load_robot(name)
    steps = differentiation_steps(robot, 0, "wrist")
    T = forward_kinematics(robot, 0, robot.n_joints)
    h = 1e-6
    for q in _configurations(robot, 2):
        assert np.allclose(_at(robot, steps.position, q)[:, 0], _at(robot, T[:3, 3], q)[:, 0])
        for i, step in enumerate(steps.columns):
            up, down = list(q), list(q)
            up[i] += h
            down[i] -= h
            slope = (_at(robot, T[:3, 3], up) - _at(robot, T[:3, 3], down))[:, 0] / (2 * h)
            assert np.allclose(_at(robot, step.linear, q)[:, 0], slope, atol=1e-6)
            if step.revolute:
                R = _at(robot, forward_kinematics(robot, 0, step.axis_frame)[:3, 2], q)[:, 0]
                assert np.allclose(_at(robot, step.angular, q)[:, 0], R)
            else:
                assert not step.angular.free_symbols and step.angular == sp.zeros(3, 1)


def test_a_prismatic_joint_has_no_lever():
    steps = cross_product_steps(load_robot("stanford"))
    assert [step.lever is None for step in steps.columns] == [False, False, True, False, False, False]
    printed = propagation_steps(steps, "latex")
    assert r"{}^{0}J_{3} = \begin{bmatrix}z_{3}\\0\end{bmatrix} = " in printed[7]
    assert sum(line.startswith("{}^{0}p_") for line in printed) == 5


def test_steps_print_in_latex_and_pretty():
    robot = load_robot("planar2r")
    latex = propagation_steps(cross_product_steps(robot), "latex")
    assert latex[:2] == [r"{}^{0}z_{0} = \begin{bmatrix}0\\0\\1\end{bmatrix}",
                         r"{}^{0}p_{0P} = \begin{bmatrix}L_{1} c_{1} + L_{2} c_{12}\\L_{1} s_{1} + L_{2} s_{12}\\0"
                         r"\end{bmatrix}"]
    assert latex[2].startswith(r"{}^{0}J_{1} = \begin{bmatrix}z_{0} \times p_{0P}\\z_{0}\end{bmatrix} = ")
    pretty = propagation_steps(differentiation_steps(robot, frame=2), "pretty")
    assert pretty[0].startswith("p_P (in frame 0) =")
    assert pretty[1].startswith("Jv_1 = ∂p_P/∂theta1 (in frame 0) =")
    assert pretty[-1].startswith("R_2_0 =")
    with pytest.raises(Exception, match="style must be"):
        propagation_steps(cross_product_steps(robot), "html")  # type: ignore[arg-type]


@pytest.mark.parametrize("method", ["cross_product", "differentiation"])
def test_the_json_steps_assemble_to_the_printed_jacobian(method, capsys):
    assert main(["jacobian", "puma560", "--method", method, "--steps", "--frame", "3", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    robot = load_robot("puma560")
    columns = [step for step in data["steps"] if step["name"].startswith("J_")]
    entries = [[sp.sympify(e, locals={s.name: s for s in (*robot.q, *robot.parameter_symbols)})
                for e in row] for row in data["entries"]]
    q = _configurations(robot, 1)[0]
    if method == "cross_product":
        assembled = sp.Matrix([[sp.sympify(e, locals={s.name: s for s in (*robot.q, *robot.parameter_symbols)})
                                for e in step["entries"]] for step in columns]).T
    else:
        assembled = differentiation_steps(robot, 3).jacobian()
        assert [step["name"] for step in data["steps"]][-1] == "R_3_0"
        assert sum(step["name"].startswith("Jv_") for step in data["steps"]) == 6
    assert np.allclose(_at(robot, assembled, q), _at(robot, sp.Matrix(entries), q), atol=1e-9)
    assert all("latex" in step for step in data["steps"])


@pytest.mark.parametrize("method", ["cross_product", "differentiation"])
def test_pretty_steps_come_before_the_jacobian(method, capsys):
    assert main(["jacobian", "scara", "--method", method, "--steps", "--format", "pretty"]) == 0
    out = capsys.readouterr().out
    first = "z_" if method == "cross_product" else "p_P (in frame 0)"
    assert out.index(first) < out.index("J in frame 0")


@pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed")
@pytest.mark.parametrize("name", ["planar3r", "stanford", "puma560"])
@pytest.mark.parametrize("method", ["cross_product", "differentiation"])
def test_standalone_steps_compile(name, method, tmp_path):
    path = tmp_path / f"{name}-{method}.tex"
    assert main(["jacobian", name, "--method", method, "--steps", "--frame", "2", "--standalone", "-o",
                 str(path)]) == 0
    assert compile_tex(path) == []


@pytest.mark.parametrize("method", [cross_product_steps, differentiation_steps])
def test_a_coupled_robot_is_stepped_joint_by_joint(method):
    """The palletizer's five joints get a step each; times C = d(theta)/dq they give the 6 x 4 Jacobian J_q."""
    robot = load_robot("palletizer")
    steps = method(robot)
    assert len(steps.columns) == robot.n_joints == 5 and len(robot.q) == 4
    values = sp.Matrix(robot.joint_values)
    C = values.jacobian(sp.Matrix(robot.q))
    J_q = jacobian(robot)
    for q in _configurations(robot, 2):
        joints = dict(zip(robot.joint_variables, _at(robot, values, q)[:, 0], strict=True))
        J_joints = np.array(sp.Matrix(steps.jacobian()).xreplace({**robot.defaults, **joints}).evalf(), dtype=float)
        assert np.allclose(J_joints @ np.array(C, dtype=float), _at(robot, J_q, q), atol=1e-9)
