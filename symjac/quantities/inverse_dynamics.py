r"""Inverse dynamics :math:`\tau(q, \dot q, \ddot q)` by recursive Newton-Euler (``symjac dynamics``).

The command's own quantity: with no part flag, ``symjac dynamics ROBOT`` prints the joint torques (with ``--steps``
every Newton-Euler step first). Coupling: the derivation already returns a coupled robot's torques in its coordinates,
:math:`\tau_q = C^T \tau(\vartheta(q), C\dot q, C\ddot q)`, which is the ``transposed`` law applied to the joints'
torques (code generation moving the joint chain's result applies exactly that).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from symjac.quantities.dynamics import command, options
from symjac.quantities.spec import Generated, Quantity

if TYPE_CHECKING:
    import sympy as sp

__all__ = ["QUANTITY", "inverse_dynamics"]


def inverse_dynamics(robot: Any, *args: Any, **kwargs: Any) -> sp.ImmutableMatrix:
    r"""The torques :math:`\tau(q, \dot q, \ddot q)`, n x 1, by recursive Newton-Euler.

    The ``torques`` of :func:`~symjac.analysis.dynamics.newton_euler.newton_euler`, called with the same arguments
    (the robot or chain, gravity, ``simplify``).
    """
    from symjac.analysis.dynamics.newton_euler import newton_euler

    return newton_euler(robot, *args, **kwargs).torques


QUANTITY = Quantity(
    name="inverse_dynamics",
    summary="print the equations of motion: the joint torques tau(q, qdot, qddot), M(q), C(q, qdot), g(q), energy",
    derivation="symjac.quantities.inverse_dynamics:inverse_dynamics",
    coupling="transposed",
    document="symjac.printing.dynamics:dynamics_document",
    codegen=Generated("inverse_dynamics",
                      "tau = M(q) qddot + C(q, qdot) qdot + g(q), one generalised force per {unit}.",
                      "Inverse dynamics tau(q, qdot, qddot) by Newton-Euler.", output="tau", scope="module",
                      dynamics=True, inputs=("qdot", "qddot"),
                      summary="Inverse dynamics tau = M(q) qddot + C(q, qdot) qdot + g(q)",
                      lowering="symjac.codegen.dynamics:lowered_inverse_dynamics"),
    command="dynamics",
    options=options,
    handler=command,
)
