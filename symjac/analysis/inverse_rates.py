r"""Joint rates for a commanded Cartesian velocity: :math:`\dot q = J^{-1}\dot x`, exactly and near singularities.

Closed form (:func:`inverse_rates`): for a square Jacobian, :math:`J^{-1} = \operatorname{adj}(J) / \det J`, so every
joint rate is a compact numerator over the factored determinant; where a factor of :math:`\det J` vanishes, the
rates that divide by it grow without bound (the lecture slides' 3R arm:
:math:`\dot\theta_1 = \dot z / (-L_1 - L_2 c_2 - L_3 c_{23})`).

Numerically (:func:`damped_least_squares`), the damped least-squares inverse

.. math:: \dot q = J^T (J J^T + \lambda^2 I)^{-1} \dot x

stays bounded. The damping follows the rule of Maciejewski and Klein, refined by Chiaverini: with the smallest
singular value :math:`\sigma_{min}` and a threshold :math:`\varepsilon`,

.. math:: \lambda^2 = \begin{cases} 0 & \sigma_{min} \ge \varepsilon \\
          \left(1 - (\sigma_{min}/\varepsilon)^2\right)\lambda_{max}^2 & \sigma_{min} < \varepsilon \end{cases}

so the solution is exact away from singularities and damped smoothly as one is approached.
:func:`rates_along_path` evaluates both along a path of configurations, to show the exact rates blowing up while
the damped ones stay bounded (at the price of a tracking error).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import determinant
from symjac.analysis.spaces import task_rows
from symjac.errors import ArgumentError
from symjac.kinematics.chain import Frame, chain_of
from symjac.kinematics.jacobian import ROW_NAMES, Point, jacobian
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.ends import end_point
from symjac.model.robot import Robot
from symjac.symbolic.simplify import simplify_matrix

__all__ = [
    "RATE_SYMBOLS",
    "InverseRates",
    "PathRates",
    "damped_least_squares",
    "damping",
    "inverse_rates",
    "rates_along_path",
]

RATE_SYMBOLS: tuple[sp.Symbol, ...] = tuple(sp.Symbol(name, real=True) for name in ROW_NAMES)
"""Symbols of the commanded Cartesian velocity components, one per Jacobian row."""


@dataclass(frozen=True)
class InverseRates:
    r"""Joint rates :math:`\dot q = \operatorname{adj}(J)\,\dot x / \det J` in closed form."""

    rates: sp.Matrix  # n x 1, entries numerator / determinant
    numerators: sp.Matrix  # adj(J) xdot, simplified
    determinant: sp.Expr
    rows: tuple[int, ...]
    frame: Frame
    velocity: tuple[sp.Symbol, ...]


def inverse_rates(
    robot: Robot, rows: Sequence[int] | None = None, frame: Frame | None = None, point: Point | None = None
) -> InverseRates:
    r"""The closed-form joint rates for commanded velocity components (the symbols :data:`RATE_SYMBOLS`).

    Parameters are as for :func:`symjac.analysis.singularity.determinant.determinant`; ``frame`` is the frame the
    velocity is commanded in (default: where the Jacobian is most compact). The adjugate is cheap for the small arms
    this is meant for (up to four joints); six-joint arms work but take longer.

    Examples
    --------
    >>> from symjac import load_robot
    >>> rates = inverse_rates(load_robot("articulated3r"), frame="tool")
    >>> rates.rates[0]
    -v_z/(L1 + L2*cos(theta2) + L3*cos(theta2 + theta3))
    """
    det = determinant(robot, rows, frame, point)
    if det.coefficient == 0:
        raise ArgumentError(f"the Jacobian of {robot.name} on rows {det.row_names} is singular everywhere")
    J = jacobian(robot, frame=det.frame, point=det.point).extract(list(det.rows), list(det.columns))
    velocity = tuple(RATE_SYMBOLS[r] for r in det.rows)
    adjugate = J.adjugate(method="berkowitz")
    numerators = simplify_matrix(adjugate * sp.Matrix(velocity), chain_of(robot).all_angle_bases())
    rates = sp.Matrix([_divide(numerator, det.coefficient, det.factors) for numerator in numerators])
    return InverseRates(rates, numerators, det.expression, det.rows, det.frame, velocity)


def _divide(numerator: sp.Expr, coefficient: sp.Expr, factors: Sequence[tuple[sp.Expr, int]]) -> sp.Expr:
    """``numerator / (coefficient * prod factors)``, cancelling the parameter factors and any factor that divides."""
    value = sp.factor_terms(numerator) / coefficient
    for factor, multiplicity in factors:
        for _ in range(multiplicity):
            quotient = sp.cancel(value / factor)
            value = quotient if sp.count_ops(quotient) <= sp.count_ops(value) + 2 else value / factor
    return value


def damping(singular_values: np.ndarray, threshold: float = 0.05, maximum: float = 0.05) -> float:
    r"""The damping factor :math:`\lambda` of the rule in the module docstring (0 away from singularities)."""
    smallest = float(np.min(singular_values)) if np.size(singular_values) else 0.0
    if smallest >= threshold:
        return 0.0
    return float(np.sqrt(1.0 - (smallest / threshold) ** 2) * maximum)


def damped_least_squares(
    J: np.ndarray, xdot: np.ndarray, threshold: float = 0.05, maximum: float = 0.05
) -> np.ndarray:
    r""":math:`\dot q = J^T (J J^T + \lambda^2 I)^{-1} \dot x` with :math:`\lambda` from :func:`damping`.

    Examples
    --------
    >>> J = np.array([[1.0, 0.0], [0.0, 1e-9]])  # nearly singular: the second direction is almost lost
    >>> damped_least_squares(J, np.array([1.0, 1.0])).round(6).tolist()  # bounded, slightly damped
    [0.997506, 0.0]
    """
    J = np.asarray(J, dtype=float)
    xdot = np.asarray(xdot, dtype=float)
    if J.ndim != 2 or xdot.shape != (J.shape[0],):
        raise ArgumentError(f"need J of shape (m, n) and xdot of shape (m,), got {J.shape} and {xdot.shape}")
    if not (np.all(np.isfinite(J)) and np.all(np.isfinite(xdot))):
        raise ArgumentError("J and xdot must be finite")
    lam = damping(np.linalg.svd(J, compute_uv=False), threshold, maximum)
    return J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(J.shape[0]), xdot)


@dataclass(frozen=True)
class PathRates:
    r"""Joint rates along a path: exact (``nan`` where singular), damped, and the smallest singular value.

    ``exact`` is :math:`J^{-1}\dot x` for a square Jacobian and the minimum-norm rates
    :math:`J^+ \dot x = J^T (J J^T)^{-1} \dot x` for a redundant arm's wide one.
    """

    exact: np.ndarray  # (m, n)
    damped: np.ndarray  # (m, n)
    smallest_singular_value: np.ndarray  # (m,)
    tracking_error: np.ndarray  # (m,) |J qdot_damped - xdot|


def rates_along_path(
    robot: Robot,
    path: np.ndarray,
    xdot: Sequence[float],
    rows: Sequence[int] | None = None,
    frame: Frame = 0,
    point: Point | None = None,
    threshold: float = 0.05,
    maximum: float = 0.05,
) -> PathRates:
    """Exact and damped joint rates for a constant commanded velocity ``xdot`` at each configuration of ``path``.

    ``path`` has shape (m, n); ``xdot`` one entry per task row (default rows:
    :func:`symjac.analysis.singularity.determinant.task_rows`), expressed in ``frame``.
    """
    if point is None:
        point = end_point(robot)
    chain_of(robot).position(frame)
    configurations = np.asarray(path, dtype=float)
    if configurations.ndim != 2 or configurations.shape[1] != robot.n_coordinates:
        raise ArgumentError(f"path must have shape (m, {robot.n_coordinates}), got {configurations.shape}")
    chosen = list(task_rows(robot, point) if rows is None else rows)
    velocity = np.asarray(xdot, dtype=float)
    if velocity.shape != (len(chosen),):
        raise ArgumentError(f"xdot needs {len(chosen)} entries (rows {chosen}), got shape {velocity.shape}")
    exact, damped, smallest, error = [], [], [], []
    for q in configurations:
        J = numeric_jacobian(robot, q, frame, point)[chosen, :]
        sigma = np.linalg.svd(J, compute_uv=False)
        smallest.append(float(sigma.min()))
        regular = J.shape[0] <= J.shape[1] and sigma.min() > sigma.max() * 1e-12
        if not regular:
            exact.append(np.full(robot.n_coordinates, np.nan))
        else:  # the inverse, or the minimum-norm rates of a wide J
            exact.append(np.linalg.solve(J, velocity) if J.shape[0] == J.shape[1]
                         else J.T @ np.linalg.solve(J @ J.T, velocity))
        rates = damped_least_squares(J, velocity, threshold, maximum)
        damped.append(rates)
        error.append(float(np.linalg.norm(J @ rates - velocity)))
    return PathRates(np.array(exact), np.array(damped), np.array(smallest), np.array(error))
