r"""A singularity report laid out for reading: the determinant, then each factor, its solutions and its meaning."""

from __future__ import annotations

from typing import TYPE_CHECKING

import sympy as sp

from symjac.printing import prose
from symjac.printing.document import Block, Equation, Style, blocks_as_pairs

if TYPE_CHECKING:
    from symjac.analysis.singularity.singularities import SingularityReport

__all__ = ["singularity_blocks", "singularity_summary"]


def _det(value: sp.Expr) -> Equation:
    return Equation(r"\det J", "det J", value)


def singularity_blocks(report: SingularityReport, degrees: bool = False) -> list[Block]:
    r"""The report as captioned blocks: :math:`\det J` (or every minor of a redundant arm), then each factor.

    Each explanation starts with the configuration its numbers were read at, its angles in degrees with
    ``degrees`` (a robot file that says ``angle_unit = "deg"``).
    """
    if report.redundant:
        return _redundant_blocks(report, degrees)
    caption = prose.rows_parts(report) if report.choice is None else prose.choice_parts(report)
    blocks = [Block(caption, (_det(report.determinant.expression),))]
    for factor in report.factors:
        where = prose.sample_parts(factor.sample, report.variables, degrees) if factor.solutions else ()
        head: list[str | sp.Basic] = ["Factor ", factor.expression, f" ({factor.kind})", *([", "] if where else []),
                                      *where, ": ", *prose.reason_parts(factor), "."]
        if factor.solutions:
            existence = prose.existence_parts(factor)
            if existence:
                head += [" ", *existence]
            lost, motion = prose.lost_words(factor), prose.self_motion_parts(factor)
            if lost or motion:
                head += [" There it ", lost or "loses rank", "; " if motion else "", *motion, "."]
            head.extend(prose.limit_parts(factor))
        blocks.append(Block(tuple(head), tuple(Equation("", "", s.equation) for s in factor.solutions)))
    return blocks


def _redundant_blocks(report: SingularityReport, degrees: bool) -> list[Block]:
    """Every minor (a zero one with its reason), then every singular set with its solutions."""
    if report.over_rows:
        blocks = [Block(prose.row_minors_caption(report))]
        blocks += [Block(prose.row_minor_words(minor), (_det(minor.expression),)) for minor in report.minors]
        return blocks + _set_blocks(report, degrees)
    blocks = [Block(prose.redundant_caption(report))]
    zeros = {zero.columns: zero for zero in report.zero_minors}
    for minor in report.minors:
        locked = [name for c, name in enumerate(report.coordinates) if c not in minor.columns]
        caption = f"{prose.locked_words(locked)}:"
        if minor.columns in zeros:
            caption = f"{prose.locked_words(locked)}: {prose.zero_minor_words(zeros[minor.columns])}."
        blocks.append(Block((caption,), (_det(minor.expression),)))
    return blocks + _set_blocks(report, degrees)


def _set_blocks(report: SingularityReport, degrees: bool) -> list[Block]:
    """How the singular sets were found, then each set with its conditions and solutions."""
    blocks = [Block((prose.sets_caption(report),))]
    names, defined = prose.long_names(report.sets), set()  # each F_k displayed once, where it first appears
    for number, singular_set in enumerate(report.sets, start=1):
        long = []
        for condition in singular_set.conditions:
            name = names.get(condition.expression)
            if name is not None and name not in defined:
                defined.add(name)
                long.append(Equation(sp.latex(name), str(name), condition.expression))
        solutions = [Equation("", "", s.equation) for s in singular_set.solutions if not prose.is_long(s.rhs)]
        blocks.append(Block((f"Set {number}: ", *prose.set_parts(singular_set, names, degrees)), (*long, *solutions)))
    return blocks


def singularity_summary(report: SingularityReport, style: Style = "latex") -> list[tuple[str, str]]:
    r"""A singularity report as (caption, equation) pairs: the determinant, then each factor with its meaning.

    ``style`` is ``"latex"`` (equations in LaTeX, captions in plain words) or ``"pretty"`` (Unicode).

    Examples
    --------
    >>> from symjac import load_robot, singularities
    >>> summary = singularity_summary(singularities(load_robot("planar2r")))
    >>> summary[0][1]
    '\\det J = L_{1} L_{2} s_{2}'
    """
    return blocks_as_pairs(singularity_blocks(report), style)
