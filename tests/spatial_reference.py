"""An independent numeric inverse dynamics for the tests: spatial-vector Newton-Euler in frame {0}, from poses alone.

Nothing of symjac's dynamics is used: the joint screws are read off the frame poses of ``reference.frames`` (moving
one joint variable by a finite angle moves the links after it by a screw motion about that joint's axis, exactly),
and the recursion is Featherstone's RNEA with spatial vectors [omega; v] at the origin of {0}. Coupled robots are
handled in their coordinates: tau_q = C^T tau with C the (constant) derivative of the joint values.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from reference import frames, joint_values

from symjac.model.robot import Robot

__all__ = ["coupling", "inverse_dynamics", "mass_matrix"]

STEP = 0.7  # a finite move: the screw is recovered exactly, not by a difference quotient


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def _poses(robot: Robot, theta: np.ndarray) -> list[np.ndarray]:
    """Frames {1}..{n} relative to {0} at the joint values ``theta``."""
    world = frames(robot, theta)
    base = np.linalg.inv(world[1])
    return [base @ world[k + 1] for k in range(1, robot.n_joints + 1)]


def _screws(robot: Robot, theta: np.ndarray, poses: list[np.ndarray]) -> list[np.ndarray]:
    screws = []
    for k, joint in enumerate(robot.joints):
        moved = theta.copy()
        moved[k] += STEP
        G = _poses(robot, moved)[k] @ np.linalg.inv(poses[k])  # the screw motion of link k+1 about joint k+1
        R, t = G[:3, :3], G[:3, 3]
        if joint.is_revolute:
            u = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (2 * np.sin(STEP))
            point = np.linalg.lstsq(np.eye(3) - R, t, rcond=None)[0]
            screws.append(np.concatenate([u, np.cross(point, u)]))
        else:
            screws.append(np.concatenate([np.zeros(3), t / STEP]))
    return screws


def _number(value: object, robot: Robot) -> float:
    return float(sp.sympify(value).subs(robot.defaults))


def _inertias(robot: Robot, poses: list[np.ndarray]) -> list[np.ndarray]:
    """Spatial inertias of the links about the origin of {0}, in {0}'s axes."""
    result = []
    for body, T in zip(robot.inertials, poses, strict=True):
        m = _number(body.mass, robot)
        c_local = np.array([_number(v, robot) for v in body.com])
        I_c = np.array([[_number(body.inertia[i, j], robot) for j in range(3)] for i in range(3)])
        R = T[:3, :3]
        c = R @ c_local + T[:3, 3]
        C = _skew(c)
        result.append(np.block([[R @ I_c @ R.T + m * C @ C.T, m * C], [m * C.T, m * np.eye(3)]]))
    return result


def _motion_cross(v: np.ndarray) -> np.ndarray:
    w, u = _skew(v[:3]), _skew(v[3:])
    return np.block([[w, np.zeros((3, 3))], [u, w]])


def coupling(robot: Robot) -> np.ndarray:
    """d theta / d q (n_joints x n_coordinates), exact for the linear couplings symjac reads."""
    n = robot.n_coordinates
    if robot.coupling is None:
        return np.eye(n)
    zero = joint_values(robot, np.zeros(n))
    return np.array([joint_values(robot, np.eye(n)[j]) - zero for j in range(n)]).T


def inverse_dynamics(robot: Robot, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, g: float = 9.81) -> np.ndarray:
    """tau(q, qd, qdd) in the robot's coordinates, gravity g along -z of {0}."""
    C = coupling(robot)
    theta = joint_values(robot, np.asarray(q, dtype=float))
    rates, accelerations = C @ qd, C @ qdd
    poses = _poses(robot, theta)
    screws, inertias = _screws(robot, theta, poses), _inertias(robot, poses)
    v, a = np.zeros(6), np.array([0, 0, 0, 0, 0, g])  # the base accelerating upwards stands for gravity
    forces = []
    for S, inertia, rate, acceleration in zip(screws, inertias, rates, accelerations, strict=True):
        a = a + S * acceleration + _motion_cross(v) @ S * rate
        v = v + S * rate
        forces.append(inertia @ a - _motion_cross(v).T @ inertia @ v)
    tau = np.zeros(robot.n_joints)
    total = np.zeros(6)
    for k in range(robot.n_joints - 1, -1, -1):
        total = total + forces[k]
        tau[k] = screws[k] @ total
    return C.T @ tau


def mass_matrix(robot: Robot, q: np.ndarray) -> np.ndarray:
    """M(q) column by column from :func:`inverse_dynamics` without gravity and rates."""
    n = robot.n_coordinates
    zero = np.zeros(n)
    return np.array([inverse_dynamics(robot, q, zero, np.eye(n)[j], g=0.0) for j in range(n)]).T
