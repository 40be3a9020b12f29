r"""Yoshikawa's manipulability :math:`w = \sqrt{\det(J J^T)}` and its gradient, at a configuration.

No command prints it (``symjac sweep`` maps it over designs); generated modules compute it from their Jacobian.
Computed from the Jacobian in the coordinates, it follows the Jacobian's coupling law.
"""

from __future__ import annotations

from symjac.quantities.spec import Generated, Quantity

__all__ = ["QUANTITY"]

QUANTITY = Quantity(
    name="manipulability",
    summary="Yoshikawa's manipulability sqrt(det(J J^T)) and its gradient at a configuration",
    derivation="symjac.analysis.manipulability:manipulability_gradient",
    coupling="columns",
    codegen=Generated(
        "manipulability", "Zero exactly at a singular configuration (up to rounding).",
        listing="sqrt(det(J J^T)) of that Jacobian.", output="w", routine="manipulability", sources=("jacobian",),
        summary="Manipulability of ``{jacobian}``: |det J| when square, else sqrt(det(J J^T)) or sqrt(det(J^T J))"),
)
