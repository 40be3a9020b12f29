"""Checks of document 000, section 4.7 to the end: explicit form, Stanford transforms, 2R/3R examples, statics.

Quantities the base does not cover, and the prose formulas (recursions, frame changes, virtual work) evaluated
at fixed example values.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import sympy as sp

from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.propagation import force_propagation, joint_rate_symbols, wrench_symbols
from symjac.model.expressions import parse_expression
from symjac.model.robot import Robot
from symjac.symbolic.transforms import skew
from symjac.teaching.errata.base import BASE_QUANTITIES, robot_of
from symjac.teaching.errata.formulas import Formula

__all__ = ["QUANTITIES_000B", "RELATIONS_000B"]


def _block(f: Formula, of: str, r: Any = None, c: Any = None, at: Any = None, **inner: Any) -> sp.Matrix:
    """Rows ``r`` and columns ``c`` (1-based) of quantity ``of``, optionally at a configuration ``at``.

    ``at`` maps names to values (``{ theta2 = "0" }``): a printed 2 x 2 block of a rotation, a Jacobian at a
    singularity. The other arguments go to ``of``.
    """
    M = sp.Matrix(BASE_QUANTITIES[of](f, **inner))
    if at:
        M = M.subs({f.names[name]: parse_expression(str(value), f.names) for name, value in dict(at).items()})
    rows = list(range(M.rows)) if r is None else [i - 1 for i in r]
    cols = list(range(M.cols)) if c is None else [j - 1 for j in c]
    return M.extract(rows, cols)


def _z_cross_p(f: Formula, joint: Any = None, tool: Any = None, frame: Any = None, matrix: bool = False) -> sp.Matrix:
    r"""The explicit form's :math:`{}^iz_i \times {}^ip_{in} = \hat Z\,{}^ip_{in}`, rotated into ``frame`` if given.

    :math:`p_{in}` runs from joint ``joint``'s frame to the origin of frame ``tool`` (default {n}); without a joint,
    :math:`\hat Z p` for the formula's symbols :math:`p = (p_x, p_y, p_z)`; with ``matrix``, :math:`\hat Z` itself.
    """
    z_hat = skew(sp.Matrix([0, 0, 1]))
    if matrix:
        return z_hat
    if joint is None:
        return z_hat * sp.Matrix(f.symbols[:3])
    chain = chain_of(robot_of(f))
    axis = chain.axis_frame(joint)
    result = z_hat * sp.Matrix(chain.simplified_transform(axis, chain.n_joints if tool is None else tool))[:3, 3]
    return result if frame is None else sp.Matrix(chain.rotation(frame, axis)) * result


def _point_shift(f: Formula, frame: Any = 0, part: str = "p") -> sp.Matrix:
    r"""The wrist-to-tool shift of section 4.9 in frame {k}.

    :math:`{}^kp_{WE}` (``part = "p"``), its cross-product matrix (``"p_hat"``) or the term
    :math:`-{}^k\hat p_{WE}\,{}^kJ_{\omega(W)}` (``"term"``).
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    p = sp.Matrix(chain.simplified_transform(frame, "tool"))[:3, 3] - sp.Matrix(
        chain.simplified_transform(frame, chain.n_joints))[:3, 3]
    p = sp.Matrix([sp.trigsimp(e) for e in p])
    if part == "p":
        return p
    if part == "p_hat":
        return skew(p)
    return -skew(p) * jacobian(robot, frame=frame, point="flange")[3:, :]


def _point_velocity(f: Formula, target: Any = None, part: str = "v") -> sp.Matrix:
    r"""Velocity in {0} of the origin of frame ``target`` (default {n}), in the joint rates.

    :math:`\frac{d}{dt}{}^0p_k` (``part = "v"``), or the angular velocity :math:`{}^0\omega_n` of the last link
    (``"omega"``).
    """
    robot = robot_of(f)
    rates = sp.Matrix(joint_rate_symbols(robot))
    if part == "omega":
        return jacobian(robot, frame=0, point="flange")[3:, :] * rates
    chain = chain_of(robot)
    p = sp.Matrix(chain.simplified_transform(0, chain.n_joints if target is None else target))[:3, 3]
    return p.jacobian(sp.Matrix(robot.q)) * rates



# helper B: checks of the prose formulas of document 000, sections 4.7 to the end, on an example configuration


def _example(robot: Robot) -> dict[sp.Symbol, sp.Expr]:
    """Fixed generic values for the joint variables, parameters, joint rates and wrench of ``robot``."""
    values: dict[sp.Symbol, sp.Expr] = {}
    for k, symbol in enumerate(robot.q):
        values[symbol] = sp.Rational(3, 10) + sp.Rational(37, 100) * k
    for k, symbol in enumerate(robot.parameter_symbols):
        values[symbol] = sp.Rational(2, 5) + sp.Rational(13, 100) * k
    for k, symbol in enumerate(joint_rate_symbols(robot)):
        values[symbol] = sp.Rational(1, 2) - sp.Rational(21, 100) * k
    for k, symbol in enumerate(wrench_symbols()):
        values[symbol] = sp.Rational(7, 10) - sp.Rational(3, 10) * k
    return values


def _at(robot: Robot, expression: Any) -> sp.Matrix:
    """``expression`` evaluated at the example configuration of ``robot`` (floats)."""
    return sp.Matrix(sp.Matrix(expression).xreplace(_example(robot)).evalf())


def _residual(left: sp.MatrixBase, right: sp.MatrixBase) -> float:
    """Relative size of ``left - right``."""
    size = max(1.0, float(sp.Matrix(left).norm()) + float(sp.Matrix(right).norm()))
    return float((sp.Matrix(left) - sp.Matrix(right)).norm()) / size


def _diag(R: sp.MatrixBase) -> sp.Matrix:
    return sp.diag(sp.Matrix(R), sp.Matrix(R))


def _frame_change(f: Formula, variant: str) -> float:
    r"""Eq. (4.98): :math:`{}^BJ = \mathrm{diag}({}^B_AR, {}^B_AR)\,{}^AJ` (A = {0}, B = {3})."""
    robot = robot_of(f)
    R = chain_of(robot).rotation(3, 0)
    J_3, J_0 = jacobian(robot, frame=3, point="flange"), jacobian(robot, frame=0, point="flange")
    return _residual(_at(robot, J_3), _at(robot, _diag(R) * J_0))


def _determinant_frame_change(f: Formula, variant: str) -> float:
    r"""Eq. (4.106): :math:`\det[{}^BJ] = \det[\mathrm{diag}({}^B_AR, {}^B_AR)]\,\det[{}^AJ]` (A = {0}, B = {3})."""
    robot = robot_of(f)
    R = _at(robot, chain_of(robot).rotation(3, 0))
    left = _at(robot, jacobian(robot, frame=3, point="flange")).det()
    right = _diag(R).det() * _at(robot, jacobian(robot, frame=0, point="flange")).det()
    return _residual(sp.Matrix([left]), sp.Matrix([right]))


def _shift_parts(robot: Robot) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """Wrist Jacobian, end-point Jacobian (frame {0}) and :math:`{}^0p_{WE}`, at the example configuration."""
    chain = chain_of(robot)
    p = sp.Matrix(chain.transform(0, "tool"))[:3, 3] - sp.Matrix(chain.transform(0, chain.n_joints))[:3, 3]
    J_n, J_e = jacobian(robot, frame=0, point="flange"), jacobian(robot, frame=0, point="tool")
    return _at(robot, J_n), _at(robot, J_e), _at(robot, p)


def _point_shift_velocity(f: Formula, variant: str) -> float:
    r"""Check of Eqs. (4.110)-(4.111) as printed in document 000.

    Eqs. (4.110)-(4.111): :math:`v_e = v_n + \omega_n \times p_{ne} = v_n - p_{ne} \times \omega_n`,
    :math:`\omega_e = \omega_n`.
    """
    robot = robot_of(f)
    J_n, J_e, p = _shift_parts(robot)
    rates = _at(robot, sp.Matrix(joint_rate_symbols(robot)))
    twist_n, twist_e = J_n * rates, J_e * rates
    v_n, omega = twist_n[:3, :], twist_n[3:, :]
    return _residual(twist_e, sp.Matrix.vstack(v_n - p.cross(omega), omega))


def _point_shift_jacobian(f: Formula, variant: str) -> float:
    r"""Check of Eqs. (4.112), (4.118), (4.120) as printed in document 000.

    Eqs. (4.112), (4.118), (4.120): :math:`{}^0J_e = \begin{pmatrix} I & -{}^0\hat p_{ne} \\ 0 & I
    \end{pmatrix} {}^0J_n`.
    """
    robot = robot_of(f)
    J_n, J_e, p = _shift_parts(robot)
    shift = sp.Matrix(sp.BlockMatrix([[sp.eye(3), -skew(p)], [sp.zeros(3), sp.eye(3)]]))
    return _residual(J_e, shift * J_n)


def _force_recursion(f: Formula, variant: str) -> float:
    r"""Check of Eqs. (4.123)-(4.130) as printed in document 000.

    Eqs. (4.123)-(4.130): :math:`{}^i f_i = {}^i_{i+1}R\,{}^{i+1}f_{i+1}`, :math:`{}^i n_i = {}^i_{i+1}R\,
    {}^{i+1}n_{i+1} + {}^ip_{i+1} \times {}^if_i` from :math:`{}^nf_n = {}^nf`, :math:`{}^nn_n = {}^nn`
    (wrench at the wrist), then :math:`\tau_i = n_i^T z_i` (revolute) or :math:`f_i^T z_i` (prismatic).
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    wrench = _at(robot, sp.Matrix(wrench_symbols()))
    force, moment = wrench[:3, :], wrench[3:, :]
    z = sp.Matrix([0, 0, 1])
    torques = [sp.S.Zero] * robot.n_joints
    for i in range(robot.n_joints, 0, -1):
        if i < robot.n_joints:
            T = _at(robot, chain.transform(i, i + 1))
            force = T[:3, :3] * force
            moment = T[:3, :3] * moment + T[:3, 3].cross(force)
        torques[i - 1] = (z.T * (moment if robot.joints[i - 1].is_revolute else force))[0]
    return _residual(sp.Matrix(torques), _at(robot, force_propagation(robot).joint_torques()))


def _velocity_recursion(robot: Robot, rotate_v: bool) -> tuple[sp.Matrix, sp.Matrix]:
    """Eqs. (4.131)-(4.132) run from the base to frame {n}; without ``rotate_v`` the linear step is not rotated."""
    chain = chain_of(robot)
    rates = _at(robot, sp.Matrix(joint_rate_symbols(robot)))
    z = sp.Matrix([0, 0, 1])
    omega, v = sp.zeros(3, 1), sp.zeros(3, 1)
    for i in range(robot.n_joints):
        T = _at(robot, chain.transform(i + 1, i))  # {i+1}_i T
        R, p = T[:3, :3], _at(robot, chain.transform(i, i + 1))[:3, 3]
        revolute = robot.joints[i].is_revolute
        v = (R if rotate_v else sp.eye(3)) * (v + omega.cross(p)) + (sp.S.Zero if revolute else rates[i]) * z
        omega = R * omega + (rates[i] if revolute else sp.S.Zero) * z
    return omega, v


def _angular_velocity_recursion(f: Formula, variant: str) -> float:
    r"""Eq. (4.131): :math:`{}^{i+1}\omega_{i+1} = {}^{i+1}_iR\,{}^i\omega_i + \dot\theta_{i+1}\,{}^{i+1}z_{i+1}`."""
    robot = robot_of(f)
    omega, _ = _velocity_recursion(robot, True)
    J = _at(robot, jacobian(robot, frame=robot.n_joints, point="flange")) * _at(robot,
                                                                               sp.Matrix(joint_rate_symbols(robot)))
    return _residual(omega, J[3:, :])


def _linear_velocity_recursion(f: Formula, variant: str) -> float:
    r"""Check of Eq. (4.132) as printed in document 000.

    Eq. (4.132): :math:`{}^{i+1}v_{i+1} = {}^{i+1}R_{i+1}({}^iv_i + {}^i\omega_i \times {}^ip_{i+1})
    + \dot d_{i+1}\,{}^{i+1}z_{i+1}` as printed (:math:`{}^{i+1}R_{i+1} = I`); corrected with :math:`{}^{i+1}_iR`.
    """
    robot = robot_of(f)
    _, v = _velocity_recursion(robot, variant == "corrected")
    J = _at(robot, jacobian(robot, frame=robot.n_joints, point="flange")) * _at(robot,
                                                                               sp.Matrix(joint_rate_symbols(robot)))
    return _residual(v, J[:3, :])


def _torques_jacobian_transpose(f: Formula, variant: str) -> float:
    r"""Section 4.10.1 and eq. (4.145): :math:`\tau = J^T F` (J and F in frame {n}, F at the wrist)."""
    robot = robot_of(f)
    wrench = _at(robot, sp.Matrix(wrench_symbols()))
    tau = _at(robot, force_propagation(robot).joint_torques())
    return _residual(tau, _at(robot, jacobian(robot, frame=robot.n_joints, point="flange")).T * wrench)


def _virtual_work(f: Formula, variant: str) -> float:
    r"""Eq. (4.144): :math:`\tau^T \delta q + (-F)^T \delta x = 0` with :math:`\delta x = J\,\delta q`."""
    robot = robot_of(f)
    wrench = _at(robot, sp.Matrix(wrench_symbols()))
    tau = _at(robot, force_propagation(robot).joint_torques())
    dq = sp.Matrix([sp.Rational(k + 2, 7) for k in range(robot.n_coordinates)])
    work = (tau.T * dq)[0] - (wrench.T * _at(robot, jacobian(robot, frame=robot.n_joints, point="flange")) * dq)[0]
    return _residual(sp.Matrix([work]), sp.Matrix([0]))


def _explicit_form(f: Formula, variant: str) -> float:
    r"""Check of Eqs. (4.68)-(4.69), (4.149)-(4.150) as printed in document 000.

    Eqs. (4.68)-(4.69), (4.149)-(4.150): column i of :math:`{}^0J` is :math:`({}^0_iR(\epsilon_iZ + \bar\epsilon_i
    \hat Z\,{}^ip_{in});\ {}^0_iR\,\bar\epsilon_iZ)`, with :math:`\epsilon_i = 1` for a prismatic joint.
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    Z, Z_hat = sp.Matrix([0, 0, 1]), skew(sp.Matrix([0, 0, 1]))
    columns = []
    for i, joint in enumerate(robot.joints, start=1):
        T = chain.transform(i, chain.n_joints)
        R = sp.Matrix(chain.rotation(0, i))
        linear = R * (Z_hat * sp.Matrix(T)[:3, 3] if joint.is_revolute else Z)
        columns.append(sp.Matrix.vstack(linear, R * Z if joint.is_revolute else sp.zeros(3, 1)))
    return _residual(_at(robot, sp.Matrix.hstack(*columns)), _at(robot, jacobian(robot, frame=0, point="flange")))


def _differentiation_form(f: Formula, variant: str) -> float:
    r"""Eqs. (4.80)-(4.81), (4.85): :math:`{}^0J = (\partial\,{}^0x_P / \partial q_i;\ \bar\epsilon_i\,{}^0_iR\,z)`."""
    robot = robot_of(f)
    chain = chain_of(robot)
    x_p = sp.Matrix(chain.transform(0, chain.n_joints))[:3, 3]
    angular = [sp.Matrix(chain.rotation(0, i))[:, 2] if j.is_revolute else sp.zeros(3, 1)
               for i, j in enumerate(robot.joints, start=1)]
    J = sp.Matrix.vstack(x_p.jacobian(sp.Matrix(robot.q)), sp.Matrix.hstack(*angular))
    return _residual(_at(robot, J), _at(robot, jacobian(robot, frame=0, point="flange")))


def _stanford_explicit(f: Formula, variant: str) -> float:
    r"""Check of Eq. (4.151) as printed in document 000.

    Eq. (4.151): :math:`{}^0J = \begin{pmatrix} {}^0(z_1 \times p_{13}) & {}^0(z_2 \times p_{23}) & {}^0z_3 & 0 & 0
    & 0 \\ {}^0z_1 & {}^0z_2 & 0 & {}^0z_4 & {}^0z_5 & {}^0z_6 \end{pmatrix}` (all vectors in {0}).
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    z = [sp.Matrix(chain.rotation(0, i))[:, 2] for i in range(robot.n_joints + 1)]
    o = [sp.Matrix(chain.transform(0, i))[:3, 3] for i in range(robot.n_joints + 1)]
    zero = sp.zeros(3, 1)
    top = [z[1].cross(o[3] - o[1]), z[2].cross(o[3] - o[2]), z[3], zero, zero, zero]
    bottom = [z[1], z[2], zero, z[4], z[5], z[6]]
    J = sp.Matrix.vstack(sp.Matrix.hstack(*top), sp.Matrix.hstack(*bottom))
    return _residual(_at(robot, J), _at(robot, jacobian(robot, frame=0, point="flange")))


def _p_in_from_base(f: Formula, variant: str) -> float:
    r"""Check of Section 4.11.2 as printed in document 000.

    Section 4.11.2: :math:`p_{in} = x_p - p_{0i}`, so :math:`{}^0_iR\,\hat Z\,{}^ip_{in} = ({}^0_iR\,\hat Z\,
    {}^0_iR^T)({}^0x_p - {}^0p_{0i})`, for every joint i.
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    Z_hat = skew(sp.Matrix([0, 0, 1]))
    x_p = sp.Matrix(chain.transform(0, chain.n_joints))[:3, 3]
    left, right = [], []
    for i in range(1, robot.n_joints + 1):
        R = sp.Matrix(chain.rotation(0, i))
        left.append(R * Z_hat * sp.Matrix(chain.transform(i, chain.n_joints))[:3, 3])
        right.append(R * Z_hat * R.T * (x_p - sp.Matrix(chain.transform(0, i))[:3, 3]))
    return _residual(_at(robot, sp.Matrix.hstack(*left)), _at(robot, sp.Matrix.hstack(*right)))


def _planar_point_recursion(f: Formula, variant: str) -> float:
    r"""Check of Eqs. (4.133)-(4.135), (4.137) as printed in document 000.

    Eqs. (4.133)-(4.135), (4.137): :math:`v_{P_1} = 0`, :math:`v_{P_{k+1}} = v_{P_k} + \omega_k \times
    p_{k,k+1}` (P_k the joints of the planar 3R arm, :math:`p_{k,k+1}` from :math:`P_k` to :math:`P_{k+1}`,
    :math:`\omega_k = (\dot\theta_1 + \dots + \dot\theta_k) z_0`).
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    rates = sp.Matrix(joint_rate_symbols(robot))
    points = [sp.Matrix(chain.transform(0, k))[:3, 3] for k in (1, 2, 3)]
    exact = [P.jacobian(sp.Matrix(robot.q)) * rates for P in points]
    v = [sp.zeros(3, 1)]
    for k in range(2):
        omega = sp.Matrix([0, 0, sum(rates[: k + 1])])
        v.append(v[-1] + omega.cross(points[k + 1] - points[k]))
    return _residual(_at(robot, sp.Matrix.hstack(*v)), _at(robot, sp.Matrix.hstack(*exact)))



def _stanford_differentiation(f: Formula, variant: str) -> float:
    r"""Check of eq. (4.97) as printed in document 000.

    :math:`J = \begin{pmatrix} \partial x_P/\partial q_1 & \partial x_P/\partial q_2 & \partial x_P/\partial q_3
    & 0 & 0 & 0 \\ {}^0z_1 & {}^0z_2 & 0 & {}^0z_4 & {}^0z_5 & {}^0z_6 \end{pmatrix}` for the Stanford arm.
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    x_p = sp.Matrix(chain.transform(0, chain.n_joints))[:3, 3]
    top = x_p.jacobian(sp.Matrix(robot.q[:3])).row_join(sp.zeros(3, 3))
    z = [sp.Matrix(chain.rotation(0, i))[:, 2] for i in range(robot.n_joints + 1)]
    bottom = sp.Matrix.hstack(z[1], z[2], sp.zeros(3, 1), z[4], z[5], z[6])
    return _residual(_at(robot, sp.Matrix.vstack(top, bottom)), _at(robot, jacobian(robot, frame=0, point="flange")))


def _singular_displacement(f: Formula, variant: str) -> float:
    r"""Check of eqs. (4.108)-(4.109) as printed in document 000.

    At :math:`\theta_2 = 0`: :math:`{}^1\delta x = 0`, :math:`{}^1\delta y = (l_1 + l_2)\delta\theta_1 +
    l_2\delta\theta_2` (planar 2R arm, parameters ``l1``, ``l2``).
    """
    robot = robot_of(f)
    values = _example(robot)
    l1, l2 = (f.names["l1"], f.names["l2"])
    singular = jacobian(robot, frame=1, point="flange")[:2, :].subs(robot.q[1], 0)
    dq = sp.Matrix([sp.Rational(2, 7), sp.Rational(-3, 7)])
    printed = sp.Matrix([0, (l1 + l2) * dq[0] + l2 * dq[1]])
    return _residual(sp.Matrix((singular * dq).subs(values)).evalf(), sp.Matrix(printed.subs(values)).evalf())



def _linear_jacobian_columns(f: Formula, variant: str) -> float:
    r"""Check of eq. (4.148) as printed in document 000.

    :math:`J_v = [\epsilon_1 z_1 + \bar\epsilon_1 (z_1 \times p_{1n}) \ \cdots\ \epsilon_n z_n + \bar\epsilon_n
    (z_n \times p_{nn})]\,\dot q` as printed (a 3-vector, not the 3 x n matrix J_v; residual 1); corrected without
    the trailing :math:`\dot q`, the columns of :math:`J_v` in {0}.
    """
    robot = robot_of(f)
    chain = chain_of(robot)
    Z_hat = skew(sp.Matrix([0, 0, 1]))
    columns = []
    for i, joint in enumerate(robot.joints, start=1):
        R = sp.Matrix(chain.rotation(0, i))
        p = sp.Matrix(chain.transform(i, chain.n_joints))[:3, 3]
        columns.append(R * (Z_hat * p if joint.is_revolute else sp.Matrix([0, 0, 1])))
    right = sp.Matrix.hstack(*columns)
    if variant == "printed":
        right = right * sp.Matrix(joint_rate_symbols(robot))
    J_v = jacobian(robot, frame=0, point="flange")[:3, :]
    if right.shape != J_v.shape:
        return 1.0  # as printed the right side is v = J_v q-dot, a 3-vector: it cannot equal the 3 x n matrix J_v
    return _residual(_at(robot, right), _at(robot, J_v))




QUANTITIES_000B: Mapping[str, Callable[..., sp.Matrix]] = {
    "block": _block,
    "z_cross_p": _z_cross_p,
    "point_shift": _point_shift,
    "point_velocity": _point_velocity,
}
RELATIONS_000B: Mapping[str, Callable[[Formula, str], float]] = {
    "frame_change": _frame_change,
    "determinant_frame_change": _determinant_frame_change,
    "point_shift_velocity": _point_shift_velocity,
    "point_shift_jacobian": _point_shift_jacobian,
    "force_recursion": _force_recursion,
    "angular_velocity_recursion": _angular_velocity_recursion,
    "linear_velocity_recursion": _linear_velocity_recursion,
    "torques_jacobian_transpose": _torques_jacobian_transpose,
    "virtual_work": _virtual_work,
    "explicit_form": _explicit_form,
    "differentiation_form": _differentiation_form,
    "stanford_explicit": _stanford_explicit,
    "p_in_from_base": _p_in_from_base,
    "planar_point_recursion": _planar_point_recursion,
    "stanford_differentiation": _stanford_differentiation,
    "singular_displacement": _singular_displacement,
    "linear_jacobian_columns": _linear_jacobian_columns,
}
