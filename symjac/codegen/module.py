"""Assembling a generated module: requests to lowered functions, printed by the target's backend, into a template."""

from __future__ import annotations

import itertools
import os
import shlex
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Literal, get_args

import sympy as sp

from symjac._version import __version__
from symjac.codegen.acceleration import lowered_bias_acceleration, lowered_hessian
from symjac.codegen.backends import backend
from symjac.codegen.description import (
    Argument,
    FunctionKind,
    FunctionSpec,
    JacobianInfo,
    ModuleDescription,
)
from symjac.codegen.lower import (
    LoweredFunction,
    angle_expansion,
    lower_function,
    lowered_forward_kinematics,
    lowered_jacobian,
    lowered_kinematics,
    lowered_torques,
)
from symjac.codegen.printers import check_identifier, float_literal
from symjac.codegen.request import (
    RESERVED,
    JacobianRequest,
    check_rows,
    frame_text,
    function_labels,
    point_text,
    point_words,
    python_call,
    requests_from,
    validate_robot,
)
from symjac.codegen.source_layout import LINE_WIDTH, comment_lines, wrap_statement
from symjac.errors import CodegenError, SymjacError
from symjac.files import write_text
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import ROW_NAMES, Point
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.io import catalog, load_robot
from symjac.model.robot import WRENCH_NAMES, Robot
from symjac.resources import render_template

Strategy = Literal["fastest", "raw", "simplified"]
STRATEGIES: tuple[str, ...] = get_args(Strategy)

__all__ = ["STRATEGIES", "Strategy", "describe", "generate", "render_module", "write_module"]


def describe(
    robot: Robot | Chain,
    target: str = "python",
    frames: Sequence[Frame] | Frame = (0,),
    points: Sequence[Point] | Point = ("wrist",),
    *,
    rows: Sequence[int] | None = None,
    jacobians: Sequence[JacobianRequest] | None = None,
    scalars: Mapping[str, sp.Expr] | None = None,
    strategy: Strategy = "fastest",
    command: str | None = None,
    acceleration: bool = False,
) -> ModuleDescription:
    """The frozen description of the module :func:`generate` renders (see there for the parameters)."""
    spec = backend(target)
    if strategy not in STRATEGIES:
        raise CodegenError(f"unknown strategy {strategy!r}; choose one of {', '.join(STRATEGIES)}")
    if not isinstance(robot, Robot | Chain):
        raise CodegenError(f"expected a symjac Robot or Chain, got {type(robot).__name__}")
    chain = as_chain(robot)
    model = chain.robot
    validate_robot(model)
    requests = requests_from(chain, frames, points, rows, jacobians)
    if not requests:
        raise CodegenError("at least one Jacobian (frame and point) must be requested")

    taken = frozenset(RESERVED) | {p.name for p in model.parameters}
    q_argument = Argument("q", tuple(s.name for s in model.q), "Joint values")
    rates = tuple(s.name for s in joint_rate_symbols(chain)) if acceleration else ()
    lowered_functions: list[tuple[LoweredFunction, FunctionSpec]] = []

    def add(lowered: LoweredFunction, name: str, kind: FunctionKind, summary: str, *arguments: Argument) -> None:
        lowered_functions.append((lowered, FunctionSpec(name, kind, summary, (q_argument, *arguments))))

    add(lowered_forward_kinematics(chain, strategy), "forward_kinematics", "forward_kinematics",
        "The pose of the tool frame in frame {0}")
    infos: list[JacobianInfo] = []
    for request, label in zip(requests, function_labels(model, requests), strict=True):
        point_name, point = point_text(model, request.point)
        selected = check_rows(request.rows)
        names = {kind: f"{kind}{label}" for kind in ("jacobian", "joint_torques", "manipulability",
                                                      "jacobian_determinant", "_kinematics", "hessian",
                                                      "bias_acceleration", "manipulability_gradient")}
        J = lowered_jacobian(chain, request.frame, point, selected, strategy)
        where, at = frame_text(request.frame), point_words(point_name)
        add(J, names["jacobian"], "jacobian", f"The basic Jacobian [v; omega] at the {at}, in frame {where}")
        add(lowered_torques(chain, J, selected), names["joint_torques"], "joint_torques",
            f"Joint torques tau = J^T F holding a wrench F at the {at}, F in frame {where}",
            Argument("wrench", tuple(WRENCH_NAMES[r] for r in selected), "Wrench (force, moment) at the point"))
        add(lowered_kinematics(chain, request.frame, point), names["_kinematics"], "kinematics",
            "Point position, ^0_nR and ^0_kR (the self-test differentiates them numerically)")
        if acceleration:
            add(lowered_hessian(chain, request.frame, point, selected, strategy), names["hessian"], "hessian",
                f"The kinematic Hessian H[i, j, m] = dJ[i, j]/dq_m of ``{names['jacobian']}``")
            add(lowered_bias_acceleration(chain, request.frame, point, selected, strategy),
                names["bias_acceleration"], "bias_acceleration",
                f"The bias acceleration Jdot qdot of ``{names['jacobian']}`` (the acceleration at zero qddot)",
                Argument("qdot", rates, "Joint rates"))
        infos.append(JacobianInfo(
            jacobian=names["jacobian"], joint_torques=names["joint_torques"], manipulability=names["manipulability"],
            determinant=names["jacobian_determinant"] if len(selected) == model.dof else None,
            kinematics=names["_kinematics"], frame=where, point=point_name,
            point_values=tuple(float_literal(v.subs(model.defaults)) for v in point),  # type: ignore[arg-type]
            rows=selected, row_names=tuple(ROW_NAMES[r] for r in selected),
            wrench_names=tuple(WRENCH_NAMES[r] for r in selected),
            **({"hessian": names["hessian"], "bias_acceleration": names["bias_acceleration"],
                "manipulability_gradient": names["manipulability_gradient"]} if acceleration else {}),
        ))

    defined = {s.name for _, s in lowered_functions} | {i.manipulability for i in infos}
    defined |= {i.determinant for i in infos if i.determinant}
    defined |= {i.manipulability_gradient for i in infos if i.manipulability_gradient}
    for scalar_name, expr in (scalars or {}).items():
        check_identifier(scalar_name, "scalar function name", {**RESERVED, **{n: "a function" for n in defined}})
        if scalar_name.startswith("_") or scalar_name in {p.name for p in model.parameters}:
            raise CodegenError(f"scalar function name {scalar_name!r} is private or a parameter name")
        lowered = lower_function(angle_expansion(chain), [sp.sympify(expr)], (), (("q", model.q),),
                                 model.parameter_symbols, "given expression")
        add(lowered, scalar_name, "scalar", f"The scalar function {scalar_name}")
        defined.add(scalar_name)

    functions = tuple(spec.emit(chain, lowered, function, taken) for lowered, function in lowered_functions)
    extras = spec.extras(chain, lowered_functions, taken) if spec.extras is not None else {}
    exports = ({"PARAMETERS", "JOINTS", "ROBOT", "selftest", *spec.exports}
               | {f.name for f in functions if not f.name.startswith("_")}
               | {i.manipulability for i in infos} | {i.determinant for i in infos if i.determinant}
               | {i.manipulability_gradient for i in infos if i.manipulability_gradient})
    parameter_names = [p.name for p in model.parameters]
    parameter_lines = wrap_statement("    parameters = ", "(" + ", ".join(parameter_names)
                                     + ("," if len(parameter_names) == 1 else "") + ")")
    if command is None:
        loader, command_note = _robot_loader(robot if isinstance(robot, Robot) else model)  # chains are shared
        command = python_call(model, target, requests, scalars or {}, strategy, loader, acceleration)
        command_lines = comment_lines(command)
    else:
        command_lines = comment_lines(command, continuation=" \\")  # a shell line continues with a backslash
        source = robot.source if isinstance(robot, Robot) else model.source
        command_note = "in the folder it was run in" if _names_relative_file(source, command) else ""
    return ModuleDescription(
        target=target, template=spec.template, version=__version__, robot=model.name,
        convention=model.convention.value, dof=model.dof,
        joints=tuple((j.variable.name, j.type.value) for j in model.joints),
        parameters=tuple((p.name, float_literal(p.default)) for p in model.parameters),
        functions=functions, jacobians=tuple(infos),
        scalars=tuple(f.name for f in functions if f.kind == "scalar"),
        exports=tuple(_sorted_exports(exports)), command=command, command_lines=command_lines,
        command_note=command_note,
        title=spec.title, description_text=spec.description, nan_policy=spec.nan_policy,
        imports=tuple(sorted(set().union(*(f.uses for f in functions)) | set(spec.imports))),
        parameter_lines=tuple(parameter_lines), extras=extras, rates=rates,
    )


def _robot_loader(robot: Robot) -> tuple[str, str]:
    """How the header's Python call gets ``robot`` back, and a note when that needs saying.

    A catalog robot loads by name, a robot from a file by the file's path as it was given (the note says from which
    folder when it is relative) as long as loading it again gives the same robot; anything else (a mapping, a URDF
    that needed ``tip_link``) is written ``robot`` and the note says which robot that is.
    """
    candidates = [robot.name] if robot.name in catalog() else []
    candidates += [robot.source] if robot.source not in ("<mapping>", "<string>") else []
    for candidate in candidates:
        try:
            same = load_robot(candidate) == robot
        except SymjacError:
            continue
        if same:
            path = Path(candidate)
            relative = candidate not in catalog() and not path.is_absolute() and path.is_file()
            return f"symjac.load_robot({_string(candidate)})", "in the folder it was run in" if relative else ""
    origin = "a mapping" if robot.source in ("<mapping>", "<string>") else robot.source
    return "robot", f"robot: the Robot given to symjac.generate, from {origin}"


def _string(text: str) -> str:
    """A Python string literal for ``text`` in double quotes (the form the header's calls use)."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _names_relative_file(source: str, command: str) -> bool:
    """Whether the command line refers to the robot file, or writes its output, through a relative path."""
    try:
        words = shlex.split(command)
    except ValueError:
        return False
    outputs = [after for before, after in itertools.pairwise(words) if before in ("-o", "--output")]
    outputs += [word.split("=", 1)[1] for word in words if word.startswith("--output=")]
    paths = [source] if Path(source).is_file() and source in words else []
    return any(not Path(path).is_absolute() and path != "-" for path in paths + outputs)


def _sorted_exports(names: Iterable[str]) -> list[str]:
    """``__all__`` in the order ruff's RUF022 expects: SCREAMING_CASE, then CamelCase, then the rest."""
    def key(name: str) -> tuple[int, str]:
        if name.isupper():
            return (0, name)
        if name[:1].isupper():
            return (1, name)
        return (2, name)

    return sorted(names, key=key)


def generate(
    robot: Robot | Chain,
    target: str = "python",
    frames: Sequence[Frame] | Frame = (0,),
    points: Sequence[Point] | Point = ("wrist",),
    *,
    rows: Sequence[int] | None = None,
    jacobians: Sequence[JacobianRequest] | None = None,
    scalars: Mapping[str, sp.Expr] | None = None,
    strategy: Strategy = "fastest",
    command: str | None = None,
    acceleration: bool = False,
) -> str:
    r"""The source text of a numeric module for ``robot``: FK, Jacobians, torques, manipulability, self-test.

    Parameters
    ----------
    robot : Robot or Chain
    target : str
        One of :data:`~symjac.codegen.TARGETS` (``"python"``, ``"numpy"``, ``"lambdify"``, ``"c"``; see
        :mod:`symjac.codegen.backends`).
    frames : frame or sequence of frames
        Frames the Jacobians are expressed in (default {0}); every frame is combined with every point.
    points : point or sequence of points
        ``"wrist"`` (default), ``"tool"`` or three coordinates in frame {n}.
    rows : sequence of int, optional
        Task rows of the Jacobians (0..5 = v_x .. omega_z); default all six.
    jacobians : sequence of JacobianRequest, optional
        Explicit requests instead of ``frames`` x ``points``.
    scalars : mapping of str to sympy.Expr, optional
        Extra scalar functions of the joint variables and parameters, generated through the same pipeline (the
        place for a factored symbolic determinant: ``scalars={"det_factored": expr}``).
    strategy : "fastest", "raw" or "simplified"
        Which Jacobian expressions to start from: the candidate with fewest operations after CSE (default), the raw
        chain products only, or the compact textbook form only.
    command : str, optional
        How to regenerate the module, for its header: the command line that was typed (the CLI passes it; the
        header adds "in the folder it was run in" when it names a relative path). Default: the equivalent
        ``symjac.generate(...)`` call, which loads a catalog robot by name and a robot read from a file by the
        path it was read from; any other robot is written ``robot`` and the header says so.
    acceleration : bool
        Also generate, for every Jacobian ``jacobian<suffix>``, the acceleration-level functions with the same
        suffix: ``hessian<suffix>(q)`` (shape rows x n x n, ``H[i, j, m] = dJ[i, j]/dq_m``),
        ``bias_acceleration<suffix>(q, qdot)`` (``Jdot qdot``, one value per row) and
        ``manipulability_gradient<suffix>(q)`` (``dw/dq_m = w trace(J^+ dJ/dq_m)``, n values), all checked by the
        module's ``selftest`` against central differences of its own Jacobian. Off by default: the Hessian has
        rows x n x n entries, which would more than double the size of every module.

    Returns
    -------
    str
        The module source; identical input gives byte-identical output. The first Jacobian requested is always
        ``jacobian`` (with ``joint_torques``, ``manipulability``, ``jacobian_determinant`` and, with
        ``acceleration``, ``hessian``, ``bias_acceleration``, ``manipulability_gradient``); every other one adds
        the suffix ``_<frame>_<point>`` and, with ``rows``, ``_r<rows>``: ``jacobian_3_tool``, ``jacobian_0_p1``
        (``p1``, ``p2``: explicit points in the order given), ``hessian_0_wrist_r012``.

    Raises
    ------
    CodegenError
        For an unknown target or strategy, a name that cannot be used in generated code, an unsupported expression.
    FrameError
        For a frame or point the robot does not have.

    Examples
    --------
    >>> from symjac import load_robot
    >>> source = generate(load_robot("planar2r"), "python")
    >>> namespace = {}
    >>> exec(compile(source, "planar2r_jacobian.py", "exec"), namespace)
    >>> [[round(v, 6) for v in row] for row in namespace["jacobian"]([0.0, 1.5707963267948966], L1=1.0)[:2]]
    [[-0.4, -0.4], [1.0, 0.0]]
    """
    return render_module(describe(robot, target, frames, points, rows=rows, jacobians=jacobians, scalars=scalars,
                                  strategy=strategy, command=command, acceleration=acceleration))


def render_module(description: ModuleDescription) -> str:
    """Render a :class:`ModuleDescription` with its target's template; check the result's line lengths."""
    text = render_template(description.template, module=description)
    for number, line in enumerate(text.splitlines(), start=1):
        if len(line) > LINE_WIDTH or line != line.rstrip():
            raise CodegenError(f"internal error: generated line {number} is too long or has trailing spaces")
    return text


def write_module(path: str | os.PathLike[str], text: str) -> Path:
    """Write a generated module to ``path`` as ``symjac codegen -o`` does (:func:`symjac.files.write_text`).

    A regular file is replaced atomically (never a partial file) and keeps its permissions; a new one gets the umask's.
    """
    return write_text(path, text)
