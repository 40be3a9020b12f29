"""What the numeric solver's list of solutions means: no 2 pi aliases of one configuration (prismatic values never
taken modulo anything), and samples of a continuum (a redundant arm's self-motion, a wrist singularity) said to be
samples, checked against the closed form, a finite-difference Jacobian of an independent forward kinematics and an
explicit self-motion."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics import seed_bounds, solve_numeric
from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan, solve_plan
from symjac.codegen.numeric_model import numeric_model
from symjac.kinematics.chain import forward_kinematics
from symjac.model.io import robot_from_toml
from symjac.solvers.inverse_kinematics import inverse_kinematics


def _independent_fk(robot):
    pose = forward_kinematics(robot).subs(robot.defaults)
    return sp.lambdify([list(robot.joint_variables)], pose, "numpy")


def _rank(fk, q, rows=slice(0, 6)) -> int:
    """The rank of the pose's derivative by central differences of ``fk`` (position, then rotation as w^)."""
    columns = []
    for k in range(len(q)):
        h = np.zeros(len(q))
        h[k] = 1e-6
        plus, minus = np.asarray(fk(q + h), dtype=float), np.asarray(fk(q - h), dtype=float)
        d = (plus - minus) / 2e-6
        w = d[:3, :3] @ np.asarray(fk(q), dtype=float)[:3, :3].T
        columns.append(np.concatenate([d[:3, 3], [w[2, 1], w[0, 2], w[1, 0]]])[rows])
    return int(np.linalg.matrix_rank(np.array(columns).T, tol=1e-5))


def _wrapped(d):
    return np.pi - np.mod(np.pi - d, 2 * np.pi)


@pytest.mark.parametrize(("name", "q0"), [
    ("puma560", [0.3, -0.5, 0.4, -1.0, 0.6, np.pi]),  # joint 6 spans +-266 degrees: pi and -pi both inside
    ("irb140", [0.3, -0.5, 0.4, np.pi, 0.6, 0.2]),     # joint 4 spans +-200 degrees
    ("irb140", [0.3, -0.5, 0.4, -1.0, 0.6, np.pi]),    # joint 6 spans +-360 degrees
])
def test_no_two_solutions_are_2pi_aliases_and_each_is_a_closed_form_one(name, q0):
    robot = load_robot(name)
    model = numeric_model(robot)
    pose = np.asarray(model.fk(np.array(q0)), dtype=float)
    closed = [s.q for s in solve_plan(closed_form_plan(robot), pose).solutions if s.within_limits]
    lower, upper = seed_bounds(robot)
    found = solve_numeric(robot, pose, model, restarts=40, rng=3)
    assert found and found.continuum_dimension == 0
    matched = []
    for solution in found:
        assert np.all(solution.q >= lower - 1e-12) and np.all(solution.q <= upper + 1e-12)
        assert np.all((solution.q > -np.pi) & (solution.q <= np.pi) | (np.abs(solution.q) > np.pi)
                      & ((solution.q - 2 * np.pi < lower) | (solution.q + 2 * np.pi > upper)))  # shifted only to fit
        distances = [np.abs(_wrapped(solution.q - q)).max() for q in closed]
        matched.append(int(np.argmin(distances)))
        assert min(distances) < 1e-6
    assert len(set(matched)) == len(matched)  # one numeric solution per closed-form solution, no aliases
    assert len(matched) >= len(closed) - 1  # and (nearly) all of them found


PERIODIC = """
name = "slide"
convention = "standard"
[[joints]]
type = "{kind}"
alpha = 0
a = 0
d = 0
limits = [-{limit}, {limit}]
"""


class _Periodic:
    """A one-joint model whose pose repeats every 2 pi of its joint: a turn about z and a point on a circle."""

    def fk(self, q):
        c, s = np.cos(q[0]), np.sin(q[0])
        return np.array([[c, -s, 0.0, c], [s, c, 0.0, s], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])

    def jacobian(self, q):
        return np.array([[-np.sin(q[0])], [np.cos(q[0])], [0.0], [0.0], [0.0], [1.0]])


@pytest.mark.parametrize("kind", ["prismatic", "revolute"])
def test_revolute_angles_merge_modulo_2pi_and_prismatic_values_never(kind):
    robot = robot_from_toml(PERIODIC.format(kind=kind, limit=10 if kind == "prismatic" else 6.2), "slide")
    found = solve_numeric(robot, _Periodic().fk([0.5]), _Periodic(), restarts=30, rng=1)
    values = sorted(float(s.q[0]) for s in found)
    if kind == "revolute":
        assert values == pytest.approx([0.5], abs=1e-9)
    else:  # 0.5 + 2 pi k for every k in the limits [-10, 10]: k = -1, 0, 1 (and no more)
        assert values == pytest.approx([0.5 - 2 * np.pi, 0.5, 0.5 + 2 * np.pi], abs=1e-9)


@pytest.mark.parametrize("name", ["panda", "iiwa7"])
def test_a_redundant_arm_gives_samples_of_a_one_dimensional_self_motion(name):
    robot = load_robot(name)
    fk = _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    q0 = np.random.default_rng(46).uniform(lower, upper)
    result = inverse_kinematics(robot, np.asarray(fk(q0), dtype=float), method="numeric", restarts=12)
    assert len(result.solutions) >= 2 and result.continuum_dimension == 1
    for solution in result.solutions:
        assert solution.continuum_dimension == 1 == 7 - _rank(fk, solution.q)
        assert "one sample of a 1-dimensional set" in solution.singular and "rank 6 for 7 joints" in solution.singular


def test_a_wrist_singularity_gives_samples_there_and_isolated_solutions_elsewhere():
    robot = load_robot("puma560")
    fk = _independent_fk(robot)
    q0 = np.array([0.3, -0.5, 0.4, -1.0, 0.0, 0.2])  # q5 = 0: only theta4 + theta6 is decided
    pose = np.asarray(fk(q0), dtype=float)
    result = inverse_kinematics(robot, pose, method="numeric", restarts=30, rng=2)
    assert result.continuum_dimension == 1
    dimensions = {solution.continuum_dimension for solution in result.solutions}
    assert dimensions == {0, 1}  # the other arm branches' wrists are not singular at this pose
    for solution in result.solutions:
        q = solution.q
        assert solution.continuum_dimension == (abs(q[4]) < 1e-6) == 6 - _rank(fk, q)
        if solution.continuum_dimension:  # an explicit self-motion: theta4 + t, theta6 - t keeps the pose
            moved = q + np.array([0, 0, 0, 0.7, 0, -0.7])
            assert np.abs(np.asarray(fk(moved), dtype=float) - pose).max() < 1e-8


def test_where_two_solutions_merge_at_the_edge_of_the_workspace_one_isolated_solution_is_reported():
    robot = load_robot("planar3r")
    fk = _independent_fk(robot)
    q0 = np.array([0.3, 0.0, 0.0])  # stretched: the Jacobian loses rank, yet no continuum opens
    found = solve_numeric(robot, np.asarray(fk(q0), dtype=float), numeric_model(robot), rng=0)
    assert _rank(fk, q0) == 2 and len(found) == 1 and found.continuum_dimension == 0
    assert np.abs(found[0].q - q0).max() < 1e-3


def test_the_command_calls_a_redundant_arms_solutions_samples(cli):
    q = "0.3,-0.4,0.2,-2.0,0.1,1.6,0.5"
    pretty = cli.ok("ik", "panda", "--q", q, "--method", "numeric", "--format", "pretty")
    assert "Inverse kinematics of panda: " in pretty and "samples of a 1-dimensional set of solutions" in pretty
    assert " solutions by the numeric solver" not in pretty and "one sample of a 1-dimensional set" in pretty
    data = cli.json("ik", "panda", "--q", q, "--method", "numeric")
    assert data["continuum_dimension"] == 1 and len(data["solutions"]) >= 1
    assert cli.json("ik", "puma560", "--q", "0.3,-0.5,0.4,-1,0.6,0.2", "--method", "numeric")[
        "continuum_dimension"] == 0


def test_without_the_limits_seeds_still_cover_each_joints_range():
    robot = load_robot("irb140")  # limited revolute joints drew their seeds from [-1, 1] when limits were ignored
    model = numeric_model(robot)
    pose = np.asarray(model.fk(np.array([0.3, -0.5, 0.4, -1.0, 0.6, 0.2])), dtype=float)
    closed = [s.q for s in solve_plan(closed_form_plan(robot), pose).solutions]
    result = inverse_kinematics(robot, pose, method="numeric", within_limits=False, restarts=40)
    matched = {int(np.argmin([np.abs(_wrapped(s.q - q)).max() for q in closed])) for s in result.solutions}
    assert len(result.solutions) == len(matched) == len(closed) == 8
