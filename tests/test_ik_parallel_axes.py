"""Closed-form IK of the UR family (joints 2, 3, 4 parallel): round trips, EAIK's count, singular and far poses.

The forward kinematics that checks every solution is the chain's symbolic tool pose lambdified at the defaults (no
plan, no generated code); the independent count is EAIK's (PyPI ``EAIK``, IK-Geo's subproblem solutions in C++).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq, least_squares

from symjac import load_robot
from symjac.analysis.inverse_kinematics.closed_form import solve_plan
from symjac.analysis.inverse_kinematics.geometry import arm_geometry
from symjac.analysis.inverse_kinematics.parallel_axes import three_parallel_axes_plan
from symjac.analysis.inverse_kinematics.planar import planar_plan
from symjac.kinematics.chain import forward_kinematics

ARMS = ["ur5", "ur5_poe"]
POSES = 10_000  # about 6 s per arm with EAIK's count and the independent FK


def _fk(robot):
    pose = forward_kinematics(robot).subs(robot.defaults)
    return sp.lambdify([list(robot.joint_variables)], pose, "numpy")


def _numbers(geometry):
    defaults = geometry.robot.defaults

    def value(m):
        return np.array(sp.Matrix(m).subs(defaults), dtype=float)

    return [value(h).ravel() for h in geometry.axes], [value(p).ravel() for p in geometry.points], value(geometry.home)


def _eaik(geometry):
    """EAIK's robot from the same axes (its tool frame is the home rotation's inverse away from ours)."""
    hp = pytest.importorskip("eaik.IK_HP")
    axes, points, home = _numbers(geometry)
    offsets = [points[0]] + [points[i + 1] - points[i] for i in range(len(points) - 1)] + [home[:3, 3] - points[-1]]
    robot = hp.HPRobot(np.array(axes), np.array(offsets))
    back = np.eye(4)
    back[:3, :3] = home[:3, :3].T
    return robot, back


def _distinct(qs):
    kept = []
    for q in qs:
        if all(np.abs(np.angle(np.exp(1j * (q - k)))).max() > 1e-6 for k in kept):
            kept.append(q)
    return kept


def _round_trips(name, count, seed):
    robot = load_robot(name)
    geometry = arm_geometry(robot)
    plan = three_parallel_axes_plan(geometry)
    fk = _fk(robot)
    eaik, back = _eaik(geometry)
    rng = np.random.default_rng(seed)
    worst, counts = 0.0, {}
    for _ in range(count):
        q = rng.uniform(-np.pi, np.pi, 6)
        pose = np.asarray(fk(q), dtype=float)
        result = solve_plan(plan, pose)
        solved = [s.q for s in result.solutions]
        assert solved, (q, result.unreachable)
        worst = max(worst, max(np.abs(np.asarray(fk(x), dtype=float) - pose).max() for x in solved))
        assert min(np.abs(np.angle(np.exp(1j * (x - q)))).max() for x in solved) < 1e-7, q
        reference = eaik.IK(pose @ back)
        expected = len(_distinct([x for x, ls in zip(reference.Q, reference.is_LS, strict=True) if not ls]))
        assert len(_distinct(solved)) == expected, (q, len(solved), expected)
        counts[expected] = counts.get(expected, 0) + 1
    assert worst < 1e-10, worst
    return counts


@pytest.mark.parametrize("name", ARMS)
def test_family_is_decided_exactly(name):
    plan = three_parallel_axes_plan(arm_geometry(load_robot(name)))
    assert plan is not None and plan.family == "three parallel axes"
    assert plan.reasons[0] == "the axes of joints 2, 3 and 4 are parallel"
    assert [s.joints for s in plan.steps] == [(0,), (4,), (5,), (2,), (1,), (3,)]
    assert plan.max_solutions == 8 and plan.controlled == "the whole pose"


@pytest.mark.parametrize("name", ["puma560", "stanford", "planar3r", "scara"])
def test_other_arms_are_not_of_the_family(name):
    assert three_parallel_axes_plan(arm_geometry(load_robot(name))) is None


def test_planar_builder_refuses_the_ur5():
    assert planar_plan(arm_geometry(load_robot("ur5"))) is None


@pytest.mark.parametrize("name", ARMS)
def test_round_trips_and_eaik_count(name):
    counts = _round_trips(name, POSES, 4646)  # seed 46 meets the near-singular pose of the test below
    assert counts.get(8, 0) > POSES // 2  # eight solutions in general


def test_near_the_wrist_singularity_every_branch_stays():
    """theta5 = 8.5e-6 rad: the shoulder-left branches must not vanish (they did: 2 solutions, both shoulder right)."""
    robot = load_robot("ur5")
    plan, fk = three_parallel_axes_plan(arm_geometry(robot)), _fk(robot)
    q = np.array([0.324479228, -0.232598535, -0.325325165, -0.114640407, 8.53447211e-06, -2.70449509])
    pose = np.asarray(fk(q), dtype=float)
    result = solve_plan(plan, pose)
    solved = [s.q for s in result.solutions]
    assert {s.branch[0] for s in result.solutions} == {"shoulder right", "shoulder left"}
    assert len(solved) == 4  # theta5 = -8.5e-6 (theta6 turned by pi) leaves the elbow out of reach: |cos| = 1.26
    assert max(np.abs(np.asarray(fk(x), dtype=float) - pose).max() for x in solved) < 1e-10
    assert min(np.abs(np.angle(np.exp(1j * (x - q)))).max() for x in solved) < 1e-6


def test_poe_copy_gives_the_same_solutions(tmp_path):
    """With the DH file's lengths, ur5_poe is the UR5 seen from a base turned by pi about z: same joint solutions."""
    text = (Path(__file__).parents[1] / "symjac" / "robots" / "ur5_poe.toml").read_text()
    lengths = {"W1": 0.10915, "W2": 0.0823, "L1": 0.425, "L2": 0.39225, "H1": 0.089159, "H2": 0.09465}
    for key, value in lengths.items():
        text = re.sub(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.MULTILINE)
    (tmp_path / "ur5_same.toml").write_text(text)
    dh, poe = load_robot("ur5"), load_robot(tmp_path / "ur5_same.toml")
    plans = [three_parallel_axes_plan(arm_geometry(r)) for r in (dh, poe)]
    fk = _fk(dh)
    turn = np.diag([-1.0, -1.0, 1.0, 1.0])
    rng = np.random.default_rng(7)
    for _ in range(50):
        pose = np.asarray(fk(rng.uniform(-np.pi, np.pi, 6)), dtype=float)
        first = solve_plan(plans[0], pose).solutions
        second = solve_plan(plans[1], turn @ pose).solutions
        assert len(first) == len(second) > 0
        for a, b in zip(first, second, strict=True):
            assert a.branch == b.branch
            assert np.abs(np.angle(np.exp(1j * (a.q - b.q)))).max() < 1e-9


def _wrist_singular(q):
    q = np.array(q, dtype=float)
    q[4] = 0.0
    return q


def test_wrist_singularity_is_described():
    robot = load_robot("ur5")
    plan, fk = three_parallel_axes_plan(arm_geometry(robot)), _fk(robot)
    q = _wrist_singular([0.4, -1.1, 1.3, -0.6, 0.0, 0.9])
    pose = np.asarray(fk(q), dtype=float)
    result = solve_plan(plan, pose)
    assert result.solutions
    for s in result.solutions:
        assert np.abs(np.asarray(fk(s.q), dtype=float) - pose).max() < 1e-9
    singular = [s for s in result.solutions if s.singular]
    assert singular and all("theta6" in s.singular for s in singular)
    # the continuum: axes 2, 3, 4 and 6 are parallel there, and the pose fixes only theta2 + theta3 + theta4 + theta6
    fixed = q[1] + q[2] + q[3] + q[5]
    assert any(abs(np.angle(np.exp(1j * (s.q[1] + s.q[2] + s.q[3] + s.q[5] - fixed)))) < 1e-9 for s in singular)
    for solution in singular:
        match = re.match(r"theta2 ([+-]) theta3 ([+-]) theta4 ([+-]) theta6 = (\S+) is fixed; theta6 shown at 0 "
                         r"\(theta2, theta3, theta4 change with theta6\); wrist down and wrist up coincide",
                         solution.singular)
        assert match, solution.singular
        signs = np.array([1.0] + [1.0 if sign == "+" else -1.0 for sign in match.groups()[:3]])
        assert solution.q[5] == 0.0 and "wrist down" in solution.branch

        def stated(x, signs=signs):
            return float(signs @ x[[1, 2, 3, 5]])

        assert abs(np.angle(np.exp(1j * (stated(solution.q) - float(match.group(4)))))) < 1e-5
        # along the continuum: another theta6, theta1 and theta5 kept, theta2..4 found by least squares on the FK
        for theta6 in (0.3, -0.5, 1.0):
            def residual(x, theta6=theta6, start=solution.q):
                moved = start.copy()
                moved[[1, 2, 3, 5]] = [*x, theta6]
                return (np.asarray(fk(moved), dtype=float) - pose)[:3].ravel()

            found = least_squares(residual, solution.q[1:4], xtol=1e-15, ftol=1e-15, gtol=1e-15)
            assert np.abs(residual(found.x)).max() < 1e-9
            moved = solution.q.copy()
            moved[[1, 2, 3, 5]] = [*found.x, theta6]
            assert abs(np.angle(np.exp(1j * (stated(moved) - stated(solution.q))))) < 1e-8


def test_shoulder_singularity_merges_the_shoulder_branches():
    """The wrist point at the offset distance from axis 1: both theta1 solutions coincide."""
    robot = load_robot("ur5")
    plan, fk = three_parallel_axes_plan(arm_geometry(robot)), _fk(robot)
    axes, points, home = _numbers(arm_geometry(robot))
    corner = points[5]  # on the UR5, the point given for axis 6 is where axes 5 and 6 meet

    def radial(t2):  # the wrist point's coordinate along h1 x h2 turned by theta1: zero over the base
        pose = np.asarray(fk([0.3, t2, 1.0, 0.0, 0.7, -0.2]), dtype=float)
        w = pose[:3, :3] @ home[:3, :3].T @ (corner - home[:3, 3]) + pose[:3, 3]
        turn = np.array([[np.cos(0.3), -np.sin(0.3), 0.0], [np.sin(0.3), np.cos(0.3), 0.0], [0.0, 0.0, 1.0]])
        return float(w @ (turn @ np.cross(axes[1], axes[0])))

    t2 = brentq(radial, -3.0, 0.0) if radial(-3.0) * radial(0.0) < 0 else brentq(radial, 0.0, 3.0)
    q = np.array([0.3, t2, 1.0, 0.0, 0.7, -0.2])
    pose = np.asarray(fk(q), dtype=float)
    result = solve_plan(plan, pose)
    assert result.solutions
    for s in result.solutions:
        assert np.abs(np.asarray(fk(s.q), dtype=float) - pose).max() < 1e-9
    assert len({round(float(s.q[0]), 6) for s in result.solutions}) == 1
    # the note says so, and the fact it states: the wrist point's distance from axis 1 is the offset along h2
    w = pose[:3, :3] @ home[:3, :3].T @ (corner - home[:3, 3]) + pose[:3, 3]
    offset = abs(float(axes[1] @ (corner - points[0])))
    note = (f"the wrist point (where axes 5 and 6 meet) {offset:.4g} from axis 1, as close as it comes: shoulder right "
            "and shoulder left coincide")
    assert all(s.branch[0] == "shoulder right" and note in s.singular for s in result.solutions)
    assert np.linalg.norm(np.cross(axes[0], w - points[0])) == pytest.approx(offset, rel=1e-9)


def test_unreachable_pose_says_how_far():
    robot = load_robot("ur5")
    plan, fk = three_parallel_axes_plan(arm_geometry(robot)), _fk(robot)
    pose = np.asarray(fk(np.zeros(6)), dtype=float)
    pose[:3, 3] *= 3.0
    result = solve_plan(plan, pose)
    assert result.solutions == ()
    assert result.unreachable == (f"the point where axes 4 and 5 meet is {result.distance:.4g} beyond "
                                  "the reach of the arm stretched at joint 3")
    assert result.distance > 0.5


def test_the_stretched_elbow_at_home_says_so():
    """At q = 0 the UR5's arm is straight: one elbow solution on each shoulder, with the same name, and a note."""
    robot = load_robot("ur5")
    plan, fk = three_parallel_axes_plan(arm_geometry(robot)), _fk(robot)
    result = solve_plan(plan, np.asarray(fk(np.zeros(6)), dtype=float))
    assert {s.branch[0] for s in result.solutions} == {"shoulder right", "shoulder left"}
    assert all(s.branch[2] == "elbow down" and "elbow stretched: elbow down and elbow up coincide" in s.singular
               for s in result.solutions)
    home = next(s for s in result.solutions if np.abs(s.q).max() < 1e-9)
    assert home.q[2] == 0.0  # stretched: theta3 = 0 on the UR5
