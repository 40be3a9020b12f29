"""The numeric inverse kinematics of the jax and casadi targets: fixed graphs, checked by the module's own FK.

On random reachable poses (from configurations within the limits) of the PUMA 560 (six joints), the Panda (seven,
no closed form: ``inverse_kinematics=True`` gets the numeric solver) and the coupled palletizer (four coordinates),
each solution found must reproduce the pose through the generated module's forward kinematics and lie within the
limits; the share of poses solved is reported in the assertion message. jax: under ``jit(vmap)`` over poses and
seeds, deterministic for a seed, a warm start at a solution takes no step. casadi: a ``casadi.Function`` of (pose,
start, p), differentiable and written to C by ``Function.generate()``.
"""

from __future__ import annotations

import subprocess
import types
from pathlib import Path

import numpy as np
import pytest

from symjac.codegen import ModuleRequest, describe, render_files
from symjac.model.io import load_robot
from symjac.solvers.controlled import coordinate_bounds

REPO = Path(__file__).resolve().parent.parent
ARMS = {"puma560": {"numeric_ik": True}, "panda": {"inverse_kinematics": True},
        "palletizer": {"numeric_ik": True}}


def _text(name: str, target: str) -> str:
    return next(iter(render_files(describe(ModuleRequest(load_robot(name), target, **ARMS[name]))).values()))


def _module(text: str, name: str) -> types.ModuleType:
    module = types.ModuleType(name)
    exec(compile(text, f"{name}.py", "exec"), module.__dict__)  # our own generated module
    return module


def _poses(robot, count: int, fk) -> tuple[np.ndarray, np.ndarray]:
    lower, upper = coordinate_bounds(robot)
    q = np.random.default_rng(46).uniform(lower, upper, (count, robot.n_coordinates))
    return q, np.array([np.asarray(fk(row)) for row in q])


def _check(module, robot, solutions, found, poses, fk, target) -> str:
    """Each solution found reproduces its pose and lies within the limits; returns the success rate's words."""
    rate = f"{target} {robot.name}: {int(np.sum(found))} of {len(poses)} poses solved"
    lower, upper = np.array(module.LOWER), np.array(module.UPPER)
    for q, ok, pose in zip(solutions, found, poses, strict=True):
        assert np.all((q >= lower - 1e-12) & (q <= upper + 1e-12)), rate
        if ok:
            assert np.abs(np.asarray(fk(q)) - pose).max() < 1e-9, rate
    return rate


@pytest.fixture(scope="module", params=sorted(ARMS))
def jax_arm(request):
    jax = pytest.importorskip("jax")
    jax.config.update("jax_enable_x64", True)
    robot = load_robot(request.param)
    text = _text(request.param, "jax")
    return jax, robot, text, _module(text, f"{request.param}_jax_ik")


def test_jax_solves_random_reachable_poses_under_jit_and_vmap(jax_arm):
    jax, robot, _, module = jax_arm
    fk = module.forward_kinematics
    _, poses = _poses(robot, 40, fk)
    solve = jax.jit(jax.vmap(module.inverse_kinematics_numeric))
    solutions, found, steps = (np.asarray(a) for a in solve(poses, np.arange(40)))
    assert solutions.shape == (40, robot.n_coordinates) and found.dtype == bool and steps.shape == (40,)
    rate = _check(module, robot, solutions, found, poses, fk, "jax")
    assert found.mean() >= 0.95, rate
    again = np.asarray(solve(poses, np.arange(40))[0])
    np.testing.assert_array_equal(again, solutions)  # deterministic for the seeds


def test_jax_warm_start_at_a_solution_takes_no_step_and_seeds_differ(jax_arm):
    jax, robot, _, module = jax_arm
    q, poses = _poses(robot, 1, module.forward_kinematics)
    solution, found, steps = module.inverse_kinematics_numeric(poses[0], 3, start=q[0])
    assert bool(found) and int(steps) == 0
    turned = (np.asarray(solution) - q[0] + np.pi) % (2 * np.pi) - np.pi  # the angles wrapped to (-pi, pi]
    np.testing.assert_allclose(turned, 0.0, rtol=0, atol=1e-12)
    far = poses[0].copy()
    far[:3, 3] *= 100.0  # out of reach
    q_far, found_far, _ = module.inverse_kinematics_numeric(far, 0, starts=4, iterations=16)
    assert not bool(found_far) and np.all(np.isfinite(np.asarray(q_far)))
    solve = jax.vmap(lambda seed: module.inverse_kinematics_numeric(poses[0], seed, starts=2, iterations=1)[0])
    first, second = np.asarray(solve(np.array([0, 1])))
    assert np.abs(first - second).max() > 1e-6  # other seeds, other starts


@pytest.fixture(scope="module", params=sorted(ARMS))
def casadi_arm(request):
    ca = pytest.importorskip("casadi")
    robot = load_robot(request.param)
    text = _text(request.param, "casadi")
    return ca, robot, text, _module(text, f"{request.param}_casadi_ik")


def test_casadi_solves_random_reachable_poses_from_random_warm_starts(casadi_arm):
    ca, robot, _, module = casadi_arm
    p = np.array(module.PARAMETER_DEFAULTS, dtype=float)

    def fk(q):
        return np.array(module.forward_kinematics(q, p))

    _, poses = _poses(robot, 30, fk)
    lower, upper = coordinate_bounds(robot)
    starts = np.random.default_rng(1).uniform(lower, upper, (30, robot.n_coordinates))
    solve = module.inverse_kinematics_numeric.map(30)  # every pose at once, as a casadi user would
    q, found, error = (np.array(a) for a in solve(np.hstack(poses), starts.T, p))
    solutions, found = q.T, found.ravel() > 0.5
    rate = _check(module, robot, solutions, found, poses, fk, "casadi")
    assert found.mean() >= 0.95, rate
    assert np.all(error[:, found] <= 1e-10), rate
    assert isinstance(module.inverse_kinematics_numeric, ca.Function)


def test_casadi_solver_is_a_graph_casadi_differentiates_and_writes_to_c(casadi_arm, tmp_path, monkeypatch):
    ca, robot, _, module = casadi_arm
    function = module.inverse_kinematics_numeric
    assert function.name_in() == ["pose", "start", "p"] and function.name_out() == ["q", "found", "error"]
    pose = ca.MX.sym("pose", 4, 4)
    start, p = ca.MX.sym("start", robot.n_coordinates), ca.MX.sym("p", len(module.PARAMETER_NAMES))
    q = function(pose, start, p)[0]
    assert ca.jacobian(q, pose).shape == (robot.n_coordinates, 16)  # an expression CasADi can differentiate
    if robot.name == "puma560":
        monkeypatch.chdir(tmp_path)  # generate() writes into the working folder
        function.generate("ik_numeric.c", {"with_header": True})
        compiled = subprocess.run(["gcc", "-O0", "-c", "ik_numeric.c", "-o", "ik.o"], capture_output=True, text=True,
                                  timeout=300, check=False)
        assert compiled.returncode == 0, compiled.stderr[-2000:]


def test_the_modules_are_deterministic_and_ruff_clean(jax_arm, casadi_arm, tmp_path):
    for (_, robot, text, _), target in ((jax_arm, "jax"), (casadi_arm, "casadi")):
        assert _text(robot.name, target) == text
        path = tmp_path / f"{robot.name}_{target}.py"
        path.write_text(text, encoding="utf-8")
        result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"), str(path)],
                                capture_output=True, text=True, timeout=120, check=False)
        assert result.returncode == 0, result.stdout
