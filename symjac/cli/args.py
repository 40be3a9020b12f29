"""Command-line text -> API arguments: the robot and its URDF chain, frames, points, rows, values.

Every function raises a :class:`~symjac.errors.SymjacError` whose message names the option, so the command line
can print it as one line. Building the parser imports nothing heavy (``symjac --version`` does not load SymPy): the
parsers import what they use when they are called.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from typing import TYPE_CHECKING

from symjac.errors import ArgumentError, ExpressionError, FrameError, RobotFileError
from symjac.quantities.options import LazyChoices

if TYPE_CHECKING:
    import sympy as sp

    from symjac.kinematics.chain import Frame
    from symjac.model.robot import Robot

__all__ = [
    "ROBOT_HELP",
    "LazyChoices",
    "add_robot_arguments",
    "configuration_values",
    "load",
    "parse_configuration",
    "parse_frame",
    "parse_point",
    "parse_rows",
    "parse_values",
    "refuse_ignored_options",
]

ROBOT_HELP = ("a built-in robot name (see 'symjac robots') or a robot file ({formats}; the format is read from its "
              "content)")


def add_robot_arguments(parser: argparse.ArgumentParser) -> None:
    """The ``ROBOT`` argument and the options that choose the chain of a tree format (URDF)."""
    from symjac.model.readers import readers, tree_formats  # the registry only: no reader is imported

    formats = tree_formats()
    parser.add_argument("robot", metavar="ROBOT",
                        help=ROBOT_HELP.format(formats=", ".join(reader.name for reader in readers())))
    parser.add_argument("--base-link", default=None, metavar="LINK",
                        help=f"{formats} files only: first link of the chain (default: the root link)")
    parser.add_argument("--tip-link", default=None, metavar="LINK",
                        help=f"{formats} files only: last link of the chain (default: the only leaf link)")
    parser.add_argument("--max-bytes", default=None, type=int, metavar="N",
                        help="largest robot file read, in bytes (default: the format's limit, 5000000 for URDF; "
                             "it keeps runaway files out)")
    site_formats = " and ".join(reader.name for reader in readers() if reader.sites)
    parser.add_argument("--tip-site", default=None, metavar="SITE",
                        help=f"{site_formats} files only: end the chain at this site (the tool frame is the site's)")


def load(args: argparse.Namespace) -> Robot:
    """The robot named by ``args.robot``; ``--base-link`` / ``--tip-link`` choose the chain of a tree format (URDF)."""
    from symjac.model.io import load_robot
    from symjac.model.readers import LinksNotApplicableError
    from symjac.model.readers.tree import ChainChoiceError

    links = {"--base-link": args.base_link, "--tip-link": args.tip_link}
    if args.max_bytes is not None and args.max_bytes < 1:
        raise ArgumentError(f"--max-bytes must be a positive whole number of bytes, got {args.max_bytes}")
    try:
        return load_robot(args.robot, base_link=args.base_link, tip_link=args.tip_link,
                          tip_site=getattr(args, "tip_site", None), max_bytes=args.max_bytes)
    except LinksNotApplicableError as error:  # say it with the options the user typed
        given = [option for option, value in links.items() if value is not None]
        verb = "applies" if len(given) == 1 else "apply"
        raise ArgumentError(f"{' and '.join(given)} {verb} to {error.formats} files only; {args.robot!r} is not "
                            "one") from None
    except ChainChoiceError as error:  # the options the user typed, never a rewritten link name
        raise RobotFileError(error.worded(base_link="--base-link", tip_link="--tip-link", tip_site="--tip-site"),
                             source=error.source, joint=error.joint, field=error.field) from None


def refuse_ignored_options(args: argparse.Namespace) -> None:
    """Refuse an option that would have no effect with the others given, instead of ignoring it silently."""
    if getattr(args, "standalone", False) and args.format != "latex":
        raise ArgumentError(f"--standalone applies to --format latex only, not --format {args.format}")
    if getattr(args, "digits", None) is not None:
        if not (args.numeric or getattr(args, "q", None) or getattr(args, "command", None) == "ik"):
            raise ArgumentError("--digits needs --numeric (or torques --q): only numbers are rounded")
        if args.digits < 1:
            raise ArgumentError(f"--digits must be at least 1, got {args.digits}")
    representation = getattr(args, "representation", None)
    if getattr(args, "position", None) is not None and hasattr(args, "representation") and representation is None:
        raise ArgumentError("--position needs --representation (it chooses the representation's position part)")
    method = getattr(args, "method", None)
    for option, given in (("--representation", representation is not None),
                          ("--derivative", getattr(args, "derivative", False))):
        if given and method not in (None, "differentiation"):
            raise ArgumentError(f"--method {method} does not apply with {option}")
    if getattr(args, "steps", False) and representation is not None:
        raise ArgumentError("--steps does not apply with --representation")


def parse_rows(text: str) -> tuple[int, ...]:
    """Task rows by name (``v_x .. omega_z``, :data:`symjac.kinematics.jacobian.ROW_NAMES`) -> indices 0..5."""
    from symjac.kinematics.jacobian import rows_from_names

    try:
        return rows_from_names(text)
    except ArgumentError as error:
        raise ArgumentError(f"--rows: {error}") from None


def parse_frame(text: str) -> Frame:
    """``--frame``: a frame number, ``world`` or ``tool``."""
    if text in ("world", "tool"):
        return text  # type: ignore[return-value]
    try:
        return int(text)
    except ValueError:
        raise FrameError(f"--frame must be a frame number, 'world' or 'tool', got {text!r}") from None


def parse_point(text: str | None, robot: Robot) -> str | tuple[sp.Expr, ...] | None:
    """``--point``: a named point, or three coordinates ``x,y,z`` in frame {n} (parameter names allowed).

    The names are ``tool``, ``flange`` (or ``wrist``) and ``wrist_centre``; not given (None) it stays None, the end
    of the chain.
    """
    from symjac.kinematics.points import POINT_NAMES
    from symjac.model.expressions import parse_expression

    if text is None or text in POINT_NAMES:
        return text
    parts = text.split(",")
    if len(parts) != 3:
        raise FrameError(f"--point must be {', '.join(map(repr, POINT_NAMES))} or three coordinates x,y,z, got "
                         f"{text!r}")
    try:
        return tuple(parse_expression(part.strip(), _parameters(robot)) for part in parts)
    except ExpressionError as error:
        raise FrameError(f"--point: {error}") from None


def _overflows(text: str) -> bool:
    """Whether ``text`` is a number too large for a float (``1e999``): not finite, though written as a number."""
    try:
        return not math.isfinite(float(text))
    except ValueError:
        return False


def parse_values(text: str, length: int, option: str, robot: Robot, *, parameters: bool = True,
                 units: str = "") -> list[sp.Expr]:
    """``length`` comma-separated values: numbers, ``pi`` and (with ``parameters``) the robot's parameter names.

    ``units`` (``"metres"``) is named in the error for a word that is none of these.
    """
    from symjac.model.expressions import parse_expression

    parts = text.split(",")
    if len(parts) != length:
        raise ArgumentError(f"{option} needs {length} comma-separated values, got {len(parts)} in {text!r}")
    names = _parameters(robot) if parameters else {}
    values = []
    for part in parts:
        try:
            values.append(parse_expression(part.strip(), names))
        except ExpressionError as error:
            words = set(re.findall(r"[A-Za-z_]\w*", part))
            if not parameters and (words & {"nan", "inf", "NaN", "Inf", "infinity"} or _overflows(part)):
                raise ArgumentError(f"{option} takes finite numbers, got {part.strip()!r}") from None
            if not parameters and words - {"pi"}:  # say what is allowed
                raise ArgumentError(f"{option} takes numbers and expressions with pi only"
                                    f"{f' ({units})' if units else ''}, got {part.strip()!r}") from None
            raise ArgumentError(f"{option}: {error}") from None
    return values


def parse_configuration(text: str, robot: Robot, option: str = "--q") -> list[float]:
    """A configuration ``q1,...,qn`` as floats in radians and metres (:func:`configuration_values`)."""
    return [float(value) for value in configuration_values(text, robot, option)]


def configuration_values(text: str, robot: Robot, option: str = "--q") -> list[sp.Expr]:
    r"""A configuration ``q1,...,qn`` in radians and metres, exact; every command's ``--q`` reads it this way.

    Each angle is ``30deg`` (degrees), ``0.5rad`` or an expression with ``pi`` (radians), or a plain number, read
    in the robot file's ``angle_unit``: in a file with ``angle_unit = "deg"``, ``--q 0,30,45`` is degrees,
    :math:`q = 30\,\pi/180`, and a one-line note on stderr says so. A prismatic coordinate is in metres.
    """
    import sympy as sp

    from symjac.model.robot import JointType

    parts = text.split(",")
    if len(parts) != robot.n_coordinates:
        raise ArgumentError(f"{option} needs {robot.n_coordinates} comma-separated values for {robot.name}, got "
                            f"{len(parts)} in {text!r}")
    values, in_file_unit = [], []
    for index, (part, kind) in enumerate(zip(parts, robot.coordinate_types, strict=True)):
        number = part.strip()
        unit = number[-3:] if number.endswith(("deg", "rad")) else None
        if unit is not None and kind is not JointType.REVOLUTE:
            raise ArgumentError(f"{option}: {robot.q[index]} is a length (a prismatic joint), so {number!r} cannot "
                                f"be in {'degrees' if unit == 'deg' else 'radians'}")
        [value] = parse_values(number if unit is None else number[:-3], 1, option, robot, parameters=False,
                               units="joint angles in radians, prismatic offsets in metres")
        if unit is None and kind is JointType.REVOLUTE and robot.angle_unit == "deg" and "pi" not in number:
            unit = "deg"  # a plain number in a file that speaks degrees (0 is 0 in any unit: not noted)
            in_file_unit += [number] if value != 0 else []
        value = value * sp.pi / 180 if unit == "deg" else value
        if not value.is_number or not math.isfinite(float(value)):
            raise ArgumentError(f"{option}: {number!r} is not a finite number")
        values.append(value)
    if in_file_unit:  # never silent: the same text means radians for a robot in radians
        sys.stderr.write(f"symjac: note: {option} {', '.join(in_file_unit)} read in degrees, as {robot.name}'s file "
                         "says angle_unit = \"deg\" (write 0.5rad or pi/6 for radians)\n")
    return values


def _parameters(robot: Robot) -> dict[str, sp.Symbol]:
    return {parameter.name: parameter.symbol for parameter in robot.parameters}
