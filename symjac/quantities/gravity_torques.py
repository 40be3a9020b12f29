r"""The gravity torques :math:`g(q) = \partial V/\partial q` (``symjac dynamics --gravity-torques``).

The torques that hold the arm still against gravity (``--gravity`` sets gravity's direction and magnitude). Coupling:
the derivation returns :math:`C^T g(\vartheta(q))` in the coordinates, the ``transposed`` law.
"""

from __future__ import annotations

import argparse

from symjac.quantities.dynamics import command
from symjac.quantities.spec import Generated, Quantity

__all__ = ["QUANTITY", "options"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--gravity-torques``."""
    sub.add_argument("--gravity-torques", action="store_true",
                     help="print the gravity torques g(q) (gravity compensation)")


QUANTITY = Quantity(
    name="gravity_torques",
    summary="print the gravity torques g(q)",
    derivation="symjac.analysis.dynamics.lagrange:gravity_torques",
    coupling="transposed",
    document="symjac.printing.dynamics:dynamics_document",
    codegen=Generated("gravity_torques", "g(q) = dV/dq, one per {unit}.", "The gravity torques g(q) = dV/dq.",
                      output="gravity", scope="module", dynamics=True, summary="Gravity torques g(q) = dV/dq",
                      lowering="symjac.codegen.dynamics:lowered_gravity_torques"),
    command="dynamics",
    flag="gravity_torques",
    options=options,
    handler=command,
)
