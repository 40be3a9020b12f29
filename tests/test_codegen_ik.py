"""Generated closed-form inverse kinematics in every target: solutions, selection, unreachable and NaN poses."""

from __future__ import annotations

import numpy as np
import pytest
from ik_generated import ik_files, ik_solvers
from ik_programs import planar_2r_programs

import symjac.codegen.inverse_kinematics as codegen_ik
from symjac.codegen.inverse_kinematics import lower_branch_programs
from symjac.codegen.numeric_model import numeric_model
from symjac.model.io import load_robot

TARGETS = ("python", "numpy", "c", "lambdify", "jax", "casadi", "c99", "cpp")


@pytest.fixture(scope="module")
def planar(tmp_path_factory):
    """The planar 2R arm with its hand-written elbow-up/down programs, every target's solver."""
    robot = load_robot("planar2r")
    ik = lower_branch_programs(planar_2r_programs(robot), robot.q,
                               [p.symbol for p in robot.geometric_parameters], (True, True), "planar 2R")
    folder = tmp_path_factory.mktemp("ik_planar")
    with pytest.MonkeyPatch.context() as patch:  # only while the modules are made
        patch.setattr(codegen_ik, "inverse_kinematics_of", lambda chain, free_joint=None: ik)
        solvers = ik_solvers(folder, robot, TARGETS)
    return robot, solvers, folder


def _poses(robot, count: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (count, robot.n_joints))
    return q, numeric_model(robot, backend="numpy").fk(q)


def test_every_target_finds_both_elbows_and_they_reproduce_the_pose(planar):
    robot, solvers, _ = planar
    q, poses = _poses(robot, 50)
    fk = numeric_model(robot, backend="numpy").fk
    reference = solvers["python"](poses)
    for target, solve in solvers.items():
        found = solve(poses)
        for k, (solutions, expected) in enumerate(zip(found, reference, strict=True)):
            assert solutions.shape == (2, 2), (target, k)
            np.testing.assert_allclose(solutions, expected, atol=1e-12, err_msg=target)
            np.testing.assert_allclose(fk(solutions)[:, :3, 3], np.repeat(poses[k:k + 1, :3, 3], 2, 0), atol=1e-10)
            assert np.min(np.abs(solutions - q[k]).max(axis=1)) < 1e-9, (target, k)  # the pose's own configuration
            assert np.all((solutions > -np.pi) & (solutions <= np.pi))


def test_elbow_up_comes_first_with_a_positive_elbow(planar):
    robot, solvers, _ = planar
    _, poses = _poses(robot, 20, seed=1)
    for solve in solvers.values():
        for solutions in solve(poses):
            assert solutions[0, 1] > 0 > solutions[1, 1]


def test_unreachable_and_nan_poses_give_no_solution(planar):
    _, solvers, _ = planar
    far = np.eye(4)
    far[0, 3] = 2.0  # beyond L1 + L2 = 0.9
    near = np.eye(4)
    near[0, 3] = 0.05  # inside |L1 - L2| = 0.1
    nan = np.full((4, 4), np.nan)
    for target, solve in solvers.items():
        assert [len(s) for s in solve(np.array([far, near, nan]))] == [0, 0, 0], target


def test_a_pose_at_full_stretch_keeps_the_branch_within_the_tolerance(planar):
    _, solvers, _ = planar
    pose = np.eye(4)
    pose[0, 3] = 0.9 * (1 + 1e-12)  # c2 = 1 + a few 1e-12: the condition is clamped, not failed
    for target, solve in solvers.items():  # both elbows give q = 0: the second is dropped, but jax/casadi's mask
        ((solutions, branches),) = solve.pairs(pose[None])
        both = target in ("jax", "casadi")
        assert solutions.shape == ((2, 2) if both else (1, 2)), target
        assert branches.tolist() == ([0, 1] if both else [0]), target
        np.testing.assert_allclose(solutions, 0.0, atol=1e-5, err_msg=target)


def test_generation_is_deterministic_and_the_header_says_how_to_regenerate_it(planar):
    robot, _, folder = planar
    for target in ("python", "c99", "cpp"):
        assert ik_files(robot, target) == ik_files(robot, target), target
    assert "inverse_kinematics=True" in (folder / "numpy" / "numpy_planar2r.py").read_text().split('"""')[0]


def test_the_numpy_target_keeps_batch_shapes(planar):
    robot, _, folder = planar
    import importlib.util

    spec = importlib.util.spec_from_file_location("ik_numpy_shape", folder / "numpy" / "numpy_planar2r.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    _, poses = _poses(robot, 6)
    solutions, count, branches = module.inverse_kinematics(poses.reshape(2, 3, 4, 4))
    assert solutions.shape == (2, 3, module.IK_MAX_SOLUTIONS, 2) and count.shape == (2, 3)
    assert branches.shape == (2, 3, module.IK_MAX_SOLUTIONS) and branches.dtype.kind == "i"
    single, one, which = module.inverse_kinematics(poses[0])
    assert single.shape == (2, 2) and one.shape == () and int(one) == 2 and which.tolist() == [0, 1]
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 4, 4\)"):
        module.inverse_kinematics(np.zeros((3, 4)))


@pytest.mark.parametrize("backend", ["numpy", "c"])
def test_the_numeric_models_ik_gives_every_solution_for_one_pose_and_a_batch(planar, backend):
    robot, solvers, _ = planar  # the model's own closed form (the planar family) against the hand-written one
    model = numeric_model(robot, backend=backend)
    _, poses = _poses(robot, 30, seed=2)
    solutions, count, branches = model.ik(poses)
    assert solutions.shape == (30, 2, 2) and count.tolist() == [2] * 30 and branches.tolist() == [[0, 1]] * 30
    expected = solvers["python"](poses)
    for k in range(30):
        np.testing.assert_allclose(solutions[k][np.argsort(solutions[k][:, 1])], expected[k][::-1], atol=1e-12)
    one, how_many, which = model.ik(poses[0])
    assert one.shape == (2, 2) and int(how_many) == 2 and which.tolist() == [0, 1]
    np.testing.assert_allclose(one, solutions[0], atol=1e-12)
    nothing, zero, none = model.ik(np.full((4, 4), np.nan))
    assert int(zero) == 0 and np.isnan(nothing).all() and none.tolist() == [-1, -1]
    with pytest.raises(Exception, match=r"shape \(4, 4\) or \(\.\.\., 4, 4\)"):
        model.ik(np.zeros(4))


def test_the_command_line_option_writes_a_module_that_solves(cli, tmp_path):
    source = cli.ok("codegen", "stanford", "--target", "numpy", "--inverse-kinematics")
    assert "--inverse-kinematics" in source.split('"""')[0]  # the regenerating command in the header
    namespace: dict = {}
    exec(compile(source, "stanford.py", "exec"), namespace)
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -0.1])
    solutions, count, _ = namespace["inverse_kinematics"](namespace["forward_kinematics"](q))
    assert int(count) == namespace["IK_MAX_SOLUTIONS"] == 8
    assert np.abs(solutions[:count] - q).max(axis=1).min() < 1e-9


def test_an_arm_without_a_closed_form_is_refused_in_one_line_or_solved_numerically(cli, tmp_path):
    error = cli.one_line_error("codegen", "panda", "--target", "jax", "--inverse-kinematics", "--free-joint", "3")
    assert "closed-form" in error and "numeric" in error  # no numeric stand-in for a given joint
    status, module, _ = cli.run("codegen", "panda", "--target", "jax", "--inverse-kinematics")
    assert status == 0 and "def inverse_kinematics_numeric(" in module and "def inverse_kinematics(" not in module
    files = ik_files(load_robot("panda"), "c99")  # C99 and C++ carry the numeric solver instead
    header = files["panda.h"]
    assert "panda_inverse_kinematics_numeric(" in header and "panda_inverse_kinematics(" not in header


def test_the_same_bytes_in_processes_with_different_hash_seeds(tmp_path):
    import os
    import subprocess
    import sys

    script = ("import sys; from symjac import load_robot; from symjac.codegen import ModuleRequest, describe, "
              "render_files; sys.stdout.write(''.join(render_files(describe(ModuleRequest(load_robot('stanford'), "
              "'c99', inverse_kinematics=True))).values()))")
    texts = [subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, timeout=600,
                            env={**os.environ, "PYTHONHASHSEED": seed}).stdout for seed in ("1", "2")]
    assert texts[0] == texts[1] and "    return count;" in texts[0]  # the source's inverse kinematics too
