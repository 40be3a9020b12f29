r"""Matrix quantities of the slides and the web notes (documents 002 and 003) that the base does not cover.

The force map :math:`J^T` on its own, torques for a given wrench, joint rates :math:`J^{-1}\dot x`, expressions in
the entries of a rotation, elementary and first-order rotations.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import sympy as sp

from symjac.analysis.representations import rotation_from
from symjac.kinematics.statics import joint_torques
from symjac.model.expressions import parse_expression
from symjac.symbolic.transforms import Axis, rotation
from symjac.teaching.errata.base import jacobian_of, robot_of
from symjac.teaching.errata.example_arm import parsed, substitution
from symjac.teaching.errata.formulas import Formula

__all__ = ["QUANTITIES_SLIDES_NOTES"]


def _jacobian_transpose(f: Formula, **kwargs: Any) -> sp.Matrix:
    """The transpose of the Jacobian (the force map :math:`J^T` printed on its own)."""
    return jacobian_of(f, **kwargs).T


def _torques_for(f: Formula, wrench: Any, frame: Any = 0, point: Any = "wrist", at: Any = None) -> sp.Matrix:
    r""":math:`\tau = ({}^kJ)^T F` for a wrench written in the formula's names, at the configuration ``at``."""
    F = [parsed(f, w) for w in wrench]
    return sp.Matrix(joint_torques(robot_of(f), F, frame=frame, point=point)).subs(substitution(f, at))


def _inverse_rates(f: Formula, rows: Any, frame: Any = 0, point: Any = "wrist", take: Any = None) -> sp.Matrix:
    r""":math:`\dot\theta = J^{-1}\dot x` with :math:`\dot x` the formula's first symbols (``xdot``, ...)."""
    J = jacobian_of(f, frame=frame, point=point, rows=rows)
    rates = J.LUsolve(sp.Matrix(f.symbols[: J.rows]))
    return rates if take is None else rates.extract([t - 1 for t in take], [0])


def _rotation_entries(f: Formula, representation: str, expressions: Any) -> sp.Matrix:
    """Expressions in the entries ``r11 .. r33`` of the representation's rotation at the formula's symbols."""
    R = rotation_from(representation, f.symbols[:3])
    names = {**f.names, **{f"r{i + 1}{j + 1}": R[i, j] for i in range(3) for j in range(3)}}
    return sp.Matrix([[parse_expression(str(e), names)] for e in expressions])


def _rotation_of_at(f: Formula, representation: str, at: Any) -> sp.Matrix:
    """The representation's rotation at the formula's symbols, some of them given values (``beta = 0``)."""
    return sp.Matrix(rotation_from(representation, f.symbols[:3])).subs(substitution(f, at))


def _axis_rotation(f: Formula, axis: Axis, angle: str) -> sp.Matrix:
    """The elementary rotation about ``x``, ``y`` or ``z`` by the declared symbol ``angle``."""
    if axis not in ("x", "y", "z"):
        raise KeyError(f"{f.id}: axis must be x, y or z, got {axis!r}")
    return rotation(axis, f.names[angle])


def _small_rotation(f: Formula) -> sp.Matrix:
    r"""First-order axis-angle rotation :math:`R_K(\Delta\theta) \approx R_K(0) + R_K'(0)\,\Delta\theta` (unit K)."""
    kx, ky, kz, angle = f.symbols[:4]
    vartheta = sp.Symbol("vartheta", real=True)
    R = sp.Matrix(rotation_from("axis_angle", [kx, ky, kz, vartheta]))
    first = R.subs(vartheta, 0) + R.diff(vartheta).subs(vartheta, 0) * angle
    unit = {kx**2: 1 - ky**2 - kz**2}
    return first.applyfunc(lambda e: sp.expand(sp.expand(e).subs(unit)))


QUANTITIES_SLIDES_NOTES: Mapping[str, Callable[..., sp.Matrix]] = {
    "jacobian_transpose": _jacobian_transpose,
    "torques_for": _torques_for,
    "inverse_rates": _inverse_rates,
    "rotation_entries": _rotation_entries,
    "rotation_of_at": _rotation_of_at,
    "axis_rotation": _axis_rotation,
    "small_rotation": _small_rotation,
}
