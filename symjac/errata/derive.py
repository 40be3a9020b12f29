r"""What symjac derives for each printed formula, and the exact comparison that decides whether the print is right.

Each ``quantity`` of the data file names a function here that returns the derived matrix for the formula's robot
and ``args``. A ``relation`` is a prose formula (a recursion, :math:`\tau = J^T F`) checked by evaluating both sides
on an example arm: its printed matrix is the left side, and the function returns the right side.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.angles import AngleBasis
from symjac.chain import chain_of
from symjac.errata.formulas import Formula
from symjac.expressions import parse_expression
from symjac.jacobian import jacobian, rows_from_names
from symjac.model import Robot
from symjac.propagation import force_propagation, joint_rates, velocity_propagation
from symjac.representations import angular_velocity_matrix, rate_matrix, rotation_from
from symjac.simplify import is_identity
from symjac.singularity import determinant
from symjac.transforms import skew

__all__ = ["QUANTITIES", "RELATIONS", "RELATION_TOLERANCE", "Comparison", "compare", "derive"]

RELATION_TOLERANCE = 1e-9
"""A relation holds when its residual on the example arm is below this (relative to the size of the terms)."""


def _robot(f: Formula) -> Robot:
    if f.robot is None:
        raise KeyError(f"{f.id}: quantity {f.quantity!r} needs a robot")
    return f.robot


def _transform(f: Formula, source: Any = 0, target: Any = None) -> sp.Matrix:
    chain = chain_of(_robot(f))
    return sp.Matrix(chain.simplified_transform(source, chain.n if target is None else target))


def _rotation(f: Formula, source: Any = 0, target: Any = None) -> sp.Matrix:
    return _transform(f, source, target)[:3, :3]


def _position(f: Formula, source: Any = 0, target: Any = None) -> sp.Matrix:
    return _transform(f, source, target)[:3, 3]


def _jacobian(f: Formula, frame: Any = 0, point: Any = "wrist", rows: Any = None, order: str = "v_first") -> sp.Matrix:
    J = jacobian(_robot(f), frame=frame, point=point)
    if order == "omega_first":
        J = sp.Matrix.vstack(J[3:, :], J[:3, :])
    return J if rows is None else J.extract(list(rows_from_names(rows)), list(range(J.cols)))


def _velocity(f: Formula, frame: Any, part: str = "v", point: Any = None) -> sp.Matrix:
    tip = (sp.S.Zero,) * 3 if point is None else (None if point == "tool" else tuple(point))
    for step_frame, omega, v in velocity_propagation(_robot(f), tip).velocities():
        if step_frame == frame:
            return omega if part == "omega" else v
    raise KeyError(f"{f.id}: no velocity step for frame {frame!r}")


def _force(f: Formula, frame: Any, part: str = "f") -> sp.Matrix:
    for step_frame, force, moment in force_propagation(_robot(f)).wrenches():
        if step_frame == frame:
            return force if part == "f" else moment
    raise KeyError(f"{f.id}: no force step for frame {frame!r}")


def _torques(f: Formula) -> sp.Matrix:
    return force_propagation(_robot(f)).joint_torques()


def _determinant(f: Formula, rows: Any = None, frame: Any = None) -> sp.Matrix:
    chosen = None if rows is None else rows_from_names(rows)
    return sp.Matrix([[determinant(_robot(f), rows=chosen, frame=frame).expression]])


def _representation(function: Callable[..., sp.Matrix]) -> Callable[..., sp.Matrix]:
    def derive(f: Formula, representation: str) -> sp.Matrix:
        return sp.Matrix(function(representation, f.symbols[:3] if len(f.symbols) >= 3 else None))

    return derive


def _skew(f: Formula) -> sp.Matrix:
    return skew(sp.Matrix(f.symbols[:3]))


def _block(f: Formula, of: str, r: Any = None, c: Any = None, at: Any = None, **inner: Any) -> sp.Matrix:
    """Rows ``r`` and columns ``c`` (1-based) of quantity ``of``, optionally at a configuration ``at``.

    ``at`` maps names to values (``{ theta2 = "0" }``): a printed 2 x 2 block of a rotation, a Jacobian at a
    singularity. The other arguments go to ``of``.
    """
    M = sp.Matrix(QUANTITIES[of](f, **inner))
    if at:
        M = M.subs({f.names[name]: parse_expression(str(value), f.names) for name, value in dict(at).items()})
    rows = list(range(M.rows)) if r is None else [i - 1 for i in r]
    cols = list(range(M.cols)) if c is None else [j - 1 for j in c]
    return M.extract(rows, cols)


def _z_cross_p(f: Formula, joint: Any = None, tool: Any = None, frame: Any = None) -> sp.Matrix:
    r"""The explicit form's :math:`{}^iz_i \times {}^ip_{in} = \hat Z\,{}^ip_{in}`, rotated into ``frame`` if given.

    :math:`p_{in}` runs from joint ``joint``'s frame to the origin of frame ``tool`` (default {n}); without a joint,
    :math:`\hat Z p` for the formula's symbols :math:`p = (p_x, p_y, p_z)`.
    """
    z_hat = skew(sp.Matrix([0, 0, 1]))
    if joint is None:
        return z_hat * sp.Matrix(f.symbols[:3])
    chain = chain_of(_robot(f))
    axis = chain.axis_frame(joint)
    result = z_hat * sp.Matrix(chain.simplified_transform(axis, chain.n if tool is None else tool))[:3, 3]
    return result if frame is None else sp.Matrix(chain.rotation(frame, axis)) * result


def _point_shift(f: Formula, frame: Any = 0, part: str = "p") -> sp.Matrix:
    r"""The wrist-to-tool shift of section 4.9 in frame {k}.

    :math:`{}^kp_{WE}` (``part = "p"``), its cross-product matrix (``"p_hat"``) or the term
    :math:`-{}^k\hat p_{WE}\,{}^kJ_{\omega(W)}` (``"term"``).
    """
    robot = _robot(f)
    chain = chain_of(robot)
    p = sp.Matrix(chain.simplified_transform(frame, "tool"))[:3, 3] - sp.Matrix(
        chain.simplified_transform(frame, chain.n))[:3, 3]
    p = sp.Matrix([sp.trigsimp(e) for e in p])
    if part == "p":
        return p
    if part == "p_hat":
        return skew(p)
    return -skew(p) * jacobian(robot, frame=frame)[3:, :]


def _point_velocity(f: Formula, target: Any = None, part: str = "v") -> sp.Matrix:
    r"""Velocity in {0} of the origin of frame ``target`` (default {n}), in the joint rates.

    :math:`\frac{d}{dt}{}^0p_k` (``part = "v"``), or the angular velocity :math:`{}^0\omega_n` of the last link
    (``"omega"``).
    """
    robot = _robot(f)
    rates = sp.Matrix(joint_rates(robot))
    if part == "omega":
        return jacobian(robot, frame=0)[3:, :] * rates
    chain = chain_of(robot)
    p = sp.Matrix(chain.simplified_transform(0, chain.n if target is None else target))[:3, 3]
    return p.jacobian(sp.Matrix(robot.q)) * rates


QUANTITIES: Mapping[str, Callable[..., sp.Matrix]] = {
    "transform": _transform,
    "rotation": _rotation,
    "position": _position,
    "jacobian": _jacobian,
    "velocity": _velocity,
    "force": _force,
    "torques": _torques,
    "determinant": _determinant,
    "rate_matrix": _representation(rate_matrix),
    "rotation_of": _representation(rotation_from),
    "angular_velocity_matrix": _representation(angular_velocity_matrix),
    "skew": _skew,
    # helper B
    "block": _block,
    "z_cross_p": _z_cross_p,
    "point_shift": _point_shift,
    "point_velocity": _point_velocity,
}


RELATIONS: Mapping[str, Callable[[Formula, str], float]] = {}
"""Checks of prose formulas: ``check(formula, "printed" | "corrected")`` is the relative residual of that form on an
example arm (0 when it holds); each check's docstring quotes the formula it evaluates."""


def derive(f: Formula) -> sp.Matrix:
    """The matrix symjac derives for formula ``f``."""
    if f.quantity not in QUANTITIES:
        raise KeyError(f"{f.id}: unknown quantity {f.quantity!r}; known: {', '.join(QUANTITIES)}")
    return sp.Matrix(QUANTITIES[f.quantity](f, **f.args))


@dataclass(frozen=True)
class Comparison:
    """The printed matrix against the derived one: entries (1-based) that differ, and the verdict they give."""

    formula: Formula
    derived: sp.Matrix
    differing: tuple[tuple[int, int], ...]
    corrected_holds: bool | None

    @property
    def verdict(self) -> str:
        """``"erratum"`` when the print differs; ``"convention"`` or ``"ok"`` (as recorded) when it holds."""
        if self.differing:
            return "erratum"
        return "convention" if self.formula.verdict == "convention" else "ok"


def _basis(f: Formula) -> AngleBasis:
    angles = [j.variable for j in f.robot.joints if j.is_revolute] if f.robot is not None else []
    return AngleBasis.of([*angles, *f.symbols])


def _differs(left: sp.Expr, right: sp.Expr, basis: AngleBasis) -> bool:
    numerator, _ = sp.fraction(sp.together(left - right))
    return not is_identity(numerator, sp.S.Zero, basis)


def _differing(printed: sp.MatrixBase, derived: sp.MatrixBase, basis: AngleBasis) -> tuple[tuple[int, int], ...]:
    if printed.shape != derived.shape:
        return ((0, 0),)
    return tuple((r + 1, c + 1) for r in range(printed.rows) for c in range(printed.cols)
                 if _differs(printed[r, c], derived[r, c], basis))


def compare(f: Formula) -> Comparison:
    """Compare the printed (and the corrected) matrix of ``f`` with the derivation, exactly.

    A relation is compared numerically on its example arm (:data:`RELATIONS`, :data:`RELATION_TOLERANCE`).
    """
    if f.quantity == "relation":
        check = RELATIONS[f.args["check"]]
        printed_holds = check(f, "printed") <= RELATION_TOLERANCE
        corrected = None if not f.corrected_text else check(f, "corrected") <= RELATION_TOLERANCE
        return Comparison(f, sp.Matrix([[0]]), () if printed_holds else ((1, 1),), corrected)
    derived = derive(f)
    basis = _basis(f)
    corrected = None if f.corrected is None else not _differing(f.corrected, derived, basis)
    return Comparison(f, derived, _differing(f.printed, derived, basis), corrected)
