"""The report's pictures as inline SVG (matplotlib, imported only here and only when a report is made).

Output is byte-stable: a fixed ``svg.hashsalt`` per figure (so the two figures' element ids differ), no date or
creator metadata, text as paths (no fonts needed to view it), the heat map as an inline PNG.
"""

from __future__ import annotations

import io
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from symjac.analysis.manipulability_map import ManipulabilityMap, SingularPath
from symjac.errors import SymjacError
from symjac.model.robot import Robot

__all__ = ["CURVE_COLOURS", "arm_svg", "map_svg", "rates_svg"]

CURVE_COLOURS = ("#e41a1c", "#ff7f00", "#f781bf", "#a65628", "#ffff33", "#4daf4a")
"""Colours of the singular factors' curves, in the order of the factors (the captions name them)."""

_JOINT_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f")


def _matplotlib() -> Any:
    try:
        import matplotlib  # heavy and optional: only a report needs it
        from matplotlib.figure import Figure
    except ImportError:
        raise SymjacError("the report's pictures need matplotlib: pip install 'symjac[report]'") from None
    return matplotlib, Figure


def _svg(figure: Any, salt: str) -> str:
    matplotlib, _ = _matplotlib()
    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.hashsalt": salt, "svg.fonttype": "path", "svg.image_inline": True}):
        figure.savefig(buffer, format="svg", metadata={"Date": None, "Creator": None, "Format": None, "Type": None})
    text = buffer.getvalue()
    return text[text.index("<svg"):].strip() + "\n"


def arm_svg(robot: Robot, q: Sequence[float], name: str, arrow: Sequence[float] | None = None) -> str:
    """The arm at ``q`` (with ``arrow`` at the tool, world coordinates) as SVG; ``name`` keeps its ids apart."""
    _matplotlib()
    from symjac.drawing.figure import draw

    figure = draw(robot, q, arrow=arrow, title="", size=(3.9, 3.7), prefix=f"{name}-")
    return _svg(figure, f"symjac-{name}")


def map_svg(plane: ManipulabilityMap, names: tuple[str, str], path: SingularPath | None = None) -> str:
    """The manipulability heat map with the singular curves (one colour per factor, then per set) and the path."""
    _, Figure = _matplotlib()
    figure = Figure(figsize=(6.4, 5.0), layout="constrained")
    axes = figure.add_subplot()
    extent = (plane.x[0], plane.x[-1], plane.y[0], plane.y[-1])
    image = axes.imshow(plane.w, origin="lower", extent=extent, aspect="auto", cmap="viridis", interpolation="nearest")
    figure.colorbar(image, ax=axes, label=plane.measure.replace("sqrt", "√"))
    for number, curve in enumerate(plane.curves):
        colour = CURVE_COLOURS[number % len(CURVE_COLOURS)]
        if curve.points is not None:
            axes.plot(*curve.points, color=colour, linewidth=1.8)
        elif curve.values is not None:
            X, Y = np.meshgrid(np.linspace(*extent[:2], curve.values.shape[1]),
                               np.linspace(*extent[2:], curve.values.shape[0]))
            axes.contour(X, Y, curve.values, levels=[0.0], colors=[colour], linewidths=1.8, linestyles="dashed")
    for number, mark in enumerate(plane.sets):
        colour = CURVE_COLOURS[(len(plane.curves) + number) % len(CURVE_COLOURS)]
        for x in mark.vertical:
            axes.axvline(x, color=colour, linewidth=1.8)
        for y in mark.horizontal:
            axes.axhline(y, color=colour, linewidth=1.8)
        if mark.points:
            axes.plot(*np.array(mark.points).T, linestyle="none", marker="X", markersize=9, color=colour,
                      markeredgecolor="white")
    if path is not None:
        xy = path.configurations[:, list(plane.joints)]
        axes.plot(xy[:, 0], xy[:, 1], color="white", linewidth=2.2, linestyle=(0, (4, 2)))
        axes.plot(xy[len(xy) // 2, 0], xy[len(xy) // 2, 1], marker="o", color="white", markersize=5)
    axes.set_xlim(*extent[:2])
    axes.set_ylim(*extent[2:])
    axes.set_xlabel(f"{names[0]} (rad)")
    axes.set_ylabel(f"{names[1]} (rad)")
    if all(math.isclose(abs(v), math.pi) for v in extent):
        ticks = [-math.pi, -math.pi / 2, 0.0, math.pi / 2, math.pi]
        labels = ["\u2212\u03c0", "\u2212\u03c0/2", "0", "\u03c0/2", "\u03c0"]  # minus signs, as matplotlib
        axes.set_xticks(ticks, labels)
        axes.set_yticks(ticks, labels)
    return _svg(figure, "symjac-map")


def rates_svg(path: SingularPath, names: list[str]) -> str:
    """Exact (solid) and damped least-squares (dashed) joint rates along the path, log scale, as SVG."""
    _, Figure = _matplotlib()
    figure = Figure(figsize=(6.4, 4.2), layout="constrained")
    axes = figure.add_subplot()
    for joint, name in enumerate(names):
        colour = _JOINT_COLOURS[joint % len(_JOINT_COLOURS)]
        exact = np.abs(path.rates.exact[:, joint])
        damped = np.abs(path.rates.damped[:, joint])
        shown = np.any(exact > 1e-12)
        if shown:
            axes.plot(path.t, np.where(exact > 1e-12, exact, np.nan), color=colour, linewidth=1.6, label=name)
        if np.any(damped > 1e-12):
            axes.plot(path.t, np.where(damped > 1e-12, damped, np.nan), color=colour, linewidth=1.0,
                      linestyle="dashed", label=None if shown else name)
    axes.axvline(0.0, color="black", linewidth=0.8, linestyle="dotted")
    axes.set_yscale("log")
    axes.set_xlabel("path parameter t (rad from the singular configuration)")
    axes.set_ylabel("|joint rate| for a unit command")
    exact = bool(np.any(np.isfinite(path.rates.exact)))
    axes.legend(loc="upper right", fontsize="small", ncols=2, title_fontsize="small",
                title="exact (solid), damped (dashed)" if exact else "damped least squares")
    return _svg(figure, "symjac-rates")
