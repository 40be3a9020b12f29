"""A redundant arm's singularities in words: minors locked and vanishing everywhere, and each singular set.

Like :mod:`symjac.printing.prose.singularities`, this names the analyses' types only for checkers and compares their
string enums by value.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import sympy as sp

from symjac.printing.prose.singularities import (
    evidence_clauses,
    finding_sentence,
    limit_parts,
    lost_words,
    sample_parts,
    self_motion_parts,
)

if TYPE_CHECKING:
    from symjac.analysis.singularity.redundant import SingularSet, ZeroMinor
    from symjac.analysis.singularity.singularities import SingularityReport

__all__ = [
    "LONG_INLINE",
    "is_long",
    "locked_words",
    "long_name",
    "long_names",
    "set_parts",
    "set_reason",
    "sets_caption",
    "zero_minor_words",
]


def _joint_list(joints: Sequence[int]) -> str:
    numbers = [str(j + 1) for j in sorted(joints)]
    return numbers[0] if len(numbers) == 1 else f"{', '.join(numbers[:-1])} and {numbers[-1]}"


def locked_words(locked: Sequence[str]) -> str:
    """``Joint 4 locked``, ``Joints 1 and 2 locked``, ``theta5 locked`` (a coupled robot's coordinate)."""
    if len(locked) == 1:
        return f"{locked[0][0].upper()}{locked[0][1:]} locked"
    joints = [name.removeprefix("joint ") for name in locked]
    label = "Joints " if all(name.startswith("joint ") for name in locked) else ""
    words = f"{', '.join(joints[:-1])} and {joints[-1]}"
    return f"{label}{words} locked" if label else f"{words[0].upper()}{words[1:]} locked"


def zero_minor_words(zero: ZeroMinor) -> str:
    """Why a minor vanishes at every configuration, in one sentence (without the final full stop)."""
    groups = [f"joints {_joint_list(group)}" for group in zero.concurrent]
    rank = f"its {len(zero.columns)} columns have rank {zero.rank} wherever the arm is"
    if len(groups) == 2:
        return (f"identically zero: the axes of {groups[0]} meet at one point and those of {groups[1]} at another, "
                f"so a force along the line through the two points loads none of these joints ({rank})")
    if groups:
        return f"identically zero: the axes of {groups[0]} meet at one point ({rank})"
    return f"identically zero: {rank}"


_SET_REASONS = {  # by SingularityKind, a string enum
    "elbow": "the arm is stretched out or folded back at {joints}",
    "shoulder": "a shoulder singularity, set by {joints} alone",
    "wrist": "a wrist singularity, set by {joints} alone",
    "alignment": "axes line up, set by {joints}",
    "other": "",
}


def set_reason(singular_set: SingularSet) -> str:
    """What happens on one singular set of a redundant arm, in one sentence (without the final full stop)."""
    from symjac.analysis.singularity.redundant import set_joints

    involved = set_joints(singular_set)
    joints = f"joint{'s' if len(involved) > 1 else ''} {_joint_list(involved)}"
    words = _SET_REASONS[singular_set.kind].format(joints=joints)
    evidence = "; ".join(finding_sentence(finding) for finding in singular_set.cause.findings)
    if not singular_set.exists_for_defaults:
        words = (words + "; " if words else "") + "no configuration of it exists for the default parameters"
    text = f"{words} ({evidence})" if words and evidence else words or evidence
    clauses = evidence_clauses(singular_set.evidence)
    text = "; ".join([text, *clauses] if text else clauses)
    return text or "no aligned axes found; see the lost direction and the self-motion"


def sets_caption(report: SingularityReport) -> str:
    """How many singular sets a redundant arm has, how they were found, and whether the list may be incomplete."""
    if all(minor.coefficient == 0 for minor in report.minors):
        rank = max((zero.rank for zero in report.zero_minors), default=0)
        return (f"Every minor vanishes identically: the arm is singular at every configuration (rank {rank} at "
                "most).")
    count = len(report.sets)
    incomplete = ""
    if report.unsolved:
        shown = ", ".join(sp.sstr(f) for f in report.unsolved[:3]) + (", ..." if len(report.unsolved) > 3 else "")
        incomplete = (f" Factors not solved for one joint were left out of the search ({shown}), so the list may be "
                      "incomplete.")
    if not count:
        return ("Singular sets: none found among the combinations of up to three minor factors, each solved for a "
                f"different joint.{incomplete}")
    sets = "one singular set" if count == 1 else f"{count} singular sets"
    each = "a combination" if count == 1 else "each a combination"
    return (f"Singular sets: the arm loses rank exactly where every nonzero minor vanishes; {sets} found, {each} "
            f"of minor factors:{incomplete}")


def _motion_count(singular_set: SingularSet) -> str:
    there, near = len(singular_set.null_space), len(singular_set.regular_null_space)
    return f"the self-motions form a space of dimension {there} there ({near} nearby)"


LONG_INLINE = 60
"""Characters (SymPy syntax) beyond which a condition or solution is displayed below a caption, not inside it."""


def long_name(number: int) -> sp.Symbol:
    """The name ``F_k`` a long condition (0-based ``number``) goes by in a caption."""
    return sp.Symbol(f"F_{number + 1}")


def long_names(sets: Sequence[SingularSet]) -> dict[sp.Expr, sp.Symbol]:
    """One name ``F_k`` per distinct long condition of a report's sets, numbered in order of first appearance.

    A document names each condition once: the same condition in two sets keeps its name, two different ones never
    share one.
    """
    names: dict[sp.Expr, sp.Symbol] = {}
    for singular_set in sets:
        for condition in singular_set.conditions:
            if is_long(condition.expression) and condition.expression not in names:
                names[condition.expression] = long_name(len(names))
    return names


def is_long(expr: sp.Basic) -> bool:
    """Whether ``expr`` is too long to stand inside a sentence (it would overrun a printed line)."""
    return len(sp.sstr(expr)) > LONG_INLINE


def set_parts(singular_set: SingularSet, names: Mapping[sp.Expr, sp.Symbol] | None = None, degrees: bool = False
              ) -> tuple[str | sp.Basic, ...]:
    """One singular set as caption parts: its conditions, kind, reason, what is lost, its self-motions and limits.

    A long condition is named ``F_k = 0`` (by ``names``, :func:`long_names` of the whole report; else k is its place
    in the set) and displayed below as ``F_k = ...``; solutions too long for a page are left to the JSON output.
    ``degrees`` writes the sample's angles in degrees (:func:`~symjac.printing.prose.singularities.sample_parts`).
    """
    parts: list[str | sp.Basic] = []
    for number, condition in enumerate(singular_set.conditions):
        name = names[condition.expression] if names is not None and is_long(condition.expression) else long_name(number)
        shown = sp.Eq(name if is_long(condition.expression) else condition.expression, 0, evaluate=False)
        parts += [" and "] * bool(number) + [shown]
    where = sample_parts(singular_set.sample, singular_set.variables, degrees)
    parts += [f" ({singular_set.kind})", *([", "] if where else []), *where, f": {set_reason(singular_set)}."]
    lost = lost_words(singular_set)
    if lost:
        parts += [f" There the arm {lost}; {_motion_count(singular_set)}"]
        motion = self_motion_parts(singular_set)
        parts += ["; the new one: ", *motion, "."] if motion else ["."]
    if any(is_long(solution.rhs) for solution in singular_set.solutions):
        parts.append(" Solutions too long to print here are in the JSON output.")
        parts.append(_limit_counts(singular_set))
    else:
        parts.extend(limit_parts(singular_set))
    return tuple(parts)


def _limit_counts(singular_set: SingularSet) -> str:
    """The solutions against the joint limits as counts, for solutions too long to name in a sentence."""
    counts: dict[str, int] = {}
    for status in singular_set.limits:
        if status != "unlimited":
            counts[str(status)] = counts.get(str(status), 0) + 1
    if not counts:
        return ""
    words = {"inside": "inside them", "outside": "outside them", "partly": "partly inside them",
             "unknown": "not checked"}
    listed = ", ".join(f"{count} {words[status]}" for status, count in counts.items())
    return f" Joint limits, over the {len(singular_set.limits)} solution branches: {listed}."
