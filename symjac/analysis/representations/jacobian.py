r"""Representation Jacobians of a robot: :math:`J_x = \mathrm{diag}(E_p, E_r)\,J_0` (course chapter, 4.36-4.38).

The symbolic result is derived once per chain (:meth:`symjac.kinematics.chain.Chain.memo`); the numeric one extracts
:math:`x` from the forward kinematics and refuses poses on a representation singularity.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.representations.extraction import extract, extract_position
from symjac.analysis.representations.maps import position_rate_matrix, rate_matrix, representation_singularities
from symjac.analysis.representations.registry import (
    Orientation,
    OrientationSpec,
    Position,
    PositionSpec,
    RepresentationSingularity,
    representation,
)
from symjac.errors import RepresentationError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import Point, jacobian, point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.kinematics.numeric import numeric_at
from symjac.model.robot import Robot

__all__ = [
    "NumericRepresentationJacobian",
    "RepresentationJacobian",
    "representation_jacobian",
    "representation_jacobian_at",
]


@dataclass(frozen=True)
class RepresentationJacobian:
    r"""A representation Jacobian :math:`J_x = E(x)\,J_0` with its rate map and representation singularities.

    Parameters
    ----------
    orientation, position : str
        The names of the representations of :math:`x_r` and :math:`x_p` (``"rpy"`` for extrinsic x-y-z).
    frame : int or "world"
        The fixed frame everything is expressed in ({0} or "world").
    point : tuple of 3 sympy.Expr
        Where :math:`x_p` is taken: coordinates in frame {n} (the tool point for ``point="tool"``).
    coordinates : tuple of sympy.Symbol
        :math:`x = [x_p; x_r]`, 3 + m symbols.
    E : sympy.ImmutableMatrix, shape (3 + m, 6)
        :math:`\mathrm{diag}(E_p, E_r)`, in the coordinates.
    J_0 : sympy.ImmutableMatrix, shape (6, n)
        The basic Jacobian, rows :math:`[v; \omega]` in ``frame``, at ``point``.
    J_x : sympy.ImmutableMatrix, shape (3 + m, n)
        :math:`E\,J_0`, written in both the coordinates :math:`x` and the joint variables (the textbook form
        :math:`J_x(q) = E(x) J_0(q)`; substitute :math:`x(q)` numerically, see :func:`representation_jacobian_at`).
    singularities : tuple of RepresentationSingularity
        Where :math:`E` does not exist: position ones first, then orientation ones. These are properties of the
        chosen coordinates, not of the arm (its own singularities are those of :math:`J_0`).
    """

    orientation: str
    position: str
    frame: Frame
    point: tuple[sp.Expr, sp.Expr, sp.Expr]
    coordinates: tuple[sp.Symbol, ...]
    E: sp.ImmutableMatrix
    J_0: sp.ImmutableMatrix
    J_x: sp.ImmutableMatrix
    singularities: tuple[RepresentationSingularity, ...]


@dataclass(frozen=True, eq=False)
class NumericRepresentationJacobian:
    r"""A representation Jacobian evaluated at one configuration (see :func:`representation_jacobian_at`).

    Parameters
    ----------
    x : numpy.ndarray, shape (3 + m,)
        :math:`[x_p; x_r]` extracted from the forward kinematics.
    E : numpy.ndarray, shape (3 + m, 6)
    J_0 : numpy.ndarray, shape (6, n)
    J_x : numpy.ndarray, shape (3 + m, n)
    factors : tuple of float
        The value of each singular factor of :attr:`RepresentationJacobian.singularities` at ``x``; a small
        value warns that :math:`E` (and so :math:`J_x`) is large and ill-conditioned.
    """

    x: np.ndarray
    E: np.ndarray
    J_0: np.ndarray
    J_x: np.ndarray
    factors: tuple[float, ...]


def _orientation(chain: Chain, orientation: Orientation) -> OrientationSpec:
    return representation(orientation, "orientation")


def _position(chain: Chain, position: Position) -> PositionSpec:
    return representation(position, "position")


def _fixed_frame(chain: Chain, frame: Frame) -> Frame:
    if chain.position(frame) > 0:
        raise RepresentationError(f"representation Jacobians are measured in a fixed frame (0 or 'world'), "
                                  f"not in frame {frame!r}")
    return frame_of(chain, frame)


@memoized(orientation=_orientation, position=_position, frame=_fixed_frame, point=point_vector)
def representation_jacobian(
    chain: Chain,
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point | None = None,
    frame: Frame = 0,
) -> RepresentationJacobian:
    r"""The representation Jacobian :math:`J_x = E(x)\,J_0` of ``robot`` (course chapter, eqs. 4.36-4.38).

    .. math::
        J_x = \begin{bmatrix} E_p(x_p) & 0 \\ 0 & E_r(x_r) \end{bmatrix}
              \begin{bmatrix} J_v \\ J_\omega \end{bmatrix}

    Parameters
    ----------
    robot : Robot or Chain
    orientation : str or EulerConvention
        One of :data:`REPRESENTATIONS` (or a representation value): the orientation of the frame at ``point`` (the
        tool frame for ``point="tool"``, frame {n} otherwise).
    position : str
        One of :data:`POSITIONS`: the coordinates of ``point``.
    point : "tool", "flange", "wrist_centre", sequence of 3, or None (the end of the chain)
        As for :func:`symjac.kinematics.jacobian`.
    frame : 0 or "world"
        The fixed frame x is measured in. Moving frames are refused: the rates of a pose relative to a moving frame
        are not :math:`E` times the absolute twist.

    Returns
    -------
    RepresentationJacobian

    Examples
    --------
    >>> from symjac import load_robot
    >>> result = representation_jacobian(load_robot("planar2r"), "rpy", "cylindrical")
    >>> result.J_x.shape, [str(s.factor) for s in result.singularities]
    ((6, 2), ['rho', 'cos(theta)'])
    >>> result.J_x[5, :]  # the yaw rate of a planar arm
    Matrix([[1, 1]])
    >>> result.J_x[2, :]  # and its height rate
    Matrix([[0, 0]])
    """
    x_r = representation(orientation, "orientation")  # already the value (normalised by @memoized): typed here
    x_p = representation(position, "position")
    model = chain.robot
    coords = (*x_p.coordinates, *x_r.coordinates)
    # compared by name: a parameter "rho" with other assumptions is another Symbol but prints the same
    clash = sorted({str(s) for s in coords} & {str(s) for s in (*model.q, *model.parameter_symbols)})
    if clash:
        raise RepresentationError(f"{model.name}: the names {', '.join(clash)} are both robot symbols and "
                                  f"coordinates of the {x_p.name}/{x_r.name} representation")
    E = sp.diag(position_rate_matrix(x_p), rate_matrix(x_r))
    J_0 = jacobian(chain, frame=frame, point=point)
    singularities = representation_singularities(x_p) + representation_singularities(x_r)
    return RepresentationJacobian(x_r.name, x_p.name, frame, point, coords, sp.ImmutableMatrix(E),  # type: ignore[arg-type]
                                  sp.ImmutableMatrix(J_0), sp.ImmutableMatrix(E * J_0), singularities)


def representation_jacobian_at(
    robot: Robot | Chain,
    q: Sequence[float | sp.Expr],
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point | None = None,
    frame: Frame = 0,
    *,
    tol: float = 1e-9,
) -> NumericRepresentationJacobian:
    r"""Evaluate :math:`J_x = E(x(q))\,J_0(q)` at joint values ``q`` and the parameters' defaults.

    :math:`x` is extracted (:func:`extract`, :func:`extract_position`) from the forward kinematics of the frame at
    ``point`` relative to ``frame``.

    Raises
    ------
    RepresentationError
        When :math:`x` lies on a representation singularity (a singular factor below ``tol`` in magnitude), where
        :math:`J_x` does not exist; the message names the condition. Another representation will do there.

    Examples
    --------
    >>> from symjac import load_robot
    >>> value = representation_jacobian_at(load_robot("planar2r"), [0.0, np.pi / 2], "rpy", "spherical")
    >>> value.x.round(4)  # L1 = 0.5, L2 = 0.4: the tip at (0.5, 0.4, 0), yawed by 90 deg
    array([0.6403, 1.5708, 0.6747, 0.    , 0.    , 1.5708])
    >>> value.J_x.round(4)[[0, 2, 5]]  # r, phi_s and yaw rates
    array([[ 0.    , -0.3123],
           [ 1.    ,  0.3902],
           [ 1.    ,  1.    ]])
    """
    chain = as_chain(robot)
    result = representation_jacobian(chain, orientation, position, point, frame)
    target: Frame = "tool" if isinstance(point, str) and point == "tool" else chain.n_joints
    T = numeric_at(chain, chain.transform(frame, target), q)
    p = T[:3, 3] if target == "tool" else T[:3, :3] @ numeric_at(chain, sp.Matrix(result.point), q).ravel() + T[:3, 3]
    x = np.concatenate([extract_position(result.position, p), extract(result.orientation, T[:3, :3])])
    values = dict(zip(result.coordinates, x.tolist(), strict=True))
    factors = tuple(float(s.factor.xreplace(values)) for s in result.singularities)
    for singularity, value in zip(result.singularities, factors, strict=True):
        if abs(value) <= tol:
            raise RepresentationError(f"{chain.robot.name} at q = {list(q)}: {singularity.representation} "
                                      f"coordinates are singular here ({singularity}); J_x does not exist")
    E = np.array(result.E.xreplace(values).evalf(), dtype=float)
    J_0 = numeric_at(chain, result.J_0, q)
    return NumericRepresentationJacobian(x, E, J_0, E @ J_0, factors)
