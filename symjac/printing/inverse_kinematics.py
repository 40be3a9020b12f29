r"""The solutions of inverse kinematics as a document (``symjac ik``): the pose, a table of solutions, their notes.

The document reads an :class:`~symjac.solvers.inverse_kinematics.InverseKinematicsResult` by its fields (it sits
below the solvers, so it names no solver type): ``robot``, ``pose``, ``method``, ``why``, ``family``, ``reasons``,
``solutions`` (each ``q``, ``branch``, ``within_limits``, ``singular``, ``position_error``, ``orientation_error``),
``outside_limits``, ``unreachable``, ``distance``, ``uncontrolled`` and ``controlled`` (``sets``, ``not_set``), and
``continuum_dimension`` when it has one (the numeric solver's samples of a continuum are called samples), and
``position_alone`` (the target was a position alone: the rotation in the pose is a stand-in).

LaTeX and pretty text print the target pose :math:`T`, then the solutions as one matrix :math:`Q`, one row per
solution and one column per joint, then a line per row (its branch, limits, singular note, and the error of its
forward kinematics); JSON gives the same as data (``solutions[k].q`` and so on) for programs.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import sympy as sp

from symjac.model.robot import Robot
from symjac.printing.document import Block, Document, Equation, Inline
from symjac.printing.latex import DIGITS, latex, rounded

__all__ = ["inverse_kinematics_data", "inverse_kinematics_document", "solution_words"]

SMALL = 1e-12
"""Entries below this in magnitude print as 0 (rounding noise of a rotation, not a value)."""


def _matrix(values: Any, digits: int) -> sp.Matrix:
    array = np.where(np.abs(np.asarray(values, dtype=float)) < SMALL, 0.0, np.asarray(values, dtype=float))
    return rounded(sp.Matrix(array.tolist()), digits)  # type: ignore[no-any-return]


def solution_words(solution: Any) -> str:
    """One solution's notes: branch, joint limits, singular continuum (``"elbow up, wrist flip; within limits"``)."""
    parts = [", ".join(solution.branch)] if solution.branch else []
    parts.append("within the joint limits" if solution.within_limits else "outside the joint limits")
    if solution.singular:
        parts.append(f"singular: {solution.singular}")
    return "; ".join(parts)


def _method_words(result: Any) -> str:
    count = len(result.solutions)
    found = f"{count} solution{'s' if count != 1 else ''}"
    samples = sum(bool(getattr(s, "continuum_dimension", 0)) for s in result.solutions)
    if samples:  # not a count: samples of a continuum, as many as the numeric solver's starts found
        sets = f"a {result.continuum_dimension}-dimensional set of solutions (they are not isolated)"
        found = (f"{count} samples of {sets}" if samples == count
                 else f"{found}, {samples} of them samples of {sets}")
    how = f"in closed form ({result.family})" if result.method == "closed_form" else "by the numeric solver"
    return f"Inverse kinematics of {result.robot}: {found} {how}."


def _notes(result: Any) -> list[str]:
    notes = [f"Why: {'; '.join(result.reasons) if result.method == 'closed_form' else result.why}."]
    if result.controlled.not_set:
        notes.append(f"The arm sets {result.controlled.sets}; it does not set {result.controlled.not_set}.")
    if getattr(result, "position_alone", False):
        notes.append("Only a position was given: the rotation in T is the identity, standing in for the orientation "
                     "the arm does not set.")
    if result.uncontrolled:
        notes.append(f"Not set: {result.uncontrolled}.")
    if result.outside_limits:
        notes.append(f"{result.outside_limits} more solution{'s' if result.outside_limits != 1 else ''} leave the "
                     "joint limits (shown with --no-within-limits).")
    if result.unreachable:  # the sentence says how far out, once (the JSON gives ``distance`` as a number)
        notes.append(f"No solution: {result.unreachable}.")
    return notes


def inverse_kinematics_document(robot: Robot, result: Any, digits: int | None = None) -> Document:
    """The pose, the table of solutions (one row each, one column per joint) and each row's notes."""
    digits = digits or DIGITS
    names = [sp.Symbol(str(symbol)) for symbol in robot.q]
    columns = ", ".join(latex(name) for name in names)
    blocks = [Block((_method_words(result), " ", " ".join(_notes(result)), " The target pose, frame {0} to the end "
                     "of the chain:"), (Equation("T", "T", _matrix(result.pose, digits)),))]
    if result.solutions:
        table = _matrix([s.q for s in result.solutions], digits)
        blocks.append(Block(("One row per solution; columns ", Inline(columns, ", ".join(map(str, names))),
                             " (radians, metres):"), (Equation("Q", "Q", table),)))
        for number, solution in enumerate(result.solutions, start=1):
            error = f"the pose by {solution.position_error:.1e} m, {solution.orientation_error:.1e} rad"
            if result.controlled.position_only:
                error = f"the position by {solution.position_error:.1e} m"
            blocks.append(Block((f"Row {number}: {solution_words(solution)}; forward kinematics misses {error}.",)))
    return Document("Inverse kinematics", robot.name, tuple(blocks), data=lambda: inverse_kinematics_data(result),
                    comments=True, model=robot)


def inverse_kinematics_data(result: Any) -> dict[str, Any]:
    """The result as JSON-ready data: the pose, method and reasons, and every solution with its notes."""
    distance = result.distance if math.isfinite(result.distance) else None
    return {
        "robot": result.robot,
        "pose": np.asarray(result.pose, dtype=float).tolist(),
        "method": result.method,
        "why": result.why,
        "family": result.family,
        "reasons": list(result.reasons),
        "controlled": result.controlled.sets,
        "not_controlled": result.controlled.not_set,
        "uncontrolled": result.uncontrolled,
        "solutions": [{"q": np.asarray(s.q, dtype=float).tolist(), "branch": list(s.branch),
                       "within_limits": bool(s.within_limits), "singular": s.singular,
                       "position_error": s.position_error, "orientation_error": s.orientation_error}
                      for s in result.solutions],
        "outside_limits": result.outside_limits,
        "unreachable": result.unreachable,
        "distance": distance,
        "continuum_dimension": getattr(result, "continuum_dimension", 0),
        "position_alone": bool(getattr(result, "position_alone", False)),
    }
