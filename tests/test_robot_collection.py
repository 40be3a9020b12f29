"""Every URDF of a public robot collection: example-robot-data (PyPI, the ``compare`` extra, 69 files in 6.0.0).

Each file loads with a chosen tip (the leaf with the most moving joints above it, so that a humanoid gives a leg or
an arm and a quadruped a leg), or is refused for a stated reason; none is refused for what its comments or text
hold (16 files of 6.0.0 keep ``${prefix}`` in commented-out xacro). On six arms from six makers, symjac's Jacobian
of the tip link's origin, in the root link's axes, equals pinocchio's frame Jacobian (LOCAL_WORLD_ALIGNED) read from
the same file, to 1e-10; a gripper finger on the chain that mimics the other finger makes that finger's joint a
coordinate (PR2, TALOS, TIAGo Pro).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from collection import example_robots

from symjac.errors import RobotFileError
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.io import load_robot
from symjac.model.readers.tree import TreeJointType
from symjac.model.readers.urdf import tree_from_urdf

pytestmark = pytest.mark.external


FOLDER = example_robots()
FILES = sorted(FOLDER.rglob("*.urdf"))

REFUSED = {  # file: why it is no arm symjac can read (a reason, never the format)
    "hector_description/robots/quadrotor_base.urdf": "no revolute, continuous or prismatic joint between",
    "iris_description/robots/iris_simple.urdf": "no revolute, continuous or prismatic joint between",  # rotors fixed
    "ur_description/urdf/ur3.urdf": "the robot has no links",  # an empty <robot> left by a failed xacro run
    # a finger mimics a joint of the other hand's naming scheme that the file does not define
    "alex_description/urdf/alex_psyonic_hands.urdf": "mimics 'index_q1', which is not a joint of this robot",
}
ARMS = {  # file: tip link, for the comparison with pinocchio
    "xarm_description/urdf/xarm7.urdf": "link7",
    "talos_data/robots/talos_left_arm.urdf": "arm_left_7_link",
    "z1_description/urdf/z1.urdf": "link06",
    "kinova_description/robots/kinova.urdf": "j2s6s200_end_effector",
    "so_arm_description/urdf/so100.urdf": "jaw",
    "ur_description/urdf/ur10_robot.urdf": "tool0",
}


def _name(path: Path) -> str:
    return path.relative_to(FOLDER).as_posix()


def _deepest_leaf(path: Path) -> str:
    """The leaf link with the most moving joints between it and the root (ties: the first name)."""
    tree = tree_from_urdf(path.read_bytes(), str(path))
    parent = {joint.child: joint for joint in tree.joints}
    leaves = {link.name for link in tree.links} - {joint.parent for joint in tree.joints}

    def depth(link: str) -> int:
        moving = 0
        while link in parent:
            moving += parent[link].type not in (TreeJointType.FIXED,)
            link = parent[link].parent
        return moving

    return min(sorted(leaves), key=lambda link: -depth(link))


def test_the_collection_is_the_one_described():
    assert len(FILES) >= 69 and set(REFUSED) | set(ARMS) <= {_name(path) for path in FILES}


@pytest.mark.filterwarnings("ignore::symjac.errors.InertialWarning")  # CAD-rounded tensors, kept as given
@pytest.mark.parametrize("path", FILES, ids=_name)
def test_every_file_loads_or_is_refused_for_a_reason(path):
    if _name(path) in REFUSED:
        with pytest.raises(RobotFileError, match=REFUSED[_name(path)]):
            load_robot(path, tip_link=_deepest_leaf(path) if "no links" not in REFUSED[_name(path)] else None)
        return
    robot = load_robot(path, tip_link=_deepest_leaf(path))
    assert robot.n_joints >= 1 and all(joint.name for joint in robot.joints)


@pytest.fixture(scope="module")
def pin():
    return pytest.importorskip("pinocchio", reason="pinocchio is not installed (pip install pin, or the [compare] "
                                                   "extra)")


@pytest.mark.parametrize("name", sorted(ARMS))
def test_jacobians_equal_pinocchios(pin, name):
    path = FOLDER / name
    robot = load_robot(path, tip_link=ARMS[name])
    model = pin.buildModelFromUrdf(str(path))
    data = model.createData()
    frame = model.getFrameId(ARMS[name])
    joints = [model.joints[model.getJointId(joint.name)] for joint in robot.joints]
    rng = np.random.default_rng(43)
    for _ in range(3):
        q = rng.uniform(-1.5, 1.5, robot.n_coordinates)
        configuration = pin.neutral(model)
        for joint, value in zip(joints, q, strict=True):
            if joint.nq == 2:  # a continuous joint: pinocchio stores (cos, sin)
                configuration[joint.idx_q:joint.idx_q + 2] = np.cos(value), np.sin(value)
            else:
                configuration[joint.idx_q] = value
        pin.computeJointJacobians(model, data, configuration)
        pin.updateFramePlacements(model, data)
        expected = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        expected = expected[:, [joint.idx_v for joint in joints]]
        # the end of the chain: the tip link's origin (the tool point, or the flange when the tip is a joint's link)
        np.testing.assert_allclose(numeric_jacobian(robot, q, 0), expected, atol=1e-10)
