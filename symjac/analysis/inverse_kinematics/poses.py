r"""Target poses for inverse kinematics, checked: from a 4 x 4 matrix, or a position with rpy angles or a quaternion.

A pose is the homogeneous transform of the end of the chain (the tool frame when the robot has one, else frame
{n}) in frame {0}, as ``numeric_model(robot).fk(q)`` returns it: ``[[R, p], [0, 0, 0, 1]]`` with ``R`` a rotation
(orthonormal, determinant +1) and ``p`` the position in metres.

Conventions, the same everywhere in symjac (Python, ``symjac ik``, the report):

* roll, pitch, yaw are URDF's ``rpy``: fixed-axis rotations about x, then y, then z of the base frame,
  :math:`R = R_z(\text{yaw})\, R_y(\text{pitch})\, R_x(\text{roll})` (SciPy's ``Rotation.from_euler("xyz", ...)``,
  lower case for fixed axes), in radians;
* a quaternion is written scalar first, ``(w, x, y, z)``, as MuJoCo and Eigen's constructor write it (SciPy's
  default is scalar last), and must have unit length to within :data:`UNIT_TOLERANCE`; ``q`` and ``-q`` are the
  same rotation.

Every check fails with one line naming what is wrong and where (``pose``, or the option a front end passes as
``name``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from symjac.errors import ArgumentError

__all__ = [
    "RIGID_TOLERANCE",
    "UNIT_TOLERANCE",
    "pose_from_matrix",
    "pose_from_quaternion",
    "pose_from_rpy",
    "quaternion_from_pose",
    "rpy_from_pose",
]

RIGID_TOLERANCE = 1e-6
r"""Largest entry of :math:`R R^T - I` (and of the last row's difference from ``[0, 0, 0, 1]``) a pose may have."""

UNIT_TOLERANCE = 1e-6
"""Largest difference of a quaternion's length from 1."""


def _numbers(values: Any, shape: tuple[int, ...], name: str, what: str) -> np.ndarray:
    """``values`` as a float array of ``shape``, finite, or a one-line error naming ``name``."""
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"{name}: {what} must be numbers, got {values!r} ({error})") from None
    if array.shape != shape:
        size = " x ".join(map(str, shape)) + (" (or its top 3 x 4 rows)" if shape == (4, 4) else "")
        raise ArgumentError(f"{name}: {what} must have shape {size}, got shape "
                            f"{' x '.join(map(str, array.shape)) or 'scalar'}")
    bad = np.argwhere(~np.isfinite(array))
    if bad.size:
        index = ", ".join(map(str, bad[0]))
        raise ArgumentError(f"{name}: {what} entry [{index}] is {array[tuple(bad[0])]}: entries must be finite")
    return array


def pose_from_matrix(matrix: Any, *, name: str = "pose") -> np.ndarray:
    r"""A checked 4 x 4 pose from a homogeneous transform (4 x 4, or its top 3 x 4 rows).

    The rotation block must be orthonormal with determinant +1 and the last row ``[0, 0, 0, 1]``, each to within
    :data:`RIGID_TOLERANCE`; the matrix is returned as given (a new float array), not re-orthonormalised.

    Examples
    --------
    >>> pose_from_matrix([[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0.2]])[:, 3].tolist()
    [0.5, 0.0, 0.2, 1.0]
    """
    try:
        rows = np.shape(matrix)[0] if len(np.shape(matrix)) == 2 else 0
    except ValueError:  # ragged rows: _numbers says so
        rows = 0
    what = "the pose matrix" if rows != 3 else "the pose matrix (its top 3 x 4 rows)"
    T = _numbers(matrix, (3, 4) if rows == 3 else (4, 4), name, what)
    if rows == 3:
        T = np.vstack([T, [0.0, 0.0, 0.0, 1.0]])
    last = np.abs(T[3] - [0.0, 0.0, 0.0, 1.0]).max()
    if last > RIGID_TOLERANCE:
        raise ArgumentError(f"{name}: the last row of a pose is [0, 0, 0, 1], got {T[3].tolist()}")
    R = T[:3, :3]
    off = float(np.abs(R @ R.T - np.eye(3)).max())
    if off > RIGID_TOLERANCE:
        raise ArgumentError(f"{name}: the rotation block is not orthonormal (R R^T differs from I by {off:.3g}; "
                            f"tolerance {RIGID_TOLERANCE:g})")
    if np.linalg.det(R) < 0:
        raise ArgumentError(f"{name}: the rotation block has determinant -1 (a reflection, not a rotation)")
    return T


def _position(position: Sequence[float], name: str) -> np.ndarray:
    return _numbers(position, (3,), name, "the position x, y, z")


def _rotation_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rotation_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _transform(R: np.ndarray, p: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def pose_from_rpy(position: Sequence[float], rpy: Sequence[float], *, name: str = "pose") -> np.ndarray:
    r"""The pose at ``position`` (x, y, z in metres) turned by URDF's roll, pitch, yaw (radians).

    .. math:: R = R_z(\text{yaw})\, R_y(\text{pitch})\, R_x(\text{roll})

    (fixed axes x, y, z of the base frame, in that order; equal to moving axes z, y', x'').

    Examples
    --------
    >>> pose_from_rpy([0.1, 0.2, 0.3], [0.0, 0.0, np.pi / 2])[:3, :3].round(12).tolist()
    [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    """
    p = _position(position, name)
    roll, pitch, yaw = _numbers(rpy, (3,), name, "roll, pitch, yaw")
    return _transform(_rotation_z(yaw) @ _rotation_y(pitch) @ _rotation_x(roll), p)


def pose_from_quaternion(position: Sequence[float], quaternion: Sequence[float], *, name: str = "pose") -> np.ndarray:
    r"""The pose at ``position`` turned by the unit quaternion ``(w, x, y, z)`` (scalar first).

    .. math:: R = I + 2 w [v]_\times + 2 [v]_\times^2, \quad v = (x, y, z)

    The quaternion must have length 1 to within :data:`UNIT_TOLERANCE` (it is not normalised silently: a length
    far from 1 is usually a scalar-last quaternion or a typo).

    Examples
    --------
    >>> pose_from_quaternion([0, 0, 0], [np.cos(0.5), 0, 0, np.sin(0.5)])[:2, :2].round(6).tolist()
    [[0.540302, -0.841471], [0.841471, 0.540302]]
    """
    p = _position(position, name)
    w, x, y, z = _numbers(quaternion, (4,), name, "the quaternion w, x, y, z")
    length = float(np.sqrt(w * w + x * x + y * y + z * z))
    if abs(length - 1.0) > UNIT_TOLERANCE:
        raise ArgumentError(f"{name}: the quaternion (w, x, y, z) must have unit length, got length {length:.6g}")
    skew = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    R = np.eye(3) + 2.0 * w * skew + 2.0 * skew @ skew
    return _transform(R, p)


def rpy_from_pose(pose: Any) -> np.ndarray:
    r"""URDF's roll, pitch, yaw of a pose's rotation (inverse of :func:`pose_from_rpy`), pitch in [-pi/2, pi/2].

    At pitch :math:`\pm\pi/2` only roll :math:`\mp` yaw is defined; roll is then reported as 0.
    """
    R = pose_from_matrix(pose)[:3, :3]
    pitch = float(np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0])))
    if np.hypot(R[0, 0], R[1, 0]) < 1e-12:
        return np.array([0.0, pitch, float(np.arctan2(-R[0, 1], R[1, 1]))])
    return np.array([float(np.arctan2(R[2, 1], R[2, 2])), pitch, float(np.arctan2(R[1, 0], R[0, 0]))])


def quaternion_from_pose(pose: Any) -> np.ndarray:
    """The unit quaternion ``(w, x, y, z)`` of a pose's rotation with ``w >= 0`` (inverse of the above)."""
    R = pose_from_matrix(pose)[:3, :3]
    # the largest of 4 w^2, 4 x^2, 4 y^2, 4 z^2 divides (Shepperd's method): never a square root of a small number
    diagonal = np.array([np.trace(R), R[0, 0], R[1, 1], R[2, 2]])
    k = int(np.argmax(diagonal))
    if k == 0:
        w = np.sqrt(1.0 + diagonal[0]) / 2.0
        q = np.array([w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)])
    else:
        i, j, m = (k - 1), k % 3, (k + 1) % 3
        u = np.zeros(4)
        u[k] = np.sqrt(max(0.0, 1.0 + 2.0 * R[i, i] - np.trace(R))) / 2.0
        u[0] = (R[m, j] - R[j, m]) / (4 * u[k])
        u[1 + j] = (R[j, i] + R[i, j]) / (4 * u[k])
        u[1 + m] = (R[m, i] + R[i, m]) / (4 * u[k])
        q = u
    q = q / np.linalg.norm(q)
    return q if q[0] >= 0 else -q
