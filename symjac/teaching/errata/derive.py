r"""What symjac derives for each printed formula, and the exact comparison that decides whether the print is right.

Each ``quantity`` of the data file names a function that returns the derived matrix for the formula's robot and
``args`` (:mod:`symjac.teaching.errata.base` for the common ones, one ``checks_*`` module per part of the notes for the
rest). A ``relation`` is a prose formula (a recursion, :math:`\tau = J^T F`) checked by evaluating it, as printed
or as corrected, on an example arm (:data:`RELATIONS`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy as sp

from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity
from symjac.teaching.errata.base import BASE_QUANTITIES
from symjac.teaching.errata.checks_000a import QUANTITIES_000A, RELATIONS_000A
from symjac.teaching.errata.checks_000b import QUANTITIES_000B, RELATIONS_000B
from symjac.teaching.errata.checks_matrices import QUANTITIES_SLIDES_NOTES
from symjac.teaching.errata.checks_notes import NOTE_RELATIONS
from symjac.teaching.errata.checks_slides import SLIDE_RELATIONS
from symjac.teaching.errata.formulas import Formula

__all__ = ["QUANTITIES", "RELATIONS", "RELATION_TOLERANCE", "Comparison", "compare", "derive"]

RELATION_TOLERANCE = 1e-9
"""A relation holds when its residual on the example arm is below this (relative to the size of the terms)."""

QUANTITIES: Mapping[str, Callable[..., sp.Matrix]] = {
    **BASE_QUANTITIES, **QUANTITIES_000A, **QUANTITIES_000B, **QUANTITIES_SLIDES_NOTES,
}


RELATIONS: Mapping[str, Callable[[Formula, str], float]] = {
    **RELATIONS_000A, **RELATIONS_000B, **SLIDE_RELATIONS, **NOTE_RELATIONS,
}
"""Checks of prose formulas: ``check(formula, "printed" | "corrected")`` is the relative residual of that form on an
example arm (0 when it holds); each check's docstring quotes the formula it evaluates."""


def derive(f: Formula) -> sp.Matrix:
    """The matrix symjac derives for formula ``f``."""
    if f.quantity not in QUANTITIES:
        raise KeyError(f"{f.id}: unknown quantity {f.quantity!r}; known: {', '.join(QUANTITIES)}")
    return sp.Matrix(QUANTITIES[f.quantity](f, **f.args))


@dataclass(frozen=True)
class Comparison:
    """The printed matrix against the derived one: entries (1-based) that differ, and the verdict they give."""

    formula: Formula
    derived: sp.Matrix
    differing: tuple[tuple[int, int], ...]
    corrected_holds: bool | None

    @property
    def verdict(self) -> str:
        """``"erratum"`` when the print differs; ``"convention"`` or ``"ok"`` (as recorded) when it holds."""
        if self.differing:
            return "erratum"
        return "convention" if self.formula.verdict == "convention" else "ok"


def _basis(f: Formula) -> AngleBasis:
    angles = [j.variable for j in f.robot.joints if j.is_revolute] if f.robot is not None else []
    return AngleBasis.of([*angles, *f.symbols])


def _differs(left: sp.Expr, right: sp.Expr, basis: AngleBasis) -> bool:
    numerator, _ = sp.fraction(sp.together(left - right))
    return not is_identity(numerator, sp.S.Zero, basis)


def _differing(printed: sp.MatrixBase, derived: sp.MatrixBase, basis: AngleBasis) -> tuple[tuple[int, int], ...]:
    if printed.shape != derived.shape:
        return ((0, 0),)
    return tuple((r + 1, c + 1) for r in range(printed.rows) for c in range(printed.cols)
                 if _differs(printed[r, c], derived[r, c], basis))


def compare(f: Formula) -> Comparison:
    """Compare the printed (and the corrected) matrix of ``f`` with the derivation, exactly.

    A relation is compared numerically on its example arm (:data:`RELATIONS`, :data:`RELATION_TOLERANCE`).
    """
    if f.quantity == "relation":
        check = RELATIONS[f.args["check"]]
        printed_holds = check(f, "printed") <= RELATION_TOLERANCE
        corrected = None if not f.corrected_text else check(f, "corrected") <= RELATION_TOLERANCE
        return Comparison(f, sp.Matrix([[0]]), () if printed_holds else ((1, 1),), corrected)
    derived = derive(f)
    basis = _basis(f)
    corrected = None if f.corrected is None else not _differing(f.corrected, derived, basis)
    return Comparison(f, derived, _differing(f.printed, derived, basis), corrected)
