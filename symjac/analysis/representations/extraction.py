r"""Numeric extraction: the coordinates of a rotation matrix or a point (inverses of ``rotation_from``, ``point_from``).

One extraction per representation type (``functools.singledispatch``); every Euler convention reduces to the Z-Y-Z
or Z-Y-X formulas of the lecture slides by relabelling the axes, and an extrinsic convention to the intrinsic one with
the axes reversed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import singledispatch

import numpy as np

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
    Spherical,
    representation,
)
from symjac.errors import RepresentationError

__all__ = ["GIMBAL_LOCK_TOLERANCE", "extract", "extract_position"]

# A gimbal-lock test on |sin(beta)| (proper) or |cos(beta)| (Tait-Bryan). The extraction below stays accurate to
# rounding for any larger value, so the threshold only decides when the lecture slides' alpha = 0 convention takes over.
GIMBAL_LOCK_TOLERANCE = 1e-12

_INDEX = {"x": 0, "y": 1, "z": 2}


def extract(name: Orientation, R: np.ndarray | Sequence[Sequence[float]], *,
            tol: float = GIMBAL_LOCK_TOLERANCE) -> np.ndarray:
    r"""Orientation coordinates of a numeric rotation matrix, such that ``rotation_from(name, x) == R``.

    Euler angles follow the lecture slides for Z-Y-Z and the same pattern for every order (by relabelling the axes):
    :math:`\beta = \mathrm{atan2}(\sqrt{r_{31}^2 + r_{32}^2}, r_{33})`, :math:`\alpha = \mathrm{atan2}(r_{23}, r_{13})`,
    and :math:`\gamma` from the better-conditioned of :math:`\alpha \pm \gamma` (read off the upper-left block) so
    that the pose is reproduced to rounding even close to gimbal lock. At gimbal lock (:math:`s_\beta` below
    ``tol``) :math:`\alpha = 0` and the whole rotation goes into :math:`\gamma`:
    :math:`\gamma = \mathrm{atan2}(-r_{12}, r_{11})` at :math:`\beta = 0` and
    :math:`\mathrm{atan2}(r_{12}, -r_{11})` at :math:`\beta = \pi`. Tait-Bryan orders likewise set the first angle
    to 0 at :math:`\beta = \pm\pi/2`. Extrinsic conventions are the intrinsic ones with the axes and the angles
    reversed, so there the *last* angle (the leftmost factor; the yaw of roll-pitch-yaw) is set to 0.

    The quaternion uses Shepperd's method (the largest of :math:`\eta^2, \epsilon_x^2, \epsilon_y^2, \epsilon_z^2`
    is computed first), with :math:`\eta \ge 0`; at :math:`\eta = 0` its first nonzero entry is made positive.
    Axis-angle comes from the quaternion: :math:`\vartheta = 2\,\mathrm{atan2}(|\epsilon|, \eta) \in [0, \pi]`,
    :math:`k = \epsilon / |\epsilon|`, and :math:`k = z` at :math:`\vartheta = 0`.

    Parameters
    ----------
    name : str or EulerConvention
        One of :data:`REPRESENTATIONS` (or an alias), or a representation value.
    R : array_like, shape (3, 3)
        A rotation matrix (orthonormal to 1e-6, determinant +1).
    tol : float
        Gimbal-lock threshold on :math:`|s_\beta|` (proper) or :math:`|c_\beta|` (Tait-Bryan).

    Returns
    -------
    x_r : numpy.ndarray, shape (m,)

    Examples
    --------
    >>> from symjac.analysis.representations import rotation_from
    >>> R = np.array(rotation_from("zyz", [0.3, 0.0, 0.5]), dtype=float)  # gimbal lock: only alpha + gamma counts
    >>> extract("zyz", R).round(12)
    array([0. , 0. , 0.8])
    """
    spec = representation(name, "orientation")
    return _extract(spec, _rotation_matrix(R), tol) + 0.0  # a new array, and no -0.0


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
    spec = representation(kind, "position")
    return _extract(spec, _point_vector(p), 0.0) + 0.0


# --- one extraction per type ---------------------------------------------------------------------------------------


@singledispatch
def _extract(spec: Representation, value: np.ndarray, tol: float) -> np.ndarray:
    raise RepresentationError(f"no numeric extraction is defined for {spec.name}")


@_extract.register
def _(spec: EulerConvention, R: np.ndarray, tol: float) -> np.ndarray:
    if spec.extrinsic:
        return _euler(R, spec.axes[::-1], tol)[::-1]
    return _euler(R, spec.axes, tol)


@_extract.register
def _(spec: DirectionCosines, R: np.ndarray, tol: float) -> np.ndarray:
    return R.reshape(9)


@_extract.register
def _(spec: Quaternion, R: np.ndarray, tol: float) -> np.ndarray:
    return _quaternion(R)


@_extract.register
def _(spec: AxisAngle, R: np.ndarray, tol: float) -> np.ndarray:
    eta, eps = (q := _quaternion(R))[0], q[1:]
    norm = float(np.linalg.norm(eps))
    axis = eps / norm if norm > 0.0 else np.array([0.0, 0.0, 1.0])
    return np.array([*axis, 2.0 * math.atan2(norm, eta)])


@_extract.register
def _(spec: Cartesian, p: np.ndarray, tol: float) -> np.ndarray:
    return p.copy()


@_extract.register
def _(spec: Spherical, p: np.ndarray, tol: float) -> np.ndarray:
    x, y, z = p
    rho = math.hypot(x, y)
    return np.array([math.hypot(rho, z), math.atan2(rho, z), math.atan2(y, x)])


@_extract.register
def _(spec: Cylindrical, p: np.ndarray, tol: float) -> np.ndarray:
    x, y, z = p
    return np.array([math.hypot(x, y), math.atan2(y, x), z])


# --- input checks ------------------------------------------------------------------------------------------------


def _rotation_matrix(R: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    M = np.asarray(R, dtype=float)
    if M.shape != (3, 3):
        raise RepresentationError(f"a rotation matrix must be 3 x 3, got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise RepresentationError("the rotation matrix has non-finite entries")
    if not np.allclose(M.T @ M, np.eye(3), atol=1e-6) or np.linalg.det(M) < 0:
        raise RepresentationError("the matrix is not a rotation (R^T R != I or det R < 0)")
    return M


def _point_vector(p: np.ndarray | Sequence[float]) -> np.ndarray:
    vector = np.asarray(p, dtype=float).reshape(-1)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise RepresentationError(f"a point needs 3 finite coordinates, got {np.asarray(p).tolist()!r}")
    return vector


# --- Euler angles and quaternions ------------------------------------------------------------------------------------


def _wrap(angle: float) -> float:
    """The same angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _euler(R: np.ndarray, order: str, tol: float) -> np.ndarray:
    r"""Intrinsic Euler angles of any order, by relabelling the axes so that the order reads Z-Y-Z or Z-Y-X.

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
    if order[0] == order[2]:
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
