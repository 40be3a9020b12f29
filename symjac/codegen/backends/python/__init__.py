"""The ``"python"`` target: standard library only (``math``), one configuration per call, nested tuples back."""

from __future__ import annotations

from collections.abc import Sequence

from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.python.printer import PythonPrinter
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, FunctionDescription, ModuleDescription
from symjac.codegen.lower import symbol_names
from symjac.codegen.source_layout import (
    LINE_WIDTH,
    angle_lines,
    entry_names,
    temporary_lines,
    tuple_literal,
    unpack,
    wrap_statement,
)

__all__ = ["BACKEND", "python_function"]


def python_function(description: ModuleDescription, function: FunctionDescription, taken: frozenset[str]
                    ) -> GeneratedFunction:
    """The function body: unpack each argument (a wrong length is a ValueError), sines, temporaries, ``return``."""
    lowered, spec = function.lowered, function.spec
    indent = "    "
    names = symbol_names(description.symbols, lowered, taken)
    printer = PythonPrinter(names.mapping)
    body: list[str] = []
    for argument, symbols in lowered.inputs:
        body.append(f"{indent}try:")
        body += unpack(entry_names(lowered, names, symbols), argument, indent + "    ")
        body.append(f"{indent}except (TypeError, ValueError):")
        body.append(f'{indent}    raise ValueError(_length_error("{argument}", {argument}, {len(symbols)})) from None')
    body += angle_lines(lowered, names, printer, indent, "")
    body += temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    return generated_function(lowered, spec, body, outputs, _return_lines(outputs, lowered.shape, indent),
                              printer.used)


def _return_lines(outputs: Sequence[str], shape: tuple[int, ...], indent: str) -> tuple[str, ...]:
    """``return (...)``: a float, a tuple, or nested tuples row by row (tuples build faster than lists)."""
    if len(shape) == 0:
        return tuple(wrap_statement(f"{indent}return ", outputs[0]))
    if len(shape) == 1:
        single = f"{indent}return {tuple_literal(outputs)}"
        if len(single) <= LINE_WIDTH:
            return (single,)
        lines = [f"{indent}return ("]
        for value in outputs:
            lines += wrap_statement(f"{indent}    ", value, ",")
        return (*lines, f"{indent})")
    if len(shape) == 3:  # one tuple of rows per leading index: H[i][j][m]
        size = shape[1] * shape[2]
        lines = [f"{indent}return ("]
        for i in range(shape[0]):
            lines += [f"{indent}    (", *_return_lines(outputs[i * size:(i + 1) * size], shape[1:], indent + "    ")
                      [1:-1], f"{indent}    ),"]
        return (*lines, f"{indent})")
    rows, columns = shape
    lines = [f"{indent}return ("]
    for r in range(rows):
        lines += wrap_statement(f"{indent}    ", tuple_literal(outputs[r * columns:(r + 1) * columns]), ",")
    return (*lines, f"{indent})")


BACKEND = Backend(
    name="python",
    order=0,
    summary="standard library",
    emits="one Python module (standard library only)",
    identifiers=PYTHON_IDENTIFIERS,
    files=("{robot}.py",),
    templates=("python/module.py.j2", "python_common/macros.py.j2", "python/ik_numeric.py.j2"),
    title="Kinematics and Jacobians in plain Python (standard library only, one configuration per call)",
    description="Each function takes one configuration as a sequence of floats and returns floats or nested tuples.",
    nan_policy="Wrong lengths raise ValueError; NaN inputs propagate to NaN outputs (an infinite angle raises\n"
               "ValueError from math.sin).",
    # the self-test uses pi and sqrt always
    render=python_module_renderer(python_function, imports=("pi", "sqrt"), ik_printer=("python", PythonPrinter)),
    batched=False,
    runtime="python.py",
)
