r"""Symbolic maps of each representation: :math:`R(x_r)`, :math:`p(x_p)`, :math:`B`, :math:`E = B^{-1}`, singularities.

Each map is defined once per representation *type* (``functools.singledispatch``); one definition covers all 24
:class:`~symjac.analysis.representations.registry.EulerConvention` values. The angular velocity :math:`\omega` is the
spatial one, expressed in the base frame: :math:`\dot R = \hat\omega R`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import cache, singledispatch

import sympy as sp

from symjac.analysis.representations.registry import (
    AxisAngle,
    Cartesian,
    Cylindrical,
    DirectionCosines,
    EulerConvention,
    Orientation,
    Position,
    Quaternion,
    Representation,
    RepresentationSingularity,
    Spherical,
    representation,
)
from symjac.errors import RepresentationError
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import simplify_matrix
from symjac.symbolic.transforms import rotation, skew

__all__ = [
    "angular_velocity_matrix",
    "point_from",
    "position_rate_matrix",
    "rate_matrix",
    "representation_singularities",
    "rotation_from",
]


def _bind(matrix: sp.MatrixBase, spec: Representation, coords: Sequence[sp.Expr] | None) -> sp.Matrix:
    """``matrix`` (built on the default symbols of ``spec``) with the caller's coordinates substituted."""
    if coords is None:
        return sp.Matrix(matrix)
    values = list(coords)
    default = spec.coordinates
    if len(values) != len(default):
        raise RepresentationError(f"{spec.name} has {len(default)} coordinates, got {len(values)}")
    return sp.Matrix(matrix).xreplace(dict(zip(default, map(sp.sympify, values), strict=True)))


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


# --- R(x_r) and p(x_p): one definition per type ---------------------------------------------------------------------


@singledispatch
def _rotation(spec: Representation) -> sp.Matrix:
    raise RepresentationError(f"{spec.name} is not an orientation representation")


@_rotation.register
def _(spec: EulerConvention) -> sp.Matrix:
    R, c = sp.eye(3), spec.coordinates
    for axis, index in spec.factors:
        R = R * rotation(axis, c[index])
    return R


@_rotation.register
def _(spec: DirectionCosines) -> sp.Matrix:
    return sp.Matrix(3, 3, spec.coordinates)


@_rotation.register
def _(spec: Quaternion) -> sp.Matrix:
    eta, *eps = spec.coordinates
    return sp.eye(3) + 2 * eta * skew(eps) + 2 * skew(eps) * skew(eps)


@_rotation.register
def _(spec: AxisAngle) -> sp.Matrix:
    *k, angle = spec.coordinates
    axis = sp.Matrix(k)
    return sp.cos(angle) * sp.eye(3) + (1 - sp.cos(angle)) * axis * axis.T + sp.sin(angle) * skew(k)


@singledispatch
def _point(spec: Representation) -> sp.Matrix:
    raise RepresentationError(f"{spec.name} is not a position representation")


@_point.register
def _(spec: Cartesian) -> sp.Matrix:
    return sp.Matrix(spec.coordinates)


@_point.register
def _(spec: Spherical) -> sp.Matrix:
    r, polar, azimuth = spec.coordinates
    return r * sp.Matrix([sp.sin(polar) * sp.cos(azimuth), sp.sin(polar) * sp.sin(azimuth), sp.cos(polar)])


@_point.register
def _(spec: Cylindrical) -> sp.Matrix:
    rho, azimuth, z = spec.coordinates
    return sp.Matrix([rho * sp.cos(azimuth), rho * sp.sin(azimuth), z])


# --- B (omega = B xdot) and E (xdot = E omega) ------------------------------------------------------------------


@singledispatch
def _angular_velocity(spec: Representation) -> sp.Matrix:
    raise RepresentationError(f"{spec.name} is not an orientation representation")


@_angular_velocity.register
def _(spec: EulerConvention) -> sp.Matrix:
    # omega = sum of (rotation axis as the base frame sees it) * angle rate; the axis of a factor is seen through
    # the product of the factors to its left, whatever the order of application
    B, R, c = sp.zeros(3, 3), sp.eye(3), spec.coordinates
    for axis, index in spec.factors:
        B[:, index] = R[:, "xyz".index(axis)]
        R = R * rotation(axis, c[index])
    return B


@_angular_velocity.register
def _(spec: DirectionCosines) -> sp.Matrix:
    return _rates(spec).T / 2


@_angular_velocity.register
def _(spec: Quaternion) -> sp.Matrix:
    eta, *eps = spec.coordinates
    return 2 * sp.Matrix.hstack(-sp.Matrix(eps), eta * sp.eye(3) + skew(eps))


@_angular_velocity.register
def _(spec: AxisAngle) -> sp.Matrix:
    *k, angle = spec.coordinates
    return sp.Matrix.hstack(sp.sin(angle) * sp.eye(3) + (1 - sp.cos(angle)) * skew(k), sp.Matrix(k))


@singledispatch
def _rates(spec: Representation) -> sp.Matrix:
    """E = B^-1 for minimal sets (square B); redundant sets register their closed form instead."""
    E, _ = _inverse(sp.Matrix(_cached(_angular_velocity, spec)), spec.coordinates)
    return E


@_rates.register
def _(spec: DirectionCosines) -> sp.Matrix:
    R, units = sp.Matrix(3, 3, spec.coordinates), sp.eye(3)
    columns = [(skew(units[:, m]) * R).reshape(9, 1) for m in range(3)]  # reshape is row-major
    return sp.Matrix.hstack(*columns)


@_rates.register
def _(spec: Quaternion) -> sp.Matrix:
    eta, *eps = spec.coordinates
    return sp.Matrix.vstack(-sp.Matrix(eps).T, eta * sp.eye(3) - skew(eps)) / 2


@_rates.register
def _(spec: AxisAngle) -> sp.Matrix:
    *k, angle = spec.coordinates
    E_k = -(skew(k) + sp.cot(angle / 2) * skew(k) * skew(k)) / 2
    return sp.Matrix.vstack(E_k, sp.Matrix([k]))


@cache
def _cached(definition: Callable[[Representation], sp.MatrixBase], spec: Representation) -> sp.ImmutableMatrix:
    """Each map of each representation is derived once (a pure function of the representation)."""
    return sp.ImmutableMatrix(definition(spec))


@cache
def _position_rates(spec: Representation) -> sp.ImmutableMatrix:
    E, _ = _inverse(sp.Matrix(_cached(_point, spec)).jacobian(sp.Matrix(spec.coordinates)), spec.coordinates)
    return sp.ImmutableMatrix(E)


# --- representation singularities -------------------------------------------------------------------------------


@singledispatch
def _singularities(spec: Representation) -> tuple[RepresentationSingularity, ...]:
    return ()  # direction cosines, quaternions and cartesian coordinates describe every pose smoothly


@_singularities.register
def _(spec: EulerConvention) -> tuple[RepresentationSingularity, ...]:
    middle = spec.coordinates[1]
    _, det = _inverse(sp.Matrix(_cached(_angular_velocity, spec)), spec.coordinates)
    (factor, _), = sp.factor_list(det)[1]
    solutions: tuple[sp.Expr, ...] = (sp.S.Zero, sp.pi) if spec.is_proper else (-sp.pi / 2, sp.pi / 2)
    return (RepresentationSingularity(spec.name, factor, middle, solutions, "gimbal lock"),)


@_singularities.register
def _(spec: AxisAngle) -> tuple[RepresentationSingularity, ...]:
    angle = spec.coordinates[3]
    return (RepresentationSingularity(spec.name, sp.sin(angle / 2), angle, (sp.S.Zero,), "no rotation axis"),)


@_singularities.register
def _(spec: Spherical) -> tuple[RepresentationSingularity, ...]:
    r, polar, _ = spec.coordinates
    return (RepresentationSingularity(spec.name, r, r, (sp.S.Zero,), "origin"),
            RepresentationSingularity(spec.name, sp.sin(polar), polar, (sp.S.Zero, sp.pi), "polar axis"))


@_singularities.register
def _(spec: Cylindrical) -> tuple[RepresentationSingularity, ...]:
    rho = spec.coordinates[0]
    return (RepresentationSingularity(spec.name, rho, rho, (sp.S.Zero,), "z axis"),)


# --- public functions ----------------------------------------------------------------------------------------------


def rotation_from(name: Orientation, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The rotation matrix :math:`R(x_r)` of orientation coordinates (symbolic, or numbers given as ``coords``).

    .. math:: R_{zyz}(\alpha, \beta, \gamma) = R_z(\alpha)\,R_y(\beta)\,R_z(\gamma), \quad
              R_{rpy}(\phi, \theta, \psi) = R_z(\psi)\,R_y(\theta)\,R_x(\phi), \ \ldots

    Parameters
    ----------
    name : str or EulerConvention
        One of :data:`REPRESENTATIONS` (or an alias), or a representation value.
    coords : sequence, optional
        Values or expressions for the coordinates (default: the symbols of :func:`.coordinates`).

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
    spec = representation(name, "orientation")
    return _bind(_cached(_rotation, spec), spec, coords)


def point_from(kind: Position, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""Cartesian position :math:`p(x_p)` of position coordinates.

    .. math:: p_{sph} = r\,[s_{\theta_s} c_{\phi_s},\ s_{\theta_s} s_{\phi_s},\ c_{\theta_s}]^T, \quad
              p_{cyl} = [\rho\,c_{\phi_c},\ \rho\,s_{\phi_c},\ z]^T

    Examples
    --------
    >>> point_from("cylindrical").T
    Matrix([[rho*cos(phi_c), rho*sin(phi_c), z]])
    """
    spec = representation(kind, "position")
    return _bind(_cached(_point, spec), spec, coords)


def angular_velocity_matrix(name: Orientation, coords: Sequence[sp.Expr] | None = None) -> sp.Matrix:
    r"""The map :math:`B(x_r)` from coordinate rates to the angular velocity in {0}: :math:`\omega = B\,\dot x_r`.

    For the three-angle sets, column j is the axis of the j-th coordinate's rotation as the base frame sees it,
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
    spec = representation(name, "orientation")
    return _bind(_cached(_angular_velocity, spec), spec, coords)


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

    For angle sets :math:`E_r = B^{-1}` (:func:`angular_velocity_matrix`); it depends on two of the angles only.

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
    spec = representation(name, "orientation")
    return _bind(_cached(_rates, spec), spec, coords)


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
    spec = representation(kind, "position")
    return _bind(_position_rates(spec), spec, coords)


@cache
def _cached_singularities(spec: Representation) -> tuple[RepresentationSingularity, ...]:
    return _singularities(spec)


def representation_singularities(name: str | Representation) -> tuple[RepresentationSingularity, ...]:
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
    return _cached_singularities(representation(name))
