r"""Inverse kinematics: every configuration reaching a pose (``symjac ik``).

The pose is the end of the chain (the tool frame when the robot has one, else frame {n}) in frame {0}, as forward
kinematics from {0} gives it, given on the command line in one of four ways: ``--pose`` (the 4 x 4 matrix, row by
row, or its top 3 x 4), ``--position`` with ``--rpy`` (URDF's roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)) or
with ``--quaternion`` (w, x, y, z, scalar first), or ``--q``: the pose the arm has at that configuration. The
options have the names and defaults of :func:`symjac.inverse_kinematics` (``--method``, ``--seed``, ``--rng``,
``--free-value``, ``--within-limits``); ``--derivation`` prints the closed form's steps instead.

The derivation is :func:`symjac.solvers.inverse_kinematics.inverse_kinematics`, in the solvers stage above this one
(its numeric solver runs on the compiled robot); the handler calls it through the spec's entry point, as code
generation reads every spec's lowering. Coupled robots are refused (the solvers work joint by joint), so the
coupling law is never applied.
"""

from __future__ import annotations

import argparse
import functools
from typing import TYPE_CHECKING, Any

from symjac.errors import ArgumentError, NoClosedFormError, OrientationNeededError
from symjac.quantities.spec import Quantity, Request

if TYPE_CHECKING:
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "ik_options", "requested_pose"]

METHOD_CHOICES = ("auto", "closed_form", "numeric")
"""The values of ``--method`` (those of :data:`symjac.solvers.inverse_kinematics.METHODS`)."""


def ik_options(sub: argparse.ArgumentParser) -> None:
    """``symjac ik``: the pose (one of four ways), the method and the numeric solver's starts."""
    pose = sub.add_argument_group("the pose (one of --pose, --position with --rpy or --quaternion, --q)")
    pose.add_argument("--pose", default=None, metavar="T",
                      help="the 4 x 4 pose row by row, 16 (or the top 12) comma-separated numbers; metres")
    pose.add_argument("--position", default=None, metavar="X,Y,Z", help="the position in metres, with --rpy or "
                      "--quaternion (write --position=-0.1,0,0 when it starts with a minus)")
    pose.add_argument("--rpy", default=None, metavar="ROLL,PITCH,YAW",
                      help="URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll); radians, pi, or 30deg")
    pose.add_argument("--quaternion", default=None, metavar="W,X,Y,Z",
                      help="a unit quaternion, scalar first (as MuJoCo writes it)")
    pose.add_argument("--q", default=None, metavar="Q",
                      help="the pose the arm has at this configuration q1,...,qn (as draw --q reads it)")
    sub.add_argument("--method", choices=METHOD_CHOICES, default="auto",
                     help="closed form where the geometry has one, else numeric (auto, the default); or either")
    sub.add_argument("--seed", default=None, metavar="Q",
                     help="numeric: the first start, a configuration q1,...,qn (then --restarts random ones)")
    sub.add_argument("--rng", type=int, default=0, help="numeric: the seed of the random starts (default 0)")
    sub.add_argument("--restarts", type=int, default=8, help="numeric: random starts (default 8)")
    sub.add_argument("--free-value", default=None, metavar="V",
                     help="a 7-joint arm's closed form: the value of its free joint (radians or metres)")
    sub.add_argument("--free-joint", type=int, default=None, metavar="K",
                     help="with --free-value: which joint is given, 1..n (default: the first leaving a closed form)")
    sub.add_argument("--within-limits", action=argparse.BooleanOptionalAction, default=True,
                     help="keep only solutions within the joint limits (default); --no-within-limits keeps all")
    sub.add_argument("--derivation", action="store_true",
                     help="print the closed form's steps (subproblems, atan2 formulas, existence conditions)")


def _numbers(request: Request, text: str, length: int, option: str) -> list[float]:
    return [float(value) for value in request.values(text, length, option, parameters=False)]


def _angles(request: Request, text: str, option: str) -> list[float]:
    """Three angles: radians, expressions with pi, or ``30deg``."""
    import math

    parts = text.split(",")
    if len(parts) != 3:
        raise ArgumentError(f"{option} needs 3 comma-separated values, got {len(parts)} in {text!r}")
    angles = []
    for part in parts:
        number = part.strip()
        degrees = number.endswith("deg")
        [value] = _numbers(request, number[:-3] if degrees else number.removesuffix("rad"), 1, option)
        angles.append(math.radians(value) if degrees else value)
    return angles


def requested_pose(request: Request) -> Any:
    """The target pose the options give (``--pose``, ``--position`` with ``--rpy`` or ``--quaternion``, or ``--q``).

    Checked, as a 4 x 4 NumPy array; ``--position`` alone gives its three numbers, a target for an arm that sets
    no orientation (:func:`symjac.inverse_kinematics` refuses it for another arm).
    """
    from symjac.analysis.inverse_kinematics.poses import pose_from_matrix, pose_from_quaternion, pose_from_rpy

    args = request.args
    given = [name for name, value in (("--pose", args.pose), ("--position", args.position), ("--q", args.q))
             if value is not None]
    rotation = [name for name, value in (("--rpy", args.rpy), ("--quaternion", args.quaternion)) if value is not None]
    if len(given) != 1:
        raise ArgumentError("ik needs the pose: --pose T, --position X,Y,Z with --rpy or --quaternion, or --q Q"
                            if not given else f"ik takes one pose, got {' and '.join(given)}")
    if given == ["--position"] and len(rotation) > 1:
        raise ArgumentError("--position takes one of --rpy and --quaternion, not both")
    if given != ["--position"] and rotation:
        raise ArgumentError(f"{rotation[0]} goes with --position, not with {given[0]}")
    if args.pose is not None:
        count = len(args.pose.split(","))
        values = _numbers(request, args.pose, count if count in (12, 16) else 16, "--pose")
        return pose_from_matrix([values[4 * k:4 * k + 4] for k in range(len(values) // 4)], name="--pose")
    if args.q is not None:
        from symjac.kinematics.chain import forward_kinematics
        from symjac.kinematics.numeric import numeric_at
        from symjac.model.ends import last_frame

        q = request.configuration(args.q, "--q")
        robot = request.robot
        return pose_from_matrix(numeric_at(robot, forward_kinematics(robot, 0, last_frame(robot)), q), name="--q")
    position = _numbers(request, args.position, 3, "--position")
    if args.rpy is None and args.quaternion is None:
        return position  # a position alone: enough for an arm that sets no orientation (the solver checks)
    if args.rpy is not None:
        return pose_from_rpy(position, _angles(request, args.rpy, "--rpy"), name="--rpy")
    return pose_from_quaternion(position, _numbers(request, args.quaternion, 4, "--quaternion"), name="--quaternion")


def command(request: Request) -> Document:
    """``symjac ik``: the solutions (or with ``--derivation`` the closed form's steps) for the pose the options give."""
    from symjac.printing.inverse_kinematics import inverse_kinematics_document

    args, robot = request.args, request.robot
    if args.numeric:
        raise ArgumentError("--numeric does not apply to ik: the solutions are numbers already (--digits rounds them)")
    if args.free_joint is not None and not 1 <= args.free_joint <= robot.n_joints:
        raise ArgumentError(f"--free-joint is a joint number, 1 to {robot.n_joints} for {robot.name}, got "
                            f"{args.free_joint}")
    if args.derivation:
        return _derivation(request)
    pose = requested_pose(request)
    if args.restarts < 0:
        raise ArgumentError(f"--restarts must be 0 or more, got {args.restarts}")
    if args.free_joint is not None and args.free_value is None:
        raise ArgumentError("--free-joint needs --free-value (the value of that joint)")
    if args.free_value is not None and args.method == "numeric":
        raise ArgumentError("--free-value gives a redundant arm's closed form one joint's value: it does not apply "
                            "with --method numeric")
    if args.free_value is not None and robot.n_joints <= 6:
        raise ArgumentError(f"--free-value gives a redundant arm's closed form one joint's value; {robot.name} has "
                            f"{robot.n_joints} joints")
    options: dict[str, Any] = {"method": args.method, "rng": args.rng, "restarts": args.restarts,
                               "within_limits": args.within_limits}
    if args.seed is not None:
        options["seed"] = [float(v) for v in request.configuration(args.seed, "--seed")]
    if args.free_value is not None:
        [value] = _numbers(request, args.free_value, 1, "--free-value")
        options["free_value"] = value
        options["free_joint"] = args.free_joint
    try:
        result = request.progress(f"inverse kinematics of {robot.name}",
                                  lambda: QUANTITY.derive(robot, pose, **options))
    except OrientationNeededError:
        raise ArgumentError(f"--position alone is a target for an arm that sets no orientation; {robot.name} sets "
                            "its orientation too: add --rpy or --quaternion") from None
    except ArgumentError as error:  # a free value where no joint given leaves a closed form: say it in options
        if not isinstance(error.__cause__, NoClosedFormError):
            raise
        given = f" with --free-joint {args.free_joint}" if args.free_joint is not None else ""
        reason = str(error.__cause__)
        raise ArgumentError(f"--free-value gives a redundant arm's closed form one joint's value, and {robot.name}"
                            f"{given} has none: {reason}{_numeric_hint(reason, 'without --free-value, --method auto')}"
                            ) from None
    except NoClosedFormError as error:  # the analysis's reason (Python's hint names keywords), then these options
        cause = error.__cause__ if isinstance(error.__cause__, NoClosedFormError) else error
        raise NoClosedFormError(reason=f"{cause}{_redundant_hint(robot, args, str(cause))}") from None
    return inverse_kinematics_document(robot, result, args.digits)  # numbers always: --digits needs no --numeric


def _redundant_hint(robot: Any, args: argparse.Namespace, reason: str) -> str:
    """After the analysis's reason why there is no closed form: the options that give one, or the numeric solver."""
    from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan

    if robot.n_joints > 6 and args.free_value is None:
        for joint in range(1, robot.n_joints + 1):
            try:
                closed_form_plan(robot, free_joint=joint)
            except NoClosedFormError:
                continue
            return (f"; a redundant arm's closed form takes one joint's value: --free-value V (joint {joint}'s, "
                    "or --free-joint K for joint K)")
    if args.method != "closed_form":
        return ""
    how = f"{'without --free-value, ' if args.free_value is not None else ''}--method auto or numeric"
    return _numeric_hint(reason, how)


def _numeric_hint(reason: str, how: str) -> str:
    """After why there is no closed form: how to solve numerically, ``how`` in the command line's options."""
    return f" ({how})" if reason.endswith("use the numeric solver") else f"; the numeric solver solves it: {how}"


def _derivation(request: Request) -> Document:
    """``--derivation``: the closed form's steps, which hold for every pose (a pose given is checked, not needed).

    A redundant arm takes ``--free-joint K`` (the closed form with joint K given); without it, the first joint whose
    value leaves a closed form, as :func:`symjac.inverse_kinematics` chooses it.
    """
    from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan
    from symjac.printing.ik_derivation import ik_derivation_document

    args, robot = request.args, request.robot
    if args.method == "numeric":
        raise ArgumentError("--derivation prints a closed form: it does not apply with --method numeric")
    if any(value is not None for value in (args.pose, args.position, args.q, args.rpy, args.quaternion)):
        requested_pose(request)  # checked, so a mistake in it is not silently ignored
    choices: list[int | None] = [args.free_joint]
    if args.free_joint is None and robot.n_joints > 6:
        choices += list(range(1, robot.n_joints + 1))
    first: NoClosedFormError | None = None
    for joint in choices:
        try:
            plan = request.progress(f"closed form of {robot.name}", functools.partial(closed_form_plan, robot,
                                                                                       free_joint=joint))
        except NoClosedFormError as error:
            first = first or error
            continue
        return ik_derivation_document(plan)
    assert first is not None
    hint = "" if args.free_joint is not None or robot.n_joints <= 6 else "; no joint, its value given, leaves one"
    raise NoClosedFormError(reason=f"{first}{hint}") from None


QUANTITY = Quantity(
    name="inverse_kinematics",
    summary="solve the inverse kinematics: every configuration that reaches a pose",
    derivation="symjac.solvers.inverse_kinematics:inverse_kinematics",
    coupling="rates",  # never applied: coupled robots are refused
    document="symjac.printing.inverse_kinematics:inverse_kinematics_document",
    command="ik",
    options=ik_options,
    handler=command,
)
