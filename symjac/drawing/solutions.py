r"""The branches of an inverse-kinematics solution drawn side by side: :func:`draw_solutions`.

Each solution is one panel drawn as :func:`~symjac.drawing.figure.draw` draws the arm (the same artists and ids,
panel k's prefixed ``panelk-``), four to a row, titled by its branch ("elbow up, wrist flip") or, from the numeric
solver, its number; a solution outside the joint limits says so in its title. The target pose is drawn as a small
triad at its origin in every panel (world coordinates, as the arm is drawn; ids ``target-x``, ``target-y``,
``target-z``), so the picture shows each arm reaching it.
"""

from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING, Any

import numpy as np

from symjac.drawing.figure import (
    AXIS_COLOURS,
    DEFAULT_VIEW,
    ArmDrawing,
    equal_axes,
    matplotlib_figure,
    view_angles,
)
from symjac.drawing.geometry import arm_pose
from symjac.errors import ArgumentError
from symjac.model.robot import Robot

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_solutions", "panel_title"]

PANEL_SIZE = (3.0, 3.2)
"""Inches per panel."""

PER_ROW = 4
"""Panels in a row at most (the PUMA's eight postures: two rows)."""


def panel_title(number: int, solution: Any) -> str:
    """A panel's title: its branch (or ``solution k``), and ``outside limits`` when it is."""
    title = ", ".join(solution.branch) if solution.branch else f"solution {number}"
    return title if solution.within_limits else f"{title} (outside limits)"


def draw_solutions(robot: Robot, result: Any, *, view: tuple[float, float] = DEFAULT_VIEW,
                   frames: bool | None = False, limits: bool = False, title: str | None = None) -> Figure:
    """Every solution of an inverse-kinematics result side by side, titled by branch, with the target's triad.

    Up to :data:`PER_ROW` panels a row, all at one scale (the first solution's reach).

    Parameters
    ----------
    robot : Robot
    result : InverseKinematicsResult
        Read by its fields ``solutions`` (each ``q``, ``branch``, ``within_limits``) and ``pose``.
    view, frames, limits, title
        As for :func:`~symjac.drawing.figure.draw` (frames default off: eight arms with every triad hide each other).
    """
    solutions = list(result.solutions)
    if not solutions:
        raise ArgumentError(f"{robot.name}: no solution to draw ({result.unreachable or 'none found'})")
    count = len(solutions)
    rows, columns = -(-count // PER_ROW), min(count, PER_ROW)
    figure = matplotlib_figure(figsize=(PANEL_SIZE[0] * columns, PANEL_SIZE[1] * rows), layout="constrained")
    azimuth, elevation = view_angles(view)
    pose = arm_pose(robot, solutions[0].q).frames[1] @ np.asarray(result.pose, dtype=float)  # {0} -> world
    drawings: list[ArmDrawing] = []
    for number, solution in enumerate(solutions, start=1):
        axes = figure.add_subplot(rows, columns, number, projection="3d")
        prefix = f"panel{number}-" if count > 1 else ""
        drawing = ArmDrawing(axes, robot, frames=frames, limits=limits,
                             reach=drawings[0].reach if drawings else None, prefix=prefix)
        drawing.update(np.asarray(solution.q, dtype=float))
        axes.view_init(elev=elevation, azim=azimuth)
        axes.set_title(textwrap.fill(panel_title(number, solution), 28), fontsize=8)
        drawings.append(drawing)
    reach = drawings[0].reach or 1.0
    everything = np.concatenate([d.points() for d in drawings])
    for number, drawing in enumerate(drawings, start=1):
        equal_axes(drawing.axes, everything, 0.1 * reach)
        prefix = f"panel{number}-" if count > 1 else ""
        for k, colour in enumerate(AXIS_COLOURS):
            ends = np.array([pose[:3, 3], pose[:3, 3] + 0.15 * reach * pose[:3, k]])
            (line,) = drawing.axes.plot(*ends.T, color=colour, linewidth=2.5, alpha=0.6)
            line.set_gid(f"{prefix}target-{'xyz'[k]}")
    figure.suptitle(title if title is not None else f"{robot.name}: {count} solution{'s' if count != 1 else ''}")
    return figure
