"""The ``"c99"`` target: a standalone ``<robot>.h`` and ``<robot>.c`` in C99, for controllers and firmware.

No Python, no allocation, no global state: every function takes the coordinates ``q``, a parameter vector ``params``
(``NULL`` for the defaults) and the caller's output buffer, row-major. The real type is ``double`` unless the
including code defines ``<ROBOT>_REAL`` (``-DPUMA560_REAL=float`` for a single-precision controller); literals are
cast to it and ``<tgmath.h>`` picks ``sinf`` or ``sin`` accordingly. ``<robot>_selftest()`` checks every function
against central differences in C. The expressions are printed by the c target's C99 printer
(:class:`~symjac.codegen.backends.c99.printer.RealPrinter` only casts the literals).
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping
from dataclasses import dataclass

from symjac.codegen.backends.c import C_KEYWORDS
from symjac.codegen.backends.c99.printer import RealPrinter
from symjac.codegen.description import Backend, FunctionDescription, IdentifierRule, ModuleDescription
from symjac.codegen.lower import symbol_names
from symjac.codegen.printers import float_literal
from symjac.codegen.source_layout import comment_lines, wrap_statement
from symjac.errors import CodegenError
from symjac.resources import render_template

__all__ = ["BACKEND", "IDENTIFIERS", "CFunction", "block_comment", "c_function", "comment", "declaration", "render"]

C99_KEYWORDS = C_KEYWORDS | {"_Bool", "_Complex", "_Imaginary"}

LIBRARY_NAMES = frozenset((
    # <math.h> and <tgmath.h> (type-generic macros: a robot or parameter named so would be expanded), <stddef.h>
    "acos", "asin", "atan", "atan2", "cbrt", "ceil", "copysign", "cos", "cosh", "erf", "exp", "exp2", "fabs", "floor",
    "fma", "fmax", "fmin", "fmod", "hypot", "isfinite", "isinf", "isnan", "log", "log10", "log2", "lround", "pow",
    "remainder", "round", "sin", "sinh", "sqrt", "tan", "tanh", "trunc", "HUGE_VAL", "INFINITY", "NAN", "M_PI",
    "M_E", "NULL", "offsetof", "size_t", "ptrdiff_t", "errno", "main", "complex", "imaginary", "bool", "true",
    "false",
))

IDENTIFIERS = IdentifierRule.of("C", C99_KEYWORDS, LIBRARY_NAMES)
"""C99's rule: no keyword, and no name of the standard library a generated file includes (``NULL``, ``sin``)."""

_LOCALS = frozenset(("q", "p", "params", "F", "qdot", "T", "J", "tau", "H", "out", "real", "k", "m", "i", "j"))
"""Names the generated functions use themselves: a temporary never takes one."""

_OUTPUT = {"forward_kinematics": "T", "jacobian": "J", "joint_torques": "tau", "kinematics": "out", "hessian": "H",
           "bias_acceleration": "out", "scalar": ""}
_INPUT = {"q": "q", "wrench": "F", "qdot": "qdot"}


@dataclass(frozen=True)
class CFunction:
    """One lowered function printed in C: its name, arguments, statements and counts."""

    name: str
    kind: str
    summary: str
    static: bool
    inputs: tuple[tuple[str, int, str], ...]  # (C name, length, description) after q
    output: str  # the output buffer's name; "" for a scalar (returned)
    size: int
    shape: tuple[int, ...]
    body: tuple[str, ...]
    op_count: int
    trig_count: int
    origin: str

    def signature(self, real: str, n: int) -> tuple[str, ...]:
        """The C declaration (without the semicolon) in the real type ``real``, as lines of at most 120 characters."""
        arguments = [f"const {real} q[{n}]", f"const {real} *params"]
        arguments += [f"const {real} {name}[{length}]" for name, length, _ in self.inputs]
        if self.output:
            arguments.append(f"{real} {self.output}[{self.size}]")
        result = real if not self.output else "void"
        return declaration(f"{'static ' if self.static else ''}{result} {self.name}", arguments)


def block_comment(text: str, indent: str = "", width: int = 120) -> tuple[str, ...]:
    """``text`` (already :func:`comment`-safe) as a C block comment broken at spaces within ``width``.

    Examples
    --------
    >>> block_comment("one two three", width=12)
    ('/* one two', ' * three */')
    """
    lines = textwrap.wrap(text, width - len(indent) - 3, break_long_words=False, break_on_hyphens=False)
    lines[-1] += " */"
    return tuple(f"{indent}{'/* ' if k == 0 else ' * '}{line}" for k, line in enumerate(lines))


def declaration(head: str, arguments: list[str], width: int = 120) -> tuple[str, ...]:
    """``head(arguments)`` on one line, or broken after commas into lines indented by four spaces."""
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


def comment(text: str) -> str:
    r"""``text`` made safe inside a C block comment: no comment delimiters, trigraphs or line breaks survive.

    Examples
    --------
    >>> comment("a */ b /* c ??/ d\ne")
    'a * / b / * c ? ?/ d e'
    """
    for old, new in (("*/", "* /"), ("/*", "/ *"), ("??", "? ?"), ("\\", "/")):
        text = text.replace(old, new)
    return " ".join(text.split())


def c_function(description: ModuleDescription, function: FunctionDescription) -> CFunction:
    """Print one function: sines and cosines of the angles it uses, the temporaries, then each output entry."""
    chain = description.chain
    assert chain is not None
    robot, lowered = chain.robot, function.lowered
    names = symbol_names(robot, lowered, C99_KEYWORDS | LIBRARY_NAMES | _LOCALS)
    mapping = dict(names.mapping)
    inputs = []
    for argument, symbols in lowered.inputs:
        for k, symbol in enumerate(symbols):
            mapping[symbol] = f"{_INPUT[argument]}[{k}]"
    for spec_argument in function.spec.arguments[1:]:
        inputs.append((_INPUT[spec_argument.name], len(spec_argument.entries), comment(spec_argument.description)))
    for k, symbol in enumerate(robot.parameter_symbols):
        mapping[symbol] = f"p[{k}]"
    printer = RealPrinter(mapping)
    indent = "    "
    body: list[str] = []
    used = lowered.used_symbols
    for sine, cosine, angle in lowered.angles:
        for symbol, function_name in ((sine, "sin"), (cosine, "cos")):
            if symbol in used:
                body += wrap_statement(f"{indent}const real {mapping[symbol]} = ", f"{function_name}("
                                       f"{printer.doprint(angle)})", ";", language="c")
    for symbol, expr in lowered.temporaries:
        body += wrap_statement(f"{indent}const real {mapping[symbol]} = ", printer.doprint(expr), ";", language="c")
    output = _OUTPUT[function.kind]
    if output:
        for k, expr in enumerate(lowered.outputs):
            body += wrap_statement(f"{indent}{output}[{k}] = ", printer.doprint(expr), ";", language="c")
    else:
        body += wrap_statement(f"{indent}return ", printer.doprint(lowered.outputs[0]), ";", language="c")
    size = 1
    for extent in lowered.shape:
        size *= extent
    static = function.name.startswith("_")
    name = f"{description.robot}{'' if static else '_'}{function.name}"
    return CFunction(name=name, kind=function.kind, summary=comment(function.spec.summary), static=static,
                     inputs=tuple(inputs), output=output, size=size, shape=lowered.shape, body=tuple(body),
                     op_count=lowered.op_count, trig_count=lowered.trig_count, origin=lowered.origin)


def render(description: ModuleDescription, backend: Backend) -> Mapping[str, str]:
    """The header and the source file: ``{"<robot>.h": ..., "<robot>.c": ...}``."""
    if description.chain is None:
        raise CodegenError("internal error: the module description carries no chain")
    functions = tuple(c_function(description, f) for f in description.functions)
    by_name = {f.name.removeprefix(description.robot).lstrip("_"): f for f in functions}
    data = {
        "module": description,
        "functions": functions,
        "by_name": by_name,
        "prefix": description.robot,
        "macro": description.robot.upper(),
        "defaults": tuple(float_literal(value) for _, value in description.parameters),
        "dimension": max([6, description.n_coordinates]),
        "declaration": declaration,
        "block_comment": block_comment,
        "command_lines": comment_lines(comment(description.command)),
        "note_lines": comment_lines(comment(f"({description.command_note})")) if description.command_note else (),
        "coupling": tuple(comment(line) for line in description.coupling),
    }
    header, source = (name.format(robot=description.robot) for name in backend.files)
    files = {header: render_template("c99/header.h.j2", **data), source: render_template("c99/source.c.j2", **data)}
    for file_name, text in files.items():
        for number, line in enumerate(text.splitlines(), start=1):
            if len(line) > 120 or line != line.rstrip():
                raise CodegenError(f"internal error: {file_name} line {number} is too long or has trailing spaces")
    return files


BACKEND = Backend(
    name="c99",
    order=4,
    summary="standalone C99 header and source",
    emits="a C99 header and source file (<math.h> only, no allocation)",
    identifiers=IDENTIFIERS,
    files=("{robot}.h", "{robot}.c"),
    templates=("c99/header.h.j2", "c99/source.c.j2"),
    title="Kinematics and Jacobians in standalone C99",
    description="Row-major outputs in the caller's buffers; params == NULL means the defaults.",
    nan_policy="NaN and infinite inputs give NaN outputs; nothing is checked at run time.",
    render=render,
    dependencies=(),
    batched=False,
    language="C",
)
