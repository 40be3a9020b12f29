"""Points fixed in any link (``link=k``): every method, every frame, the Hessian, J-dot and the bias.

Independent references: the plain-NumPy forward kinematics of ``reference.py`` (central differences of the point's
position, angular velocity from :math:`R(q+h)R(q)^T`), and central differences of the numeric link Jacobian for the
acceleration level. Catalog arms of every structural class (planar and modified DH, SCARA and Stanford with prismatic
joints, the coupled palletizer, the PoE UR5) and hypothesis chains (standard and modified DH, prismatic joints).
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from marks import marked
from reference import frame_index, frames, random_configuration
from strategies import robots

from symjac import load_robot
from symjac.errors import ArgumentError, FrameError
from symjac.kinematics.acceleration import bias_acceleration, hessian, jacobian_derivative
from symjac.kinematics.acceleration_propagation import acceleration_propagation
from symjac.kinematics.chain import Chain, forward_kinematics
from symjac.kinematics.coupling import COUPLING_LAWS, LAW_NAMES
from symjac.kinematics.jacobian import METHODS, jacobian
from symjac.kinematics.memo import memoized
from symjac.kinematics.points import point_position
from symjac.kinematics.propagation import force_propagation, joint_rate_symbols, velocity_propagation
from symjac.kinematics.screws import space_jacobian
from symjac.kinematics.statics import joint_torques
from symjac.symbolic.nested import lambdify_cse

CATALOG = ["planar3r", "articulated3r", "scara", "stanford", "palletizer", "ur5_poe"]
H = 1e-6


@cache
def _robot(name: str):
    return load_robot(name)


def _numeric(robot, matrix: sp.MatrixBase):
    """A function of the coordinates q (and their rates) for a symbolic matrix, parameters at their defaults."""
    expr = sp.Matrix(matrix).xreplace(robot.defaults)
    function = sp.lambdify([list(robot.q), list(joint_rate_symbols(robot))], expr, modules="numpy", cse=lambdify_cse)
    return lambda q, qd=None: np.asarray(function(q, np.zeros(len(q)) if qd is None else qd), dtype=float)


@cache
def _poses(robot, q: tuple[float, ...]) -> tuple[list[np.ndarray], list[tuple[list[np.ndarray], list[np.ndarray]]]]:
    """The NumPy chain's frames at q and at q -+ h along each coordinate: computed once per robot and q."""
    at = np.array(q)
    steps = [H * np.eye(len(q))[i] for i in range(len(q))]
    return frames(robot, at), [(frames(robot, at + step), frames(robot, at - step)) for step in steps]


def _reference(robot, q: np.ndarray, link: int, point, frame) -> np.ndarray:
    """6 x n_coordinates: central differences of the point's position and orientation from the NumPy chain."""
    p = np.append(np.array([float(sp.sympify(c).xreplace(robot.defaults)) for c in point]), 1.0)
    middle, shifted = _poses(robot, tuple(q))
    R = middle[link + 1][:3, :3]  # frame positions world, 0, 1, .., n, tool
    J = np.zeros((6, len(q)))
    for i, (plus, minus) in enumerate(shifted):
        T_plus, T_minus = plus[link + 1], minus[link + 1]
        J[:3, i] = ((T_plus - T_minus) @ p)[:3] / (2 * H)
        W = (T_plus[:3, :3] - T_minus[:3, :3]) / (2 * H) @ R.T
        J[3:, i] = W[2, 1], W[0, 2], W[1, 0]
    R_world_k = middle[frame_index(robot, frame)][:3, :3]
    return np.kron(np.eye(2), R_world_k.T) @ J


def _point(rng: np.random.Generator) -> list[sp.Rational]:
    return [sp.Rational(int(rng.integers(-50, 51)), 100) for _ in range(3)]


def _frames(robot, link: int, rng: np.random.Generator) -> list:
    """{0}, the link's own frame, one drawn at random and the tool frame (a moving frame past the link)."""
    n = robot.n_joints
    return list(dict.fromkeys([0, link, int(rng.integers(0, n + 1)), "tool"]))


def _check_link_jacobians(robot, link: int, point, frame, q: np.ndarray, simplify: bool = True) -> None:
    """Every method against the reference; compact forms are also the same expressions (one normal form)."""
    expected = _reference(robot, q, link, point, frame)
    first = None
    for method in METHODS:
        J = jacobian(robot, frame, point, method, simplify=simplify, link=link)
        np.testing.assert_allclose(_numeric(robot, J)(q), expected, atol=1e-6, err_msg=f"{method} link {link}")
        first = J if first is None else first
        assert not simplify or first == J, f"{method} differs from {METHODS[0]}: link {link}, frame {frame}"


@pytest.mark.parametrize("name", marked(CATALOG))
def test_every_method_matches_finite_differences_on_every_link(name):
    robot = _robot(name)
    rng = np.random.default_rng(sum(map(ord, name)))
    q = random_configuration(robot, rng)
    for link in range(robot.n_joints + 1):
        point = _point(rng)
        for frame in _frames(robot, link, rng):
            _check_link_jacobians(robot, link, point, frame, q)


@pytest.mark.parametrize("name", marked(["planar3r", "stanford", "palletizer"]))
def test_acceleration_level_of_a_link_point_matches_finite_differences(name):
    robot = _robot(name)
    rng = np.random.default_rng(3)
    q, qd = random_configuration(robot, rng), rng.uniform(-1.5, 1.5, robot.n_coordinates)
    n = robot.n_coordinates
    for link in sorted(set(rng.integers(1, robot.n_joints, size=2).tolist())):  # two middle links, drawn
        point = _point(rng)
        for frame in (0, link, robot.n_joints):  # fixed, the link's own, a frame moved by later joints
            J = _numeric(robot, jacobian(robot, frame, point, simplify=False, link=link))
            Hq = hessian(robot, frame, point, link=link)
            H_numeric = _numeric(robot, sp.Matrix(Hq.reshape(6, n * n).tolist()))(q).reshape(6, n, n)
            for m in range(n):
                step = np.zeros(n)
                step[m] = H
                slice_m = (J(q + step) - J(q - step)) / (2 * H)
                np.testing.assert_allclose(H_numeric[:, :, m], slice_m, atol=1e-6, err_msg=f"{frame} {link} {m}")
            Jdot = np.einsum("ijm,m->ij", H_numeric, qd)
            for method in ("hessian", "differentiation"):
                derivative = jacobian_derivative(robot, frame, point, method, link=link)
                np.testing.assert_allclose(_numeric(robot, derivative)(q, qd), Jdot, atol=1e-6)
                bias = bias_acceleration(robot, frame, point, method, link=link)
                np.testing.assert_allclose(_numeric(robot, bias)(q, qd)[:, 0], Jdot @ qd, atol=1e-6)


@pytest.mark.parametrize("name", marked(["scara", "palletizer"]))
def test_acceleration_propagation_to_a_link_point_gives_the_bias(name):
    robot = _robot(name)
    rng = np.random.default_rng(5)
    q, qd = random_configuration(robot, rng), rng.uniform(-1.5, 1.5, robot.n_coordinates)
    for link in range(robot.n_joints + 1):
        point = _point(rng)
        tip = acceleration_propagation(robot, point, link=link).bias  # in the axes of {link}
        R_0_link = sp.Matrix(Chain(robot).joint_chain.rotation(0, link)).xreplace(
            dict(zip(robot.joint_variables, robot.joint_values, strict=True)))
        rotated = sp.diag(R_0_link, R_0_link) * tip
        np.testing.assert_allclose(_numeric(robot, rotated)(q, qd),
                                   _numeric(robot, bias_acceleration(robot, 0, point, link=link))(q, qd), atol=1e-9)


def test_columns_after_the_link_are_zero_and_the_base_does_not_move():
    robot = _robot("stanford")
    for link in range(robot.n_joints + 1):
        J = jacobian(robot, 0, [1, 2, 3], "cross_product", link=link)
        assert J[:, link:] == sp.zeros(6, robot.n_joints - link)
        torques = force_propagation(robot, (1, 2, 3), link=link).torques
        assert torques[link:, :] == sp.zeros(robot.n_joints - link, 6)
    assert jacobian(robot, "tool", link=0) == sp.zeros(6, robot.n_joints)


def test_defaults_share_one_cache_entry_the_end_without_a_link_the_origin_with_one():
    chain = Chain(_robot("planar3r"))  # it has a tool: the end of the chain is the tool point, not the flange
    n = chain.n_joints
    J = jacobian(chain, 1, "wrist", link=n)
    kept = len(chain._memo)
    assert jacobian(chain, 1, link=n) == J == jacobian(chain, 1, (0, 0, 0), link=np.int64(n))
    assert jacobian(chain, 1, "flange") == J
    assert len(chain._memo) == kept  # link None and n, point "flange", "wrist" and (0, 0, 0) with link n: one key
    assert jacobian(chain, 1) == jacobian(chain, 1, "tool") != J
    assert jacobian(chain, 1, link=n - 1) != J and len(chain._memo) > kept  # the link is part of the key


def test_statics_and_positions_of_a_link_point():
    robot = _robot("scara")
    rng = np.random.default_rng(11)
    q = random_configuration(robot, rng)
    F = rng.uniform(-1, 1, 6)
    for link in range(robot.n_joints + 1):
        point = _point(rng)
        tau = joint_torques(robot, list(F), frame=0, point=point, link=link)
        expected = _reference(robot, q, link, point, 0).T @ F
        np.testing.assert_allclose(_numeric(robot, tau)(q)[:, 0], expected, atol=1e-6)
        p = np.append(np.array([float(c) for c in point]), 1.0)
        world = frames(robot, q)[link + 1] @ p
        np.testing.assert_allclose(_numeric(robot, point_position(robot, point, link))(q)[:, 0], world[:3],
                                   atol=1e-9)


@pytest.mark.parametrize(("call", "error", "message"), [
    (lambda r: jacobian(r, point="tool", link=2), FrameError, "fixed in the last link .4., not in link 2"),
    (lambda r: jacobian(r, point="wrist", link=1), FrameError, "'wrist' is the origin of frame"),
    (lambda r: hessian(r, link=5), ArgumentError, "link 5 does not exist for scara: use 0..4"),
    (lambda r: jacobian(r, link=True), ArgumentError, "link must be a whole number 0..4, got True"),
    (lambda r: jacobian(r, link="tool"), ArgumentError, "link must be a whole number 0..4, got 'tool'"),
    (lambda r: jacobian(r, link=1.5), ArgumentError, "link must be a whole number 0..4, got 1.5"),
    (lambda r: jacobian(r, point="x", link=3), FrameError, r"unknown point 'x': give .* frame \{3\}"),
    (lambda r: velocity_propagation(r, None, link=3), FrameError, "tool frame is fixed in the last link"),
    (lambda r: acceleration_propagation(r, None, link=0), FrameError, "tool frame is fixed in the last link"),
    (lambda r: joint_torques(r, point="tool", link=1), FrameError, "not in link 1"),
    (lambda r: jacobian(r, point=[1, 2], link=1), FrameError, r"3 coordinates in frame \{1\}, got 2"),
])
def test_named_points_belong_to_the_last_link(call, error, message):
    with pytest.raises(error, match=message):
        call(_robot("scara"))


def test_each_quantity_names_its_coupling_law():
    laws = {jacobian: "columns", jacobian_derivative: "columns", velocity_propagation: "columns",
            space_jacobian: "columns", force_propagation: "transposed", hessian: "congruent",
            bias_acceleration: "rates", acceleration_propagation: "rates", forward_kinematics: "rates"}
    assert set(LAW_NAMES) == set(COUPLING_LAWS) == set(laws.values())
    for function, name in laws.items():
        assert function.coupling_law is COUPLING_LAWS[name], function.__name__
    with pytest.raises(ArgumentError, match="unknown coupling law 'rows'; choose one of columns, transposed"):
        memoized(coupling="rows")


@settings(deadline=None, max_examples=12)
@given(robot=robots(max_joints=6), data=st.data())
def test_random_chains_every_method_on_a_random_link(robot, data):
    link = data.draw(st.integers(0, robot.n_joints), label="link")
    frame = data.draw(st.sampled_from(["world", 0, link, robot.n_joints, "tool"]), label="frame")
    point = data.draw(st.lists(st.sampled_from([0, sp.Rational(1, 4), sp.Rational(-2, 5), 1]), min_size=3,
                               max_size=3), label="point")
    q = random_configuration(robot, np.random.default_rng(robot.n_joints))
    _check_link_jacobians(robot, link, point, frame, q, simplify=False)


@settings(deadline=None, max_examples=8)
@given(robot=robots(max_joints=5), data=st.data())
def test_random_chains_hessian_of_a_link_point(robot, data):
    n = robot.n_joints
    link = data.draw(st.integers(1, n), label="link")
    frame = data.draw(st.sampled_from([0, link, n, "tool"]), label="frame")
    point = (sp.Rational(1, 3), 0, sp.Rational(-1, 2))
    q = random_configuration(robot, np.random.default_rng(n))
    J = _numeric(robot, jacobian(robot, frame, point, simplify=False, link=link))
    Hq = hessian(robot, frame, point, simplify=False, link=link)
    H_numeric = _numeric(robot, sp.Matrix(Hq.reshape(6, n * n).tolist()))(q).reshape(6, n, n)
    for m in range(n):
        step = np.zeros(n)
        step[m] = H
        np.testing.assert_allclose(H_numeric[:, :, m], (J(q + step) - J(q - step)) / (2 * H), atol=1e-5)


# --- the command line: --link ---------------------------------------------------------------------------------------


def _json(capsys, *argv: str) -> dict:
    import json

    from symjac.cli.main import main

    assert main([*argv, "--format", "json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize(("command", "derive"), [
    ("jacobian", lambda r, p: jacobian(r, 0, p, link=2)),
    ("torques", lambda r, p: joint_torques(r, frame=0, point=p, link=2)),
])
def test_the_command_line_prints_what_python_derives_for_a_link_point(capsys, command, derive):
    robot = _robot("planar3r")
    data = _json(capsys, command, "planar3r", "--link", "2", "--point", "0.1,0.2,0")
    expected = derive(robot, (sp.Rational(1, 10), sp.Rational(1, 5), 0))
    key = "entries" if command == "jacobian" else "torques"
    entries = data[key] if command == "jacobian" else [[entry] for entry in data[key]]
    assert data["link"] == 2 and sp.Matrix(entries).applyfunc(sp.sympify) == sp.Matrix(expected).applyfunc(
        lambda e: sp.sympify(str(e)))


def test_the_command_line_link_defaults_to_the_origin_and_says_where(capsys):
    from symjac.cli.main import main

    assert main(["jacobian", "planar3r", "--link", "1", "--format", "pretty"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("Basic Jacobian at the origin of frame {1} (fixed in link 1), differentiation")
    hessian_data = _json(capsys, "hessian", "planar3r", "--link", "1")
    assert hessian_data["link"] == 1 and all(entry == "0" for row in hessian_data["entries"] for col in row
                                             for entry in col[1:])  # joints 2, 3 move nothing of link 1
    for argv, message in ((["--representation", "zyz"], "--link does not apply with --representation"),
                          (["--point", "tool"], "fixed in the last link")):
        assert main(["jacobian", "planar3r", "--link", "1", *argv]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and message in err, err
