"""A plain lowering of the dynamics (temporary: replaced by :mod:`symjac.codegen.dynamics`, the fast one).

Each function lowers the symbolic result of :mod:`symjac.analysis.dynamics` (Newton-Euler for the torques, the
Lagrangian route for M, C and g), raw (``simplify=False``), through the common CSE; inputs ``q``, ``qdot``,
``qddot`` in the robot's coordinates, gravity's magnitude ``g`` a parameter.
"""

from __future__ import annotations

import sympy as sp

from symjac.analysis.dynamics import GRAVITY_SYMBOL, coriolis_matrix, gravity_torques, mass_matrix, newton_euler
from symjac.codegen.lower import LoweredFunction, angle_expansion, lower_function
from symjac.kinematics.chain import Chain

__all__ = ["lowered_bias_forces", "lowered_coriolis_matrix", "lowered_gravity_torques", "lowered_inverse_dynamics",
           "lowered_mass_matrix"]


def _lowered(chain: Chain, matrix: sp.MatrixBase, inputs: tuple[str, ...], shape: tuple[int, ...],
             origin: str) -> LoweredFunction:
    model = chain.robot
    symbols = {"q": tuple(model.q), "qdot": model.coordinate_rates, "qddot": model.coordinate_accelerations}
    return lower_function(angle_expansion(chain), list(matrix), shape, tuple((name, symbols[name]) for name in inputs),
                          (*model.parameter_symbols, GRAVITY_SYMBOL), origin)


def lowered_inverse_dynamics(chain: Chain, strategy: str) -> LoweredFunction:
    """tau(q, qdot, qddot) by Newton-Euler."""
    del strategy
    n = chain.robot.n_coordinates
    return _lowered(chain, newton_euler(chain, simplify=False).torques, ("q", "qdot", "qddot"), (n,), "Newton-Euler")


def lowered_mass_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    """M(q)."""
    del strategy
    n = chain.robot.n_coordinates
    return _lowered(chain, mass_matrix(chain, simplify=False), ("q",), (n, n), "Lagrange")


def lowered_coriolis_matrix(chain: Chain, strategy: str) -> LoweredFunction:
    """C(q, qdot), Christoffel."""
    del strategy
    n = chain.robot.n_coordinates
    return _lowered(chain, coriolis_matrix(chain, simplify=False), ("q", "qdot"), (n, n), "Christoffel symbols")


def lowered_bias_forces(chain: Chain, strategy: str) -> LoweredFunction:
    """C(q, qdot) qdot + g(q)."""
    del strategy
    model = chain.robot
    n = model.n_coordinates
    C = coriolis_matrix(chain, simplify=False)
    b = C * sp.Matrix(model.coordinate_rates) + gravity_torques(chain, simplify=False)
    return _lowered(chain, b, ("q", "qdot"), (n,), "Christoffel symbols and gravity")


def lowered_gravity_torques(chain: Chain, strategy: str) -> LoweredFunction:
    """g(q) = dV/dq."""
    del strategy
    n = chain.robot.n_coordinates
    return _lowered(chain, gravity_torques(chain, simplify=False), ("q",), (n,), "potential energy")
