"""Generated closed-form inverse kinematics near a wrist singularity (theta5 = 1e-4 ... 1e-8), in numpy and C99.

Subproblem 2's ``gamma^2`` written as ``|u|^2 - alpha^2 - ...`` (the PUMA 560's ``1 - q4_z^2``) loses all digits of
``sin(theta5)^2`` there, and clamping it below rounding noise set ``theta5 = 0``: rows off the pose by 1e-8 at
``theta5 = 1e-8``. Every written row must reproduce the pose to 1e-9 and one of them be the generating configuration
(``theta4`` and ``theta6`` to 1e-6: apart, they are only determined to rounding / ``theta5``).
"""

from __future__ import annotations

import numpy as np
import pytest
from ik_generated import ik_solvers

from symjac.codegen.numeric_model import numeric_model
from symjac.model.io import load_robot


@pytest.fixture(scope="module", params=["puma560", "irb140"])
def arm(request, tmp_path_factory):
    robot = load_robot(request.param)
    return robot, ik_solvers(tmp_path_factory.mktemp(f"wrist_{robot.name}"), robot, ("numpy", "c99"))


@pytest.mark.parametrize("theta5", [1e-4, 1e-6, 1e-7, 1e-8, -1e-8])
def test_rows_near_a_wrist_singularity_reproduce_the_pose(arm, theta5):
    robot, solvers = arm
    fk = numeric_model(robot, backend="numpy").fk
    q = np.array([0.3, -0.5, 0.4, 0.7, theta5, -0.2])
    pose = fk(q[None])[0]
    for target, solve in solvers.items():
        (rows,) = solve(pose[None])
        assert len(rows) == 8, target
        assert np.abs(fk(rows) - pose).max() < 1e-9, target
        nearest = np.abs((rows - q + np.pi) % (2 * np.pi) - np.pi).max(axis=1).min()
        assert nearest < 1e-6, target
