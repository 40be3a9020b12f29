"""How a short arm's rows were chosen, in words: which rows, in which frame, and why their determinant is the test.

Like the other prose modules it names the analyses' types only for checkers and reads string enums by value.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import sympy as sp

from symjac.kinematics.jacobian import ROW_NAMES
from symjac.printing.document import Inline
from symjac.printing.prose.results import point_phrase

if TYPE_CHECKING:
    from symjac.analysis.singularity.determinant import Determinant
    from symjac.analysis.singularity.singularities import SingularityReport

__all__ = ["choice_parts", "row_minor_words", "row_minors_caption"]

_ROW_WORDS = {"v_x": "v_x", "v_y": "v_y", "v_z": "v_z", "omega_x": "ω_x", "omega_y": "ω_y", "omega_z": "ω_z"}


def _row(row: int) -> Inline:
    symbol = sp.Symbol(ROW_NAMES[row])
    return Inline(sp.latex(symbol), _ROW_WORDS[symbol.name], symbol)


def _listed(rows: tuple[int, ...]) -> list[str | Inline]:
    parts: list[str | Inline] = []
    for number, row in enumerate(rows):
        parts += [", " if number < len(rows) - 1 or len(rows) == 1 else " and "] * bool(number) + [_row(row)]
    return parts


def _size(rows: int, columns: int) -> Inline:
    """``6 × 4`` as inline math."""
    return Inline(rf"{rows} \times {columns}", f"{rows} \N{MULTIPLICATION SIGN} {columns}")


def _joints(n: int, report: SingularityReport) -> str:
    """``4 joints``, or for a coupled robot ``5 joints and 4 independent coordinates``."""
    return f"{n} joints" if report.n_joints in (n, 0) else f"{report.n_joints} joints and {n} independent coordinates"


def _why(report: SingularityReport) -> list[str | Inline]:
    """Why the determinant of the chosen rows is the arm's test, as caption parts (empty for six rows)."""
    choice, n = report.choice, len(report.variables)
    if choice is None:
        return []
    if choice.criterion == "position":
        parts: list[str | Inline] = [f" The arm only positions a point with its {n} joints, so it is singular where "
                                     "the linear rows of its Jacobian lose rank"]
    else:
        parts = [f" The arm has {_joints(n, report)} and moves in {n} independent directions, so it is singular "
                 "where its ", _size(6, n), " Jacobian loses rank"]
    zero = tuple(row for row, anchor in choice.dropped if anchor is None)
    multiples = [(row, anchor) for row, anchor in choice.dropped if anchor is not None]
    if zero or multiples:
        parts.append(f"; in frame {{{choice.frame}}} the rows left out are ")
        if zero:
            parts += ["zero (", *_listed(zero), ")"]
        if multiples:
            parts.append(" or multiples of kept rows (" if zero else "multiples of kept rows (")
            for number, (row, anchor) in enumerate(multiples):
                parts += ["; "] * bool(number) + [_row(row), " of ", _row(anchor)]
            parts.append(")")
        parts.append(", so this determinant vanishes exactly there.")
    else:
        parts.append("; these are its three linear rows.")
    return parts


def choice_parts(report: SingularityReport) -> tuple[str | Inline, ...]:
    """``Determinant of rows v_x, v_y of the Jacobian in frame {2}:``, with the reason for a short arm's rows."""
    det = report.determinant
    where = point_phrase(report.point_name, n=report.n_joints)
    parts: list[str | Inline] = ["Determinant of rows ", *_listed(det.rows),
                                 f" of the Jacobian in frame {{{det.frame}}}, at {where}"]
    why = _why(report)
    return (*parts, ":") if not why else (*parts, ".", *why)


def row_minors_caption(report: SingularityReport) -> tuple[str | Inline, ...]:
    """Why a short arm's report lists row minors: no frame holds its rank in as many rows as it has joints."""
    choice, n = report.choice, len(report.variables)
    assert choice is not None
    position = choice.criterion == "position"
    criterion = ("its linear rows lose",) if position else ("its ", _size(6, n), " Jacobian loses")
    frames = "No frame carries" if choice.everywhere else f"Frame {{{choice.frame}}} does not carry"
    return (f"{report.robot} has {_joints(n, report)} and is singular at "
            f"{point_phrase(report.point_name, n=report.n_joints)} where ", *criterion, f" rank. {frames} that rank "
            f"in {n} rows alone, so every ", _size(n, n), " minor of the rows ", *_listed(choice.rows),
            f" in frame {{{choice.frame}}} is below; the arm is singular exactly where all of them vanish at once (the "
            "minors that vanish everywhere are left out).")


def row_minor_words(minor: Determinant) -> tuple[str | Inline, ...]:
    """``Rows v_x, v_y, v_z and ω_z:``, the caption of one row minor."""
    return ("Rows ", *_listed(minor.rows), ":")
