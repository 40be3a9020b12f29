"""The numeric inverse-kinematics solver: round trips on catalog arms, checked by an independent forward kinematics."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics import NumericSolution, seed_bounds, solve_numeric
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import ArgumentError
from symjac.kinematics.chain import forward_kinematics

ARMS = ["puma560", "ur5", "panda", "iiwa7", "stanford"]
POSES = 50


def _independent_fk(robot):
    """The symbolic tool pose, parameters at their defaults, lambdified (no generated code involved)."""
    pose = forward_kinematics(robot).subs(robot.defaults)
    return sp.lambdify([list(robot.joint_variables)], pose, "numpy")


@pytest.mark.parametrize("name", ARMS)
def test_round_trip_reproduces_the_pose(name):
    robot = load_robot(name)
    model, fk = numeric_model(robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(46)
    solved = 0
    for _ in range(POSES):
        q = generator.uniform(lower, upper)
        pose = np.asarray(fk(q), dtype=float)
        solutions = solve_numeric(robot, pose, model, rng=1)
        for solution in solutions:
            assert isinstance(solution, NumericSolution)
            assert np.abs(np.asarray(fk(solution.q), dtype=float) - pose).max() < 1e-9
            assert np.all(solution.q >= lower - 1e-12) and np.all(solution.q <= upper + 1e-12)
        for a in range(len(solutions)):  # distinct
            for b in range(a):
                assert np.abs(solutions[a].q - solutions[b].q).max() > 1e-6
        solved += bool(solutions)
    print(f"{name}: {solved}/{POSES} poses solved")
    assert solved >= 0.98 * POSES


def test_unreachable_pose_gives_no_solution():
    robot = load_robot("puma560")
    pose = np.eye(4)
    pose[:3, 3] = [5.0, 0.0, 0.0]  # far beyond the PUMA's reach of about 0.9 m
    assert solve_numeric(robot, pose, numeric_model(robot), restarts=2, until_found=4) == []


def test_deterministic_for_a_fixed_rng():
    robot = load_robot("panda")
    model = numeric_model(robot)
    pose = np.asarray(model.fk([0.3, -0.4, 0.2, -2.0, 0.1, 1.6, 0.5]), dtype=float)
    first = solve_numeric(robot, pose, model, rng=7)
    second = solve_numeric(robot, pose, model, rng=7)
    assert first and len(first) == len(second)
    assert all(np.array_equal(a.q, b.q) for a, b in zip(first, second, strict=True))


def test_seed_at_a_solution_converges_at_once():
    robot = load_robot("ur5")
    model = numeric_model(robot)
    q = np.array([0.4, -1.1, 1.3, -0.7, 1.2, 0.3])
    solutions = solve_numeric(robot, np.asarray(model.fk(q), dtype=float), model, seed=q, restarts=0)
    assert len(solutions) == 1 and np.abs(solutions[0].q - q).max() < 1e-9 and solutions[0].iterations <= 1


@pytest.mark.parametrize(("pose", "match"), [
    (np.eye(3), "4 x 4"),
    (np.full((4, 4), np.nan), "NaN"),
    (np.diag([2.0, 1.0, 1.0, 1.0]), "rigid transform"),
    (np.diag([1.0, 1.0, -1.0, 1.0]), "rigid transform"),
    ([["a"] * 4] * 4, "numeric"),
])
def test_bad_pose_is_one_clear_error(pose, match):
    robot = load_robot("planar2r")
    with pytest.raises(ArgumentError, match=match):
        solve_numeric(robot, pose, numeric_model(robot, backend="numpy"))


@pytest.mark.parametrize("task", ["limits", "manipulability"])
def test_null_space_task_keeps_the_pose_and_improves_its_objective(task):
    from symjac.analysis.inverse_kinematics.null_space import limit_distance, manipulability

    robot = load_robot("panda")
    model, fk = numeric_model(robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(5)
    gained = 0.0
    for k in range(4):
        pose = np.asarray(fk(generator.uniform(lower, upper)), dtype=float)
        plain = solve_numeric(robot, pose, model, rng=k, restarts=1)[0]
        moved = solve_numeric(robot, pose, model, rng=k, restarts=1, null_space=task)[0]
        assert np.abs(np.asarray(fk(moved.q), dtype=float) - pose).max() < 1e-9
        assert np.all(moved.q >= lower) and np.all(moved.q <= upper)
        if task == "limits":
            before, after = limit_distance(plain.q, lower, upper), limit_distance(moved.q, lower, upper)
        else:
            before, after = manipulability(model.jacobian(plain.q)), manipulability(model.jacobian(moved.q))
        assert after >= before - 1e-12
        gained += after - before
    assert gained > 1e-3  # it moves, not only stays put


def test_unknown_null_space_task_is_one_clear_error():
    robot = load_robot("planar2r")
    with pytest.raises(ArgumentError, match="null_space must be one of limits, manipulability"):
        solve_numeric(robot, np.eye(4), numeric_model(robot, backend="numpy"), null_space="distance")


@pytest.mark.parametrize("name", ["panda", "iiwa7", "puma560", "ur5"])
def test_one_seed_per_call_solves_a_fixed_set_within_the_limits(name):
    robot = load_robot(name)
    model, fk = numeric_model(robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(2046)
    for k in range(30):
        pose = np.asarray(fk(generator.uniform(lower, upper)), dtype=float)
        solutions = solve_numeric(robot, pose, model, rng=k, restarts=1)
        assert len(solutions) == 1, k  # the first solution found, restarting from further seeds of rng=k
        q = solutions[0].q
        assert np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9
        assert np.all(q >= lower) and np.all(q <= upper)
