"""What a generated module is asked to contain: Jacobian requests, validated before anything is derived or written.

Every name and number that reaches generated text passes through here first (robot and parameter names, point
coordinates, task rows); anything unusable raises :class:`~symjac.errors.CodegenError` with what and where.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal, get_args

import sympy as sp

from symjac.codegen.names import PYTHON_IDENTIFIERS, RESERVED, IdentifierRule
from symjac.codegen.printers import check_expression, float_literal
from symjac.errors import ArgumentError, CodegenError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import Point, check_row_indices, point_vector
from symjac.kinematics.memo import one_of
from symjac.model.ends import end_point
from symjac.model.robot import Robot

__all__ = [
    "RESERVED",
    "STRATEGIES",
    "JacobianRequest",
    "Strategy",
    "check_rows",
    "end_words",
    "frame_text",
    "function_labels",
    "point_text",
    "point_words",
    "python_call",
    "requests_from",
    "rows_of",
    "strategy_of",
    "validate_robot",
]

Strategy = Literal["fastest", "raw", "simplified"]
"""A lowering strategy (see :data:`STRATEGIES`)."""
STRATEGIES: tuple[str, ...] = get_args(Strategy)
"""Which expressions a generated function starts from: the fewest operations, raw chain products, or compact."""

strategy_of = one_of(STRATEGIES, "strategy")
"""The :func:`~symjac.kinematics.memo.memoized` normaliser of a lowering strategy: one of :data:`STRATEGIES`."""

@dataclass(frozen=True)
class JacobianRequest:
    """One Jacobian a generated module should contain.

    Parameters
    ----------
    frame : int or "world" or "tool"
        Frame {k} the Jacobian is expressed in.
    point : "tool", "flange", "wrist", "wrist_centre" or three coordinates in frame {n}, optional
        Where the linear velocity is taken (see :func:`symjac.kinematics.jacobian`). Default: the end of the chain,
        the origin of the frame the module's ``forward_kinematics`` ends at (the tool point when the robot has a
        tool, else the flange, the origin of {n}).
    rows : tuple of int, optional
        Task rows to keep, from 0..5 = v_x, v_y, v_z, omega_x, omega_y, omega_z (default all six). With as many rows
        as joints the Jacobian is square and the module gets a ``jacobian_determinant`` function.
    """

    frame: Frame = 0
    point: Point | None = None
    rows: tuple[int, ...] | None = None


def validate_robot(robot: Robot, identifiers: IdentifierRule = PYTHON_IDENTIFIERS, name: str | None = None) -> None:
    """Refuse a robot whose name, parameter names or defaults cannot appear in the target's generated code.

    ``name``, when given, is the module's name chosen instead of the robot's (``symjac codegen --name``).
    """
    if name is None:
        identifiers.check(robot.name, "robot name")
    else:
        identifiers.check(name, "module name")
    variables = {joint.variable.name for joint in robot.joints}
    for parameter in robot.parameters:
        identifiers.check(parameter.name, "parameter name", RESERVED)
        if parameter.name.startswith("_") or parameter.name in variables:
            raise CodegenError(f"parameter name {parameter.name!r} is private (leading '_') or a joint variable")
        float_literal(parameter.default)


def requests_from(
    chain: Chain, frames: Sequence[Frame] | Frame, points: Sequence[Point | None] | Point | None,
    rows: Sequence[int] | None,
    jacobians: Sequence[JacobianRequest] | None,
) -> list[JacobianRequest]:
    """The requests of a call: ``jacobians`` as given, else every frame with every point; frames checked."""
    if jacobians is not None:
        requests = list(jacobians)
        if not all(isinstance(r, JacobianRequest) for r in requests):
            raise CodegenError("jacobians must be a sequence of JacobianRequest")
    else:
        frame_list = [frames] if isinstance(frames, int | str) else list(frames)
        point_list: list[Point | None] = (
            [points] if points is None or isinstance(points, str) or _is_coordinates(points)  # type: ignore[list-item]
            else list(points))  # type: ignore[arg-type]
        requests = [JacobianRequest(f, p, None if rows is None else tuple(rows)) for f in frame_list
                    for p in point_list]
    for request in requests:
        chain.position(request.frame)  # FrameError with a clear message
    return requests


def _is_coordinates(points: object) -> bool:
    return (isinstance(points, Sequence) and len(points) == 3
            and all(not isinstance(p, str) and not isinstance(p, Sequence) for p in points))


def check_rows(rows: Sequence[int] | None) -> tuple[int, ...]:
    """The task rows as a tuple of distinct indices 0..5 (all six if ``rows`` is None)."""
    if rows is None:
        return tuple(range(6))
    try:
        return check_row_indices(rows)
    except ArgumentError as error:
        raise CodegenError(str(error)) from None


def rows_of(chain: Chain, rows: Sequence[int] | None) -> tuple[int, ...]:
    """:func:`check_rows` as a :func:`~symjac.kinematics.memo.memoized` normaliser (the chain is not needed)."""
    return check_rows(rows)


def point_text(robot: Robot, point: Point | None) -> tuple[str, tuple[sp.Expr, sp.Expr, sp.Expr]]:
    """A short text for the point (its name, or its coordinates) and its validated coordinates in frame {n}.

    ``None`` is the end of the chain, named as :func:`~symjac.model.ends.end_point` names it.
    """
    point = end_point(robot) if point is None else point
    coordinates = point_vector(robot, point)
    allowed = set(robot.parameter_symbols)
    for value in coordinates:
        check_expression(value)
        extra = value.free_symbols - allowed
        if extra:
            raise CodegenError(f"point coordinate {value} uses {', '.join(sorted(map(str, extra)))}, which is not a "
                               f"parameter of {robot.name}")
    if isinstance(point, str):
        return point, coordinates
    text = "(" + ", ".join(str(value) for value in coordinates) + ")"
    if len(text) > 32:  # keep comment and docstring lines short: the numbers at the default parameters
        text = "(" + ", ".join(f"{float(value.subs(robot.defaults)):.6g}" for value in coordinates) + ")"
    return text, coordinates


def point_words(text: str, n: int) -> str:
    """Which point :func:`point_text`'s ``text`` is, for a docstring sentence after "at" (``n`` the last frame).

    Examples
    --------
    >>> point_words("tool", 6), point_words("flange", 6), point_words("(0, 0, 1)", 2)
    ('the tool point', 'the origin of frame {6} (flange)', 'the point (0, 0, 1) of frame {2}')
    """
    if text in ("flange", "wrist"):
        return f"the origin of frame {{{n}}} (flange)"
    if text == "tool":
        return "the tool point"
    if text == "wrist_centre":
        return "the wrist centre"
    return f"the point {text} of frame {{{n}}}"


def end_words(robot: Robot) -> str:
    """The frame generated forward kinematics ends at: ``the tool frame``, or ``frame {n} (its origin the flange)``."""
    return "the tool frame" if robot.tool is not None else f"frame {{{robot.n_joints}}} (its origin the flange)"


def frame_text(frame: Frame) -> str:
    """``{3}`` for a DH frame, ``'tool'`` for a named one."""
    return f"{{{frame}}}" if isinstance(frame, int) else f"'{frame}'"


def function_labels(robot: Robot, requests: Sequence[JacobianRequest]) -> list[str]:
    """Function-name suffixes: none for the first request, ``_<frame>_<point>[_r<rows>]`` for every other one.

    The first Jacobian requested is always ``jacobian`` (and ``joint_torques``, ``manipulability``, ``hessian``,
    ...), however many follow, so code written against a one-Jacobian module keeps working when a frame is added.
    The others are named by frame, point and rows: ``_3_tool``, ``_0_wrist_r01`` (rows v_x, v_y), ``_0_p1`` (the
    first explicit point; ``p2`` the second distinct one, and so on).

    Raises
    ------
    CodegenError
        If two requests are the same Jacobian (same frame, point and rows).

    Examples
    --------
    >>> from symjac import load_robot
    >>> function_labels(load_robot("planar2r"), [JacobianRequest(0), JacobianRequest("tool", "flange", (0, 1))])
    ['', '_tool_flange_r01']
    """
    labels = []
    custom: dict[tuple[sp.Expr, ...], str] = {}
    for request in requests:
        frame = str(request.frame)
        if request.point is None or isinstance(request.point, str):
            point = end_point(robot) if request.point is None else request.point
        else:
            point = custom.setdefault(point_vector(robot, request.point), f"p{len(custom) + 1}")
        rows = "" if request.rows is None else "_r" + "".join(str(r) for r in request.rows)
        label = f"_{frame}_{point}{rows}"
        if label in labels:
            raise CodegenError(f"the Jacobian in frame {request.frame} at point {point} is requested twice")
        labels.append(label)
    return ["", *labels[1:]]


def python_call(
    robot: Robot, target: str, requests: Sequence[JacobianRequest], scalars: Mapping[str, sp.Expr], strategy: str,
    loader: str, acceleration: bool = False, name: str | None = None, dynamics: bool = False,
    identification: bool = False, inverse_kinematics: bool = False, numeric_ik: bool = False,
    free_joint: int | None = None,
) -> str:
    """The Python call that generates the module, for its header: ``symjac.generate(...)`` from the request data.

    ``loader`` is the Python expression that gives the robot back: ``symjac.load_robot("planar2r")`` for a catalog
    robot or one read from a file, ``robot`` for one the call cannot load (the header then says which it is).

    Examples
    --------
    >>> from symjac import load_robot
    >>> robot = load_robot("planar2r")
    >>> python_call(robot, "numpy", [JacobianRequest(0), JacobianRequest("tool", (1, 0, 0), (0, 1))], {}, "raw",
    ...             'symjac.load_robot("planar2r")')
    'symjac.generate(symjac.load_robot("planar2r"), "numpy", jacobians=[symjac.JacobianRequest(0), symjac.JacobianRequest("tool", (1, 0, 0), (0, 1))], strategy="raw")'
    """  # noqa: E501  # a doctest's expected output cannot be wrapped
    items = [_request_text(robot, request) for request in requests]
    parts = [loader, f'"{target}"', f"jacobians=[{', '.join(items)}]"]
    if scalars:
        parts.append("scalars={" + ", ".join(f'"{name}": {expr}' for name, expr in scalars.items()) + "}")
    if strategy != "fastest":
        parts.append(f'strategy="{strategy}"')
    if acceleration:
        parts.append("acceleration=True")
    if identification:
        parts.append("identification=True")
    elif dynamics:
        parts.append("dynamics=True")
    if inverse_kinematics:
        parts.append("inverse_kinematics=True")
    if numeric_ik:
        parts.append("numeric_ik=True")
    if free_joint is not None:
        parts.append(f"free_joint={free_joint}")
    if name is not None:
        parts.append(f'name="{name}"')
    return f"symjac.generate({', '.join(parts)})"


def _request_text(robot: Robot, request: JacobianRequest) -> str:
    frame = f'"{request.frame}"' if isinstance(request.frame, str) else str(request.frame)
    if request.point is None:
        point = "None"
    elif isinstance(request.point, str):
        point = f'"{request.point}"'
    else:
        point = "(" + ", ".join(str(v) for v in point_vector(robot, request.point)) + ")"
    if request.point is None and request.rows is None:
        return f"symjac.JacobianRequest({frame})"
    rows = "" if request.rows is None else f", {tuple(request.rows)}"
    return f"symjac.JacobianRequest({frame}, {point}{rows})"
