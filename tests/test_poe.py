"""The product of exponentials: robot files with screws, space and body Jacobians, conversions, printing.

The references are independent of symjac's chain: SciPy's matrix exponential of the screws as the file gives them
(space form :math:`T = e^{[S_1]q_1} \\cdots e^{[S_n]q_n} M`, body form :math:`T = M e^{[B_1]q_1} \\cdots
e^{[B_n]q_n}`), and central differences of that T for the twists: :math:`[\\mathcal{V}_s] = \\dot T T^{-1}`,
:math:`[\\mathcal{V}_b] = T^{-1} \\dot T`.
"""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from marks import marked
from reference import end_of_chain, evaluate, finite_difference_jacobian, frames, random_configuration
from scipy.linalg import expm
from strategies import robots

from symjac import (
    AngleBasis,
    body_jacobian,
    catalog,
    chain_of,
    exponential_product,
    forward_kinematics,
    generate,
    is_identity,
    jacobian,
    load_robot,
    numeric_jacobian,
    robot_from_mapping,
    robot_from_toml,
    robot_to_toml,
    screw_exponential,
    space_jacobian,
)
from symjac.errors import RobotFileError
from symjac.kinematics.convert import convert, converted
from symjac.model.conventions.poe import home_pose

RNG = np.random.default_rng(27)
BOOK = {"W1": 0.109, "W2": 0.082, "L1": 0.425, "L2": 0.392, "H1": 0.089, "H2": 0.095}


def ur5_mapping(**overrides: Any) -> dict[str, Any]:
    """The UR5 of Modern Robotics (example 4.5) in space form, as a robot-file mapping."""
    data = {
        "name": "ur5", "convention": "poe", "parameters": dict(BOOK),
        "home": {"matrix": [[-1, 0, 0, "L1 + L2"], [0, 0, 1, "W1 + W2"], [0, 1, 0, "H1 - H2"], [0, 0, 0, 1]]},
        "joints": [{"type": "revolute", "screw": screw} for screw in (
            [0, 0, 1, 0, 0, 0], [0, 1, 0, "-H1", 0, 0], [0, 1, 0, "-H1", 0, "L1"], [0, 1, 0, "-H1", 0, "L1 + L2"],
            [0, 0, -1, "-W1", "L1 + L2", 0], [0, 1, 0, "H2 - H1", 0, "L1 + L2"])],
    }
    data.update(overrides)
    return data


# --- the independent reference: the file's screws through SciPy's expm ------------------------------------------


def _number(value: Any, parameters: dict[str, float]) -> float:
    return float(sp.sympify(value, locals={k: sp.Symbol(k) for k in parameters}).subs(parameters)) \
        if isinstance(value, str) else float(value)


def _se3(screw: np.ndarray) -> np.ndarray:
    w, v = screw[:3], screw[3:]
    return np.array([[0, -w[2], w[1], v[0]], [w[2], 0, -w[0], v[1]], [-w[1], w[0], 0, v[2]], [0, 0, 0, 0.0]])


def file_screws(data: dict[str, Any]) -> tuple[list[np.ndarray], np.ndarray, bool]:
    """The screws, M and the body flag exactly as the mapping gives them (axis and point turned into w, -w x q)."""
    parameters = {k: float(v) for k, v in data.get("parameters", {}).items()}
    screws = []
    for row in data["joints"]:
        if "screw" in row:
            screws.append(np.array([_number(e, parameters) for e in row["screw"]]))
        elif row["type"] == "revolute":
            w = np.array([_number(e, parameters) for e in row["axis"]])
            w = w / np.linalg.norm(w)
            q = np.array([_number(e, parameters) for e in row["point"]])
            screws.append(np.concatenate([w, -np.cross(w, q)]))
        else:
            v = np.array([_number(e, parameters) for e in row["axis"]])
            screws.append(np.concatenate([np.zeros(3), v / np.linalg.norm(v)]))
    home = data["home"]
    if "matrix" in home:
        M = np.array([[_number(e, parameters) for e in row] for row in home["matrix"]])
    else:
        roll, pitch, yaw = (_number(e, parameters) for e in home["rpy"])
        cr, sr, cp, spi, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
        M = np.eye(4)
        M[:3, :3] = (np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]) @ np.array([[cp, 0, spi], [0, 1, 0],
                     [-spi, 0, cp]]) @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]]))
        M[:3, 3] = [_number(e, parameters) for e in home["xyz"]]
    return screws, M, bool(data.get("body", False))


def reference_pose(data: dict[str, Any], q: np.ndarray) -> np.ndarray:
    screws, M, body = file_screws(data)
    product = np.eye(4)
    for screw, value in zip(screws, q, strict=True):
        product = product @ expm(_se3(screw) * value)
    return M @ product if body else product @ M


def _vee(matrix: np.ndarray) -> np.ndarray:
    return np.array([matrix[2, 1], matrix[0, 2], matrix[1, 0], *matrix[:3, 3]])


def reference_jacobians(data: dict[str, Any], q: np.ndarray, h: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
    """J_s and J_b from central differences of the reference pose: columns (T' T^-1)^v and (T^-1 T')^v."""
    T = reference_pose(data, q)
    T_inv = np.linalg.inv(T)
    space, body = [], []
    for i in range(len(q)):
        step = np.zeros(len(q))
        step[i] = h
        derivative = (reference_pose(data, q + step) - reference_pose(data, q - step)) / (2 * h)
        space.append(_vee(derivative @ T_inv))
        body.append(_vee(T_inv @ derivative))
    return np.array(space).T, np.array(body).T


def numbers(matrix: sp.MatrixBase, robot, q: np.ndarray) -> np.ndarray:
    """``matrix`` at the coordinates ``q`` and the parameters' defaults: floats substituted, then evaluated (no
    lambdify: printing the raw products of long converted chains costs more than evaluating them)."""
    values = {**{s: sp.Float(float(v)) for s, v in robot.defaults.items()},
              **{s: sp.Float(float(v)) for s, v in zip(robot.q, q, strict=True)}}
    values.update({joint: value.xreplace(values) for joint, value in zip(robot.joint_variables, robot.joint_values,
                                                                         strict=True)})  # a coupled robot's joints
    return np.array(sp.Matrix(matrix).xreplace(values).evalf(), dtype=float)


def world_to_tool(robot, q: np.ndarray) -> np.ndarray:
    """The raw chain product from the world frame to the tool (frame {n} without one), in numbers."""
    return numbers(chain_of(robot).transform("world", "tool" if robot.tool is not None else robot.n_joints), robot, q)


# --- the UR5 of the book ---------------------------------------------------------------------------------------


def test_the_catalog_ur5_is_the_book_robot():
    robot = load_robot("ur5_poe")
    data = ur5_mapping()
    assert robot == robot_from_mapping({**data, "name": "ur5_poe", "description": robot.description,
                                        "inertials": "symbolic"})
    assert {p.name: float(p.default) for p in robot.geometric_parameters} == BOOK
    for _ in range(5):
        q = random_configuration(robot, RNG)
        assert np.allclose(numbers(forward_kinematics(robot, 0, "tool"), robot, q), reference_pose(data, q),
                           atol=1e-12)


def test_forward_kinematics_is_the_product_of_rodrigues_exponentials_exactly():
    robot = load_robot("ur5_poe")
    T, product = forward_kinematics(robot, 0, "tool"), exponential_product(robot)
    basis = AngleBasis.of(list(robot.q))
    assert all(is_identity(a, b, basis) for a, b in zip(T, product, strict=True))
    assert sp.simplify(product.xreplace(dict.fromkeys(robot.q, 0)) - home_pose(robot)) == sp.zeros(4, 4)


def test_screw_exponential_in_closed_form_matches_expm():
    t = sp.Symbol("t")
    for screw in ([0, 0, 1, 0, -1, 0], [0, 0.6, 0.8, 0.3, -0.4, 0.3], [0, 0, 0, 0, 0.6, 0.8]):
        exact = screw_exponential(screw, t)
        for value in (-2.1, 0.4, 3.0):
            assert np.allclose(np.array(exact.subs(t, value), dtype=float), expm(_se3(np.array(screw)) * value),
                               atol=1e-12)
    with pytest.raises(ValueError, match="6 entries"):
        screw_exponential([0, 0, 1], t)


@pytest.mark.parametrize("name", marked(["ur5_poe", "puma560", "stanford", "scara", "panda.urdf"]))
def test_space_and_body_jacobians_against_the_twists_of_the_reference(name):
    robot = load_robot(name)
    J_s, J_b = space_jacobian(robot), body_jacobian(robot)
    for _ in range(4):
        q = random_configuration(robot, RNG)
        poses = frames(robot, q)
        T = np.linalg.inv(poses[1]) @ poses[-1]  # frame {0} to the tool (or frame {n})
        # the twists from central differences of the independent forward kinematics (frames of tests/reference.py)
        space, body = [], []
        for i in range(len(q)):
            step = np.zeros(len(q))
            step[i] = 1e-6
            plus, minus = frames(robot, q + step), frames(robot, q - step)
            derivative = (np.linalg.inv(plus[1]) @ plus[-1] - np.linalg.inv(minus[1]) @ minus[-1]) / 2e-6
            space.append(_vee(derivative @ np.linalg.inv(T)))
            body.append(_vee(np.linalg.inv(T) @ derivative))
        assert np.allclose(numbers(J_s, robot, q), np.array(space).T, atol=1e-6)
        assert np.allclose(numbers(J_b, robot, q), np.array(body).T, atol=1e-6)


def test_body_jacobian_is_the_adjoint_of_the_space_jacobian_exactly():
    robot = load_robot("ur5_poe")
    T = forward_kinematics(robot, 0, "tool")
    R, p = T[:3, :3], T[:3, 3]
    J_s, J_b = space_jacobian(robot), body_jacobian(robot)
    # J_s = [Ad_T] J_b: omega_s = R omega_b, v_s = [p] R omega_b + R v_b
    omega = R * J_b[:3, :]
    expected = sp.Matrix.vstack(omega, sp.Matrix([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]]) * omega
                                + R * J_b[3:, :])
    basis = AngleBasis.of(list(robot.q))
    assert all(is_identity(a, b, basis) for a, b in zip(J_s, expected, strict=True))


def test_space_jacobian_columns_at_home_are_the_screws_and_the_first_never_moves():
    robot = load_robot("ur5_poe")
    J_s = space_jacobian(robot)
    screws = [joint.placement.screw for joint in robot.joints]
    assert J_s.xreplace(dict.fromkeys(robot.q, 0)) == sp.Matrix(screws).T
    assert list(J_s[:, 0]) == list(screws[0])
    # the book's second column: (-s1, c1, 0, -H1 c1, -H1 s1, 0)
    H1, t1 = sp.Symbol("H1", real=True), robot.q[0]
    assert sp.simplify(J_s[:, 1] - sp.Matrix([-sp.sin(t1), sp.cos(t1), 0, -H1 * sp.cos(t1), -H1 * sp.sin(t1), 0])) \
        == sp.zeros(6, 1)


def test_the_poe_ur5_agrees_with_the_dh_ur5_after_the_change_of_frame_and_point():
    dh = load_robot("ur5")
    book = {"d1": BOOK["H1"], "a2": -BOOK["L1"], "a3": -BOOK["L2"], "d4": BOOK["W1"], "d5": BOOK["H2"],
            "d6": BOOK["W2"]}
    poe = load_robot("ur5_poe")
    q = random_configuration(dh, RNG)
    # the DH arm points along -x at q = 0 and the book's along +x: the space frame is the DH frame {0} turned by pi
    turn = np.diag([-1.0, -1.0, 1.0])
    J_dh = evaluate(jacobian(dh, 0, "wrist"), dh, q, {sp.Symbol(k, real=True): v for k, v in book.items()})
    J_poe = numbers(jacobian(poe, 0, "tool"), poe, q)
    assert np.allclose(np.kron(np.eye(2), turn) @ J_dh, J_poe, atol=1e-12)


# --- random screw chains, space and body form ------------------------------------------------------------------

UNIT_AXES = st.sampled_from([[0, 0, 1], [0, -1, 0], [1, 0, 0], [0, 0.6, 0.8], [-0.8, 0, 0.6]])
POINTS = st.sampled_from([[0, 0, 0], [0.3, 0, 0], ["L", 0.1, 0], [0, -0.2, "L"], [0.1, 0.2, 0.3]])


@st.composite
def screw_rows(draw: st.DrawFn) -> dict[str, Any]:
    kind = draw(st.sampled_from(["revolute", "revolute", "prismatic"]))
    axis = draw(UNIT_AXES)
    if kind == "prismatic":
        return {"type": kind, "screw": [0, 0, 0, *axis]} if draw(st.booleans()) else {"type": kind, "axis": axis}
    point = draw(POINTS)
    if draw(st.booleans()):
        return {"type": kind, "axis": axis, "point": point}
    w, q = np.array(axis, dtype=float), np.array([0.35 if e == "L" else e for e in point], dtype=float)
    return {"type": kind, "screw": [*axis, *(-np.cross(w, q)).round(12).tolist()]}


@st.composite
def screw_chains(draw: st.DrawFn, max_joints: int = 7) -> dict[str, Any]:
    """A random screw chain. A body chain's home turns by right angles only: with a generic angle its screws in {s}
    (Ad_M B) carry products of its sines and cosines, and the raw products grow past what a test should wait for."""
    body = draw(st.booleans())
    angles = st.sampled_from([0, "pi/2", "-pi/2"] if body else [0, "pi/2", -0.3])
    return {"name": "chain", "convention": "poe", "parameters": {"L": 0.35}, "body": body,
            "joints": draw(st.lists(screw_rows(), min_size=1, max_size=max_joints)),
            "home": {"xyz": [draw(st.sampled_from([0, 0.4, "L"])) for _ in range(3)],
                     "rpy": [draw(angles) for _ in range(3)]}}


@settings(deadline=None, max_examples=25, suppress_health_check=[HealthCheck.too_slow])
@given(data=screw_chains())
def test_random_screw_chains_in_space_and_body_form(data):
    robot = robot_from_mapping(data)
    assert robot_from_toml(robot_to_toml(robot)) == robot
    q = random_configuration(robot, np.random.default_rng(len(data["joints"])))
    assert np.allclose(numbers(forward_kinematics(robot, 0, "tool"), robot, q), reference_pose(data, q),
                       atol=1e-12)
    space, body = reference_jacobians(data, q)
    assert np.allclose(numbers(space_jacobian(robot, simplify=False), robot, q), space, atol=1e-6)
    assert np.allclose(numbers(body_jacobian(robot, simplify=False), robot, q), body, atol=1e-6)
    expected = finite_difference_jacobian(robot, q, frame=0, point=end_of_chain(robot))  # the home pose's origin
    assert np.allclose(numeric_jacobian(robot, q), expected, atol=1e-6)


@st.composite
def right_angle_dh_robots(draw: st.DrawFn, max_joints: int = 6) -> Any:
    """Random DH robots whose twists, offsets and base and tool angles are right angles (real arms): their screws
    are exact, and written to a file they read back to the very same robot."""
    angle = st.sampled_from([0, "pi/2", "-pi/2", "pi"])
    rows = draw(st.lists(st.fixed_dictionaries({
        "type": st.sampled_from(["revolute", "revolute", "prismatic"]), "alpha": angle,
        "a": st.sampled_from([0, 0.25, "L"]), "d": st.sampled_from([0, -0.4, "L"]), "theta": angle}),
        min_size=1, max_size=max_joints))
    data = {"name": "random", "convention": draw(st.sampled_from(["standard", "modified"])),
            "parameters": {"L": 0.35}, "joints": rows}
    for key in ("base", "tool"):
        if draw(st.booleans()):
            data[key] = {"xyz": [draw(st.sampled_from([0, 0.1, "L"])) for _ in range(3)],
                         "rpy": [draw(angle) for _ in range(3)]}
    return robot_from_mapping(data)


@settings(deadline=None, max_examples=20, suppress_health_check=[HealthCheck.too_slow])
@given(robot=right_angle_dh_robots())
def test_dh_to_poe_to_numbers_equals_dh_to_numbers(robot):
    poe = convert(robot, "poe")
    again = robot_from_toml(robot_to_toml(poe))
    same = again == poe
    assert same
    q = random_configuration(robot, np.random.default_rng(robot.n_joints))
    expected = world_to_tool(robot, q)
    assert np.allclose(world_to_tool(poe, q), expected, atol=1e-12)
    assert np.allclose(world_to_tool(again, q), expected, atol=1e-12)
    point = "tool" if robot.tool is not None else "wrist"
    assert np.allclose(numeric_jacobian(poe, q, frame="world", point="tool"),
                       numeric_jacobian(robot, q, frame="world", point=point), atol=1e-12)


@pytest.mark.parametrize("name", marked([*sorted(catalog()), "panda.urdf", "ur5.urdf"]))
def test_every_catalog_robot_converts_to_poe_and_back_to_a_table(name):
    robot = load_robot(name)
    poe = convert(robot, "poe")
    assert robot_from_toml(robot_to_toml(poe)) == poe
    q = random_configuration(robot, RNG)
    assert np.allclose(world_to_tool(poe, q), world_to_tool(robot, q), atol=1e-12)
    for target in ("modified", "general") if name == "ur5_poe" else ():
        other, _ = converted(robot, target)
        assert np.allclose(world_to_tool(other, q), world_to_tool(robot, q), atol=1e-12)


@pytest.mark.slow  # long screws; the fast loop converts right-angle tables and the catalog's
@settings(deadline=None, max_examples=8, suppress_health_check=[HealthCheck.too_slow])
@given(robot=robots(max_joints=3))
def test_dh_tables_with_generic_angles_convert_to_poe(robot):
    """Generic twists (0.3 rad) give screws of sines and cosines, long ones to double precision."""
    poe = convert(robot, "poe")
    again = robot_from_toml(robot_to_toml(poe))
    q = random_configuration(robot, np.random.default_rng(robot.n_joints))
    expected = world_to_tool(robot, q)
    assert np.allclose(world_to_tool(poe, q), expected, atol=1e-12)
    assert np.allclose(world_to_tool(again, q), expected, atol=1e-12)


def test_body_files_round_trip_as_body_screws():
    space = robot_from_mapping(ur5_mapping())
    body_rows = [[0, 1, 0, "W1 + W2", 0, "L1 + L2"], [0, 0, 1, "H2", "-L1 - L2", 0], [0, 0, 1, "H2", "-L2", 0],
                 [0, 0, 1, "H2", 0, 0], [0, -1, 0, "-W2", 0, 0], [0, 0, 1, 0, 0, 0]]  # example 4.7 of the book
    body = robot_from_mapping(ur5_mapping(body=True, joints=[{"type": "revolute", "screw": s} for s in body_rows]))
    assert [j.placement.screw for j in body.joints] == [j.placement.screw for j in space.joints]
    text = robot_to_toml(body)
    assert "body = true" in text and 'screw = [0, 1, 0, "W1 + W2", 0, "L1 + L2"]' in text
    assert robot_from_toml(text) == body


# --- bad files -------------------------------------------------------------------------------------------------

BAD = [
    ({"joints": [{"type": "revolute", "screw": [0, 0, 2, 0, 0, 0]}]}, r"joint 1, field 'screw': .*unit length"),
    ({"joints": [{"type": "revolute", "axis": [0, 0.5, 0.5], "point": [0, 0, 0]}]},
     r"joint 1, field 'axis': 'axis' must have unit length, got .* of length 0.707107"),
    ({"joints": [{"type": "prismatic", "screw": [0, 0, 1, 0, 0, 1]}]}, r"joint 1, field 'screw': a prismatic .*w = 0"),
    ({"joints": [{"type": "revolute", "screw": [0, 0, 1, 0, 0]}]}, r"field 'screw': 'screw' must be a list of 6"),
    ({"joints": [{"type": "revolute", "screw": [0, 0, 1, 0, 0, 1]}]}, r"joint 1, field 'screw': .*zero pitch"),
    ({"joints": [{"type": "revolute", "axis": [0, 0, 1]}]}, r"joint 1, field 'point': .*needs a 'point'"),
    ({"joints": [{"type": "prismatic", "axis": [0, 0, 1], "point": [0, 0, 0]}]}, r"field 'point': a prismatic"),
    ({"joints": [{"type": "revolute", "screw": [0, 0, 1, 0, 0, 0], "theta": 0.1}]}, r"field 'theta': 'theta' has no"),
    ({"joints": [{"type": "revolute"}]}, r"joint 1, field 'screw': give the joint's 'screw'"),
    ({"home": {"matrix": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}},
     r"field 'home.matrix': the upper-left 3 x 3 block of 'matrix' is not a rotation"),
    ({"home": None}, r"field 'home': 'home' is required"),
    ({"tool": {"xyz": [0, 0, 1]}}, r"field 'tool': 'tool' is not used by the poe convention"),
    ({"body": "yes"}, r"field 'body': 'body' must be true"),
    ({"joints": [{"type": "revolute", "screw": [0, 0, "c", 0, 0, 0]}]}, r"joint 1, field 'screw': unknown name 'c'"),
]


@pytest.mark.parametrize(("change", "message"), BAD, ids=[m.split(":")[-1].strip()[:30] for _, m in BAD])
def test_a_bad_poe_file_is_refused_in_one_line(change, message):
    data = ur5_mapping(**change)
    if change.get("home", 0) is None:
        del data["home"]
    with pytest.raises(RobotFileError, match=message) as error:
        robot_from_mapping(data, source="arm.toml")
    assert "\n" not in str(error.value)


def test_a_symbolic_axis_must_be_a_unit_vector_identically():
    joints = [{"type": "revolute", "axis": ["cos(a)", "sin(a)", 0], "point": [0, 0, 0]}]
    robot = robot_from_mapping(ur5_mapping(parameters={**BOOK, "a": 0.3}, joints=joints))
    assert robot.joints[0].placement.omega[0] == sp.cos(sp.Symbol("a", real=True))
    joints = [{"type": "revolute", "axis": ["cos(a)", "cos(a)", 0], "point": [0, 0, 0]}]
    with pytest.raises(RobotFileError, match="not identically 1"):
        robot_from_mapping(ur5_mapping(parameters={**BOOK, "a": 0.3}, joints=joints))


def test_the_command_line_refuses_a_bad_poe_file_without_a_traceback(tmp_path):
    path = tmp_path / "arm.toml"
    text = robot_to_toml(load_robot("ur5_poe")).replace("screw = [0, 0, 1, 0, 0, 0]", "screw = [0, 0, 3, 0, 0, 0]")
    path.write_text(text)
    result = subprocess.run([sys.executable, "-m", "symjac", "jacobian", str(path), "--kind", "space"],
                            capture_output=True, text=True, check=False)
    assert result.returncode != 0 and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1 and "joint 1, field 'screw'" in result.stderr


# --- printing, command line, code generation -------------------------------------------------------------------


def test_command_line_space_and_body_jacobians_and_the_screw_table(tmp_path):
    def run(*args: str) -> str:
        return subprocess.run([sys.executable, "-m", "symjac", *args], capture_output=True, text=True,
                              check=True).stdout

    space = run("jacobian", "ur5_poe", "--kind", "space", "--format", "pretty")
    assert space.startswith("Space Jacobian") and "J_s =" in space and "s₂₃₄" in space
    assert "J_b =" in run("jacobian", "ur5_poe", "--kind", "body", "--format", "pretty")
    assert '"rows": [\n    "omega_x"' in run("jacobian", "ur5_poe", "--kind", "space", "--format", "json")
    shown = run("show", "ur5_poe", "--format", "pretty")
    assert "omega_i" in shown and "M =" in shown and "exp([S1] theta1)" in shown
    assert r"\omega_i & v_i & q_i" in run("show", "ur5_poe")
    data = json.loads(run("show", "ur5_poe", "--format", "json"))
    assert data["transforms"]["M"][0] == ["-1", "0", "0", "L1 + L2"]
    assert data["parameter_table"][1] == ["2", "revolute", "[0, 1, 0]", "[-H1, 0, 0]", "[0, 0, H1]"]
    converted_text = run("convert", "puma560", "--to", "poe")
    path = tmp_path / "puma_poe.toml"
    path.write_text(converted_text)
    assert load_robot(path).convention == "poe"


def test_the_report_shows_the_screw_table():
    from symjac.report.content import parameter_table_html

    html = parameter_table_html(load_robot("ur5_poe"))
    assert "&#969;<sub>i</sub>" in html and "q<sub>i</sub>" in html


def test_generated_code_of_a_poe_robot_matches_the_reference(tmp_path):
    robot = load_robot("ur5_poe")
    namespace: dict[str, Any] = {}
    exec(compile(generate(robot, "numpy"), "ur5_poe.py", "exec"), namespace)  # our own generated module
    for _ in range(3):
        q = random_configuration(robot, RNG)
        expected = finite_difference_jacobian(robot, q, point=end_of_chain(robot))  # the tool point, by default
        assert np.allclose(namespace["jacobian"](q), expected, atol=1e-6)


def test_a_dh_table_mixing_parameter_angles_and_generic_ones_converts_and_back():
    robot = robot_from_mapping({"name": "mixed", "convention": "modified", "parameters": {"al": 0.2, "b": 0.1},
                                "joints": [{"type": "revolute", "alpha": "al", "theta": "b", "a": 0.3},
                                           {"type": "revolute", "alpha": 0.4, "a": 0.2, "limits": [-1, 1]}]})
    poe = convert(robot, "poe")
    q = random_configuration(robot, RNG)
    assert np.allclose(world_to_tool(poe, q), world_to_tool(robot, q), atol=1e-12)
    assert np.allclose(world_to_tool(robot_from_toml(robot_to_toml(poe)), q), world_to_tool(robot, q), atol=1e-12)


def test_a_poe_robot_with_parameter_limits_converts_to_a_readable_numeric_table():
    data = ur5_mapping(parameters={**BOOK, "lim": 3})
    data["joints"][0]["limits"] = ["-lim", "lim"]
    table, notes = converted(robot_from_mapping(data), "modified")
    assert table.joints[0].limits == (-3, 3) and any("defaults" in note for note in notes)
    assert robot_from_toml(robot_to_toml(table)) == table


def test_a_long_symbolic_axis_is_checked_without_hanging():
    axis = ["sin(a)*cos(b)", "sin(a)*sin(b)", "cos(a)"]  # a unit vector for every a, b
    robot = robot_from_mapping(ur5_mapping(parameters={**BOOK, "a": 0.3, "b": 0.2},
                                           joints=[{"type": "revolute", "axis": axis, "point": [0, 0, 0]}]))
    assert robot.n_joints == 1
    with pytest.raises(RobotFileError, match="not identically 1"):
        robot_from_mapping(ur5_mapping(parameters={**BOOK, "a": 0.3, "b": 0.2}, joints=[
            {"type": "revolute", "axis": ["sin(a)*cos(b)**3", "sin(a)*sin(b)", "cos(a)"], "point": [0, 0, 0]}]))


def test_screw_exponential_refuses_a_non_unit_axis():
    with pytest.raises(ValueError, match="unit w"):
        screw_exponential([0, 0, 2, 0, 0, 0], sp.Symbol("t"))
