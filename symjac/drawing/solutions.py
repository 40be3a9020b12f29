r"""The branches of an inverse-kinematics solution drawn side by side: :func:`draw_solutions`.

Each solution is one panel of :func:`~symjac.drawing.figure.draw` (the same artists and ids, panel k's prefixed
``panelk-``), titled by its branch ("elbow up, wrist flip") or, from the numeric solver, its number; a solution
outside the joint limits says so in its title. The target pose is drawn as a small triad at its origin in every
panel (world coordinates, as the arm is drawn; ids ``target-x``, ``target-y``, ``target-z``), so the picture shows
each arm reaching it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from symjac.drawing.figure import AXIS_COLOURS, DEFAULT_VIEW, draw
from symjac.drawing.geometry import arm_pose
from symjac.errors import ArgumentError
from symjac.model.robot import Robot

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_solutions", "panel_title"]

PANEL_SIZE = (3.0, 3.2)
"""Inches per panel."""


def panel_title(number: int, solution: Any) -> str:
    """A panel's title: its branch (or ``solution k``), and ``outside limits`` when it is."""
    title = ", ".join(solution.branch) if solution.branch else f"solution {number}"
    return title if solution.within_limits else f"{title} (outside limits)"


def draw_solutions(robot: Robot, result: Any, *, view: tuple[float, float] = DEFAULT_VIEW,
                   frames: bool | None = False, limits: bool = False, title: str | None = None) -> Figure:
    """Every solution of an inverse-kinematics result side by side, titled by branch, with the target's triad.

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
    configurations = np.array([np.asarray(s.q, dtype=float) for s in solutions])
    size = (PANEL_SIZE[0] * len(solutions), PANEL_SIZE[1])
    figure = draw(robot, configurations, view=view, frames=frames, limits=limits, size=size,
                  title=title if title is not None else f"{robot.name}: {len(solutions)} solutions")
    pose = arm_pose(robot, configurations[0]).frames[1] @ np.asarray(result.pose, dtype=float)  # {0} -> world
    origin = pose[:3, 3]
    for number, (axes, solution) in enumerate(zip(figure.axes, solutions, strict=True), start=1):
        axes.set_title(panel_title(number, solution), fontsize=9)
        length = 0.1 * max(float(np.ptp(np.asarray(axes.get_xlim()))), 1e-3)
        for k, colour in enumerate(AXIS_COLOURS):
            tip = origin + length * pose[:3, k]
            (line,) = axes.plot(*zip(origin, tip, strict=True), color=colour, linewidth=2.5, alpha=0.6)
            line.set_gid(f"panel{number}-target-{'xyz'[k]}" if len(solutions) > 1 else f"target-{'xyz'[k]}")
    return figure
