"""Target poses for inverse kinematics: rpy and quaternions against SciPy's Rotation, and every check in one line."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from symjac import pose_from_matrix, pose_from_quaternion, pose_from_rpy
from symjac.analysis.inverse_kinematics.poses import quaternion_from_pose, rpy_from_pose
from symjac.errors import ArgumentError

RNG = np.random.default_rng(46)
ANGLES = RNG.uniform(-4.0, 4.0, size=(200, 3))
QUATERNIONS = RNG.normal(size=(200, 4))
QUATERNIONS /= np.linalg.norm(QUATERNIONS, axis=1)[:, None]


def test_rpy_is_urdfs_fixed_axis_xyz_as_scipy_writes_it():
    for rpy in ANGLES:
        T = pose_from_rpy([0.1, -0.2, 0.3], rpy)
        assert np.allclose(T[:3, :3], Rotation.from_euler("xyz", rpy).as_matrix(), atol=1e-14)
        assert np.allclose(T[:3, :3], Rotation.from_euler("ZYX", rpy[::-1]).as_matrix(), atol=1e-14)  # moving z, y, x
        assert T[:3, 3].tolist() == [0.1, -0.2, 0.3] and T[3].tolist() == [0, 0, 0, 1]


def test_a_quaternion_is_scalar_first():
    for wxyz in QUATERNIONS:
        T = pose_from_quaternion([1.0, 2.0, 3.0], wxyz)
        assert np.allclose(T[:3, :3], Rotation.from_quat(np.roll(wxyz, -1)).as_matrix(), atol=1e-14)
        assert np.allclose(T[:3, :3], pose_from_quaternion([0, 0, 0], -wxyz)[:3, :3], atol=1e-14)  # q and -q


def test_rpy_and_quaternion_read_back():
    for rpy, wxyz in zip(ANGLES, QUATERNIONS, strict=True):
        T = pose_from_rpy([0, 0, 0], rpy)
        back = rpy_from_pose(T)
        assert abs(back[1]) <= np.pi / 2 + 1e-12
        assert np.allclose(pose_from_rpy([0, 0, 0], back), T, atol=1e-12)
        x, y, z, w = Rotation.from_matrix(pose_from_quaternion([0, 0, 0], wxyz)[:3, :3]).as_quat()
        expected = np.array([w, x, y, z]) * np.sign(w)
        assert np.allclose(quaternion_from_pose(pose_from_quaternion([0, 0, 0], wxyz)), expected, atol=1e-12)


def test_pitch_at_ninety_degrees_keeps_the_rotation():
    T = pose_from_rpy([0, 0, 0], [0.3, np.pi / 2, -0.4])
    assert np.allclose(pose_from_rpy([0, 0, 0], rpy_from_pose(T)), T, atol=1e-12)
    assert rpy_from_pose(T)[0] == 0.0


def test_a_matrix_is_checked_and_kept_as_given():
    T = pose_from_rpy([0.5, 0.0, 0.2], [0.1, 0.2, 0.3])
    assert np.array_equal(pose_from_matrix(T), T)
    assert np.array_equal(pose_from_matrix(T[:3].tolist()), T)  # the top 3 x 4 rows


@pytest.mark.parametrize(("call", "message"), [
    (lambda: pose_from_matrix(np.full((4, 4), np.nan)), r"pose: the pose matrix entry \[0, 0\] is nan: entries"),
    (lambda: pose_from_matrix(np.eye(3)), r"pose: the pose matrix \(its top 3 x 4 rows\) must have shape 3 x 4, got "
                                          r"shape 3 x 3"),
    (lambda: pose_from_matrix(np.eye(5)), r"pose: the pose matrix must have shape 4 x 4 \(or its top 3 x 4 rows\), got "
                                          r"shape 5 x 5"),
    (lambda: pose_from_matrix(np.ones(16)), r"must have shape 4 x 4 \(or its top 3 x 4 rows\), got shape 16"),
    (lambda: pose_from_matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]]), r"last row of a pose is"),
    (lambda: pose_from_matrix(np.diag([1.0, 1.0, 1.01, 1.0])), r"not orthonormal \(R R\^T differs from I by 0.0201"),
    (lambda: pose_from_matrix(np.diag([1.0, 1.0, -1.0, 1.0])), r"determinant -1 \(a reflection"),
    (lambda: pose_from_matrix("eye"), r"the pose matrix must be numbers"),
    (lambda: pose_from_rpy([0, 0, 0], [0, 0]), r"pose: roll, pitch, yaw must have shape 3, got shape 2"),
    (lambda: pose_from_rpy([0, 0, 0], [0, np.inf, 0]), r"roll, pitch, yaw entry \[1\] is inf"),
    (lambda: pose_from_rpy([0, 0], [0, 0, 0], name="--position"), r"--position: the position x, y, z must have"),
    (lambda: pose_from_quaternion([0, 0, 0], [0, 0, 0, 2]), r"unit length, got length 2$"),
    (lambda: pose_from_quaternion([0, 0, 0], [0.5, 0.5, 0.5, 0.6]), r"unit length, got length 1.05357"),
    (lambda: pose_from_quaternion([0, 0, 0], [1, 0, 0]), r"the quaternion w, x, y, z must have shape 4"),
])
def test_each_bad_pose_is_one_line_naming_what(call, message):
    with pytest.raises(ArgumentError, match=message) as error:
        call()
    assert "\n" not in str(error.value)
