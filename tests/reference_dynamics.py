r"""An independent numeric Newton-Euler: spatial vectors in frame {0}, from the robot's data and ``reference.frames``.

Nothing here uses symjac's dynamics, chain or simplification. The frames come from :func:`reference.frames` (plain
NumPy forward kinematics of every convention); joint *j* turns about, or slides along, the z axis of frame {j-1} in
the standard DH convention and of frame {j} in the others (modified DH; general, whose frame {j} is aligned with the
axis; product of exponentials, whose frame {j} sits on the axis). Everything is written in frame {0}, about its
origin (Featherstone's spatial algebra, motion vectors :math:`[\omega; v_O]`):

.. math::
    V_k = V_{k-1} + S_k\dot\vartheta_k, \quad
    A_k = A_{k-1} + S_k\ddot\vartheta_k + V_k \times S_k\dot\vartheta_k, \quad
    F_k = I_k A_k + V_k \times^* I_k V_k, \quad
    \tau_k = S_k^T \sum_{j \ge k} F_j

with :math:`A_0 = [0; 0; 0; 0; 0; g]` (gravity, 9.81 m/s² along -z of {0}, as the base accelerating upwards) and
:math:`I_k` the link's spatial inertia about the origin of {0}. A coupling :math:`\vartheta = \vartheta(q)`
(``robot.joint_values``) enters through its Jacobian :math:`K = \partial\vartheta/\partial q`:
:math:`\dot\vartheta = K\dot q`, :math:`\ddot\vartheta = K\ddot q + \dot K\dot q`, :math:`\tau_q = K^T\tau_\vartheta`
(SymPy differentiates the law, once per robot). A joint's drive (``robot.drives``) adds
:math:`I_a\ddot\vartheta + F_v\dot\vartheta + F_c\operatorname{sign}(\dot\vartheta)` to its torque. Then
:math:`M e_i` is the torque at :math:`(q, 0, e_i)` without gravity, :math:`C\dot q` the rigid bodies' torque at
:math:`(q, \dot q, 0)` without gravity (no friction), and :math:`g` the torque at rest.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from reference import frames

from symjac import Robot

G = 9.81


def _hat(v: np.ndarray) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0.0]])


def _cross_motion(V: np.ndarray) -> np.ndarray:
    """The 6 x 6 matrix of :math:`V\\times` acting on motion vectors."""
    X = np.zeros((6, 6))
    X[:3, :3] = X[3:, 3:] = _hat(V[:3])
    X[3:, :3] = _hat(V[3:])
    return X


class NumericDynamics:
    """Inverse dynamics, M, C qd and g of ``robot`` at numbers, parameters and inertial data at their defaults."""

    def __init__(self, robot: Robot, gravity: float = G):
        self.robot, self.gravity = robot, gravity
        defaults = robot.defaults

        def number(e: object) -> float:
            return float(sp.sympify(e).xreplace(defaults))

        self.bodies = [(number(b.mass), np.array([number(c) for c in b.com]),
                        np.array([[number(b.inertia[i, j]) for j in range(3)] for i in range(3)]))
                       for b in robot.inertials]
        q = sp.Matrix(robot.q)
        law = sp.Matrix([sp.sympify(v).xreplace(defaults) for v in robot.joint_values])
        K = law.jacobian(q)
        rates = sp.symbols(f"r0:{len(q)}", real=True)
        K_dot = sp.zeros(*K.shape)
        for c, rate in enumerate(rates):
            K_dot += K.diff(q[c]) * rate
        self._K = sp.lambdify(list(q), K, modules="numpy")
        self.drives = np.array([[0.0] * 3 if d is None else [number(d.armature), number(d.viscous), number(d.coulomb)]
                                for d in robot.drives]).reshape(-1, 3)
        self._K_dot = sp.lambdify([*q, *rates], K_dot, modules="numpy")

    def _screws_and_inertias(self, q: np.ndarray) -> tuple[list[np.ndarray], list[np.ndarray]]:
        world = frames(self.robot, q)
        to_base = np.linalg.inv(world[1])
        poses = [to_base @ T for T in world[1:-1]]  # frames {0}..{n} in {0}
        standard = self.robot.convention == "standard"
        screws, inertias = [], []
        for k, joint in enumerate(self.robot.joints, start=1):
            T = poses[k - 1] if standard else poses[k]
            axis, point = T[:3, 2], T[:3, 3]
            screws.append(np.concatenate([axis, np.cross(point, axis)]) if joint.is_revolute
                          else np.concatenate([np.zeros(3), axis]))
            m, c_k, I_c = self.bodies[k - 1]
            R, p = poses[k][:3, :3], poses[k][:3, 3]
            c = R @ c_k + p
            inertia = np.zeros((6, 6))
            inertia[:3, :3] = R @ I_c @ R.T + m * (c @ c * np.eye(3) - np.outer(c, c))
            inertia[:3, 3:] = m * _hat(c)
            inertia[3:, :3] = -m * _hat(c)
            inertia[3:, 3:] = m * np.eye(3)
            inertias.append(inertia)
        return screws, inertias

    def tau(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray, gravity: bool = True,
            drives: bool = True) -> np.ndarray:
        """The generalised forces at (q, qd, qdd), one per coordinate (with the drives' share unless ``drives``)."""
        q, qd, qdd = (np.asarray(x, dtype=float) for x in (q, qd, qdd))
        K = np.array(self._K(*q), dtype=float)
        rate = K @ qd
        acceleration = K @ qdd + np.array(self._K_dot(*q, *qd), dtype=float) @ qd
        screws, inertias = self._screws_and_inertias(q)
        V, A = np.zeros(6), np.array([0, 0, 0, 0, 0, self.gravity if gravity else 0.0])
        forces = []
        for S, inertia, w, dw in zip(screws, inertias, rate, acceleration, strict=True):
            V = V + S * w
            A = A + S * dw + _cross_motion(V) @ S * w
            forces.append(inertia @ A - _cross_motion(V).T @ inertia @ V)
        torques, total = np.zeros(len(screws)), np.zeros(6)
        for k in reversed(range(len(screws))):
            total = total + forces[k]
            torques[k] = screws[k] @ total
        if drives:
            Ia, Fv, Fc = self.drives.T
            torques = torques + Ia * acceleration + Fv * rate + Fc * np.sign(rate)
        return K.T @ torques

    def friction(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """The drives' friction torques at (q, qd), one per coordinate."""
        n = len(q)
        return self.tau(q, qd, np.zeros(n), gravity=False) - self.C_qd(q, qd)

    def M(self, q: np.ndarray) -> np.ndarray:
        n = len(q)
        return np.column_stack([self.tau(q, np.zeros(n), e, gravity=False) for e in np.eye(n)])

    def C_qd(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        return self.tau(q, qd, np.zeros(len(q)), gravity=False, drives=False)

    def g(self, q: np.ndarray) -> np.ndarray:
        return self.tau(q, np.zeros(len(q)), np.zeros(len(q)))

    def V(self, q: np.ndarray) -> float:
        """The potential energy sum_k m_k g z_k, z_k the height of link k's centre of mass in {0}."""
        world = frames(self.robot, np.asarray(q, dtype=float))
        to_base = np.linalg.inv(world[1])
        poses = [to_base @ T for T in world[1:-1]]
        return sum(m * self.gravity * (poses[k][:3, :3] @ c + poses[k][:3, 3])[2]
                   for k, (m, c, _) in enumerate(self.bodies, start=1))
