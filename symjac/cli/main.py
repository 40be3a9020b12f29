"""The ``symjac`` command: list robots, show DH tables and transforms, print forward kinematics and Jacobians.

Results go to stdout (or ``-o FILE``, written only once complete: see :func:`symjac.files.write_text`; ``-o -`` is
stdout); after two seconds, the stage a command has reached shows on one line of stderr when it is a terminal
(:func:`symjac.cli.output.progress_line`), cleared when it ends. Any failure after the arguments are parsed
prints one line and exits with status 2, Ctrl-C prints ``symjac: interrupted`` and exits with 130 (:func:`main`).
Turning option text into API arguments lives in :mod:`symjac.cli.args`, output and error lines in
:mod:`symjac.cli.output`, the documents in :mod:`symjac.printing.results`. The commands that print a derived quantity
(``fk``, ``jacobian``, ``hessian``, ``torques``) are built from the quantities' specs (:mod:`symjac.cli.quantities`).

A handler parses, calls the API, builds the document; :func:`main` renders it. Only the command given is set up,
and each handler imports what it uses: ``symjac --version`` loads no SymPy, ``symjac fk`` no code generator.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shlex
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, NoReturn

from symjac._version import __version__
from symjac.cli.args import load, parse_frame, parse_point, parse_rows, refuse_ignored_options
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
from symjac.cli.output import emit, one_line, progress, progress_line, silence_stdout
from symjac.cli.quantities import quantity_commands
from symjac.cli.sweeping import sweep_command
from symjac.errors import SymjacError
from symjac.progress import report as report_stage
from symjac.quantities.bias_acceleration import command as derivative_command
from symjac.quantities.jacobian import propagation, representation

if TYPE_CHECKING:
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
        with warnings.catch_warnings():
            warnings.showwarning = _warning_line
            with progress_line(args.command):  # cleared before the result, an error or "interrupted" is written
                refuse_ignored_options(args)
                result = args.handler(args)
                report_stage("printing the result")  # the last stage derived is no longer what takes the time
                text = result if isinstance(result, str) else _rendered(result, args)
            emit(text, args.output)
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


def _warning_line(message: Warning | str, category: type[Warning], filename: str, lineno: int, file: object = None,
                  line: str | None = None) -> None:
    """A warning as one line on stderr, ``symjac: warning: ...``, as errors are (no source file or line of code)."""
    text = " ".join(str(message).split())
    print(f"symjac: warning: {text}", file=sys.stderr)


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
    from symjac.errors import ArgumentError

    robot = load(args)
    frames = [parse_frame(text) for text in (args.frame or ["0"])]
    points = [parse_point(text, robot) for text in (args.point or [None])]
    rows = None if args.rows is None else parse_rows(args.rows)
    requests = [JacobianRequest(frame, point, rows) for frame in frames for point in points]
    if args.free_joint is not None and not 1 <= args.free_joint <= robot.n_joints:
        raise ArgumentError(f"--free-joint is a joint number, 1 to {robot.n_joints} for {robot.name}, got "
                            f"{args.free_joint}")
    request = ModuleRequest(robot, args.target, jacobians=requests, strategy=args.strategy,
                            command=shlex.join(["symjac", *args.argv]), acceleration=args.acceleration,
                            name=args.name, dynamics=args.dynamics, identification=args.identification,
                            inverse_kinematics=args.inverse_kinematics,
                            free_joint=args.free_joint)
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
    "show": (_show, "show the parameter table (DH, screw axes, origins and axes) and the link transforms",
             result_options),
    **quantity_commands(),  # fk, jacobian, hessian, torques, ...: one per quantity spec (symjac.quantities)
    "singularities": (_singularities, "factor det J, solve every factor and explain what the arm loses there",
                      result_options),
}
"""Each command: its handler, its one-line help, and the function that adds its options."""

# The jacobian command's variants, under the names they had when their code was here (tests read their source).
_representation, _derivative, _propagation = representation, derivative_command, propagation


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
