r"""Lowering of the dynamics for machines: inverse dynamics, mass matrix, Coriolis matrix, bias forces, gravity.

Each function returns a :class:`~symjac.codegen.lower.LoweredFunction` whose inputs are the coordinates ``q`` and, as
the function needs them, their rates ``qdot`` and accelerations ``qddot``; the inertial parameters and the geometric
ones are parameters (symbols with defaults, :attr:`Robot.parameter_symbols <symjac.model.robot.Robot>`), and so is
the magnitude of gravity when it is a symbol (``g`` by default; a generated module takes it as the parameter ``g``;
:func:`numeric_gravity` writes its value in instead).

.. math::
    \tau = M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q), \qquad b(q, \dot q) = C(q, \dot q)\,\dot q + g(q)

Strategies: ``"fastest"`` runs the customised recursions of :mod:`symjac.codegen.recursions` (Newton-Euler over
numbers and names, composite rigid bodies for M, composite first moments for g, C from the Christoffel symbols of
the traced M by forward-mode differentiation), then one CSE over the whole function; ``"raw"`` lowers the raw
symbolic recursion of :mod:`symjac.analysis.dynamics.newton_euler` (``simplify=False``) and the raw Christoffel
form; ``"simplified"`` lowers the compact textbook forms. A robot with coupled joints is derived on the chain of its
joints and written in its coordinates: :math:`\tau_q = C^T\tau`, :math:`M_q = C^T M C`, :math:`C_q = C^T C_\vartheta C`
with :math:`\vartheta = \vartheta(q)`, :math:`\dot\vartheta = C\dot q`, :math:`\ddot\vartheta = C\ddot q`.

Drive data (:attr:`Robot.drives <symjac.model.robot.Robot>`) enter in joint space, before the coupling: the armature
on M's diagonal and :math:`I_a\ddot\vartheta + F_v\dot\vartheta + F_c\operatorname{sign}(\dot\vartheta)` in the
inverse dynamics and the bias forces (so :math:`b` is everything but :math:`M\ddot q`, and forward dynamics solves
:math:`M\ddot q = \tau - b` with the friction in :math:`b`); g and C do not change. Without drive data nothing
is added.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import sympy as sp

from symjac.analysis.dynamics.drives import coulomb_law
from symjac.analysis.dynamics.gravity import EARTH, Gravity
from symjac.analysis.dynamics.lagrange import coriolis_matrix, gravity_torques, mass_matrix
from symjac.analysis.dynamics.newton_euler import newton_euler, newton_euler_mass_matrix, recursion
from symjac.analysis.identification.parameters import standard_values
from symjac.analysis.identification.regressor import Regressor, regressor
from symjac.codegen.cse import eliminate_common
from symjac.codegen.lower import Inputs, LoweredFunction, angle_expansion
from symjac.codegen.recursions import (
    Trace,
    gravity_trace,
    mass_matrix_trace,
    newton_euler_trace,
    potential_energy_trace,
)
from symjac.codegen.request import strategy_of
from symjac.kinematics.chain import Chain
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.memo import memoized

if TYPE_CHECKING:
    from symjac.analysis.identification.base import BaseParameters

__all__ = [
    "identification_base",
    "identification_regressor",
    "lowered_base_regressor",
    "lowered_base_values",
    "lowered_bias_forces",
    "lowered_coriolis_matrix",
    "lowered_gravity_torques",
    "lowered_inverse_dynamics",
    "lowered_mass_matrix",
    "lowered_potential_energy",
    "lowered_regressor",
    "lowered_standard_values",
    "numeric_gravity",
]

Derive = Callable[[Trace, Sequence[sp.Expr], Sequence[sp.Expr]], list[sp.Expr]]


def numeric_gravity(gravity: Gravity) -> Gravity:
    """``gravity`` with a symbolic magnitude replaced by its value (what generated code computes with)."""
    if isinstance(gravity.magnitude, sp.Symbol):
        return Gravity(direction=gravity.direction, magnitude=gravity.value, value=gravity.value)
    return gravity


class _Space:
    r"""Where a function is derived (the chain of the joints) and evaluated (the coordinates), and C between them."""

    def __init__(self, chain: Chain):
        self.chain = chain
        self.joints = chain.joint_chain
        model = chain.robot
        self.coupled = model.coupling is not None
        self.C = coupling_matrix(chain) if self.coupled else sp.eye(model.n_joints)
        self.rates = list(self.C * sp.Matrix(model.coordinate_rates))
        self.accelerations = list(self.C * sp.Matrix(model.coordinate_accelerations))
        self.values = {joint.variable: value for joint, value in zip(model.joints, model.joint_values, strict=True)
                       if value != joint.variable}

    def inputs(self, *names: str) -> Inputs:
        model = self.chain.robot
        available = {"q": model.q, "qdot": model.coordinate_rates, "qddot": model.coordinate_accelerations}
        return tuple((name, tuple(available[name])) for name in names)

    def vector(self, tau: Sequence[sp.Expr]) -> list[sp.Expr]:
        r""":math:`C^T\tau`."""
        return list(self.C.T * sp.Matrix(tau)) if self.coupled else list(tau)

    def matrix(self, M: Sequence[Sequence[sp.Expr]]) -> list[list[sp.Expr]]:
        r""":math:`C^T M C`."""
        return (self.C.T * sp.Matrix(M) * self.C).tolist() if self.coupled else [list(row) for row in M]


def _drive_terms(space: _Space, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr]) -> list[sp.Expr]:
    r"""Per joint, :math:`I_a\ddot\vartheta + F_v\dot\vartheta + F_c\operatorname{sign}(\dot\vartheta)`, 0 without."""
    terms = []
    for drive, rate, acceleration in zip(space.chain.robot.drives, rates, accelerations, strict=True):
        if drive is None:
            terms.append(sp.S.Zero)
            continue
        coulomb = drive.coulomb * coulomb_law(rate) if drive.coulomb != 0 and rate != 0 else sp.S.Zero
        terms.append(drive.armature * acceleration + drive.viscous * rate + coulomb)
    return terms


def _with_drives(space: _Space, tau: Sequence[sp.Expr], rates: Sequence[sp.Expr],
                 accelerations: Sequence[sp.Expr]) -> list[sp.Expr]:
    """``tau`` (joint space) with the drives' share added, or ``tau`` itself for a robot without drive data."""
    if all(drive is None for drive in space.chain.robot.drives):
        return list(tau)
    return [t + d for t, d in zip(tau, _drive_terms(space, rates, accelerations), strict=True)]


def _finished(space: _Space, trace: Trace, outputs: Sequence[sp.Expr], shape: tuple[int, ...], inputs: Inputs,
              origin: str) -> LoweredFunction:
    """The trace's code for ``outputs``: unused temporaries dropped, one CSE over all, angles in the coordinates."""
    flat = [sp.sympify(e) for e in outputs]
    needed = set().union(*(e.free_symbols for e in flat))
    kept: list[tuple[sp.Symbol, sp.Expr]] = []
    for symbol, expr in reversed(trace.temporaries):
        if symbol in needed:
            kept.append((symbol, expr))
            needed |= expr.free_symbols
    kept.reverse()
    temporaries, reduced = eliminate_common(flat, kept)
    first = [(variable, value) for variable, value in space.values.items() if variable in needed]
    body = (*first, *temporaries)
    used = set().union(*(e.free_symbols for _, e in body), *(e.free_symbols for e in reduced))
    expansion = trace.expansion
    angles = tuple((s, c, sp.expand(a.xreplace(space.values)))
                   for s, c, a in zip(expansion.sines, expansion.cosines, expansion.angles, strict=True)
                   if s in used or c in used)
    op_count = sum(int(sp.count_ops(e)) for _, e in body) + sum(int(sp.count_ops(e)) for e in reduced)
    return LoweredFunction(inputs, angles, body, tuple(reduced), tuple(flat), shape, op_count, origin)


def _symbolic(space: _Space, values: Sequence[sp.Expr], shape: tuple[int, ...], inputs: Inputs, origin: str
              ) -> LoweredFunction:
    """Lower symbolic results derived in the joint variables (the raw and simplified strategies)."""
    joints = space.joints
    substitution = {**dict(zip(joints.robot.coordinate_rates, space.rates, strict=True)),
                    **dict(zip(joints.robot.coordinate_accelerations, space.accelerations, strict=True))}
    trace = Trace(joints, angle_expansion(joints))
    flat = trace.expansion.expand_all([sp.sympify(v).xreplace(substitution) for v in values])
    return _finished(space, trace, flat, shape, inputs, origin)


def _torque_function(chain: Chain, strategy: str, gravity: Gravity, rates: bool, accelerations: bool,
                     names: tuple[str, ...], what: str) -> LoweredFunction:
    space = _Space(chain)
    n = space.joints.n_joints
    zero = [sp.S.Zero] * n
    qd = space.rates if rates else zero
    qdd = space.accelerations if accelerations else zero
    g = gravity  # a symbolic magnitude stays the symbol: generated modules take it as the parameter g
    inputs = space.inputs(*names)
    if strategy == "fastest":
        trace = Trace(space.joints, angle_expansion(space.joints))
        if not rates and not accelerations:
            tau = gravity_trace(trace, g.vector)
            origin = "gravity from composite first moments"
        else:
            tau = _with_drives(space, newton_euler_trace(trace, qd, qdd, g.vector), qd, qdd)
            origin = f"customised Newton-Euler{what}"
        return _finished(space, trace, space.vector(tau), (space.chain.robot.n_coordinates,), inputs, origin)
    if strategy == "simplified":
        model = space.joints.robot
        if not rates and not accelerations:
            values = list(gravity_torques(space.joints, g))
        else:
            full = newton_euler(space.joints, g).torques
            values = list(full.xreplace({**({} if rates else dict.fromkeys(model.coordinate_rates, 0)),
                                         **({} if accelerations else dict.fromkeys(model.coordinate_accelerations,
                                                                                   0))}))
        return _symbolic(space, space.vector(values), (space.chain.robot.n_coordinates,), inputs,
                         f"compact Newton-Euler torques{what}")
    joint_rates = space.joints.robot.coordinate_rates if rates else zero
    joint_accelerations = space.joints.robot.coordinate_accelerations if accelerations else zero
    steps = recursion(space.joints, joint_rates, joint_accelerations, g, simplify=False)
    tau = _with_drives(space, [step.tau for step in steps], joint_rates, joint_accelerations)
    return _symbolic(space, space.vector(tau), (space.chain.robot.n_coordinates,), inputs,
                     f"raw Newton-Euler recursion{what}")


@memoized(strategy=strategy_of)
def lowered_inverse_dynamics(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``inverse_dynamics(q, qdot, qddot)``: :math:`\tau` by Newton-Euler, n values."""
    return _torque_function(chain, strategy, gravity, True, True, ("q", "qdot", "qddot"), "")


@memoized(strategy=strategy_of)
def lowered_bias_forces(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``bias_forces(q, qdot)``: :math:`C\dot q + g`, Newton-Euler with :math:`\ddot q = 0`, n values."""
    return _torque_function(chain, strategy, gravity, True, False, ("q", "qdot"), ", qddot = 0")


@memoized(strategy=strategy_of)
def lowered_gravity_torques(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``gravity_torques(q)``: :math:`g(q)`, n values."""
    return _torque_function(chain, strategy, gravity, False, False, ("q",), ", qdot = qddot = 0")


@memoized()
def lowered_potential_energy(chain: Chain, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``_potential_energy(q)``: :math:`V(q) = -\sum_i m_i\,g_0^T p_{ci}`, a scalar (for the self-test: g = dV/dq).

    One lowering whatever the strategy (the self-test differentiates it; nothing else calls it): the masses beyond
    each joint and the first moments, traced (:func:`~symjac.codegen.recursions.potential_energy_trace`).
    """
    space = _Space(chain)
    trace = Trace(space.joints, angle_expansion(space.joints))
    V = potential_energy_trace(trace, gravity.vector)
    return _finished(space, trace, [V], (), space.inputs("q"), "masses beyond each joint and first moments")


@memoized(strategy=strategy_of)
def lowered_mass_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    r"""``mass_matrix(q)``: :math:`M(q)`, n x n (row-major)."""
    space = _Space(chain)
    n = chain.robot.n_coordinates
    inputs = space.inputs("q")
    if strategy == "fastest":
        trace = Trace(space.joints, angle_expansion(space.joints))
        M_joints = mass_matrix_trace(trace)
        for i, drive in enumerate(space.chain.robot.drives):  # the armature on the joints' diagonal
            if drive is not None and drive.armature != 0:
                M_joints[i][i] = M_joints[i][i] + drive.armature
        M = space.matrix(M_joints)
        return _finished(space, trace, [e for row in M for e in row], (n, n), inputs, "composite rigid bodies")
    if strategy == "simplified":
        M_joints = mass_matrix(space.joints)
        origin = "compact mass matrix"
    else:
        M_joints = newton_euler_mass_matrix(space.joints, simplify=False)
        origin = "raw Newton-Euler recursion per column"
    M = space.matrix(M_joints.tolist())
    return _symbolic(space, [e for row in M for e in row], (n, n), inputs, origin)


@memoized(strategy=strategy_of)
def lowered_coriolis_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    r"""``coriolis_matrix(q, qdot)``: :math:`C(q, \dot q)` (Christoffel symbols), n x n (row-major).

    With the momentum :math:`p = M\dot q` (rates held fixed),
    :math:`C_{kj} = \tfrac12 \dot M_{kj} + \tfrac12(\partial p_k/\partial q_j - \partial p_j/\partial q_k)`.
    """
    space = _Space(chain)
    n = chain.robot.n_coordinates
    inputs = space.inputs("q", "qdot")
    if strategy != "fastest":
        C_joints = coriolis_matrix(space.joints, simplify=strategy == "simplified")
        C = space.matrix(C_joints.tolist())
        return _symbolic(space, [e for row in C for e in row], (n, n), inputs,
                         "compact Christoffel symbols" if strategy == "simplified" else "raw Christoffel symbols of M")
    trace = Trace(space.joints, angle_expansion(space.joints))
    M = mass_matrix_trace(trace)
    m = len(M)
    M = [[trace.value(e) for e in row] for row in M]
    rates = space.rates
    M_dot = trace.derivative([e for row in M for e in row], dict(enumerate(rates)))
    p = [trace.value(sp.Add(*(M[k][i] * rates[i] for i in range(m)))) for k in range(m)]
    dp = [trace.derivative(p, {j: sp.S.One}) for j in range(m)]  # dp[j][k] = dp_k / dq_j
    half = sp.Rational(1, 2)
    C = [[half * (M_dot[k * m + j] + dp[j][k] - dp[k][j]) for j in range(m)] for k in range(m)]
    C = space.matrix(C)
    return _finished(space, trace, [e for row in C for e in row], (n, n), inputs,
                     "Christoffel symbols of the composite-body M, by forward differentiation")



def _carries(chain: Chain, field: str) -> bool:
    """Whether the robot's own dynamics carry this drive parameter (armature, viscous, coulomb) on some joint."""
    drives = [drive for drive in getattr(chain.robot, "drives", None) or () if drive is not None]
    return any(sp.sympify(getattr(drive, field)) != 0 for drive in drives)


def identification_regressor(chain: Chain, joints: bool = False) -> Regressor:
    """The regressor generated code computes: the link parameters, and the drive parameters the robot's model has.

    In the robot's coordinates (:math:`C^T Y` for coupled joints), or with ``joints`` on the chain of its joints.
    """
    return regressor(chain.joint_chain if joints else chain, EARTH, armature=_carries(chain, "armature"),
                     viscous=_carries(chain, "viscous"), coulomb=_carries(chain, "coulomb"))


def identification_base(chain: Chain) -> BaseParameters:
    """The base parameters of :func:`identification_regressor`, in the coordinates (coupling can group more)."""
    from symjac.analysis.identification.base import base_parameters

    return base_parameters(identification_regressor(chain))


def _regressor_function(chain: Chain, matrix: sp.MatrixBase, origin: str) -> LoweredFunction:
    space = _Space(chain)
    combined = space.C.T * sp.Matrix(matrix) if space.coupled else sp.Matrix(matrix)
    return _symbolic(space, list(combined), (combined.rows, combined.cols), space.inputs("q", "qdot", "qddot"),
                     origin)


@memoized()
def lowered_regressor(chain: Chain) -> LoweredFunction:
    r"""``regressor(q, qdot, qddot)``: :math:`Y` with :math:`\tau = Y\pi`, n x p (row-major), p standard parameters."""
    matrix = identification_regressor(chain, joints=True).matrix
    return _regressor_function(chain, matrix, "regressor, Newton-Euler per column")


@memoized()
def lowered_base_regressor(chain: Chain) -> LoweredFunction:
    r"""``base_regressor(q, qdot, qddot)``: :math:`Y_b` with :math:`\tau = Y_b\pi_b`, n x b (row-major).

    The kept columns of the joints' regressor, moved to the coordinates as the regressor is (:math:`C^T Y_b`).
    """
    Y = identification_regressor(chain, joints=True)
    kept = [Y.parameters.index(symbol) for symbol in identification_base(chain).standard]
    return _regressor_function(chain, Y.matrix.extract(list(range(Y.matrix.rows)), kept), "base regressor")


def _values_function(chain: Chain, values: Sequence[sp.Expr], origin: str) -> LoweredFunction:
    space = _Space(chain)
    return _symbolic(space, [sp.sympify(v) for v in values], (len(values),), space.inputs("q"), origin)


@memoized()
def lowered_standard_values(chain: Chain) -> LoweredFunction:
    r"""``_standard_values(q)``: the robot's own standard parameters :math:`\pi` (q unused), for the self-test."""
    Y = identification_regressor(chain, joints=True)
    values = standard_values(chain.joint_chain)
    return _values_function(chain, [values.get(p, sp.S.Zero) for p in Y.parameters], "the robot's inertial data")


@memoized()
def lowered_base_values(chain: Chain) -> LoweredFunction:
    r"""``_base_values(q)``: the robot's own base parameters :math:`\pi_b` (q unused), for the self-test."""
    Y = identification_regressor(chain, joints=True)
    values = standard_values(chain.joint_chain)
    full = {p: values.get(p, sp.S.Zero) for p in Y.parameters}
    return _values_function(chain, [sp.sympify(e).xreplace(full) for e in identification_base(chain).expressions],
                            "the robot's inertial data, grouped")
