r"""The example arm the prose formulas of the notes are evaluated on: a configuration, joint rates, a wrench, a tool.

A relation check (:data:`symjac.teaching.errata.derive.RELATIONS`) evaluates a printed formula numerically on one of the
catalog arms at :data:`Q_EXAMPLE` and compares it with symjac's derivation; these are the shared pieces.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import sympy as sp

from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.numeric import evaluate_at
from symjac.model.expressions import parse_expression
from symjac.model.robot import Robot
from symjac.symbolic.transforms import homogeneous, rotation_rpy
from symjac.teaching.errata.formulas import Formula

__all__ = [
    "Q_EXAMPLE", "RATES_EXAMPLE", "TOOL_EXAMPLE", "WRENCH_EXAMPLE", "frame_transform", "hat", "jacobian_at", "numbers",
    "parsed", "q_example", "rates_example", "residual", "substitution", "wrist_and_tool",
]


def parsed(f: Formula, text: Any) -> sp.Expr:
    """A shorthand expression (``"F*c1"``) in the formula's names."""
    return parse_expression(str(text), f.names)


def substitution(f: Formula, at: Mapping[str, Any] | None) -> dict[sp.Expr, sp.Expr]:
    """Values for some of the formula's names (``{theta2 = "0"}``), as a substitution."""
    return {} if not at else {f.names[name]: parsed(f, value) for name, value in at.items()}


Q_EXAMPLE = (0.31, -0.72, 0.45, 0.93, -0.61, 1.14, 0.27)
"""A generic configuration (the first n values are used): no joint at a singular or special angle."""


RATES_EXAMPLE = (0.4, -0.3, 0.7, -0.5, 0.6, 0.2, -0.8)


WRENCH_EXAMPLE = (1.3, -0.7, 2.1, 0.4, -0.9, 0.6)


TOOL_EXAMPLE = homogeneous(rotation_rpy(sp.Rational(3, 10), sp.Rational(-1, 2), sp.Rational(7, 10)),
                            sp.Matrix([sp.Rational(1, 20), sp.Rational(-1, 50), sp.Rational(3, 20)]))
"""A tool {T} held by the last frame: tilted and offset, so no term of a tool-tip formula vanishes by accident."""


def numbers(matrix: Any) -> np.ndarray:
    """A SymPy matrix (numbers only) as a float array."""
    return np.array(sp.Matrix(matrix).evalf(), dtype=float)


def residual(left: Any, right: Any) -> float:
    """The difference of two arrays, relative to their size: 0 when they agree."""
    left, right = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    return float(np.linalg.norm(left - right) / (1.0 + np.linalg.norm(left) + np.linalg.norm(right)))


def hat(p: np.ndarray) -> np.ndarray:
    """The skew-symmetric cross-product matrix of a numeric 3-vector."""
    x, y, z = np.ravel(p)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def q_example(robot: Robot) -> list[float]:
    """The example configuration of ``robot`` (the first n values of :data:`Q_EXAMPLE`)."""
    return list(Q_EXAMPLE[: robot.n_coordinates])


def rates_example(robot: Robot) -> np.ndarray:
    """Example joint rates of ``robot``."""
    return np.array(RATES_EXAMPLE[: robot.n_coordinates])


def frame_transform(robot: Robot, source: Any, target: Any) -> np.ndarray:
    r""":math:`{}^{source}_{target}T` at the example configuration, from symjac's chain."""
    return numbers(evaluate_at(robot, chain_of(robot).transform(source, target), q_example(robot)))


def jacobian_at(robot: Robot, **kwargs: Any) -> np.ndarray:
    """The Jacobian from symjac (arguments as for :func:`symjac.kinematics.jacobian`) at the example configuration."""
    if "point" not in kwargs and kwargs.get("link") is None:
        kwargs["point"] = "flange"  # the course's wrist point, the origin of {n}
    return numbers(evaluate_at(robot, jacobian(robot, **kwargs), q_example(robot)))


def wrist_and_tool(f: Formula) -> tuple[np.ndarray, np.ndarray]:
    r"""Frames {i} (the wrist, frame n) and {i+1} (the example tool {T}): :math:`{}^i_{i+1}T` and its inverse."""
    T = numbers(TOOL_EXAMPLE)
    return T, np.linalg.inv(T)
