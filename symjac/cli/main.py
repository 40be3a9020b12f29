"""The ``symjac`` command: list robots, show DH tables and transforms, print forward kinematics and Jacobians.

Results go to stdout (or ``-o FILE``, written only once complete: see :func:`symjac.files.write_text`; ``-o -`` is
stdout); progress of slow steps goes to stderr when it is a terminal. Any failure after the arguments are parsed
prints one line and exits with status 2, Ctrl-C prints ``symjac: interrupted`` and exits with 130 (:func:`main`).
Turning option text into API arguments lives in :mod:`symjac.cli.args`, output and error lines in
:mod:`symjac.cli.output`.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import shlex
import sys
from collections.abc import Callable, Sequence
from typing import Any, NoReturn

import sympy as sp

from symjac._version import __version__
from symjac.analysis.representations import POSITIONS, REPRESENTATIONS, representation_jacobian
from symjac.analysis.singularity.singularities import singularities
from symjac.cli.args import (
    add_robot_arguments,
    load,
    parse_frame,
    parse_point,
    parse_rows,
    parse_values,
    refuse_ignored_options,
)
from symjac.cli.output import emit, note_if_large, one_line, progress, silence_stdout
from symjac.codegen import BACKENDS, STRATEGIES, TARGETS, JacobianRequest, ModuleRequest, describe, render_files
from symjac.codegen.module import single_or_written
from symjac.errors import ArgumentError, SymjacError
from symjac.kinematics.acceleration import (
    bias_acceleration,
    carried_joints,
    hessian,
    hessian_slice,
    jacobian_derivative,
)
from symjac.kinematics.acceleration_propagation import acceleration_propagation
from symjac.kinematics.chain import Frame, chain_of
from symjac.kinematics.jacobian import METHODS, jacobian, point_vector
from symjac.kinematics.propagation import force_propagation, joint_rate_symbols, velocity_propagation, wrench_symbols
from symjac.kinematics.statics import joint_torques
from symjac.model.io import catalog
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import FORMATS, Block, DHTable, Document, Equation, Inline, render
from symjac.printing.json import (
    forward_kinematics_data,
    hessian_data,
    jacobian_data,
    jacobian_derivative_data,
    metadata,
    representation_data,
    show_data,
    singularity_data,
    torques_data,
)
from symjac.printing.latex import DIGITS, rounded
from symjac.printing.steps import step_equations
from symjac.printing.summary import singularity_blocks
from symjac.symbolic.simplify import simplify_matrix
from symjac.teaching.errata import SHEET_FORMATS, errata_sheet

__all__ = ["main"]

RECURSION_LIMIT = 10_000
"""Python frames the command line allows (see :func:`main`)."""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status.

    0 on success; 2 on a usage or input error, reported as one line ``symjac: error: ...`` on stderr; 130 when
    interrupted (Ctrl-C), reported as ``symjac: interrupted``. When stdout is closed early (``symjac show puma560 |
    head -1``) the command stops quietly with status 141, as a program ended by SIGPIPE does. Set the environment
    variable ``SYMJAC_TRACEBACK=1`` to get the full traceback of an unexpected error instead of its one line.
    """
    parser = _parser()
    args = parser.parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)  # the command as typed, for generated headers
    # SymPy walks raw chain products recursively (``is_number``, printing), a few frames per link: 200 links need
    # more than Python's default 1000 frames.
    sys.setrecursionlimit(max(sys.getrecursionlimit(), RECURSION_LIMIT))
    try:
        refuse_ignored_options(args)
        result = args.handler(args)
        text = result if isinstance(result, str) else render(result, args.format, args.standalone)
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


class _Parser(argparse.ArgumentParser):
    """argparse with usage errors on one line, like every other error (the usage is one ``--help`` away)."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"symjac: error: {message} (see '{self.prog} --help')\n")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="symjac", description="Symbolic kinematics and Jacobians of serial arms.")
    parser.add_argument("--version", action="version", version=f"symjac {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def command(name: str, handler: Callable[[argparse.Namespace], str | Document],
                help_text: str) -> argparse.ArgumentParser:
        sub = commands.add_parser(name, help=help_text, description=help_text)
        sub.set_defaults(handler=handler)
        sub.add_argument("-o", "--output", metavar="FILE",  # kept as typed: "./-" is a file, "-" is stdout
                         help="write the result to this file instead of stdout (- for stdout)")
        return sub

    command("robots", _robots, "list the built-in robots")
    errata = command("errata", _errata, "the errata sheet of the course notes: every printed formula checked")
    errata.add_argument("--format", dest="sheet_format", choices=SHEET_FORMATS, default="markdown",
                        help="markdown or a standalone LaTeX document (default markdown)")
    generator = command("codegen", _codegen, "generate a numeric module: forward kinematics, Jacobians, torques")
    add_robot_arguments(generator)
    generator.add_argument("--target", choices=TARGETS, default="python",
                           help="; ".join(f"{b.name} ({b.summary})" for b in BACKENDS.values()) + "; default python")
    generator.add_argument("--frame", action="append", default=None, metavar="K",
                           help="frame to express the Jacobian in: 0..n, world or tool (repeatable; default 0)")
    generator.add_argument("--point", action="append", default=None, metavar="P",
                           help="wrist, tool, or x,y,z in frame {n} (repeatable; default wrist)")
    generator.add_argument("--rows", default=None,
                           help="task rows, comma-separated from v_x,v_y,v_z,omega_x,omega_y,omega_z (default all)")
    generator.add_argument("--strategy", choices=STRATEGIES, default="fastest",
                           help="expressions to start from (default: fewest operations after CSE)")
    generator.add_argument("--acceleration", action="store_true",
                           help="also generate hessian, bias_acceleration (Jdot qdot) and manipulability_gradient")
    reporter = command("report", _report, "write the whole derivation as one self-contained HTML page")
    add_robot_arguments(reporter)
    converter = command("convert", _convert, "print the robot as a TOML robot file, converted to a DH convention")
    add_robot_arguments(converter)
    converter.add_argument("--to", choices=("modified", "standard", "toml"), required=True,
                           help="the DH convention to convert to, or toml to keep the robot as it is")
    for name, handler, help_text in (
        ("show", _show, "show the DH table and the link transforms"),
        ("fk", _fk, "print the forward kinematics"),
        ("jacobian", _jacobian, "print the basic Jacobian [v; omega]"),
        ("hessian", _hessian, "print the kinematic Hessian: dJ/dq_k for every joint k"),
        ("torques", _torques, "print the joint torques tau = J^T F that hold a wrench"),
        ("singularities", _singularities, "factor det J, solve every factor and explain what the arm loses there"),
    ):
        sub = command(name, handler, help_text)
        add_robot_arguments(sub)
        sub.add_argument("--format", choices=FORMATS, default="latex", help="output format (default: latex)")
        sub.add_argument("--numeric", action="store_true", help="substitute the parameters' numeric defaults")
        sub.add_argument("--standalone", action="store_true", help="with --format latex: a complete LaTeX document")
        if name != "singularities":
            sub.add_argument("--digits", type=int, default=None, metavar="N",
                             help=f"with --numeric (or torques --q): significant digits printed (default {DIGITS})")
        if name in ("jacobian", "torques", "hessian"):
            sub.add_argument("--frame", default="0", help="frame to express it in: 0..n, world or tool (default 0)")
            sub.add_argument("--point", default="wrist", help="wrist, tool, or x,y,z in frame {n} (default wrist)")
        if name == "jacobian":
            sub.add_argument("--method", choices=METHODS, default="differentiation", help="derivation method")
            sub.add_argument("--steps", action="store_true",
                             help="with a propagation method (or --derivative): print every propagation step first")
            sub.add_argument("--representation", choices=REPRESENTATIONS, default=None,
                             help="print the representation Jacobian J_x = E(x) J_0 for these orientation coordinates")
            sub.add_argument("--position", choices=POSITIONS, default=None,
                             help="with --representation: position coordinates (default cartesian)")
            sub.add_argument("--derivative", action="store_true",
                             help="print the time derivative dJ/dt and the bias acceleration Jdot qdot instead")
        if name == "singularities":
            sub.add_argument("--frame", default=None, help="frame to analyse in (default: the most compact one)")
            sub.add_argument("--point", default=None, help="wrist, tool, or x,y,z in frame {n} (default: tool if "
                                                            "the robot has one, else wrist)")
            sub.add_argument("--rows", default=None,
                             help="task rows, comma-separated from v_x,v_y,v_z,omega_x,omega_y,omega_z "
                                  "(default: chosen automatically)")
        if name == "torques":
            sub.add_argument("--wrench", help="fx,fy,fz,nx,ny,nz applied at the point, in the frame (default symbolic)")
            sub.add_argument("--q", help="a configuration q1,...,qn (numbers or expressions with pi)")
    return parser


# --- commands ----------------------------------------------------------------------------------------------


def _robots(args: argparse.Namespace) -> str:
    robots = catalog()
    width = max(map(len, robots))
    return "".join(f"{name:<{width}}  {description}\n" for name, description in robots.items())


def _errata(args: argparse.Namespace) -> str:
    """``errata``: a sheet, not a Document; its formats are its own, hence its own ``dest``."""
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
    from symjac.report import derivation_report  # only this command needs it (and matplotlib)

    robot = load(args)
    return progress(f"derivation report of {robot.name}", lambda: derivation_report(robot, args.robot))


def _show(args: argparse.Namespace) -> Document:
    robot = load(args)  # no note for a long chain: each link is simplified alone, 200 links in about a second
    chain = chain_of(robot)
    transforms = [(f"{{}}^{{{i - 1}}}_{{{i}}}T", f"T_{i - 1}_{i}", chain.simplified_transform(i - 1, i))
                  for i in range(1, robot.dof + 1)]
    for key in ("base", "tool"):
        fixed = getattr(robot, key)
        if fixed is not None:
            source, target = ("world", 0) if key == "base" else (robot.dof, "tool")
            transforms.append((f"{{}}^{{{_tex(source)}}}_{{{_tex(target)}}}T", f"T_{source}_{target}", fixed.matrix))
    matrices = [(tex, plain, _numeric(robot, m, args)) for tex, plain, m in transforms]
    blocks = [Block((prose.dh_caption(robot),), (DHTable(robot),))]
    blocks += [Block((), (Equation(tex, plain, m),)) for tex, plain, m in matrices]
    data = show_data(robot, {plain: m for _, plain, m in matrices})
    return Document(f"{robot.name}: DH table and link transforms", robot.name, tuple(blocks), data)


def _fk(args: argparse.Namespace) -> Document:
    robot = load(args)
    note_if_large(robot.name, robot.dof)
    chain = chain_of(robot)
    source: Frame = "world" if robot.base else 0
    target: Frame = "tool" if robot.tool else robot.dof
    T = progress(f"forward kinematics of {robot.name}", lambda: chain.simplified_transform(source, target))
    T = _numeric(robot, T, args)
    equation = Equation(f"{{}}^{{{_tex(source)}}}_{{{_tex(target)}}}T", f"T_{source}_{target}", T)
    data = forward_kinematics_data(robot, equation, source, target)
    return Document(f"{robot.name}: forward kinematics", robot.name, (Block((), (equation,)),), data)


def _jacobian(args: argparse.Namespace) -> Document:
    robot = load(args)
    note_if_large(robot.name, robot.dof)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    if args.representation is not None:
        return _representation(args, robot, frame, point)
    if args.derivative:
        return _derivative(args, robot, frame, point)
    steps = _steps(args, robot, point) if args.steps else []
    J = progress(f"Jacobian of {robot.name} in frame {frame}",
                  lambda: jacobian(robot, frame=frame, point=point, method=args.method))
    J = _numeric(robot, J, args)
    equation = Equation(f"{{}}^{{{_tex(frame)}}}J", f"J in frame {frame}", J)
    caption = f"Basic Jacobian at the {args.point} point, {args.method.replace('_', ' ')}"
    blocks = [Block((), (step,)) for step in steps] + [Block((caption,), (equation,))]
    data = jacobian_data(robot, equation, frame, args.point, args.method, steps if args.steps else None)
    return Document(f"{robot.name}: Jacobian in frame {frame}", robot.name, tuple(blocks), data)


def _representation(args: argparse.Namespace, robot: Robot, frame: Frame, point: Any) -> Document:
    """``jacobian --representation``: x, E(x), the basic Jacobian and J_x = E(x) J_0, then E's own singularities."""
    position = args.position or "cartesian"
    rj = progress(f"{args.representation} representation Jacobian of {robot.name}",
                   lambda: representation_jacobian(robot, args.representation, position, point, frame))
    notes = [prose.representation_parts(s) for s in rj.singularities]
    J_x = simplify_matrix(rj.J_x, chain_of(robot).angle_basis(rj.frame)).applyfunc(
        lambda entry: sp.factor_terms(sp.together(entry)))  # multiplied out, then over one denominator
    J_0, J_x = _numeric(robot, rj.J_0, args), _numeric(robot, J_x, args)
    blocks = [Block(("Representation coordinates",), (Equation("x", "x", sp.Matrix(rj.coordinates)),)),
              Block(("Rate matrix, ", Inline(r"\dot{x} = E(x)\,[v;\ \omega]", "xdot = E(x) [v; omega]")),
                    (Equation("E(x)", "E(x)", rj.E),)),
              Block((f"Representation Jacobian at the {args.point} point",),
                    (Equation(rf"J_x = E(x)\,{{}}^{{{_tex(rj.frame)}}}J", f"J_x = E(x) J_{rj.frame}", J_x),))]
    blocks += [Block(note) for note in notes]
    data = representation_data(robot, rj, J_0, J_x, args.point, args.representation, position)
    title = f"{robot.name}: {args.representation} representation Jacobian"
    return Document(title, robot.name, tuple(blocks), data, comments=True)


def _derivative(args: argparse.Namespace, robot: Robot, frame: Frame, point: Any) -> Document:
    """``jacobian --derivative``: the time derivative of the Jacobian and the bias acceleration."""
    tip = None if point == "tool" else point_vector(robot, point)
    steps = []
    if args.steps:
        propagation = progress(f"acceleration propagation of {robot.name}",
                                lambda: acceleration_propagation(robot, tip))
        steps = _numeric_steps(robot, step_equations(propagation), args)
    Jdot = progress(f"Jacobian derivative of {robot.name} in frame {frame}",
                     lambda: jacobian_derivative(robot, frame=frame, point=point))
    bias = bias_acceleration(robot, frame=frame, point=point)
    Jdot, bias = _numeric(robot, Jdot, args), _numeric(robot, bias, args)
    moving = " (in a moving frame: its rotation is differentiated too)" if carried_joints(robot, frame) else ""
    Jdot_equation = Equation(rf"{{}}^{{{_tex(frame)}}}\dot{{J}}", f"Jdot in frame {frame}", Jdot)
    bias_equation = Equation(rf"{{}}^{{{_tex(frame)}}}\dot{{J}}\,\dot{{q}}", f"Jdot qdot in frame {frame}", bias)
    blocks = (*(Block((), (step,)) for step in steps),
              Block((f"Time derivative of the basic Jacobian at the {args.point} point{moving}",), (Jdot_equation,)),
              Block(("Bias acceleration, the acceleration at zero joint acceleration",), (bias_equation,)))
    data = jacobian_derivative_data(robot, Jdot_equation, bias_equation, frame, args.point,
                                    [str(r) for r in joint_rate_symbols(robot)], steps if args.steps else None)
    return Document(f"{robot.name}: time derivative of the Jacobian in frame {frame}", robot.name, blocks, data)


def _hessian(args: argparse.Namespace) -> Document:
    """``hessian``: one 6 x n slice dJ/dq_k per joint."""
    robot = load(args)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    H = progress(f"Hessian of {robot.name} in frame {frame}", lambda: hessian(robot, frame=frame, point=point))
    equations = [Equation(rf"\frac{{\partial\,{{}}^{{{_tex(frame)}}}J}}{{\partial {sp.latex(q)}}}", f"dJ/d{q}",
                          _numeric(robot, hessian_slice(H, k), args)) for k, q in enumerate(robot.q)]
    blocks = tuple(Block((f"Derivative of the Jacobian with respect to joint {k + 1}",), (equation,))
                   for k, equation in enumerate(equations))
    data = hessian_data(robot, equations, frame, args.point)
    return Document(f"{robot.name}: kinematic Hessian in frame {frame}", robot.name, blocks, data)


def _steps(args: argparse.Namespace, robot: Robot, point: Any) -> list[Equation]:
    """The propagation steps of ``--steps``."""
    tip = None if point == "tool" else point_vector(robot, point)
    derive: dict[str, Callable[[], Any]] = {
        "velocity_propagation": lambda: velocity_propagation(robot, tip),
        "force_propagation": lambda: force_propagation(robot, tip),
    }
    if args.method not in derive:
        raise ArgumentError("--steps needs --method velocity_propagation or --method force_propagation")
    propagation = progress(f"{args.method.replace('_', ' ')} of {robot.name}", derive[args.method])
    return _numeric_steps(robot, step_equations(propagation), args)


def _torques(args: argparse.Namespace) -> Document:
    robot = load(args)
    frame = parse_frame(args.frame)
    point = parse_point(args.point, robot)
    wrench = None if args.wrench is None else parse_values(args.wrench, 6, "--wrench", robot)
    q = None if args.q is None else parse_values(args.q, robot.dof, "--q", robot, parameters=False)
    tau = progress(f"joint torques of {robot.name}",
                    lambda: joint_torques(robot, wrench=wrench, frame=frame, point=point, q=q))
    tau = _numeric(robot, tau, args)
    if q is not None:  # evaluated at a configuration: numbers, shown as decimals
        tau = rounded(tau, args.digits or DIGITS)
    equation = Equation(r"\tau", "tau", tau)
    caption = f"Joint torques for a wrench in frame {frame} at the {args.point} point"
    data = torques_data(robot, equation, frame, args.point, args.wrench, args.q, [str(s) for s in wrench_symbols()])
    return Document(f"{robot.name}: joint torques", robot.name, (Block((caption,), (equation,)),), data)


def _singularities(args: argparse.Namespace) -> Document:
    robot = load(args)
    frame = None if args.frame is None else parse_frame(args.frame)
    point = None if args.point is None else parse_point(args.point, robot)
    rows = None if args.rows is None else parse_rows(args.rows)
    report = progress(f"singularities of {robot.name}",
                       lambda: singularities(robot, rows=rows, frame=frame, point=point, numeric=args.numeric))
    return Document(f"{robot.name}: singular configurations", robot.name, tuple(singularity_blocks(report)),
                    {**metadata(robot), **singularity_data(report)}, comments=True)


def _codegen(args: argparse.Namespace) -> str:
    robot = load(args)
    frames = [parse_frame(text) for text in (args.frame or ["0"])]
    points = [parse_point(text, robot) for text in (args.point or ["wrist"])]
    rows = None if args.rows is None else parse_rows(args.rows)
    requests = [JacobianRequest(frame, point, rows) for frame in frames for point in points]
    request = ModuleRequest(robot, args.target, jacobians=requests, strategy=args.strategy,
                            command=shlex.join(["symjac", *args.argv]), acceleration=args.acceleration)
    files = progress(f"{args.target} module for {robot.name}", lambda: render_files(describe(request)))
    text = single_or_written(files, args.output)  # several files are written here, all or none
    args.output = args.output if text is not None else None
    return text or ""


# --- output helpers ------------------------------------------------------------------------------------------


def _tex(frame: Frame | str) -> str:
    r"""A frame as a LaTeX index: ``3``, or an upright name (``\mathrm{tool}``)."""
    return str(frame) if isinstance(frame, int) else rf"\mathrm{{{frame}}}"


def _numeric(robot: Robot, matrix: sp.MatrixBase, args: argparse.Namespace) -> sp.MatrixBase:
    """With ``--numeric``, the parameters' defaults substituted and every number a decimal of ``--digits`` digits.

    The derivation stays exact; only the printed result is rounded (``0.4318``, not ``2159/5000``).
    """
    if not args.numeric:
        return matrix
    return rounded(matrix.xreplace(robot.defaults), args.digits or DIGITS)


def _numeric_steps(robot: Robot, steps: list[Equation], args: argparse.Namespace) -> list[Equation]:
    return [dataclasses.replace(step, rhs=_numeric(robot, step.rhs, args)) for step in steps]


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
