r"""Time derivatives of representation Jacobians: the bias term of an analytic-Jacobian controller.

With :math:`\dot x = J_x \dot q` and :math:`J_x = E(x)\,J_0(q)` (:mod:`symjac.analysis.representations.jacobian`),
one more derivative gives

.. math::
    \ddot x = J_x \ddot q + \dot J_x \dot q, \qquad
    \dot J_x = \dot E\,J_0 + E\,\dot J_0, \qquad
    \dot E = \sum_i \frac{\partial E}{\partial x_i}\,\dot x_i, \qquad \dot x = E\,J_0\,\dot q .

:math:`\dot J_0` is the fixed-frame derivative of the basic Jacobian
(:func:`symjac.kinematics.acceleration.jacobian_derivative` with frame {0} or "world"). :math:`\dot E` is written in the
coordinates and their rates (the symbols of
:func:`coordinate_rates`: ``alphadot``, ``epsilondot_x``, ``rdot12``, ...); in :math:`\dot J_x` the rates are replaced
by :math:`E J_0 \dot q`, so it is a function of :math:`x`, :math:`q` and :math:`\dot q` only.

For the redundant sets (direction cosines, quaternion, axis-angle), :math:`E` is the map that keeps their constraint
(unit norm, orthonormality) and the formula is exact on it. Where :math:`E` does not exist (a representation
singularity), neither does :math:`\dot J_x`; :func:`representation_jacobian_derivative_at` refuses such poses as
:func:`~symjac.analysis.representations.jacobian.representation_jacobian_at` does.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from symjac.analysis.representations.jacobian import representation_jacobian, representation_jacobian_at
from symjac.analysis.representations.maps import position_rate_matrix, rate_matrix
from symjac.analysis.representations.registry import (
    Orientation,
    OrientationSpec,
    Position,
    PositionSpec,
    Representation,
    representation,
)
from symjac.errors import ArgumentError, RepresentationError
from symjac.kinematics.acceleration import jacobian_derivative
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import Point, point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import Robot

__all__ = [
    "NumericRepresentationJacobianDerivative",
    "RepresentationJacobianDerivative",
    "coordinate_rates",
    "representation_jacobian_derivative",
    "representation_jacobian_derivative_at",
]

_NAME = re.compile(r"([A-Za-z]+?)(\d*|_\w*)")


def _rate_symbol(coordinate: sp.Symbol) -> sp.Symbol:
    """``alpha`` -> ``alphadot``, ``epsilon_x`` -> ``epsilondot_x``, ``r12`` -> ``rdot12`` (SymPy prints a dot)."""
    match = _NAME.fullmatch(coordinate.name)
    base, suffix = match.groups() if match else (coordinate.name, "")
    return sp.Symbol(f"{base}dot{suffix}", real=True)


def coordinate_rates(name: str | Representation) -> tuple[sp.Symbol, ...]:
    r"""The rate symbols :math:`\dot x` of a representation's coordinates, in the order of :func:`.coordinates`.

    Examples
    --------
    >>> coordinate_rates("zyz"), coordinate_rates("quaternion")
    ((alphadot, betadot, gammadot), (etadot, epsilondot_x, epsilondot_y, epsilondot_z))
    >>> sp.latex(coordinate_rates("direction_cosines")[1])
    '\\dot{r}_{12}'
    """
    return tuple(_rate_symbol(c) for c in representation(name).coordinates)


@cache
def _rate_map(x_p: PositionSpec, x_r: OrientationSpec) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
    r""":math:`E = \mathrm{diag}(E_p, E_r)` and :math:`\dot E = \sum_i \partial E / \partial x_i\,\dot x_i`."""
    E = sp.diag(position_rate_matrix(x_p), rate_matrix(x_r))
    coords = (*x_p.coordinates, *x_r.coordinates)
    rates = (*coordinate_rates(x_p), *coordinate_rates(x_r))
    E_dot = sp.zeros(*E.shape)
    for coordinate, rate in zip(coords, rates, strict=True):
        E_dot += E.diff(coordinate) * rate
    return sp.ImmutableMatrix(E), sp.ImmutableMatrix(E_dot.applyfunc(sp.factor_terms))


@dataclass(frozen=True)
class RepresentationJacobianDerivative:
    r"""The time derivative :math:`\dot J_x = \dot E\,J_0 + E\,\dot J_0` of a representation Jacobian.

    Parameters
    ----------
    orientation, position : str
        The names of the representations of :math:`x_r` and :math:`x_p`.
    frame : 0 or "world"
        The fixed frame everything is expressed in.
    point : tuple of 3 sympy.Expr
        Where :math:`x_p` is taken, as coordinates in frame {n}.
    coordinates, coordinate_rates : tuple of sympy.Symbol
        :math:`x = [x_p; x_r]` and :math:`\dot x`.
    joint_rate_symbols : tuple of sympy.Symbol
        :math:`\dot q` (:func:`symjac.joint_rate_symbols`).
    E, E_dot : sympy.ImmutableMatrix, shape (3 + m, 6)
        :math:`E(x)` and :math:`\dot E(x, \dot x)`.
    J_x : sympy.ImmutableMatrix, shape (3 + m, n)
        :math:`E\,J_0`, in :math:`x` and :math:`q` (as :attr:`RepresentationJacobian.J_x`).
    x_dot : sympy.ImmutableMatrix, shape (3 + m, 1)
        :math:`J_x \dot q`, in :math:`x`, :math:`q`, :math:`\dot q`.
    Jdot_0 : sympy.ImmutableMatrix, shape (6, n)
        :math:`\dot J_0` in :math:`q` and :math:`\dot q`.
    Jdot_x : sympy.ImmutableMatrix, shape (3 + m, n)
        :math:`\dot E|_{\dot x = J_x \dot q}\,J_0 + E\,\dot J_0`, in :math:`x`, :math:`q` and :math:`\dot q`.
    """

    orientation: str
    position: str
    frame: Frame
    point: tuple[sp.Expr, sp.Expr, sp.Expr]
    coordinates: tuple[sp.Symbol, ...]
    coordinate_rates: tuple[sp.Symbol, ...]
    joint_rate_symbols: tuple[sp.Symbol, ...]
    E: sp.ImmutableMatrix
    E_dot: sp.ImmutableMatrix
    J_x: sp.ImmutableMatrix
    x_dot: sp.ImmutableMatrix
    Jdot_0: sp.ImmutableMatrix
    Jdot_x: sp.ImmutableMatrix

    @property
    def bias(self) -> sp.Matrix:
        r"""The bias :math:`\dot J_x \dot q` ((3 + m) x 1): :math:`\ddot x` at zero joint acceleration."""
        return self.Jdot_x * sp.Matrix(self.joint_rate_symbols)


@dataclass(frozen=True, eq=False)
class NumericRepresentationJacobianDerivative:
    r"""A representation Jacobian and its time derivative at one state :math:`(q, \dot q)`.

    Parameters
    ----------
    x, x_dot : numpy.ndarray, shape (3 + m,)
        The coordinates extracted from the forward kinematics and their rates :math:`J_x \dot q`.
    E, E_dot : numpy.ndarray, shape (3 + m, 6)
    J_0, Jdot_0 : numpy.ndarray, shape (6, n)
    J_x, Jdot_x : numpy.ndarray, shape (3 + m, n)
    bias : numpy.ndarray, shape (3 + m,)
        :math:`\dot J_x \dot q`, so that :math:`\ddot x = J_x \ddot q + \text{bias}`.
    factors : tuple of float
        The representation's singular factors at ``x`` (as in :class:`NumericRepresentationJacobian`).
    """

    x: np.ndarray
    x_dot: np.ndarray
    E: np.ndarray
    E_dot: np.ndarray
    J_0: np.ndarray
    Jdot_0: np.ndarray
    J_x: np.ndarray
    Jdot_x: np.ndarray
    bias: np.ndarray
    factors: tuple[float, ...]


@memoized(orientation=lambda chain, name: representation(name, "orientation"),
          position=lambda chain, name: representation(name, "position"), point=point_vector, frame=frame_of)
def representation_jacobian_derivative(
    chain: Chain,
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point | None = None,
    frame: Frame = 0,
) -> RepresentationJacobianDerivative:
    r"""The time derivative :math:`\dot J_x` of the representation Jacobian :math:`J_x = E(x)\,J_0`, symbolic.

    .. math:: \dot J_x = \Bigl(\sum_i \frac{\partial E}{\partial x_i}\,(E J_0 \dot q)_i\Bigr) J_0 + E\,\dot J_0

    Parameters are those of :func:`~symjac.analysis.representations.jacobian.representation_jacobian`. Derived once per
    chain.

    Returns
    -------
    RepresentationJacobianDerivative

    Examples
    --------
    >>> from symjac import load_robot
    >>> result = representation_jacobian_derivative(load_robot("planar2r"), "rpy", "cylindrical")
    >>> result.Jdot_x[5, :]  # a planar arm's yaw rate is thetadot1 + thetadot2 at every pose
    Matrix([[0, 0]])
    >>> result.E_dot[0, :2]  # rho rate = cos(phi_c) v_x + sin(phi_c) v_y turns with the azimuth
    Matrix([[-phidot_c*sin(phi_c), phidot_c*cos(phi_c)]])
    """
    base = representation_jacobian(chain, orientation, position, point, frame)
    x_r = representation(orientation, "orientation")  # already the value (normalised by @memoized): typed here
    x_p = representation(position, "position")
    rates = (*coordinate_rates(x_p), *coordinate_rates(x_r))
    q_dot = joint_rate_symbols(chain)
    model = chain.robot
    clash = sorted({str(s) for s in rates} & {str(s) for s in (*model.q, *model.parameter_symbols, *q_dot)})
    if clash:
        raise RepresentationError(f"{model.name}: the names {', '.join(clash)} are both robot symbols and "
                                  f"coordinate rates of the {x_p.name}/{x_r.name} representation")
    E, E_dot = _rate_map(x_p, x_r)
    x_dot = base.J_x * sp.Matrix(q_dot)
    Jdot_0 = jacobian_derivative(chain, base.frame, list(base.point))
    E_dot_along = E_dot.xreplace(dict(zip(rates, x_dot, strict=True)))
    Jdot_x = E_dot_along * base.J_0 + E * Jdot_0
    return RepresentationJacobianDerivative(
        base.orientation, base.position, base.frame, base.point, base.coordinates, rates, q_dot, E, E_dot,
        base.J_x, sp.ImmutableMatrix(x_dot), sp.ImmutableMatrix(Jdot_0), sp.ImmutableMatrix(Jdot_x))


@memoized(frame=frame_of, point=point_vector)
def _compiled_jacobian_derivative(chain: Chain, frame: Frame, point: Point | None) -> Callable[..., Any]:
    r""":math:`\dot J_0` lambdified over :math:`(q, \dot q)`, the parameters at their defaults."""
    Jdot = jacobian_derivative(chain, frame, point, simplify=False).xreplace(chain.robot.defaults)
    return sp.lambdify([list(chain.robot.q), list(joint_rate_symbols(chain))], Jdot, modules="numpy", cse=True)


@memoized()
def _compiled_rate_map_derivative(chain: Chain, x_p: PositionSpec, x_r: OrientationSpec) -> Callable[..., Any]:
    r""":math:`\dot E` lambdified over the coordinates and their rates (kept per chain, like every compiled map)."""
    coords = [*x_p.coordinates, *x_r.coordinates]
    coord_rates = [*coordinate_rates(x_p), *coordinate_rates(x_r)]
    E_dot = _rate_map(x_p, x_r)[1].xreplace(chain.robot.defaults)
    return sp.lambdify([coords, coord_rates], E_dot, modules="numpy", cse=True)


def representation_jacobian_derivative_at(
    robot: Robot | Chain,
    q: Sequence[float],
    q_dot: Sequence[float],
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point | None = None,
    frame: Frame = 0,
    *,
    tol: float = 1e-9,
) -> NumericRepresentationJacobianDerivative:
    r"""Evaluate :math:`J_x`, :math:`\dot J_x` and the bias :math:`\dot J_x \dot q` at the state :math:`(q, \dot q)`.

    :math:`x` is extracted from the forward kinematics as in
    :func:`~symjac.analysis.representations.jacobian.representation_jacobian_at` (same arguments, same refusal of
    representation singularities, raised as :class:`~symjac.errors.RepresentationError`); :math:`\dot J_0` and
    :math:`\dot E` are compiled once per chain and evaluated at :math:`(q, \dot q)` and :math:`(x, \dot x)`, so the
    (possibly large) symbolic :math:`\dot J_x` is never built.

    Examples
    --------
    >>> from symjac import load_robot
    >>> value = representation_jacobian_derivative_at(load_robot("planar2r"), [0.0, np.pi / 2], [0.0, 1.0],
    ...                                               "rpy", "cylindrical")
    >>> value.bias.round(4)  # joint 2 alone: rho and phi_c accelerate as the tip circles joint 2; the yaw does not
    array([-0.1524, -0.1071,  0.    ,  0.    ,  0.    ,  0.    ])
    """
    chain = as_chain(robot)
    n = chain.robot.n_coordinates
    rates = np.asarray(q_dot, dtype=float)
    if rates.shape != (n,) or not np.all(np.isfinite(rates)):
        raise ArgumentError(f"q_dot must be {n} finite numbers for {chain.robot.name}, got {list(q_dot)}")
    value = representation_jacobian_at(chain, q, orientation, position, point, frame, tol=tol)
    jdot = _compiled_jacobian_derivative(chain, frame, point)
    edot = _compiled_rate_map_derivative(chain, representation(position, "position"),
                                         representation(orientation, "orientation"))
    Jdot_0 = np.asarray(jdot(np.asarray(q, dtype=float), rates), dtype=float)
    x_dot = value.J_x @ rates
    E_dot = np.asarray(edot(value.x, x_dot), dtype=float)
    Jdot_x = E_dot @ value.J_0 + value.E @ Jdot_0
    return NumericRepresentationJacobianDerivative(value.x, x_dot, value.E, E_dot, value.J_0, Jdot_0, value.J_x,
                                                   Jdot_x, Jdot_x @ rates, value.factors)
