"""The quantities every document uses: transforms, Jacobians, propagation steps, determinants, representation maps.

Each takes the :class:`~symjac.teaching.errata.formulas.Formula` (its robot and symbols) and the formula's ``args``, and
returns what symjac derives, as a matrix to compare with the printed one.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import sympy as sp

from symjac.analysis.representations import angular_velocity_matrix, rate_matrix, rotation_from
from symjac.analysis.singularity.determinant import determinant
from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian, rows_from_names
from symjac.kinematics.propagation import force_propagation, velocity_propagation
from symjac.model.robot import Robot
from symjac.symbolic.transforms import skew
from symjac.teaching.errata.formulas import Formula

__all__ = ["BASE_QUANTITIES", "jacobian_of", "position_of", "representation_quantity", "robot_of"]


def robot_of(f: Formula) -> Robot:
    """The formula's robot (an error naming the formula if it has none)."""
    if f.robot is None:
        raise KeyError(f"{f.id}: quantity {f.quantity!r} needs a robot")
    return f.robot


def _transform(f: Formula, source: Any = 0, target: Any = None, columns: Any = None) -> sp.Matrix:
    """The compact transform; only some ``columns`` (1-based) when the print leaves the others unreadable."""
    chain = chain_of(robot_of(f))
    T = sp.Matrix(chain.simplified_transform(source, chain.n_joints if target is None else target))
    return T if columns is None else T.extract(list(range(T.rows)), [column - 1 for column in columns])


def _rotation(f: Formula, source: Any = 0, target: Any = None) -> sp.Matrix:
    return _transform(f, source, target)[:3, :3]


def position_of(f: Formula, source: Any = 0, target: Any = None) -> sp.Matrix:
    """The origin of frame ``target`` in frame ``source``."""
    return _transform(f, source, target)[:3, 3]


def jacobian_of(f: Formula, frame: Any = 0, point: Any = "wrist", rows: Any = None,
                order: str = "v_first") -> sp.Matrix:
    """The Jacobian of the formula's robot; some ``rows`` by name, or with the angular rows first."""
    J = jacobian(robot_of(f), frame=frame, point=point)
    if order == "omega_first":
        J = sp.Matrix.vstack(J[3:, :], J[:3, :])
    return J if rows is None else J.extract(list(rows_from_names(rows)), list(range(J.cols)))


def _velocity(f: Formula, frame: Any, part: str = "v", point: Any = None) -> sp.Matrix:
    tip = (sp.S.Zero,) * 3 if point is None else (None if point == "tool" else tuple(point))
    for step_frame, omega, v in velocity_propagation(robot_of(f), tip).velocities():
        if step_frame == frame:
            return omega if part == "omega" else v
    raise KeyError(f"{f.id}: no velocity step for frame {frame!r}")


def _force(f: Formula, frame: Any, part: str = "f") -> sp.Matrix:
    for step_frame, force, moment in force_propagation(robot_of(f)).wrenches():
        if step_frame == frame:
            return force if part == "f" else moment
    raise KeyError(f"{f.id}: no force step for frame {frame!r}")


def _torques(f: Formula) -> sp.Matrix:
    return force_propagation(robot_of(f)).joint_torques()


def _determinant(f: Formula, rows: Any = None, frame: Any = None) -> sp.Matrix:
    chosen = None if rows is None else rows_from_names(rows)
    return sp.Matrix([[determinant(robot_of(f), rows=chosen, frame=frame).expression]])


def representation_quantity(function: Callable[..., sp.Matrix]) -> Callable[..., sp.Matrix]:
    """A quantity from a representation map (``rate_matrix``, ...) in the formula's first three symbols."""
    def derive(f: Formula, representation: str) -> sp.Matrix:
        return sp.Matrix(function(representation, f.symbols[:3] if len(f.symbols) >= 3 else None))

    return derive


def _skew(f: Formula) -> sp.Matrix:
    return skew(sp.Matrix(f.symbols[:3]))


BASE_QUANTITIES: Mapping[str, Callable[..., sp.Matrix]] = {
    "transform": _transform,
    "rotation": _rotation,
    "position": position_of,
    "jacobian": jacobian_of,
    "velocity": _velocity,
    "force": _force,
    "torques": _torques,
    "determinant": _determinant,
    "rate_matrix": representation_quantity(rate_matrix),
    "rotation_of": representation_quantity(rotation_from),
    "angular_velocity_matrix": representation_quantity(angular_velocity_matrix),
    "skew": _skew,
}
