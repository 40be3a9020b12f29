r"""The sentences of the HTML report (:func:`symjac.report.derivation_report`), as plain text or caption parts.

Plain strings are words (the page escapes them); caption parts mix words with SymPy objects, which the page prints
as inline MathML.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp

from symjac.model.robot import Robot

__all__ = [
    "ARM_INTRO",
    "METHODS_HEADING",
    "NO_SINGULAR_CURVE",
    "PATH_IN_MAP",
    "arm_home_caption",
    "arm_singular_parts",
    "curve_parts",
    "forward_kinematics_intro",
    "jacobian_frame_heading",
    "jacobian_intro",
    "map_caption",
    "methods_verdict",
    "point_words",
    "rates_parts",
    "regular_self_motion_parts",
    "set_mark_parts",
]

METHODS_HEADING = "Four methods, one Jacobian"
NO_SINGULAR_CURVE = ("No singular curve crosses this plane (the singular factors do not involve these joints, or the "
                     "arm is redundant and singular only where every minor vanishes).")
PATH_IN_MAP = "The dashed white segment is the path of the next figure."


ARM_INTRO = ("The arm drawn from its forward kinematics (parameters at their defaults): links between the frame "
             "origins, a cylinder on each revolute axis and a box on each prismatic one, and the frames' axes "
             "(x red, y green, z blue).")


def arm_home_caption(configuration: str) -> str:
    """The caption of the arm at its home configuration (``configuration``: the values, formatted)."""
    return f"Home: q = ({configuration})."


def arm_singular_parts(factor: sp.Expr, kind: str, configuration: Sequence[Any], shown: str) -> tuple[Any, ...]:
    """The caption of the arm at a singular configuration, with the lost direction as a red arrow at the tool.

    ``configuration`` is the sample as caption parts (:func:`~symjac.printing.prose.singularities.sample_parts`, the
    same numbers as the explanation's). ``shown`` says what the arrow is: ``linear`` (a direction the tool point
    cannot move in), ``angular`` (an axis the tool cannot turn about), or ``mixed`` (the translation part of a lost
    twist, lost only with its rotation).
    """
    arrow = {"linear": "the direction the tool point cannot move in",
             "angular": "the axis the tool cannot turn about",
             "mixed": ("the translation part of the lost direction: the arm cannot move this way while turning as "
                       "the lost direction says, though it can move this way alone")}[shown]
    # a redundant arm's set comes as its conditions (an And, or one equation)
    where = (factor,) if isinstance(factor, sp.And | sp.core.relational.Relational) else (factor, " = 0")
    return ("Singular where ", *where, f" ({kind}), ", *configuration, f". The red arrow is {arrow}.")


def point_words(robot: Robot, point: Sequence[sp.Expr]) -> str:
    """The point a report's Jacobian moves: the tool point, the flange (the origin of {n}), or a reference point."""
    if robot.tool is not None:
        return "the tool point"
    return f"the origin of frame {{{robot.n_joints}}} (flange)" if not any(point) else "the reference point"


def forward_kinematics_intro(source: object, target: object) -> str:
    """What the forward kinematics is, above its matrix."""
    return f"The pose of frame {{{target}}} relative to frame {{{source}}}, the product of the link transforms."


def jacobian_intro(point: str) -> str:
    """The Jacobian section's first line (``point`` from :func:`point_words`)."""
    return f"Basic Jacobian [v; \u03c9] (linear velocity first) at {point}."


def jacobian_frame_heading(frame: object) -> str:
    """``Expressed in frame {0}, the base frame``, or the frame where the Jacobian is most compact."""
    words = "the base frame" if frame == 0 else "the frame where it is most compact"
    return f"Expressed in frame {{{frame}}}, {words}"


def methods_verdict(agree: bool) -> str:
    """Whether the four derivation methods gave the same Jacobian."""
    if agree:
        return ("All four methods agree: each gives exactly the same matrix as differentiation, compared entry by "
                "entry as exact SymPy expressions.")
    return "The methods DISAGREE: see the table; this is a bug in symjac, please report it."


def map_caption(measure: str, rows: str, joints: tuple[str, str], fixed: str) -> str:
    """The manipulability map's caption (``measure`` is ``|det J|`` or ``sqrt(det(J J^T))``)."""
    shown = "w = |det J|" if measure == "|det J|" else "w = \u221adet(J J\u1d40)"
    return (f"Manipulability {shown} of the rows {rows} over {joints[0]} and {joints[1]}, the other joints fixed "
            f"({fixed or 'none'}), parameters at their defaults. Singular sets:")


def curve_parts(factor: sp.Expr, kind: str, solutions: Sequence[sp.Basic]) -> tuple[Any, ...]:
    """One singular curve of the map: the factor, and how it is drawn (from its solutions, or as a contour)."""
    if not solutions:
        return ("factor ", factor, f" ({kind}): no solved form in this plane: its exact values on a 601 \u00d7 601 "
                "grid, zero contour (dashed)")
    parts: list[Any] = ["factor ", factor, f" ({kind}): drawn exactly from its solutions "]
    for number, solution in enumerate(solutions):
        parts += [", "] * bool(number) + [solution]
    return tuple(parts)


def set_mark_parts(number: int, conditions: Sequence[sp.Expr], points: bool) -> tuple[Any, ...]:
    """One singular set of a redundant arm on the map: its number and conditions, drawn as lines or points."""
    parts: list[Any] = [f"singular set {number}: "]
    for index, condition in enumerate(conditions):
        parts += [" and "] * bool(index) + [sp.Eq(condition, 0, evaluate=False)]
    shape = "points (crosses)" if points else "lines"
    return (*parts, f", drawn as {shape} at its exact solutions")


def regular_self_motion_parts(t: float, rates: Any, names: Sequence[str]) -> tuple[Any, ...]:
    """The self-motion of a redundant arm at a regular configuration of the path, as caption parts."""
    shown = [f"{float(rate):+.3f} on {name}" for rate, name in zip(rates, names, strict=True) if abs(rate) > 1e-9]
    return (f"At the start of the path (t = {t:.2f}, a regular configuration) the arm keeps one self-motion: joint "
            f"rates {', '.join(shown)} (a unit vector of the null space of J) move nothing. The minimum-norm rates "
            "never use it; a redundancy resolution adds it to reach a secondary goal.",)


def rates_parts(command: str, crossing: sp.Expr | None, square: bool) -> tuple[Any, ...]:
    """The joint-rates figure's caption: the commanded velocity, the factor crossed at t = 0, what the rates do."""
    behaviour = ("The exact rates (solid) grow like 1/|t|; the damped least-squares rates (dashed) stay bounded at "
                 "the price of a tracking error." if square else
                 "The arm is redundant, so J has no inverse: the solid lines are the minimum-norm rates "
                 "J\u207a x\u0307 = J\u1d40 (J J\u1d40)\u207b\u00b9 x\u0307, which grow like 1/|t| at the "
                 "singular set, the dashed ones the damped least-squares rates, which stay bounded.")
    inverse = "J\u207b\u00b9" if square else "J\u207a"
    head = (f"Joint rates q\u0307 = {inverse} x\u0307 for a constant commanded velocity x\u0307 = ({command}) "
            "(the direction lost at the singular configuration), along the straight path of the map")
    middle = () if crossing is None else (
        (" crossing the singular set ", crossing) if isinstance(crossing, sp.And | sp.core.relational.Relational) else
        (" crossing the singular set of the factor ", crossing))
    return (head, *middle, f" at t = 0. {behaviour}")
