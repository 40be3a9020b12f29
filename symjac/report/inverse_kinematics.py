r"""The report's inverse-kinematics section: the family, and every solution at one example pose, tabled and drawn.

Where the arm has no closed form, the section says why, and the numeric solver's solutions follow.

The example pose is the arm's own at :func:`example_configuration` (a generic configuration inside the limits), so
it is reachable and the configuration that made it is among the solutions. The solutions come from
:func:`symjac.solvers.inverse_kinematics.inverse_kinematics` (closed form where the geometry has one, else numeric)
with ``within_limits=False``: every one, each flagged within or outside the joint limits, one row each, then every
branch drawn in one picture (:func:`~symjac.drawing.solutions.draw_solutions`, an inline PNG).
"""

from __future__ import annotations

import base64
import dataclasses
import html
import io

import numpy as np

from symjac.analysis.inverse_kinematics.poses import rpy_from_pose
from symjac.codegen.numeric_model import numeric_model
from symjac.drawing.solutions import draw_solutions, panel_title
from symjac.errors import SymjacError
from symjac.model.robot import Robot
from symjac.printing.inverse_kinematics import solution_words
from symjac.solvers.controlled import coordinate_bounds
from symjac.solvers.inverse_kinematics import InverseKinematicsResult, inverse_kinematics

__all__ = ["DPI", "EXAMPLE_FRACTIONS", "MOST_DRAWN", "example_configuration", "inverse_kinematics_html",
           "solutions_png"]

EXAMPLE_FRACTIONS = (0.55, 0.35, 0.62, 0.45, 0.68, 0.4, 0.58)
"""Where each joint of the example configuration sits between its lower and upper seed bound (then repeating)."""

MOST_DRAWN = 8
"""Solutions drawn at most (the PUMA's eight postures)."""

DPI = 80
"""Resolution of the picture of the branches (four panels a row, 12 inches wide: 960 pixels)."""


def example_configuration(robot: Robot) -> np.ndarray:
    """A generic configuration inside the limits: each joint at a fixed fraction of its range (+-pi when free)."""
    lower, upper = coordinate_bounds(robot)
    fractions = np.resize(np.array(EXAMPLE_FRACTIONS), len(lower))
    return lower + fractions * (upper - lower)  # type: ignore[no-any-return]


def _numbers(values: np.ndarray) -> str:
    return ", ".join(f"{value + 0.0:.4g}" for value in values)  # + 0.0: no "-0"


def _table(robot: Robot, result: InverseKinematicsResult) -> str:
    names = "".join(f"<th>{html.escape(str(name))}</th>" for name in robot.q)
    rows = "".join(
        f"<tr><td>{number}</td>" + "".join(f"<td>{value:.4f}</td>" for value in solution.q)
        + f"<td>{html.escape(solution_words(solution))}</td></tr>"
        for number, solution in enumerate(result.solutions, start=1))
    return (f'<table class="solutions"><thead><tr><th>#</th>{names}<th>branch, limits</th></tr></thead>'
            f"<tbody>{rows}</tbody></table>")


def solutions_png(robot: Robot, result: InverseKinematicsResult) -> bytes:
    """Every solution (up to :data:`MOST_DRAWN`) side by side, titled by branch: one PNG, the same bytes each time."""
    shown = dataclasses.replace(result, solutions=result.solutions[:MOST_DRAWN])
    figure = draw_solutions(robot, shown, title="")
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI, metadata={"Software": None})
    return buffer.getvalue()


def _figure(robot: Robot, result: InverseKinematicsResult) -> str:
    """One picture of every branch, inline as a data URI (nothing fetched; the arm figures above stay SVG)."""
    data = base64.b64encode(solutions_png(robot, result)).decode("ascii")
    words = "; ".join(f"{number}: {panel_title(number, s)}" for number, s in enumerate(result.solutions, start=1))
    return (f'<figure class="ik-solutions"><img src="data:image/png;base64,{data}" alt="{html.escape(words)}" '
            f'style="max-width: 100%; height: auto"><figcaption>{html.escape(words)}</figcaption></figure>')


def inverse_kinematics_html(robot: Robot) -> str:
    """The section's body: method and reasons, what the arm controls, the example pose, the solutions and drawings."""
    q = example_configuration(robot)
    try:
        pose = np.asarray(numeric_model(robot).fk(q), dtype=float)
        result = inverse_kinematics(robot, pose, within_limits=False)
    except SymjacError as error:  # a coupled arm: said in one sentence
        return f'<p class="note">No inverse kinematics: {html.escape(str(error))}.</p>\n'
    if result.method == "closed_form":
        command = f"symjac ik {robot.name} --q {','.join(f'{value:.4g}' for value in q)} --derivation"
        intro = (f"Closed form, family {result.family}: {'; '.join(result.reasons)}. Each step is a subproblem "
                 f"solved with atan2; {command} prints the steps in LaTeX.")
    else:
        reason = result.why.removeprefix("numeric, as there is no closed form: ")
        intro = f"No closed form: {reason}. The numeric solver finds the solutions."
    controlled = f"The arm sets {result.controlled.sets}"
    controlled += f"; it does not set {result.controlled.not_set}." if result.controlled.not_set else "."
    inside = sum(solution.within_limits for solution in result.solutions)
    example = (f"At the example pose (the arm's own at q = ({_numbers(q)}): position ({_numbers(pose[:3, 3])}) m, "
               f"roll, pitch, yaw ({_numbers(rpy_from_pose(pose))}) rad), {len(result.solutions)} solution"
               f"{'s' if len(result.solutions) != 1 else ''}, {inside} of them within the joint limits:")
    parts = [f"<p>{html.escape(intro)}</p>", f"<p>{html.escape(controlled)}</p>", f"<p>{html.escape(example)}</p>"]
    if result.solutions:
        parts += [_table(robot, result), _figure(robot, result)]
    else:
        parts.append(f'<p class="note">{html.escape(result.unreachable)}</p>')
    return "\n".join(parts) + "\n"
