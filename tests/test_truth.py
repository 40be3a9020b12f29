"""What symjac says is true for every arm: no constant reported as a parameter of a singular condition."""

from __future__ import annotations

import re

import numpy as np
import pytest
import sympy as sp
from robot_mappings import PLANAR

from symjac import determinant, jacobian, robot_from_toml
from symjac.cli.main import main

FORTY_FIVE = """
name = "forty_five"
convention = "poe"
[parameters]
L = 0.5
[home]
matrix = [[1, 0, 0, "2*L"], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
[[joints]]
type = "revolute"
axis = [0, 0, 1]
point = [0, 0, 0]
[[joints]]
type = "revolute"
axis = [0, "sqrt(2)/2", "sqrt(2)/2"]
point = [0, 0, 0]
[[joints]]
type = "revolute"
axis = [0, 1, 0]
point = ["L", 0, 0]
"""
"""A 3R arm whose second axis is turned 45 degrees: sqrt(2) appears in its determinant as a number."""


def test_a_constant_of_the_determinant_is_part_of_its_coefficient_not_a_parameter_factor():
    robot = robot_from_toml(FORTY_FIVE)
    det = determinant(robot)
    assert all(factor.free_symbols for factor, _ in det.factors)  # sqrt(2) was reported as a "parameter" factor
    J = jacobian(robot, frame=det.frame, point=det.point)
    values = {**dict(zip(robot.q, (0.3, -0.7, 1.1), strict=True)), **robot.defaults}
    rows = sp.Matrix([J.row(r) for r in det.rows])
    expected = float(rows.xreplace(values).det())
    assert np.isclose(float(det.expression.xreplace(values)), expected, rtol=1e-12)


def test_an_existence_condition_is_simplified_and_printed_as_mathematics():
    from symjac.analysis.singularity.solve import nonnegative_condition
    from symjac.printing.pretty import one_line

    a1, a2, a3, d4 = sp.symbols("a1 a2 a3 d4")
    slack = sp.expand((a2 + sp.sqrt(a3**2 + d4**2)) ** 2) - a1**2  # the IRB 2400's shoulder set
    condition = nonnegative_condition(slack)
    assert condition == sp.Ge(a2 + sp.sqrt(a3**2 + d4**2), a1, evaluate=False)
    assert one_line(condition) == "a₂ + √(a₃² + d₄²) ≥ a₁"
    assert one_line(-sp.sqrt(2) / 2 * sp.Symbol("x")) == "-√2⋅x/2"


def test_computed_numbers_in_sentences_read_as_numbers():
    from symjac.printing.prose.singularities import readable_number

    assert [readable_number(v) for v in (0.9999999, 0.0171, -0.70710678)] == ["1", "0.017", "-√2/2"]


@pytest.mark.slow
def test_every_long_condition_of_a_redundant_arm_has_a_name_of_its_own(capsys):
    assert main(["singularities", "panda", "--format", "pretty"]) == 0
    definitions = re.findall(r"^(F[₀-₉]+) = (.*)$", capsys.readouterr().out, flags=re.MULTILINE)
    names = [name for name, _ in definitions]
    assert len(names) >= 3 and len(names) == len(set(names))  # F₂ named three expressions before


OFFSET_2R = PLANAR.replace("limits = [-3, 3]", 'theta = "pi/2"')
"""A planar 2R whose second joint has a DH offset of pi/2: stretched out at theta2 = -pi/2 and pi/2."""


def test_singular_configurations_are_solved_for_the_joint_variable_not_the_dh_angle():
    from symjac import singularities

    robot = robot_from_toml(OFFSET_2R)
    (factor,) = [f for f in singularities(robot).factors if f.solutions]
    theta2 = robot.q[1]
    assert {s.lhs for s in factor.solutions} == {theta2}  # not theta2 + pi/2
    assert {s.rhs for s in factor.solutions} == {-sp.pi / 2, sp.pi / 2}
    for solution in factor.solutions:  # and they are singular: the 2 x 2 position Jacobian loses rank
        J = jacobian(robot)[:2, :].xreplace({**robot.defaults, robot.q[0]: 0.3, theta2: solution.rhs})
        assert abs(float(J.det())) < 1e-12


def test_explanations_state_the_configuration_their_numbers_were_read_at(capsys):
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "offset2r.toml"
        path.write_text(OFFSET_2R, encoding="utf-8")
        assert main(["singularities", str(path), "--format", "pretty"]) == 0
    text = capsys.readouterr().out
    where = re.search(r"\(elbow\), at θ₁ = (-?[\d.]+), θ₂ = (-?π/2): .* There it cannot", text)
    assert where is not None, text


def test_one_sentence_names_its_vectors_in_one_frame():
    from symjac.analysis.singularity.directions import DirectionPart, LostDirection
    from symjac.analysis.singularity.geometry import FrameAxis
    from symjac.printing.prose.singularities import lost_words

    class Set:  # what lost_words reads of a singular factor
        lost_direction = LostDirection((1.0, 0, 0, 0, 0.6, 0.8), (0, 1, 2, 3, 4, 5), 3,
                                       DirectionPart((1.0, 0.0, 0.0), FrameAxis(2, 0)),
                                       DirectionPart((0.0, 0.6, 0.8), None))
        evidence = None  # no checked facts: the words state the direction as given

    words = lost_words(Set())  # x of frame {2} happens to be (1, 0, 0) in frame {3}; the angular half is only there
    assert "frame {2}" not in words and "(1, 0, 0) in frame {3}" in words and "(0, 3/5, 4/5) in frame {3}" in words
