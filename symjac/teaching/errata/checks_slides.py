r"""Relation checks of the lecture slides (document 002): tool-tip propagation, statics, Z-Y-Z extraction, spaces.

Each check ``check(formula, "printed" | "corrected")`` returns the relative residual of that form of the formula on
an example arm (:mod:`symjac.teaching.errata.example_arm`) against symjac; its docstring quotes the formula.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
import sympy as sp

from symjac.analysis.representations import extract, rotation_from
from symjac.analysis.singularity.determinant import determinant
from symjac.analysis.spaces import jacobian_spaces
from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian, rows_from_names
from symjac.kinematics.numeric import evaluate_at
from symjac.kinematics.propagation import force_propagation, velocity_propagation
from symjac.kinematics.statics import joint_torques
from symjac.model.io import load_robot
from symjac.symbolic.transforms import rotation, twist_transform, wrench_transform
from symjac.teaching.errata.base import robot_of
from symjac.teaching.errata.example_arm import (
    Q_EXAMPLE,
    TOOL_EXAMPLE,
    WRENCH_EXAMPLE,
    frame_transform,
    hat,
    jacobian_at,
    numbers,
    parsed,
    q_example,
    rates_example,
    residual,
    substitution,
    wrist_and_tool,
)
from symjac.teaching.errata.formulas import Formula

__all__ = ["SLIDE_RELATIONS"]


def _twist_map(f: Formula, variant: str) -> float:
    r"""Twists of two rigidly connected frames {i} (wrist) and {i+1} (tool), 002's tool-tip slides.

    Forward: :math:`{}^{i+1}\omega_{i+1} = {}^{i+1}_iR\,{}^i\omega_i`,
    :math:`{}^{i+1}v_{i+1} = {}^{i+1}_iR({}^iv_i + {}^i\omega_i \times {}^iP_{i+1})` and the block matrix
    :math:`[R,\ R(\square \times P);\ 0,\ R]`; backward: :math:`{}^i\omega_i = {}^i_{i+1}R\,{}^{i+1}\omega_{i+1}`,
    :math:`{}^iv_i = {}^i_{i+1}R\,{}^{i+1}v_{i+1} - {}^i\omega_i \times {}^iP_{i+1}` and the block matrix
    :math:`[R,\ -\square \times P;\ 0,\ R]`; the step "multiply both sides by :math:`{}^i_{i+1}R`" with the printed
    :math:`{}^{i+1}_{i+1}R` (the identity) or the corrected :math:`{}^{i+1}_iR`. Reference:
    :func:`symjac.symbolic.transforms.twist_transform`.
    """
    T_i_j, T_j_i = wrist_and_tool(f)
    R, P = T_i_j[:3, :3], T_i_j[:3, 3]
    twist_i = np.array(WRENCH_EXAMPLE)
    twist_j = numbers(twist_transform(sp.Matrix(T_j_i))) @ twist_i  # the reference
    v_i, w_i, v_j, w_j = twist_i[:3], twist_i[3:], twist_j[:3], twist_j[3:]
    form = f.args["form"]
    if form == "forward_vector":
        return residual(np.r_[R.T @ (v_i + np.cross(w_i, P)), R.T @ w_i], twist_j)
    if form == "forward_matrix":  # the operator (box x P) applied to omega is omega x P = -P^ omega
        M = np.block([[R.T, R.T @ -hat(P)], [np.zeros((3, 3)), R.T]])
        return residual(M, numbers(twist_transform(sp.Matrix(T_j_i))))
    if form in ("back_multiply_omega", "back_multiply_v"):
        middle = np.eye(3) if variant == "printed" else R.T  # printed {}^{i+1}_{i+1}R, corrected {}^{i+1}_iR
        if form == "back_multiply_omega":
            return residual(R @ w_j, R @ middle @ w_i)
        return residual(R @ v_j, R @ middle @ (v_i + np.cross(w_i, P)))
    back = numbers(twist_transform(sp.Matrix(T_i_j)))
    if form == "back_vector":
        w = R @ w_j
        return residual(np.r_[R @ v_j - np.cross(w, P), w], back @ twist_j)
    if form == "back_matrix":  # printed: -(box x P) acts on {}^{i+1}omega; corrected: -(R box) x P
        upper = hat(P) if variant == "printed" else hat(P) @ R
        return residual(np.block([[R, upper], [np.zeros((3, 3)), R]]), back)
    raise KeyError(form)


def _wrench_map(f: Formula, variant: str) -> float:
    r"""Wrenches of two rigidly connected frames, 002's tool-tip and force/torque-sensor slides.

    :math:`{}^if_i = {}^i_{i+1}R\,{}^{i+1}f_{i+1}`, :math:`{}^in_i = {}^i_{i+1}R\,{}^{i+1}n_{i+1} + {}^iP_{i+1}
    \times {}^if_{i+1}` and :math:`\begin{bmatrix} R & 0 \\ P \times R & R \end{bmatrix}` (also with {T}, {S} for the
    sensor). Reference: :func:`symjac.symbolic.transforms.wrench_transform`.
    """
    T_i_j, _ = wrist_and_tool(f)
    R, P = T_i_j[:3, :3], T_i_j[:3, 3]
    reference = numbers(wrench_transform(sp.Matrix(T_i_j)))
    if f.args["form"] == "vector":
        F = np.array(WRENCH_EXAMPLE)
        f_i = R @ F[:3]
        return residual(np.r_[f_i, R @ F[3:] + np.cross(P, f_i)], reference @ F)
    return residual(np.block([[R, np.zeros((3, 3))], [hat(P) @ R, R]]), reference)


def _tool_path(f: Formula, variant: str) -> float:
    r"""002's tool-tip position equations, on the PUMA 560 with the example tool.

    002, tool tip position: :math:`T_{path} = {}^0_1T \cdots {}^5_6T\,{}^6_TT`, :math:`({}^6_TT)^{-1} = {}^T_6T`,
    :math:`T_{path}({}^6_TT)^{-1} = {}^0_1T \cdots {}^5_6T\,{}^T_6T\,({}^6_TT)^{-1}` (printed; corrected with
    :math:`{}^6_TT` before the inverse) and :math:`T_{path}\,{}^T_6T = {}^0_1T \cdots {}^5_6T`, on the PUMA 560 with
    the example tool.
    """
    robot = robot_of(f)
    links = [frame_transform(robot, k - 1, k) for k in range(1, robot.n_joints + 1)]
    arm = np.linalg.multi_dot(links)
    tool = numbers(TOOL_EXAMPLE)
    T_tool_wrist = np.linalg.inv(tool)
    path = frame_transform(robot, 0, robot.n_joints) @ tool  # the pose of {T} from symjac's chain
    step = f.args["step"]
    if step == "product":
        return residual(path, arm @ tool)
    if step == "inverse":
        return residual(np.linalg.inv(tool), T_tool_wrist)
    if step == "multiply":
        inner = T_tool_wrist if variant == "printed" else tool
        return residual(path @ np.linalg.inv(tool), arm @ inner @ np.linalg.inv(tool))
    return residual(path @ T_tool_wrist, arm)


def _point_frames(f: Formula, variant: str) -> float:
    r"""A point described in two frames (vector and homogeneous forms).

    A point in two frames: :math:`{}^AP_Q = {}^AP_{BORG} + {}^A_BR\,{}^BP_Q` and the homogeneous form
    :math:`{}^AP_Q = {}^A_BT\,{}^BP_Q` (002; also 003's :math:`{}^AQ = {}^AO_B + {}^A_BR\,{}^BQ`), frames of the arm.
    """
    robot = robot_of(f)
    a, b = f.args["frames"]
    Q_B = np.array([0.2, -0.4, 0.3])
    Q_A = numbers(evaluate_at(robot, chain_of(robot).transform(a, b) * sp.Matrix([*Q_B, 1]), q_example(robot)))[:3, 0]
    T = frame_transform(robot, a, b)
    printed = T[:3, 3] + T[:3, :3] @ Q_B if f.args["form"] == "vector" else (T @ np.r_[Q_B, 1.0])[:3]
    return residual(printed, Q_A)


def _frame_change(f: Formula, variant: str) -> float:
    r"""A Jacobian moved from frame {N} to the base frame {0}.

    :math:`{}^0J_N = \mathrm{diag}({}^0_NR, {}^0_NR)\,{}^NJ_N` with :math:`{}^NJ_N` from the velocity iteration,
    or from the force iteration (the transpose of its torque map), or the plain Jacobian in {N}; also the
    vector form :math:`{}^0v_N = {}^0_NR\,{}^Nv_N`, :math:`{}^0\omega_N = {}^0_NR\,{}^N\omega_N`.
    """
    robot = robot_of(f)
    n = robot.n_joints
    method = f.args.get("method", "jacobian")
    if method == "velocity":
        J_N = velocity_propagation(robot).jacobian
    elif method == "force":
        J_N = force_propagation(robot).jacobian
    else:
        J_N = jacobian(robot, frame=n, point="flange")
    J_N = numbers(evaluate_at(robot, J_N, q_example(robot)))
    R = frame_transform(robot, 0, n)[:3, :3]
    block = np.block([[R, np.zeros((3, 3))], [np.zeros((3, 3)), R]])
    return residual(block @ J_N, jacobian_at(robot, frame=0))


def _inverse_jacobian(f: Formula, variant: str) -> float:
    r"""Joint rates through the inverse Jacobian.

    :math:`\dot\theta = J(\theta)^{-1}\dot x` for :math:`\dot x = J(\theta)\dot\theta` (the 3R arm's square
    Jacobian at the tool point).
    """
    robot = robot_of(f)
    J = jacobian_at(robot, frame="tool", point="tool")[:3, :]
    qdot = rates_example(robot)
    return residual(np.linalg.inv(J) @ (J @ qdot), qdot)


def _statics_jt(f: Formula, variant: str) -> float:
    r"""Joint torques that hold a wrench, and the virtual-work argument for them.

    Joint torques against :func:`symjac.joint_torques` (:math:`\tau = J^T F`): the printed
    :math:`\tau = J(\theta)^T F`, or 003's virtual-work steps :math:`\mathcal F^T \Delta r = \tau^T \Delta\theta`,
    :math:`\mathcal F^T J(\Theta)\Theta = \tau^T\Delta\theta` (printed; corrected :math:`\Delta\Theta`) and
    :math:`\mathcal F^T J(\Theta) = \tau^T, \text{ or } \tau = J(\Theta)\mathcal F` (printed; corrected
    :math:`J^T`).
    """
    robot = robot_of(f)
    F = np.array(WRENCH_EXAMPLE)
    tau = numbers(joint_torques(robot, list(F), point="flange", q=q_example(robot)))[:, 0]
    J = jacobian_at(robot, frame=0)
    form = f.args["form"]
    if form == "tau_JT":
        return residual(J.T @ F, tau)
    dq = rates_example(robot) * 1e-3
    if form == "virtual_work":
        return residual(F @ (J @ dq), tau @ dq)
    if form == "virtual_work_J":
        increment = np.array(q_example(robot)) if variant == "printed" else dq
        return residual(F @ (J @ increment), tau @ dq)
    # "F^T J = tau^T, or tau = J F"
    other = J @ F if variant == "printed" else J.T @ F
    return max(residual(F @ J, tau), residual(other, tau))


def _zyz_extraction(f: Formula, variant: str) -> float:
    r"""002's Z-Y-Z Euler-angle extraction formulas, checked by round trips.

    002's Z-Y-Z extraction, round trip through :func:`symjac.analysis.representations.rotation_from`:
    :math:`\beta = \mathrm{Atan2}(\pm\sqrt{r_{31}^2 + r_{32}^2}, r_{33})`,
    :math:`\alpha = \mathrm{Atan2}(r_{23}/s\beta, r_{13}/s\beta)`, :math:`\gamma = \mathrm{Atan2}(r_{32}/s\beta,
    -r_{31}/s\beta)`; at :math:`\beta = 0`: :math:`\alpha = 0`, :math:`\gamma = \mathrm{Atan2}(-r_{12}, r_{11})`; at
    :math:`\beta = 180^\circ`: :math:`\alpha = 0`, :math:`\gamma = \mathrm{Atan2}(r_{12}, -r_{11})`. Angles a slide
    does not give come from :func:`symjac.analysis.representations.extract` (for the other sign of :math:`s\beta`, its
    twin :math:`(\alpha + \pi, -\beta, \gamma + \pi)`).
    """
    worst = 0.0
    angle = f.args["angle"]
    cases = {"beta0": [(0.4, 0.0, 0.9)], "beta180": [(0.4, math.pi, 0.9)]}.get(
        angle, [(0.4, 0.8, -1.1), (-2.5, 2.3, 2.9), (1.9, 0.3, 0.2)])
    for alpha, beta, gamma in cases:
        R = numbers(rotation_from("zyz", [alpha, beta, gamma]))
        r = {f"{i + 1}{j + 1}": R[i, j] for i in range(3) for j in range(3)}
        if angle in ("beta0", "beta180"):
            sign = 1.0 if angle == "beta0" else -1.0
            found = [(0.0, beta, math.atan2(-sign * r["12"], sign * r["11"]))]
        else:
            found = []
            for sign in (1.0, -1.0):
                a, b, g = extract("zyz", R)
                if sign < 0:
                    a, b, g = a + math.pi, -b, g + math.pi
                if angle in ("beta", "all"):
                    b = math.atan2(sign * math.hypot(r["31"], r["32"]), r["33"])
                s_beta = math.sin(b)
                if angle in ("alpha", "all"):
                    a = math.atan2(r["23"] / s_beta, r["13"] / s_beta)
                if angle in ("gamma", "all"):
                    g = math.atan2(r["32"] / s_beta, -r["31"] / s_beta)
                found.append((a, b, g))
        for a, b, g in found:
            worst = max(worst, residual(numbers(rotation_from("zyz", [a, b, g])), R))
    return worst


def _wrist_euler(f: Formula, variant: str) -> float:
    r"""002's wrist as Z-Y-Z Euler angles of its joint angles.

    002: :math:`R_{Euler} = R_{z_4}(	heta_4)R_{y_4}(-	heta_5)R_{z_4}(	heta_6)`, the wrist rotation measured from
    frame {4} at :math:`	heta_4 = 0`: :math:`({}^3_4R|_{	heta_4 = 0})^T\,{}^3_6R` of the PUMA 560.
    """
    robot = robot_of(f)
    q = q_example(robot)
    start = numbers(evaluate_at(robot, chain_of(robot).rotation(3, 4), [*q[:3], 0, *q[4:]]))
    wrist = start.T @ frame_transform(robot, 3, 6)[:3, :3]
    printed = numbers(rotation("z", q[3]) * rotation("y", -q[4]) * rotation("z", q[5]))
    return residual(printed, wrist)


def _zyz_gimbal_sum(f: Formula, variant: str) -> float:
    r"""002's Z-Y-Z matrix at beta = 0, written with the sum of the two other angles.

    002: at :math:`\beta = 0` the Z-Y-Z matrix is :math:`\begin{bmatrix} c(\alpha+\gamma) & -s(\alpha+\gamma) & 0
    \\ s(\alpha+\gamma) & c(\alpha+\gamma) & 0 \\ 0 & 0 & 1 \end{bmatrix}` (only the sum counts).
    """
    worst = 0.0
    for alpha, gamma in ((0.4, 0.9), (-2.0, 1.3), (0.9, 0.4)):
        c, s = math.cos(alpha + gamma), math.sin(alpha + gamma)
        printed = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        worst = max(worst, residual(printed, numbers(rotation_from("zyz", [alpha, 0, gamma]))))
    return worst


def _null_dimension(f: Formula, variant: str) -> float:
    r"""002's dimension of the null space of a redundant arm's Jacobian.

    002: for a full-rank redundant arm :math:`\dim N(J) = n - m`, printed :math:`n-m = 7-1 = 1` (corrected
    :math:`7-6=1`): the middle difference against the rank of the Panda's 6 x 7 Jacobian (symjac.jacobian_spaces).
    """
    robot = robot_of(f)
    spaces = jacobian_spaces(jacobian_at(robot, frame=0))
    null = robot.n_coordinates - spaces.rank
    middle = 7 - 1 if variant == "printed" else 7 - 6
    return max(abs(middle - null), abs(robot.n_coordinates - 6 - null)) / robot.n_coordinates


def _rank_nullity(f: Formula, variant: str) -> float:
    r"""002's rank-nullity statement for the Jacobian.

    002: :math:`\dim(R(J)) + \dim(N(J)) = n`, for the 2R arm stretched out (rank 1) and the Panda (rank 6).
    """
    worst = 0.0
    for robot, q in ((load_robot("planar2r"), [0.4, 0.0]), (load_robot("panda"), list(Q_EXAMPLE))):
        J = numbers(evaluate_at(robot, jacobian(robot, frame=0, point="flange"), q))
        J = J[[0, 1], :] if robot.n_coordinates == 2 else J
        spaces = jacobian_spaces(J)
        worst = max(worst, abs(spaces.rank + spaces.null_space.shape[1] - robot.n_coordinates))
    return worst


def _singular_factors(f: Formula, variant: str) -> float:
    r"""Printed singular conditions against symjac's determinant.

    Each printed factor (``args.factors``, shorthand) must divide the determinant of the rows ``args.rows`` and
    together they must leave only a constant; each printed singular configuration (``args.zeros``) must make the
    determinant vanish. 002: :math:`s_3 = 0`, :math:`-L_1 - L_2c_2 - L_3c_{23} = 0`, :math:`\theta_3 = 0^\circ,
    180^\circ`; :math:`\theta_2 = 0` (stretched out), :math:`\theta_2 = \pi` (folded back).
    """
    robot = robot_of(f)
    det = determinant(robot, rows=rows_from_names(f.args["rows"]), frame=f.args.get("frame")).expression
    worst = 0.0
    factors = [parsed(f, text) for text in f.args.get("factors", [])]
    if factors:
        ratio = sp.cancel(sp.expand_trig(det / sp.Mul(*factors)))
        worst = max(worst, float(bool(ratio.free_symbols & set(robot.q))))
    for zero in f.args.get("zeros", []):
        at = {**dict(zip(robot.q, q_example(robot), strict=True)), **substitution(f, zero)}
        value = evaluate_at(robot, sp.Matrix([[det]]).xreplace(at), q_example(robot))[0, 0]
        worst = max(worst, abs(float(value)))
    return worst


SLIDE_RELATIONS: Mapping[str, Callable[[Formula, str], float]] = {
    "twist_map": _twist_map,
    "wrench_map": _wrench_map,
    "tool_path": _tool_path,
    "point_frames": _point_frames,
    "frame_change": _frame_change,
    "inverse_jacobian": _inverse_jacobian,
    "statics_jt": _statics_jt,
    "zyz_extraction": _zyz_extraction,
    "zyz_gimbal_sum": _zyz_gimbal_sum,
    "wrist_euler": _wrist_euler,
    "null_dimension": _null_dimension,
    "rank_nullity": _rank_nullity,
    "singular_factors": _singular_factors,
}
