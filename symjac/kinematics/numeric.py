r"""Numbers from symbolic results: one place that substitutes a configuration and the parameters' defaults.

Every numeric value symjac computes from a symbolic one (a torque at a configuration, a Jacobian for an SVD, a
frame's axes for the singularity geometry) goes through :func:`values_at`, so every caller validates ``q`` the same
way and substitutes the same exact defaults.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame, MemoKey, as_chain
from symjac.kinematics.jacobian import Method, Point, jacobian, point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.model.robot import Robot
from symjac.symbolic.nested import lambdify_cse

__all__ = ["as_vector", "evaluate_at", "numeric_at", "numeric_jacobian", "values_at"]


def as_vector(values: Sequence[sp.Expr | float], length: int, name: str) -> sp.Matrix:
    """A column of ``length`` finite numbers or expressions; a clear error naming ``name`` for anything else.

    Examples
    --------
    >>> as_vector([1, 0.5, sp.pi], 3, "q").T
    Matrix([[1, 0.5, pi]])
    """
    if isinstance(values, str | bytes | Mapping) or not hasattr(values, "__len__"):
        raise ArgumentError(f"{name} must be a sequence of {length} numbers, got {type(values).__name__}")
    entries = list(values)
    if len(entries) != length:
        raise ArgumentError(f"{name} needs {length} entries, got {len(entries)}")
    column = []
    for index, value in enumerate(entries):
        if isinstance(value, numbers.Real) and not isinstance(value, bool):
            if not math.isfinite(value):
                raise ArgumentError(f"{name}[{index}] is {value}: entries must be finite")
            integral = isinstance(value, numbers.Integral)
            column.append(sp.Integer(int(value)) if integral else sp.Float(float(value)))  # type: ignore[call-overload]
        elif isinstance(value, sp.Expr) and not value.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            column.append(value)
        else:
            raise ArgumentError(f"{name}[{index}] must be a finite number or SymPy expression, got {value!r}")
    return sp.Matrix(column)


def values_at(robot: Robot | Chain, q: Sequence[float | sp.Expr]) -> dict[sp.Symbol, sp.Expr]:
    """The substitution of a configuration ``q`` (validated) and of the parameters' exact defaults.

    ``q`` gives the coordinates; a coupled robot's joint variables take their values from them, so expressions in
    either (a transform of the chain, a Jacobian) evaluate.
    """
    model = as_chain(robot).robot
    values: dict[sp.Symbol, sp.Expr] = dict(zip(model.q, as_vector(q, model.n_coordinates, "q"), strict=True))
    values.update(model.defaults)
    if model.coupling is not None:
        given = dict(values)
        values.update({joint: value.xreplace(given) for joint, value
                       in zip(model.joint_variables, model.coupling.values, strict=True) if joint not in given})
    return values


def evaluate_at(robot: Robot | Chain, expr: sp.MatrixBase, q: Sequence[float | sp.Expr]) -> sp.Matrix:
    """``expr`` at configuration ``q`` and the parameters' defaults, evaluated to SymPy floats.

    Examples
    --------
    >>> from symjac import load_robot
    >>> robot = load_robot("planar2r")
    >>> evaluate_at(robot, sp.Matrix([robot.q[0] + robot.q[1]]), [1, 2])
    Matrix([[3.0]])
    """
    return sp.Matrix(expr).xreplace(values_at(robot, q)).evalf()


def numeric_at(robot: Robot | Chain, expr: sp.MatrixBase, q: Sequence[float | sp.Expr]) -> np.ndarray:
    """:func:`evaluate_at` as a float NumPy array."""
    return np.array(evaluate_at(robot, expr, q), dtype=float)


def numeric_jacobian(robot: Robot | Chain, q: Sequence[float], frame: Frame = 0, point: Point | None = None
                     ) -> np.ndarray:
    """The 6 x n_coordinates basic Jacobian at configuration ``q`` as floats (parameters at their defaults).

    The point is as for :func:`~symjac.kinematics.jacobian.jacobian`: default the end of the chain (the tool point
    when the robot has a tool, else the flange, the origin of {n}).

    The first call per frame and point compiles the raw Jacobian with :func:`sympy.lambdify` (kept in the chain);
    later calls cost microseconds (about 30 for a 6-joint arm). This is the analyses' own evaluation, one
    configuration at a time; ``symjac.numeric_jacobian`` is :func:`symjac.codegen.numeric_model.numeric_jacobian`,
    over generated code, which also takes batches.
    """
    chain = as_chain(robot)
    model = chain.robot
    values = np.asarray(q, dtype=float)
    if values.shape != (model.n_coordinates,):
        raise ArgumentError(f"q must have {model.n_coordinates} entries for {model.name}, got shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ArgumentError(f"q must be finite, got {values.tolist()}")
    raw = (frame, point if point is None or isinstance(point, str) else tuple(point))
    try:
        hash(raw)
    except TypeError:
        return np.asarray(_compiled_jacobian(chain, frame, point)(values), dtype=float)
    # Keyed by the arguments as given, so later calls skip normalising the point (a tool transform rebuilt, a wrist
    # centre found again: 0.3-4 ms a call before); the memoized function still shares one lambdify per quantity.
    compiled = chain.memo(MemoKey(numeric_jacobian, raw), lambda: _compiled_jacobian(chain, frame, point))
    return np.asarray(compiled(values), dtype=float)


@memoized(frame=frame_of, point=point_vector)
def _compiled_jacobian(chain: Chain, frame: Frame, point: Point | None) -> Callable[..., Any]:
    """The raw Jacobian lambdified over q, parameters at their defaults."""
    method: Method = "cross_product" if chain.nested else "differentiation"  # nested: n + 1 frames, not n derivatives
    J = jacobian(chain, frame=frame, point=point, method=method, simplify=False).xreplace(chain.robot.defaults)
    return sp.lambdify([chain.robot.q], J, modules="numpy", cse=lambdify_cse)
