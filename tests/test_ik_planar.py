"""Closed-form IK of arms with fewer than six joints: planar 2R and 3R, SCARA, articulated 3R.

Every solution is checked by the chain's symbolic tool pose lambdified at the defaults, in the components the plan
controls; counts against EAIK (planar 3R) or the numeric solver with many restarts (SCARA, 2R, articulated 3R).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from ik_robots import CYLINDRICAL
from scipy.optimize import least_squares

from symjac import load_robot
from symjac.analysis.inverse_kinematics import solve_numeric
from symjac.analysis.inverse_kinematics.closed_form import branch_programs, closed_form_plan, solve_plan
from symjac.analysis.inverse_kinematics.geometry import arm_geometry
from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS
from symjac.analysis.inverse_kinematics.planar import articulated_plan, planar_plan, scara_plan, spherical_arm_plan
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
    reached, target = solve_plan(plan, pose), solve_plan(plan, tilted)
    same, other = [s.q for s in reached.solutions], [s.q for s in target.solutions]
    assert len(same) == len(other) == 2
    assert np.allclose(same, other, atol=1e-12)
    assert reached.uncontrolled_distance < 1e-12  # the orientation may differ: a 2R arm does not control it
    assert target.uncontrolled.startswith("the arm controls the position in the plane across the axes only")
    assert target.uncontrolled_distance == pytest.approx(0.3, abs=1e-9)


def test_unreachable_2r_says_how_far():
    pose = np.eye(4)
    pose[0, 3] = 1.2  # L1 + L2 = 0.9
    _, _, _, _, result = _solve("planar2r", pose=pose)
    assert result.solutions == ()
    assert result.unreachable == "the tool point is 0.3 beyond the reach of the arm stretched at joint 2"
    assert result.distance == pytest.approx(0.3, abs=1e-9)


def test_too_close_2r_says_the_arm_cannot_fold_that_far():
    pose = np.eye(4)
    pose[0, 3] = 0.04  # L1 - L2 = 0.1: the folded arm reaches no closer
    _, _, _, _, result = _solve("planar2r", pose=pose)
    assert result.solutions == () and result.distance == pytest.approx(0.06, abs=1e-9)
    assert result.unreachable == ("the tool point is 0.06 closer in than the arm folded at joint 2 "
                                  "reaches")


def test_stretched_2r_has_one_solution():
    _, _, _, _, result = _solve("planar2r", q=np.array([0.7, 0.0]))
    assert len(result.solutions) == 1
    (solution,) = result.solutions
    assert solution.branch == ("elbow down",)
    assert solution.singular == "elbow stretched: elbow down and elbow up coincide"
    _, _, _, pose, folded = _solve("planar2r", q=np.array([0.7, np.pi]))
    assert np.linalg.norm(pose[:2, 3]) == pytest.approx(0.1, abs=1e-12)  # L1 - L2: folded
    assert [s.singular for s in folded.solutions] == ["elbow folded: elbow down and elbow up coincide"]


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


def _program_values(program, compiled, pose):
    """One branch program run in order; None when one of its conditions is negative (no such branch here)."""
    pose = np.asarray(pose)
    values = dict(zip(POSE_SYMBOLS, [*pose[:3, :3].ravel(), *pose[:3, 3]], strict=True))
    for symbol, expr in program.assignments:
        arguments, function = compiled(expr)
        value = float(function(*(values[a] for a in arguments)))
        if symbol in program.conditions:
            if value < -1e-9:
                return None
            value = max(value, 0.0)
        values[symbol] = value
    return values


@pytest.mark.parametrize("name", ["planar2r", "planar3r", "scara", "articulated3r", "ur5"])
def test_branch_programs_agree_with_the_executor(name):
    """The symbolic programs code generation prints, against the numeric executor, branch by branch."""
    robot = load_robot(name)
    plan, fk = closed_form_plan(robot), _fk(robot)
    programs = branch_programs(plan)
    assert len(programs) == plan.max_solutions
    cache = {}

    def compiled(expr):  # the branches share most assignments: each distinct one is compiled once
        if expr not in cache:
            arguments = sorted(expr.free_symbols - set(robot.defaults), key=str)
            cache[expr] = (arguments, sp.lambdify(arguments, expr.subs(robot.defaults), "math"))
        return cache[expr]

    rng = np.random.default_rng(8)
    for _ in range(20):
        pose = np.asarray(fk(_sample(robot, rng)), dtype=float)
        numeric = {s.branch: s.q for s in solve_plan(plan, pose).solutions}
        for program in programs:
            values = _program_values(program, compiled, pose)
            if values is None:
                assert program.branch not in numeric
                continue
            change = np.array([values[v] for v in robot.joint_variables]) - numeric[program.branch]
            difference = np.where([j.is_revolute for j in robot.joints], np.angle(np.exp(1j * change)), change)
            assert np.abs(difference).max() < 1e-8, program.branch


def test_palletizer_keeps_the_coupling_and_reaches_the_flange_pose():
    """Coupled theta4 = -theta2 - theta3: every solution keeps it, reaches the pose, and matches the numeric count."""
    robot = load_robot("palletizer")
    plan = closed_form_plan(robot)
    assert plan.family == "palletizer" and "keeps link 4 level" in plan.reasons[1]
    assert all(b(arm_geometry(robot)) is None for b in set(BUILDERS.values()))
    uncoupled = robot.uncoupled
    fk = _fk(uncoupled)
    rng = np.random.default_rng(21)
    for trial in range(200):
        c = rng.uniform(-np.pi, np.pi, 4)
        q = np.array([c[0], c[1], c[2], -c[1] - c[2], c[3]])
        pose = np.asarray(fk(q), dtype=float)
        result = solve_plan(plan, pose)
        for s in result.solutions:
            assert np.abs(np.asarray(fk(s.q), dtype=float) - pose).max() < 1e-10
            assert abs(np.angle(np.exp(1j * (s.q[3] + s.q[1] + s.q[2])))) < 1e-12
        assert min(np.abs(np.angle(np.exp(1j * (s.q - q)))).max() for s in result.solutions) < 1e-7
        if trial < 5:  # SciPy's least squares from 60 starts, on the coordinates theta1, theta2, theta3, theta5
            def residual(c, pose=pose):
                return (np.asarray(fk([c[0], c[1], c[2], -c[1] - c[2], c[3]]), dtype=float) - pose)[:3].ravel()

            starts = np.random.default_rng(trial).uniform(-np.pi, np.pi, (60, 4))
            fits = [least_squares(residual, start, xtol=1e-15, ftol=1e-15, gtol=1e-15) for start in starts]
            numeric = [f.x for f in fits if np.abs(f.fun).max() < 1e-10]
            coordinates = [s.q[[0, 1, 2, 4]] for s in result.solutions]
            assert len(_distinct(coordinates)) == len(_distinct(numeric, 1e-5))


POLAR = """
name = "polar"
description = "Spherical arm: the Stanford arm's first three joints, the tool point at the end of the slide"
convention = "modified"

[parameters]
d2 = 0.154

[[joints]]
type = "revolute"
alpha = 0
a = 0
d = 0
theta = 0

[[joints]]
type = "revolute"
alpha = "-pi/2"
a = 0
d = "d2"
theta = 0

[[joints]]
type = "prismatic"
alpha = "pi/2"
a = 0
d = 0
theta = 0
limits = [0.3, 1.3]
"""


def test_spherical_arm_round_trips_and_count(tmp_path):
    """The Stanford arm's first three joints: four solutions (two slides, two shoulders), two within the limits."""
    (tmp_path / "polar.toml").write_text(POLAR)
    robot = load_robot(tmp_path / "polar.toml")
    plan = closed_form_plan(robot)
    assert plan.family == "spherical arm" and plan.max_solutions == 4
    assert spherical_arm_plan(arm_geometry(load_robot("stanford"))) is None
    fk, model = _fk(robot), numeric_model(robot)
    rng = np.random.default_rng(5)
    for trial in range(300):
        q = _sample(robot, rng)
        pose = np.asarray(fk(q), dtype=float)
        result = solve_plan(plan, pose)
        for s in result.solutions:
            assert np.abs(np.asarray(fk(s.q), dtype=float)[:3, 3] - pose[:3, 3]).max() < 1e-10
        inside = [s.q for s in result.solutions if s.within_limits]
        assert len(inside) == 2
        assert min(np.abs(np.angle(np.exp(1j * (x - q)))).max() for x in inside) < 1e-7
        if trial < 5:
            numeric = solve_numeric(robot, pose, model, rng=5, restarts=60, orientation_weight=0.0)
            assert len(_distinct(inside)) == len(_distinct([s.q for s in numeric], 1e-5))


def test_cylindrical_arm_round_trips(tmp_path):
    """Two solutions (the waist and its half turn with the radial slide negated), one within the limits."""
    (tmp_path / "cylindrical.toml").write_text(CYLINDRICAL)
    robot = load_robot(tmp_path / "cylindrical.toml")
    plan = closed_form_plan(robot)
    assert plan.family == "cylindrical" and plan.max_solutions == 2
    fk, model = _fk(robot), numeric_model(robot)
    rng = np.random.default_rng(6)
    for trial in range(300):
        q = _sample(robot, rng)
        pose = np.asarray(fk(q), dtype=float)
        result = solve_plan(plan, pose)
        assert len(result.solutions) == 2
        for s in result.solutions:
            assert np.abs(np.asarray(fk(s.q), dtype=float)[:3, 3] - pose[:3, 3]).max() < 1e-10
        inside = [s.q for s in result.solutions if s.within_limits]
        assert len(inside) == 1 and np.abs(np.angle(np.exp(1j * (inside[0] - q)))).max() < 1e-9
        if trial < 5:
            numeric = solve_numeric(robot, pose, model, rng=5, restarts=60, orientation_weight=0.0)
            assert len(_distinct([s.q for s in numeric], 1e-5)) == 1
