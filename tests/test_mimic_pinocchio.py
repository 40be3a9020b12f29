"""URDF mimic joints against pinocchio: its Jacobian with every joint free times C, and its own mimic support.

pinocchio (PyPI ``pin``, the ``compare`` extra) loads the same URDF text. With every joint free, its frame Jacobian of
the tip link in LOCAL_WORLD_ALIGNED (rows [v; omega] of the tip link's origin, in the root link's axes) at the joint
positions theta(q) is symjac's frame-{0} Jacobian at the ``"tool"`` point (frame {0} is the root link, the tool frame
is the tip link) with one column per joint; times C it must be symjac's Jacobian in the independent coordinates.
Recent pinocchio (4.1 when this was written) also reads ``<mimic>`` itself (``buildModelFromUrdf(..., mimic=True)``):
its Jacobian then has one column per independent joint and must equal symjac's directly. pinocchio 4.1 refuses a
revolute joint that mimics a prismatic one, so the screw arm is compared with every joint free only.
"""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest
from test_mimic import CASES, _robot

from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.io import load_robot

pytestmark = pytest.mark.external
pin = pytest.importorskip("pinocchio", reason="pinocchio is not installed (pip install pin, or the [compare] extra)")

OWN_MIMIC = ["gripper"]  # the URDFs pinocchio's own mimic support reads (see the module docstring)


def _model(name: str, tmp_path, mimic: bool):
    text, tip = CASES[name]
    path = tmp_path / f"{name}.urdf"
    path.write_text(text, encoding="utf-8")
    model = pin.buildModelFromUrdf(str(path), mimic=mimic)
    return model, model.getFrameId(tip)


def _tip_jacobian(model, frame_id: int, configuration: np.ndarray) -> np.ndarray:
    data = model.createData()
    pin.computeJointJacobians(model, data, configuration)
    pin.updateFramePlacements(model, data)
    return pin.getFrameJacobian(model, data, frame_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)


def _configurations(robot, count: int = 4) -> list[np.ndarray]:
    rng = np.random.default_rng(2028)
    return [rng.uniform(-1.5, 1.5, robot.n_coordinates) for _ in range(count)]


@pytest.mark.parametrize("name", sorted(CASES))
def test_pinocchio_with_every_joint_free_times_c(name, tmp_path):
    robot = _robot(name)
    model, frame_id = _model(name, tmp_path, mimic=False)
    joints = [model.joints[model.getJointId(joint.name)] for joint in robot.joints]
    assert all(joint.nq == 1 and joint.nv == 1 for joint in joints)  # revolute and prismatic: one number each
    C = np.array(coupling_matrix(robot).xreplace(robot.defaults), dtype=float)
    for q in _configurations(robot):
        theta = [float(value.xreplace(dict(zip(robot.q, q, strict=True)))) for value in robot.joint_values]
        configuration = pin.neutral(model)  # the joints off the chain stay where they are: they move nothing here
        for joint, value in zip(joints, theta, strict=True):
            configuration[joint.idx_q] = value
        J_joints = _tip_jacobian(model, frame_id, configuration)[:, [joint.idx_v for joint in joints]]
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0, "tool"), J_joints @ C, atol=1e-12)


@pytest.mark.parametrize("name", OWN_MIMIC)
def test_pinocchio_own_mimic_support(name, tmp_path):
    robot = _robot(name)
    try:
        model, frame_id = _model(name, tmp_path, mimic=True)
    except TypeError:  # an older pinocchio has no mimic argument
        pytest.skip(f"pinocchio {pin.__version__} has no mimic support in buildModelFromUrdf")
    assert model.nv == robot.n_coordinates  # one velocity per joint that mimics nothing
    free = [model.joints[model.getJointId(robot.joints[robot.joint_variables.index(c)].name)] for c in robot.q]
    for q in _configurations(robot):
        configuration = pin.neutral(model)
        for joint, value in zip(free, q, strict=True):
            configuration[joint.idx_q] = value
        J = _tip_jacobian(model, frame_id, configuration)[:, [joint.idx_v for joint in free]]
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0, "tool"), J, atol=1e-12)


def test_a_finger_that_mimics_the_other_finger_against_pinocchio(tmp_path):
    """The catalog gripper to its right fingertip: the leader, finger_joint, is on the other finger, off the chain."""
    robot = load_robot("gripper.urdf", tip_link="right_fingertip")
    path = tmp_path / "gripper.urdf"
    path.write_bytes(resources.files("symjac.robots").joinpath("urdf", "gripper.urdf").read_bytes())
    try:
        model = pin.buildModelFromUrdf(str(path), mimic=True)
    except TypeError:  # an older pinocchio has no mimic argument
        pytest.skip(f"pinocchio {pin.__version__} has no mimic support in buildModelFromUrdf")
    frame_id = model.getFrameId("right_fingertip")
    names = [str(c) if c not in robot.joint_variables else robot.joints[robot.joint_variables.index(c)].name
             for c in robot.q]
    assert "finger_joint" in names
    free = [model.joints[model.getJointId(name)] for name in names]
    for q in _configurations(robot):
        configuration = pin.neutral(model)
        for joint, value in zip(free, q, strict=True):
            configuration[joint.idx_q] = value
        J = _tip_jacobian(model, frame_id, configuration)[:, [joint.idx_v for joint in free]]
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0, "tool"), J, atol=1e-12)
