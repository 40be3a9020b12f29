"""``symjac draw``: the arm as an image, or as a movie along a joint path (matplotlib is imported only here)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from symjac.cli.args import load, parse_configuration, parse_values
from symjac.cli.output import progress
from symjac.errors import ArgumentError, OrientationNeededError

if TYPE_CHECKING:
    from symjac.model.robot import Robot

__all__ = ["draw_command", "ik_pose"]


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
    if args.ik_pose is not None:
        data = _solutions_figure(args, robot, suffix, view)
    elif args.path:
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


def _solutions_figure(args: argparse.Namespace, robot: Robot, suffix: str, view: tuple[float, float]) -> bytes:
    """``--ik-pose``: every solution reaching the pose, one panel each (:func:`.solutions.draw_solutions`)."""
    from symjac.drawing.animation import figure_bytes
    from symjac.drawing.solutions import draw_solutions
    from symjac.solvers.inverse_kinematics import inverse_kinematics

    refused = [option for option, given in (("--q", args.q), ("--path", args.path), ("--ellipsoid", args.ellipsoid))
               if given]
    if refused:
        raise ArgumentError(f"--ik-pose draws the solutions it finds: {' and '.join(refused)} does not apply")
    pose = ik_pose(args.ik_pose, robot)
    try:
        result = progress(f"inverse kinematics of {robot.name}",
                          lambda: inverse_kinematics(robot, pose, within_limits=args.within_limits))
    except OrientationNeededError:
        raise ArgumentError(f"--ik-pose x,y,z is a target for an arm that sets no orientation; {robot.name} sets "
                            "its orientation too: give 6, 7, 12 or 16 numbers") from None
    hidden = result.outside_limits
    if hidden and not result.solutions:
        raise ArgumentError(f"{robot.name}: all {hidden} solutions leave the joint limits (--no-within-limits "
                            "draws them)")
    title = None
    if hidden:
        count = len(result.solutions)
        title = (f"{robot.name}: {count} solution{'s' if count != 1 else ''} within the joint limits, {hidden} more "
                 "outside (--no-within-limits draws them)")
    figure = draw_solutions(robot, result, view=view, frames=args.frames or False, limits=args.limits, title=title)
    return figure_bytes(figure, suffix)  # type: ignore[no-any-return]


def ik_pose(text: str, robot: Robot) -> Any:
    """``--ik-pose``: 6 numbers (position, URDF rpy), 7 (position, quaternion w first), 12 or 16 (the matrix), or 3.

    Three numbers are a position alone, for an arm that sets no orientation (the solver refuses it for another).
    """
    from symjac.analysis.inverse_kinematics.poses import pose_from_matrix, pose_from_quaternion, pose_from_rpy

    count = len(text.split(","))
    if count not in (3, 6, 7, 12, 16):
        raise ArgumentError(f"--ik-pose takes 6 numbers (x,y,z,roll,pitch,yaw), 7 (x,y,z,w,qx,qy,qz), 12 or 16 "
                            f"(the matrix row by row), or 3 (x,y,z), got {count} in {text!r}")
    values = [float(value) for value in parse_values(text, count, "--ik-pose", robot, parameters=False)]
    if count == 3:
        return values
    if count == 6:
        return pose_from_rpy(values[:3], values[3:], name="--ik-pose")
    if count == 7:
        return pose_from_quaternion(values[:3], values[3:], name="--ik-pose")
    return pose_from_matrix([values[k:k + 4] for k in range(0, count, 4)], name="--ik-pose")


def _view(text: str) -> tuple[float, float]:
    parts = text.split(",")
    try:
        azimuth, elevation = (float(part) for part in parts)
    except ValueError:
        raise ArgumentError(f"--view must be two numbers AZIMUTH,ELEVATION in degrees, got {text!r}") from None
    return azimuth, elevation
