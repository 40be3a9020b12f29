"""Why a factor is singular and what the arm loses there, in words; the DH caption; representation singularities.

The analyses return data (:class:`~symjac.analysis.singularity.geometry.Finding`,
:class:`~symjac.analysis.singularity.singularities.LostDirection`,
...); these functions put them into words. The module names the analyses'
types only for checkers and compares their string enums by value, so printing a Jacobian does not load the analyses.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import sympy as sp

from symjac.kinematics.jacobian import ROW_NAMES
from symjac.model.conventions import plugin
from symjac.model.robot import Robot
from symjac.printing.document import Inline
from symjac.printing.pretty import one_line
from symjac.printing.prose.evidence import evidence_clauses, landmark_name
from symjac.printing.prose.results import point_phrase

if TYPE_CHECKING:
    from symjac.analysis.representations import RepresentationSingularity
    from symjac.analysis.singularity.evidence import Evidence
    from symjac.analysis.singularity.geometry import Cause, Finding, FrameAxis
    from symjac.analysis.singularity.redundant import SingularSet
    from symjac.analysis.singularity.singularities import (
        DirectionPart,
        LostDirection,
        SingularFactor,
        SingularityReport,
    )

__all__ = [
    "axis_name",
    "existence_parts",
    "existence_words",
    "finding_sentence",
    "limit_parts",
    "limit_text",
    "lost_words",
    "readable_number",
    "readable_value",
    "reason",
    "reason_parts",
    "redundant_caption",
    "representation_parts",
    "representation_words",
    "rows_caption",
    "rows_parts",
    "sample_parts",
    "self_motion_parts",
    "self_motion_words",
    "table_caption",
]

_AXIS_NAMES = ("x", "y", "z")


def finding_sentence(finding: Finding) -> str:
    """A geometric fact in words: ``the axes of joints 4 and 6 are collinear``."""
    from symjac.analysis.singularity.geometry import Relation

    joints = [j + 1 for j in finding.joints]
    name = "" if finding.landmark is None else landmark_name(finding.landmark)
    if finding.relation is Relation.PARALLEL_AXES:
        shape = "collinear" if finding.collinear else "parallel"
        return f"the axes of joints {joints[0]} and {joints[1]} are {shape}"
    if finding.relation is Relation.ON_FIRST_AXIS:
        return f"{name} lies on the axis of joint 1"
    if finding.relation is Relation.IN_SHOULDER_PLANE:
        return f"{name} lies in the plane through the axis of joint 1 parallel to the axis of joint 2"
    return f"{name} lies in the plane of the parallel axes of joints {joints[0]} and {joints[1]}"


def _cause_words(cause: Cause, facts: Evidence | None = None) -> str:
    clauses = evidence_clauses(facts, cause)
    if cause.kind in ("wrist", "shoulder", "elbow") and cause.findings:
        finding = cause.findings[0]
        said = [finding_sentence(finding)]
        if cause.kind == "elbow" and finding.landmark is not None and finding.landmark.kind != "joint axis":
            said[0] += " (the arm is stretched out or folded back)"
        return "; ".join([*said, *clauses])
    if cause.wrist_joints:
        said = [f"the factor depends only on the wrist joints {', '.join(str(j + 1) for j in cause.wrist_joints)}"]
    elif cause.findings:
        said = ["; ".join(sorted(finding_sentence(finding) for finding in cause.findings))]
    elif clauses:
        return "; ".join(clauses)
    else:
        return "no aligned axes found; see the lost direction and the self-motion"
    return "; ".join([*said, *clauses])


def reason(factor: SingularFactor) -> str:
    """Why ``factor`` is singular, in one sentence (without the final full stop)."""
    if factor.kind == "parameter":
        return (f"{factor.expression} depends on parameters only: a design with {factor.expression} = 0 would be "
                "singular everywhere; the default parameters are not")
    return _cause_words(factor.cause, factor.evidence)


def reason_parts(factor: SingularFactor) -> tuple[str | sp.Basic, ...]:
    """:func:`reason` as caption parts, its formulas as SymPy objects (printed as math)."""
    if factor.kind == "parameter":
        return (factor.expression, " depends on parameters only: a design with ",
                sp.Eq(factor.expression, 0, evaluate=False), " would be singular everywhere; the default parameters "
                "are not")
    return (_cause_words(factor.cause, factor.evidence),)


def axis_name(axis: FrameAxis) -> str:
    """``x of frame {3}``, ``z of the tool frame``."""
    label = f"frame {{{axis.frame}}}" if isinstance(axis.frame, int) else f"the {axis.frame} frame"
    return f"{_AXIS_NAMES[axis.axis]} of {label}"


def readable_number(value: float) -> str:
    """A computed number as a reader writes it: exact when it is a simple surd (``sqrt(2)/2``), else 3 decimals.

    Examples
    --------
    >>> readable_number(0.7071067811865476), readable_number(-0.5), readable_number(0.55412)
    ('√2/2', '-1/2', '0.554')
    """
    return one_line(readable_value(value))


def readable_value(value: float) -> sp.Expr:
    """:func:`readable_number` as a SymPy number, for math: the simple surd, else a float with 3 decimals."""
    exact = sp.nsimplify(value, [sp.sqrt(2), sp.sqrt(3), sp.sqrt(5)], tolerance=1e-9)
    if sp.count_ops(exact) <= 4 and all(abs(n) <= 12 for n in exact.atoms(sp.Integer)):
        return exact
    if abs(value) < 5e-4:
        return sp.S.Zero
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    if "." not in text:  # 0.9999999 is 1 to 3 decimals: the integer, not the float "1."
        return sp.Integer(text)
    return sp.Float(text, len(text.lstrip("-").replace(".", "").lstrip("0")))  # as many digits as shown


def _part_name(part: DirectionPart, frame: object, named: bool = True) -> str:
    """A named axis (if ``named``), or the unit vector's components (exact when simple, else rounded) in ``frame``."""
    import numpy as np

    if part.axis is not None and named:
        return axis_name(part.axis)
    return f"({', '.join(readable_number(float(c)) for c in np.asarray(part.unit))}) in frame {{{frame}}}"


def _direction(lost: LostDirection, words: tuple[str, str, str, str]) -> str:
    """``words`` = (linear alone, angular alone, angular after a linear part, joiner).

    Both halves are named in one frame: when a named axis belongs to another frame than the other half's vector (or
    than the other named axis), both are written as vectors in the lost direction's frame.
    """
    parts = [part for part in (lost.linear, lost.angular) if part is not None]
    frames = {part.axis.frame if part.axis is not None else lost.frame for part in parts}
    named = len(frames) <= 1
    linear = None if lost.linear is None else _part_name(lost.linear, lost.frame, named)
    angular = None if lost.angular is None else _part_name(lost.angular, lost.frame, named)
    if linear and angular:
        return f"{words[0]} along {linear} {words[3]} {words[2]} about {angular}"
    if linear:
        return f"{words[0]} along {linear}"
    return f"{words[1]} about {angular}" if angular else "nothing"


def lost_words(factor: SingularFactor | SingularSet) -> str:
    """What the arm cannot do on the singular set, and the wrench it holds for free there (``""`` if unknown)."""
    lost = factor.lost_direction
    if lost is None or (factor.evidence is not None and not factor.evidence.lost_checked):
        return ""  # stated only when u^T J = 0 was checked at the sample
    if lost.radial and lost.angular is None:  # the line says it exactly; the sample vector only illustrates it
        line = "the line from the origin of frame {0} to the point"
        return (f"cannot translate radially, along {line}, and it holds a force along that line with zero joint "
                f"torque (here: along {_part_name(lost.linear, lost.frame)})"
                if lost.linear is not None else "")
    radial = " (radially: along the line from the origin of frame {0} to the point)" if lost.radial else ""
    motion = _direction(lost, ("translate", "rotate", "rotating", "while"))
    wrench = _direction(lost, ("a force", "a moment", "a moment", "with"))
    return f"cannot {motion}{radial}, and it holds {wrench} with zero joint torque"


def _self_motion_rates(factor: SingularFactor | SingularSet) -> list[tuple[float, str]]:
    """The nonzero rates of the motion that moves nothing, with what they drive (``joint 2``, or ``theta5``)."""
    motion = factor.self_motion
    if motion is None or (factor.evidence is not None and not factor.evidence.motion_checked):
        return []  # stated only when J qdot = 0 was checked at the sample
    return [(rate, motion.names[i] if motion.names else f"joint {motion.columns[i] + 1}")
            for i, rate in enumerate(motion.rates) if abs(rate) > 1e-9]


def _still(factor: SingularFactor | SingularSet) -> str:
    """What a null motion leaves still: nothing moves for all six rows, else only what the rows analysed see."""
    rows = factor.lost_direction.rows if factor.lost_direction is not None else tuple(range(6))
    if set(rows) == set(range(6)):
        return " move nothing"
    if set(rows) <= {0, 1, 2}:
        return " leave the reference point still"
    return " produce nothing in the rows analysed"


def self_motion_words(factor: SingularFactor | SingularSet) -> str:
    """The joint motion that moves nothing, in words (``""`` if unknown)."""
    shown = [(readable_number(rate), joint) for rate, joint in _self_motion_rates(factor)]
    if not shown:
        return ""
    rates = ", ".join(f"{'' if value.startswith('-') else '+'}{value} on {joint}" for value, joint in shown)
    return f"joint rates {rates}{_still(factor)}"


def self_motion_parts(factor: SingularFactor | SingularSet) -> tuple[str | sp.Basic, ...]:
    """:func:`self_motion_words` as caption parts, each rate a number in math (``()`` if unknown)."""
    shown = _self_motion_rates(factor)
    if not shown:
        return ()
    parts: list[str | sp.Basic] = ["joint rates "]
    for number, (rate, joint) in enumerate(shown):
        parts += [", "] * bool(number) + [readable_value(rate), f" on {joint}"]
    return (*parts, _still(factor))


def sample_parts(sample: Sequence[float] | None, variables: Sequence[sp.Symbol], degrees: bool = False
                 ) -> tuple[str | sp.Basic | Inline, ...]:
    """Where the numbers of an explanation were read, as caption parts: ``at θ₁ = 0.3, θ₂ = π/2`` (``()`` if unknown).

    The lost direction and the joint rates that move nothing are computed at this configuration of the singular
    set (parameters at their defaults), so a reader can check them. With ``degrees`` (a robot file in degrees) the
    angles are written in degrees, ``θ₂ = 90°``, as the reader would type them.
    """
    if sample is None or len(sample) != len(variables):
        return ()
    parts: list[str | sp.Basic | Inline] = ["at "]
    for number, (variable, value) in enumerate(zip(variables, sample, strict=True)):
        angle = str(variable).startswith("theta")
        if angle and degrees:  # one piece of math: the degree sign is a superscript in LaTeX
            equation = sp.Eq(variable, readable_value(math.degrees(float(value))), evaluate=False)
            parts += [", "] * bool(number) + [Inline(f"{sp.latex(equation)}^{{\\circ}}", f"{one_line(equation)}°")]
            continue
        shown = _readable_angle(float(value)) if angle else None
        shown = readable_value(float(value)) if shown is None else shown
        parts += [", "] * bool(number) + [sp.Eq(variable, shown, evaluate=False)]
    return tuple(parts)


def _readable_angle(value: float) -> sp.Expr | None:
    """A joint angle that is a simple multiple of pi (``-pi/2``, ``2*pi/3``), else ``None``."""
    turns = sp.nsimplify(value / math.pi, tolerance=1e-9, rational=True)
    return turns * sp.pi if turns.q <= 12 and abs(turns.p) <= 24 else None


def existence_words(factor: SingularFactor) -> str:
    """When the factor's zeros exist, if that depends on the parameters (``""`` when they always exist)."""
    if factor.existence is None or factor.existence is sp.true:
        return ""
    verdict = {True: "holds", False: "does not hold", None: "unknown"}[factor.exists_for_defaults]
    return (f"Exists only if {one_line(factor.existence)} (assuming positive lengths; {verdict} for the default "
            "parameters).")


def existence_parts(factor: SingularFactor) -> tuple[str | sp.Basic, ...]:
    """:func:`existence_words` as caption parts, the condition as a SymPy relation (``()`` when none)."""
    if factor.existence is None or factor.existence is sp.true:
        return ()
    verdict = {True: "holds", False: "does not hold", None: "unknown"}[factor.exists_for_defaults]
    return ("Exists only if ", factor.existence, f" (assuming positive lengths; {verdict} for the default "
            "parameters).")


_LIMIT_WORDS = {  # by LimitStatus, a string enum
    "inside": "is inside them",
    "outside": "is outside them",
    "partly": "is partly inside them (depending on the other joints)",
    "unknown": "could not be checked",
}


def limit_parts(factor: SingularFactor | SingularSet) -> tuple[str | sp.Basic, ...]:
    """Where each solution lies relative to the joint limits, as caption parts (words and equations).

    Nothing when no solution involves a joint with limits; a factor whose every solution lies outside them is
    "not reachable within the joint limits".
    """
    marked = [(solution.equation, status) for solution, status in zip(factor.solutions, factor.limits, strict=True)
              if status != "unlimited"]
    if not marked:
        return ()
    parts: list[str | sp.Basic] = [" Not reachable within the joint limits:" if factor.reachable is False
                                   else " Joint limits:"]
    for number, (equation, status) in enumerate(marked):
        parts += [" " if number == 0 else "; ", equation, f" {_LIMIT_WORDS[status]}"]
    parts.append(".")
    return tuple(parts)


def limit_text(factor: SingularFactor | SingularSet) -> str:
    """:func:`limit_parts` as one line of plain text (``""`` when there is nothing to say)."""
    def plain(part: str | sp.Basic) -> str:
        return part if isinstance(part, str) else f"{sp.sstr(part.lhs)} = {sp.sstr(part.rhs)}"  # type: ignore[attr-defined]

    return "".join(plain(part) for part in limit_parts(factor)).strip()


def rows_caption(report: SingularityReport) -> str:
    """``Determinant of rows v_x, v_y of the Jacobian in frame {2}:``."""
    det = report.determinant
    rows = ", ".join(ROW_NAMES[r] for r in det.rows)
    return f"Determinant of rows {rows} of the Jacobian in frame {{{det.frame}}}:"


def _row_symbol(name: str) -> Inline:
    symbol = sp.Symbol(name)
    return Inline(sp.latex(symbol), name.replace("omega", "\N{GREEK SMALL LETTER OMEGA}"), symbol)


def rows_parts(report: SingularityReport) -> tuple[str | Inline, ...]:
    r""":func:`rows_caption` as caption parts, the rows as math (:math:`v_x, \omega_z`)."""
    det = report.determinant
    parts: list[str | Inline] = ["Determinant of rows "]
    for number, row in enumerate(det.rows):
        parts += [", "] * bool(number) + [_row_symbol(ROW_NAMES[row])]
    where = point_phrase(report.point_name, n=report.n_joints)
    return (*parts, f" of the Jacobian in frame {{{det.frame}}}, at {where}:")


def redundant_caption(report: SingularityReport) -> tuple[str | Inline, ...]:
    """Why a redundant arm's report lists minors instead of one determinant, as caption parts."""
    det = report.determinant
    rows = rows_parts(report)[1:-1]  # the row names between "Determinant of rows " and the frame
    condition = Inline(r"\sqrt{\det(J J^{T})} = 0", "sqrt(det(J J^T)) = 0")
    return (f"Redundant arm: {report.robot} has more joints than task rows (", *rows, "); it is singular only where "
            "every square minor below vanishes (where ", condition, f"). Minors in frame {{{det.frame}}}.")


def table_caption(robot: Robot) -> str:
    """The robot and the kind of its table: ``puma560: Unimation PUMA 560 ..., standard DH table``."""
    return f"{robot.name}: {robot.description}, {plugin(robot.convention).table_name}"


def representation_words(singularity: RepresentationSingularity) -> str:
    """What goes wrong at a representation singularity, in one sentence (without the final full stop)."""
    from symjac.analysis.representations.registry import REGISTRY

    spec = REGISTRY[singularity.representation]
    if singularity.cause == "gimbal lock":
        first, middle, last = spec.coordinates
        axes = spec.axes  # type: ignore[union-attr]
        if spec.is_proper:  # type: ignore[union-attr]
            return (f"the first and third rotation axes ({axes[0]}) line up (gimbal lock); only {first} + {last} "
                    f"({middle} = 0) or {first} - {last} ({middle} = pi) is defined, so their rates are unbounded")
        return (f"the first and third rotation axes ({axes[0]} and {axes[2]}) line up (gimbal lock); only the sum "
                f"or difference of {first} and {last} is defined, so their rates are unbounded")
    return _REPRESENTATION_CAUSES[singularity.cause]


_REPRESENTATION_CAUSES = {
    "no rotation axis": "the identity orientation has no rotation axis, so the axis rates are unbounded",
    "origin": "at the origin both angles are undefined",
    "polar axis": "on the polar (z) axis the azimuth is undefined",
    "z axis": "on the z-axis the azimuth is undefined",
}


def representation_parts(singularity: RepresentationSingularity) -> tuple[str | sp.Basic, ...]:
    """A singularity of a representation's rate matrix, told apart from a kinematic one, as caption parts."""
    values: list[str | sp.Basic] = []
    for number, value in enumerate(singularity.solutions):
        values += [" or "] * bool(number) + [sp.Eq(singularity.variable, value, evaluate=False)]
    return ("Representation singularity (not kinematic): ", sp.Eq(singularity.factor, 0, evaluate=False), ", that is ",
            *values, f": {representation_words(singularity)}.")
