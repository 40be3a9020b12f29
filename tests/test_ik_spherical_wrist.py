"""The spherical-wrist family on the PUMA 560, the Stanford arm, the IRB 140-like arm and the iiwa with joint 3 given:
round trips on random configurations within limits, every solution checked by forward kinematics, counted against
EAIK (an independent subproblem solver) or, for the prismatic Stanford arm, a numeric solver with many restarts."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from eaik.IK_Homogeneous import HomogeneousRobot

from symjac import load_robot, robot_from_toml
from symjac.analysis.inverse_kinematics import closed_form_plan, seed_bounds, solve_numeric, solve_plan
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import NoClosedFormError
from symjac.kinematics.convert import axes_at_home

POSES = 10_000  # about 5 s per arm on the 2-core machine, EAIK's count and FK checks included


def eaik_robot(robot, fixed=None):
    """EAIK's model of ``robot`` from its joint frames at home (same joint variables, same frame {0})."""
    frames, home = axes_at_home(robot)
    transforms = np.array([np.array(F.subs(robot.defaults), dtype=float) for F in (*frames, home)])
    return HomogeneousRobot(transforms, fixed_axes=fixed)


def differences(a, b, revolute):
    """Largest joint difference between each row of ``a`` and each row of ``b`` (revolute ones modulo 2 pi)."""
    difference = np.asarray(a)[:, None, :] - np.asarray(b)[None, :, :]
    difference = np.where(revolute, np.abs(np.remainder(difference + np.pi, 2 * np.pi) - np.pi), np.abs(difference))
    return difference.max(axis=2)


def distinct(solutions, revolute, tolerance=1e-6):
    """The solutions with near-duplicates (closer than ``tolerance``) left out."""
    if not len(solutions):
        return []
    close = differences(solutions, solutions, revolute) < tolerance
    return [s for i, s in enumerate(solutions) if not close[i, :i].any()]


def same(a, b, revolute, tolerance=1e-7):
    return bool(differences([a], [b], revolute)[0, 0] < tolerance)


NEAR_SINGULAR = 1e-5
"""Configurations whose Jacobian's smallest singular value is below this are near a singular one. There the
single angles are ill-conditioned (near theta5 = 0 only theta4 + theta6 is): every solution must still reproduce the
pose and the generating configuration must be among them within a tolerance that grows like 1 / (smallest singular
value); EAIK's count is not compared there (it merges nearby solutions by its own rule)."""


def round_trip(plan, configurations, model, revolute, eaik=None):
    """Failures of the round trip: FK of every solution, the generating configuration found, the count vs EAIK."""
    failures = []
    poses = model.fk(configurations)
    smallest = np.linalg.svd(model.jacobian(configurations), compute_uv=False)[:, -1]
    assert (smallest < NEAR_SINGULAR).mean() < 0.01  # a few at most: the checks below are not skipped wholesale
    for q, pose, sigma in zip(configurations, poses, smallest, strict=True):
        near = sigma < NEAR_SINGULAR
        result = solve_plan(plan, pose)
        solutions = np.array([s.q for s in result.solutions])
        if not len(solutions):
            failures.append(f"{q}: no solution ({result.unreachable})")
            continue
        error = np.abs(model.fk(solutions) - pose).max()
        if error > 1e-10:
            failures.append(f"{q}: a solution misses the pose by {error:.3g}")
        if not (differences(solutions, [q], revolute) < max(1e-7, 1e-12 / sigma)).any():
            failures.append(f"{q}: the generating configuration is not among the solutions")
        if eaik is not None and not near:
            found = eaik.IK(pose)
            exact = [s for s, ls in zip(found.Q, found.is_LS, strict=True) if not ls]
            theirs, ours = len(distinct(exact, revolute)), len(distinct(solutions, revolute))
            if theirs != ours:
                failures.append(f"{q}: {ours} solutions, EAIK finds {theirs}")
    return failures


ARMS = ["puma560", "irb140", "stanford"]


def _setup(name):
    robot = load_robot(name)
    revolute = np.array([joint.is_revolute for joint in robot.joints])
    eaik = eaik_robot(robot) if revolute.all() else None  # EAIK has no prismatic joints
    return robot, closed_form_plan(robot), numeric_model(robot, backend="numpy"), revolute, eaik


@pytest.mark.parametrize("name", ARMS)
def test_round_trip_on_ten_thousand_random_configurations_within_limits(name):
    robot, plan, model, revolute, eaik = _setup(name)
    lower, upper = seed_bounds(robot)
    configurations = np.random.default_rng(46).uniform(lower, upper, (POSES, robot.n_joints))
    assert round_trip(plan, configurations, model, revolute, eaik) == []


def test_a_planted_sign_error_fails_the_round_trip():
    robot, plan, model, revolute, eaik = _setup("puma560")
    step = plan.steps[0]
    planted = dataclasses.replace(step, arguments={**step.arguments, "d": -step.arguments["d"]})
    broken = dataclasses.replace(plan, steps=(planted, *plan.steps[1:]))
    configurations = np.random.default_rng(1).uniform(*seed_bounds(robot), (20, 6))
    assert len(round_trip(broken, configurations, model, revolute, eaik)) >= 20
    assert round_trip(plan, configurations, model, revolute, eaik) == []


def test_the_stanford_count_matches_a_numeric_solver_with_many_restarts():
    robot, plan, model, revolute, _ = _setup("stanford")
    generator = np.random.default_rng(7)
    for _ in range(3):
        q = generator.uniform(*seed_bounds(robot))
        pose = model.fk(q)
        ours = [s.q for s in solve_plan(plan, pose).solutions]
        numeric = [s.q for s in solve_numeric(robot, pose, model, rng=3, restarts=120, respect_limits=False)]
        assert len(distinct(ours, revolute)) == 8
        assert all(any(same(n, o, revolute, 1e-6) for o in ours) for n in numeric)
        assert len(distinct(numeric, revolute)) == 8


def test_plans_say_why_they_apply():
    puma = closed_form_plan(load_robot("puma560"))
    assert puma.family == "spherical wrist" and puma.max_solutions == 8
    assert puma.reasons[0].startswith("the axes of joints 4, 5 and 6 meet at the wrist centre")
    assert "the axes of joints 2 and 3 are parallel" in puma.reasons
    assert [s.subproblem for s in puma.steps] == ["rotation_to_plane", "rotation_to_distance", "rotation_to_point",
                                                   "two_rotations_to_point", "rotation_to_point"]
    stanford = closed_form_plan(load_robot("stanford"))
    assert "joint 3 is prismatic" in stanford.reasons and stanford.steps[0].subproblem == "slide_to_distance"


@pytest.mark.parametrize("name", ARMS)
def test_branch_names_follow_their_rules(name):
    robot, plan, model, _, _ = _setup(name)
    generator = np.random.default_rng(5)
    for _ in range(50):
        result = solve_plan(plan, model.fk(generator.uniform(*seed_bounds(robot))))
        assert len({s.branch for s in result.solutions}) == len(result.solutions) >= 4  # the IRB's offset: 4 or 8
        for solution in result.solutions:
            assert ("no flip" in solution.branch) == (solution.q[4] >= 0)


@pytest.mark.parametrize("given", [1, 2, 3])
def test_the_iiwa_with_one_joint_given_round_trips_and_matches_eaik(given):
    robot = load_robot("iiwa7")
    plan = closed_form_plan(robot, free_joint=given)
    assert plan.free_joint == given and f"joint {given} is given" in " ".join(plan.reasons)
    model = numeric_model(robot, backend="numpy")
    revolute = np.ones(7, dtype=bool)
    generator = np.random.default_rng(11)
    for _ in range(12):
        q = generator.uniform(*seed_bounds(robot))
        pose = model.fk(q)
        solutions = np.array([s.q for s in solve_plan(plan, pose, free_value=q[given - 1]).solutions])
        assert np.abs(model.fk(solutions) - pose).max() < 1e-10
        assert np.allclose(solutions[:, given - 1], q[given - 1])
        assert any(same(s, q, revolute) for s in solutions)
        found = eaik_robot(robot, fixed=[(given - 1, q[given - 1])]).IK(pose)
        exact = [s for s, ls in zip(found.Q, found.is_LS, strict=True) if not ls]
        assert len(distinct(exact, np.ones(len(exact[0]), dtype=bool))) == len(distinct(solutions, revolute))


def test_the_stanford_slide_is_named_by_its_sign():
    """"slide out" is the wrist centre beyond the slide line's closest point to the shoulder, at d3 = 0 on this arm."""
    robot, plan, model, _, _ = _setup("stanford")
    generator = np.random.default_rng(3)
    for _ in range(20):
        q = generator.uniform(*seed_bounds(robot))
        level = q.copy()
        level[2] = 0.0
        # the flange is the wrist centre, the shoulder the origin: |w|^2 = |w(d3 = 0)|^2 + d3^2 (closest at d3 = 0)
        assert np.linalg.norm(model.fk(q)[:3, 3]) ** 2 == pytest.approx(
            np.linalg.norm(model.fk(level)[:3, 3]) ** 2 + q[2] ** 2, rel=1e-12)
        result = solve_plan(plan, model.fk(q))
        assert len(result.solutions) == 8
        for solution in result.solutions:
            assert ("slide out" in solution.branch) == (solution.q[2] > 0)
            assert ("slide reversed" in solution.branch) == (solution.q[2] < 0)
        slides = sorted(abs(s.q[2]) for s in result.solutions)
        assert slides[0] == pytest.approx(slides[-1], rel=1e-9)  # the same length either way: no "shorter" slide


def test_the_iiwa_with_its_elbow_given_has_no_closed_form():
    with pytest.raises(NoClosedFormError, match=r"7 joints, one more than a pose fixes \(give one joint's value as "
                                                r"the redundancy parameter to solve the six that remain\)") as raised:
        closed_form_plan(load_robot("iiwa7"))
    message = str(raised.value)  # geometry and neutral advice: no function, keyword or option of any front end
    assert "tried: spherical wrist, three parallel axes" in message
    assert not any(word in message for word in ("_plan", "free_joint", "=", "within_limits", "--"))
    with pytest.raises(NoClosedFormError, match="joints 1, 2 and 3 meet in one point as well, so they cannot change"):
        closed_form_plan(load_robot("iiwa7"), free_joint=4)


def test_the_panda_has_no_closed_form_with_any_joint_given():
    for joint in range(1, 8):
        with pytest.raises(NoClosedFormError, match=rf"panda with joint {joint} given: no closed-form family"):
            closed_form_plan(load_robot("panda"), free_joint=joint)
    with pytest.raises(NoClosedFormError, match=r"the axes of joints 5 and 7 are parallel, 0\.088 apart"):
        closed_form_plan(load_robot("panda"), free_joint=3)
    with pytest.raises(NoClosedFormError) as raised:  # "as well" only after a wrist whose axes meet
        closed_form_plan(load_robot("panda"))
    assert "the axes of joints 1, 2 and 3 meet in one point;" in str(raised.value)
    assert "as well" not in str(raised.value)


def _six_r(name, rows):
    """A 6R arm in standard DH from rows (d, a, alpha), no limits."""
    joints = "".join(f'[[joints]]\ntype = "revolute"\nd = {d}\na = {a}\nalpha = "{alpha}"\n\n' for d, a, alpha in rows)
    return robot_from_toml(f'name = "{name}"\nconvention = "standard"\n\n{joints}')


OTHER_ARMS = {  # the spherical-wrist arms the catalog lacks: shoulder and elbow offsets, other signs of the twists
    "kr_like": [(0.4, 0.025, "-pi/2"), (0, 0.455, "0"), (0, 0.035, "-pi/2"), (0.42, 0, "pi/2"), (0, 0, "-pi/2"),
                (0.08, 0, "0")],
    "fanuc_like": [(0.33, 0.05, "pi/2"), (0, 0.33, "0"), (0, 0.035, "pi/2"), (-0.335, 0, "-pi/2"), (0, 0, "pi/2"),
                   (-0.08, 0, "0")],
}


@pytest.mark.parametrize("name", sorted(OTHER_ARMS))
def test_other_spherical_wrist_arms_round_trip_and_match_eaik(name):
    robot = _six_r(name, OTHER_ARMS[name])
    plan = closed_form_plan(robot)
    assert plan.family == "spherical wrist" and "the axes of joints 2 and 3 are parallel" in plan.reasons
    configurations = np.random.default_rng(9).uniform(-np.pi, np.pi, (300, 6))
    model = numeric_model(robot, backend="numpy")
    assert round_trip(plan, configurations, model, np.ones(6, dtype=bool), eaik_robot(robot)) == []


def _axes_from_the_jacobian(model, n):
    """Joint axes and points on them at q = 0 from the numeric Jacobian at the tool point: independent of the arm
    geometry the family is decided on. A column is (v, h) with v = h x (tool - p), so h x v = -(tool - p) across h and
    tool + h x v lies on the axis."""
    jacobian = model.jacobian(np.zeros(n))
    tool = model.fk(np.zeros(n))[:3, 3]
    axes = jacobian[3:].T
    return axes, [tool + np.cross(h, v) for v, h in zip(jacobian[:3].T, axes, strict=True)]


def _solvable(axes, points):
    """The family's conditions for a 6R arm, numerically: axis 6 through the point where axes 4 and 5 meet (the wrist
    centre), which is off axis 3, and axes 2 and 3 parallel and apart (axis 1 not parallel to them), or axes 1
    and 2 meeting off axis 3."""
    def on_line(x, h, p):
        return np.linalg.norm(np.cross(x - p, h)) < 1e-9

    h4, h5, p4, p5 = axes[3], axes[4], points[3], points[4]
    normal = np.cross(h4, h5)  # the wrist centre: where axes 4 and 5 meet
    centre = p4 + h4 * (np.cross(p5 - p4, h5) @ normal) / (normal @ normal)
    if not on_line(centre, axes[5], points[5]) or on_line(centre, axes[2], points[2]):
        return False
    parallel_23 = np.linalg.norm(np.cross(axes[1], axes[2])) < 1e-9
    if parallel_23 and not on_line(points[1], axes[2], points[2]) and np.linalg.norm(np.cross(axes[0], axes[1])) > 1e-9:
        return True
    normal = np.cross(axes[0], axes[1])
    if np.linalg.norm(normal) < 1e-9 or abs((points[1] - points[0]) @ normal) > 1e-9:
        return False
    meet = points[0] + axes[0] * (np.cross(points[1] - points[0], axes[1]) @ normal) / (normal @ normal)
    return not on_line(meet, axes[2], points[2])


def test_random_arms_with_a_spherical_wrist_are_decided_exactly():
    generator = np.random.default_rng(21)
    decided = {True: 0, False: 0}
    for index in range(12):
        length = lambda: 0 if generator.random() < 0.4 else round(float(generator.uniform(0.05, 0.5)), 3)  # noqa: E731
        twist = lambda *choices: choices[generator.integers(len(choices))]  # noqa: E731
        rows = [(length(), length(), twist("pi/2", "-pi/2")), (length(), length(), twist("0", "pi/2", "-pi/2")),
                (length(), length(), twist("pi/2", "-pi/2")), (round(float(generator.uniform(0.2, 0.5)), 3), 0,
                                                               twist("pi/2", "-pi/2")),
                (0, 0, twist("pi/2", "-pi/2")), (round(float(generator.uniform(0.05, 0.2)), 3), 0, "0")]
        robot = _six_r(f"random{index}", rows)
        model = numeric_model(robot, backend="numpy")
        solvable = _solvable(*_axes_from_the_jacobian(model, 6))
        try:
            plan = closed_form_plan(robot)
        except NoClosedFormError as error:
            decided[False] += 1
            assert not solvable, f"{rows}: {error}"
            continue
        decided[True] += 1
        assert solvable, rows
        configurations = generator.uniform(-np.pi, np.pi, (100, 6))
        assert round_trip(plan, configurations, model, np.ones(6, dtype=bool), eaik_robot(robot)) == [], rows
    assert decided[True] >= 3 and decided[False] >= 3, decided  # both outcomes were met
