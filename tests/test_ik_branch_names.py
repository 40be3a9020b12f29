"""Elbow branch names against the arm's posture: "elbow up" must put the elbow above the line from shoulder to wrist.

The posture comes from an independent forward kinematics (the symbolic frames, lambdified), not from the plan. In the
arm plane (across the shoulder axis, joint 2) the shoulder point S lies on axis 2, the elbow point E on axis 3 and the
wrist point W on axis 5 (the wrist centre of the PUMA 560 and IRB 140) or on axis 4 (the UR5, whose axes 2, 3, 4 are
parallel). The elbow's offset from the line S-W, in that plane, has a base-z component; the elbow is up when it is
positive. Skipped, where "above" says nothing: that component under 1 mm (the elbow on the line, or the line nearly
vertical), and the wrist point horizontally between axis 1 and the shoulder axis (the arm reaching back over the
vertical through its own shoulder, as only an arm with a shoulder offset like the IRB 140's can: which way the upper
arm faces is then undecided).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from symjac import forward_kinematics, load_robot
from symjac.analysis.inverse_kinematics import closed_form_plan, seed_bounds, solve_plan

POSES = 300
# the joints (1-based) whose axes hold the wrist point and the point the shoulder step places (the wrist centre; on the
# UR5 the point where axes 5 and 6 meet)
WRIST_AXIS = {"puma560": (5, 5), "irb140": (5, 5), "ur5": (4, 6)}


def _frames(robot, joints):
    """A function q -> (origin, z axis) of the frame of each joint in ``joints`` (1-based), in base coordinates."""
    offset = 0 if robot.convention == "modified" else -1  # modified DH: joint i turns about z_i; standard: z_(i-1)
    matrices = [forward_kinematics(robot, 0, j + offset).subs(robot.defaults) for j in joints]
    stacked = sympy.Matrix.hstack(*(m[:3, 2:4] for m in matrices))
    function = sympy.lambdify([robot.joint_variables], stacked, "numpy")
    return lambda q: [(block[:, 1], block[:, 0]) for block in np.split(np.asarray(function(q), float), len(joints), 1)]


def _elbow_height(frames, q):
    """The base-z component of the elbow's offset from the shoulder-wrist line in the arm plane, and whether the
    wrist lies horizontally between axis 1 and the shoulder axis."""
    (base, _), (shoulder, across), (elbow, _), (wrist, _), (centre, _) = frames(q)
    flatten = lambda v: v - across * (v @ across)  # noqa: E731  (into the arm plane)
    line, arm = flatten(wrist - shoulder), flatten(elbow - shoulder)
    offset = arm - line * (arm @ line) / (line @ line)
    forward = np.cross([0.0, 0.0, 1.0], across)
    behind = (wrist - shoulder) @ forward * ((centre - base) @ forward) < 0
    return offset[2], behind


@pytest.mark.parametrize("name", sorted(WRIST_AXIS))
def test_elbow_up_puts_the_elbow_above_the_line_from_shoulder_to_wrist(name):
    robot = load_robot(name)
    plan = closed_form_plan(robot)
    frames = _frames(robot, (1, 2, 3, *WRIST_AXIS[name]))
    pose_of = sympy.lambdify([robot.joint_variables], forward_kinematics(robot).subs(robot.defaults), "numpy")
    generator = np.random.default_rng(46)
    checked, wrong = 0, []
    for q in generator.uniform(*seed_bounds(robot), (POSES, robot.n_joints)):
        for solution in solve_plan(plan, np.asarray(pose_of(q), float)).solutions:
            height, behind = _elbow_height(frames, solution.q)
            if abs(height) < 1e-3 or behind:
                continue
            checked += 1
            if ("elbow up" in solution.branch) != (height > 0):
                wrong.append((solution.branch, np.round(solution.q, 3).tolist(), round(float(height), 4)))
    assert checked > 4 * POSES  # most of the 8 (or 4) solutions per pose are decided
    assert wrong == [], f"{len(wrong)} of {checked} misnamed, e.g. {wrong[:3]}"


def test_the_puma_example_names_its_elbows_by_height():
    """The reviewer's pose: shoulder right with the elbow at z = -0.406 was called "elbow up"."""
    robot = load_robot("puma560")
    plan = closed_form_plan(robot)
    frames = _frames(robot, (1, 2, 3, 5, 5))
    pose = np.asarray(sympy.lambdify([robot.joint_variables], forward_kinematics(robot).subs(robot.defaults))(
        [0.4, -0.6, 0.3, 0.5, 0.7, -0.2]), float)
    heights = {s.branch[:2]: frames(s.q)[2][0][2] for s in solve_plan(plan, pose).solutions}
    assert heights[("shoulder right", "elbow up")] > 0 > heights[("shoulder right", "elbow down")]



def test_scara_handedness_follows_the_side_of_the_elbow():
    """Right-handed: the elbow to the right of the line from shoulder to wrist seen with the axes pointing at the
    viewer, z.((E - S) x (W - E)) > 0; on this SCARA (axes up, straight at home) the elbow angle theta2 > 0."""
    robot = load_robot("scara")
    plan = closed_form_plan(robot)
    frames = _frames(robot, (1, 2, 4))
    fk = sympy.lambdify([robot.joint_variables], forward_kinematics(robot).subs(robot.defaults), "numpy")
    generator = np.random.default_rng(12)
    checked = 0
    for _ in range(POSES):
        q = generator.uniform(*seed_bounds(robot))
        for solution in solve_plan(plan, np.asarray(fk(q), float)).solutions:
            (shoulder, z), (elbow, _), (wrist, _) = frames(solution.q)
            side = float(z @ np.cross(elbow - shoulder, wrist - elbow))
            if abs(side) < 1e-6:
                continue
            assert solution.branch[0] == ("right-handed" if side > 0 else "left-handed")
            assert (solution.q[1] > 0) == (side > 0)
            checked += 1
    assert checked > POSES
    # the boundary, theta2 = 0, is right-handed (theta2 >= 0)
    (solution,) = solve_plan(plan, np.asarray(fk([0.3, 0.0, -0.1, 0.2]), float)).solutions
    assert solution.branch[0] == "right-handed"
    assert solution.singular == "elbow stretched: right-handed and left-handed coincide"
