"""The catalog's published inertial data against the tools that publish it.

The PUMA 560 carries Armstrong, Khatib and Burdick's parameters as the Robotics Toolbox (roboticstoolbox-python)
holds them, moved from the Toolbox's standard-DH frames to the file's modified-DH ones (the file's comments say how).
Its torques are those of the Toolbox's pure-Python ``rne_python`` (not the compiled ``rne``, whose gravity is wrong
for some models), which adds the motors' inertia G^2 Jm qdd and friction B G^2 qd + |G| Tc (the file carries them as
drives, Coulomb friction as the mean of the Toolbox's two directions: the Toolbox model gets that mean here), at the
Toolbox's angles q + (pi, pi, 0, 0, 0, 0), to 1e-9 relative to the largest torque; and without the motors, the
rigid bodies alone. The Panda carries Gaz et al.'s (2019) identified parameters as the Toolbox's
DH Panda holds them (the same frames but the last), checked the same way.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.dynamics import dynamics_defaults, newton_euler

pytestmark = pytest.mark.external
rtb = pytest.importorskip("roboticstoolbox", reason="roboticstoolbox-python is not installed (the [compare] extra)")

OFFSET = np.array([np.pi, np.pi, 0, 0, 0, 0])  # the Toolbox's angles are the file's plus these


def _toolbox_puma(motors: bool = False):
    """The Toolbox's PUMA 560: rigid bodies only, or with its motors (Coulomb friction the same in both directions)."""
    if motors:
        puma = rtb.models.DH.Puma560()
        for link in puma.links:
            mean = (link.Tc[0] - link.Tc[1]) / 2
            link.Tc = [mean, -mean]
        return puma
    puma = rtb.models.DH.Puma560().nofriction(coulomb=True, viscous=True)
    for link in puma.links:
        link.Jm = 0  # rigid-body torques only: no motor (armature) inertia
    return puma


@pytest.mark.parametrize("motors", [True, False])
def test_puma560_torques_equal_the_robotics_toolboxs_rne_python(motors):
    arm = load_robot("puma560")
    assert all(drive is not None for drive in arm.drives)
    arm = arm if motors else dataclasses.replace(arm, drives=())
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]
    torques = sp.lambdify(args, newton_euler(arm, simplify=False).torques, cse=True)
    puma = _toolbox_puma(motors)
    rng = np.random.default_rng(560)
    for _ in range(4):
        q, qd, qdd = (rng.uniform(-2, 2, 6) for _ in range(3))
        expected = np.asarray(puma.rne_python(q + OFFSET, qd, qdd), dtype=float).ravel()
        got = np.array(torques(*q, *qd, *qdd, *numbers.values()), dtype=float).ravel()
        assert np.abs(got - expected).max() <= 1e-9 * np.abs(expected).max(), (got, expected)
        assert np.abs(expected).max() > 1  # real torques


def test_the_file_and_the_toolbox_are_one_arm():
    """Each Toolbox frame {i} is fixed in the file's frame {i} (pedestal aside): the same links, the data moved."""
    from reference import frames

    arm, puma = load_robot("puma560"), _toolbox_puma()
    pedestal = np.eye(4)
    pedestal[2, 3] = -puma.links[0].d
    poses = []
    for seed in range(3):
        q = np.random.default_rng(seed).uniform(-2, 2, 6)
        ours, theirs = frames(arm, q)[2:8], puma.fkine_all(q + OFFSET)[1:]
        poses.append([np.linalg.inv(T) @ pedestal @ X.A for T, X in zip(ours, theirs, strict=True)])
    for other in poses[1:]:
        np.testing.assert_allclose(np.array(other), np.array(poses[0]), atol=1e-12)


def test_panda_torques_equal_the_robotics_toolboxs_rne_python():
    """Gaz et al.'s identified parameters, in the Toolbox's frames (its frame 7 is the flange: link 7 moved by dF)."""
    arm = load_robot("panda")
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]
    torques = sp.lambdify(args, newton_euler(arm, simplify=False).torques, cse=True)
    panda = rtb.models.DH.Panda()
    assert all(link.Jm == 0 and link.B == 0 and not np.any(link.Tc) for link in panda.links)  # rigid bodies only
    rng = np.random.default_rng(7)
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-2, 2, 7) for _ in range(3))
        expected = np.asarray(panda.rne_python(q, qd, qdd), dtype=float).ravel()
        got = np.array(torques(*q, *qd, *qdd, *numbers.values()), dtype=float).ravel()
        assert np.abs(got - expected).max() <= 1e-9 * np.abs(expected).max(), (got, expected)
        assert np.abs(expected).max() > 1
