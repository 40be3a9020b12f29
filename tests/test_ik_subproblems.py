"""The Paden-Kahan subproblems: known rotations are recovered, every solution maps p where it must, and the symbolic
forms agree with the numeric ones."""

from __future__ import annotations

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from symjac.analysis.inverse_kinematics import (
    rotation_to_distance,
    rotation_to_distance_symbolic,
    rotation_to_plane,
    rotation_to_plane_symbolic,
    rotation_to_point,
    rotation_to_point_symbolic,
    slide_to_distance,
    slide_to_distance_symbolic,
    slide_to_point,
    slide_to_point_symbolic,
    two_rotations_to_point,
    two_rotations_to_point_symbolic,
)
from symjac.errors import ArgumentError

coordinates = st.floats(-2.0, 2.0, allow_nan=False)
points = st.tuples(coordinates, coordinates, coordinates).map(np.array)
angles = st.floats(-3.1, 3.1)
axes = points.filter(lambda x: np.linalg.norm(x) > 0.1).map(lambda x: x / np.linalg.norm(x))


def rotate(k: np.ndarray, theta: float, x: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Independent rotation (SciPy's rotation vector) about the axis k through r."""
    return Rotation.from_rotvec(theta * k).apply(x - r) + r


def same_angle(a: float, b: float) -> bool:
    return abs(np.angle(np.exp(1j * (a - b)))) < 1e-7


@settings(max_examples=150, deadline=None)
@given(axes, points, points, angles)
def test_rotation_to_point_recovers_the_angle(k, p, r, theta):
    if np.linalg.norm(np.cross(k, p - r)) < 1e-2:
        return
    q = rotate(k, theta, p, r)
    result = rotation_to_point(k, p, q, r)
    assert len(result.solutions) == 1 and not result.every_angle
    assert same_angle(result.solutions[0][0], theta)
    assert np.allclose(rotate(k, result.solutions[0][0], p, r), q, atol=1e-10)


@settings(max_examples=100, deadline=None)
@given(axes, points, points, st.floats(0.01, 1.0))
def test_rotation_to_point_reports_none_off_the_circle(k, p, q, offset):
    shifted = q + offset * k * max(1.0, np.linalg.norm(q))
    result = rotation_to_point(k, p + (k @ (q - p)) * k, shifted)  # p level with q, q lifted off its level
    assert result.solutions == () and "along the axis" in result.reason


def test_rotation_to_point_on_the_axis_takes_every_angle():
    result = rotation_to_point([0, 0, 1], [0, 0, 2], [0, 0, 2])
    assert result.every_angle and "every angle" in result.reason
    assert rotation_to_point([0, 0, 1], [0, 0, 2], [1, 0, 2]).solutions == ()


@settings(max_examples=150, deadline=None)
@given(axes, axes, points, points, angles, angles)
def test_two_rotations_recover_the_angles(k1, k2, p, r, theta1, theta2):
    if np.linalg.norm(np.cross(k1, k2)) < 0.1 or np.linalg.norm(np.cross(k2, p - r)) < 1e-2:
        return
    q = rotate(k1, theta1, rotate(k2, theta2, p, r), r)
    result = two_rotations_to_point(k1, k2, p, q, r)
    assert 1 <= len(result.solutions) <= 2
    for a1, a2 in result.solutions:
        assert np.allclose(rotate(k1, a1, rotate(k2, a2, p, r), r), q, atol=1e-10)
    middle = rotate(k2, theta2, p, r)
    if np.linalg.norm(np.cross(k1, middle - r)) > 1e-2:
        assert any(same_angle(a1, theta1) and same_angle(a2, theta2) for a1, a2 in result.solutions)


def test_two_rotations_count_and_refusals():
    x, y, z = np.eye(3)
    assert len(two_rotations_to_point(z, x, y, x).solutions) == 2  # y about x onto the circle, then about z
    assert len(two_rotations_to_point(z, x, x, x).solutions) == 1  # the two solutions merge
    assert two_rotations_to_point(z, x, x, 2 * x).solutions == ()  # different distances from the intersection
    assert two_rotations_to_point(z, x, x, z).solutions == ()  # z is out of reach: x stays on the circle x^2=1
    assert two_rotations_to_point(z, x, 0 * x, 0 * x).every_angle
    with pytest.raises(ArgumentError, match="parallel"):
        two_rotations_to_point(z, -z, x, y)
    with pytest.raises(ArgumentError, match="unit vector"):
        two_rotations_to_point(2 * z, x, x, y)


@settings(max_examples=150, deadline=None)
@given(axes, points, points, points, angles)
def test_rotation_to_distance_recovers_the_angle(k, p, q, r, theta):
    if min(np.linalg.norm(np.cross(k, p - r)), np.linalg.norm(np.cross(k, q - r))) < 1e-2:
        return
    delta = float(np.linalg.norm(rotate(k, theta, p, r) - q))
    result = rotation_to_distance(k, p, q, delta, r)
    assert 1 <= len(result.solutions) <= 2
    for (angle,) in result.solutions:
        assert abs(np.linalg.norm(rotate(k, angle, p, r) - q) - delta) < 1e-9
    if len(result.solutions) == 2:
        assert any(same_angle(angle, theta) for (angle,) in result.solutions)


def test_rotation_to_distance_boundaries():
    x, y, z = np.eye(3)
    assert len(rotation_to_distance(z, x, 2 * x, 1.0).solutions) == 1  # nearest: theta = 0
    assert len(rotation_to_distance(z, x, 2 * x, 3.0).solutions) == 1  # farthest: theta = pi
    assert len(rotation_to_distance(z, x, 2 * x, 2.0).solutions) == 2
    assert rotation_to_distance(z, x, 2 * x, 3.5).solutions == ()
    assert rotation_to_distance(z, x, 2 * x + 5 * z, 1.0).solutions == ()
    assert rotation_to_distance(z, z, x, np.sqrt(2)).every_angle
    with pytest.raises(ArgumentError, match="delta"):
        rotation_to_distance(z, x, y, -1.0)


def _symbols(name):
    return sympy.Matrix(sympy.symbols(f"{name}x {name}y {name}z", real=True))


K1, K2, P, Q, R = (_symbols(n) for n in ("k", "j", "p", "q", "r"))
DELTA = sympy.Symbol("delta", positive=True)
ARGS = [*K1, *K2, *P, *Q, *R, DELTA]


def _compiled(subproblem):
    """The solutions and the conditions' two sides' differences as NumPy functions, made once."""
    solutions = sympy.lambdify(ARGS, [list(s) for s in subproblem.solutions], "numpy")
    conditions = sympy.lambdify(ARGS, [c.lhs - c.rhs for c in subproblem.conditions], "numpy")
    return solutions, conditions


def _evaluate(compiled, values):
    with np.errstate(invalid="ignore"):  # sqrt(gamma^2) of a rounding-negative gamma^2 where two solutions merge
        return compiled[0](*values), compiled[1](*values)


SYMBOLIC = {
    "point": _compiled(rotation_to_point_symbolic(K1, P, Q, R)),
    "two": _compiled(two_rotations_to_point_symbolic(K1, K2, P, Q, R)),
    "distance": _compiled(rotation_to_distance_symbolic(K1, P, Q, DELTA, R)),
}


@settings(max_examples=60, deadline=None)
@given(axes, axes, points, points, angles, angles)
def test_symbolic_forms_equal_the_numeric_ones(k1, k2, p, r, theta1, theta2):
    if (
        np.linalg.norm(np.cross(k1, k2)) < 0.1
        or np.linalg.norm(np.cross(k1, p - r)) < 1e-2
        or np.linalg.norm(np.cross(k2, p - r)) < 1e-2
    ):
        return
    q1 = rotate(k1, theta1, p, r)
    values = [*k1, *k2, *p, *q1, *r, 0.0]
    solutions, conditions = _evaluate(SYMBOLIC["point"], values)
    assert np.allclose(conditions, 0.0, atol=1e-9)
    assert same_angle(solutions[0][0], rotation_to_point(k1, p, q1, r).solutions[0][0])

    q2 = rotate(k1, theta1, rotate(k2, theta2, p, r), r)
    values = [*k1, *k2, *p, *q2, *r, 0.0]
    solutions, conditions = _evaluate(SYMBOLIC["two"], values)
    numeric = two_rotations_to_point(k1, k2, p, q2, r).solutions
    assert abs(conditions[0]) < 1e-9 and conditions[1] >= -1e-9
    if len(numeric) == 2:
        for expected, found in zip(numeric, solutions, strict=True):
            assert same_angle(found[0], expected[0]) and same_angle(found[1], expected[1])

    q3 = rotate(k2, theta2, p, r)
    if np.linalg.norm(np.cross(k1, q3 - r)) < 1e-2:
        return
    delta = float(np.linalg.norm(rotate(k1, theta1, p, r) - q3))
    values = [*k1, *k2, *p, *q3, *r, delta]
    solutions, conditions = _evaluate(SYMBOLIC["distance"], values)
    numeric = rotation_to_distance(k1, p, q3, delta, r).solutions
    if len(numeric) == 2:
        assert min(conditions) >= -1e-9
        for expected, found in zip(numeric, solutions, strict=True):
            assert same_angle(found[0], expected[0])


# ---------------------------------------------------------------- rotation to a plane, the two slides


@settings(max_examples=150, deadline=None)
@given(axes, points, points, points, angles)
def test_rotation_to_plane_recovers_the_angle(k, p, h, r, theta):
    if np.linalg.norm(np.cross(k, p - r)) < 1e-2 or np.linalg.norm(h - k * (k @ h)) < 1e-2:
        return
    d = float(h @ rotate(k, theta, p, r))
    result = rotation_to_plane(k, p, h, d, r)
    assert 1 <= len(result.solutions) <= 2
    for (angle,) in result.solutions:
        assert abs(h @ rotate(k, angle, p, r) - d) < 1e-9
    if len(result.solutions) == 2:
        assert any(same_angle(angle, theta) for (angle,) in result.solutions)


def test_rotation_to_plane_boundaries():
    x, y, z = np.eye(3)
    assert len(rotation_to_plane(z, x, x, 0.5).solutions) == 2  # cos(theta) = 1/2
    assert len(rotation_to_plane(z, x, x, 1.0).solutions) == 1  # the plane touches the circle
    assert rotation_to_plane(z, x, x, 1.5).solutions == ()
    assert rotation_to_plane(z, z, x + z, 1.0).every_angle  # p on the axis, inside the plane
    assert rotation_to_plane(z, z, x, 1.0).solutions == ()  # p on the axis, off the plane
    with pytest.raises(ArgumentError, match="finite"):
        rotation_to_plane(z, x, y, float("nan"))


@settings(max_examples=100, deadline=None)
@given(axes, points, st.floats(-2.0, 2.0), points)
def test_slides_recover_the_displacement(k, p, s, q):
    target = p + s * k
    (found,), = slide_to_point(k, p, target).solutions
    assert abs(found - s) < 1e-9
    delta = float(np.linalg.norm(target - q))
    if np.linalg.norm(np.cross(k, target - q)) < 1e-3 and abs(k @ (target - q)) < 1e-3:
        return  # q within a millimetre of the line at the target: the tolerance (on squares) merges the two roots
    result = slide_to_distance(k, p, q, delta)
    for (value,) in result.solutions:
        assert abs(np.linalg.norm(p + value * k - q) - delta) < 1e-9
    assert any(abs(value - s) < 1e-6 for (value,) in result.solutions)


def test_out_of_range_reasons_give_the_range_reached():
    """No cosine or A, B, C in the reasons: the distances (or plane offsets) the rotation reaches, and the target."""
    x, y, z = np.eye(3)
    far = rotation_to_distance(z, x, 2 * y + z, 4.0)  # |rot(z, t) x - (2y + z)| runs from sqrt(2) to sqrt(10)
    assert far.solutions == ()
    assert far.reason == f"delta = 4 is outside the distances the rotation reaches, {2**0.5:.6g} to {10**0.5:.6g}"
    plane = rotation_to_plane(z, x + 3 * z, x + z, 5.0)  # h.x = cos(t) + 3 runs from 2 to 4
    assert plane.solutions == () and plane.reason == "h.x of the turned point reaches 2 to 4, not d = 5"


def test_slide_boundaries():
    # two slides 4e-6 apart stay two (the square-root argument, 4e-12, is below the tolerance, the slides are not)
    near = slide_to_distance(np.array([0.0, 1.0, 2e-6]), np.zeros(3), np.array([0.0, 0.0, 1.0]), 1.0).solutions
    assert len(near) == 2 and min(abs(value) for (value,) in near) < 1e-10
    x, y, z = np.eye(3)
    assert slide_to_point(z, x, x + z).solutions == ((1.0,),)
    assert slide_to_point(z, x, y).solutions == () and "off the line" in slide_to_point(z, x, y).reason
    assert len(slide_to_distance(z, x, 0 * x, 2.0).solutions) == 2
    assert slide_to_distance(z, x, 0 * x, 1.0).solutions == ((0.0,),)  # q as near as the line comes
    assert slide_to_distance(z, x, 0 * x, 0.5).solutions == ()
    with pytest.raises(ArgumentError, match="delta"):
        slide_to_distance(z, x, y, -1.0)


H, D = _symbols("h"), sympy.Symbol("d", real=True)
NEW = {
    "plane": (sympy.lambdify([*K1, *P, *H, D, *R], [list(s) for s in rotation_to_plane_symbolic(K1, P, H, D, R)
                                                     .solutions]), rotation_to_plane),
    "point": sympy.lambdify([*K1, *P, *Q], [list(s) for s in slide_to_point_symbolic(K1, P, Q).solutions]),
    "distance": sympy.lambdify([*K1, *P, *Q, DELTA], [list(s) for s in slide_to_distance_symbolic(K1, P, Q, DELTA)
                                                      .solutions]),
}


@settings(max_examples=60, deadline=None)
@given(axes, points, points, points, angles, st.floats(-2.0, 2.0))
def test_new_symbolic_forms_equal_the_numeric_ones(k, p, h, r, theta, s):
    if np.linalg.norm(np.cross(k, p - r)) < 1e-2 or np.linalg.norm(h - k * (k @ h)) < 1e-2:
        return
    d = float(h @ rotate(k, theta, p, r))
    numeric = rotation_to_plane(k, p, h, d, r).solutions
    with np.errstate(invalid="ignore"):
        symbolic = NEW["plane"][0](*k, *p, *h, d, *r)
    if len(numeric) == 2:
        for expected, found in zip(numeric, symbolic, strict=True):
            assert same_angle(found[0], expected[0])
    target = p + s * k
    assert abs(NEW["point"](*k, *p, *target)[0][0] - s) < 1e-9
    delta = float(np.linalg.norm(target - r))
    numeric = slide_to_distance(k, p, r, delta).solutions
    if len(numeric) == 2:
        assert np.allclose(NEW["distance"](*k, *p, *r, delta), numeric, atol=1e-9)
