r"""Relation checks of the web notes (document 003): moving frames, the derivative of R, propagation, statics.

Each check ``check(formula, "printed" | "corrected")`` returns the relative residual of that form of the formula on
an example arm (:mod:`symjac.teaching.errata.example_arm`) against symjac; its docstring quotes the formula.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import sympy as sp

from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.numeric import evaluate_at, values_at
from symjac.kinematics.propagation import force_propagation, joint_rate_symbols, velocity_propagation, wrench_symbols
from symjac.symbolic.transforms import rotation
from symjac.teaching.errata.base import robot_of
from symjac.teaching.errata.example_arm import (
    RATES_EXAMPLE,
    WRENCH_EXAMPLE,
    frame_transform,
    hat,
    jacobian_at,
    numbers,
    q_example,
    rates_example,
    residual,
)
from symjac.teaching.errata.formulas import Formula

__all__ = ["NOTE_RELATIONS"]


def _moving(f: Formula) -> dict[str, np.ndarray]:
    r"""A point Q moving in a moving frame {B}, seen from a frame {A} fixed while the joints in ``moving`` turn.

    Returns the reference :math:`{}^AV_Q` (the time derivative of :math:`{}^A_BT(q(t))\,{}^BQ(t)` at t = 0, q(t) =
    q0 + q' t), :math:`{}^AQ`, :math:`{}^BQ`, :math:`{}^BV_Q`, :math:`{}^A_BR`, its derivative, :math:`{}^AV_B` and
    :math:`{}^A\Omega_B` (from symjac's velocity iteration, frame {B}, rotated into {A}).
    """
    robot = robot_of(f)
    a, b = f.args["frames"]
    moving = f.args["moving"]
    t = sp.Symbol("t", real=True)
    rates = [(RATES_EXAMPLE[k] if k + 1 in moving else 0.0) for k in range(robot.n_coordinates)]
    Q_B = sp.Matrix([sp.Rational(1, 5), sp.Rational(-2, 5), sp.Rational(3, 10)])
    V_B = sp.Matrix([0, 0, 0]) if f.args.get("fixed_point") else sp.Matrix([sp.Rational(1, 2), 0, sp.Rational(-1, 4)])
    T = sp.Matrix(chain_of(robot).transform(a, b))
    path = {qk: q0 + rate * t for qk, q0, rate in zip(robot.q, q_example(robot), rates, strict=True)}
    T_t = evaluate_at(robot, T.xreplace(path), [path[qk] for qk in robot.q])
    Q_A_t = (T_t * sp.Matrix([*(Q_B + V_B * t), 1]))[:3, 0]
    at0 = {t: 0}
    R_t = T_t[:3, :3]
    for frame, omega, v in velocity_propagation(robot).velocities():
        if frame == b:
            values = dict(zip(joint_rate_symbols(robot), rates, strict=True))
            omega_b = numbers(evaluate_at(robot, omega.xreplace(values), q_example(robot)))[:, 0]
            v_b = numbers(evaluate_at(robot, v.xreplace(values), q_example(robot)))[:, 0]
    R = numbers(R_t.subs(at0))
    return {"V": numbers(Q_A_t.diff(t).subs(at0))[:, 0], "Q_A": numbers(Q_A_t.subs(at0))[:, 0],
            "Q_B": numbers(Q_B)[:, 0], "V_B": numbers(V_B)[:, 0], "R": R, "Rdot": numbers(R_t.diff(t).subs(at0)),
            "V_O": numbers(T_t[:3, 3].diff(t).subs(at0))[:, 0],
            "v_B": R @ v_b, "Omega": R @ omega_b}


def _moving_frames(f: Formula, variant: str) -> float:
    r"""003's velocities of a point in moving frames.

    003, velocities in moving frames, against the derivative of symjac's chain transform:
    prismatic :math:`{}^AV_Q = {}^AV_{O_B} + {}^A_BR\,{}^BV_Q` (R constant); revolute (i) :math:`{}^AV_Q =
    {}^A\Omega_B \times {}^AQ` and (ii) :math:`{}^AV_Q = {}^A_BR\,{}^BV_Q + {}^A\Omega_B \times ({}^A_BR\,{}^BQ)`;
    general :math:`{}^AV_Q = {}^AV_B + {}^A\Omega_B \times {}^A_BR\,{}^BQ + {}^A_BR\,{}^BV_Q`; Lemma 2
    :math:`{}^AV_Q = {}^A_BS\,{}^AQ + {}^A_BR\,{}^BV_Q` with :math:`S = \dot R R^T` and its proof step
    :math:`{}^AV_Q = {}^A_B\dot R\,{}^BQ + {}^A_BR\,{}^BV_Q`.
    """
    m = _moving(f)
    R, Omega = m["R"], m["Omega"]
    form = f.args["form"]
    printed = {
        "prismatic": lambda: m["v_B"] + R @ m["V_B"],
        "revolute_fixed": lambda: np.cross(Omega, m["Q_A"]),
        "revolute_moving": lambda: R @ m["V_B"] + np.cross(Omega, R @ m["Q_B"]),
        "general": lambda: m["v_B"] + np.cross(Omega, R @ m["Q_B"]) + R @ m["V_B"],
        "lemma2": lambda: m["Rdot"] @ R.T @ m["Q_A"] + R @ m["V_B"],
        "lemma2_proof": lambda: m["Rdot"] @ m["Q_B"] + R @ m["V_B"],
    }[form]()
    return residual(printed, m["V"])


def _rotation_rate(f: Formula, variant: str) -> float:
    r"""003's derivative of a rotation matrix and the skew-symmetric S.

    003: :math:`S = \dot R R^T` has :math:`S + S^T = 0` (Lemma 1), :math:`\dot R = S(\dot\theta\hat K)\,R` and
    :math:`\dot R R^T = S(\dot\theta\hat K)` with :math:`\Omega = \dot\theta\hat K` (symjac's angular velocity).
    """
    m = _moving(f)
    S = m["Rdot"] @ m["R"].T
    form = f.args["form"]
    if form == "lemma1":
        return residual(S + S.T, np.zeros((3, 3)))
    if form == "rdot":
        return residual(m["Rdot"], hat(m["Omega"]) @ m["R"])
    return residual(S, hat(m["Omega"]))


def _rotation_limit(f: Formula, variant: str) -> float:
    r"""003's limits that define a derivative.

    003: :math:`\dot R = \lim (R(t+\Delta t) - R(t))/\Delta t`, printed with :math:`\Delta \rightarrow \infty`
    (corrected :math:`\Delta t \rightarrow 0`), exact limits for R(t) = R_z(t) at t = 1/3 against
    :math:`\dot R`; with a robot, 003's Jacobian step (divide :math:`{}^0\Delta r = {}^0J\,\Delta\Theta` by
    :math:`\Delta t` and let :math:`\Delta t \rightarrow \infty`, corrected 0): the wrist position along
    q(t) = (t, 2t, ...) against :math:`{}^0J_v\,\dot q` of symjac.
    """
    t, h = sp.symbols("t h", real=True)
    t0 = sp.Rational(1, 3)
    if f.robot is None:
        path = rotation("z", t)
        rate = path.diff(t).subs(t, t0)
    else:
        robot = f.robot
        times = {q: (k + 1) * t for k, q in enumerate(robot.q)}
        exact = values_at(robot, [0] * robot.n_coordinates)
        exact = {symbol: value for symbol, value in exact.items() if symbol not in times}
        path = sp.Matrix(chain_of(robot).transform(0, robot.n_joints)[:3, 3]).xreplace(times).xreplace(exact)
        J = jacobian(robot, frame=0, point="flange")[:3, :].xreplace(times).xreplace(exact).subs(t, t0)
        rate = J * sp.Matrix([k + 1 for k in range(robot.n_coordinates)])
    quotient = (path.subs(t, t0 + h) - path.subs(t, t0)) / h
    point = sp.oo if variant == "printed" else 0
    limit = quotient.applyfunc(lambda e: sp.limit(e, h, point))
    return residual(numbers(limit), numbers(rate))


def _propagation_steps(f: Formula, variant: str) -> float:
    r"""003's velocity propagation from frame {i} to frame {i+1}.

    003's velocity propagation, step {i} -> {i+1}, against symjac's velocity iteration:
    :math:`{}^iv_{i+1} = {}^iv_i + {}^i\omega_{i+1} \times {}^iO_{i+1}` and :math:`{}^{i+1}v_{i+1} = {}^{i+1}_iR[\dots]`
    (revolute; printed with :math:`\omega_{i+1}`, corrected :math:`\omega_i`), the prismatic
    :math:`{}^{i+1}v_{i+1} = {}^{i+1}_iR[{}^iv_i + {}^i\omega_{i+1} \times {}^iO_{i+1}] + \dot d_{i+1}\hat Z_{i+1}`,
    :math:`{}^i\omega_{i+1} = {}^i\omega_i + {}^i_{i+1}R\,\dot\theta_{i+1}\,{}^{i+1}\hat Z_{i+1}`,
    :math:`{}^{i+1}\omega_{i+1} = {}^{i+1}_iR\,{}^i\omega_i + \dot\theta_{i+1}\,{}^{i+1}\hat Z_{i+1}` and the
    prismatic :math:`{}^{i+1}\omega_{i+1} = {}^{i+1}_iR\,{}^i\omega_i`.
    """
    robot = robot_of(f)
    i = f.args["i"]
    qdot = rates_example(robot)
    values = dict(zip(joint_rate_symbols(robot), qdot, strict=True))
    steps = {frame: (numbers(evaluate_at(robot, w.xreplace(values), q_example(robot)))[:, 0],
                     numbers(evaluate_at(robot, v.xreplace(values), q_example(robot)))[:, 0])
             for frame, w, v in velocity_propagation(robot).velocities() if frame in (i, i + 1)}
    (w_i, v_i), (w_j, v_j) = steps[i], steps[i + 1]
    T = frame_transform(robot, i, i + 1)
    R, origin = T[:3, :3], T[:3, 3]  # {}^i_{i+1}R, {}^iO_{i+1}
    rate = qdot[i]  # joint i+1
    z = np.array([0.0, 0.0, 1.0])
    w_next_in_i = R @ w_j
    w_cross = w_next_in_i if variant == "printed" else w_i
    form = f.args["form"]
    if form == "v_revolute_in_i":
        return residual(R @ v_j, v_i + np.cross(w_cross, origin))
    if form == "v_revolute":
        return residual(v_j, R.T @ (v_i + np.cross(w_cross, origin)))
    if form == "v_prismatic":
        return residual(v_j, R.T @ (v_i + np.cross(w_cross, origin)) + rate * z)
    if form == "w_revolute_in_i":
        return residual(w_next_in_i, w_i + R @ (rate * z))
    if form == "w_revolute":
        return residual(w_j, R.T @ w_i + rate * z)
    return residual(w_j, R.T @ w_i)  # w_prismatic


def _velocity_jacobian(f: Formula, variant: str) -> float:
    r"""003's end-effector velocity as the Jacobian times the joint rates.

    003: :math:`{}^0\nu = [{}^0v;\ {}^0\omega] = {}^0J(\Theta)\dot\Theta`, rows [v; omega], against the time
    derivative of the wrist position and :math:`\dot R R^T` of symjac's chain.
    """
    m = _moving(f)
    robot = robot_of(f)
    rates = np.array([(RATES_EXAMPLE[k] if k + 1 in f.args["moving"] else 0.0) for k in range(robot.n_coordinates)])
    nu = jacobian_at(robot, frame=0) @ rates
    S = m["Rdot"] @ m["R"].T
    return residual(nu, np.r_[m["V_O"], S[2, 1], S[0, 2], S[1, 0]])


def _statics_steps(f: Formula, variant: str) -> float:
    r"""003's static force propagation and the joint torques it gives.

    003's static force propagation, against symjac's force iteration on every link of the arm:
    :math:`{}^if_i - {}^if_{i+1} = 0`, :math:`{}^in_i - {}^in_{i+1} - {}^iP_{i+1} \times {}^if_{i+1} = 0`; the same
    solved for :math:`{}^if_i`, :math:`{}^in_i`; in the link frames :math:`{}^if_i = {}^i_{i+1}R\,{}^{i+1}f_{i+1}`,
    :math:`{}^in_i = {}^i_{i+1}R\,{}^{i+1}n_{i+1} + {}^iP_{i+1} \times {}^if_i`; joint torques
    :math:`\tau_i = {}^in_i^T\,{}^i\hat Z_i` (revolute) and :math:`\tau_i = {}^if_i^T\,{}^i\hat Z_i` (prismatic).
    """
    robot = robot_of(f)
    wrench = dict(zip(wrench_symbols(), WRENCH_EXAMPLE, strict=True))
    propagation = force_propagation(robot)
    steps = {frame: (numbers(evaluate_at(robot, fo.xreplace(wrench), q_example(robot)))[:, 0],
                     numbers(evaluate_at(robot, n.xreplace(wrench), q_example(robot)))[:, 0])
             for frame, fo, n in propagation.wrenches()}
    tau = numbers(evaluate_at(robot, propagation.joint_torques().xreplace(wrench), q_example(robot)))[:, 0]
    form = f.args["form"]
    worst = 0.0
    for i in range(1, robot.n_joints + 1):
        joint = robot.joints[i - 1]
        f_i, n_i = steps[i]
        if form == "tau_revolute" and joint.is_revolute:
            worst = max(worst, residual(n_i[2], tau[i - 1]))
        if form == "tau_prismatic" and not joint.is_revolute:
            worst = max(worst, residual(f_i[2], tau[i - 1]))
        if i == robot.n_joints or form.startswith("tau"):
            continue
        f_j, n_j = steps[i + 1]
        T = frame_transform(robot, i, i + 1)
        R, P = T[:3, :3], T[:3, 3]
        f_next, n_next = R @ f_j, R @ n_j  # {}^if_{i+1}, {}^in_{i+1}
        if form in ("equilibrium", "solved"):
            worst = max(worst, residual(f_i, f_next), residual(n_i, n_next + np.cross(P, f_next)))
        else:
            worst = max(worst, residual(f_i, R @ f_j), residual(n_i, R @ n_j + np.cross(P, f_i)))
    return worst


NOTE_RELATIONS: Mapping[str, Callable[[Formula, str], float]] = {
    "moving_frames": _moving_frames,
    "rotation_rate": _rotation_rate,
    "rotation_limit": _rotation_limit,
    "propagation_steps": _propagation_steps,
    "velocity_jacobian": _velocity_jacobian,
    "statics_steps": _statics_steps,
}
