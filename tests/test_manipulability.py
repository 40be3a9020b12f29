"""Manipulability gradient: numeric (any arm, any rows) against differences of w(q), closed form against numeric.

Independent checks: central differences of w = sqrt(det(J J^T)) computed from the compiled Jacobian alone (no
Hessian), exact identities of the barrier terms (cot(theta5) for the PUMA 560's wrist, 2 / d3 for the Stanford
arm's squared prismatic factor), and gradient ascent that must increase w.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import random_configuration

from symjac import catalog, load_robot, urdf_catalog
from symjac.analysis.manipulability import log_det_gradient, manipulability_gradient
from symjac.analysis.spaces import task_rows
from symjac.errors import ArgumentError
from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import rows_from_names
from symjac.kinematics.numeric import numeric_jacobian
from symjac.symbolic.simplify import is_identity

H = 1e-6


@pytest.fixture(scope="module")
def robots():
    """Each robot loaded once (its chain, and so every compiled Jacobian and Hessian, is shared by the tests)."""
    return {name: load_robot(name) for name in [*catalog(), *urdf_catalog()]}


def manipulability(robot, q, rows, frame=0, point=None):
    if point is None:
        point = "tool" if robot.tool is not None else "wrist"
    J = numeric_jacobian(robot, q, frame, point)[list(rows)]
    return float(np.sqrt(np.linalg.det(J @ J.T)))


def regular_configuration(robot, rng, rows, frame=0, point=None, margin=1e-2):
    """A random configuration whose chosen rows are well away from a singularity."""
    if point is None:
        point = "tool" if robot.tool is not None else "wrist"
    for _ in range(50):
        q = random_configuration(robot, rng)
        sigma = np.linalg.svd(numeric_jacobian(robot, q, frame, point)[list(rows)], compute_uv=False)
        if sigma.min() > margin * max(sigma.max(), 1.0):
            return q
    raise AssertionError(f"no regular configuration of {robot.name} on rows {rows}")


def differences(robot, q, rows, frame=0, point=None):
    gradient = np.empty(robot.n_coordinates)
    for k in range(robot.n_coordinates):
        step = np.zeros(robot.n_coordinates)
        step[k] = H
        gradient[k] = (manipulability(robot, q + step, rows, frame, point)
                       - manipulability(robot, q - step, rows, frame, point)) / (2 * H)
    return gradient


# --- numeric gradient against differences ------------------------------------------------------------------------

CASES = [(name, None, 0) for name in [*catalog(), *urdf_catalog()]] + [
    ("panda", "v_x,v_y,v_z", 0),  # a redundant arm on its position rows (3 x 7)
    ("puma560", "v_x,v_y,omega_z", 3),  # a row subset in a moving frame: w is that of exactly those rows there
    ("ur5", ["omega_x", "omega_y", "omega_z"], "world"),
    ("planar3r", [0, 1], "tool"),
]


@pytest.mark.parametrize(("name", "rows", "frame"), marked(CASES), ids=lambda value: str(value))
def test_numeric_gradient_against_central_differences(robots, name, rows, frame):
    robot = robots[name]
    point = "tool" if robot.tool is not None else "wrist"
    chosen = task_rows(robot, point) if rows is None else (
        rows_from_names(rows) if isinstance(rows[0], str) or isinstance(rows, str) else tuple(rows))
    rng = np.random.default_rng(sum(map(ord, name)))
    for _ in range(2):
        q = regular_configuration(robot, rng, chosen, frame)
        w, gradient = manipulability_gradient(robot, q, frame, rows=rows)
        assert w == pytest.approx(manipulability(robot, q, chosen, frame), rel=1e-9)
        expected = differences(robot, q, chosen, frame)
        scale = max(np.abs(expected).max(), w)
        np.testing.assert_allclose(gradient, expected, rtol=1e-6, atol=1e-7 * scale, err_msg=f"{name} at {q}")


def test_gradient_stays_accurate_near_a_singularity(robots):
    """The SVD form never divides by the vanishing singular value: at theta5 = 1e-7 it matches w * cot(theta5)."""
    robot = robots["puma560"]
    q = np.array([0.3, -0.6, 0.4, 0.8, 1e-7, -0.5])
    w, gradient = manipulability_gradient(robot, q)
    assert 0 < w < 1e-7
    total = log_det_gradient(robot).total
    expected = np.array(sp.Matrix(total).xreplace({**dict(zip(robot.q, q, strict=True)), **robot.defaults}).evalf(),
                        dtype=float).ravel() * w
    np.testing.assert_allclose(gradient, expected, rtol=1e-6, atol=1e-9)


def test_gradient_ascent_increases_manipulability(robots):
    robot = robots["puma560"]
    q = np.array([0.2, -0.4, 0.3, 0.5, 0.15, 0.1])  # near the wrist singularity theta5 = 0
    values = []
    for _ in range(6):
        w, gradient = manipulability_gradient(robot, q)
        values.append(w)
        q = q + 0.05 * gradient / np.linalg.norm(gradient)
    assert all(later > earlier for earlier, later in itertools.pairwise(values))
    assert values[-1] > 1.2 * values[0]


# --- closed form for square Jacobians ----------------------------------------------------------------------------

SQUARE = [("puma560", None), ("stanford", None), ("planar2r", "v_x,v_y"), ("scara", None), ("articulated3r", None)]


@pytest.mark.parametrize(("name", "rows"), marked(SQUARE))
def test_closed_form_times_w_is_the_numeric_gradient(robots, name, rows):
    robot = robots[name]
    result = log_det_gradient(robot, rows)
    total = sp.Matrix(result.total)
    assert total == sum((sp.Matrix(term.gradient) for term in result.terms), sp.zeros(robot.n_coordinates, 1))
    rng = np.random.default_rng(7)
    for _ in range(3):
        q = regular_configuration(robot, rng, result.determinant.rows)
        w, gradient = manipulability_gradient(robot, q, rows=result.determinant.rows)
        values = {**dict(zip(robot.q, q, strict=True)), **robot.defaults}
        closed = np.array(total.xreplace(values).evalf(), dtype=float).ravel()
        np.testing.assert_allclose(w * closed, gradient, rtol=1e-8, atol=1e-10, err_msg=f"{name} at {q}")


def test_puma_wrist_barrier_is_cot_theta5(robots):
    robot = robots["puma560"]
    theta5 = robot.q[4]
    term = log_det_gradient(robot).term(sp.sin(theta5))
    assert term.multiplicity == 1
    assert term.gradient[4] == sp.cot(theta5)
    assert all(entry == 0 for k, entry in enumerate(term.gradient) if k != 4)
    # the elbow factor's term, checked as an identity: its numerator is the factor's derivative
    elbow = next(t for t in log_det_gradient(robot).terms if t.factor.has(robot.q[1]))
    basis = chain_of(robot).all_angle_bases()[0]
    for k in (1, 2):
        assert is_identity(sp.cancel(elbow.gradient[k] * elbow.factor), elbow.factor.diff(robot.q[k]), basis)


def test_stanford_squared_prismatic_factor_gives_two_over_d3(robots):
    robot = robots["stanford"]
    d3 = robot.q[2]
    term = log_det_gradient(robot).term("d3")
    assert term.multiplicity == 2
    assert term.gradient[2] == 2 / d3
    assert log_det_gradient(robot).term("sin(theta2)").gradient[1] == sp.cot(robot.q[1])


# --- errors ---------------------------------------------------------------------------------------------------------


def test_errors(robots):
    puma, panda, planar = robots["puma560"], robots["panda"], robots["planar2r"]
    q = [0.3, -0.6, 0.4, 0.8, 0.5, -0.5]
    with pytest.raises(ArgumentError, match="unknown row 'v_w'"):
        manipulability_gradient(puma, q, rows="v_x,v_w")
    with pytest.raises(ArgumentError, match="must not repeat"):
        manipulability_gradient(puma, q, rows=["v_x", "v_x"])
    with pytest.raises(ArgumentError, match=r"indices 0\.\.5"):
        manipulability_gradient(puma, q, rows=[0, 6])
    with pytest.raises(ArgumentError, match="choose at most 2 rows"):
        manipulability_gradient(planar, [0.1, 0.2], rows="v_x,v_y,omega_z")
    with pytest.raises(ArgumentError, match=r"singular on rows .* no gradient"):
        manipulability_gradient(puma, [0.3, -0.6, 0.4, 0.8, 0.0, -0.5])
    with pytest.raises(ArgumentError, match=r"q must have 6 entries"):
        manipulability_gradient(puma, [0.1] * 5)
    with pytest.raises(ArgumentError, match=r"square Jacobian.*6 x 7.*choose 7 rows, or use\s+manipulability_gradient"):
        log_det_gradient(panda)
    with pytest.raises(ArgumentError, match=r"square Jacobian.*choose 2 rows"):
        log_det_gradient(planar, "v_x")
    with pytest.raises(ArgumentError, match="not a singular factor"):
        log_det_gradient(planar).term("cos(theta1)")
