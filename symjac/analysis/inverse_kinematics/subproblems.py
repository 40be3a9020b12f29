"""The Paden-Kahan subproblems: the geometric steps closed-form inverse kinematics is built from.

Each rotation is about a unit axis ``k`` through a point ``r`` (the origin unless given). With ``u = p - r`` and
``v = q - r``, the parts of ``u`` and ``v`` across the axis are ``u' = u - k (k.u)`` and ``v' = v - k (k.v)``; two
identities keep the formulas short: ``u'.v' = u.v - (k.u)(k.v)`` and ``k.(u' x v') = k.(u x v)``.

- **Rotation to a point** (subproblem 1): the angle ``theta`` with ``rot(k, theta) u = v``,
  ``theta = atan2(k.(u x v), u.v - (k.u)(k.v))``, when ``k.u = k.v`` and ``|u'| = |v'|``; every angle works when ``p``
  lies on the axis.
- **Two rotations to a point** (subproblem 2): ``rot(k1, theta1) rot(k2, theta2) u = v`` for axes meeting at ``r``.
  The middle point ``c = rot(k2, theta2) u`` is ``alpha k1 + beta k2 + gamma (k1 x k2)`` with
  ``alpha = (k1.v - w k2.u) / (1 - w^2)``, ``beta = (k2.u - w k1.v) / (1 - w^2)``, ``w = k1.k2`` and
  ``gamma^2 = |k1 x v|^2 / |k1 x k2|^2 - beta^2`` (not ``(|u|^2 - alpha^2 - ...) / ...``: it cancels near a wrist
  singularity); zero, one or two solutions by its sign (and ``|u| = |v|``), each then two rotations to a point.
- **Rotation to a distance** (subproblem 3): ``|rot(k, theta) u - v| = delta``. Across the axis the distance is
  ``delta'^2 = delta^2 - (k.(u - v))^2``, and ``theta = theta0 -+ atan2(sqrt(1 - c^2), c)`` with ``theta0`` the angle
  from ``u'`` to ``v'`` and ``c = (|u'|^2 + |v'|^2 - delta'^2) / (2 |u'| |v'|)``; zero, one or two solutions.
- **Rotation to a plane** (subproblem 4): ``h.(r + rot(k, theta) u) = d``. With ``A = h.u'``, ``B = h.(k x u)`` and
  ``C = d - h.r - (k.u)(k.h)`` it reads ``A cos(theta) + B sin(theta) = C``, so
  ``theta = atan2(A, -B) - atan2(C, -+sqrt(A^2 + B^2 - C^2))`` (the textbook form); zero, one or two solutions.
- **Slides** to a point, ``p + s k = q``: ``s = k.(q - p)`` when ``q - p`` is along ``k``; to a distance,
  ``|p + s k - q| = delta`` with ``u = p - q``: ``s = -k.u -+ sqrt(delta^2 - |u'|^2)``, zero, one or two solutions.

Each is a numeric function (floats, every solution, a tolerance for existence, one solution where two merge) and a
``_symbolic`` one giving a :class:`Subproblem`: SymPy solutions with ``atan2`` and their existence conditions.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from symjac.errors import ArgumentError

__all__ = ["AngleSolutions", "Subproblem", "rotation_to_distance", "rotation_to_distance_symbolic",
           "rotation_to_plane", "rotation_to_plane_symbolic", "rotation_to_point", "rotation_to_point_symbolic",
           "slide_to_distance", "slide_to_distance_symbolic", "slide_to_point", "slide_to_point_symbolic",
           "two_rotations_to_point", "two_rotations_to_point_symbolic"]


@dataclass(frozen=True)
class AngleSolutions:
    """Numeric solutions of a subproblem.

    ``solutions`` holds one tuple of angles per solution (``(theta,)``, or ``(theta1, theta2)`` for two rotations),
    empty when there is none; ``reason`` then says why. ``every_angle`` is true when the point lies on the axis, so
    that any angle works (the solutions list ``0`` as a representative).
    """

    solutions: tuple[tuple[float, ...], ...]
    reason: str = ""
    every_angle: bool = False


@dataclass(frozen=True)
class Subproblem:
    """A subproblem solved symbolically.

    ``solutions`` holds one tuple of SymPy expressions per solution; ``conditions`` the SymPy relations
    (``Eq(a, b)`` or ``a >= 0``) under which the solutions exist.
    """

    solutions: tuple[tuple[sympy.Expr, ...], ...]
    conditions: tuple[sympy.Basic, ...]


# ---------------------------------------------------------------- numeric


Vector = tuple[float, float, float]  # the numeric subproblems work on tuples: a tenth of NumPy's cost on one 3-vector


def _dot(a: Vector, b: Vector) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: Vector, b: Vector) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _minus(a: Vector, b: Vector) -> Vector:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _combination(*terms: tuple[float, Vector]) -> Vector:
    """``sum(c v)`` over ``(c, v)`` pairs."""
    return (sum(c * v[0] for c, v in terms), sum(c * v[1] for c, v in terms), sum(c * v[2] for c, v in terms))


def _norm(a: Vector) -> float:
    return math.sqrt(_dot(a, a))


def _vector(value: Any, name: str) -> Vector:
    try:
        x, y, z = value.tolist() if isinstance(value, np.ndarray) else value
        vector = (float(x), float(y), float(z))
    except (TypeError, ValueError):
        vector = (math.nan, math.nan, math.nan)
    if not (math.isfinite(vector[0]) and math.isfinite(vector[1]) and math.isfinite(vector[2])):
        raise ArgumentError(f"subproblem argument {name}: expected 3 finite numbers, got {value!r}")
    return vector


def _axis(value: Any, name: str) -> Vector:
    axis = _vector(value, name)
    if abs(_norm(axis) - 1.0) > 1e-9:
        raise ArgumentError(f"subproblem argument {name}: the axis must be a unit vector, norm {_norm(axis):.12g}")
    return axis


def _number(value: Any, what: str, distance: bool = False) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or (distance and number < 0):
        raise ArgumentError(f"{what} must be a finite {'distance >= 0' if distance else 'number'}, got {value!r}")
    return number


def _relative(p: Any, q: Any, point: Any) -> tuple[Vector, Vector]:
    r = (0.0, 0.0, 0.0) if point is None else _vector(point, "point on the axis")
    return _minus(_vector(p, "p"), r), _minus(_vector(q, "q"), r)


def _angle_across(k: Vector, u: Vector, v: Vector) -> float:
    """The angle about ``k`` from ``u'`` to ``v'``: ``atan2(k.(u' x v'), u'.v')`` (``u.v - (k.u)(k.v)`` cancels)."""
    a, b = _combination((1.0, u), (-_dot(k, u), k)), _combination((1.0, v), (-_dot(k, v), k))
    return math.atan2(_dot(k, _cross(a, b)), _dot(a, b))


_ROUNDING = 256 * sys.float_info.epsilon  # 1 - |cos| this small is rounding: one merged solution (3.4e-7 rad)


def _scale(*lengths: float) -> float:
    return max(1.0, *lengths)


def rotation_to_point(k: Any, p: Any, q: Any, point_on_axis: Any = None, tolerance: float = 1e-9) -> AngleSolutions:
    """Subproblem 1: the angle of the rotation about ``k`` taking ``p`` to ``q``.

    The axis ``k`` is a unit vector through ``r = point_on_axis``;
    ``theta = atan2(k.(u x v), u.v - (k.u)(k.v))`` with ``u = p - r``, ``v = q - r``.

    Solvable when ``k.u = k.v`` and ``|u'| = |v'|`` (to ``tolerance`` times the larger of 1 and the lengths).
    """
    k = _axis(k, "k")
    u, v = _relative(p, q, point_on_axis)
    scale = tolerance * _scale(_norm(u), _norm(v))
    ku, kv = _dot(k, u), _dot(k, v)
    if abs(ku - kv) > scale:
        return AngleSolutions((), f"p and q differ along the axis by {kv - ku:.6g}")
    across_u = _norm(_combination((1.0, u), (-ku, k)))  # not sqrt(|u|^2 - (k.u)^2): 1e-8 of rounding near the axis
    across_v = _norm(_combination((1.0, v), (-kv, k)))
    if abs(across_u - across_v) > scale:
        return AngleSolutions((), f"p and q lie at distances {across_u:.6g} and {across_v:.6g} from the axis")
    if across_u <= scale:
        return AngleSolutions(((0.0,),), "p lies on the axis: every angle works", every_angle=True)
    return AngleSolutions(((_angle_across(k, u, v),),))


def two_rotations_to_point(k1: Any, k2: Any, p: Any, q: Any, intersection: Any = None,
                           tolerance: float = 1e-9) -> AngleSolutions:
    """Subproblem 2: two rotations about axes that meet, taking ``p`` to ``q``.

    The angles ``(theta1, theta2)`` satisfy ``rot(k1, theta1) rot(k2, theta2) (p - r) = q - r`` for unit
    axes ``k1``, ``k2`` meeting at ``r = intersection``: first ``theta2`` about ``k2``, then ``theta1`` about ``k1``.

    The middle point is ``c = alpha k1 + beta k2 + gamma (k1 x k2)`` (formulas in the module docstring); there are two
    solutions when ``gamma^2 > 0``, one when ``gamma^2 = 0`` (within ``tolerance``), none otherwise or when
    ``|p - r| != |q - r|``. Parallel axes raise :class:`~symjac.errors.ArgumentError`.
    """
    k1, k2 = _axis(k1, "k1"), _axis(k2, "k2")
    normal = _cross(k1, k2)
    if _norm(normal) <= 1e-9:
        raise ArgumentError("two rotations to a point: the axes k1 and k2 are parallel; the subproblem needs axes "
                            "that meet in one point")
    u, v = _relative(p, q, intersection)
    length_u, length_v = _norm(u), _norm(v)
    scale = tolerance * _scale(length_u, length_v)
    if abs(length_u - length_v) > scale:
        return AngleSolutions((), f"p and q lie at distances {length_u:.6g} and {length_v:.6g} from the meeting point")
    if length_u <= scale:
        return AngleSolutions(((0.0, 0.0),), "p is the intersection point: every pair of angles works", True)
    w = _dot(k1, k2)
    alpha = (_dot(k1, v) - w * _dot(k2, u)) / (1.0 - w * w)
    beta = (_dot(k2, u) - w * _dot(k1, v)) / (1.0 - w * w)
    # gamma^2 from the smaller circle, e.g. about k1: |v'|^2 = (beta^2 + gamma^2) |k1 x k2|^2 (accurate near a wrist
    # singularity, where |u|^2 - alpha^2 - ... cancels); the two solutions merge at a half angle of rounding's size
    radius, side = min((_norm(_cross(k1, v)), beta), (_norm(_cross(k2, u)), alpha))
    gamma_squared = radius**2 / _dot(normal, normal) - side**2
    if gamma_squared < -scale * _scale(length_u):
        return AngleSolutions((), f"no middle point: gamma^2 = {gamma_squared:.6g} < 0")
    root = math.sqrt(max(gamma_squared, 0.0))
    merged = root <= scale or root * _norm(normal) <= math.sqrt(2 * _ROUNDING) * radius
    gammas = (0.0,) if merged else (root, -root)
    solutions = []
    for gamma in gammas:
        middle = _combination((alpha, k1), (beta, k2), (gamma, normal))
        solutions.append((_angle_across(k1, middle, v), _angle_across(k2, u, middle)))
    return AngleSolutions(tuple(solutions))


def rotation_to_distance(k: Any, p: Any, q: Any, delta: float, point_on_axis: Any = None,
                         tolerance: float = 1e-9) -> AngleSolutions:
    """Subproblem 3: the angles ``theta`` with ``|rot(k, theta) (p - r) - (q - r)| = delta``.

    ``theta = theta0 -+ atan2(sqrt(1 - c^2), c)`` with ``theta0`` the angle from ``u'`` to ``v'`` and
    ``c = (|u'|^2 + |v'|^2 - delta'^2) / (2 |u'| |v'|)``, ``delta'^2 = delta^2 - (k.(u - v))^2``: two solutions when
    ``|c| < 1``, one when ``|c| = 1`` (within ``tolerance``), none otherwise.
    """
    k = _axis(k, "k")
    u, v = _relative(p, q, point_on_axis)
    delta = _number(delta, "rotation to a distance: delta", distance=True)
    scale = tolerance * _scale(_norm(u), _norm(v), delta)
    ku, kv = _dot(k, u), _dot(k, v)
    delta_across_squared = delta**2 - (ku - kv) ** 2
    across_u_squared = max(_dot(u, u) - ku**2, 0.0)
    across_v_squared = max(_dot(v, v) - kv**2, 0.0)
    if delta_across_squared < -scale:
        return AngleSolutions((), f"p and q differ along the axis by more than delta = {delta:.6g}")
    if across_u_squared <= scale**2 or across_v_squared <= scale**2:
        if abs(across_u_squared + across_v_squared - delta_across_squared) <= scale:
            return AngleSolutions(((0.0,),), "p or q lies on the axis: every angle gives the same distance", True)
        return AngleSolutions((), "p or q lies on the axis and the distance is not delta")
    product = 2.0 * math.sqrt(across_u_squared * across_v_squared)
    c = (across_u_squared + across_v_squared - max(delta_across_squared, 0.0)) / product
    if abs(c) > 1.0 + scale:
        low, high = (math.hypot(ku - kv, math.sqrt(across_u_squared) + sign * math.sqrt(across_v_squared))
                     for sign in (-1.0, 1.0))
        return AngleSolutions((), f"delta = {delta:.6g} is outside the distances the rotation reaches, {low:.6g} to "
                                  f"{high:.6g}")
    theta0 = _angle_across(k, u, v)
    sine = math.sqrt(max(1.0 - c * c, 0.0))
    if sine <= scale or 1.0 - abs(c) <= _ROUNDING:  # they coincide, to what rounding in c can resolve
        return AngleSolutions(((theta0 - math.atan2(0.0, math.copysign(1.0, c)),),))
    half = math.atan2(sine, c)
    return AngleSolutions(((theta0 - half,), (theta0 + half,)))


def rotation_to_plane(k: Any, p: Any, h: Any, d: float, point_on_axis: Any = None,
                      tolerance: float = 1e-9) -> AngleSolutions:
    """Subproblem 4: the angles ``theta`` with ``h.(r + rot(k, theta) (p - r)) = d``.

    ``A cos(theta) + B sin(theta) = C`` with ``A = h.u'``, ``B = h.(k x u)``, ``C = d - h.r - (k.u)(k.h)``, so
    ``theta = atan2(A, -B) - atan2(C, -+sqrt(A^2 + B^2 - C^2))``: two solutions when ``C^2 < A^2 + B^2``, one when they
    are equal (within ``tolerance``), none otherwise; every angle when ``A = B = C = 0``. ``h`` need not be a unit
    vector.
    """
    k = _axis(k, "k")
    h = _vector(h, "h")
    r = (0.0, 0.0, 0.0) if point_on_axis is None else _vector(point_on_axis, "point on the axis")
    u = _minus(_vector(p, "p"), r)
    d = _number(d, "rotation to a plane: d")
    ku, kh = _dot(k, u), _dot(k, h)
    a = _dot(h, u) - ku * kh
    b = _dot(h, _cross(k, u))
    c = d - _dot(h, r) - ku * kh
    size = _scale(_norm(u), _norm(h), abs(d)) * _scale(_norm(h))  # A, B and C scale like |h| times a length
    radius = math.hypot(a, b)
    if radius <= tolerance * size:
        if abs(c) <= tolerance * size:
            return AngleSolutions(((0.0,),), "p lies on the axis and the plane holds it: every angle works",
                                  every_angle=True)
        return AngleSolutions((), f"the rotation does not move p across the plane, which it misses by {c:.6g}")
    theta0 = math.atan2(a, -b)
    if abs(c) > radius + tolerance * size:
        return AngleSolutions((), f"h.x of the turned point reaches {d - c - radius:.6g} to {d - c + radius:.6g}, "
                                  f"not d = {d:.6g}")
    root = math.sqrt(max(radius * radius - c * c, 0.0))
    if root <= tolerance * size or radius - abs(c) <= _ROUNDING * radius:  # they coincide, to rounding
        return AngleSolutions(((theta0 - math.atan2(c, 0.0),),))
    return AngleSolutions(((theta0 - math.atan2(c, -root),), (theta0 - math.atan2(c, root),)))


def slide_to_point(k: Any, p: Any, q: Any, tolerance: float = 1e-9) -> AngleSolutions:
    """A slide along ``k`` taking ``p`` to ``q``: ``s = k.(q - p)``, when ``q - p - s k = 0`` (within ``tolerance``)."""
    k = _axis(k, "k")
    u = _minus(_vector(q, "q"), _vector(p, "p"))
    s = _dot(k, u)
    miss = _norm(_combination((1.0, u), (-s, k)))
    if miss > tolerance * _scale(_norm(u)):
        return AngleSolutions((), f"q lies {miss:.6g} off the line through p along k")
    return AngleSolutions(((s,),))


def slide_to_distance(k: Any, p: Any, q: Any, delta: float, tolerance: float = 1e-9) -> AngleSolutions:
    """The slides ``s`` along ``k`` with ``|p + s k - q| = delta``: ``s = -k.u -+ sqrt(delta^2 - |u'|^2)``, u = p - q.

    Two solutions when ``delta`` exceeds the distance ``|u'|`` from ``q`` to the line, one when it equals it (within
    ``tolerance``), none when it is shorter.
    """
    k = _axis(k, "k")
    u = _minus(_vector(p, "p"), _vector(q, "q"))
    delta = _number(delta, "slide to a distance: delta", distance=True)
    along = _dot(k, u)
    across_squared = max(_dot(u, u) - along**2, 0.0)
    discriminant = delta**2 - across_squared
    scale = tolerance * _scale(_norm(u), delta)
    if discriminant < -scale:
        gap = math.sqrt(across_squared) - delta
        return AngleSolutions((), f"q lies {gap:.6g} farther from the line than delta = {delta:.6g}")
    root = math.sqrt(max(discriminant, 0.0))  # one solution only where the two coincide
    if root <= scale or discriminant <= _ROUNDING * _scale(delta, _norm(u)) ** 2:
        return AngleSolutions(((-along,),))
    return AngleSolutions(((-along - root,), (-along + root,)))


# ---------------------------------------------------------------- symbolic


def _matrix(value: Any, name: str) -> sympy.Matrix:
    matrix = sympy.Matrix(value)
    if matrix.shape not in ((3, 1), (1, 3)):
        raise ArgumentError(f"subproblem argument {name}: expected 3 entries, got shape {matrix.shape}")
    return matrix.reshape(3, 1)


def _relative_symbolic(p: Any, q: Any, point: Any) -> tuple[sympy.Matrix, sympy.Matrix]:
    r = sympy.zeros(3, 1) if point is None else _matrix(point, "point on the axis")
    return _matrix(p, "p") - r, _matrix(q, "q") - r


def _angle_across_symbolic(k: sympy.Matrix, u: sympy.Matrix, v: sympy.Matrix) -> sympy.Expr:
    return sympy.atan2(k.dot(u.cross(v)), u.dot(v) - k.dot(u) * k.dot(v))


def rotation_to_point_symbolic(k: Any, p: Any, q: Any, point_on_axis: Any = None) -> Subproblem:
    """Subproblem 1 in symbols.

    ``theta = atan2(k.(u x v), u.v - (k.u)(k.v))`` under the conditions ``k.u = k.v`` and
    ``|u'|^2 = |v'|^2`` (``|u'|^2 = u.u - (k.u)^2``); ``k`` is taken to be a unit vector.
    """
    k = _matrix(k, "k")
    u, v = _relative_symbolic(p, q, point_on_axis)
    conditions = (sympy.Eq(k.dot(u), k.dot(v), evaluate=False),
                  sympy.Eq(u.dot(u) - k.dot(u) ** 2, v.dot(v) - k.dot(v) ** 2, evaluate=False))
    return Subproblem(((_angle_across_symbolic(k, u, v),),), conditions)


def two_rotations_to_point_symbolic(k1: Any, k2: Any, p: Any, q: Any, intersection: Any = None) -> Subproblem:
    """Subproblem 2 in symbols.

    Two solutions ``(theta1, theta2)``, one for each sign of ``gamma = +-sqrt(gamma^2)``, under the conditions
    ``|u|^2 = |v|^2`` and ``gamma^2 >= 0`` (module docstring); ``k1`` and ``k2`` are unit vectors, not parallel.
    """
    k1, k2 = _matrix(k1, "k1"), _matrix(k2, "k2")
    u, v = _relative_symbolic(p, q, intersection)
    normal = k1.cross(k2)
    w = k1.dot(k2)
    alpha = (k1.dot(v) - w * k2.dot(u)) / (1 - w**2)
    beta = (k2.dot(u) - w * k1.dot(v)) / (1 - w**2)
    # gamma^2 from the circle about k1 through v, |k1 x v|^2 = (beta^2 + gamma^2) |k1 x k2|^2 (about k2 through u where
    # alpha is 0 and beta not): |u|^2 - alpha^2 - ... cancels near a wrist singularity (PUMA: 1 - q4_z^2 for theta5)
    axis, point, side = (k2, u, alpha) if sympy.expand(alpha) == 0 != sympy.expand(beta) else (k1, v, beta)
    gamma_squared = axis.cross(point).dot(axis.cross(point)) / normal.dot(normal) - side**2
    solutions = []
    for sign in (1, -1):
        middle = alpha * k1 + beta * k2 + sign * sympy.sqrt(gamma_squared) * normal
        solutions.append((_angle_across_symbolic(k1, middle, v), _angle_across_symbolic(k2, u, middle)))
    conditions = (sympy.Eq(u.dot(u), v.dot(v), evaluate=False), sympy.Ge(gamma_squared, 0, evaluate=False))
    return Subproblem(tuple(solutions), conditions)


def rotation_to_distance_symbolic(k: Any, p: Any, q: Any, delta: Any, point_on_axis: Any = None) -> Subproblem:
    """Subproblem 3 in symbols.

    ``theta = theta0 -+ atan2(sqrt(D), N)`` with ``N = |u'|^2 + |v'|^2 - delta'^2`` and ``D = 4 |u'|^2 |v'|^2 - N^2``
    (the module docstring's ``c = N / (2 |u'| |v'|)``, both atan2 arguments scaled by ``2 |u'| |v'|``), under the
    conditions ``delta'^2 >= 0`` and ``D >= 0``; ``k`` is a unit vector.
    """
    k = _matrix(k, "k")
    u, v = _relative_symbolic(p, q, point_on_axis)
    delta = sympy.sympify(delta)
    delta_across_squared = delta**2 - k.dot(u - v) ** 2
    across_u_squared = u.dot(u) - k.dot(u) ** 2
    across_v_squared = v.dot(v) - k.dot(v) ** 2
    n = across_u_squared + across_v_squared - delta_across_squared
    d = 4 * across_u_squared * across_v_squared - n**2
    theta0 = _angle_across_symbolic(k, u, v)
    half = sympy.atan2(sympy.sqrt(d), n)
    conditions = (sympy.Ge(delta_across_squared, 0, evaluate=False), sympy.Ge(d, 0, evaluate=False))
    return Subproblem(((theta0 - half,), (theta0 + half,)), conditions)


def rotation_to_plane_symbolic(k: Any, p: Any, h: Any, d: Any, point_on_axis: Any = None) -> Subproblem:
    """Subproblem 4 in symbols.

    ``theta = atan2(A, -B) - atan2(C, -+sqrt(A^2 + B^2 - C^2))`` under the condition
    ``A^2 + B^2 - C^2 >= 0`` (``A``, ``B``, ``C`` as in the module docstring); ``k`` is a unit vector.
    """
    k, h = _matrix(k, "k"), _matrix(h, "h")
    r = sympy.zeros(3, 1) if point_on_axis is None else _matrix(point_on_axis, "point on the axis")
    u = _matrix(p, "p") - r
    a = h.dot(u) - k.dot(u) * k.dot(h)
    b = h.dot(k.cross(u))
    c = sympy.sympify(d) - h.dot(r) - k.dot(u) * k.dot(h)
    root, theta0 = sympy.sqrt(a**2 + b**2 - c**2), sympy.atan2(a, -b)
    return Subproblem(((theta0 - sympy.atan2(c, -root),), (theta0 - sympy.atan2(c, root),)),
                      (sympy.Ge(a**2 + b**2 - c**2, 0, evaluate=False),))


def slide_to_point_symbolic(k: Any, p: Any, q: Any) -> Subproblem:
    """A slide to a point in symbols: ``s = k.(q - p)`` under the condition ``|q - p|^2 = (k.(q - p))^2``."""
    k, u = _matrix(k, "k"), _matrix(q, "q") - _matrix(p, "p")
    return Subproblem(((k.dot(u),),), (sympy.Eq(u.dot(u), k.dot(u) ** 2, evaluate=False),))


def slide_to_distance_symbolic(k: Any, p: Any, q: Any, delta: Any) -> Subproblem:
    """A slide to a distance in symbols: ``s = -k.u -+ sqrt(delta^2 - |u'|^2)`` under ``delta^2 - |u'|^2 >= 0``."""
    k, u = _matrix(k, "k"), _matrix(p, "p") - _matrix(q, "q")
    discriminant = sympy.sympify(delta) ** 2 - (u.dot(u) - k.dot(u) ** 2)
    root, along = sympy.sqrt(discriminant), k.dot(u)
    return Subproblem(((-along - root,), (-along + root,)), (sympy.Ge(discriminant, 0, evaluate=False),))
