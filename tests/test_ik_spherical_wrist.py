"""The spherical-wrist family on the PUMA 560, the Stanford arm, the IRB 140-like arm and the iiwa with joint 3 given:
round trips on random configurations within limits, every solution checked by forward kinematics, counted against
EAIK (an independent subproblem solver) or, for the prismatic Stanford arm, a numeric solver with many restarts."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from eaik.IK_Homogeneous import HomogeneousRobot

from symjac import load_robot
from symjac.analysis.inverse_kinematics import closed_form_plan, seed_bounds, solve_numeric, solve_plan
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import NoClosedFormError
from symjac.kinematics.convert import axes_at_home

FAST_POSES = 1000
SLOW_POSES = 10_000


def eaik_robot(robot, fixed=None):
    """EAIK's model of ``robot`` from its joint frames at home (same joint variables, same frame {0})."""
    frames, home = axes_at_home(robot)
    transforms = np.array([np.array(F.subs(robot.defaults), dtype=float) for F in (*frames, home)])
    return HomogeneousRobot(transforms, fixed_axes=fixed)


def distinct(solutions, revolute, tolerance=1e-6):
    kept = []
    for q in solutions:
        if not any(same(q, other, revolute, tolerance) for other in kept):
            kept.append(q)
    return kept


def same(a, b, revolute, tolerance=1e-7):
    difference = np.asarray(a) - np.asarray(b)
    difference = np.where(revolute, np.angle(np.exp(1j * difference)), difference)
    return bool(np.abs(difference).max() < tolerance)


def round_trip(plan, configurations, model, revolute, eaik=None):
    """Failures of the round trip: FK of every solution, the generating configuration found, the count vs EAIK."""
    failures = []
    poses = model.fk(configurations)
    for q, pose in zip(configurations, poses, strict=True):
        result = solve_plan(plan, pose)
        solutions = np.array([s.q for s in result.solutions])
        if not len(solutions):
            failures.append(f"{q}: no solution ({result.unreachable})")
            continue
        error = np.abs(model.fk(solutions) - pose).max()
        if error > 1e-10:
            failures.append(f"{q}: a solution misses the pose by {error:.3g}")
        if not any(same(s, q, revolute) for s in solutions):
            failures.append(f"{q}: the generating configuration is not among the solutions")
        if eaik is not None:
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
def test_round_trip_on_random_configurations_within_limits(name):
    robot, plan, model, revolute, eaik = _setup(name)
    lower, upper = seed_bounds(robot)
    configurations = np.random.default_rng(46).uniform(lower, upper, (FAST_POSES, robot.n_joints))
    assert round_trip(plan, configurations, model, revolute, eaik) == []


@pytest.mark.slow
@pytest.mark.parametrize("name", ARMS)
def test_round_trip_on_ten_thousand_poses(name):
    robot, plan, model, revolute, eaik = _setup(name)
    lower, upper = seed_bounds(robot)
    configurations = np.random.default_rng(4646).uniform(lower, upper, (SLOW_POSES, robot.n_joints))
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


def test_branch_names_follow_their_rules_on_the_puma():
    robot, plan, model, _, _ = _setup("puma560")
    generator = np.random.default_rng(5)
    for _ in range(50):
        result = solve_plan(plan, model.fk(generator.uniform(*seed_bounds(robot))))
        assert len({s.branch for s in result.solutions}) == len(result.solutions) == 8
        for solution in result.solutions:
            assert ("no flip" in solution.branch) == (solution.q[4] >= 0)


def test_the_iiwa_with_joint_3_given_round_trips_and_matches_eaik():
    robot = load_robot("iiwa7")
    plan = closed_form_plan(robot, free_joint=2)
    assert plan.free_joint == 2 and "joint 3 is given" in " ".join(plan.reasons)
    model = numeric_model(robot, backend="numpy")
    revolute = np.ones(7, dtype=bool)
    generator = np.random.default_rng(11)
    for _ in range(30):
        q = generator.uniform(*seed_bounds(robot))
        pose = model.fk(q)
        solutions = np.array([s.q for s in solve_plan(plan, pose, free_value=q[2]).solutions])
        assert np.abs(model.fk(solutions) - pose).max() < 1e-10
        assert np.allclose(solutions[:, 2], q[2])
        assert any(same(s, q, revolute) for s in solutions)
        found = eaik_robot(robot, fixed=[(2, q[2])]).IK(pose)
        exact = [s for s, ls in zip(found.Q, found.is_LS, strict=True) if not ls]
        assert len(distinct(exact, np.ones(len(exact[0]), dtype=bool))) == len(distinct(solutions, revolute))


def test_the_panda_has_no_closed_form_with_any_joint_given():
    for joint in range(7):
        with pytest.raises(NoClosedFormError, match=rf"panda with joint {joint + 1} given: no closed-form family"):
            closed_form_plan(load_robot("panda"), free_joint=joint)
    with pytest.raises(NoClosedFormError, match=r"the axes of joints 5 and 7 are parallel, 0\.088 apart"):
        closed_form_plan(load_robot("panda"), free_joint=2)
