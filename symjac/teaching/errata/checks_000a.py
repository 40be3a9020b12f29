"""Checks of document 000, sections 4.1 to 4.6: the 2R and Stanford examples, representations, motion of frames.

Quantities the base does not cover, and the prose formulas (velocity definitions, recursions) evaluated on the
Stanford arm at one configuration.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from typing import Any

import sympy as sp

from symjac.analysis.representations import angular_velocity_matrix, position_rate_matrix, rate_matrix, rotation_from
from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.propagation import joint_rate_symbols, velocity_propagation
from symjac.model.expressions import parse_expression
from symjac.model.robot import Robot
from symjac.symbolic.transforms import skew
from symjac.teaching.errata.base import position_of, representation_quantity, robot_of
from symjac.teaching.errata.formulas import Formula

__all__ = ["QUANTITIES_000A", "RELATIONS_000A"]




def _coordinates(f: Formula, source: Any = 0, target: Any = None, components: str = "xyz") -> sp.Matrix:
    """Some of the coordinates x, y, z of a frame origin (a planar arm's position is printed as x and y only)."""
    p = position_of(f, source, target)
    return sp.Matrix([p["xyz".index(c)] for c in components])


def _rotation_rate(f: Formula, representation: str, coords: Any, rates: Any, part: str = "R") -> sp.Matrix:
    r"""A rotation :math:`R(x_r)` of given coordinates, or with coordinate rates a quantity of its motion.

    ``part``: ``R``, its derivative ``Rdot``, the product ``RdotRT`` (:math:`\dot R R^T`), the angular velocity
    ``omega`` (:math:`\Omega = B(x_r)\,\dot x_r`) or its cross-product matrix ``omega_hat``.
    """
    x = [parse_expression(str(c), f.names) for c in coords]
    xdot = sp.Matrix([parse_expression(str(c), f.names) for c in rates])
    R = sp.Matrix(rotation_from(representation, x))
    # the coordinates are symbols or constants: the chain rule over the symbols
    Rdot = sum((R.diff(c) * r for c, r in zip(x, xdot, strict=True) if isinstance(c, sp.Symbol)), sp.zeros(3, 3))
    omega = sp.Matrix(angular_velocity_matrix(representation, x)) * xdot
    values = {"R": R, "Rdot": Rdot, "RdotRT": Rdot * R.T, "omega": omega, "omega_hat": skew(omega)}
    return values[part].applyfunc(sp.simplify)


_EXAMPLE_Q = (0.3, -0.7, 0.9, 0.4, 1.1, -0.5, 0.25, -0.35)
_EXAMPLE_RATES = (0.2, -0.6, 0.35, 0.8, -0.4, 0.5, -0.3, 0.45)


@dataclass(frozen=True)
class _Arm:
    """An example arm at one configuration and one set of joint rates, every quantity numeric (in {0})."""

    robot: Robot
    T: tuple[sp.Matrix, ...]  # 0_kT, k = 0..n
    Tdot: tuple[sp.Matrix, ...]  # its time derivative
    omega: tuple[sp.Matrix, ...]  # omega_k of link k, symjac's velocity propagation, in {0}
    v: tuple[sp.Matrix, ...]  # v_k of origin k, symjac's velocity propagation, in {0}
    local: tuple[tuple[sp.Matrix, sp.Matrix], ...]  # (k omega_k, k v_k) as symjac propagates them
    J: sp.Matrix  # symjac's basic Jacobian at the wrist, in {0}, rows [v; omega]
    Jx: sp.Matrix  # d(position, direction cosines row by row)/dq, 12 x n
    q: tuple[float, ...]
    qdot: sp.Matrix

    def R(self, k: int) -> sp.Matrix:
        return self.T[k][:3, :3]

    def p(self, k: int) -> sp.Matrix:
        return self.T[k][:3, 3]


@cache
def _arm(robot: Robot) -> _Arm:
    chain = chain_of(robot)
    q, rates = robot.q, joint_rate_symbols(robot)
    values = {**dict(zip(q, _EXAMPLE_Q, strict=False)), **dict(zip(rates, _EXAMPLE_RATES, strict=False)),
              **{p.symbol: p.default for p in robot.parameters}}
    symbolic = [sp.Matrix(chain.simplified_transform(0, k)) for k in range(chain.n_joints + 1)]
    n = lambda m: sp.Matrix(m).subs(values).evalf()  # noqa: E731
    T = tuple(n(t) for t in symbolic)
    Tdot = tuple(n(sum((t.diff(c) * r for c, r in zip(q, rates, strict=True)), sp.zeros(4, 4))) for t in symbolic)
    steps = velocity_propagation(robot).velocities()
    local = tuple((n(w), n(v)) for _, w, v in steps[:chain.n_joints + 1])
    omega = tuple(T[k][:3, :3] * local[k][0] for k in range(chain.n_joints + 1))
    v = tuple(T[k][:3, :3] * local[k][1] for k in range(chain.n_joints + 1))
    end = symbolic[-1]
    x = sp.Matrix.vstack(end[:3, 3], end[:3, :3].reshape(9, 1))  # position, then rows r1, r2, r3 of 0_nR
    return _Arm(robot, T, Tdot, omega, v, local, n(jacobian(robot, frame=0, point="wrist")), n(x.jacobian(q)),
                tuple(float(values[c]) for c in q), n(sp.Matrix(rates)))


def _residual(left: sp.Matrix, right: sp.Matrix) -> float:
    """Relative size of left - right (0 when the two sides agree)."""
    return float((left - right).norm() / max(1.0, left.norm() + right.norm()))



# helper A: checks of the prose formulas of document 000, sections 4.1 to 4.6, on the Stanford arm


def _example(f: Formula) -> _Arm:
    return _arm(robot_of(f))


def _position_rate(f: Formula, variant: str) -> float:
    r"""Eq. (4.26): :math:`\dot x_p = E_p(x_p)\,v` (printed without the dot: :math:`x_p = E_p(x_p)\,v`).

    Cartesian coordinates (:math:`E_p = I`) of the wrist; :math:`v = J_v \dot q` from symjac's basic Jacobian.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    left = arm.p(n) if variant == "printed" else arm.Tdot[n][:3, 3]
    return _residual(left, position_rate_matrix("cartesian") * arm.J[:3, :] * arm.qdot)


def _orientation_rate(f: Formula, variant: str) -> float:
    r"""Eq. (4.27): :math:`\dot x_r = E_r(x_r)\,\omega`.

    Direction cosines of the end frame (rows of :math:`{}^0_nR`), :math:`E_r` from symjac's rate maps,
    :math:`\omega = J_\omega \dot q` from the basic Jacobian.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    E = rate_matrix("direction_cosines", list(arm.R(n).reshape(9, 1)))
    return _residual(arm.Tdot[n][:3, :3].reshape(9, 1), E * arm.J[3:, :] * arm.qdot)


def _basic_jacobian(f: Formula, variant: str) -> float:
    r"""Eqs. (4.25), (4.32), (4.33), (4.39): :math:`(v;\ \omega) = J_0(q)\,\dot q`.

    The wrist velocity (time derivative of its position) and the end link's angular velocity (velocity
    propagation) against symjac's basic Jacobian, rows :math:`[v;\ \omega]`.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    return _residual(sp.Matrix.vstack(arm.Tdot[n][:3, 3], arm.omega[n]), arm.J * arm.qdot)


def _representation_jacobian(f: Formula, variant: str) -> float:
    r"""Eqs. (4.34)-(4.38): :math:`J_x = E(x) J_0` with :math:`E = \mathrm{diag}(E_p, E_r)`.

    Cartesian position and direction cosines: the 12 x 6 :math:`J_x` of eqs. (4.23)-(4.24), differentiated from the
    forward kinematics.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    E = sp.diag(position_rate_matrix("cartesian"), rate_matrix("direction_cosines", list(arm.R(n).reshape(9, 1))))
    return _residual(arm.Jx, E * arm.J)


def _jp_is_jv(f: Formula, variant: str) -> float:
    r"""Eq. (4.40): :math:`E_p = I_3;\ J_p = J_v`.

    The derivative of the Cartesian wrist position is the linear part of the basic Jacobian.
    """
    arm = _example(f)
    return _residual(arm.Jx[:3, :], arm.J[:3, :])


_BODY_POINT = sp.Matrix([0.3, -0.2, 0.5])


def _rotation_velocity(f: Formula, variant: str) -> float:
    r"""Eqs. (4.42)-(4.43): :math:`v_P = \Omega \times p = \hat\Omega p`.

    P is fixed in link 1 of the arm, which rotates about :math:`z_0` through the origin (:math:`\Omega` from
    symjac's velocity propagation).
    """
    arm = _example(f)
    p = arm.R(1) * _BODY_POINT + arm.p(1)
    v = arm.Tdot[1][:3, :3] * _BODY_POINT + arm.Tdot[1][:3, 3]
    return max(_residual(v, arm.omega[1].cross(p)), _residual(v, skew(arm.omega[1]) * p))


def _rotating_vector(f: Formula, variant: str) -> float:
    r"""Eqs. (4.49)-(4.50): :math:`{}^A\dot p = ({}^A_B\dot R\, {}^A_BR^T)\, {}^Ap`.

    A vector fixed in the end link, {B} = {n}, {A} = {0}; also the unnumbered step
    :math:`{}^A\dot p = {}^A_B\dot R\,{}^Bp` before eq. (4.48).
    """
    arm = _example(f)
    n = len(arm.T) - 1
    R, Rdot = arm.R(n), arm.Tdot[n][:3, :3]
    return _residual(Rdot * _BODY_POINT, Rdot * R.T * (R * _BODY_POINT))


def _omega_hat(f: Formula, variant: str) -> float:
    r"""Eqs. (4.51), (4.57): :math:`\hat\Omega = \dot R R^T`.

    The end link's rotation; :math:`\Omega` from symjac's basic Jacobian.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    return _residual(arm.Tdot[n][:3, :3] * arm.R(n).T, skew(arm.J[3:, :] * arm.qdot))


def _combined_motion(f: Formula, variant: str) -> float:
    r"""Eqs. (4.58)-(4.59): :math:`{}^Av_{P/A} = {}^Av_{B/A} + {}^A_BR\,{}^Bv_{P/B} + {}^A\Omega_B \times {}^Ap_B`.

    {A} = {0}, {B} = link 2 (its origin moves with joint 1) and P the origin of frame 3 (it slides in {B} with
    joint 3).
    """
    arm = _example(f)
    R2, p2, R2dot, p2dot = arm.R(2), arm.p(2), arm.Tdot[2][:3, :3], arm.Tdot[2][:3, 3]
    bp = R2.T * (arm.p(3) - p2)  # P in {B}
    bv = R2.T * (arm.Tdot[3][:3, 3] - p2dot - R2dot * bp)  # its velocity relative to {B}, in {B}
    right = arm.v[2] + R2 * bv + arm.omega[2].cross(R2 * bp)
    return max(_residual(arm.v[3], right), _residual(arm.Tdot[3][:3, 3], right))


def _omega_recursion(f: Formula, variant: str) -> float:
    r"""Eqs. (4.60)-(4.61): :math:`\omega_{i+1} = \omega_i + \Omega_{i+1}`, :math:`\Omega_{i+1} = \dot\theta z_{i+1}`.

    :math:`\dot\theta` is :math:`\dot\theta_{i+1}`, and :math:`\Omega_{i+1} = 0` for a prismatic joint; against
    symjac's propagation, all in {0}.
    """
    arm = _example(f)
    worst = 0.0
    for i, joint in enumerate(arm.robot.joints):
        local = arm.qdot[i] * arm.R(i + 1)[:, 2] if joint.is_revolute else sp.zeros(3, 1)
        worst = max(worst, _residual(arm.omega[i + 1], arm.omega[i] + local))
    return worst


def _v_recursion(f: Formula, variant: str) -> float:
    r"""Eq. (4.62): :math:`v_{i+1} = v_i + \omega_i \times p_{i+1} + \dot d_{i+1} z_{i+1}`.

    The last term for a prismatic joint only; printed with :math:`d_{i+1}`, the joint position, for
    :math:`\dot d_{i+1}`. Modified DH frames, :math:`p_{i+1}` from origin i to origin i+1, against symjac's
    propagation, all in {0}.
    """
    arm = _example(f)
    worst = 0.0
    for i, joint in enumerate(arm.robot.joints):
        slide = arm.q[i] if variant == "printed" else arm.qdot[i]
        local = slide * arm.R(i + 1)[:, 2] if not joint.is_revolute else sp.zeros(3, 1)
        right = arm.v[i] + arm.omega[i].cross(arm.p(i + 1) - arm.p(i)) + local
        worst = max(worst, _residual(arm.v[i + 1], right))
    return worst


def _base_frame_velocities(f: Formula, variant: str) -> float:
    r"""Eq. (4.63): :math:`({}^0v;\ {}^0\omega) = \mathrm{diag}({}^0_nR, {}^0_nR)\,({}^nv;\ {}^n\omega)`.

    As printed the lower-left block reads :math:`n` (taken as :math:`n I`, n the number of joints) instead of 0.
    The end velocities in {n} are symjac's propagation, those in {0} its basic Jacobian times the rates.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    R = arm.R(n)
    E = sp.diag(R, R)
    if variant == "printed":
        E[3:, :3] = n * sp.eye(3)
    local = sp.Matrix.vstack(arm.local[n][1], arm.local[n][0])
    return _residual(arm.J * arm.qdot, E * local)


def _euler_representation_jacobian(f: Formula, variant: str) -> float:
    r"""Eq. (4.41) with (4.31): :math:`J_x = E J_0`, :math:`E = \mathrm{diag}(I, E_r)`.

    Cartesian position and Z-X-Z Euler angles :math:`(\alpha, \beta, \gamma)`; the angle rates come from the
    rotation's derivative (:math:`\alpha = \mathrm{atan2}(r_{13}, -r_{23})`, :math:`\beta = \arccos r_{33}`,
    :math:`\gamma = \mathrm{atan2}(r_{31}, r_{32})`), :math:`E_r` from symjac's rate maps.
    """
    arm = _example(f)
    n = len(arm.T) - 1
    R, Rdot = arm.R(n), arm.Tdot[n][:3, :3]

    def atan2_rate(y: int, x: int, sign: int) -> sp.Expr:
        ys, xs, yd, xd = R[y], sign * R[x], Rdot[y], sign * Rdot[x]
        return (xs * yd - ys * xd) / (xs**2 + ys**2)

    angles = [sp.atan2(R[0, 2], -R[1, 2]), sp.acos(R[2, 2]), sp.atan2(R[2, 0], R[2, 1])]
    rates = sp.Matrix([atan2_rate(2, 5, -1), -Rdot[2, 2] / sp.sqrt(1 - R[2, 2]**2), atan2_rate(6, 7, 1)])
    E = sp.diag(sp.eye(3), rate_matrix("zxz", angles))
    return _residual(sp.Matrix.vstack(arm.Tdot[n][:3, 3], rates), E * arm.J * arm.qdot)


def _pure_translation(f: Formula, variant: str) -> float:
    r"""Section 4.4.1: :math:`v_{P/B} = v_{A/B} + v_{P/A}` when {A} only translates with respect to {B}.

    {B} = link 2, {A} = link 3 (the prismatic joint 3 slides it, :math:`{}^2_3R` is constant), P fixed in link 4;
    all in {B}.
    """
    arm = _example(f)
    point = sp.Matrix([*_BODY_POINT, 1])

    def relative(k: int, j: int) -> tuple[sp.Matrix, sp.Matrix]:
        """k_jT and its time derivative."""
        inverse = arm.T[k].inv()
        return inverse * arm.T[j], inverse * arm.Tdot[j] - inverse * arm.Tdot[k] * inverse * arm.T[j]

    T23, T23dot = relative(2, 3)
    _, T24dot = relative(2, 4)
    _, T34dot = relative(3, 4)
    return _residual(T24dot * point, T23dot[:, 3] + T23 * (T34dot * point))


def _pure_rotation(f: Formula, variant: str) -> float:
    r"""Section 4.4.3, eq. (4.47) and the unnumbered step after it.

    :math:`{}^Ap = {}^A_BR\,{}^Bp` and :math:`{}^A\dot p = {}^A_B\dot R\,{}^Bp + {}^A_BR\,{}^B\dot p` for frames with
    a common origin: {A} = {0}, {B} = link 1 (its origin is the base origin), P the origin of frame 3, which moves in
    {B} with joints 2 and 3 (:math:`{}^Bp` from symjac's transform :math:`{}^1_3T`).
    """
    arm = _example(f)
    R1, R1dot, p3, p3dot = arm.R(1), arm.Tdot[1][:3, :3], arm.p(3), arm.Tdot[3][:3, 3]
    bp = (arm.T[1].inv() * arm.T[3])[:3, 3]
    bpdot = R1dot.T * p3 + R1.T * p3dot
    return max(_residual(p3, R1 * bp), _residual(p3dot, R1dot * bp + R1 * bpdot))




QUANTITIES_000A: Mapping[str, Callable[..., sp.Matrix]] = {
    "coordinates": _coordinates,
    "rotation_rate": _rotation_rate,
    "position_rate_matrix": representation_quantity(position_rate_matrix),
}
RELATIONS_000A: Mapping[str, Callable[[Formula, str], float]] = {
    "position_rate": _position_rate,
    "orientation_rate": _orientation_rate,
    "basic_jacobian": _basic_jacobian,
    "representation_jacobian": _representation_jacobian,
    "jp_is_jv": _jp_is_jv,
    "rotation_velocity": _rotation_velocity,
    "rotating_vector": _rotating_vector,
    "omega_hat": _omega_hat,
    "combined_motion": _combined_motion,
    "omega_recursion": _omega_recursion,
    "v_recursion": _v_recursion,
    "base_frame_velocities": _base_frame_velocities,
    "euler_representation_jacobian": _euler_representation_jacobian,
    "pure_translation": _pure_translation,
    "pure_rotation": _pure_rotation,
}
