"""example-robot-data's URDF arms read by symjac and by pinocchio, the two models made the same rigid chain.

symjac reads the file up to the tip link; joints off the chain (the Panda's fingers, the grippers of TALOS's arm and
of the Z1) are held at zero by symjac, which lumps their bodies into the chain link that carries them. pinocchio's
model is reduced the same way (``buildReducedModel``, those joints locked at zero), so that its dynamics are those of
the same rigid arm. Shared by the dynamics and identification comparisons with pinocchio.
"""

from __future__ import annotations

import numpy as np
import pytest
from collection import example_robots

from symjac.model.io import load_robot

pin = pytest.importorskip("pinocchio", reason="pinocchio is not installed (pip install pin, or the [compare] extra)")

FOLDER = example_robots()

ARMS = {  # name: (file, tip link)
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "tool0"),
    "panda": ("panda_description/urdf/panda.urdf", "panda_link8"),
    "xarm7": ("xarm_description/urdf/xarm7.urdf", "link7"),
    "talos-left-arm": ("talos_data/robots/talos_left_arm.urdf", "arm_left_7_link"),
    "z1": ("z1_description/urdf/z1.urdf", "link06"),
    "kinova": ("kinova_description/robots/kinova.urdf", "j2s6s200_end_effector"),
    "so100": ("so_arm_description/urdf/so100.urdf", "jaw"),
    "ur10": ("ur_description/urdf/ur10_robot.urdf", "tool0"),
}


class PinocchioArm:
    """One arm read by both libraries: symjac's ``robot`` and pinocchio's (reduced) ``model``, joints in one order."""

    def __init__(self, name: str):
        self.name = name
        path, tip = ARMS[name]
        self.robot = arm = load_robot(str(FOLDER / path), tip_link=tip)
        full = pin.buildModelFromUrdf(str(FOLDER / path))
        ids = [full.getJointId(joint.name) for joint in arm.joints]
        locked = [i for i in range(1, full.njoints) if i not in ids]
        self.locked = [full.names[i] for i in locked]
        # (reduced only when needed: pinocchio refuses to reduce the SO-100's model, two of whose frames share a name)
        self.model = pin.buildReducedModel(full, locked, pin.neutral(full)) if locked else full
        self.data = self.model.createData()
        self.joints = [self.model.joints[self.model.getJointId(joint.name)] for joint in arm.joints]
        assert [j.idx_v for j in self.joints] == list(range(arm.n_joints)) == list(range(self.model.nv))

    def configuration(self, q: np.ndarray) -> np.ndarray:
        """pinocchio's configuration vector for the chain's angles (a continuous joint stores cos and sin)."""
        out = pin.neutral(self.model)
        for joint, value in zip(self.joints, q, strict=True):
            if joint.nq == 2:
                out[joint.idx_q:joint.idx_q + 2] = np.cos(value), np.sin(value)
            else:
                out[joint.idx_q] = value
        return out


def states(n: int, count: int = 3):
    """``count`` random (q, qd, qdd) of an n-joint arm, the same on every run."""
    rng = np.random.default_rng(44)
    return [tuple(rng.uniform(-2, 2, n) for _ in range(3)) for _ in range(count)]


def close(got: np.ndarray, expected: np.ndarray, tolerance: float = 1e-10) -> None:
    """``got`` equals ``expected`` to ``tolerance`` relative to the largest entry (at least 1)."""
    scale = max(1.0, float(np.abs(expected).max()))
    assert np.abs(got - expected).max() <= tolerance * scale, np.abs(got - expected).max()
