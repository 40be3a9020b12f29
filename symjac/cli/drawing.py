"""``symjac draw``: the arm as an image, or as a movie along a joint path (matplotlib is imported only here)."""

from __future__ import annotations

import argparse

from symjac.cli.args import load, parse_configuration
from symjac.errors import ArgumentError

__all__ = ["draw_command"]


def draw_command(args: argparse.Namespace) -> str:
    """``draw``: the arm as SVG, PNG or PDF, or along a path as GIF or MP4 (matplotlib imported only here)."""
    from pathlib import Path

    from symjac.drawing.animation import (
        ANIMATION_SUFFIXES,
        IMAGE_SUFFIXES,
        animate,
        figure_bytes,
        joint_path,
        movie_bytes,
    )
    from symjac.drawing.figure import DEFAULT_VIEW, draw
    from symjac.files import write_bytes

    if args.output in (None, "-"):
        raise ArgumentError("draw writes a file: give -o FILE with a suffix of "
                            f"{', '.join(IMAGE_SUFFIXES + ANIMATION_SUFFIXES)}")
    suffix = Path(args.output).suffix.lower()
    if suffix not in IMAGE_SUFFIXES + ANIMATION_SUFFIXES:
        raise ArgumentError(f"-o {args.output}: unknown suffix {suffix or '(none)'}; use "
                            f"{', '.join(IMAGE_SUFFIXES)}, or {' or '.join(ANIMATION_SUFFIXES)} with --path")
    if args.path != (suffix in ANIMATION_SUFFIXES):
        raise ArgumentError("--path needs -o FILE.gif or FILE.mp4" if args.path
                            else f"a {suffix} file animates a path: give --path and two or more --q")
    for option, value in (("--path-steps", args.path_steps), ("--fps", args.fps)):
        if value < 1:
            raise ArgumentError(f"{option} must be at least 1, got {value}")
    robot = load(args)
    configurations = [parse_configuration(text, robot) for text in args.q or []] or None
    view = DEFAULT_VIEW if args.view is None else _view(args.view)
    options = {"frames": args.frames, "ellipsoids": args.ellipsoid or (), "limits": args.limits, "view": view}
    if args.path:
        if configurations is None or len(configurations) < 2:
            raise ArgumentError("--path needs two or more --q waypoints")
        motion = animate(robot, joint_path(configurations, args.path_steps), fps=args.fps, **options)
        data = movie_bytes(motion, suffix, args.fps)
    else:
        figure = draw(robot, configurations, **options)
        data = figure_bytes(figure, suffix)
    write_bytes(args.output, data)
    args.output = None  # written: nothing left for stdout
    return ""


def _view(text: str) -> tuple[float, float]:
    parts = text.split(",")
    try:
        azimuth, elevation = (float(part) for part in parts)
    except ValueError:
        raise ArgumentError(f"--view must be two numbers AZIMUTH,ELEVATION in degrees, got {text!r}") from None
    return azimuth, elevation
