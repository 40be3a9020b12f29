"""The ``"casadi"`` target: a module that builds ``casadi.Function`` objects (SX) from the lowered expressions.

Each function of the other targets becomes a ``casadi.Function`` of the same name taking ``(q, p)`` (and the wrench
or the rates after them), ``p`` the parameter vector in the order of ``PARAMETER_NAMES`` with
``PARAMETER_DEFAULTS`` beside it: ready for ``casadi.Opti``, for CasADi's own derivatives and for
``Function.generate()``. The graph is the CSE list itself, one SX node per temporary; nothing is traced.
"""

from __future__ import annotations

from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.casadi.printer import CasadiPrinter
from symjac.codegen.description import (
    PYTHON_IDENTIFIERS,
    Backend,
    FunctionDescription,
    IdentifierRule,
    ModuleDescription,
)
from symjac.codegen.kinds import KINDS
from symjac.codegen.lower import symbol_names
from symjac.codegen.source_layout import angle_lines, entry_names, temporary_lines, unpack, wrap_statement

__all__ = ["BACKEND", "casadi_function", "entry"]

_OUTPUT = {name: spec.output or "value" for name, spec in KINDS.items() if not spec.derived}
"""Each lowered kind's output name in its builder (the kinds table's C-family name; ``value`` for a scalar)."""

IDENTIFIERS = PYTHON_IDENTIFIERS | IdentifierRule.of(
    "CasADi", ("jac", "hess", "null"), ("ca", "casadi", "p", "q", "wrench", "qdot", *_OUTPUT.values()))
"""Python's rule; no name CasADi refuses; not the module's import nor a local of the builders (the parameter vector
``p``, the inputs, the outputs ``T``, ``J``, ``tau``, ``H``, ``value``), which the parameters are unpacked beside."""

def entry(shape: tuple[int, ...], k: int) -> str:
    """Where entry ``k`` (row-major) of an output of ``shape`` goes: ``[i]``, ``[i, j]``, or ``[i, m * n + j]``.

    CasADi matrices have two dimensions: a Hessian ``(rows, n, n)`` is ``[dJ/dq_1 | ... | dJ/dq_n]``.
    """
    if len(shape) == 3:
        i, rest = divmod(k, shape[1] * shape[2])
        j, m = divmod(rest, shape[2])
        return f"[{i}, {m * shape[1] + j}]"
    if len(shape) == 2:
        return f"[{k // shape[1]}, {k % shape[1]}]"
    return f"[{k}]"


def casadi_function(description: ModuleDescription, function: FunctionDescription, taken: frozenset[str]
                    ) -> GeneratedFunction:
    """The builder's body: symbols, unpacking, sines and cosines, temporaries, then each non-zero entry."""
    lowered, spec = function.lowered, function.spec
    indent = "    "
    names = symbol_names(description.symbols, lowered, taken | {"ca", "casadi", "p", *_OUTPUT.values()})
    printer = CasadiPrinter(names.mapping)
    body: list[str] = []
    for argument, symbols in lowered.inputs:
        body.append(f'{indent}{argument} = ca.SX.sym("{argument}", {len(symbols)})')
    body.append(f'{indent}p = ca.SX.sym("p", {len(description.parameter_symbols)})')
    for argument, symbols in lowered.inputs:
        body += unpack(entry_names(lowered, names, symbols), f"ca.vertsplit({argument})", indent)
    if description.parameter_symbols:
        used = lowered.used_symbols
        parameter_names = [s.name if s in used else f"_{s.name}" for s in description.parameter_symbols]
        body += unpack(parameter_names, "ca.vertsplit(p)", indent)
    body += angle_lines(lowered, names, printer, indent, "ca.")
    body += temporary_lines(lowered, names, printer, indent)
    output = _OUTPUT[spec.kind]
    shape = lowered.shape
    size = (shape[0], shape[1] * shape[2]) if len(shape) == 3 else (*shape, 1, 1)[:2]
    lines = [f"{indent}{output} = ca.SX.zeros({size[0]}, {size[1]})"]
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    for k, (expr, value) in enumerate(zip(lowered.outputs, outputs, strict=True)):
        if expr != 0:
            lines += wrap_statement(f"{indent}{output}{entry(shape, k)} = ", value)
    arguments = ", ".join(argument for argument, _ in lowered.inputs)
    names_text = ", ".join(f'"{argument}"' for argument, _ in lowered.inputs)
    # CasADi's function names start with a letter: the private kinematics is "kinematics" inside CasADi
    lines += wrap_statement(f"{indent}return ", f'ca.Function("{spec.name.lstrip("_")}", [{arguments}, p], [{output}], '
                            f'[{names_text}, "p"], ["{output}"])')
    return generated_function(lowered, spec, body, outputs, lines, printer.used)


BACKEND = Backend(
    name="casadi",
    order=7,
    summary="casadi.Function objects (SX) for Opti and Function.generate",
    emits="one Python module building casadi.Function objects",
    identifiers=IDENTIFIERS,
    files=("{robot}.py",),
    templates=("casadi/module.py.j2", "python_common/macros.py.j2"),
    title="Kinematics and Jacobians as casadi.Function objects (SX), for optimal control and code generation",
    description="Each function is a casadi.Function of (q, p) (the wrench or the rates after q), p the parameter\n"
                "vector in the order of PARAMETER_NAMES, PARAMETER_DEFAULTS its defaults.",
    nan_policy="CasADi checks the shapes of what it is called with; NaN inputs give NaN outputs.",
    render=python_module_renderer(casadi_function, ik_printer=("casadi", CasadiPrinter)),
    dependencies=("casadi",),
    batched=False,
    language="Python/CasADi",
    runtime="casadi.py",
)
