"""Closed-form IK of arms with fewer than six joints: planar 2R and 3R, SCARA, articulated 3R.

Every solution is checked by the chain's symbolic tool pose lambdified at the defaults, in the components the plan
controls; counts against EAIK (planar 3R) or the numeric solver with many restarts (SCARA, 2R, articulated 3R).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics import solve_numeric
from symjac.analysis.inverse_kinematics.closed_form import solve_plan
from symjac.analysis.inverse_kinematics.geometry import arm_geometry
from symjac.analysis.inverse_kinematics.planar import articulated_plan, planar_plan, scara_plan
from symjac.codegen.numeric_model import numeric_model
from symjac.kinematics.chain import forward_kinematics

BUILDERS = {"planar2r": planar_plan, "planar3r": planar_plan, "scara": scara_plan, "articulated3r": articulated_plan}
FAMILIES = {"planar2r": "planar 2R", "planar3r": "planar 3R", "scara": "SCARA", "articulated3r": "articulated 3R"}
POSES = 500


def _fk(robot):
    pose = forward_kinematics(robot).subs(robot.defaults)
    return sp.lambdify([list(robot.joint_variables)], pose, "numpy")


def _controlled(name, pose):
    """The numbers of a pose that the arm controls: x, y (and z); the rotation about z as (cos, sin)."""
    pose = np.asarray(pose, dtype=float)
    if name in ("planar2r",):
        return pose[:2, 3]
    if name == "articulated3r":
        return pose[:3, 3]
    position = pose[:3, 3] if name == "scara" else pose[:2, 3]
    return np.concatenate([position, pose[:2, 0]])


def _sample(robot, rng):
    q = rng.uniform(-np.pi, np.pi, len(robot.joints))
    for i, joint in enumerate(robot.joints):
        if not joint.is_revolute:
            q[i] = rng.uniform(*[float(v) for v in joint.limits])
    return q


def _solve(name, q=None, pose=None):
    robot = load_robot(name)
    plan = BUILDERS[name](arm_geometry(robot))
    fk = _fk(robot)
    pose = np.asarray(fk(q), dtype=float) if pose is None else pose
    return robot, plan, fk, pose, solve_plan(plan, pose)


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_family_and_what_it_controls(name):
    robot = load_robot(name)
    plan = BUILDERS[name](arm_geometry(robot))
    assert plan.family == FAMILIES[name]
    assert plan.controlled != "the whole pose"
    assert "parallel" in plan.reasons[0]
    others = [b for n, b in BUILDERS.items() if b is not BUILDERS[name]]
    assert all(b(arm_geometry(robot)) is None for b in others)


@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford"])
def test_six_joint_arms_are_none_of_these(name):
    geometry = arm_geometry(load_robot(name))
    assert all(b(geometry) is None for b in set(BUILDERS.values()))


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_round_trips(name):
    robot = load_robot(name)
    plan, fk = BUILDERS[name](arm_geometry(robot)), _fk(robot)
    rng = np.random.default_rng(46)
    for _ in range(POSES):
        q = _sample(robot, rng)
        pose = np.asarray(fk(q), dtype=float)
        result = solve_plan(plan, pose)
        assert result.solutions, (q, result.unreachable)
        for s in result.solutions:
            assert np.abs(_controlled(name, fk(s.q)) - _controlled(name, pose)).max() < 1e-10
        assert min(np.abs(np.angle(np.exp(1j * (s.q - q)))).max() for s in result.solutions) < 1e-7


def test_planar_2r_elbow_down_is_the_positive_elbow_angle():
    """The textbook form: c2 = (x^2 + y^2 - L1^2 - L2^2) / (2 L1 L2); elbow down has theta2 = +acos(c2)."""
    robot, _, _, pose, result = _solve("planar2r", q=np.array([0.3, 1.1]))
    defaults = {str(k): float(v) for k, v in robot.defaults.items()}
    l1, l2 = defaults["L1"], defaults["L2"]
    x, y = pose[0, 3], pose[1, 3]
    c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    branches = {s.branch: s.q for s in result.solutions}
    assert np.isclose(branches[("elbow down",)][1], np.arccos(c2))
    assert np.isclose(branches[("elbow up",)][1], -np.arccos(c2))
    k1, k2 = l1 + l2 * c2, l2 * np.sin(np.arccos(c2))
    assert np.isclose(branches[("elbow down",)][0], np.arctan2(y, x) - np.arctan2(k2, k1))


def test_planar_2r_ignores_what_it_does_not_control():
    robot = load_robot("planar2r")
    fk = _fk(robot)
    pose = np.asarray(fk([0.4, -0.8]), dtype=float)
    tilted = pose.copy()
    tilted[2, 3] = 0.3  # out of the plane
    tilted[:3, :3] = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])
    plan = planar_plan(arm_geometry(robot))
    same = [s.q for s in solve_plan(plan, pose).solutions]
    other = [s.q for s in solve_plan(plan, tilted).solutions]
    assert len(same) == len(other) == 2
    assert np.allclose(same, other, atol=1e-12)


def test_unreachable_2r_says_how_far():
    pose = np.eye(4)
    pose[0, 3] = 1.2  # L1 + L2 = 0.9
    _, _, _, _, result = _solve("planar2r", pose=pose)
    assert result.solutions == ()
    assert result.unreachable
    assert result.distance == pytest.approx(0.3, abs=1e-9)


def test_stretched_2r_has_one_solution():
    _, _, _, _, result = _solve("planar2r", q=np.array([0.7, 0.0]))
    assert len(result.solutions) == 1


def _distinct(qs, tolerance=1e-6):
    kept = []
    for q in qs:
        if all(np.abs(np.angle(np.exp(1j * (q - k)))).max() > tolerance for k in kept):
            kept.append(q)
    return kept


@pytest.mark.parametrize("name", ["scara", "planar2r", "articulated3r"])
def test_count_against_the_numeric_solver(name):
    """Many restarts of the numeric solver (position only where the plan controls only the position)."""
    robot = load_robot(name)
    plan, fk, model = BUILDERS[name](arm_geometry(robot)), _fk(robot), numeric_model(robot)
    rng = np.random.default_rng(3)
    orientation = 1.0 if name == "scara" else 0.0
    for _ in range(6):
        pose = np.asarray(fk(_sample(robot, rng)), dtype=float)
        closed = _distinct([s.q for s in solve_plan(plan, pose).solutions])
        numeric = solve_numeric(robot, pose, model, rng=5, restarts=60, orientation_weight=orientation)
        assert len(closed) == len(_distinct([s.q for s in numeric], 1e-5))


def test_planar_3r_count_equals_eaik():
    hp = pytest.importorskip("eaik.IK_HP")
    robot = load_robot("planar3r")
    geometry = arm_geometry(robot)
    plan, fk = planar_plan(geometry), _fk(robot)

    def value(m):
        return np.array(sp.Matrix(m).subs(robot.defaults), dtype=float)

    axes, points, home = [value(h).ravel() for h in geometry.axes], [value(p).ravel() for p in geometry.points], value(
        geometry.home
    )
    offsets = [points[0], points[1] - points[0], points[2] - points[1], home[:3, 3] - points[2]]
    eaik = hp.HPRobot(np.array(axes), np.array(offsets))
    rng = np.random.default_rng(11)
    for _ in range(200):
        pose = np.asarray(fk(rng.uniform(-np.pi, np.pi, 3)), dtype=float)
        reference = eaik.IK(pose)
        expected = len(_distinct([q for q, ls in zip(reference.Q, reference.is_LS, strict=True) if not ls]))
        assert len(_distinct([s.q for s in solve_plan(plan, pose).solutions])) == expected
