"""The ``"lambdify"`` target: SymPy + NumPy; the module rebuilds the expressions and lambdifies them at import."""

from __future__ import annotations

from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.lambdify.printer import SymPyPrinter
from symjac.codegen.backends.numpy.printer import NumPyPrinter
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, FunctionDescription, ModuleDescription
from symjac.codegen.lower import symbol_names
from symjac.codegen.source_layout import angle_lines, input_lines, temporary_lines, wrap_statement

__all__ = ["BACKEND", "sympy_function"]


def sympy_function(description: ModuleDescription, function: FunctionDescription, taken: frozenset[str]
                   ) -> GeneratedFunction:
    """Statements that rebuild the CSE'd expressions in SymPy, returning the list of entries."""
    lowered, spec = function.lowered, function.spec
    indent = "    "
    names = symbol_names(description.symbols, lowered, taken)
    printer = SymPyPrinter(names.mapping)
    body = input_lines(description.parameter_symbols, lowered, names, indent)
    body += angle_lines(lowered, names, printer, indent, "sympy.")
    body += temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    lines = [f"{indent}return ["]
    for value in outputs:
        lines += wrap_statement(f"{indent}    ", value, ",")
    lines.append(f"{indent}]")
    return generated_function(lowered, spec, body, outputs, lines, ())


BACKEND = Backend(
    name="lambdify",
    order=2,
    summary="sympy at import",
    emits="one Python module (NumPy and SymPy)",
    identifiers=PYTHON_IDENTIFIERS,
    files=("{robot}.py",),
    templates=("lambdify/module.py.j2", "python_common/macros.py.j2"),
    title="Kinematics and Jacobians through sympy.lambdify, built when this module is imported",
    description="The expressions are rebuilt in SymPy and compiled with ``sympy.lambdify(..., cse=True)`` at\n"
                "import; functions take q of shape (..., n) and return arrays of shape (..., rows, columns).",
    nan_policy="Wrong shapes raise ValueError; NaN inputs propagate to NaN outputs.",
    render=python_module_renderer(sympy_function, ik_printer=("numpy", NumPyPrinter)),
    dependencies=("numpy", "sympy"),
    runtime="numpy.py",
)
