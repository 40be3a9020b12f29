"""The errata sheet: where, as printed, corrected, and why, for every formula the derivation does not confirm.

Generated from the data file and the comparison (:func:`symjac.teaching.errata.derive.compare`), in Markdown or LaTeX;
convention notes (a formula that holds in another stated convention) are listed apart from the errata.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache

import sympy as sp

from symjac.errors import ArgumentError
from symjac.printing.latex import latex
from symjac.teaching.errata.derive import Comparison, compare
from symjac.teaching.errata.formulas import DOCUMENTS, formulas

__all__ = ["SHEET_FORMATS", "comparisons", "errata_sheet", "summary"]

SHEET_FORMATS = ("markdown", "latex")
"""Formats of the errata sheet: Markdown, or a standalone LaTeX document."""


@cache
def comparisons() -> tuple[Comparison, ...]:
    """Every formula of the data file compared with the derivation, in file order (computed once)."""
    return tuple(compare(f) for f in formulas())


def summary(results: Sequence[Comparison]) -> dict[str, dict[str, int]]:
    """Per document: how many formulas were checked, confirmed, misprinted and convention notes."""
    counts = {doc: {"checked": 0, "ok": 0, "erratum": 0, "convention": 0} for doc in DOCUMENTS}
    for result in results:
        entry = counts[result.formula.document]
        entry["checked"] += 1
        entry[result.verdict] += 1
    return counts


def _entries(matrix: sp.MatrixBase, cells: Sequence[tuple[int, int]]) -> list[sp.Expr]:
    return [matrix[r - 1, c - 1] for r, c in cells]


def _cell_text(result: Comparison, matrix: sp.MatrixBase, style: str) -> str:
    if result.formula.quantity == "relation":
        text = result.formula.printed_text if matrix is result.formula.printed else result.formula.corrected_text
        return f"${text}$" if style == "latex" else f"`{text}`"
    cells = result.differing
    if matrix.shape == (1, 1) or cells == ((0, 0),):
        return f"${latex(matrix[0, 0] if matrix.shape == (1, 1) else matrix)}$" if style == "latex" else (
            f"`{sp.sstr(matrix[0, 0] if matrix.shape == (1, 1) else matrix)}`")
    parts = []
    for (r, c), value in zip(cells, _entries(matrix, cells), strict=True):
        parts.append(f"$({r},{c})$: ${latex(value)}$" if style == "latex" else f"({r},{c}): `{sp.sstr(value)}`")
    return "; ".join(parts)


def errata_sheet(fmt: str = "markdown") -> str:
    """The errata sheet as Markdown or as a LaTeX document (``fmt`` in :data:`SHEET_FORMATS`)."""
    if fmt not in SHEET_FORMATS:
        raise ArgumentError(f"unknown errata format {fmt!r}; choose one of {', '.join(SHEET_FORMATS)}")
    results = comparisons()
    errata = [r for r in results if r.verdict == "erratum"]
    notes = [r for r in results if r.verdict == "convention"]
    counts = summary(results)
    if fmt == "markdown":
        lines = ["# Errata for the course notes", "",
                 "| document | formulas checked | confirmed | errata | convention notes |",
                 "| --- | --- | --- | --- | --- |"]
        lines += [f"| {doc} ({DOCUMENTS[doc]}) | {c['checked']} | {c['ok']} | {c['erratum']} | {c['convention']} |"
                  for doc, c in counts.items()]
        lines += ["", "## Errata", "", "| where | as printed | corrected | why |", "| --- | --- | --- | --- |"]
        for r in errata:
            lines.append(f"| {r.formula.document}, {r.formula.where}: {r.formula.what} | "
                         f"{_cell_text(r, r.formula.printed, 'markdown')} | {_cell_text(r, _right(r), 'markdown')} | "
                         f"{r.formula.why} |")
        lines += ["", "## Convention notes", "", "| where | what differs |", "| --- | --- |"]
        lines += [f"| {r.formula.document}, {r.formula.where}: {r.formula.what} | {r.formula.convention} |"
                  for r in notes]
        return "\n".join(lines) + "\n"
    rows = [rf"{_tex(r.formula.document + ', ' + r.formula.where + ': ' + r.formula.what)} & "
            rf"{_cell_text(r, r.formula.printed, 'latex')} & {_cell_text(r, _right(r), 'latex')} & "
            rf"{_tex(r.formula.why)} \\ \hline" for r in errata]
    notes_tex = [rf"\item {_tex(r.formula.where + ': ' + r.formula.what)}: {_tex(r.formula.convention)}" for r in notes]
    counts_tex = [rf"{doc} & {c['checked']} & {c['ok']} & {c['erratum']} & {c['convention']} \\"
                  for doc, c in counts.items()]
    return "\n".join([
        r"\documentclass[10pt]{article}", r"\usepackage[margin=1.5cm,landscape]{geometry}",
        r"\usepackage{amsmath,amssymb,longtable,array}", r"\begin{document}", r"\section*{Errata for the course notes}",
        r"\begin{tabular}{lrrrr} document & checked & confirmed & errata & convention notes \\ \hline",
        *counts_tex, r"\end{tabular}", "",
        r"\small\setlength{\tabcolsep}{4pt}",  # the widest printed formulas fit their cells
        r"\begin{longtable}{|p{4cm}|p{7.5cm}|p{7.5cm}|p{4.5cm}|} \hline where & as printed & corrected & why \\ \hline",
        *rows, r"\end{longtable}", "", r"\subsection*{Convention notes}",
        r"\begin{itemize}" if notes_tex else "", *notes_tex, r"\end{itemize}" if notes_tex else "",
        r"\end{document}", ""])


def _right(result: Comparison) -> sp.MatrixBase:
    """What the corrected column shows: the derivation (for a relation, the corrected text)."""
    return result.derived if result.formula.quantity != "relation" else result.formula.corrected or result.derived


def _tex(text: str) -> str:
    """Plain words for LaTeX text mode: the special characters escaped."""
    replacements = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
                    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}"}
    return "".join(replacements.get(ch, ch) for ch in text)
