"""An independent numeric reference: forward kinematics in plain NumPy and finite-difference Jacobians.

Nothing here uses symjac's transforms, chain or simplification: only the robot's data (DH rows, base, tool), turned
into floats. The Jacobian comes from central differences of this forward kinematics; the angular part from
:math:`\\hat\\omega \\approx (R(q + h e_i) - R(q - h e_i)) R(q)^T / 2h`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from symjac import Robot


def _float(expr: sp.Expr, robot: Robot) -> float:
    return float(sp.sympify(expr).subs(robot.defaults))


def _rot_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rot_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _trans(x: float, y: float, z: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def frames(robot: Robot, q: np.ndarray) -> list[np.ndarray]:
    """World poses of frame positions world, 0, 1, ..., n, tool (n + 3 matrices)."""
    base = np.array(robot.base.matrix.subs(robot.defaults), dtype=float) if robot.base else np.eye(4)
    tool = np.array(robot.tool.matrix.subs(robot.defaults), dtype=float) if robot.tool else np.eye(4)
    poses = [np.eye(4), base]
    for joint, value in zip(robot.joints, q, strict=True):
        alpha, a = _float(joint.alpha, robot), _float(joint.a, robot)
        theta, d = _float(joint.theta, robot), _float(joint.d, robot)
        if joint.is_revolute:
            theta += value
        else:
            d += value
        if robot.convention == "standard":
            link = _rot_z(theta) @ _trans(0, 0, d) @ _trans(a, 0, 0) @ _rot_x(alpha)
        else:
            link = _rot_x(alpha) @ _trans(a, 0, 0) @ _rot_z(theta) @ _trans(0, 0, d)
        poses.append(poses[-1] @ link)
    poses.append(poses[-1] @ tool)
    return poses


def frame_index(robot: Robot, frame: int | str) -> int:
    """Index into :func:`frames` of a symjac frame name."""
    return 0 if frame == "world" else robot.dof + 2 if frame == "tool" else int(frame) + 1


def finite_difference_jacobian(
    robot: Robot, q: np.ndarray, frame: int | str = 0, point: np.ndarray | None = None, h: float = 1e-6
) -> np.ndarray:
    """6 x n Jacobian [v; omega] at the point (coordinates in frame {n}) expressed in ``frame``."""
    point_h = np.append(np.zeros(3) if point is None else np.asarray(point, dtype=float), 1.0)
    n = robot.dof

    def pose(qq: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        T_world_n = frames(robot, qq)[n + 1]
        return (T_world_n @ point_h)[:3], T_world_n[:3, :3]

    _, R_mid = pose(q)
    J_world = np.zeros((6, n))
    for i in range(n):
        step = np.zeros(n)
        step[i] = h
        (x_plus, R_plus), (x_minus, R_minus) = pose(q + step), pose(q - step)
        J_world[:3, i] = (x_plus - x_minus) / (2 * h)
        omega_hat = (R_plus - R_minus) / (2 * h) @ R_mid.T
        J_world[3:, i] = (omega_hat[2, 1], omega_hat[0, 2], omega_hat[1, 0])
    R_world_k = frames(robot, q)[frame_index(robot, frame)][:3, :3]
    rotate = np.kron(np.eye(2), R_world_k.T)
    return rotate @ J_world


def evaluate(matrix: sp.MatrixBase, robot: Robot, q: np.ndarray, extra: dict | None = None) -> np.ndarray:
    """Numeric value of a symbolic matrix at joint values ``q`` and the parameters' defaults."""
    values = {**{s: float(v) for s, v in robot.defaults.items()}, **dict(zip(robot.q, map(float, q), strict=True))}
    values.update(extra or {})
    symbols = sorted(values, key=str)
    function = sp.lambdify(symbols, matrix, modules="numpy")
    return np.array(function(*[values[s] for s in symbols]), dtype=float)


def random_configuration(robot: Robot, rng: np.random.Generator) -> np.ndarray:
    """Joint values: angles in (-pi, pi), prismatic extensions in (0.1, 1)."""
    return np.array([rng.uniform(-np.pi, np.pi) if j.is_revolute else rng.uniform(0.1, 1.0) for j in robot.joints])
