"""What the C-family targets share (c, c99, cpp): one function printed as C statements, and safe comments.

A lowered function becomes the same statements in both languages (sines and cosines of the angles it uses, the CSE
temporaries, each output entry) in a type ``real``; a :class:`Dialect` says how each language names a parameter
and an output entry and writes a literal. The registry skips this module (a leading underscore: not a target).
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy as sp

from symjac.codegen.backends.c.printer import CPrinter, RealPrinter
from symjac.codegen.description import FunctionDescription, ModuleDescription
from symjac.codegen.kinds import kind_spec
from symjac.codegen.lower import LoweredFunction, symbol_names
from symjac.codegen.source_layout import comment_lines, wrap_statement

__all__ = [
    "C_DIALECT",
    "CFunction",
    "Dialect",
    "Statements",
    "block_comment",
    "c_function",
    "c_statements",
    "call_statement",
    "comment",
    "declaration",
    "header_comments",
    "line_comment",
]


@dataclass(frozen=True)
class Dialect:
    """How one C-family language writes what the statements need.

    ``reserved``: names a temporary may not take (keywords, library names, the function's own locals);
    ``printer``: the target's printer class (its literals cast to ``real``); ``parameter(index, name)``: a
    parameter's value;
    ``element(output, shape, k)``: entry ``k`` (row-major) of an output of ``shape``; ``angle_array``: the
    function's body receives the sines ``S`` and cosines ``C`` of the angles it uses from its caller (C: the c99
    file computes them per call, the c target's extension for a block of configurations, vectorised), else it
    calls ``sin`` or ``cos`` once per value (C++: overloads pick the scalar type's own).
    """

    reserved: frozenset[str]
    printer: Callable[[Mapping[sp.Symbol, str]], CPrinter]
    parameter: Callable[[int, str], str]
    element: Callable[[str, tuple[int, ...], int], str]
    angle_array: bool = False


_LOCALS = frozenset(("q", "p", "params", "F", "qdot", "T", "J", "tau", "H", "out", "real", "k", "m", "i", "j", "A",
                     "S", "C", "qddot", "M", "b", "coriolis", "gravity"))
"""Names the generated functions use themselves: a temporary never takes one."""

_INPUT = {"q": "q", "wrench": "F", "qdot": "qdot", "qddot": "qddot", "tau": "tau"}


@dataclass(frozen=True)
class CFunction:
    """One lowered function printed in C: its name, arguments, statements and counts."""

    name: str
    base: str  # the name without the robot's prefix (C++ puts it in a namespace instead)
    kind: str
    summary: str
    static: bool
    inputs: tuple[tuple[str, int, str], ...]  # (C name, length, description) after q
    output: str  # the output buffer's name; "" for a scalar (returned)
    size: int
    shape: tuple[int, ...]
    body: tuple[str, ...]
    angles: tuple[str, ...]  # with an angle array: the angles whose sines S and cosines C the body reads
    op_count: int
    trig_count: int
    origin: str
    layout: str = ""  # how a flat three-dimensional output is indexed (the kinds table's layout)

    @property
    def body_name(self) -> str:
        """The C function of the body alone, given the sines and cosines (``sj_body_jacobian``)."""
        return f"sj_body_{self.base}"

    def signature(self, real: str, n: int) -> tuple[str, ...]:
        """The C declaration (without the semicolon) in the real type ``real``, as lines of at most 120 characters."""
        return self._declaration(self.name, real, [f"const {real} q[{n}]", f"const {real} *params"])

    def body_signature(self, real: str, n: int) -> tuple[str, ...]:
        """The declaration of :attr:`body_name`: after ``q`` and ``p``, the sines ``S`` and cosines ``C`` if any."""
        arguments = [f"const {real} q[{n}]", f"const {real} *p"]
        if self.angles:
            arguments += [f"const {real} S[{len(self.angles)}]", f"const {real} C[{len(self.angles)}]"]
        return self._declaration(self.body_name, real, arguments, static=True)

    def _declaration(self, name: str, real: str, arguments: list[str], static: bool = False) -> tuple[str, ...]:
        arguments += [f"const {real} {input_name}[{length}]" for input_name, length, _ in self.inputs]
        if self.output:
            arguments.append(f"{real} {self.output}[{self.size}]")
        result = real if not self.output else "void"
        return declaration(f"{'static ' if self.static or static else ''}{result} {name}", arguments)

    def sine_initializers(self, indent: str) -> tuple[str, ...]:
        """``const real S[n] = {sin(q[0]), ...};`` and the cosines ``C``: one configuration's, for the body."""
        return tuple(line for array, function in (("S", "sin"), ("C", "cos"))
                     for line in wrap_statement(f"{indent}const real {array}[{len(self.angles)}] = {{",
                                                ", ".join(f"{function}({angle})" for angle in self.angles), "};",
                                                language="c"))

    def angle_assignments(self, indent: str, row: str) -> tuple[str, ...]:
        """``A[row * n + i] = angle;`` for each angle: one configuration's row of a block of angles (flat, n wide)."""
        n = len(self.angles)
        return tuple(line for i, angle in enumerate(self.angles)
                     for line in wrap_statement(f"{indent}A[{row} * {n} + {i}] = ", angle, ";", language="c"))

    def body_call(self, q: str, p: str, inputs: tuple[str, ...], output: str, S: str = "S", C: str = "C") -> str:
        """A call of the body: ``sj_body_jacobian(q, p, S, C, J)``, or ``return sj_body_...(...)`` for a scalar."""
        arguments = [q, p, *((S, C) if self.angles else ()), *inputs, *((output,) if self.output else ())]
        return f"{'' if self.output else 'return '}{self.body_name}({', '.join(arguments)});"


def block_comment(text: str, indent: str = "", width: int = 120) -> tuple[str, ...]:
    """``text`` (already :func:`comment`-safe) as a C block comment broken at spaces within ``width``.

    Examples
    --------
    >>> block_comment("one two three", width=15)
    ('/* one two', ' * three */')
    """
    lines = textwrap.wrap(text, width - len(indent) - 6, break_long_words=False, break_on_hyphens=False)  # "/* ", " */"
    lines[-1] += " */"
    return tuple(f"{indent}{'/* ' if k == 0 else ' * '}{line}" for k, line in enumerate(lines))


def header_comments(description: ModuleDescription) -> dict[str, tuple[str, ...]]:
    """The texts a C-family header comments on, made safe: the regenerating command, its note, the coupling."""
    note = description.command_note
    return {
        "command_lines": comment_lines(comment(description.command), width=119),
        "note_lines": comment_lines(comment(f"({note})"), width=119) if note else (),
        "coupling": tuple(comment(line) for line in description.coupling),
    }


def line_comment(text: str, indent: str = "", width: int = 120) -> tuple[str, ...]:
    """``text`` (already :func:`comment`-safe) as ``//`` comment lines broken at spaces within ``width``.

    Examples
    --------
    >>> line_comment("one two three", width=12)
    ('// one two', '// three')
    """
    lines = textwrap.wrap(text, width - len(indent) - 3, break_long_words=False, break_on_hyphens=False)
    return tuple(f"{indent}// {line}" for line in lines)


def declaration(head: str, arguments: list[str], width: int = 119) -> tuple[str, ...]:
    """``head(arguments)`` on one line, or broken after commas into lines indented by four spaces.

    The width leaves one column of the 120 for the semicolon that ends a declaration in the header.
    """
    line = f"{head}({', '.join(arguments)})"
    if len(line) <= width:
        return (line,)
    lines, current = [f"{head}("], "   "
    for k, argument in enumerate(arguments):
        piece = f" {argument}{',' if k < len(arguments) - 1 else ')'}"
        if len(current) + len(piece) > width:
            lines.append(current)
            current = "   "
        current += piece
    return (*lines, current)


def call_statement(head: str, function: str, arguments: list[object], width: int = 120) -> tuple[str, ...]:
    """``head function(arguments);`` on one line, or broken after commas, continued four spaces further in.

    Examples
    --------
    >>> call_statement("    n += ", "f", [1, "q"])
    ('    n += f(1, q);',)
    >>> call_statement("  ", "f", ["alpha", "beta", "gamma"], width=18)
    ('  f(alpha, beta,', '      gamma);')
    """
    texts = [str(argument) for argument in arguments]
    line = f"{head}{function}({', '.join(texts)});"
    if len(line) <= width:
        return (line,)
    indent = " " * (len(head) - len(head.lstrip()) + 4)
    lines, current = [], f"{head}{function}("
    for k, text in enumerate(texts):
        piece = text + (", " if k < len(texts) - 1 else ");")
        if len(current) + len(piece.rstrip()) > width:
            lines.append(current.rstrip())
            current = indent
        current += piece
    return (*lines, current)


def comment(text: str) -> str:
    r"""``text`` made safe inside a C block comment: no comment delimiters, trigraphs or line breaks survive.

    Examples
    --------
    >>> comment("a */ b /* c ??/ d\ne *\\/ f")
    'a * / b / * c ? ?/ d e * // f'
    """
    text = " ".join(text.replace("\\", "/").split())  # no line splice, no line break
    while any(mark in text for mark in ("*/", "/*", "??")):  # a replacement may form a new mark: repeat
        text = text.replace("*/", "* /").replace("/*", "/ *").replace("??", "? ?")
    return text


@dataclass(frozen=True)
class Statements:
    """A lowered function as C statements: sines and cosines, CSE temporaries, output assignments.

    ``angles`` are the statements that compute or read the sines and cosines; ``angle_values`` the printed angles
    whose sines and cosines an ``angle_array`` function receives (``S[i] = sin(angle_values[i])``).
    """

    angles: tuple[str, ...]
    angle_values: tuple[str, ...]
    temporaries: tuple[str, ...]
    outputs: tuple[str, ...]


def c_statements(lowered: LoweredFunction, mapping: Mapping[sp.Symbol, str], printer: CPrinter, indent: str,
                 real: str, target: Callable[[int], str | None], angle_array: bool = False) -> Statements:
    """The C statements of ``lowered``, symbols named by ``mapping``, values of type ``real``.

    The sines and cosines of the joint angles come first: one ``sin`` or ``cos`` call per value used, or with
    ``angle_array`` reads such as ``const real s2 = S[1], c2 = C[1];`` from the arrays ``S`` and ``C`` of the
    sines and cosines of the angles whose sine or cosine is used (computed by the caller, which a target may
    vectorise). The CSE temporaries follow, then the outputs: ``target(k)`` is where entry ``k`` goes, or ``None``
    for a scalar function (``return value;``). Every C-family target (c, c99, cpp) prints its statements here.
    """
    used = lowered.used_symbols
    angles = [(s, c, a) for s, c, a in lowered.angles if s in used or c in used]
    lines: list[str] = []
    for index, (sine, cosine, angle) in enumerate(angles):
        if angle_array:
            reads = [f"{mapping[symbol]} = {array}[{index}]" for symbol, array in ((sine, "S"), (cosine, "C"))
                     if symbol in used]
            lines.append(f"{indent}const {real} {', '.join(reads)};")
            continue
        for symbol, function_name in ((sine, "sin"), (cosine, "cos")):
            if symbol in used:
                lines += wrap_statement(f"{indent}const {real} {mapping[symbol]} = ",
                                        f"{function_name}({printer.doprint(angle)})", ";", language="c")
    values = tuple(printer.doprint(angle) for _, _, angle in angles) if angle_array else ()
    temporaries: list[str] = []
    for symbol, expr in lowered.temporaries:
        temporaries += wrap_statement(f"{indent}const {real} {mapping[symbol]} = ", printer.doprint(expr), ";",
                                      language="c")
    outputs: list[str] = []
    for k, expr in enumerate(lowered.outputs):
        place = target(k)
        head = f"{indent}return " if place is None else f"{indent}{place} = "
        outputs += wrap_statement(head, printer.doprint(expr), ";", language="c")
    return Statements(tuple(lines), values, tuple(temporaries), tuple(outputs))


def c_function(description: ModuleDescription, function: FunctionDescription, dialect: Dialect) -> CFunction:
    """Print one function: sines and cosines of the angles it uses, the temporaries, then each output entry."""
    lowered = function.lowered
    names = symbol_names(description.symbols, lowered, dialect.reserved | _LOCALS)
    mapping = dict(names.mapping)
    inputs = []
    for argument, symbols in lowered.inputs:
        for k, symbol in enumerate(symbols):
            mapping[symbol] = f"{_INPUT[argument]}[{k}]"
    for spec_argument in function.spec.arguments[1:]:
        inputs.append((_INPUT[spec_argument.name], len(spec_argument.entries), comment(spec_argument.description)))
    for k, symbol in enumerate(description.parameter_symbols):
        mapping[symbol] = dialect.parameter(k, symbol.name)
    kind = kind_spec(function.kind)
    output = kind.output
    statements = c_statements(lowered, mapping, dialect.printer(mapping), "    ", "real",
                              lambda k: dialect.element(output, lowered.shape, k) if output else None,
                              dialect.angle_array)
    body = [*statements.angles, *statements.temporaries, *statements.outputs]
    size = math.prod(lowered.shape)
    static = function.name.startswith("_")
    name = f"{description.robot}{'' if static else '_'}{function.name}"
    return CFunction(name=name, base=function.name.lstrip("_"), kind=function.kind,
                     layout=kind.layout.format(shape=lowered.shape) if kind.layout else "",
                     summary=comment(function.spec.summary), static=static,
                     inputs=tuple(inputs), output=output, size=size, shape=lowered.shape, body=tuple(body),
                     angles=statements.angle_values, op_count=lowered.op_count, trig_count=lowered.trig_count,
                     origin=lowered.origin)


C_DIALECT = Dialect(frozenset(), RealPrinter, lambda index, _: f"p[{index}]", lambda output, _, k: f"{output}[{k}]",
                    angle_array=True)
"""Plain C (c99, and the c target's extension): parameters by index into ``p``, outputs as flat row-major arrays,
sines and cosines from the caller."""
