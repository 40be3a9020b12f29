"""Coupled joints in robot files: the ``coupled`` field, its refusals, writing it back, convert, the catalog palletizer.

The palletizer's Jacobian is checked against central differences of the plain-NumPy forward kinematics of
``reference.py`` in its four coordinates, and its square position-and-yaw Jacobian and determinant against the
expressions derived by hand below; random DH chains with a random affine coupling are checked the same way.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import end_of_chain, evaluate, finite_difference_jacobian, frames, random_configuration
from strategies import robots

import symjac
from symjac import RobotFileError, jacobian, load_robot, robot_from_mapping
from symjac.analysis.singularity.determinant import determinant
from symjac.kinematics.acceleration import hessian, hessian_slice, jacobian_derivative
from symjac.kinematics.convert import convert
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.coordinates import Coupling
from symjac.model.io import robot_from_toml, robot_to_toml
from symjac.model.robot_file import robot_to_mapping
from symjac.printing.json import document_data, metadata
from symjac.printing.results import transforms_document
from symjac.printing.tables import parameter_table_latex, parameter_table_text
from symjac.report.content import parameter_table_html
from symjac.symbolic.nested import lambdify_cse

METHODS = ("differentiation", "cross_product", "velocity_propagation", "force_propagation")
t1, t2, t3, t4, t5 = sp.symbols("theta1:6", real=True)
L1, L2, L3, L4, d1, d5 = sp.symbols("L1 L2 L3 L4 d1 d5", real=True)


def _arm(*couplings: tuple[int, object], prismatic: int | None = None) -> dict:
    """A four-joint modified-DH arm; ``couplings`` put ``coupled = value`` on joint ``number``."""
    joints = [{"type": "prismatic" if number == prismatic else "revolute", "a": "L"} for number in range(1, 5)]
    for number, value in couplings:
        joints[number - 1]["coupled"] = value
    return {"name": "arm", "convention": "modified", "parameters": {"L": 0.5, "k": 0.02}, "joints": joints}


# --------------------------------------------------------------------------------------------------------- reading


def test_coupled_field_gives_the_coupling_in_the_uncoupled_joints_variables():
    robot = robot_from_mapping(_arm((4, "-(theta2 + theta3)")))
    assert robot.q == (t1, t2, t3)
    assert robot.joint_values == (t1, t2, t3, -t2 - t3)
    assert robot.coupling.matrix == sp.Matrix([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, -1]])


def test_prismatic_joint_coupled_to_an_angle_with_symbolic_coefficients():
    robot = robot_from_mapping(_arm((3, "k * theta4 / (2*pi) + L"), prismatic=3))
    k, L = sp.symbols("k L", real=True)
    assert robot.q == (t1, t2, t4)
    assert robot.joint_values[2] == k * t4 / (2 * sp.pi) + L


REFUSALS = [
    ("itself", _arm((4, "theta4 + theta2")), 4, "theta4 refers to itself"),
    ("coupled reference", _arm((3, "theta1"), (4, "theta3")), 4, "theta3 in 'theta3' is itself coupled"),
    ("cycle", _arm((3, "theta4"), (4, "theta3")), 3, "theta4 in 'theta4' is itself coupled"),
    ("unknown name", _arm((4, "theta2 + phi")), 4, "unknown name 'phi'"),
    ("unknown joint", _arm((4, "theta7")), 4, "unknown name 'theta7'"),
    ("product", _arm((4, "theta2 * theta3")), 4, "is not affine in the coordinates (theta1, theta2, theta3)"),
    ("sine", _arm((4, "sin(theta2)")), 4, "is not affine"),
    ("square", _arm((4, "theta2**2")), 4, "is not affine"),
    ("division", _arm((4, "1 / theta2")), 4, "is not affine"),
    ("infinite coefficient", _arm((4, "theta2 / (L - 0.5)")), 4, "not a finite number"),
    ("not an expression", _arm((4, ["theta2"])), 4, "must be an expression of the coordinates"),
    ("boolean", _arm((4, True)), 4, "must be an expression of the coordinates"),
    ("every joint", _arm((1, "0"), (2, "0"), (3, "0"), (4, "0")), 4, "every joint is coupled"),
    ("eval", _arm((4, "__import__('os')")), 4, "not allowed"),
]


@pytest.mark.parametrize(("data", "joint", "words"), [case[1:] for case in REFUSALS], ids=[c[0] for c in REFUSALS])
def test_refusals_are_one_line_naming_file_joint_and_field(data, joint, words):
    with pytest.raises(RobotFileError) as info:
        robot_from_mapping(data, source="arm.toml")
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"arm.toml, joint {joint}, field 'coupled': ")
    assert words in message


def test_a_joint_may_be_locked_by_a_constant():
    robot = robot_from_mapping(_arm((2, "pi/4")))
    assert robot.q == (t1, t3, t4) and robot.joint_values[1] == sp.pi / 4


# --------------------------------------------------------------------------------------------------------- writing


def test_catalog_palletizer_file_round_trips_exactly():
    text = (Path(symjac.__file__).parent / "robots" / "palletizer.toml").read_text(encoding="utf-8")
    robot = load_robot("palletizer")
    assert robot_to_toml(robot) == text
    assert robot_from_toml(text, source="palletizer.toml") == robot


@pytest.mark.parametrize("data", [_arm((4, "-(theta2 + theta3)")), _arm((3, "k * theta4 / (2*pi) + L"), prismatic=3),
                                  _arm((2, "2*theta1 - 1/3"), (4, "theta3 / 2 + pi"))], ids=["level", "screw", "two"])
def test_mapping_round_trip(data):
    robot = robot_from_mapping(data)
    written = robot_to_mapping(robot)
    assert robot_from_mapping(written) == robot
    assert robot_to_mapping(robot_from_mapping(written)) == written
    assert robot_from_toml(robot_to_toml(robot)) == robot
    assert sum("coupled" in row for row in written["joints"]) == robot.n_joints - robot.n_coordinates


def test_writing_a_coupling_to_coordinates_that_are_not_joint_variables_is_refused():
    base = load_robot("planar2r")
    s = sp.Symbol("s", real=True)
    robot = dataclasses.replace(base, coupling=Coupling((s,), (s, -s)))
    with pytest.raises(RobotFileError, match="the coordinate s is not a joint variable"):
        robot_to_mapping(robot)


# --------------------------------------------------------------------------------------------------------- convert


@pytest.mark.parametrize("to", ["standard", "modified"])
def test_convert_keeps_the_coupling_and_the_kinematics(to):
    robot = load_robot("palletizer")
    other = convert(robot, to)
    assert other.convention == to and other.coupling == robot.coupling
    assert robot_from_toml(robot_to_toml(other)) == other
    assert convert(other, "modified") == robot
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = random_configuration(robot, rng)
        np.testing.assert_allclose(frames(other, q)[-1], frames(robot, q)[-1], atol=1e-12)


# ------------------------------------------------------------------------------------------------ the palletizer


@pytest.fixture(scope="module")
def palletizer():
    return load_robot("palletizer")


def test_palletizer_jacobian_by_every_method_against_finite_differences(palletizer):
    rng = np.random.default_rng(28)
    configurations = [random_configuration(palletizer, rng) for _ in range(3)]
    for method in METHODS:
        J = jacobian(palletizer, frame=0, method=method)
        assert J.shape == (6, 4)
        for q in configurations:
            np.testing.assert_allclose(evaluate(J, palletizer, q), finite_difference_jacobian(palletizer, q, 0),
                                       atol=1e-7, err_msg=method)


def test_palletizer_square_jacobian_and_singular_conditions_derived_by_hand(palletizer):
    r"""By hand: the flange point sits at radius r = L1 + L2 c2 + L3 c23 + L4 from the base axis (the parallelogram
    keeps link 4 horizontal) and height z = d1 - L2 s2 - L3 s23 - d5; x = r c1, y = r s1. The flange turns about the
    vertical by theta1 - theta5 (its z points down). So in (theta1, theta2, theta3, theta5), rows v_x, v_y, v_z,
    omega_z:

        J = [[-r s1, c1 r_2, c1 r_3, 0], [r c1, s1 r_2, s1 r_3, 0], [0, z_2, z_3, 0], [1, 0, 0, -1]]

    with r_2 = -L2 s2 - L3 s23, r_3 = -L3 s23, z_2 = -L2 c2 - L3 c23, z_3 = -L3 c23. Expanding along the last column,
    det J = -r (z_2 r_3 - z_3 r_2) = -r L2 L3 (s23 c2 - c23 s2) = -L2 L3 sin(theta3) r.
    """
    c, s = sp.cos, sp.sin
    r = L1 + L2 * c(t2) + L3 * c(t2 + t3) + L4
    r_2, r_3 = -L2 * s(t2) - L3 * s(t2 + t3), -L3 * s(t2 + t3)
    z_2, z_3 = -L2 * c(t2) - L3 * c(t2 + t3), -L3 * c(t2 + t3)
    by_hand = sp.Matrix([[-r * s(t1), c(t1) * r_2, c(t1) * r_3, 0], [r * c(t1), s(t1) * r_2, s(t1) * r_3, 0],
                         [0, z_2, z_3, 0], [1, 0, 0, -1]])
    J = jacobian(palletizer, frame=0)
    assert J[3:5, :] == sp.zeros(2, 4)  # no roll or pitch: the flange stays level
    square = J.extract([0, 1, 2, 5], list(range(4)))
    assert (square - by_hand).applyfunc(lambda e: sp.simplify(sp.expand_trig(e))) == sp.zeros(4, 4)
    det = determinant(palletizer, rows=(0, 1, 2, 5), frame=0)
    assert sp.simplify(sp.expand_trig(det.expression - (-L2 * L3 * s(t3) * r))) == 0
    factors = {f for f, _ in det.factors if f.free_symbols & set(palletizer.q)}
    assert factors == {s(t3), r}  # folded or stretched elbow; flange point on the base axis
    assert det.expression.free_symbols & {t4} == set()


# ----------------------------------------------------------------------------------------------------- printing


def test_tables_show_the_coupled_joint_and_what_it_equals(palletizer):
    text = parameter_table_text(palletizer)
    assert text.splitlines()[0].split()[-1] == "variable"
    assert text.splitlines()[4].endswith("theta4 = -theta2 - theta3")
    assert text.splitlines()[5].endswith("theta5")
    assert r"\text{variable}" in parameter_table_latex(palletizer)
    assert r"\theta_{4} = - \theta_{2} - \theta_{3}" in parameter_table_latex(palletizer)
    html = parameter_table_html(palletizer)
    assert "<th>variable</th>" in html and html.count("<tr>") == 6 and "<mo>=</mo>" in html
    assert "variable" not in parameter_table_text(load_robot("scara"))  # uncoupled tables are unchanged


def test_json_names_the_coordinates_and_the_coupling(palletizer):
    data = json.loads(json.dumps(document_data(transforms_document(palletizer, []))))
    assert data["joint_variables"] == ["theta1", "theta2", "theta3", "theta5"]
    assert data["coupling"] == {"theta4": "-theta2 - theta3"}
    assert data["parameter_table"][3][-1] == "theta4 = -theta2 - theta3"
    assert "coupling" not in metadata(load_robot("scara"))


# ---------------------------------------------------------------------------------------------------- hypothesis


@st.composite
def coupled_robots(draw: st.DrawFn):
    """A random DH chain (2..7 joints) with one or two joints coupled affinely to the others, read from a mapping."""
    robot = draw(robots(max_joints=7).filter(lambda r: r.n_joints >= 2))
    data = robot_to_mapping(robot)
    n = robot.n_joints
    coupled = draw(st.lists(st.integers(0, n - 1), min_size=1, max_size=min(2, n - 1), unique=True))
    free = [v for i, v in enumerate(robot.joint_variables) if i not in coupled]
    coefficient = st.sampled_from(["1", "-1", "2", "-1/2", "0.3", "L", "-2*L"])
    for i in coupled:
        used = draw(st.lists(st.sampled_from(free), min_size=1, max_size=len(free), unique=True))
        terms = [f"({draw(coefficient)}) * {v}" for v in used]
        offset = draw(st.sampled_from(["", " + 0.2", " - pi/6", " + L"]))
        data["joints"][i]["coupled"] = " + ".join(terms) + offset
    return robot_from_mapping(data)


@pytest.mark.slow
@settings(deadline=None, max_examples=20, suppress_health_check=[HealthCheck.too_slow])
@given(robot=coupled_robots(), data=st.data())
def test_random_coupled_chains_jacobian_against_finite_differences(robot, data):
    assert robot.n_coordinates < robot.n_joints
    method = data.draw(st.sampled_from(METHODS), label="method")
    q = random_configuration(robot, np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed")))
    J = jacobian(robot, frame=0, method=method, simplify=False)
    assert J.shape == (6, robot.n_coordinates)
    expected = finite_difference_jacobian(robot, q, 0, point=end_of_chain(robot))  # the default: the end of the chain
    np.testing.assert_allclose(evaluate(J, robot, q), expected, atol=1e-6)


@pytest.mark.slow
@settings(deadline=None, max_examples=10, suppress_health_check=[HealthCheck.too_slow])
@given(robot=coupled_robots(), data=st.data())
def test_random_coupled_chains_hessian_and_jdot_against_finite_differences(robot, data):
    """dJ/dq_m and dJ/dt of a coupled chain, against central differences of its Jacobian (itself checked above)."""
    n = robot.n_coordinates
    rng = np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed"))
    q, qdot, h = random_configuration(robot, rng), rng.uniform(-1, 1, n), 1e-5
    rates = joint_rate_symbols(robot)
    parameters = {s: float(v) for s, v in robot.defaults.items()}
    J, H = jacobian(robot, frame=0, simplify=False), hessian(robot, frame=0, simplify=False)
    assert H.shape == (6, n, n)
    Jdot = jacobian_derivative(robot, frame=0, simplify=False)
    # one lambdified function (printing the expressions is what costs here), evaluated at several points
    function = sp.lambdify([*robot.q, *rates, *parameters], [J, *(hessian_slice(H, m) for m in range(n)), Jdot],
                           modules="numpy", cse=lambdify_cse)  # nested results too (generic twists)

    def at(point):
        values = function(*point, *qdot, *parameters.values())
        return [np.array(value, dtype=float) for value in values]

    _, *slices, Jdot_at = at(q)
    for m, slice_m in enumerate(slices):
        step = np.zeros(n)
        step[m] = h
        np.testing.assert_allclose(slice_m, (at(q + step)[0] - at(q - step)[0]) / (2 * h), atol=1e-6)
    np.testing.assert_allclose(Jdot_at, (at(q + h * qdot)[0] - at(q - h * qdot)[0]) / (2 * h), atol=1e-6)


def test_singularity_words_name_the_coordinates_not_joint_numbers(palletizer):
    from symjac import singularities
    from symjac.printing.prose import self_motion_words

    report = singularities(palletizer)
    (shoulder,) = [f for f in report.factors if f.expression.has(t2) and not f.expression.is_Function]
    words = self_motion_words(shoulder)
    assert "on theta1" in words and "on theta5" in words and "joint 4" not in words
