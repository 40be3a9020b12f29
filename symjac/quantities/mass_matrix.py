r"""The mass matrix :math:`M(q)` (``symjac dynamics --mass-matrix``).

Derived from the link-COM Jacobians, :math:`M = \sum_i m_i J_{v_i}^T J_{v_i} + J_{\omega_i}^T R_i I_i R_i^T
J_{\omega_i}` (:func:`~symjac.analysis.dynamics.lagrange.mass_matrix`; Newton-Euler's columns agree). Coupling: the
derivation returns :math:`C^T M(\vartheta(q))\,C` in the coordinates, the ``congruent`` law on a matrix.
"""

from __future__ import annotations

import argparse

from symjac.quantities.dynamics import command
from symjac.quantities.spec import Generated, Quantity

__all__ = ["QUANTITY", "options"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--mass-matrix``."""
    sub.add_argument("--mass-matrix", action="store_true", help="print the mass matrix M(q)")


QUANTITY = Quantity(
    name="mass_matrix",
    summary="print the mass matrix M(q)",
    derivation="symjac.analysis.dynamics.lagrange:mass_matrix",
    coupling="congruent",
    document="symjac.printing.dynamics:dynamics_document",
    codegen=Generated("mass_matrix", "M(q), symmetric positive definite, shape {shape}.", "The mass matrix M(q).",
                      output="M", scope="module", dynamics=True, summary="Mass matrix M(q) (joint-space inertia)",
                      lowering="symjac.codegen.dynamics:lowered_mass_matrix"),
    command="dynamics",
    flag="mass_matrix",
    options=options,
    handler=command,
)
