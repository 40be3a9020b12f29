"""Generated closed-form inverse kinematics of catalog arms in every target, against the Python executor.

The PUMA 560 (spherical wrist), the Stanford arm (a prismatic joint) and the UR5 (three parallel axes) where its
family is registered: at random poses from configurations within the limits, every target finds the same solutions
as :func:`~symjac.analysis.inverse_kinematics.closed_form.solve_plan` (up to 2 pi), each reproducing the pose to
1e-10, the configuration that made the pose among them.
"""

from __future__ import annotations

import numpy as np
import pytest
from ik_generated import ik_solvers

from symjac.analysis.inverse_kinematics import closed_form_plan, seed_bounds, solve_plan
from symjac.codegen.inverse_kinematics import inverse_kinematics_of
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import NoClosedFormError
from symjac.model.io import load_robot

TARGETS = ("python", "numpy", "c", "lambdify", "jax", "casadi", "c99", "cpp")
ARMS = {"puma560": TARGETS, "stanford": ("numpy", "c99", "cpp"), "ur5": TARGETS}


@pytest.fixture(scope="module", params=sorted(ARMS))
def arm(request, tmp_path_factory):
    """An arm, its plan, every target's generated solver and 60 poses of configurations within its limits."""
    robot = load_robot(request.param)
    try:
        plan = closed_form_plan(robot)
    except NoClosedFormError as error:  # pragma: no cover - until its family is registered
        pytest.skip(f"no closed form yet: {error}")
    solvers = ik_solvers(tmp_path_factory.mktemp(f"ik_{robot.name}"), robot, ARMS[robot.name])
    lower, upper = seed_bounds(robot)
    q = np.random.default_rng(46).uniform(lower, upper, (60, robot.n_joints))
    return robot, plan, solvers, q, numeric_model(robot, backend="numpy").fk(q)


def _distance(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Largest difference per pair of rows, angles compared modulo 2 pi."""
    difference = a[:, None, :] - b[None, :, :]
    turned = (difference + np.pi) % (2 * np.pi) - np.pi
    return np.abs(np.where(revolute, turned, difference)).max(axis=2)


def test_every_target_finds_the_executors_solutions(arm):
    robot, plan, solvers, q, poses = arm
    fk = numeric_model(robot, backend="numpy").fk
    revolute = np.array([kind.value == "revolute" for kind in robot.coordinate_types])
    expected = [np.array([s.q for s in solve_plan(plan, pose).solutions]) for pose in poses]
    for target, solve in solvers.items():
        for k, (found, reference) in enumerate(zip(solve(poses), expected, strict=True)):
            assert len(found) == len(reference), (target, k)
            assert np.all(_distance(found, reference, revolute).min(axis=1) < 1e-6), (target, k)
            assert np.abs(fk(found) - poses[k]).max() < 1e-10, (target, k)
            assert _distance(found, q[k:k + 1], revolute).min() < 1e-6, (target, k)
            angles = found[:, revolute]
            lower, upper = (np.array(v)[revolute] for v in seed_bounds(robot))
            inside = (angles >= lower - 1e-12) & (angles <= upper + 1e-12)
            assert np.all(inside | ((angles > -np.pi) & (angles <= np.pi))), (target, k)


def test_every_row_names_the_executors_branch_of_that_solution(arm):
    """Each written row's branch index (``IK_BRANCHES``, jax/casadi: the row's position) is the branch under which
    the executor finds that solution, at the 60 random poses and at 200 more for the UR5 and the PUMA, where some
    poses have fewer solutions than branches (a branch without a solution leaves no gap in the rows)."""
    robot, plan, solvers, _, poses = arm
    ik = inverse_kinematics_of(robot)
    revolute = np.array([kind.value == "revolute" for kind in robot.coordinate_types])
    if robot.name in ("puma560", "ur5"):
        lower, upper = seed_bounds(robot)
        more = np.random.default_rng(8).uniform(lower, upper, (200, robot.n_joints))
        poses = np.concatenate([poses, numeric_model(robot, backend="numpy").fk(more)])
    expected = [solve_plan(plan, pose).solutions for pose in poses]
    fewer = sum(len(solutions) < ik.max_solutions for solutions in expected)
    assert robot.name != "ur5" or fewer >= 10  # the point: rows whose branches are not the first ones
    for target, solve in solvers.items():
        for k, ((found, branches), reference) in enumerate(zip(solve.pairs(poses), expected, strict=True)):
            assert len(branches) == len(found) == len(reference), (target, k)
            for row, branch in zip(found, branches, strict=True):
                names = ik.branches[branch]
                (match,) = [s for s in reference if s.branch == names]
                assert _distance(row[None], match.q[None], revolute)[0, 0] < 1e-6, (target, k, names)


def _distinct(rows: np.ndarray, revolute: np.ndarray) -> list[np.ndarray]:
    found: list[np.ndarray] = []
    for row in rows:
        if not found or _distance(row[None], np.array(found), revolute).min() > 1e-9:
            found.append(row)
    return found


def test_at_singular_poses_every_target_gives_the_executors_representatives_exactly(arm):
    """At home (the wrist singularity of all three) and with the wrist straight: the same distinct solutions as the
    executor (the free joint at 0), each reproducing the pose to 1e-12; of branches that coincide only the first is
    written (jax and casadi mark both valid), so the rows' branches are the executor's (the PUMA at q5 = 0: 7 of 8)."""
    robot, plan, solvers, _, _ = arm
    ik = inverse_kinematics_of(robot)
    fk = numeric_model(robot, backend="numpy").fk
    revolute = np.array([kind.value == "revolute" for kind in robot.coordinate_types])
    straight = np.array([0.3, -0.5, 0.4, 0.2, 0.0, -0.1])  # theta5 = 0 (the Stanford arm: d3 = 0.4)
    poses = fk(np.array([np.zeros(robot.n_joints), straight]))
    for k, pose in enumerate(poses):
        executor = solve_plan(plan, pose).solutions
        expected = _distinct(np.array([s.q for s in executor]), revolute)
        for target, solve in solvers.items():
            ((found, branches),) = solve.pairs(pose[None])
            names = [ik.branches[b] for b in branches]
            assert target in ("jax", "casadi") or names == [s.branch for s in executor], (target, k)
            assert np.abs(fk(found) - pose).max() < 1e-12, (target, k)
            distinct = _distinct(found, revolute)
            assert len(distinct) == len(expected), (target, k)
            assert target in ("jax", "casadi") or len(found) == len(expected), (target, k)
            assert _distance(np.array(distinct), np.array(expected), revolute).min(axis=1).max() < 1e-9, (target, k)


def test_the_compiled_targets_agree_row_for_row(arm):
    _, _, solvers, _, poses = arm
    reference = solvers["numpy"](poses)
    for target in ("c99", "cpp"):
        for found, expected in zip(solvers[target](poses), reference, strict=True):
            np.testing.assert_allclose(found, expected, rtol=0, atol=1e-10, err_msg=target)


def test_unreachable_and_nan_poses_give_no_solution(arm):
    robot, _, solvers, _, poses = arm
    far = poses[0].copy()
    far[:3, 3] *= 100.0  # out of reach of every revolute arm (a prismatic joint without limits reaches it)
    nan = np.full((4, 4), np.nan)
    bounded = all(kind.value == "revolute" for kind in robot.coordinate_types)
    for target, solve in solvers.items():
        counts = [len(s) for s in solve(np.array([far, nan]))]
        assert counts[1] == 0 and (counts[0] == 0 or not bounded), target


def test_ten_thousand_poses_round_trip_through_the_numeric_model(arm):
    robot = arm[0]
    model = numeric_model(robot)
    lower, upper = seed_bounds(robot)
    q = np.random.default_rng(10_000).uniform(lower, upper, (10_000, robot.n_joints))
    poses = model.fk(q)
    solutions, count, branches = model.ik(poses)
    assert count.min() >= 1
    assert np.array_equal(branches >= 0, np.arange(branches.shape[-1]) < count[:, None])
    assert model.ik_branches == inverse_kinematics_of(robot).branch_names
    numpy_model = numeric_model(robot, backend="numpy")  # one pose through the python module, as floats
    for k in range(5):
        rows, how_many, which = numpy_model.ik(poses[k])
        assert int(how_many) == count[k] and which.tolist() == branches[k].tolist(), k
        np.testing.assert_allclose(rows, solutions[k], rtol=0, atol=1e-10)
    flat = solutions.reshape(-1, robot.n_joints)
    valid = ~np.isnan(flat).any(axis=1)
    assert valid.sum() == count.sum()
    errors = np.abs(model.fk(flat[valid]) - np.repeat(poses, count, axis=0)).max()
    assert errors < 1e-10


def test_the_jax_closed_form_differentiates_to_the_joint_rates(arm, tmp_path):
    """Along a motion q + t qdot, d/dt of the branch that holds q is qdot (jvp through FK, then through the IK)."""
    jax = pytest.importorskip("jax")
    jax.config.update("jax_enable_x64", True)
    from ik_generated import ik_files

    robot, _, _, q, _ = arm
    (name, text), = ik_files(robot, "jax").items()
    namespace: dict = {}
    exec(compile(text, name, "exec"), namespace)
    fk, ik = namespace["forward_kinematics"], namespace["inverse_kinematics"]
    rates = np.random.default_rng(7).normal(size=(5, robot.n_joints))
    for configuration, qdot in zip(q[:5], rates, strict=True):
        pose, pose_rate = jax.jvp(fk, (configuration,), (qdot,))
        (solutions, valid), (rates_found, _) = jax.jvp(ik, (pose,), (pose_rate,))
        solutions, rates_found = np.asarray(solutions), np.asarray(rates_found)
        turned = (solutions - configuration + np.pi) % (2 * np.pi) - np.pi
        revolute = np.array([kind.value == "revolute" for kind in robot.coordinate_types])
        branch = int(np.argmin(np.abs(np.where(revolute, turned, solutions - configuration)).max(axis=1)))
        assert bool(valid[branch])
        np.testing.assert_allclose(rates_found[branch], qdot, rtol=1e-6, atol=1e-6)
