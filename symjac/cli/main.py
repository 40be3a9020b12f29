"""The ``symjac`` command: list robots, show DH tables and transforms, print forward kinematics and Jacobians.

Results go to stdout (or ``-o FILE``, written only once complete: see :func:`symjac.files.write_text`; ``-o -`` is
stdout); progress of slow steps goes to stderr when it is a terminal. Any failure after the arguments are parsed
prints one line and exits with status 2, Ctrl-C prints ``symjac: interrupted`` and exits with 130 (:func:`main`).
Turning option text into API arguments lives in :mod:`symjac.cli.args`, output and error lines in
:mod:`symjac.cli.output`, the documents in :mod:`symjac.printing.results`.

A handler parses, calls the API, builds the document; :func:`main` renders it. Only the command given is set up,
and each handler imports what it uses: ``symjac --version`` loads no SymPy, ``symjac fk`` no code generator.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shlex
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn

from symjac._version import __version__
from symjac.cli.args import (
    load,
    parse_frame,
    parse_point,
    parse_rows,
    parse_values,
    refuse_ignored_options,
)
from symjac.cli.drawing import draw_command
from symjac.cli.options import (
    codegen_options,
    convert_options,
    draw_options,
    errata_options,
    no_options,
    result_options,
    robot_options,
    sweep_options,
)
from symjac.cli.output import emit, note_if_large, one_line, progress, silence_stdout
from symjac.cli.sweeping import sweep_command
from symjac.errors import ArgumentError, SymjacError

if TYPE_CHECKING:
    from symjac.kinematics.chain import Frame
    from symjac.model.robot import Robot
    from symjac.printing.document import Document

__all__ = ["full_parser", "main", "run"]

RECURSION_LIMIT = 10_000
"""Python frames the command line allows (see :func:`main`)."""


def run() -> NoReturn:
    """The ``symjac`` program (console script and ``python -m symjac``): :func:`main`, then exit at once.

    A derivation leaves SymPy's caches holding hundreds of thousands of expressions; letting the interpreter free
    them one by one at exit took a third of a second after a 7-joint Jacobian, longer than printing it. The
    output is complete by then (streams flushed, files written and closed), so the process ends without that
    teardown. Call :func:`main` to run the command line inside a Python process.
    """
    status = main()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed or broken pipe has nothing left to flush
            stream.flush()
    os._exit(status)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status.

    0 on success; 2 on a usage or input error, reported as one line ``symjac: error: ...`` on stderr; 130 when
    interrupted (Ctrl-C), reported as ``symjac: interrupted``. When stdout is closed early (``symjac show puma560 |
    head -1``) the command stops quietly with status 141, as a program ended by SIGPIPE does. Set the environment
    variable ``SYMJAC_TRACEBACK=1`` to get the full traceback of an unexpected error instead of its one line.
    """
    typed = list(sys.argv[1:] if argv is None else argv)
    args = _parser(_command_in(typed)).parse_args(typed)
    args.argv = typed  # the command as typed, for generated headers
    # SymPy walks raw chain products recursively (``is_number``, printing), a few frames per link: 200 links need
    # more than Python's default 1000 frames.
    sys.setrecursionlimit(max(sys.getrecursionlimit(), RECURSION_LIMIT))
    try:
        refuse_ignored_options(args)
        result = args.handler(args)
        emit(result if isinstance(result, str) else _rendered(result, args), args.output)
    except KeyboardInterrupt:
        print("symjac: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError as error:
        if error.filename is not None:  # an -o FIFO whose reader went away: a real error
            print(f"symjac: error: {one_line(error)}", file=sys.stderr)
            return 2
        silence_stdout()
        return 141
    except Exception as error:  # every failure is one line; SYMJAC_TRACEBACK=1 shows the unexpected ones in full
        if os.environ.get("SYMJAC_TRACEBACK") and not isinstance(error, SymjacError | OSError):
            raise
        print(f"symjac: error: {one_line(error)}", file=sys.stderr)
        return 2
    return 0


def _rendered(document: Document, args: argparse.Namespace) -> str:
    """The document in the format asked for; LaTeX too long to read goes only to a file (``-o FILE``)."""
    from symjac.printing.document import render, render_for_terminal
    from symjac.printing.prose import LATEX_TOO_LONG

    if args.output in (None, "-"):
        return render_for_terminal(document, args.format, args.standalone, LATEX_TOO_LONG)
    return render(document, args.format, args.standalone)


class _Parser(argparse.ArgumentParser):
    """argparse with usage errors on one line, like every other error (the usage is one ``--help`` away)."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"symjac: error: {message} (see '{self.prog} --help')\n")


def _command_in(argv: Sequence[str]) -> str | None:
    """The command named in ``argv``: its first word that is not an option (the top level has only flags)."""
    return next((word for word in argv if not word.startswith("-")), None)


def full_parser() -> argparse.ArgumentParser:
    """The parser with every command's options set up: what the documentation's CLI reference is made from.

    The command line itself builds only the options of the command given (:func:`main`), so that ``symjac fk``
    imports no code generator; this one imports what every command lists.
    """
    return _parser(every=True)


def _parser(command: str | None = None, *, every: bool = False) -> argparse.ArgumentParser:
    """The parser; only ``command``'s own options are set up (the others' would import what they list)."""
    parser = _Parser(prog="symjac", description="Symbolic kinematics and Jacobians of serial arms.")
    parser.add_argument("--version", action="version", version=f"symjac {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, (handler, help_text, options) in COMMANDS.items():
        sub = commands.add_parser(name, help=help_text, description=help_text)
        sub.set_defaults(handler=handler)
        folder = "; a target that writes several files takes a folder" if name == "codegen" else ""
        sub.add_argument("-o", "--output", metavar="FILE",  # kept as typed: "./-" is a file, "-" is stdout
                         help=f"write the result to this file instead of stdout (- for stdout){folder}")
        if every or name == command:
            options(sub, name)
    return parser


# --- options of each command ----------------------------------------------------------------------------------


# --- commands ----------------------------------------------------------------------------------------------


def _robots(args: argparse.Namespace) -> str:
    from symjac.model.io import catalog

    robots = catalog()
    width = max(map(len, robots))
    return "".join(f"{name:<{width}}  {description}\n" for name, description in robots.items())


def _errata(args: argparse.Namespace) -> str:
    """``errata``: a sheet, not a Document; its formats are its own, hence its own ``dest``."""
    from symjac.teaching.errata import errata_sheet

    return progress("the errata sheet", lambda: errata_sheet(args.sheet_format))


def _convert(args: argparse.Namespace) -> str:
    from symjac.kinematics.convert import converted  # only this command needs it
    from symjac.model.io import robot_to_toml

    robot = load(args)
    if args.to == "toml":
        return robot_to_toml(robot)
    result, notes = converted(robot, args.to)  # notes: whether the table needs a base or tool transform, in words
    return "".join(f"# {note}\n" for note in notes) + robot_to_toml(result)


def _report(args: argparse.Namespace) -> str:
    """``report``: one HTML page (matplotlib is imported only for this command)."""
    from symjac.report import derivation_report

    robot = load(args)
    return progress(f"derivation report of {robot.name}", lambda: derivation_report(robot, args.robot))


def _show(args: argparse.Namespace) -> Document:
    from symjac.printing.results import link_transforms, transforms_document

    robot = load(args)
    return transforms_document(robot, link_transforms(robot), _digits(args))


def _fk(args: argparse.Namespace) -> Document:
    from symjac.kinematics.chain import forward_kinematics
    from symjac.printing.results import forward_kinematics_document

    robot = load(args)
    note_if_large(robot.name, robot.n_joints)
    source: Frame = "world" if robot.base else 0
    target: Frame = "tool" if robot.tool else robot.n_joints
    T = progress(f"forward kinematics of {robot.name}", lambda: forward_kinematics(robot, source, target))
    return forward_kinematics_document(robot, source, target, T, _digits(args))


def _jacobian(args: argparse.Namespace) -> Document:
    from symjac.kinematics.jacobian import jacobian
    from symjac.printing.results import jacobian_document

    robot = load(args)
    note_if_large(robot.name, robot.n_joints)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    if args.kind != "geometric":
        return _screw_jacobian(args, robot)
    if args.representation is not None:
        return _representation(args, robot, frame, point)
    if args.derivative:
        return _derivative(args, robot, frame, point)
    propagation = _propagation(args, robot, point) if args.steps else None
    J = progress(f"Jacobian of {robot.name} in frame {frame}",
                  lambda: jacobian(robot, frame=frame, point=point, method=args.method))
    return jacobian_document(robot, J, frame, args.point, args.method, propagation, _digits(args))


def _screw_jacobian(args: argparse.Namespace, robot: Robot) -> Document:
    """``jacobian --kind space|body``: J_s or J_b (the frame and point are the space and tool frames)."""
    from symjac.kinematics.screws import body_jacobian, space_jacobian
    from symjac.printing.results import screw_jacobian_document

    others = [flag for flag, given in (("--frame", args.frame != "0"), ("--point", args.point != "wrist"),
                                       ("--representation", args.representation is not None),
                                       ("--derivative", args.derivative), ("--steps", args.steps)) if given]
    if others:
        raise ArgumentError(f"--kind {args.kind} takes neither {' nor '.join(others)}: J_s is in the space frame "
                            f"{{0}}, J_b in the tool frame")
    derive = space_jacobian if args.kind == "space" else body_jacobian
    J = progress(f"{args.kind} Jacobian of {robot.name}", lambda: derive(robot))
    return screw_jacobian_document(robot, J, args.kind, _digits(args))


def _representation(args: argparse.Namespace, robot: Robot, frame: Frame, point: Any) -> Document:
    """``jacobian --representation``: x, E(x), the basic Jacobian and J_x = E(x) J_0, then E's own singularities."""
    from symjac.analysis.representations import representation_jacobian
    from symjac.printing.results import representation_document

    position = args.position or "cartesian"
    result = progress(f"{args.representation} representation Jacobian of {robot.name}",
                      lambda: representation_jacobian(robot, args.representation, position, point, frame))
    return representation_document(robot, result, args.point, args.representation, position, _digits(args))


def _derivative(args: argparse.Namespace, robot: Robot, frame: Frame, point: Any) -> Document:
    """``jacobian --derivative``: the time derivative of the Jacobian and the bias acceleration."""
    from symjac.kinematics.acceleration import bias_acceleration, carried_joints, jacobian_derivative
    from symjac.kinematics.acceleration_propagation import acceleration_propagation
    from symjac.kinematics.jacobian import point_vector
    from symjac.kinematics.propagation import joint_rate_symbols
    from symjac.printing.results import derivative_document

    propagation = None
    if args.steps:
        tip = None if point == "tool" else point_vector(robot, point)
        propagation = progress(f"acceleration propagation of {robot.name}",
                               lambda: acceleration_propagation(robot, tip))
    Jdot = progress(f"Jacobian derivative of {robot.name} in frame {frame}",
                     lambda: jacobian_derivative(robot, frame=frame, point=point))
    bias = bias_acceleration(robot, frame=frame, point=point)
    return derivative_document(robot, Jdot, bias, frame, args.point, bool(carried_joints(robot, frame)),
                               joint_rate_symbols(robot), propagation, _digits(args))


def _hessian(args: argparse.Namespace) -> Document:
    """``hessian``: one 6 x n slice dJ/dq_k per joint."""
    from symjac.kinematics.acceleration import hessian, hessian_slice
    from symjac.printing.results import hessian_document

    robot = load(args)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    H = progress(f"Hessian of {robot.name} in frame {frame}", lambda: hessian(robot, frame=frame, point=point))
    slices = [hessian_slice(H, k) for k in range(len(robot.q))]
    return hessian_document(robot, slices, frame, args.point, _digits(args))


def _propagation(args: argparse.Namespace, robot: Robot, point: Any) -> Any:
    """The velocity or force propagation whose steps ``--steps`` prints."""
    from symjac.kinematics.jacobian import point_vector
    from symjac.kinematics.propagation import force_propagation, velocity_propagation

    tip = None if point == "tool" else point_vector(robot, point)
    derive: dict[str, Callable[[], Any]] = {
        "velocity_propagation": lambda: velocity_propagation(robot, tip),
        "force_propagation": lambda: force_propagation(robot, tip),
    }
    if args.method not in derive:
        raise ArgumentError("--steps needs --method velocity_propagation or --method force_propagation")
    return progress(f"{args.method.replace('_', ' ')} of {robot.name}", derive[args.method])


def _torques(args: argparse.Namespace) -> Document:
    from symjac.kinematics.propagation import wrench_symbols
    from symjac.kinematics.statics import joint_torques
    from symjac.printing.latex import DIGITS
    from symjac.printing.results import torques_document

    robot = load(args)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    wrench = None if args.wrench is None else parse_values(args.wrench, 6, "--wrench", robot)
    q = None if args.q is None else parse_values(args.q, robot.n_coordinates, "--q", robot, parameters=False)
    tau = progress(f"joint torques of {robot.name}",
                    lambda: joint_torques(robot, wrench=wrench, frame=frame, point=point, q=q))
    evaluated = None if q is None else args.digits or DIGITS  # at a configuration: numbers, shown as decimals
    return torques_document(robot, tau, frame, args.point, args.wrench, args.q, wrench_symbols(), _digits(args),
                            evaluated)


def _singularities(args: argparse.Namespace) -> Document:
    from symjac.analysis.singularity.singularities import singularities
    from symjac.printing.results import singularities_document

    robot = load(args)
    frame = None if args.frame is None else parse_frame(args.frame)
    point = None if args.point is None else parse_point(args.point, robot)
    rows = None if args.rows is None else parse_rows(args.rows)
    report = progress(f"singularities of {robot.name}",
                       lambda: singularities(robot, rows=rows, frame=frame, point=point, numeric=args.numeric))
    return singularities_document(robot, report)


def _codegen(args: argparse.Namespace) -> str:
    from symjac.codegen import JacobianRequest, ModuleRequest, describe, render_files
    from symjac.codegen.module import single_or_written

    robot = load(args)
    frames = [parse_frame(text) for text in (args.frame or ["0"])]
    points = [parse_point(text, robot) for text in (args.point or ["wrist"])]
    rows = None if args.rows is None else parse_rows(args.rows)
    requests = [JacobianRequest(frame, point, rows) for frame in frames for point in points]
    request = ModuleRequest(robot, args.target, jacobians=requests, strategy=args.strategy,
                            command=shlex.join(["symjac", *args.argv]), acceleration=args.acceleration,
                            name=args.name)
    files = progress(f"{args.target} module for {robot.name}", lambda: render_files(describe(request)))
    text = single_or_written(files, args.output)  # several files are written here, all or none
    args.output = args.output if text is not None else None
    return text or ""


def _digits(args: argparse.Namespace) -> int | None:
    """``--numeric``: the significant digits of the printed numbers (``--digits``, default DIGITS); else None."""
    if not args.numeric:
        return None
    from symjac.printing.latex import DIGITS

    return args.digits or DIGITS


Handler = Callable[[argparse.Namespace], "str | Document"]
"""A command's handler: the parsed arguments in, the text or document to emit out."""
Options = Callable[[argparse.ArgumentParser, str], None]
"""A command's option builder: adds its options to the command's subparser (see :mod:`symjac.cli.options`)."""

COMMANDS: dict[str, tuple[Handler, str, Options]] = {
    "robots": (_robots, "list the built-in robots", no_options),
    "errata": (_errata, "the errata sheet of the course notes: every printed formula checked", errata_options),
    "codegen": (_codegen, "generate a numeric module: forward kinematics, Jacobians, torques", codegen_options),
    "draw": (draw_command, "draw the arm (SVG, PNG, PDF), or animate it along a joint path (GIF, MP4)", draw_options),
    "sweep": (sweep_command, "dexterity metrics over a grid of designs and joint samples (on dask)", sweep_options),
    "report": (_report, "write the whole derivation as one self-contained HTML page", robot_options),
    "convert": (_convert, "print the robot as a TOML robot file, converted to another convention", convert_options),
    "show": (_show, "show the DH table and the link transforms", result_options),
    "fk": (_fk, "print the forward kinematics", result_options),
    "jacobian": (_jacobian, "print the basic Jacobian [v; omega]", result_options),
    "hessian": (_hessian, "print the kinematic Hessian: dJ/dq_k for every joint k", result_options),
    "torques": (_torques, "print the joint torques tau = J^T F that hold a wrench", result_options),
    "singularities": (_singularities, "factor det J, solve every factor and explain what the arm loses there",
                      result_options),
}
"""Each command: its handler, its one-line help, and the function that adds its options."""


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
