"""One default point and frame for the whole arm: forward kinematics, the Jacobian and generated code agree.

The default is the end of the chain: the tool point when the robot has a tool (a URDF's tip link), else the origin of
frame {n} (the flange). Checked numerically and independently: the Jacobian's columns are central differences of the
forward kinematics' position, its angular rows come from :math:`(R(q + h) - R(q - h)) R(q)^T / 2h`, in Python, in
the command line's JSON and in generated NumPy code (a UR5 read from a URDF with ``--tip-link tool0`` included). The
wrist centre is checked against the joint axes of the independent reference kinematics.
"""

from __future__ import annotations

import importlib.util
import json
import math

import numpy as np
import pytest
import sympy as sp
from reference import evaluate, frames, random_configuration

from symjac import forward_kinematics, jacobian, load_robot
from symjac.codegen import JacobianRequest, generate
from symjac.errors import FrameError
from symjac.kinematics.points import point_vector, wrist_centre
from symjac.model.ends import end_point, last_frame

ROBOTS = ("planar2r", "planar3r", "puma560", "stanford", "iiwa7")
"""Without a tool (planar2r, puma560, stanford, iiwa7) and with one (planar3r)."""

H = 1e-6


def _differences(pose, q: np.ndarray) -> np.ndarray:
    """The 6 x n Jacobian [v; omega] in the pose's own base frame, by central differences of ``pose(q)`` (4 x 4)."""
    R = pose(q)[:3, :3]
    J = np.zeros((6, len(q)))
    for i in range(len(q)):
        step = np.zeros(len(q))
        step[i] = H
        plus, minus = pose(q + step), pose(q - step)
        J[:3, i] = (plus[:3, 3] - minus[:3, 3]) / (2 * H)
        omega = (plus[:3, :3] - minus[:3, :3]) / (2 * H) @ R.T
        J[3:, i] = omega[2, 1], omega[0, 2], omega[1, 0]
    return J


@pytest.mark.parametrize("name", ROBOTS)
def test_python_defaults_agree(name):
    robot = load_robot(name)
    T, J = forward_kinematics(robot), jacobian(robot)
    assert end_point(robot) == ("tool" if robot.tool is not None else "flange")
    rng = np.random.default_rng(5)
    for _ in range(3):
        q = random_configuration(robot, rng)
        np.testing.assert_allclose(evaluate(J, robot, q), _differences(lambda x: evaluate(T, robot, x), q),
                                   atol=1e-7)
    assert jacobian(robot, point=end_point(robot)) == J
    assert forward_kinematics(robot, 0, last_frame(robot)) == T


def test_flange_and_wrist_name_the_origin_of_frame_n():
    robot = load_robot("planar3r")
    flange = jacobian(robot, point="flange")
    assert flange == jacobian(robot, point="wrist") == jacobian(robot, point=(0, 0, 0))
    assert flange != jacobian(robot)  # planar3r has a tool: the default is the tool point


@pytest.mark.parametrize("name", ["planar2r", "planar3r", "puma560"])
def test_command_line_json_defaults_agree(cli, name):
    robot = load_robot(name)
    fk = cli.json("fk", name)
    jac = cli.json("jacobian", name)
    assert jac["point"] == end_point(robot) and fk["target"] == last_frame(robot) and fk["source"] == 0
    T = sp.Matrix([[sp.sympify(e, locals={s.name: s for s in robot.q}) for e in row] for row in fk["entries"]])
    J = sp.Matrix([[sp.sympify(e, locals={s.name: s for s in robot.q}) for e in row] for row in jac["entries"]])
    q = random_configuration(robot, np.random.default_rng(9))
    np.testing.assert_allclose(evaluate(J, robot, q), _differences(lambda x: evaluate(T, robot, x), q), atol=1e-7)


def _module(tmp_path, source: str, name: str):
    path = tmp_path / f"{name}.py"
    path.write_text(source)
    spec = importlib.util.spec_from_file_location(f"default_point_{name}_{id(path)}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _generated_agree(module, n: int, seed: int) -> None:
    """The generated jacobian is the Jacobian of the generated forward_kinematics' point, at random q."""
    rng = np.random.default_rng(seed)
    pose = lambda x: np.asarray(module.forward_kinematics(x), dtype=float).reshape(4, 4)  # noqa: E731
    for _ in range(3):
        q = rng.uniform(-math.pi, math.pi, n)
        J = np.asarray(module.jacobian(q), dtype=float).reshape(6, n)
        np.testing.assert_allclose(J, _differences(pose, q), atol=1e-7)


@pytest.mark.parametrize("name", ["planar3r", "puma560"])
def test_generated_numpy_defaults_agree(tmp_path, name):
    robot = load_robot(name)
    source = generate(robot, "numpy")
    module = _module(tmp_path, source, name)
    _generated_agree(module, robot.n_joints, 3)
    where = "the tool point" if robot.tool is not None else f"the origin of frame {{{robot.n_joints}}} (flange)"
    assert f"at {where}" in source


UR5_URDF = """<?xml version="1.0"?>
<robot name="ur5">
  <link name="base_link"/><link name="shoulder_link"/><link name="upper_arm_link"/><link name="forearm_link"/>
  <link name="wrist_1_link"/><link name="wrist_2_link"/><link name="wrist_3_link"/><link name="tool0"/>
  <joint name="shoulder_pan_joint" type="revolute"><parent link="base_link"/><child link="shoulder_link"/>
    <origin xyz="0 0 0.089159" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-6.28" upper="6.28"/></joint>
  <joint name="shoulder_lift_joint" type="revolute"><parent link="shoulder_link"/><child link="upper_arm_link"/>
    <origin xyz="0 0.13585 0" rpy="0 1.570796325 0"/><axis xyz="0 1 0"/><limit lower="-6.28" upper="6.28"/></joint>
  <joint name="elbow_joint" type="revolute"><parent link="upper_arm_link"/><child link="forearm_link"/>
    <origin xyz="0 -0.1197 0.425" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-3.14" upper="3.14"/></joint>
  <joint name="wrist_1_joint" type="revolute"><parent link="forearm_link"/><child link="wrist_1_link"/>
    <origin xyz="0 0 0.39225" rpy="0 1.570796325 0"/><axis xyz="0 1 0"/><limit lower="-6.28" upper="6.28"/></joint>
  <joint name="wrist_2_joint" type="revolute"><parent link="wrist_1_link"/><child link="wrist_2_link"/>
    <origin xyz="0 0.093 0" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-6.28" upper="6.28"/></joint>
  <joint name="wrist_3_joint" type="revolute"><parent link="wrist_2_link"/><child link="wrist_3_link"/>
    <origin xyz="0 0 0.09465" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-6.28" upper="6.28"/></joint>
  <joint name="wrist_3_link-tool0_fixed_joint" type="fixed"><parent link="wrist_3_link"/><child link="tool0"/>
    <origin xyz="0 0.0823 0" rpy="-1.570796325 0 0"/></joint>
</robot>
"""
"""The UR5 as its URDF describes it (joint origins and axes), with the tool0 flange link."""


def test_codegen_of_a_urdf_tip_link_agrees_with_its_forward_kinematics(tmp_path, cli):
    path = tmp_path / "ur5.urdf"
    path.write_text(UR5_URDF, encoding="utf-8")
    out = tmp_path / "ur5_numpy.py"
    status, _, err = cli.run("codegen", str(path), "--tip-link", "tool0", "--target", "numpy", "-o", str(out))
    assert status == 0, err
    source = out.read_text()
    assert "at the tool point" in source and "pose of the tool frame" in source
    module = _module(tmp_path, source, "ur5_urdf")
    _generated_agree(module, 6, 11)
    robot = load_robot(path, tip_link="tool0")
    T_0_world = np.linalg.inv(evaluate(forward_kinematics(robot, "world", 0), robot, np.zeros(6)))
    rng = np.random.default_rng(2)
    for _ in range(3):
        q = rng.uniform(-math.pi, math.pi, 6)
        T = np.asarray(module.forward_kinematics(q), dtype=float).reshape(4, 4)
        np.testing.assert_allclose(T, T_0_world @ _urdf_tool0(q), atol=1e-12)  # the pose of tool0 in {0}
        flange = evaluate(forward_kinematics(robot, 0, 6), robot, q)[:3, 3]
        assert np.linalg.norm(T[:3, 3] - flange) == pytest.approx(0.0823)  # not the origin of {6}


_UR5_JOINTS = (((0, 0, 0.089159), (0, 0, 0), (0, 0, 1)), ((0, 0.13585, 0), (0, 1.570796325, 0), (0, 1, 0)),
               ((0, -0.1197, 0.425), (0, 0, 0), (0, 1, 0)), ((0, 0, 0.39225), (0, 1.570796325, 0), (0, 1, 0)),
               ((0, 0.093, 0), (0, 0, 0), (0, 0, 1)), ((0, 0, 0.09465), (0, 0, 0), (0, 1, 0)))
"""The joints of :data:`UR5_URDF`: origin xyz, origin rpy, axis."""


def _rotation(axis, angle: float) -> np.ndarray:
    """Rodrigues' formula: the 4 x 4 rotation by ``angle`` about the unit ``axis``."""
    k = np.asarray(axis, dtype=float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K
    return T


def _origin(xyz, rpy) -> np.ndarray:
    """A URDF origin: translate by xyz, then R = Rz(yaw) Ry(pitch) Rx(roll)."""
    T = _rotation((0, 0, 1), rpy[2]) @ _rotation((0, 1, 0), rpy[1]) @ _rotation((1, 0, 0), rpy[0])
    T[:3, 3] = xyz
    return T


def _urdf_tool0(q: np.ndarray) -> np.ndarray:
    """The pose of tool0 in base_link, straight from the URDF's numbers (as a URDF library computes it)."""
    T = np.eye(4)
    for (xyz, rpy, axis), angle in zip(_UR5_JOINTS, q, strict=True):
        T = T @ _origin(xyz, rpy) @ _rotation(axis, angle)
    return T @ _origin((0, 0.0823, 0), (-1.570796325, 0, 0))


@pytest.mark.parametrize("name", ["puma560", "stanford", "iiwa7"])
def test_wrist_centre_lies_on_the_last_three_axes(name):
    robot = load_robot(name)
    centre = np.array([float(v.subs(robot.defaults)) for v in wrist_centre(robot)] + [1.0])
    n, rng = robot.n_joints, np.random.default_rng(17)
    for _ in range(5):
        q = random_configuration(robot, rng)
        poses = frames(robot, q)  # world, {0}, ..., {n}, tool: independent of symjac's chain
        point = (poses[n + 1] @ centre)[:3]
        for joint in range(n - 2, n + 1):
            axis = poses[joint if robot.convention == "standard" else joint + 1]  # {j-1} standard, {j} modified
            offset = point - axis[:3, 3]
            distance = np.linalg.norm(offset - (offset @ axis[:3, 2]) * axis[:3, 2])
            assert distance < 1e-12, (name, joint, distance)


def test_wrist_centre_is_minus_d_n_along_z_n_for_a_standard_dh_wrist():
    d7 = sp.Symbol("d7", real=True)
    assert wrist_centre(load_robot("iiwa7")) == (0, 0, -d7)
    assert point_vector(load_robot("iiwa7"), "wrist_centre") == (0, 0, -d7)


@pytest.mark.parametrize(("name", "why"), [("planar2r", "not all revolute"), ("scara", "not all revolute"),
                                           ("planar3r", "do not meet"), ("ur5", "do not meet")])
def test_arms_without_a_wrist_centre_are_refused_by_name(name, why):
    with pytest.raises(FrameError, match=f"{name} has no wrist centre: .*{why}"):
        wrist_centre(load_robot(name))
    with pytest.raises(FrameError, match=f"{name} has no wrist centre"):
        jacobian(load_robot(name), point="wrist_centre")


def test_the_command_line_refuses_a_missing_wrist_centre_in_one_line(cli):
    assert "ur5 has no wrist centre" in cli.one_line_error("jacobian", "ur5", "--point", "wrist_centre")
    assert "ur5 has no wrist centre" in cli.one_line_error("codegen", "ur5", "--point", "wrist_centre")


def test_captions_and_headers_say_which_point(cli):
    assert "at the origin of frame {6} (flange)" in cli.ok("jacobian", "puma560", "--format", "pretty")
    assert "at the wrist centre" in cli.ok("jacobian", "puma560", "--point", "wrist_centre", "--format", "pretty")
    assert "at the tool point" in cli.ok("jacobian", "planar3r", "--format", "pretty")
    assert "Pose of the tool frame in frame {0}" in cli.ok("fk", "planar3r", "--format", "pretty")
    assert "Pose of frame {6} in frame {0}: the end of the chain, its origin the flange" in cli.ok(
        "fk", "puma560", "--format", "pretty")
    centre = generate(load_robot("puma560"), "numpy", jacobians=[JacobianRequest(0, "wrist_centre")])
    assert "at the wrist centre" in centre
    document = json.loads(cli.ok("jacobian", "puma560", "--point", "wrist_centre", "--format", "json"))
    assert document["point"] == "wrist_centre" and document["at"].startswith("the wrist centre")
    assert cli.json("fk", "planar3r")["at"] == "the tool point" == cli.json("jacobian", "planar3r")["at"]
    flange = "the origin of frame {2} (flange)"
    assert cli.json("fk", "planar2r")["at"] == flange == cli.json("jacobian", "planar2r")["at"]


@pytest.mark.parametrize("name", ["planar3r", "puma560"])  # with a tool, and without
def test_the_propagations_end_where_the_jacobian_does_by_default(name):
    """velocity_propagation(robot).jacobian and the force propagation's torques are J at the end of the chain."""
    from symjac.kinematics.propagation import force_propagation, velocity_propagation

    robot = load_robot(name)
    last = "tool" if robot.tool is not None else robot.n_joints
    q = np.random.default_rng(2).uniform(-2, 2, robot.n_coordinates)
    values = {**dict(zip(robot.q, q, strict=True)), **robot.defaults}
    expected = np.array(jacobian(robot, frame=last).xreplace(values), dtype=float)
    for J in (velocity_propagation(robot).jacobian, sp.Matrix(force_propagation(robot).torques).T):
        assert np.allclose(np.array(sp.Matrix(J).xreplace(values), dtype=float), expected, atol=1e-12)
