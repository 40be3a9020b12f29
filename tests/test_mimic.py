"""URDF mimic joints read as a coupling: parsing, refusals, finite differences and pinocchio.

The forward kinematics the Jacobians are checked against is written here from the URDF text alone (origin, then a
rotation about or a translation along the axis as written, mimic positions m * x_J + o), so it shares nothing with
symjac's alignment of general joints: a sign flipped between a URDF position and symjac's joint variable would show.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from importlib import resources

import numpy as np
import pytest
import sympy as sp

from symjac import RobotFileError, jacobian, load_robot, robot_from_toml, robot_to_toml
from symjac.kinematics.acceleration import bias_acceleration, hessian, jacobian_derivative
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.numeric import numeric_jacobian
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.urdf import robot_from_urdf

METHODS = ("differentiation", "cross_product", "velocity_propagation", "force_propagation")
H = 1e-6
GRIPPER = resources.files("symjac.robots").joinpath("urdf", "gripper.urdf").read_text(encoding="utf-8")


def _joint(name, kind, parent, child, xyz="0 0 0", rpy="0 0 0", axis="0 0 1", mimic=""):
    limit = '<limit lower="-4" upper="4" effort="1" velocity="1"/>' if kind in ("revolute", "prismatic") else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>{limit}{mimic}</joint>')


def _urdf(*joints: str, links: int = 7) -> str:
    names = "".join(f'<link name="l{i}"/>' for i in range(links))
    return f'<robot name="mimic_arm">{names}{"".join(joints)}</robot>'


# A revolute joint driving a screw (prismatic j2 = 0.02 j1 + 0.1), a revolute joint that mimics the screw (a mimic of
# a mimic: j3 = -2 j2 + 0.3 = -0.04 j1 + 0.1), an independent joint about -y, and a joint about -z that follows it
# with an offset (j5 = 1.5 j4 - 0.2); the tip sits past a fixed joint.
SCREW_ARM = _urdf(
    _joint("j1", "revolute", "l0", "l1", "0 0 0.3", "0 0 0", "0 0 1"),
    _joint("j2", "prismatic", "l1", "l2", "0.1 0 0.05", "0 0 0", "0 0.6 0.8",
           '<mimic joint="j1" multiplier="0.02" offset="0.1"/>'),
    _joint("j3", "revolute", "l2", "l3", "0 0.2 0", "0 1.5707963267949 0", "1 0 0",
           '<mimic joint="j2" multiplier="-2" offset="0.3"/>'),
    _joint("j4", "revolute", "l3", "l4", "0.25 0 0", "0 0 0", "0 -1 0"),
    _joint("j5", "revolute", "l4", "l5", "0 0 0.15", "-1.5707963267949 0 0", "0 0 -1",
           '<mimic joint="j4" multiplier="1.5" offset="-0.2"/>'),
    _joint("tip", "fixed", "l5", "l6", "0.05 0.02 0.1", "0 0.3 0"))


def _rotation(axis, angle: float) -> np.ndarray:
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return _rotation((0, 0, 1), yaw) @ _rotation((0, 1, 0), pitch) @ _rotation((1, 0, 0), roll)


class UrdfChain:
    """The chain root .. tip of a URDF document as plain NumPy, positions given for the joints that mimic nothing."""

    def __init__(self, text: str, tip: str):
        root = ET.fromstring(text)
        by_child = {j.find("child").get("link"): j for j in root.findall("joint")}
        self.path = []
        link = tip
        while link in by_child:
            self.path.insert(0, by_child[link])
            link = by_child[link].find("parent").get("link")
        self.moving = [j for j in self.path if j.get("type") != "fixed"]
        self.free = [j.get("name") for j in self.moving if j.find("mimic") is None]
        self.by_name = {j.get("name"): j for j in root.findall("joint")}

    def position(self, name: str, q: dict[str, float]) -> float:
        mimic = self.by_name[name].find("mimic")
        if mimic is None:
            return q[name]
        return float(mimic.get("multiplier", "1")) * self.position(mimic.get("joint"), q) + float(
            mimic.get("offset", "0"))

    def positions(self, coordinates: np.ndarray) -> np.ndarray:
        """Every moving joint's position (chain order) at these values of the free joints."""
        q = dict(zip(self.free, coordinates, strict=True))
        return np.array([self.position(j.get("name"), q) for j in self.moving])

    def pose(self, coordinates: np.ndarray) -> np.ndarray:
        q = dict(zip(self.free, coordinates, strict=True))
        T = np.eye(4)
        for joint in self.path:
            origin = joint.find("origin")
            step = np.eye(4)
            step[:3, :3] = _rpy(*map(float, origin.get("rpy").split()))
            step[:3, 3] = [float(v) for v in origin.get("xyz").split()]
            T = T @ step
            if joint.get("type") == "fixed":
                continue
            axis = np.array([float(v) for v in joint.find("axis").get("xyz").split()])
            motion = np.eye(4)
            x = self.position(joint.get("name"), q)
            if joint.get("type") == "prismatic":
                motion[:3, 3] = x * axis / np.linalg.norm(axis)
            else:
                motion[:3, :3] = _rotation(axis, x)
            T = T @ motion
        return T

    def jacobian(self, coordinates: np.ndarray) -> np.ndarray:
        """6 x n [v; omega] of the tip link's origin in the root frame, by central differences in the coordinates."""
        n = len(coordinates)
        R = self.pose(coordinates)[:3, :3]
        J = np.zeros((6, n))
        for j in range(n):
            step = np.zeros(n)
            step[j] = H
            plus, minus = self.pose(coordinates + step), self.pose(coordinates - step)
            J[:3, j] = (plus[:3, 3] - minus[:3, 3]) / (2 * H)
            w = (plus[:3, :3] - minus[:3, :3]) / (2 * H) @ R.T
            J[3:, j] = (w[2, 1], w[0, 2], w[1, 0])
        return J


CASES = {"gripper": (GRIPPER, "left_fingertip"), "screw_arm": (SCREW_ARM, "l6")}
CACHE: dict[str, object] = {}


def _robot(name: str):
    if name not in CACHE:
        text, tip = CASES[name]
        CACHE[name] = robot_from_urdf(text, source=f"{name}.urdf", tip_link=tip)
    return CACHE[name]


def _configurations(robot, count: int = 3) -> list[np.ndarray]:
    rng = np.random.default_rng(28)
    return [rng.uniform(-1.5, 1.5, robot.n_coordinates) for _ in range(count)]


def _at(robot, matrix, q, qdot=None) -> np.ndarray:
    values = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
    if qdot is not None:
        values.update(zip(joint_rate_symbols(robot), qdot, strict=True))
    return np.array(sp.Matrix(matrix).xreplace(values).evalf(), dtype=float)


def test_gripper_coupling_is_the_mimic_with_its_sign():
    robot = load_robot("gripper.urdf")
    t1, t2, t3, _ = robot.joint_variables
    assert [j.name for j in robot.joints] == ["yaw", "pitch", "finger_joint", "left_inner_finger_joint"]
    assert robot.q == (t1, t2, t3) and robot.joint_values == (t1, t2, t3, -t3)
    assert coupling_matrix(robot) == sp.Matrix([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1]])
    # the inner finger undoes the knuckle's turn: the pad stays parallel to the palm whatever the finger does
    assert jacobian(robot, point="tool")[3:, 2] == sp.zeros(3, 1)


def test_mimic_of_a_mimic_is_followed_to_the_joint_that_mimics_nothing():
    robot = _robot("screw_arm")
    t1, t4 = robot.joint_variables[0], robot.joint_variables[3]
    assert robot.q == (t1, t4)
    R = sp.Rational
    assert robot.joint_values == (t1, R(1, 50) * t1 + R(1, 10), -R(1, 25) * t1 + R(1, 10), t4, R(3, 2) * t4 - R(1, 5))
    chain = UrdfChain(SCREW_ARM, "l6")
    for q in _configurations(robot):
        theta = [float(v.xreplace(dict(zip(robot.q, q, strict=True)))) for v in robot.joint_values]
        np.testing.assert_allclose(theta, chain.positions(q), atol=1e-12)


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("method", METHODS)
def test_tip_jacobian_by_every_method_matches_finite_differences_of_the_urdf(name, method):
    robot = _robot(name)
    chain = UrdfChain(*CASES[name])
    for simplify in (True, False):
        J = jacobian(robot, point="tool", method=method, simplify=simplify)
        assert J.shape == (6, robot.n_coordinates)
        for q in _configurations(robot):
            np.testing.assert_allclose(_at(robot, J, q), chain.jacobian(q), atol=1e-7)


@pytest.mark.parametrize("name", sorted(CASES))
def test_forward_kinematics_of_the_tool_matches_the_urdf(name):
    from symjac import forward_kinematics

    robot = _robot(name)
    T = forward_kinematics(robot, 0, "tool")
    chain = UrdfChain(*CASES[name])
    for q in _configurations(robot):
        np.testing.assert_allclose(_at(robot, T, q), chain.pose(q), atol=1e-12)


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("frame", [0, 2])
def test_hessian_and_jdot_match_finite_differences(name, frame):
    robot = _robot(name)
    n, h = robot.n_coordinates, 1e-5
    Hq = hessian(robot, frame=frame)
    assert Hq.shape == (6, n, n)
    for q in _configurations(robot, 2):
        qdot = np.linspace(-0.7, 0.9, n)
        for m in range(n):
            step = np.zeros(n)
            step[m] = h
            slice_m = np.array([[float(_at(robot, sp.Matrix([Hq[i, j, m]]), q)[0, 0]) for j in range(n)]
                                for i in range(6)])
            central = (numeric_jacobian(robot, q + step, frame) - numeric_jacobian(robot, q - step, frame)) / (2 * h)
            np.testing.assert_allclose(slice_m, central, atol=1e-7)
        path = (numeric_jacobian(robot, q + h * qdot, frame) - numeric_jacobian(robot, q - h * qdot, frame)) / (2 * h)
        for method in ("hessian", "differentiation"):
            np.testing.assert_allclose(_at(robot, jacobian_derivative(robot, frame=frame, method=method), q, qdot),
                                       path, atol=1e-7)
            np.testing.assert_allclose(_at(robot, bias_acceleration(robot, frame=frame, method=method), q, qdot),
                                       path @ qdot[:, None], atol=1e-7)


def _refused(*joints: str, tip: str = "l3") -> str:
    with pytest.raises(RobotFileError) as caught:
        robot_from_urdf(_urdf(*joints, links=4), source="bad.urdf", tip_link=tip)
    message = str(caught.value)
    assert "\n" not in message and message.startswith("bad.urdf")
    return message


A = _joint("a", "revolute", "l0", "l1")


@pytest.mark.parametrize(("joints", "expected"), [
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="nothing"/>'), _joint("c", "fixed", "l2", "l3")),
     "joint b mimic.*mimics 'nothing', which is not a joint of this robot"),
    ((_joint("a", "fixed", "l0", "l1"), _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a"/>'),
      _joint("c", "revolute", "l2", "l3")), "joint b mimic.*mimics joint 'a', a fixed joint"),
    ((_joint("a", "revolute", "l0", "l1", mimic='<mimic joint="b"/>'),
      _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a"/>'), _joint("c", "revolute", "l2", "l3")),
     "mimic joints form a cycle: a -> b -> a"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="b"/>'), _joint("c", "fixed", "l2", "l3")),
     "mimic joints form a cycle: b -> b"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic multiplier="2"/>'), _joint("c", "fixed", "l2", "l3")),
     "joint b mimic.*must name the joint it follows"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a" multiplier="nan"/>'),
      _joint("c", "fixed", "l2", "l3")), "joint b mimic.*expected a finite number, got 'nan'"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a" offset="inf"/>'),
      _joint("c", "fixed", "l2", "l3")), "joint b mimic.*expected a finite number, got 'inf'"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a" multiplier="two"/>'),
      _joint("c", "fixed", "l2", "l3")), "joint b mimic.*expected a finite number, got 'two'"),
    ((A, _joint("b", "revolute", "l1", "l2", mimic='<mimic joint="a" offset="1e12"/>'),
      _joint("c", "fixed", "l2", "l3")), "joint b mimic.*at most 1e\\+09 in size"),
], ids=["not-a-joint", "fixed-leader", "cycle", "self", "no-joint", "nan", "inf", "text", "huge"])
def test_bad_mimics_are_refused_in_one_line_naming_file_and_joint(joints, expected):
    assert re.search(expected, _refused(*joints))


def test_mimic_defaults_and_mimics_off_the_chain_and_on_fixed_joints():
    robot = robot_from_urdf(_urdf(
        A, _joint("b", "prismatic", "l1", "l2", axis="0 0 -2", mimic='<mimic joint="a"/>'),
        _joint("c", "fixed", "l2", "l3", mimic='<mimic joint="a" multiplier="3"/>'),
        _joint("side", "revolute", "l0", "l4", mimic='<mimic joint="elsewhere"/>'), links=5), tip_link="l3")
    t1 = robot.joint_variables[0]
    assert robot.q == (t1,) and robot.joint_values == (t1, t1)  # multiplier 1 and offset 0 by default
    assert robot.joints[1].placement.axis == (0, 0, -2)  # the axis as written: the sign lives in the frame, not in C


def test_convert_writes_the_mimic_coupling_back(tmp_path):
    from symjac.cli.main import main

    robot = load_robot("gripper.urdf")
    text = robot_to_toml(robot)
    back = robot_from_toml(text, source="gripper.toml")
    assert back.joint_values == robot.joint_values and back.q == robot.q
    output = tmp_path / "gripper.toml"
    assert main(["convert", "gripper.urdf", "--to", "toml", "-o", str(output)]) == 0
    assert load_robot(output).joint_values == robot.joint_values


def test_the_catalog_gripper_names_its_default_tip_and_other_tips_still_load_or_are_refused():
    assert load_robot("gripper.urdf") == load_robot("gripper.urdf", tip_link="left_fingertip")
    wrist = load_robot("gripper.urdf", tip_link="palm")
    assert wrist.n_joints == wrist.n_coordinates == 2 and wrist.coupling is None
    # the right finger follows finger_joint, which lies on the left finger's branch: a coordinate of its own
    right = load_robot("gripper.urdf", tip_link="right_fingertip")
    finger = sp.Symbol("finger_joint", real=True)
    assert finger in right.q and finger not in right.joint_variables
    assert right.n_coordinates == right.n_joints - 1  # right_knuckle_joint and its inner finger follow finger_joint
    with pytest.raises(RobotFileError, match="choose tip_link"):  # the comment is the catalog's, not URDF's
        robot_from_urdf(GRIPPER, source="gripper.urdf")


def test_a_leader_off_the_chain_is_a_coordinate_named_after_its_joint():
    robot = robot_from_urdf(_urdf(A, _joint("b", "revolute", "l1", "l3", mimic='<mimic joint="c" multiplier="2"/>'),
                                  _joint("c", "revolute", "l1", "l2"), _joint("d", "revolute", "l3", "l4"),
                                  links=5), tip_link="l4")
    t1, _, t3 = robot.joint_variables
    c = sp.Symbol("c", real=True)
    assert robot.q == (t1, c, t3) and robot.joint_values == (t1, 2 * c, t3)
    # a name that reads as a joint variable gets a prefix: theta2 may only be joint 2's own variable
    renamed = robot_from_urdf(_urdf(A, _joint("b", "revolute", "l1", "l3", mimic='<mimic joint="theta2"/>'),
                                    _joint("theta2", "revolute", "l1", "l2"), links=4), tip_link="l3")
    assert [str(q) for q in renamed.q] == ["theta1", "q_theta2"]


def test_a_leader_further_down_the_chain_and_a_zero_multiplier():
    robot = robot_from_urdf(_urdf(
        _joint("a", "revolute", "l0", "l1", mimic='<mimic joint="b" multiplier="-0.5" offset="0.25"/>'),
        _joint("b", "prismatic", "l1", "l2", axis="1 0 0"),
        _joint("c", "revolute", "l2", "l3", mimic='<mimic joint="b" multiplier="0" offset="1.5707963267949"/>'),
        links=4), tip_link="l3")
    d2 = robot.joint_variables[1]
    assert robot.q == (d2,)
    assert robot.joint_values == (-d2 / 2 + sp.Rational(1, 4), d2, sp.pi / 2)  # a revolute offset snaps like angles


def test_the_command_line_prints_forward_kinematics_and_the_report_in_the_coordinates(cli, tmp_path):
    import json

    robot = load_robot("gripper.urdf")
    hidden = {str(v) for v in robot.joint_variables} - {str(q) for q in robot.q}
    assert hidden
    for command in ("fk", "jacobian"):
        data = json.loads(cli.ok(command, "gripper.urdf", "--format", "json"))
        assert not any(name in json.dumps(data["entries"]) for name in hidden), command
        assert data["coupling"] == {"theta4": "-theta3"}
    assert cli.run("report", "gripper.urdf", "-o", str(tmp_path / "g.html"))[0] == 0
