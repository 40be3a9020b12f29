r"""MJCF numbers and frames, exactly: ``pos`` with one of ``quat``, ``axisangle``, ``euler``, ``xyaxes``, ``zaxis``.

Every number becomes the exact rational it is written as (:func:`~symjac.model.expressions.exact_number`); an angle
in degrees (MJCF's default, ``<compiler angle="degree">``) becomes :math:`x\,\pi/180` exactly (``90 -> pi/2``), an
angle in radians is snapped to a multiple of :math:`\pi/12` when within 1e-9 of one
(:func:`~symjac.model.expressions.snap_angle`). The rotations are MuJoCo's:

``quat="w x y z"``
    normalised by MuJoCo; its matrix :math:`R = I + 2 (w [v]_\times + [v]_\times^2) / |q|^2` is rational when the
    entries are, so no square root is needed.
``axisangle="x y z a"``
    a turn by ``a`` about the normalised axis (Rodrigues' formula).
``euler="a b c"``
    three turns about the axes ``<compiler eulerseq>`` names (default ``xyz``): a lower-case letter turns about the
    moving frame's axis (post-multiplied), an upper-case one about the fixed frame's (pre-multiplied).
``xyaxes="x1 x2 x3 y1 y2 y3"``
    the frame's x axis, and its y axis made orthogonal to x (Gram-Schmidt), both normalised; z is their cross product.
``zaxis="z1 z2 z3"``
    the smallest turn taking (0, 0, 1) onto the normalised vector (a half turn about x for the opposite direction).
``fromto="a1 a2 a3 b1 b2 b3"`` (sites of capsule, cylinder, box or ellipsoid type)
    the frame at the midpoint of a and b, its z axis along a - b (MuJoCo's direction, from the end to the start) as
    for ``zaxis``; it overrides ``pos`` and the orientation.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import sympy as sp

from symjac.errors import ExpressionError, RobotFileError
from symjac.model.bounds import size_problem
from symjac.model.expressions import exact_number, snap_angle
from symjac.symbolic.transforms import homogeneous, skew

__all__ = ["MAX_NUMBER", "ORIENTATIONS", "Compiler", "angle", "frame", "numbers", "rotation_about"]

ORIENTATIONS = ("quat", "axisangle", "euler", "xyaxes", "zaxis")
"""The attributes that give an MJCF frame's orientation (at most one per element)."""
_SIZES = {"quat": 4, "axisangle": 4, "euler": 3, "xyaxes": 6, "zaxis": 3}
_MAX_DIGITS = 40
MAX_NUMBER = 1e9
"""Largest number in size an MJCF attribute may hold that is no length (a quaternion entry, a mass, a coefficient)."""


@dataclass(frozen=True)
class Compiler:
    """The ``<compiler>`` settings the kinematics depends on (MuJoCo's defaults)."""

    degree: bool = True
    eulerseq: str = "xyz"
    autolimits: bool = True
    inertia_from_geoms: bool = False  # inertiafromgeom="true": MuJoCo replaces every <inertial> by the geoms'


def _fail(source: str, message: str, element: str | None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def numbers(text: str, count: int | tuple[int, ...], source: str, element: str, *,
            length: bool = True) -> list[sp.Rational]:
    """The ``count`` exact numbers of an attribute: finite, a ``length`` at most 1000 m, others :data:`MAX_NUMBER`."""
    parts = text.split()
    counts = (count,) if isinstance(count, int) else count
    if len(parts) not in counts:
        wanted = " or ".join(str(c) for c in counts)
        raise _fail(source, f"expected {wanted} numbers, got {text[:60]!r}", element)
    values = []
    for token in parts:
        if len(token) > _MAX_DIGITS:
            raise _fail(source, f"number too long: {token[:_MAX_DIGITS]!r}...", element)
        try:
            value = exact_number(float(token))
        except (ValueError, ExpressionError):
            raise _fail(source, f"expected a finite number, got {token!r}", element) from None
        problem = size_problem(float(value), angle=False) if length else \
            f"{float(value):.6g} is larger than {MAX_NUMBER:.0e} in size" if abs(value) > MAX_NUMBER else None
        if problem is not None:
            raise _fail(source, problem, element)
        values.append(value)
    return values


def angle(value: sp.Rational, compiler: Compiler, source: str, element: str) -> sp.Expr:
    """An angle of the file in radians, exactly: degrees times pi/180, or radians snapped (refused beyond 1000 rad)."""
    radians = float(value) * (math.pi / 180 if compiler.degree else 1.0)
    problem = size_problem(radians, angle=True)
    if problem is not None:
        unit = "degrees" if compiler.degree else "radians (<compiler angle=\"radian\">)"
        raise _fail(source, f"{float(value):.6g} is too large an angle in {unit}", element)
    return value * sp.pi / 180 if compiler.degree else snap_angle(value)


def rotation_about(axis: list[sp.Expr], turn: sp.Expr) -> sp.Matrix:
    r"""The turn by ``turn`` about ``axis`` (not zero): :math:`I + \sin a\,[k]_\times + (1 - \cos a)[k]_\times^2`."""
    norm = sp.sqrt(sum(v**2 for v in axis))
    K = skew([sp.radsimp(v / norm) for v in axis])
    return (sp.eye(3) + sp.sin(turn) * K + (1 - sp.cos(turn)) * K * K).applyfunc(sp.expand)


def _unit(values: list[sp.Expr], source: str, element: str) -> list[sp.Expr]:
    norm = sp.sqrt(sum(v**2 for v in values))
    if norm == 0 or float(norm) < 1e-12:
        raise _fail(source, "the direction must not be the zero vector", element)
    return [sp.radsimp(v / norm) for v in values]


def _quaternion(values: list[sp.Expr], source: str, element: str) -> sp.Matrix:
    norm2 = sum(v**2 for v in values)
    if norm2 == 0 or float(norm2) < 1e-24:
        raise _fail(source, "a quaternion must not be zero", element)
    w, *vector = values
    K = skew(vector)
    return (sp.eye(3) + 2 * (w * K + K * K) / norm2).applyfunc(sp.expand)


def _euler(values: list[sp.Expr], compiler: Compiler) -> sp.Matrix:
    R = sp.eye(3)
    for letter, value in zip(compiler.eulerseq, values, strict=True):
        basis = [sp.S.One if letter.lower() == axis else sp.S.Zero for axis in "xyz"]
        turn = rotation_about(basis, value)
        R = R * turn if letter.islower() else turn * R
    return R.applyfunc(sp.expand)


def _xyaxes(values: list[sp.Expr], source: str, element: str) -> sp.Matrix:
    x = sp.Matrix(_unit(values[:3], source, element))
    y = sp.Matrix(values[3:])
    y = y - x * (x.dot(y))
    y = sp.Matrix(_unit([sp.radsimp(sp.expand(v)) for v in y], source, element))
    z = x.cross(y).applyfunc(lambda e: sp.radsimp(sp.expand(e)))
    return sp.Matrix.hstack(x, y, z)


def _zaxis(values: list[sp.Expr], source: str, element: str) -> sp.Matrix:
    z = sp.Matrix(_unit(values, source, element))
    cosine = z[2]
    if cosine == -1:
        return sp.diag(1, -1, -1)  # MuJoCo's choice for the opposite direction: a half turn about x
    K = skew([-z[1], z[0], 0])  # (0, 0, 1) x z, of length sin(a)
    return (sp.eye(3) + K + K * K / (1 + cosine)).applyfunc(lambda e: sp.radsimp(sp.expand(e)))


def frame(attributes: Mapping[str, str], compiler: Compiler, source: str, element: str) -> sp.Matrix:
    """The 4 x 4 pose an element's ``pos`` and orientation attribute give (the identity without them)."""
    if "fromto" in attributes:
        ends = numbers(attributes["fromto"], 6, source, f"{element} fromto")
        middle = sp.Matrix([(a + b) / 2 for a, b in zip(ends[:3], ends[3:], strict=True)])
        return homogeneous(_zaxis([a - b for a, b in zip(ends[:3], ends[3:], strict=True)], source,
                                  f"{element} fromto"), middle)
    given = [key for key in ORIENTATIONS if key in attributes]
    if len(given) > 1:
        raise _fail(source, f"more than one orientation given ({', '.join(given)})", element)
    position = sp.Matrix(numbers(attributes["pos"], 3, source, f"{element} pos") if "pos" in attributes else [0] * 3)
    if not given:
        return homogeneous(sp.eye(3), position)
    key = given[0]
    where = f"{element} {key}"
    values: list[sp.Expr] = list(numbers(attributes[key], _SIZES[key], source, where, length=False))
    if key == "quat":
        R = _quaternion(values, source, where)
    elif key == "axisangle":
        _unit(values[:3], source, where)
        R = rotation_about(values[:3], angle(values[3], compiler, source, where))  # type: ignore[arg-type]
    elif key == "euler":
        R = _euler([angle(v, compiler, source, where) for v in values], compiler)  # type: ignore[arg-type]
    elif key == "xyaxes":
        R = _xyaxes(values, source, where)
    else:
        R = _zaxis(values, source, where)
    return homogeneous(R, position)
