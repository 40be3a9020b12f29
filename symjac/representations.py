r"""Representation Jacobians :math:`J_x = E(x)\,J_0`: end-effector rates in the coordinates a user picks.

The basic Jacobian :math:`J_0` maps joint rates to the twist :math:`[v; \omega]`. No set of orientation coordinates
has :math:`\omega` as its time derivative, but every one has a rate map that depends only on the coordinates
themselves (seed 000, section 4.3):

.. math::
    \dot x_p = E_p(x_p)\,v, \qquad \dot x_r = E_r(x_r)\,\omega, \qquad
    J_x = \begin{bmatrix} E_p & 0 \\ 0 & E_r \end{bmatrix} J_0 = E(x)\,J_0 .

Conventions (one set, used by every function here):

* :math:`v` and :math:`\omega` are expressed in the base frame {0} (or "world"), as the rows of
  :func:`symjac.jacobian` with ``frame=0``; :math:`\omega` is the spatial angular velocity,
  :math:`\dot R = \hat\omega R`.
* **Euler angles** (all twelve orders) rotate about the axes of the *moving* frame, so the named axes multiply left to
  right: ``"zyz"`` is :math:`R = R_z(\alpha) R_y(\beta) R_z(\gamma)` (the wrist of seed 002), ``"xyz"`` is
  :math:`R_x(\alpha) R_y(\beta) R_z(\gamma)`. Proper orders (first axis = last axis) have :math:`\beta \in [0, \pi]`,
  Tait-Bryan orders :math:`\beta \in [-\pi/2, \pi/2]`; the other angles lie in :math:`(-\pi, \pi]`.
* **Roll-pitch-yaw** ``"rpy"``: rotations about the *fixed* axes x, y, z, in that order, by roll :math:`\phi`, pitch
  :math:`\theta` and yaw :math:`\psi`: :math:`R = R_z(\psi) R_y(\theta) R_x(\phi)` (Craig's X-Y-Z fixed angles, and the
  ``rpy`` field of robot files, :func:`symjac.transforms.rotation_rpy`). Coordinates are ordered
  :math:`(\phi, \theta, \psi)`; it is ``"zyx"`` with the angles listed in reverse.
* **Direction cosines**: the nine entries of :math:`R`, row by row :math:`(r_{11}, r_{12}, \ldots, r_{33})`;
  :math:`\dot R = \hat\omega R`.
* **Euler parameters** (unit quaternion) ``"quaternion"``: :math:`(\eta, \epsilon_x, \epsilon_y, \epsilon_z)` with
  :math:`R = I + 2\eta\hat\epsilon + 2\hat\epsilon^2` and :math:`\eta \ge 0` when extracted.
* **Equivalent axis-angle** ``"axis_angle"``: unit axis :math:`k` and angle :math:`\vartheta \in [0, \pi]`,
  :math:`(k_x, k_y, k_z, \vartheta)`, :math:`R = c_\vartheta I + (1 - c_\vartheta) k k^T + s_\vartheta \hat k` (four
  coordinates, as the notes count them).
* **Position**: ``"cartesian"`` :math:`(x, y, z)`; ``"spherical"`` :math:`(r, \theta_s, \phi_s)` with polar angle
  :math:`\theta_s` from the z-axis and azimuth :math:`\phi_s`; ``"cylindrical"`` :math:`(\rho, \phi_c, z)`.

Representation singularities (where :math:`E` does not exist because the coordinates stop describing every nearby
pose, e.g. gimbal lock at :math:`s_\beta = 0` for Z-Y-Z) belong to the representation, not to the arm; they are
reported by :func:`representation_singularities`, apart from the kinematic singularities of :math:`J_0`.

The seed's printed :math:`E_r` (4.31) is, in this convention, the Z-X-Z matrix (``rate_matrix("zxz")``); the Z-Y-Z
angles of seed 002 give the matrix below.

Examples
--------
>>> rate_matrix("zyz")
Matrix([
[-cos(alpha)*cos(beta)/sin(beta), -sin(alpha)*cos(beta)/sin(beta), 1],
[                    -sin(alpha),                      cos(alpha), 0],
[           cos(alpha)/sin(beta),            sin(alpha)/sin(beta), 0]])
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache, lru_cache
from typing import Literal, get_args

import numpy as np
import sympy as sp

from symjac.chain import Frame, chain_of
from symjac.errors import RepresentationError
from symjac.jacobian import Point, jacobian, point_vector
from symjac.model import Robot
from symjac.numeric import evaluate_at
from symjac.simplify import AngleBasis, simplify_matrix
from symjac.transforms import Axis, rotation, skew

__all__ = [
    "EULER_ORDERS",
    "GIMBAL_LOCK_TOLERANCE",
    "POSITIONS",
    "REPRESENTATIONS",
    "NumericRepresentationJacobian",
    "Orientation",
    "Position",
    "RepresentationError",
    "RepresentationJacobian",
    "RepresentationSingularity",
    "angular_velocity_matrix",
    "coordinates",
    "extract",
    "extract_position",
    "point_from",
    "position_rate_matrix",
    "rate_matrix",
    "representation_jacobian",
    "representation_jacobian_at",
    "representation_singularities",
    "rotation_from",
]

Orientation = Literal[
    "zyz", "zxz", "xyx", "xzx", "yxy", "yzy",  # proper Euler angles
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx",  # Tait-Bryan angles
    "rpy", "direction_cosines", "quaternion", "axis_angle",
]
Position = Literal["cartesian", "spherical", "cylindrical"]

REPRESENTATIONS: tuple[str, ...] = get_args(Orientation)
EULER_ORDERS: tuple[str, ...] = REPRESENTATIONS[:12]
POSITIONS: tuple[str, ...] = get_args(Position)

# A gimbal-lock test on |sin(beta)| (proper) or |cos(beta)| (Tait-Bryan). The extraction below stays accurate to
# rounding for any larger value, so the threshold only decides when the seed's alpha = 0 convention takes over.
GIMBAL_LOCK_TOLERANCE = 1e-12

_AXIS: dict[str, Axis] = {"x": "x", "y": "y", "z": "z"}
_INDEX = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class RepresentationSingularity:
    r"""Where the rate map :math:`E` of one representation does not exist: ``factor`` :math:`= 0`.

    Parameters
    ----------
    representation : str
        The orientation or position representation it belongs to.
    factor : sympy.Expr
        A factor of :math:`\det(\partial x / \partial\,\text{pose})^{-1}`, in the representation's coordinates.
    variable : sympy.Symbol
        The coordinate the condition restricts.
    solutions : tuple of sympy.Expr
        The values of ``variable`` in its range where ``factor`` vanishes.
    explanation : str
        What goes wrong there, in one sentence.
    """

    representation: str
    factor: sp.Expr
    variable: sp.Symbol
    solutions: tuple[sp.Expr, ...]
    explanation: str

    def __str__(self) -> str:
        values = " or ".join(str(value) for value in self.solutions)
        return f"{self.factor} = 0 ({self.variable} = {values}): {self.explanation}"


@dataclass(frozen=True)
class RepresentationJacobian:
    r"""A representation Jacobian :math:`J_x = E(x)\,J_0` with its rate map and representation singularities.

    Parameters
    ----------
    orientation, position : str
        The representations of :math:`x_r` and :math:`x_p`.
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

    orientation: Orientation
    position: Position
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


# --- names and coordinates ---------------------------------------------------------------------------------------


def _real(*names: str, **assumptions: bool) -> tuple[sp.Symbol, ...]:
    return tuple(sp.Symbol(name, real=True, **assumptions) for name in names)


_COORDINATES: dict[str, tuple[sp.Symbol, ...]] = {
    **{order: _real("alpha", "beta", "gamma") for order in EULER_ORDERS},
    "rpy": _real("phi", "theta", "psi"),
    "direction_cosines": _real(*(f"r{i}{j}" for i in range(1, 4) for j in range(1, 4))),
    "quaternion": _real("eta", "epsilon_x", "epsilon_y", "epsilon_z"),
    "axis_angle": _real("k_x", "k_y", "k_z", "vartheta"),
    "cartesian": _real("x", "y", "z"),
    "spherical": (*_real("r", nonnegative=True), *_real("theta_s", "phi_s")),
    "cylindrical": (*_real("rho", nonnegative=True), *_real("phi_c", "z")),
}


def coordinates(name: str) -> tuple[sp.Symbol, ...]:
    r"""The coordinate symbols of an orientation or position representation, in the order of :math:`x`.

    Examples
    --------
    >>> coordinates("quaternion")
    (eta, epsilon_x, epsilon_y, epsilon_z)
    >>> coordinates("spherical")
    (r, theta_s, phi_s)
    """
    _check_name(name, REPRESENTATIONS + POSITIONS)
    return _COORDINATES[name]


def _check_name(name: str, allowed: tuple[str, ...]) -> None:
    if name not in allowed:
        kind = "orientation" if allowed == REPRESENTATIONS else "position" if allowed == POSITIONS else "representation"
        raise RepresentationError(f"unknown {kind} representation {name!r}; choose one of {', '.join(allowed)}")


def _bind(matrix: sp.MatrixBase, name: str, coords: Sequence[sp.Expr] | None) -> sp.Matrix:
    """``matrix`` (built on the default symbols of ``name``) with the caller's coordinates substituted."""
    if coords is None:
        return sp.Matrix(matrix)
    values = list(coords)
    default = _COORDINATES[name]
    if len(values) != len(default):
        raise RepresentationError(f"{name} has {len(default)} coordinates, got {len(values)}")
    return sp.Matrix(matrix).xreplace(dict(zip(default, map(sp.sympify, values), strict=True)))


def _factors(name: str) -> list[tuple[Axis, int]]:
    """A minimal angle set as rotation factors in product order: (axis, index of its coordinate)."""
    if name == "rpy":
        return [("z", 2), ("y", 1), ("x", 0)]
    return [(_AXIS[letter], index) for index, letter in enumerate(name)]


def _is_proper(order: str) -> bool:
    return order[0] == order[2]


# --- rotation and point from coordinates ---------------------------------------------------------------------------


def rotation_from(name: Orientation, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The rotation matrix :math:`R(x_r)` of orientation coordinates (symbolic, or numbers given as ``coords``).

    .. math:: R_{zyz}(\alpha, \beta, \gamma) = R_z(\alpha)\,R_y(\beta)\,R_z(\gamma), \quad
              R_{rpy}(\phi, \theta, \psi) = R_z(\psi)\,R_y(\theta)\,R_x(\phi), \ \ldots

    Parameters
    ----------
    name : str
        One of :data:`REPRESENTATIONS`.
    coords : sequence, optional
        Values or expressions for the coordinates (default: the symbols of :func:`coordinates`).

    Returns
    -------
    R : sympy.Matrix, shape (3, 3)

    Examples
    --------
    >>> rotation_from("zyz", [0, sp.pi / 2, 0])
    Matrix([
    [ 0, 0, 1],
    [ 0, 1, 0],
    [-1, 0, 0]])
    """
    _check_name(name, REPRESENTATIONS)
    return _bind(_rotation(name), name, coords)


@cache
def _rotation(name: str) -> sp.ImmutableMatrix:
    c = _COORDINATES[name]
    if name == "direction_cosines":
        return sp.ImmutableMatrix(3, 3, c)
    if name == "quaternion":
        eta, eps = c[0], skew(c[1:])
        return sp.ImmutableMatrix(sp.eye(3) + 2 * eta * eps + 2 * eps * eps)
    if name == "axis_angle":
        k, angle = sp.Matrix(c[:3]), c[3]
        R = sp.cos(angle) * sp.eye(3) + (1 - sp.cos(angle)) * k * k.T + sp.sin(angle) * skew(c[:3])
        return sp.ImmutableMatrix(R)
    R = sp.eye(3)
    for axis, index in _factors(name):
        R = R * rotation(axis, c[index])
    return sp.ImmutableMatrix(R)


def point_from(kind: Position, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""Cartesian position :math:`p(x_p)` of position coordinates.

    .. math:: p_{sph} = r\,[s_{\theta_s} c_{\phi_s},\ s_{\theta_s} s_{\phi_s},\ c_{\theta_s}]^T, \quad
              p_{cyl} = [\rho\,c_{\phi_c},\ \rho\,s_{\phi_c},\ z]^T

    Examples
    --------
    >>> point_from("cylindrical").T
    Matrix([[rho*cos(phi_c), rho*sin(phi_c), z]])
    """
    _check_name(kind, POSITIONS)
    return _bind(_point(kind), kind, coords)


@cache
def _point(kind: str) -> sp.ImmutableMatrix:
    a, b, c = _COORDINATES[kind]
    if kind == "spherical":
        return sp.ImmutableMatrix([a * sp.sin(b) * sp.cos(c), a * sp.sin(b) * sp.sin(c), a * sp.cos(b)])
    if kind == "cylindrical":
        return sp.ImmutableMatrix([a * sp.cos(b), a * sp.sin(b), c])
    return sp.ImmutableMatrix([a, b, c])


# --- rate matrices -------------------------------------------------------------------------------------------------


def angular_velocity_matrix(name: Orientation, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The map :math:`B(x_r)` from coordinate rates to the angular velocity in {0}: :math:`\omega = B\,\dot x_r`.

    For the three-angle sets, column j is the axis of the j-th rotation as the base frame sees it,
    e.g. Z-Y-Z: :math:`B = [z,\ R_z(\alpha) y,\ R_z(\alpha) R_y(\beta) z]`, and :math:`E_r = B^{-1}`. For the
    redundant sets :math:`B` is the left inverse of :math:`E_r` on unit-norm or orthonormal coordinates:
    direction cosines :math:`B = E_r^T / 2`, quaternion :math:`B = 2[-\epsilon,\ \eta I + \hat\epsilon]`, axis-angle
    :math:`B = [s_\vartheta I + (1 - c_\vartheta)\hat k,\ k]`.

    Returns
    -------
    B : sympy.Matrix, shape (3, m)

    Examples
    --------
    >>> angular_velocity_matrix("zyz")
    Matrix([
    [0, -sin(alpha), sin(beta)*cos(alpha)],
    [0,  cos(alpha), sin(alpha)*sin(beta)],
    [1,           0,            cos(beta)]])
    """
    _check_name(name, REPRESENTATIONS)
    return _bind(_angular_velocity_matrix(name), name, coords)


@cache
def _angular_velocity_matrix(name: str) -> sp.ImmutableMatrix:
    c = _COORDINATES[name]
    if name == "direction_cosines":
        return sp.ImmutableMatrix(_rate_matrix(name).T / 2)
    if name == "quaternion":
        eta, eps = c[0], sp.Matrix(c[1:])
        return sp.ImmutableMatrix(2 * sp.Matrix.hstack(-eps, eta * sp.eye(3) + skew(c[1:])))
    if name == "axis_angle":
        k, angle = sp.Matrix(c[:3]), c[3]
        return sp.ImmutableMatrix(sp.Matrix.hstack(sp.sin(angle) * sp.eye(3) + (1 - sp.cos(angle)) * skew(c[:3]), k))
    B = sp.zeros(3, 3)
    R = sp.eye(3)
    for axis, index in _factors(name):
        B[:, index] = R[:, _INDEX[axis]]
        R = R * rotation(axis, c[index])
    return sp.ImmutableMatrix(B)


def rate_matrix(name: Orientation, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The orientation rate matrix :math:`E_r(x_r)`: :math:`\dot x_r = E_r\,\omega`, :math:`\omega` in {0}.

    .. math::
        E_{zyz} = \begin{bmatrix} -c_\alpha c_\beta / s_\beta & -s_\alpha c_\beta / s_\beta & 1 \\
                                  -s_\alpha & c_\alpha & 0 \\ c_\alpha / s_\beta & s_\alpha / s_\beta & 0
                  \end{bmatrix}, \quad
        \dot R = \hat\omega R \ \text{(direction cosines)}, \quad
        \begin{bmatrix} \dot\eta \\ \dot\epsilon \end{bmatrix} =
        \frac12 \begin{bmatrix} -\epsilon^T \\ \eta I - \hat\epsilon \end{bmatrix} \omega, \quad
        \begin{bmatrix} \dot k \\ \dot\vartheta \end{bmatrix} =
        \begin{bmatrix} -\tfrac12 (\hat k + \cot(\vartheta/2)\,\hat k^2) \\ k^T \end{bmatrix} \omega

    For angle sets :math:`E_r = B^{-1}` (:func:`angular_velocity_matrix`); it depends on the first two angles only.

    Returns
    -------
    E_r : sympy.Matrix, shape (m, 3)
        m = 3 (angle sets), 9 (direction cosines, row by row) or 4 (quaternion, axis-angle).

    Examples
    --------
    >>> rate_matrix("quaternion")
    Matrix([
    [-epsilon_x/2, -epsilon_y/2, -epsilon_z/2],
    [       eta/2,  epsilon_z/2, -epsilon_y/2],
    [-epsilon_z/2,        eta/2,  epsilon_x/2],
    [ epsilon_y/2, -epsilon_x/2,        eta/2]])
    """
    _check_name(name, REPRESENTATIONS)
    return _bind(_rate_matrix(name), name, coords)


@cache
def _rate_matrix(name: str) -> sp.ImmutableMatrix:
    c = _COORDINATES[name]
    if name == "direction_cosines":
        R = sp.Matrix(3, 3, c)
        units = sp.eye(3)
        columns = [(skew(units[:, m]) * R).reshape(9, 1) for m in range(3)]  # reshape is row-major
        return sp.ImmutableMatrix(sp.Matrix.hstack(*columns))
    if name == "quaternion":
        eta, eps = c[0], sp.Matrix(c[1:])
        return sp.ImmutableMatrix(sp.Matrix.vstack(-eps.T, eta * sp.eye(3) - skew(c[1:])) / 2)
    if name == "axis_angle":
        k_hat, angle = skew(c[:3]), c[3]
        E_k = -(k_hat + sp.cot(angle / 2) * k_hat * k_hat) / 2
        return sp.ImmutableMatrix(sp.Matrix.vstack(E_k, sp.Matrix([c[:3]])))
    E, _ = _inverse(sp.Matrix(_angular_velocity_matrix(name)), c)
    return sp.ImmutableMatrix(E)


def position_rate_matrix(kind: Position, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The position rate matrix :math:`E_p(x_p) = (\partial p / \partial x_p)^{-1}`: :math:`\dot x_p = E_p\,v`.

    Returns
    -------
    E_p : sympy.Matrix, shape (3, 3)

    Examples
    --------
    >>> position_rate_matrix("cylindrical")
    Matrix([
    [     cos(phi_c),     sin(phi_c), 0],
    [-sin(phi_c)/rho, cos(phi_c)/rho, 0],
    [              0,              0, 1]])
    """
    _check_name(kind, POSITIONS)
    return _bind(_position_rate_matrix(kind), kind, coords)


@cache
def _position_rate_matrix(kind: str) -> sp.ImmutableMatrix:
    c = _COORDINATES[kind]
    E, _ = _inverse(sp.Matrix(_point(kind)).jacobian(sp.Matrix(c)), c)
    return sp.ImmutableMatrix(E)


def _inverse(B: sp.Matrix, coords: Sequence[sp.Symbol]) -> tuple[sp.Matrix, sp.Expr]:
    r""":math:`B^{-1} = \mathrm{adj}(B) / \det B`, entries in trigonometric normal form, and :math:`\det B`."""
    angles = [s for s in coords if any(f.has(s) for f in B.atoms(sp.sin, sp.cos))]
    basis = AngleBasis.of(angles)
    det = simplify_matrix(sp.Matrix([B.det()]), basis)[0]
    adjugate = simplify_matrix(B.adjugate(), basis)

    def divide(entry: sp.Expr) -> sp.Expr:
        # the normal form writes s^2 as 1 - c^2, which hides a common factor with det; trigsimp finds it, and the
        # tangents it leaves are written back as s / c, as in the textbook
        quotient = sp.trigsimp(sp.factor(entry / det))
        quotient = quotient.replace(sp.tan, lambda a: sp.sin(a) / sp.cos(a))
        return quotient.replace(sp.cot, lambda a: sp.cos(a) / sp.sin(a))

    return adjugate.applyfunc(divide), sp.factor(det)


# --- representation singularities ---------------------------------------------------------------------------------


def representation_singularities(name: str) -> tuple[RepresentationSingularity, ...]:
    r"""Where the rate map of a representation does not exist (empty for direction cosines and quaternions).

    For the three-angle sets the factors are those of :math:`\det B` (:func:`angular_velocity_matrix`):
    :math:`s_\beta` for proper Euler orders, :math:`c_\beta` for Tait-Bryan orders and :math:`c_\theta` for
    roll-pitch-yaw. Axis-angle fails at :math:`s_{\vartheta/2} = 0` (no axis at the identity), spherical coordinates
    at :math:`r = 0` and on the polar axis :math:`s_{\theta_s} = 0`, cylindrical ones on the axis :math:`\rho = 0`.

    Examples
    --------
    >>> [str(s.factor) for s in representation_singularities("zyz")]
    ['sin(beta)']
    >>> representation_singularities("quaternion")
    ()
    """
    _check_name(name, REPRESENTATIONS + POSITIONS)
    return _singularities(name)


@cache
def _singularities(name: str) -> tuple[RepresentationSingularity, ...]:
    c = _COORDINATES[name]
    if name in EULER_ORDERS or name == "rpy":
        _, det = _inverse(sp.Matrix(_angular_velocity_matrix(name)), c)
        (factor, _), = sp.factor_list(det)[1]
        middle = c[1]
        if name == "rpy":
            solutions: tuple[sp.Expr, ...] = (-sp.pi / 2, sp.pi / 2)
            text = ("pitch at +-90 deg: the roll and yaw axes line up (gimbal lock); only their sum or difference is "
                    "defined, so roll and yaw rates are unbounded")
        elif _is_proper(name):
            solutions = (sp.S.Zero, sp.pi)
            text = (f"the first and third rotation axes ({name[0]}) line up (gimbal lock); only alpha + gamma "
                    "(beta = 0) or alpha - gamma (beta = pi) is defined, so their rates are unbounded")
        else:
            solutions = (-sp.pi / 2, sp.pi / 2)
            text = (f"the first and third rotation axes ({name[0]} and {name[2]}) line up (gimbal lock); only the sum "
                    "or difference of alpha and gamma is defined, so their rates are unbounded")
        return (RepresentationSingularity(name, factor, middle, solutions, text),)
    if name == "axis_angle":
        angle = c[3]
        text = "the identity orientation has no rotation axis, so the axis rates are unbounded"
        return (RepresentationSingularity(name, sp.sin(angle / 2), angle, (sp.S.Zero,), text),)
    if name == "spherical":
        r, polar, _ = c
        return (
            RepresentationSingularity(name, r, r, (sp.S.Zero,), "at the origin both angles are undefined"),
            RepresentationSingularity(name, sp.sin(polar), polar, (sp.S.Zero, sp.pi),
                                      "on the polar (z) axis the azimuth is undefined"),
        )
    if name == "cylindrical":
        rho = c[0]
        return (RepresentationSingularity(name, rho, rho, (sp.S.Zero,), "on the z-axis the azimuth is undefined"),)
    return ()


# --- numeric extraction --------------------------------------------------------------------------------------------


def extract(name: Orientation, R: np.ndarray | Sequence[Sequence[float]], *,
            tol: float = GIMBAL_LOCK_TOLERANCE) -> np.ndarray:
    r"""Orientation coordinates of a numeric rotation matrix, such that ``rotation_from(name, x) == R``.

    Euler angles follow seed 002 for Z-Y-Z and the same pattern for every order (by relabelling the axes):
    :math:`\beta = \mathrm{atan2}(\sqrt{r_{31}^2 + r_{32}^2}, r_{33})`, :math:`\alpha = \mathrm{atan2}(r_{23}, r_{13})`,
    and :math:`\gamma` from the better-conditioned of :math:`\alpha \pm \gamma` (read off the upper-left block) so
    that the pose is reproduced to rounding even close to gimbal lock. At gimbal lock (:math:`s_\beta` below
    ``tol``) :math:`\alpha = 0` and the whole rotation goes into :math:`\gamma`:
    :math:`\gamma = \mathrm{atan2}(-r_{12}, r_{11})` at :math:`\beta = 0` and
    :math:`\mathrm{atan2}(r_{12}, -r_{11})` at :math:`\beta = \pi`. Tait-Bryan orders likewise set the first angle
    to 0 at :math:`\beta = \pm\pi/2`, roll-pitch-yaw sets the yaw to 0.

    The quaternion uses Shepperd's method (the largest of :math:`\eta^2, \epsilon_x^2, \epsilon_y^2, \epsilon_z^2`
    is computed first), with :math:`\eta \ge 0`; at :math:`\eta = 0` its first nonzero entry is made positive.
    Axis-angle comes from the quaternion: :math:`\vartheta = 2\,\mathrm{atan2}(|\epsilon|, \eta) \in [0, \pi]`,
    :math:`k = \epsilon / |\epsilon|`, and :math:`k = z` at :math:`\vartheta = 0`.

    Parameters
    ----------
    name : str
        One of :data:`REPRESENTATIONS`.
    R : array_like, shape (3, 3)
        A rotation matrix (orthonormal to 1e-6, determinant +1).
    tol : float
        Gimbal-lock threshold on :math:`|s_\beta|` (proper) or :math:`|c_\beta|` (Tait-Bryan).

    Returns
    -------
    x_r : numpy.ndarray, shape (m,)

    Examples
    --------
    >>> R = np.array(rotation_from("zyz", [0.3, 0.0, 0.5]), dtype=float)  # gimbal lock: only alpha + gamma counts
    >>> extract("zyz", R).round(12)
    array([0. , 0. , 0.8])
    """
    _check_name(name, REPRESENTATIONS)
    M = _rotation_matrix(R)
    if name == "direction_cosines":
        x = M.reshape(9)
    elif name == "quaternion":
        x = _quaternion(M)
    elif name == "axis_angle":
        eta, eps = (q := _quaternion(M))[0], q[1:]
        norm = float(np.linalg.norm(eps))
        axis = eps / norm if norm > 0.0 else np.array([0.0, 0.0, 1.0])
        x = np.array([*axis, 2.0 * math.atan2(norm, eta)])
    elif name == "rpy":
        x = _euler(M, "zyx", tol)[::-1]
    else:
        x = _euler(M, name, tol)
    return x + 0.0  # a new array, and no -0.0


def _rotation_matrix(R: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    M = np.asarray(R, dtype=float)
    if M.shape != (3, 3):
        raise RepresentationError(f"a rotation matrix must be 3 x 3, got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise RepresentationError("the rotation matrix has non-finite entries")
    if not np.allclose(M.T @ M, np.eye(3), atol=1e-6) or np.linalg.det(M) < 0:
        raise RepresentationError("the matrix is not a rotation (R^T R != I or det R < 0)")
    return M


def _wrap(angle: float) -> float:
    """The same angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _euler(R: np.ndarray, order: str, tol: float) -> np.ndarray:
    r"""Euler angles of any order, by relabelling the axes so that the order reads Z-Y-Z or Z-Y-X.

    With :math:`P` the rotation taking axis ``order[0]`` to z, ``order[1]`` to y and the remaining axis to
    :math:`\pm x`, :math:`P R_a(t) P^T = R_{Pa}(t)`, so :math:`P R P^T` has the same angles in the canonical order
    (the third one negated when the remaining axis lands on -x).
    """
    i, j = _INDEX[order[0]], _INDEX[order[1]]
    k = 3 - i - j
    P = np.zeros((3, 3))
    P[0, k], P[1, j], P[2, i] = 1.0, 1.0, 1.0
    sign = float(round(np.linalg.det(P)))
    P[0, k] = sign
    M = P @ R @ P.T
    if _is_proper(order):
        return np.array(_zyz(M, tol))
    alpha, beta, gamma = _zyx(M, tol)
    return np.array([alpha, beta, _wrap(sign * gamma)])


def _zyz(R: np.ndarray, tol: float) -> tuple[float, float, float]:
    # alpha + gamma has weight 1 + c_beta in the upper-left block, alpha - gamma weight 1 - c_beta
    plus = math.atan2(R[1, 0] - R[0, 1], R[0, 0] + R[1, 1])
    minus = math.atan2(-(R[1, 0] + R[0, 1]), R[1, 1] - R[0, 0])
    s_beta = math.hypot(R[0, 2], R[1, 2])
    beta = math.atan2(s_beta, R[2, 2])
    if s_beta <= tol:
        return 0.0, beta, _wrap(plus if R[2, 2] > 0 else -minus)
    alpha = math.atan2(R[1, 2], R[0, 2])
    gamma = plus - alpha if R[2, 2] >= 0 else alpha - minus
    return alpha, beta, _wrap(gamma)


def _zyx(R: np.ndarray, tol: float) -> tuple[float, float, float]:
    # at beta = +pi/2 only gamma - alpha is defined, at beta = -pi/2 only gamma + alpha
    difference = math.atan2(R[0, 1] - R[1, 2], R[0, 2] + R[1, 1])
    total = math.atan2(-(R[0, 1] + R[1, 2]), R[1, 1] - R[0, 2])
    c_beta = math.hypot(R[0, 0], R[1, 0])
    beta = math.atan2(-R[2, 0], c_beta)
    if c_beta <= tol:
        return 0.0, beta, _wrap(difference if R[2, 0] < 0 else total)
    alpha = math.atan2(R[1, 0], R[0, 0])
    gamma = alpha + difference if R[2, 0] <= 0 else total - alpha
    return alpha, beta, _wrap(gamma)


def _quaternion(R: np.ndarray) -> np.ndarray:
    """Shepperd's method: start from the largest of 4 eta^2, 4 eps_x^2, 4 eps_y^2, 4 eps_z^2 (no cancellation)."""
    trace = R[0, 0] + R[1, 1] + R[2, 2]
    candidates = [trace, R[0, 0], R[1, 1], R[2, 2]]
    largest = int(np.argmax(candidates))
    if largest == 0:
        s = 2.0 * math.sqrt(max(1.0 + trace, 0.0))
        q = [s / 4, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    elif largest == 1:
        s = 2.0 * math.sqrt(max(1.0 + R[0, 0] - R[1, 1] - R[2, 2], 0.0))
        q = [(R[2, 1] - R[1, 2]) / s, s / 4, (R[0, 1] + R[1, 0]) / s, (R[0, 2] + R[2, 0]) / s]
    elif largest == 2:
        s = 2.0 * math.sqrt(max(1.0 - R[0, 0] + R[1, 1] - R[2, 2], 0.0))
        q = [(R[0, 2] - R[2, 0]) / s, (R[0, 1] + R[1, 0]) / s, s / 4, (R[1, 2] + R[2, 1]) / s]
    else:
        s = 2.0 * math.sqrt(max(1.0 - R[0, 0] - R[1, 1] + R[2, 2], 0.0))
        q = [(R[1, 0] - R[0, 1]) / s, (R[0, 2] + R[2, 0]) / s, (R[1, 2] + R[2, 1]) / s, s / 4]
    quaternion = np.array(q) / np.linalg.norm(q)
    leading = quaternion[np.flatnonzero(quaternion)[0]]
    return -quaternion if leading < 0 else quaternion


def extract_position(kind: Position, p: np.ndarray | Sequence[float]) -> np.ndarray:
    r"""Position coordinates of a numeric point, such that ``point_from(kind, x) == p``.

    Spherical :math:`r = |p|`, :math:`\theta_s = \mathrm{atan2}(\sqrt{x^2 + y^2}, z)`,
    :math:`\phi_s = \mathrm{atan2}(y, x)`; cylindrical :math:`\rho = \sqrt{x^2 + y^2}`,
    :math:`\phi_c = \mathrm{atan2}(y, x)`. On the z-axis the azimuth is 0 and at the origin :math:`\theta_s = 0`.

    Examples
    --------
    >>> extract_position("cylindrical", [0.0, 2.0, 1.0]).round(6)
    array([2.      , 1.570796, 1.      ])
    """
    _check_name(kind, POSITIONS)
    x, y, z = _point_vector(p)
    if kind == "spherical":
        rho = math.hypot(x, y)
        return np.array([math.hypot(rho, z), math.atan2(rho, z), math.atan2(y, x)]) + 0.0
    if kind == "cylindrical":
        return np.array([math.hypot(x, y), math.atan2(y, x), z]) + 0.0
    return np.array([x, y, z]) + 0.0


def _point_vector(p: np.ndarray | Sequence[float]) -> tuple[float, float, float]:
    vector = np.asarray(p, dtype=float).reshape(-1)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise RepresentationError(f"a point needs 3 finite coordinates, got {np.asarray(p).tolist()!r}")
    return float(vector[0]), float(vector[1]), float(vector[2])


# --- representation Jacobians of a robot ---------------------------------------------------------------------------


def representation_jacobian(
    robot: Robot,
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point = "wrist",
    frame: Frame = 0,
) -> RepresentationJacobian:
    r"""The representation Jacobian :math:`J_x = E(x)\,J_0` of ``robot`` (seed 000, equations 4.36-4.38).

    .. math::
        J_x = \begin{bmatrix} E_p(x_p) & 0 \\ 0 & E_r(x_r) \end{bmatrix}
              \begin{bmatrix} J_v \\ J_\omega \end{bmatrix}

    Parameters
    ----------
    robot : Robot
    orientation : str
        One of :data:`REPRESENTATIONS`: the orientation of the frame at ``point`` (the tool frame for
        ``point="tool"``, frame {n} otherwise).
    position : str
        One of :data:`POSITIONS`: the coordinates of ``point``.
    point : "wrist", "tool" or sequence of 3
        As for :func:`symjac.jacobian`.
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
    _check_name(orientation, REPRESENTATIONS)
    _check_name(position, POSITIONS)
    if chain_of(robot).position(frame) > 0:
        raise RepresentationError(f"representation Jacobians are measured in a fixed frame (0 or 'world'), "
                                  f"not in frame {frame!r}")
    return _representation_jacobian(robot, orientation, position, point_vector(robot, point), frame)


@lru_cache(maxsize=64)
def _representation_jacobian(
    robot: Robot, orientation: Orientation, position: Position, point: tuple[sp.Expr, sp.Expr, sp.Expr], frame: Frame
) -> RepresentationJacobian:
    coords = (*_COORDINATES[position], *_COORDINATES[orientation])
    # compared by name: a parameter "rho" with other assumptions is another Symbol but prints the same
    clash = sorted({str(s) for s in coords} & {str(s) for s in (*robot.q, *robot.parameter_symbols)})
    if clash:
        raise RepresentationError(f"{robot.name}: the names {', '.join(clash)} are both robot symbols and "
                                  f"coordinates of the {position}/{orientation} representation")
    E = sp.diag(_position_rate_matrix(position), _rate_matrix(orientation))
    J_0 = jacobian(robot, frame=frame, point=list(point))
    singularities = _singularities(position) + _singularities(orientation)
    return RepresentationJacobian(orientation, position, frame, point, coords, sp.ImmutableMatrix(E),
                                  sp.ImmutableMatrix(J_0), sp.ImmutableMatrix(E * J_0), singularities)


def representation_jacobian_at(
    robot: Robot,
    q: Sequence[float | sp.Expr],
    orientation: Orientation = "zyz",
    position: Position = "cartesian",
    point: Point = "wrist",
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
    >>> value = representation_jacobian_at(load_robot("planar2r"), [0.0, math.pi / 2], "rpy", "spherical")
    >>> value.x.round(4)  # L1 = 0.5, L2 = 0.4: the tip at (0.5, 0.4, 0), yawed by 90 deg
    array([0.6403, 1.5708, 0.6747, 0.    , 0.    , 1.5708])
    >>> value.J_x.round(4)[[0, 2, 5]]  # r, phi_s and yaw rates
    array([[ 0.    , -0.3123],
           [ 1.    ,  0.3902],
           [ 1.    ,  1.    ]])
    """
    result = representation_jacobian(robot, orientation, position, point, frame)
    chain = chain_of(robot)
    target: Frame = "tool" if isinstance(point, str) and point == "tool" else chain.n
    T = np.array(evaluate_at(robot, chain.transform(frame, target), q), dtype=float)
    if target == "tool":
        p = T[:3, 3]
    else:
        p = T[:3, :3] @ np.array(evaluate_at(robot, sp.Matrix(result.point), q), dtype=float).ravel() + T[:3, 3]
    x = np.concatenate([extract_position(position, p), extract(orientation, T[:3, :3])])
    values = dict(zip(result.coordinates, x.tolist(), strict=True))
    factors = tuple(float(s.factor.xreplace(values)) for s in result.singularities)
    for singularity, value in zip(result.singularities, factors, strict=True):
        if abs(value) <= tol:
            raise RepresentationError(f"{robot.name} at q = {list(q)}: {singularity.representation} coordinates are "
                                      f"singular here ({singularity}); J_x does not exist")
    E = np.array(result.E.xreplace(values).evalf(), dtype=float)
    J_0 = np.array(evaluate_at(robot, result.J_0, q), dtype=float)
    return NumericRepresentationJacobian(x, E, J_0, E @ J_0, factors)
