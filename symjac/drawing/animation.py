"""The arm moving along a joint path, and figures written to files: :func:`animate`, :func:`figure_bytes`.

An animation is matplotlib's :class:`~matplotlib.animation.FuncAnimation` over one :class:`ArmDrawing` whose
artists are moved in place, frame by frame. Files are made in memory (or in a private temporary folder for an
animation) and handed back as bytes, so the caller writes them whole or not at all.
"""

from __future__ import annotations

import io
import itertools
import numbers
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from symjac.drawing.figure import DEFAULT_VIEW, ArmDrawing, equal_axes, matplotlib_figure, view_angles
from symjac.drawing.geometry import EllipsoidKind, arm_pose, configuration, ellipsoid
from symjac.errors import ArgumentError, SymjacError
from symjac.kinematics.chain import Chain, as_chain
from symjac.model.robot import Robot

__all__ = ["ANIMATION_SUFFIXES", "IMAGE_SUFFIXES", "animate", "figure_bytes", "joint_path", "movie_bytes"]

IMAGE_SUFFIXES = (".svg", ".png", ".pdf")
ANIMATION_SUFFIXES = (".gif", ".mp4")


def joint_path(waypoints: Sequence[Sequence[float]] | np.ndarray, steps: int = 30) -> np.ndarray:
    """Straight lines in joint space through ``waypoints``, ``steps`` configurations per segment (ends included once).

    Examples
    --------
    >>> joint_path([[0.0, 0.0], [1.0, 2.0]], steps=2).tolist()
    [[0.0, 0.0], [0.5, 1.0], [1.0, 2.0]]
    """
    points = _rows(waypoints, "waypoints", 2)
    steps = _positive_integer(steps, "steps")
    t = np.linspace(0.0, 1.0, steps + 1)[:-1, None]
    segments = [a + t * (b - a) for a, b in itertools.pairwise(points)]
    return np.concatenate([*segments, points[-1:]])


def _rows(values: object, name: str, least: int) -> np.ndarray:
    """``values`` as a 2-D float array of at least ``least`` finite rows (configurations), or a clear error."""
    try:
        rows = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError(f"{name} must be configurations (rows of numbers), got {values!r}") from None
    if rows.ndim != 2 or len(rows) < least:
        raise ArgumentError(f"{name} needs at least {least} configuration(s) as rows, got shape {rows.shape}")
    if not np.all(np.isfinite(rows)):
        raise ArgumentError(f"{name} must be finite")
    return rows


def _positive_integer(value: object, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or int(value) < 1:
        raise ArgumentError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def animate(robot: Robot | Chain, path: Sequence[Sequence[float]] | np.ndarray, *, fps: int = 20,
            frames: bool | None = None, ellipsoids: Sequence[EllipsoidKind] | EllipsoidKind = (),
            limits: bool = False,
            view: tuple[float, float] = DEFAULT_VIEW) -> Any:
    """The arm following ``path`` (configurations as rows), as a :class:`matplotlib.animation.FuncAnimation`.

    The options are those of :func:`~symjac.drawing.figure.draw`. The axes hold every configuration of the path, so
    the camera stays still. Save it with :func:`movie_bytes` (or matplotlib's own ``save``).
    """
    chain = as_chain(robot)
    rows = _rows(path, "path", 1)
    configurations = [configuration(chain, row) for row in rows]
    fps = _positive_integer(fps, "fps")
    figure = matplotlib_figure(figsize=(5.6, 5.2), layout="constrained")  # says so when matplotlib is missing
    from matplotlib.animation import FuncAnimation

    azimuth, elevation = view_angles(view)
    axes = figure.add_subplot(projection="3d")
    drawing = ArmDrawing(axes, chain, frames=frames, ellipsoids=ellipsoids, limits=limits)
    drawing.update(configurations[0])
    reach = drawing.reach or 1.0
    points = [drawing.points()]
    for values in configurations:  # the camera holds the whole motion, ellipsoids included
        pose = arm_pose(chain, values)
        points.append(pose.origins)
        for kind in drawing.ellipsoids:
            shape = ellipsoid(pose, kind)
            drawn = drawing.scales[kind] * shape.axes
            points += [shape.centre + drawn, shape.centre - drawn]
    equal_axes(axes, np.concatenate(points), 0.15 * reach)
    axes.view_init(elev=elevation, azim=azimuth)
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_zlabel("z (m)")
    figure.suptitle(chain.robot.name)

    def step(index: int) -> list[Any]:
        drawing.update(configurations[index])
        return []

    return FuncAnimation(figure, step, frames=len(configurations), interval=1000 / fps, blit=False, repeat=False)


def figure_bytes(figure: Any, suffix: str) -> bytes:
    """The figure as an SVG, PNG or PDF file's bytes (the same input gives the same bytes: no dates, fixed ids)."""
    if suffix not in IMAGE_SUFFIXES:
        raise ArgumentError(f"cannot write a figure as {suffix or 'a file without suffix'}: use "
                            f"{', '.join(IMAGE_SUFFIXES)} (or {', '.join(ANIMATION_SUFFIXES)} with a path)")
    import matplotlib

    buffer = io.BytesIO()
    metadata: dict[str, Any] = {"svg": {"Date": None, "Creator": None}, "png": {"Software": None},
                                "pdf": {"CreationDate": None, "ModDate": None, "Producer": None,
                                        "Creator": None}}[suffix[1:]]
    with matplotlib.rc_context({"svg.hashsalt": "symjac-arm", "svg.fonttype": "path"}):
        figure.savefig(buffer, format=suffix[1:], dpi=110, metadata=metadata)
    return buffer.getvalue()


def movie_bytes(animation: Any, suffix: str, fps: int = 20) -> bytes:
    """The animation as a GIF (Pillow, which matplotlib needs anyway) or an MP4 (ffmpeg) file's bytes."""
    from matplotlib import animation as writers

    if suffix not in ANIMATION_SUFFIXES:
        raise ArgumentError(f"cannot write an animation as {suffix or 'a file without suffix'}: use "
                            f"{' or '.join(ANIMATION_SUFFIXES)}")
    if suffix == ".mp4" and not writers.writers.is_available("ffmpeg"):
        raise SymjacError("writing .mp4 needs ffmpeg on the PATH (Debian: apt-get install ffmpeg); .gif needs nothing")
    writer = writers.PillowWriter(fps=fps) if suffix == ".gif" else writers.FFMpegWriter(fps=fps)
    with tempfile.TemporaryDirectory(prefix="symjac-") as folder:
        path = Path(folder) / f"arm{suffix}"
        animation.save(path, writer=writer, dpi=80)
        return path.read_bytes()
