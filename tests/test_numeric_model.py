"""The compiled numeric model: FK and Jacobians against plain-NumPy FK, its central differences and the symbolic ones.

The references are independent of generated code: :mod:`reference` builds forward kinematics from the robot's data
in NumPy (its Jacobian by central differences, the angular rows from R(q + h) R(q)^T), and the symbolic Jacobian is
evaluated by ``sympy.lambdify``. Speed is measured in ``benchmarks/numeric_model.py``, not here.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from marks import marked
from reference import evaluate, finite_difference_jacobian, frames, random_configuration

from symjac import (
    ArgumentError,
    Chain,
    CodegenError,
    FrameError,
    NumericModel,
    jacobian,
    load_robot,
    numeric_jacobian,
    numeric_model,
    robot_from_mapping,
)
from symjac.kinematics.points import point_vector

HAVE_C = bool(shutil.which("cc") or shutil.which("gcc")) and (
    Path(sysconfig.get_paths()["include"]) / "Python.h").is_file()
BACKENDS = ["numpy", "c"]  # "c" cases are external (marks.marked)
# one robot per structural class: standard DH, prismatic joint and spherical wrist (modified DH), URDF with a mimic
# joint, product of exponentials, coupled coordinates; the PUMA for its wrist centre and the UR5 from its URDF
ROBOTS = ["planar2r", "stanford", "gripper.urdf", "ur5_poe", "palletizer", "puma560", "ur5.urdf"]


@pytest.fixture(scope="module", autouse=True)
def private_cache(tmp_path_factory):
    """Compiled kernels go to a cache of this module's own, not the user's."""
    previous = os.environ.get("SYMJAC_CACHE_DIR")
    os.environ["SYMJAC_CACHE_DIR"] = str(tmp_path_factory.mktemp("c-cache"))
    yield
    if previous is None:
        os.environ.pop("SYMJAC_CACHE_DIR", None)
    else:
        os.environ["SYMJAC_CACHE_DIR"] = previous


def _points(robot):
    """Points by name (None: the end of the chain) with their coordinates in frame {n} for the reference."""
    points = {None: None if robot.tool is None else _coordinates(robot, "tool"), "flange": None,
              (0.5, 0, -0.25): np.array([0.5, 0, -0.25])}  # short: a longer text overflows a coupled module's
    # docstring line (a codegen defect, reported)
    with contextlib.suppress(FrameError):  # an arm without a wrist centre has no such point
        points["wrist_centre"] = _coordinates(robot, "wrist_centre")
    return points


def _coordinates(robot, name):
    return np.array([float(v.subs(robot.defaults)) for v in point_vector(robot, name)])


def _frames(robot):
    return [0, "world", robot.n_joints // 2, "tool"]


def _cases(backends):
    return marked([(name, backend) for name in ROBOTS for backend in backends])


def _model(robot, frame=0, point=None, backend="numpy"):
    if backend == "c" and not HAVE_C:
        pytest.skip("no C compiler or no Python.h")
    return numeric_model(robot, frame, point, backend)


@pytest.mark.parametrize(("name", "backend"), _cases(BACKENDS))
def test_jacobian_matches_finite_differences_and_the_symbolic_jacobian(name, backend):
    robot = load_robot(name)
    rng = np.random.default_rng(43)
    batch = np.array([random_configuration(robot, rng) for _ in range(3)])
    for frame in _frames(robot):
        for point, coordinates in _points(robot).items():
            model = _model(robot, frame, point, backend)
            J = model.jacobian(batch)
            assert J.shape == (3, 6, robot.n_coordinates)
            symbolic = jacobian(robot, frame=frame, point=point)
            for q, J_q in zip(batch, J, strict=True):
                where = f"{name} frame {frame} point {point}"
                np.testing.assert_allclose(J_q, evaluate(symbolic, robot, q), atol=1e-10, err_msg=where)
                np.testing.assert_allclose(J_q, finite_difference_jacobian(robot, q, frame, coordinates),
                                           atol=1e-6, err_msg=where)
                np.testing.assert_allclose(model.jacobian(q), J_q, rtol=0, atol=1e-14)  # one configuration


@pytest.mark.parametrize(("name", "backend"), _cases(BACKENDS))
def test_forward_kinematics_is_the_end_of_the_chain_in_frame_0(name, backend):
    robot = load_robot(name)
    rng = np.random.default_rng(7)
    batch = np.array([random_configuration(robot, rng) for _ in range(4)])
    model = _model(robot, backend=backend)
    T = model.fk(batch)
    assert T.shape == (4, 4, 4)
    for q, T_q in zip(batch, T, strict=True):
        poses = frames(robot, q)
        np.testing.assert_allclose(T_q, np.linalg.inv(poses[1]) @ poses[-1], atol=1e-12)
        np.testing.assert_allclose(model.fk(q.tolist()), T_q, atol=1e-12)


@pytest.mark.parametrize("backend", marked(BACKENDS))
def test_a_batch_of_any_shape_equals_the_loop_and_fills_out(backend):
    robot = load_robot("stanford")
    model = _model(robot, "tool", "wrist_centre", backend)
    # 40 configurations: more than the numpy backend evaluates one by one in plain Python floats
    q = np.array([random_configuration(robot, np.random.default_rng(k)) for k in range(40)]).reshape(5, 8, 6)
    J = model.jacobian(q)
    assert J.shape == (5, 8, 6, 6)
    loop = np.array([[model.jacobian(row) for row in rows] for rows in q])
    np.testing.assert_allclose(J, loop, rtol=0, atol=1e-14)
    out = np.empty((5, 8, 4, 4))
    assert model.fk(q, out=out) is out
    np.testing.assert_allclose(out, [[model.fk(row) for row in rows] for rows in q], rtol=0, atol=1e-14)
    few = q[0]  # eight configurations: one by one in plain Python floats for the numpy backend
    np.testing.assert_allclose(model.jacobian(few), J[0], rtol=0, atol=1e-14)
    with pytest.raises(ArgumentError, match=r"q\[2\] is nan"):  # the common call's own check
        model.jacobian(np.array([0.1, 0.2, np.nan, 0.3, 0.4, 0.5]))
    with pytest.raises(ArgumentError, match=r"q\[0\] is -inf"):
        model.fk(np.array([-np.inf, 0.2, 0.5, 0.3, 0.4, 0.5]))
    np.testing.assert_array_equal(model.fk(np.arange(6)), model.fk(np.arange(6.0)))  # integers become floats
    single = np.empty((6, 6))
    assert model.jacobian(q[0, 0], out=single) is single
    np.testing.assert_allclose(single, J[0, 0], rtol=0, atol=1e-14)


def test_the_model_says_what_it_is_and_is_kept_per_request():
    robot = load_robot("puma560")
    model = numeric_model(robot, backend="numpy")
    assert isinstance(model, NumericModel)
    assert (model.robot, model.n, model.names[0], model.frame, model.point) == ("puma560", 6, "theta1", 0, "flange")
    assert model.backend == "numpy"
    assert numeric_model(robot, point="wrist", backend="numpy") is model  # the flange by its older name
    assert numeric_model(robot, frame="world", backend="numpy") is not model
    explicit = numeric_model(robot, point=(0, 0, 0.1), backend="numpy")
    assert explicit.point == (0.0, 0.0, 0.1)
    assert "backend='numpy'" in repr(model)


@pytest.mark.parametrize(("q", "message"), [
    ([0.1, 0.2], r"q must have shape \(6,\) or \(N, 6\) for puma560 \(theta1, .*got shape \(2,\)"),
    (0.5, r"got shape \(\)"),
    ([[0.1] * 6, [0.2] * 5 + [float("nan")]], r"q must be finite; q\[\(1, 5\)\] is nan"),
    ([0.1] * 5 + [float("inf")], r"q\[5\] is inf"),
    ("0.1 0.2", "q must be numbers"),
    ([[0.1] * 6, [0.2] * 5], "q must be numbers"),
])
def test_bad_configurations_are_refused_in_one_line(q, message):
    model = numeric_model(load_robot("puma560"), backend="numpy")
    with pytest.raises(ArgumentError, match=message):
        model.jacobian(q)


def test_bad_requests_and_outputs_are_refused():
    robot = load_robot("puma560")
    with pytest.raises(ArgumentError, match="unknown backend 'fortran'; choose one of auto, c, numpy"):
        numeric_model(robot, backend="fortran")
    with pytest.raises(FrameError, match="no 'tool' point"):
        numeric_model(robot, point="tool")
    with pytest.raises(FrameError):
        numeric_model(robot, frame=9)
    model = numeric_model(robot, backend="numpy")
    with pytest.raises(ArgumentError, match=r"out must be .* shape \(6, 6\), got shape \(6, 5\)"):
        model.jacobian([0.1] * 6, out=np.empty((6, 5)))
    with pytest.raises(ArgumentError, match=r"shape \(4, 4\), got list"):
        model.fk([0.1] * 6, out=[])


def test_without_a_compiler_auto_runs_numpy_and_says_why_and_c_refuses(monkeypatch, tmp_path):
    monkeypatch.setenv("CC", str(tmp_path / "no-such-compiler"))
    monkeypatch.setenv("SYMJAC_CACHE_DIR", str(tmp_path / "cache"))
    chain = Chain(load_robot("planar2r"))  # a chain of its own: no model kept from another test
    model = numeric_model(chain, backend="auto")
    assert model.backend == "numpy"
    assert "no-such-compiler" in model.note
    np.testing.assert_allclose(model.jacobian([0.0, 0.0])[:2], [[0.0, 0.0], [0.9, 0.4]], atol=1e-15)
    with pytest.raises(CodegenError, match=r"the C kernels of planar2r did not build: .*no-such-compiler"):
        numeric_model(chain, backend="c")


@pytest.mark.parametrize("name", ["puma560", "ur5_poe", "palletizer"])
def test_numeric_jacobian_is_the_model_one_configuration_or_a_batch(name):
    robot = load_robot(name)
    rng = np.random.default_rng(1)
    batch = np.array([random_configuration(robot, rng) for _ in range(5)])
    model = numeric_model(robot, "world", "flange", "numpy")
    np.testing.assert_array_equal(numeric_jacobian(robot, batch, "world", "flange"), model.jacobian(batch))
    np.testing.assert_array_equal(numeric_jacobian(robot, batch[0].tolist(), "world", "flange"),
                                  model.jacobian(batch[0]))
    with pytest.raises(ArgumentError, match="must be finite"):
        numeric_jacobian(robot, [float("nan")] * robot.n_coordinates)


def test_numeric_jacobian_of_a_robot_generated_code_cannot_name_evaluates_through_lambdify():
    robot = robot_from_mapping({"name": "arm", "convention": "standard", "parameters": {"seed": 0.5, "L2": 0.4},
                                "joints": [{"type": "revolute", "alpha": 0, "a": "seed", "d": 0, "theta": 0},
                                           {"type": "revolute", "alpha": 0, "a": "L2", "d": 0, "theta": 0}]})
    with pytest.raises(CodegenError, match="seed"):  # an argument of every generated selftest
        numeric_model(robot, backend="numpy")
    batch = np.array([[0.0, 1.5707963267948966], [0.3, -0.2]])
    J = numeric_jacobian(robot, batch)
    assert J.shape == (2, 6, 2)
    np.testing.assert_allclose(J[0, :2], [[-0.4, -0.4], [0.5, 0.0]], atol=1e-12)
    np.testing.assert_allclose(J[1], finite_difference_jacobian(robot, batch[1]), atol=1e-6)
    np.testing.assert_allclose(numeric_jacobian(robot, batch[1].tolist()), J[1], atol=1e-15)


@pytest.mark.parametrize("backend", marked(["numpy", "c"], keep=["ur5.urdf"]))
def test_the_model_names_its_coordinates_as_the_file_does_and_reads_a_joint_state(backend):
    model = numeric_model(load_robot("ur5.urdf"), backend=backend)
    assert model.names == ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
                           "wrist_2_joint", "wrist_3_joint")
    state = (["wrist_3_joint", "finger", "elbow_joint", "shoulder_pan_joint", "wrist_1_joint", "shoulder_lift_joint",
              "wrist_2_joint"], [0.6, 9.0, 0.3, 0.1, 0.4, 0.2, 0.5])
    q = model.coordinates(*state)
    np.testing.assert_array_equal(q, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    np.testing.assert_array_equal(model.coordinates(dict(zip(model.names, q, strict=True))), q)
    with pytest.raises(ValueError, match="wrist_3_joint"):
        model.coordinates(state[0][1:], state[1][1:])
