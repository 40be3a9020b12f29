r"""The Coriolis matrix :math:`C(q, \dot q)` from the Christoffel symbols (``symjac dynamics --coriolis``).

:math:`C_{kj} = \sum_i \tfrac12 (\partial M_{kj}/\partial q_i + \partial M_{ki}/\partial q_j - \partial M_{ij}/\partial
q_k)\,\dot q_i`, so that :math:`\dot M - 2C` is skew-symmetric. Coupling: the derivation returns
:math:`C^T C(\vartheta(q), C\dot q)\,C` in the coordinates, the ``congruent`` law on a matrix.
"""

from __future__ import annotations

import argparse

from symjac.quantities.dynamics import command
from symjac.quantities.spec import Generated, Quantity

__all__ = ["QUANTITY", "options"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--coriolis``."""
    sub.add_argument("--coriolis", action="store_true",
                     help="print the Coriolis matrix C(q, qdot) (Christoffel symbols: Mdot - 2C skew)")


QUANTITY = Quantity(
    name="coriolis_matrix",
    summary="print the Coriolis matrix C(q, qdot)",
    derivation="symjac.analysis.dynamics.lagrange:coriolis_matrix",
    coupling="congruent",
    document="symjac.printing.dynamics:dynamics_document",
    codegen=Generated("coriolis_matrix", "C(q, qdot) from the Christoffel symbols (Mdot - 2C is skew), shape {shape}.",
                      "The Coriolis and centrifugal matrix C(q, qdot) (Christoffel symbols: Mdot - 2C is skew).",
                      output="coriolis", scope="module", dynamics=True, inputs=("qdot",),
                      summary="Coriolis and centrifugal matrix C(q, qdot), from the Christoffel symbols",
                      lowering="symjac.codegen.dynamics:lowered_coriolis_matrix"),
    command="dynamics",
    flag="coriolis",
    options=options,
    handler=command,
)
