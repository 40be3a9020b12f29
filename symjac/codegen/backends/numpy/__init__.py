"""The ``"numpy"`` target: NumPy only, batched over configurations by block kernels, split over threads."""

from __future__ import annotations

from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.numpy.printer import NumPyPrinter
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, FunctionDescription, ModuleDescription
from symjac.codegen.lower import symbol_names
from symjac.codegen.source_layout import angle_lines, indices, input_lines, temporary_lines, wrap_statement

__all__ = ["BACKEND", "numpy_function"]


def numpy_function(description: ModuleDescription, function: FunctionDescription, taken: frozenset[str]
                   ) -> GeneratedFunction:
    """The block kernel: inputs are rows ``(size, m)``, ``out`` is ``shape + (m,)``; every write is contiguous."""
    lowered, spec = function.lowered, function.spec
    indent = "    "
    names = symbol_names(description.symbols, lowered, taken)
    printer = NumPyPrinter(names.mapping)
    body = input_lines(description.parameter_symbols, lowered, names, indent)
    body += angle_lines(lowered, names, printer, indent, "np.", pair="_sincos")  # one half-angle tangent for both
    body += temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    lines: list[str] = []
    for index, value in zip(indices(lowered.shape), outputs, strict=True):
        lines += wrap_statement(f"{indent}out[{index}] = ", value)
    return generated_function(lowered, spec, body, outputs, lines, printer.used)


BACKEND = Backend(
    name="numpy",
    order=1,
    summary="batched",
    emits="one Python module (NumPy)",
    identifiers=PYTHON_IDENTIFIERS,
    files=("{robot}.py",),
    templates=("numpy/module.py.j2", "python_common/macros.py.j2"),
    title="Kinematics and Jacobians in NumPy, batched over configurations",
    description="Each function takes q of shape (..., n) and returns an array of shape (..., rows, columns); an\n"
                "``out`` array of that shape may be given (written and returned). Large batches are split over\n"
                "threads (``THREADS``, default the number of CPUs).",
    nan_policy="Wrong shapes raise ValueError; NaN inputs propagate to NaN outputs (infinite angles give NaN with a\n"
               "RuntimeWarning).",
    # its angle lines call _sincos
    render=python_module_renderer(numpy_function, sections=("sincos",), ik_printer=("numpy", NumPyPrinter)),
    dependencies=("numpy",),
    runtime="numpy.py",
)
