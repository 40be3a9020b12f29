r"""Lowering of the dynamics for machines: inverse dynamics, mass matrix, Coriolis matrix, bias forces, gravity.

Each function returns a :class:`~symjac.codegen.lower.LoweredFunction` whose inputs are the coordinates ``q`` and, as
the function needs them, their rates ``qdot`` and accelerations ``qddot``; the inertial parameters and the geometric
ones are parameters (symbols with defaults, :attr:`Robot.parameter_symbols <symjac.model.robot.Robot>`), and the
magnitude of gravity is written as its number (:attr:`Gravity.value
<symjac.analysis.dynamics.gravity.Gravity>` when it is a symbol).

.. math::
    \tau = M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q), \qquad b(q, \dot q) = C(q, \dot q)\,\dot q + g(q)

This first version lowers the raw recursion of :mod:`symjac.analysis.dynamics.newton_euler` (``simplify=False``)
and the raw Christoffel form of :func:`~symjac.analysis.dynamics.lagrange.coriolis_matrix`; robots with coupled
joints are refused.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from symjac.analysis.dynamics.gravity import EARTH, Gravity
from symjac.analysis.dynamics.lagrange import coriolis_matrix
from symjac.analysis.dynamics.newton_euler import newton_euler_mass_matrix, recursion
from symjac.codegen.lower import Inputs, LoweredFunction, angle_expansion, lower_function
from symjac.codegen.request import strategy_of
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain
from symjac.kinematics.memo import memoized

__all__ = [
    "lowered_bias_forces",
    "lowered_coriolis_matrix",
    "lowered_gravity_torques",
    "lowered_inverse_dynamics",
    "lowered_mass_matrix",
    "numeric_gravity",
]


def numeric_gravity(gravity: Gravity) -> Gravity:
    """``gravity`` with a symbolic magnitude replaced by its value (what generated code computes with)."""
    if isinstance(gravity.magnitude, sp.Symbol):
        return Gravity(direction=gravity.direction, magnitude=gravity.value, value=gravity.value)
    return gravity


def _uncoupled(chain: Chain, what: str) -> Chain:
    if chain.robot.coupling is not None:
        raise CodegenError(f"{chain.robot.name}: generated {what} of a robot with coupled joints is not supported "
                           "yet; generate it for the robot without its coupling")
    return chain


def _inputs(chain: Chain, *names: str) -> Inputs:
    robot = chain.robot
    available = {"q": robot.q, "qdot": robot.coordinate_rates, "qddot": robot.coordinate_accelerations}
    return tuple((name, tuple(available[name])) for name in names)


def _lowered(chain: Chain, values: Sequence[sp.Expr], shape: tuple[int, ...], inputs: Inputs,
             origin: str) -> LoweredFunction:
    return lower_function(angle_expansion(chain), list(values), shape, inputs, chain.robot.parameter_symbols, origin)


def _torques(chain: Chain, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr], gravity: Gravity
             ) -> list[sp.Expr]:
    steps = recursion(chain, rates, accelerations, numeric_gravity(gravity), simplify=False)
    return [step.tau for step in steps]


@memoized(strategy=strategy_of)
def lowered_inverse_dynamics(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``inverse_dynamics(q, qdot, qddot)``: :math:`\tau` by Newton-Euler, n values."""
    chain = _uncoupled(chain, "inverse dynamics")
    robot = chain.robot
    tau = _torques(chain, robot.coordinate_rates, robot.coordinate_accelerations, gravity)
    return _lowered(chain, tau, (len(tau),), _inputs(chain, "q", "qdot", "qddot"), "raw Newton-Euler recursion")


@memoized(strategy=strategy_of)
def lowered_bias_forces(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``bias_forces(q, qdot)``: :math:`C\dot q + g`, Newton-Euler with :math:`\ddot q = 0`, n values."""
    chain = _uncoupled(chain, "bias forces")
    robot = chain.robot
    tau = _torques(chain, robot.coordinate_rates, [sp.S.Zero] * robot.n_coordinates, gravity)
    return _lowered(chain, tau, (len(tau),), _inputs(chain, "q", "qdot"), "raw Newton-Euler recursion, qddot = 0")


@memoized(strategy=strategy_of)
def lowered_gravity_torques(chain: Chain, strategy: str, gravity: Gravity = EARTH) -> LoweredFunction:
    r"""``gravity_torques(q)``: :math:`g(q)`, Newton-Euler with :math:`\dot q = \ddot q = 0`, n values."""
    chain = _uncoupled(chain, "gravity torques")
    n = chain.robot.n_coordinates
    tau = _torques(chain, [sp.S.Zero] * n, [sp.S.Zero] * n, gravity)
    return _lowered(chain, tau, (n,), _inputs(chain, "q"), "raw Newton-Euler recursion, qdot = qddot = 0")


@memoized(strategy=strategy_of)
def lowered_mass_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    r"""``mass_matrix(q)``: :math:`M(q)`, n x n (row-major), column j from Newton-Euler with :math:`\ddot q = e_j`."""
    chain = _uncoupled(chain, "mass matrix")
    M = newton_euler_mass_matrix(chain, simplify=False)
    return _lowered(chain, list(M), M.shape, _inputs(chain, "q"), "raw Newton-Euler recursion per column")


@memoized(strategy=strategy_of)
def lowered_coriolis_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    r"""``coriolis_matrix(q, qdot)``: :math:`C(q, \dot q)` (Christoffel symbols), n x n (row-major)."""
    chain = _uncoupled(chain, "Coriolis matrix")
    C = coriolis_matrix(chain, simplify=False)
    return _lowered(chain, list(C), C.shape, _inputs(chain, "q", "qdot"), "raw Christoffel symbols of M")

