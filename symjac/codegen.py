r"""Generated numeric modules: forward kinematics, Jacobians, torques and manipulability as fast, dependency-free code.

A generated module is what a controller, a simulator or a script imports when it has no SymPy: small, readable,
correct (its own :func:`selftest` compares the Jacobian with central differences of its forward kinematics) and fast.

Targets
-------
``"python"``
    Standard library only (``math``), one configuration per call; results are nested lists.
``"numpy"``
    NumPy only, batched: ``q`` of shape ``(..., n)`` gives ``J`` of shape ``(..., 6, n)`` without a Python loop over
    configurations (blocks of configurations, split over threads for large batches).
``"lambdify"``
    SymPy + NumPy: the module rebuilds the expressions and calls :func:`sympy.lambdify` with CSE at import time.
``"c"``
    The NumPy module plus C kernels compiled at first import with the system C compiler into a CPython extension
    (cached per user); vectorised sine/cosine through glibc's libmvec where the CPU has AVX2. Without a compiler,
    headers or a writable cache it silently falls back to its NumPy functions (``BACKEND`` says which runs).

Pipeline (one function at a time)
----------------------------------
1. **Candidates.** For a Jacobian: the raw chain products differentiated, the raw cross-product form, the compact
   textbook form, and the latter two in a neighbouring frame rotated back. Simplified entries are not always faster
   (raw chain products won on Panda with an earlier simplifier), so nothing is assumed: every candidate is lowered
   and the one with the fewest operations after CSE is kept (ties: the first).
2. **Angles.** Every sine/cosine of a joint-angle combination is expanded by the angle-addition formulas into the
   sines and cosines of the joint angles themselves (partial sums nested, so CSE shares them): a module evaluates
   exactly one ``sin`` and one ``cos`` per revolute joint. Numeric subexpressions are folded to floats.
3. **Lowering.** Flatten, check that every free symbol is an argument (the error names the others),
   ``sympy.cse(order="canonical")``.
4. **Printing.** Printer subclasses map symbols to validated names (:mod:`symjac.codegen_printers`).
5. **Rendering.** Frozen descriptions (:class:`GeneratedFunction`, :class:`ModuleDescription`) fill one template
   per target through the single jinja2 environment (:mod:`symjac.resources`).

Every name and number that reaches the generated text is validated first; anything else raises
:class:`CodegenError` before a file is touched, and :func:`write_module` replaces a file atomically.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property, lru_cache
from pathlib import Path
from typing import Any, Literal, get_args

import sympy as sp

from symjac._version import __version__
from symjac.angles import AngleExpansion
from symjac.chain import Frame, chain_of
from symjac.codegen_printers import (
    CPrinter,
    NumPyPrinter,
    PythonPrinter,
    SymPyPrinter,
    check_expression,
    check_identifier,
    float_literal,
    layout,
)
from symjac.errors import CodegenError
from symjac.files import write_text
from symjac.jacobian import ROW_NAMES, Point, jacobian, point_vector
from symjac.model import Robot
from symjac.resources import render_template
from symjac.transforms import block_rotation

Target = Literal["python", "numpy", "lambdify", "c"]
Strategy = Literal["fastest", "raw", "simplified"]

TARGETS: tuple[str, ...] = get_args(Target)
STRATEGIES: tuple[str, ...] = get_args(Strategy)
TEMPLATES: dict[str, str] = {
    "python": "python_module.py.j2",
    "numpy": "numpy_module.py.j2",
    "lambdify": "lambdify_module.py.j2",
    "c": "c_module.py.j2",
}
WRENCH_NAMES: tuple[str, ...] = ("f_x", "f_y", "f_z", "n_x", "n_y", "n_z")
LINE_WIDTH = 120

__all__ = [
    "STRATEGIES",
    "TARGETS",
    "CodegenError",
    "GeneratedFunction",
    "JacobianRequest",
    "ModuleDescription",
    "describe",
    "generate",
    "render_module",
    "write_module",
]

# Names every generated module defines or imports for itself, with the reason a parameter may not take them.
_RESERVED: dict[str, str] = {
    **{name: "an argument of the generated functions" for name in ("q", "out", "wrench", "samples", "seed",
                                                                    "tolerance", "threads")},
    **{name: "an import of the generated module" for name in ("annotations", "np", "sympy", "math", "os", "sys",
                                                               "cos", "sin", "sqrt", "pi", "random", "threading",
                                                               "importlib", "sysconfig", "hashlib", "shutil",
                                                               "subprocess", "tempfile", "Path", "Sequence",
                                                               "ArrayLike", "MappingProxyType", "Any")},
    **{name: "a constant of the generated module" for name in ("PARAMETERS", "JOINTS", "ROBOT", "CONVENTION",
                                                                "SYMJAC_VERSION", "JACOBIANS", "BACKEND", "THREADS",
                                                                "BUILD_ERROR", "DOF")},
    **{name: "a function of the generated module" for name in ("selftest", "forward_kinematics", "jacobian",
                                                                "joint_torques", "manipulability",
                                                                "jacobian_determinant")},
}


# --- requests ---------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class JacobianRequest:
    """One Jacobian a generated module should contain.

    Parameters
    ----------
    frame : int or "world" or "tool"
        Frame {k} the Jacobian is expressed in.
    point : "wrist", "tool" or three coordinates in frame {n}
        Where the linear velocity is taken (see :func:`symjac.jacobian`).
    rows : tuple of int, optional
        Task rows to keep, from 0..5 = v_x, v_y, v_z, omega_x, omega_y, omega_z (default all six). With as many rows
        as joints the Jacobian is square and the module gets a ``jacobian_determinant`` function.
    """

    frame: Frame = 0
    point: Point = "wrist"
    rows: tuple[int, ...] | None = None


# --- frozen descriptions ------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Argument:
    """An array argument of a generated function: its name and the names of its entries."""

    name: str
    entries: tuple[str, ...]
    description: str


@dataclass(frozen=True)
class GeneratedFunction:
    """Everything a template needs to lay out one generated function, already printed for its target.

    ``body`` holds the statements (indented for the template), ``outputs`` the printed value of every entry in
    row-major order of ``shape`` (constant entries included), ``op_count`` the arithmetic operations per
    configuration after CSE (``sympy.count_ops``) and ``trig_count`` the sine and cosine evaluations.
    """

    name: str
    kind: Literal["forward_kinematics", "jacobian", "joint_torques", "scalar", "kinematics"]
    summary: str
    arguments: tuple[Argument, ...]
    shape: tuple[int, ...]
    op_count: int
    trig_count: int
    origin: str
    body: tuple[str, ...]
    outputs: tuple[str, ...]
    output_lines: tuple[str, ...] = ()
    constant: tuple[bool, ...] = ()
    uses: tuple[str, ...] = ()

    @property
    def kernel_name(self) -> str:
        """Name of the block kernel (NumPy) or C function that evaluates it."""
        return f"_{self.name.lstrip('_')}_kernel"

    @property
    def shape_literal(self) -> str:
        """The output shape as Python source: ``(6, 7)``."""
        return _tuple_literal(str(extent) for extent in self.shape) if self.shape else "()"

    @property
    def inputs_literal(self) -> str:
        """``((q, 6, "q"), (wrench, 6, "wrench"))``: each array argument, its length and its name."""
        return _tuple_literal(f'({a.name}, {len(a.entries)}, "{a.name}")' for a in self.arguments)

    def call_lines(self, head: str, first: str) -> list[str]:
        """``head(first, inputs, shape, out, parameters)`` laid out within the line width (one line if it fits)."""
        arguments = f"{first}, {self.inputs_literal}, {self.shape_literal}, out, parameters"
        line = f"{head}({arguments})"
        if len(line) <= LINE_WIDTH:
            return [line]
        indent = " " * (len(head) - len(head.lstrip()))
        return [f"{head}(", *layout(f"{indent}    ", arguments, ",", width=LINE_WIDTH, language="c"), f"{indent})"]

    @property
    def lengths_literal(self) -> str:
        """The lengths of the array arguments as Python source: ``(6, 6)``."""
        return _tuple_literal(str(len(a.entries)) for a in self.arguments)

    @property
    def size(self) -> int:
        """Number of output entries."""
        size = 1
        for extent in self.shape:
            size *= extent
        return size


@dataclass(frozen=True)
class JacobianInfo:
    """Names and meaning of the functions generated for one :class:`JacobianRequest`."""

    jacobian: str
    joint_torques: str
    manipulability: str
    determinant: str | None
    kinematics: str
    frame: str
    point: str
    point_values: tuple[str, str, str]
    rows: tuple[int, ...]
    row_names: tuple[str, ...]
    wrench_names: tuple[str, ...]


@dataclass(frozen=True)
class ModuleDescription:
    """The whole generated module as data: what :func:`generate` renders."""

    target: str
    template: str
    version: str
    robot: str
    convention: str
    dof: int
    joints: tuple[tuple[str, str], ...]
    parameters: tuple[tuple[str, str], ...]
    functions: tuple[GeneratedFunction, ...]
    jacobians: tuple[JacobianInfo, ...]
    scalars: tuple[str, ...]
    exports: tuple[str, ...]
    command: str
    title: str
    description_text: str
    nan_policy: str
    imports: tuple[str, ...] = ()
    parameter_lines: tuple[str, ...] = ()
    c_source: str = ""
    c_module: str = ""

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Parameter names, in robot-file order."""
        return tuple(name for name, _ in self.parameters)

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Joint variable names, in chain order."""
        return tuple(name for name, _ in self.joints)

    @property
    def revolute(self) -> tuple[bool, ...]:
        """Whether each joint is revolute."""
        return tuple(kind == "revolute" for _, kind in self.joints)

    @property
    def joint_names_text(self) -> str:
        """``"theta1 theta2"``: the joint names as one Python string literal."""
        return '"' + " ".join(self.joint_names) + '"'

    @property
    def parameter_names_text(self) -> str:
        """``"a2 d3"``: the parameter names as one Python string literal."""
        return '"' + " ".join(self.parameter_names) + '"'

    @property
    def joints_literal(self) -> str:
        """``("theta1", "theta2")`` as Python source."""
        return _tuple_literal(f'"{name}"' for name in self.joint_names)

    @property
    def revolute_literal(self) -> str:
        """``(True, False)`` as Python source."""
        return _tuple_literal(str(flag) for flag in self.revolute)


def _tuple_literal(items: Iterable[str]) -> str:
    entries = list(items)
    return f"({entries[0]},)" if len(entries) == 1 else f"({', '.join(entries)})"


# --- lowering --------------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Lowered:
    """One function as SymPy data after CSE (target-independent)."""

    inputs: tuple[tuple[str, tuple[sp.Symbol, ...]], ...]
    angles: tuple[tuple[sp.Symbol, sp.Symbol, sp.Expr], ...]
    temporaries: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: tuple[sp.Expr, ...]
    expanded: tuple[sp.Expr, ...]
    shape: tuple[int, ...]
    op_count: int
    origin: str

    @cached_property
    def used_symbols(self) -> set[sp.Symbol]:
        """Every symbol the evaluation reads: arguments, sines and cosines, and the variables in the angles."""
        exprs = [e for _, e in self.temporaries] + list(self.outputs) + [a for _, _, a in self.angles]
        return set().union(*(e.free_symbols for e in exprs))

    @property
    def trig_count(self) -> int:
        """Sines and cosines evaluated per configuration."""
        used = self.used_symbols
        return sum((s in used) + (c in used) for s, c, _ in self.angles)

    @property
    def cost(self) -> int:
        """What candidate selection minimises: operations plus one per sine and cosine."""
        return self.op_count + self.trig_count


def lower(
    outputs: Sequence[sp.Expr] | sp.MatrixBase,
    arguments: Iterable[sp.Symbol],
) -> tuple[tuple[tuple[sp.Symbol, sp.Expr], ...], tuple[sp.Expr, ...]]:
    """Flatten ``outputs``, check every free symbol is one of ``arguments``, and apply canonical CSE.

    Returns
    -------
    temporaries : tuple of (Symbol, Expr)
        In evaluation order; the symbols are ``_x0, _x1, ...``.
    outputs : tuple of Expr
        The flattened outputs in terms of arguments and temporaries.

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> lower([sp.sin(x) * y, sp.sin(x) * y + 1], [x, y])
    (((_x0, y*sin(x)),), (_x0, _x0 + 1))
    >>> lower([x + y], [x])
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: expressions depend on y, which is not an argument (arguments: x)
    """
    flat = list(outputs)
    allowed = set(arguments)
    unknown = set().union(*(sp.sympify(e).free_symbols for e in flat)) - allowed if flat else set()
    if unknown:
        names = ", ".join(sorted(map(str, unknown)))
        known = ", ".join(sorted(map(str, allowed))) or "none"
        raise CodegenError(f"expressions depend on {names}, which is not an argument (arguments: {known})")
    for expr in flat:
        check_expression(sp.sympify(expr))
    temporaries, reduced = sp.cse(flat, symbols=sp.numbered_symbols("_x", real=True), order="canonical")
    return tuple(temporaries), tuple(reduced)


def _lower_function(
    angles: AngleExpansion,
    exprs: Sequence[sp.Expr],
    shape: tuple[int, ...],
    inputs: tuple[tuple[str, tuple[sp.Symbol, ...]], ...],
    parameters: tuple[sp.Symbol, ...],
    origin: str,
    expanded: bool = False,
) -> _Lowered:
    flat = [sp.sympify(e) for e in exprs] if expanded else [angles.expand(sp.sympify(e)) for e in exprs]
    arguments = {s for _, symbols in inputs for s in symbols} | set(parameters) | set(angles.sines)
    arguments |= set(angles.cosines)
    temporaries, outputs = lower(flat, arguments)
    used = set().union(*(e.free_symbols for _, e in temporaries), *(e.free_symbols for e in outputs))
    angle_list = tuple((s, c, a) for s, c, a in zip(angles.sines, angles.cosines, angles.angles, strict=True)
                       if s in used or c in used)
    op_count = sum(int(sp.count_ops(e)) for _, e in temporaries) + sum(int(sp.count_ops(e)) for e in outputs)
    return _Lowered(inputs, angle_list, temporaries, outputs, tuple(flat), shape, op_count, origin)


def _frame_text(frame: Frame) -> str:
    return f"{{{frame}}}" if isinstance(frame, int) else f"'{frame}'"


def _jacobian_candidates(
    robot: Robot, frame: Frame, point: tuple[sp.Expr, ...], strategy: str
) -> Iterator[tuple[str, sp.Matrix]]:
    chain = chain_of(robot)
    where = _frame_text(frame)
    if strategy in ("fastest", "raw"):
        yield "raw chain products, differentiated", jacobian(robot, frame, point, "differentiation", simplify=False)
    if strategy == "raw":
        return
    yield "compact (simplified) Jacobian", jacobian(robot, frame, point, simplify=True)
    if strategy == "simplified":
        return
    yield "raw chain products, cross-product form", jacobian(robot, frame, point, "cross_product", simplify=False)
    for via in (0, 1):
        if via > chain.n or chain.position(frame) == via:
            continue
        rotation = block_rotation(chain.rotation(frame, via))
        yield (f"compact Jacobian in frame {{{via}}}, rotated into {where}",
               rotation * jacobian(robot, via, point, simplify=True))
        yield (f"raw cross-product form in frame {{{via}}}, rotated into {where}",
               rotation * jacobian(robot, via, point, "cross_product", simplify=False))


@lru_cache(maxsize=128)
def _lowered_jacobian(
    robot: Robot, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> _Lowered:
    angles = _angles(robot)
    q = ("q", robot.q)
    best: _Lowered | None = None
    for origin, J in _jacobian_candidates(robot, frame, point, strategy):
        selected = [J[r, c] for r in rows for c in range(robot.dof)]
        candidate = _lower_function(angles, selected, (len(rows), robot.dof), (q,), robot.parameter_symbols, origin)
        if best is None or candidate.cost < best.cost:
            best = candidate
    assert best is not None  # every strategy yields at least one candidate
    return best


@lru_cache(maxsize=32)
def _angles(robot: Robot) -> AngleExpansion:
    revolute = [joint for joint in robot.joints if joint.is_revolute]
    return AngleExpansion(tuple(j.variable for j in revolute), tuple(j.angle for j in revolute),
                          tuple(j.index for j in revolute))


@lru_cache(maxsize=32)
def _lowered_forward_kinematics(robot: Robot, strategy: str) -> _Lowered:
    chain = chain_of(robot)
    candidates = []
    if strategy in ("fastest", "raw"):
        candidates.append(("raw chain product", chain.transform(0, "tool")))
    if strategy in ("fastest", "simplified"):
        candidates.append(("compact (simplified) transform", chain.simplified_transform(0, "tool")))
    lowered = [_lower_function(_angles(robot), list(T), (4, 4), (("q", robot.q),), robot.parameter_symbols, origin)
               for origin, T in candidates]
    return min(lowered, key=lambda candidate: candidate.cost)


def _lowered_kinematics(robot: Robot, frame: Frame, point: tuple[sp.Expr, ...]) -> _Lowered:
    """Point position in {0}, ^0_nR and ^0_kR (21 values): what the self-test differentiates numerically."""
    chain = chain_of(robot)
    T_0_n = chain.transform(0, chain.n)
    x_P = T_0_n[:3, :3] * sp.Matrix(point) + T_0_n[:3, 3]
    values = [*x_P, *T_0_n[:3, :3], *chain.rotation(0, frame)]
    return _lower_function(_angles(robot), values, (21,), (("q", robot.q),), robot.parameter_symbols,
                           "raw chain products")


def _lowered_torques(robot: Robot, J: _Lowered, rows: tuple[int, ...]) -> _Lowered:
    wrench = tuple(sp.Symbol(f"_F{r}", real=True) for r in rows)
    n = robot.dof
    tau = [sum((J.expanded[k * n + i] * wrench[k] for k in range(len(rows))), sp.S.Zero) for i in range(n)]
    return _lower_function(_angles(robot), tau, (n,), (("q", robot.q), ("wrench", wrench)), robot.parameter_symbols,
                           f"J^T F from the Jacobian ({J.origin})", expanded=True)


# --- names -----------------------------------------------------------------------------------------------------------


class _Names:
    """Printed names for a function's symbols: validated robot names, fresh names for everything generated."""

    def __init__(self, robot: Robot, taken: Iterable[str]):
        self.taken = set(taken)
        self.mapping: dict[sp.Symbol, str] = {}
        for symbol in (*robot.q, *robot.parameter_symbols):
            self.mapping[symbol] = symbol.name
            self.taken.add(symbol.name)

    def fresh(self, symbol: sp.Symbol, base: str) -> str:
        if symbol in self.mapping:
            return self.mapping[symbol]
        name = base
        while name in self.taken:
            name = f"{name}_"
        self.taken.add(name)
        self.mapping[symbol] = name
        return name


def _symbol_names(robot: Robot, lowered: _Lowered, taken: Iterable[str]) -> _Names:
    names = _Names(robot, taken)
    joint_index = {j.variable: j.index for j in robot.joints}
    for sine, cosine, angle in lowered.angles:
        index = next(joint_index[v] for v in angle.free_symbols if v in joint_index)
        names.fresh(sine, f"s{index}")
        names.fresh(cosine, f"c{index}")
    for argument, symbols in lowered.inputs:
        if argument == "wrench":
            for symbol, label in zip(symbols, lowered_wrench_labels(symbols), strict=True):
                names.fresh(symbol, label)
    for k, (symbol, _) in enumerate(lowered.temporaries):
        names.fresh(symbol, f"x{k}")
    return names


def lowered_wrench_labels(symbols: Sequence[sp.Symbol]) -> list[str]:
    """``f_x .. n_z`` for the wrench symbols ``_F0 .. _F5`` (the row each multiplies)."""
    return [WRENCH_NAMES[int(s.name.removeprefix("_F"))] for s in symbols]


# --- printing per target -------------------------------------------------------------------------------------------


def _entry_names(lowered: _Lowered, names: _Names, symbols: Sequence[sp.Symbol]) -> list[str]:
    """Names to unpack an argument into; entries the function never reads get a leading underscore (ruff RUF059)."""
    used = lowered.used_symbols
    return [names.mapping[s] if s in used else f"_{names.mapping[s]}" for s in symbols]


def _unpack(names: Sequence[str], value: str, indent: str) -> list[str]:
    """``a, b, c = value``, or a parenthesised target list over several lines if that is too long."""
    line = f"{indent}{', '.join(names)}{',' if len(names) == 1 else ''} = {value}"
    if len(line) <= LINE_WIDTH:
        return [line]
    lines = [f"{indent}("]
    lines += layout(f"{indent}    ", ", ".join(names), ",", width=LINE_WIDTH)
    lines.append(f"{indent}) = {value}")
    return lines


def _input_lines(robot: Robot, lowered: _Lowered, names: _Names, indent: str) -> list[str]:
    """Unpack the argument rows (and the parameters) into the generated local names."""
    lines: list[str] = []
    for argument, symbols in lowered.inputs:
        lines += _unpack(_entry_names(lowered, names, symbols), argument, indent)
    if robot.parameters:
        lines += _unpack(_entry_names(lowered, names, robot.parameter_symbols), "parameters", indent)
    return lines


def _angle_lines(lowered: _Lowered, names: _Names, printer: Any, indent: str, module: str,
                 pair: str | None = None) -> list[str]:
    """One sine and one cosine per joint angle the expressions use (``pair(a)`` gives both at once if set)."""
    lines: list[str] = []
    used = lowered.used_symbols
    for sine, cosine, angle in lowered.angles:
        text = printer.doprint(angle)
        if pair is not None and sine in used and cosine in used:
            lines.append(f"{indent}{names.mapping[sine]}, {names.mapping[cosine]} = {pair}({text})")
            continue
        if sine in used:
            lines.append(f"{indent}{names.mapping[sine]} = {module}sin({text})")
        if cosine in used:
            lines.append(f"{indent}{names.mapping[cosine]} = {module}cos({text})")
    return lines


def _temporary_lines(lowered: _Lowered, names: _Names, printer: Any, indent: str) -> list[str]:
    """The common subexpressions, one assignment each, in CSE order."""
    lines: list[str] = []
    for symbol, expr in lowered.temporaries:
        lines += layout(f"{indent}{names.mapping[symbol]} = ", printer.doprint(expr), width=LINE_WIDTH)
    return lines


def _python_function(robot: Robot, lowered: _Lowered, name: str, kind: str, summary: str,
                     arguments: tuple[Argument, ...], taken: Iterable[str], indent: str = "    ") -> GeneratedFunction:
    names = _symbol_names(robot, lowered, taken)
    printer = PythonPrinter(names.mapping)
    body: list[str] = []
    for argument, symbols in lowered.inputs:
        body.append(f"{indent}try:")
        body += _unpack(_entry_names(lowered, names, symbols), argument, indent + "    ")
        body.append(f"{indent}except (TypeError, ValueError):")
        body.append(f'{indent}    raise ValueError(_length_error("{argument}", {argument}, {len(symbols)})) from None')
    body += _angle_lines(lowered, names, printer, indent, "")
    body += _temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    output_lines = _python_return(outputs, lowered.shape, indent)
    return _function(lowered, name, kind, summary, arguments, body, outputs, output_lines, printer.used)


def _python_return(outputs: Sequence[str], shape: tuple[int, ...], indent: str) -> tuple[str, ...]:
    """``return (...)``: a float, a tuple, or a tuple of row tuples (tuples build faster than lists)."""
    if len(shape) == 0:
        return tuple(layout(f"{indent}return ", outputs[0], width=LINE_WIDTH))
    if len(shape) == 1:
        single = f"{indent}return {_tuple_literal(outputs)}"
        if len(single) <= LINE_WIDTH:
            return (single,)
        lines = [f"{indent}return ("]
        for value in outputs:
            lines += layout(f"{indent}    ", value, ",", width=LINE_WIDTH)
        return (*lines, f"{indent})")
    rows, columns = shape
    lines = [f"{indent}return ("]
    for r in range(rows):
        lines += layout(f"{indent}    ", _tuple_literal(outputs[r * columns:(r + 1) * columns]), ",", width=LINE_WIDTH)
    return (*lines, f"{indent})")


def _function(lowered: _Lowered, name: str, kind: str, summary: str, arguments: tuple[Argument, ...],
              body: Sequence[str], outputs: Sequence[str], output_lines: Sequence[str], uses: Iterable[str]
              ) -> GeneratedFunction:
    constant = tuple(not e.free_symbols for e in lowered.outputs)
    used = set(uses) | ({"sin", "cos"} if lowered.angles else set())
    return GeneratedFunction(
        name=name, kind=kind, summary=summary, arguments=arguments, shape=lowered.shape,  # type: ignore[arg-type]
        op_count=lowered.op_count, trig_count=lowered.trig_count, origin=lowered.origin, body=tuple(body),
        outputs=tuple(outputs), output_lines=tuple(output_lines), constant=constant, uses=tuple(sorted(used)),
    )


def _numpy_function(robot: Robot, lowered: _Lowered, name: str, kind: str, summary: str,
                    arguments: tuple[Argument, ...], taken: Iterable[str]) -> GeneratedFunction:
    """The block kernel: inputs are rows ``(size, m)``, ``out`` is ``shape + (m,)``; every write is contiguous."""
    indent = "    "
    names = _symbol_names(robot, lowered, taken)
    printer = NumPyPrinter(names.mapping)
    body = _input_lines(robot, lowered, names, indent)
    body += _angle_lines(lowered, names, printer, indent, "np.", pair="_sincos")  # one half-angle tangent for both
    body += _temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    lines: list[str] = []
    for index, value in zip(_indices(lowered.shape), outputs, strict=True):
        lines += layout(f"{indent}out[{index}] = ", value, width=LINE_WIDTH)
    return _function(lowered, name, kind, summary, arguments, body, outputs, lines, printer.used)


def _indices(shape: tuple[int, ...]) -> list[str]:
    if not shape:
        return ["..."]
    if len(shape) == 1:
        return [str(i) for i in range(shape[0])]
    rows, columns = shape
    return [f"{r}, {c}" for r in range(rows) for c in range(columns)]


def _sympy_function(robot: Robot, lowered: _Lowered, name: str, kind: str, summary: str,
                    arguments: tuple[Argument, ...], taken: Iterable[str]) -> GeneratedFunction:
    """Statements that rebuild the CSE'd expressions in SymPy (the lambdify target lambdifies them at import)."""
    indent = "    "
    names = _symbol_names(robot, lowered, taken)
    printer = SymPyPrinter(names.mapping)
    body = _input_lines(robot, lowered, names, indent)
    body += _angle_lines(lowered, names, printer, indent, "sympy.")
    body += _temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    lines = [f"{indent}return ["]
    for value in outputs:
        lines += layout(f"{indent}    ", value, ",", width=LINE_WIDTH)
    lines.append(f"{indent}]")
    return _function(lowered, name, kind, summary, arguments, body, outputs, lines, ())


def _c_function(robot: Robot, lowered: _Lowered, name: str, kind: str, summary: str,
                arguments: tuple[Argument, ...], taken: Iterable[str]) -> GeneratedFunction:
    """The per-configuration C body: angles come as ``s[j]``/``c[j]`` (vectorised before), outputs go to ``o[k]``."""
    indent = "        "
    names = _symbol_names(robot, lowered, set(taken) | _C_KEYWORDS)
    mapping = dict(names.mapping)
    for argument, symbols in lowered.inputs:
        pointer = "x" if argument == "q" else "wk"
        for k, symbol in enumerate(symbols):
            mapping[symbol] = f"{pointer}[{k}]"
    for parameter_index, symbol in enumerate(robot.parameter_symbols):
        mapping[symbol] = f"p[{parameter_index}]"
    angle_index = {a: k for k, a in enumerate(_angles(robot).angles)}
    for sine, cosine, angle in lowered.angles:
        mapping[sine] = f"S[{angle_index[angle]}][k]"
        mapping[cosine] = f"C[{angle_index[angle]}][k]"
    printer = CPrinter(mapping)
    body: list[str] = []
    for symbol, expr in lowered.temporaries:
        body += layout(f"{indent}const double {mapping[symbol]} = ", printer.doprint(expr), ";", width=LINE_WIDTH,
                       language="c")
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    lines: list[str] = []
    for k, value in enumerate(outputs):
        lines += layout(f"{indent}o[{k}] = ", value, ";", width=LINE_WIDTH, language="c")
    return _function(lowered, name, kind, summary, arguments, body, outputs, lines, printer.used)


_C_KEYWORDS = frozenset((
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum", "extern",
    "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return", "short", "signed",
    "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void", "volatile", "while",
    "x", "w", "wk", "p", "o", "k", "q", "out", "S", "C", "m", "A",  # names of the kernel's own locals
))


# --- the module ------------------------------------------------------------------------------------------------------


def _validate_robot(robot: Robot) -> None:
    if not isinstance(robot, Robot):
        raise CodegenError(f"expected a symjac Robot, got {type(robot).__name__}")
    check_identifier(robot.name, "robot name")
    variables = {joint.variable.name for joint in robot.joints}
    for parameter in robot.parameters:
        check_identifier(parameter.name, "parameter name", _RESERVED)
        if parameter.name.startswith("_") or parameter.name in variables:
            raise CodegenError(f"parameter name {parameter.name!r} is private (leading '_') or a joint variable")
        float_literal(parameter.default)


def _point_text(robot: Robot, point: Point) -> tuple[str, tuple[sp.Expr, sp.Expr, sp.Expr]]:
    """The point's coordinates in frame {n} (validated) and a short text for comments and docstrings."""
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
    if len(text) > 48:  # keep comment and docstring lines short: the numbers at the default parameters
        text = "(" + ", ".join(f"{float(value.subs(robot.defaults)):.6g}" for value in coordinates) + ")"
    return text, coordinates


def _check_rows(rows: Sequence[int] | None) -> tuple[int, ...]:
    if rows is None:
        return tuple(range(6))
    values = tuple(rows)
    if not values or any(isinstance(r, bool) or not isinstance(r, int) or not 0 <= r < 6 for r in values):
        raise CodegenError(f"rows must be a non-empty sequence of row numbers 0..5 "
                           f"({', '.join(ROW_NAMES)}), got {rows!r}")
    if len(set(values)) != len(values):
        raise CodegenError(f"rows must not repeat a row, got {rows!r}")
    return values


def _requests(
    robot: Robot, frames: Sequence[Frame] | Frame, points: Sequence[Point] | Point, rows: Sequence[int] | None,
    jacobians: Sequence[JacobianRequest] | None,
) -> list[JacobianRequest]:
    if jacobians is not None:
        requests = list(jacobians)
        if not all(isinstance(r, JacobianRequest) for r in requests):
            raise CodegenError("jacobians must be a sequence of JacobianRequest")
    else:
        frame_list = [frames] if isinstance(frames, int | str) else list(frames)
        point_list: list[Point] = ([points] if isinstance(points, str) or _is_coordinates(points)  # type: ignore[list-item]
                                   else list(points))  # type: ignore[arg-type]
        requests = [JacobianRequest(f, p, None if rows is None else tuple(rows)) for f in frame_list
                    for p in point_list]
    chain = chain_of(robot)
    for request in requests:
        chain.position(request.frame)  # FrameError with a clear message
    return requests


def _is_coordinates(points: object) -> bool:
    return (isinstance(points, Sequence) and len(points) == 3
            and all(not isinstance(p, str) and not isinstance(p, Sequence) for p in points))


def describe(
    robot: Robot,
    target: Target = "python",
    frames: Sequence[Frame] | Frame = (0,),
    points: Sequence[Point] | Point = ("wrist",),
    *,
    rows: Sequence[int] | None = None,
    jacobians: Sequence[JacobianRequest] | None = None,
    scalars: Mapping[str, sp.Expr] | None = None,
    strategy: Strategy = "fastest",
) -> ModuleDescription:
    """The frozen description of the module :func:`generate` renders (see there for the parameters)."""
    if target not in TARGETS:
        raise CodegenError(f"unknown target {target!r}; choose one of {', '.join(TARGETS)}")
    if strategy not in STRATEGIES:
        raise CodegenError(f"unknown strategy {strategy!r}; choose one of {', '.join(STRATEGIES)}")
    _validate_robot(robot)
    requests = _requests(robot, frames, points, rows, jacobians)
    if not requests:
        raise CodegenError("at least one Jacobian (frame and point) must be requested")

    printer = {"python": _python_function, "numpy": _numpy_function, "lambdify": _sympy_function,
               "c": _numpy_function}[target]
    taken = set(_RESERVED) | {p.name for p in robot.parameters}
    q_argument = Argument("q", tuple(s.name for s in robot.q), "Joint values")
    functions: list[GeneratedFunction] = []
    c_functions: list[GeneratedFunction] = []
    infos: list[JacobianInfo] = []

    def add(lowered: _Lowered, name: str, kind: str, summary: str, arguments: tuple[Argument, ...]) -> None:
        functions.append(printer(robot, lowered, name, kind, summary, arguments, taken))
        if target == "c" and kind != "kinematics":
            c_functions.append(_c_function(robot, lowered, name, kind, summary, arguments, taken))

    fk = _lowered_forward_kinematics(robot, strategy)
    add(fk, "forward_kinematics", "forward_kinematics", "The pose of the tool frame in frame {0}", (q_argument,))

    labels = _labels(robot, requests)
    seen: set[str] = set()
    for request, label in zip(requests, labels, strict=True):
        point_text, point = _point_text(robot, request.point)
        selected = _check_rows(request.rows)
        names = {kind: f"{kind}{label}" for kind in ("jacobian", "joint_torques", "manipulability",
                                                      "jacobian_determinant", "_kinematics")}
        if names["jacobian"] in seen:
            raise CodegenError(f"the Jacobian in frame {request.frame} at point {point_text} is requested twice")
        seen.add(names["jacobian"])
        J = _lowered_jacobian(robot, request.frame, point, selected, strategy)
        frame_text = _frame_text(request.frame)
        add(J, names["jacobian"], "jacobian",
            f"The basic Jacobian [v; omega] at the {_point_words(point_text)}, in frame {frame_text}", (q_argument,))
        wrench = Argument("wrench", tuple(WRENCH_NAMES[r] for r in selected), "Wrench (force, moment) at the point")
        add(_lowered_torques(robot, J, selected), names["joint_torques"], "joint_torques",
            f"Joint torques tau = J^T F holding a wrench F at the {_point_words(point_text)}, F in frame {frame_text}",
            (q_argument, wrench))
        add(_lowered_kinematics(robot, request.frame, point), names["_kinematics"], "kinematics",
            "Point position, ^0_nR and ^0_kR (the self-test differentiates them numerically)", (q_argument,))
        infos.append(JacobianInfo(
            jacobian=names["jacobian"], joint_torques=names["joint_torques"], manipulability=names["manipulability"],
            determinant=names["jacobian_determinant"] if len(selected) == robot.dof else None,
            kinematics=names["_kinematics"], frame=frame_text, point=point_text,
            point_values=tuple(float_literal(v.subs(robot.defaults)) for v in point),  # type: ignore[arg-type]
            rows=selected, row_names=tuple(ROW_NAMES[r] for r in selected),
            wrench_names=tuple(WRENCH_NAMES[r] for r in selected),
        ))

    scalar_names: list[str] = []
    defined = {f.name for f in functions} | {i.manipulability for i in infos}
    defined |= {i.determinant for i in infos if i.determinant}
    for scalar_name, expr in (scalars or {}).items():
        check_identifier(scalar_name, "scalar function name", {**_RESERVED, **{n: "a function" for n in defined}})
        if scalar_name.startswith("_") or scalar_name in {p.name for p in robot.parameters}:
            raise CodegenError(f"scalar function name {scalar_name!r} is private or a parameter name")
        lowered = _lower_function(_angles(robot), [sp.sympify(expr)], (), (("q", robot.q),), robot.parameter_symbols,
                                  "given expression")
        add(lowered, scalar_name, "scalar", f"The scalar function {scalar_name}", (q_argument,))
        scalar_names.append(scalar_name)
        defined.add(scalar_name)

    exports = sorted({"PARAMETERS", "JOINTS", "ROBOT", "selftest"}
                     | {f.name for f in functions if not f.name.startswith("_")}
                     | {i.manipulability for i in infos} | {i.determinant for i in infos if i.determinant}
                     | ({"BACKEND"} if target == "c" else set()))
    c_source, c_module = ("", "")
    if target == "c":
        c_source, c_module = _c_source(robot, tuple(c_functions))
    uses = set().union(*(f.uses for f in functions))
    imports = tuple(sorted(uses | {"pi", "sqrt"})) if target == "python" else tuple(sorted(uses))
    parameter_names = [p.name for p in robot.parameters]
    parameter_lines = tuple(layout("    parameters = ", "(" + ", ".join(parameter_names)
                                   + ("," if len(parameter_names) == 1 else "") + ")", width=LINE_WIDTH))
    return ModuleDescription(
        target=target, template=TEMPLATES[target], version=__version__, robot=robot.name,
        convention=robot.convention.value, dof=robot.dof,
        joints=tuple((j.variable.name, j.type.value) for j in robot.joints),
        parameters=tuple((p.name, float_literal(p.default)) for p in robot.parameters),
        functions=tuple(functions), jacobians=tuple(infos), scalars=tuple(scalar_names),
        exports=tuple(_sorted_exports(exports)), command=_command_text(robot, target, requests),
        title=_TITLES[target], description_text=_DESCRIPTIONS[target], nan_policy=_NAN_POLICIES[target],
        imports=imports, parameter_lines=parameter_lines, c_source=c_source, c_module=c_module,
    )


_TITLES = {
    "python": "Kinematics and Jacobians in plain Python (standard library only, one configuration per call)",
    "numpy": "Kinematics and Jacobians in NumPy, batched over configurations",
    "lambdify": "Kinematics and Jacobians through sympy.lambdify, built when this module is imported",
    "c": "Kinematics and Jacobians in C, compiled at first import, with a NumPy fallback",
}
_DESCRIPTIONS = {
    "python": "Each function takes one configuration as a sequence of floats and returns floats or nested tuples.",
    "numpy": "Each function takes q of shape (..., n) and returns an array of shape (..., rows, columns); an\n"
             "``out`` array of that shape may be given (written and returned). Large batches are split over\n"
             "threads (``THREADS``, default the number of CPUs).",
    "lambdify": "The expressions are rebuilt in SymPy and compiled with ``sympy.lambdify(..., cse=True)`` at\n"
                "import; functions take q of shape (..., n) and return arrays of shape (..., rows, columns).",
    "c": "The NumPy functions are the reference and the fallback; C kernels replace them when a C compiler and\n"
         "the Python headers are present (``BACKEND`` is \"c\" or \"numpy\", ``BUILD_ERROR`` says why not).\n"
         "The extension is cached in $SYMJAC_CACHE_DIR or ~/.cache/symjac.",
}
_NAN_POLICIES = {
    "python": "Wrong lengths raise ValueError; NaN inputs propagate to NaN outputs (an infinite angle raises\n"
              "ValueError from math.sin).",
    "numpy": "Wrong shapes raise ValueError; NaN inputs propagate to NaN outputs (infinite angles give NaN with a\n"
             "RuntimeWarning).",
    "lambdify": "Wrong shapes raise ValueError; NaN inputs propagate to NaN outputs.",
    "c": "Wrong shapes raise ValueError; NaN and infinite angles give NaN outputs (no warning from C).",
}


def _sorted_exports(names: Iterable[str]) -> list[str]:
    """``__all__`` in the order ruff's RUF022 expects: SCREAMING_CASE, then CamelCase, then the rest."""
    def key(name: str) -> tuple[int, str]:
        if name.isupper():
            return (0, name)
        if name[:1].isupper():
            return (1, name)
        return (2, name)

    return sorted(names, key=key)


def _point_words(point_text: str) -> str:
    if point_text == "wrist":
        return "wrist"
    if point_text == "tool":
        return "tool point"
    return f"point {point_text}"


def _labels(robot: Robot, requests: Sequence[JacobianRequest]) -> list[str]:
    """Function-name suffixes: none for a single Jacobian, else ``_<frame>_<point>`` (``_3_tool``, ``_0_p1``)."""
    if len(requests) == 1:
        return [""]
    labels = []
    custom: dict[tuple[sp.Expr, ...], str] = {}
    for request in requests:
        frame = str(request.frame)
        if isinstance(request.point, str):
            point = request.point
        else:
            point = custom.setdefault(point_vector(robot, request.point), f"p{len(custom) + 1}")
        rows = "" if request.rows is None else "_r" + "".join(str(r) for r in request.rows)
        labels.append(f"_{frame}_{point}{rows}")
    return labels


def _command_text(robot: Robot, target: str, requests: Sequence[JacobianRequest]) -> str:
    frames = sorted({str(r.frame) for r in requests})
    parts = [f"symjac codegen {robot.name} --target {target}"]
    parts += [f"--frame {frame}" for frame in frames]
    points = []
    for request in requests:
        text = request.point if isinstance(request.point, str) else ",".join(
            str(v) for v in point_vector(robot, request.point))
        if text not in points:
            points.append(text)
    parts += [f"--point {point}" for point in points if point != "wrist" or len(points) > 1]
    rows = {r.rows for r in requests if r.rows is not None}
    if rows:
        parts.append("--rows " + ",".join(ROW_NAMES[r] for r in sorted(rows)[0]))
    return " ".join(parts)


# --- C sources -------------------------------------------------------------------------------------------------------


def _c_source(robot: Robot, functions: tuple[GeneratedFunction, ...]) -> tuple[str, str]:
    """The C extension's source and module name (``_symjac_<robot>_<hash of the source>``)."""
    angles = _angles(robot)
    printer = CPrinter({**{v: f"x[{k}]" for k, v in enumerate(robot.q)},
                        **{s: f"p[{k}]" for k, s in enumerate(robot.parameter_symbols)}})
    angle_code = tuple(printer.doprint(angle) for angle in angles.angles)
    data = {"robot": robot.name, "dof": robot.dof, "angles": angle_code, "functions": functions,
            "parameter_count": len(robot.parameters)}
    body = render_template("c_kernels.c.j2", module="MODULE_NAME", **data)
    digest = hashlib.sha256(body.encode()).hexdigest()[:16]
    module = f"_symjac_{robot.name}_{digest}"
    source = render_template("c_kernels.c.j2", module=module, **data)
    if '"""' in source or "\\" in source:
        raise CodegenError("internal error: the C source cannot be embedded in a Python raw string")
    return source, module


# --- public API ------------------------------------------------------------------------------------------------------


def generate(
    robot: Robot,
    target: Target = "python",
    frames: Sequence[Frame] | Frame = (0,),
    points: Sequence[Point] | Point = ("wrist",),
    *,
    rows: Sequence[int] | None = None,
    jacobians: Sequence[JacobianRequest] | None = None,
    scalars: Mapping[str, sp.Expr] | None = None,
    strategy: Strategy = "fastest",
) -> str:
    r"""The source text of a numeric module for ``robot``: FK, Jacobians, torques, manipulability, self-test.

    Parameters
    ----------
    robot : Robot
    target : "python", "numpy", "lambdify" or "c"
        See the module docstring.
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

    Returns
    -------
    str
        The module source; identical input gives byte-identical output.

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
    description = describe(robot, target, frames, points, rows=rows, jacobians=jacobians, scalars=scalars,
                           strategy=strategy)
    return render_module(description)


def render_module(description: ModuleDescription) -> str:
    """Render a :class:`ModuleDescription` with its target's template; check the result's line lengths."""
    text = render_template(description.template, module=description)
    for number, line in enumerate(text.splitlines(), start=1):
        if len(line) > LINE_WIDTH or line != line.rstrip():
            raise CodegenError(f"internal error: generated line {number} is too long or has trailing spaces")
    return text


def write_module(path: str | os.PathLike[str], text: str) -> Path:
    """Write a generated module to ``path`` atomically (:func:`symjac.files.write_text`): never a partial file."""
    return write_text(path, text)


# --- command line ----------------------------------------------------------------------------------------------------
