"""The ``"jax"`` target: a module of pure ``jax.numpy`` functions of one configuration ``(q, **params)``.

Every function takes one configuration (``q`` of shape ``(n,)``) and the parameters as keyword floats, uses no
Python control flow on values and builds its output with nested ``jnp.stack`` calls, so that ``jax.jit``,
``jax.vmap`` (for batches) and ``jax.grad`` or ``jax.jacfwd`` compose with it. Numbers are Python floats, weakly
typed: results are in float32 unless ``jax_enable_x64`` is on, then in float64.
"""

from __future__ import annotations

from collections.abc import Sequence

from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.jax.printer import JaxPrinter
from symjac.codegen.description import (
    PYTHON_IDENTIFIERS,
    Backend,
    FunctionDescription,
    IdentifierRule,
    ModuleDescription,
)
from symjac.codegen.lower import symbol_names
from symjac.codegen.source_layout import LINE_WIDTH, angle_lines, entry_names, temporary_lines, unpack, wrap_statement

__all__ = ["BACKEND", "jax_function"]

IDENTIFIERS = PYTHON_IDENTIFIERS | IdentifierRule.of("JAX", (), ("jnp", "jax"))
"""Python's rule, and not the module's own import."""


def jax_function(description: ModuleDescription, function: FunctionDescription, taken: frozenset[str]
                 ) -> GeneratedFunction:
    """The body: unpack each argument, sines and cosines, temporaries, then the entries stacked row by row."""
    lowered, spec = function.lowered, function.spec
    indent = "    "
    names = symbol_names(description.symbols, lowered, taken | {"jnp", "jax"})
    printer = JaxPrinter(names.mapping)
    body: list[str] = []
    for argument, symbols in lowered.inputs:
        body += unpack(entry_names(lowered, names, symbols), f"jnp.asarray({argument})", indent)
    body += angle_lines(lowered, names, printer, indent, "jnp.")
    body += temporary_lines(lowered, names, printer, indent)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    return generated_function(lowered, spec, body, outputs, _return_lines(outputs, lowered.shape, indent),
                              printer.used)


def _return_lines(outputs: Sequence[str], shape: tuple[int, ...], indent: str) -> tuple[str, ...]:
    """``return jnp.stack([jnp.stack([...]), ...])``: one stack per row, then the rows stacked.

    Nested stacks, not one flat stack reshaped: on the CPU, XLA split the flat form of the PUMA 560 Jacobian into
    23 fusions that evaluated sines 104 times, against 6 fusions and 10 sines nested (``jit(vmap)`` 4x faster).
    """
    if not shape:
        return tuple(wrap_statement(f"{indent}return jnp.asarray(", outputs[0], ")"))
    return tuple(_stack(list(outputs), shape, indent, "return "))


def _stack(outputs: list[str], shape: tuple[int, ...], indent: str, head: str = "") -> list[str]:
    """The lines of ``head jnp.stack([...])`` over the leading axis of ``shape``, nested for the others."""
    if len(shape) == 1:
        single = f"{indent}{head}jnp.stack([{', '.join(outputs)}])"
        if len(single) < LINE_WIDTH:  # room for the comma a nested row ends with
            return [single]
        lines = [f"{indent}{head}jnp.stack(["]
        for value in outputs:
            lines += wrap_statement(f"{indent}    ", value, ",")
        return [*lines, f"{indent}])"]
    size = len(outputs) // shape[0]
    lines = [f"{indent}{head}jnp.stack(["]
    for k in range(shape[0]):
        inner = _stack(outputs[k * size:(k + 1) * size], shape[1:], indent + "    ")
        inner[-1] += ","
        lines += inner
    return [*lines, f"{indent}])"]


BACKEND = Backend(
    name="jax",
    order=6,
    summary="pure jax.numpy functions (jit, vmap, grad)",
    emits="one Python module of jax.numpy functions",
    identifiers=IDENTIFIERS,
    files=("{robot}.py",),
    templates=("jax/module.py.j2", "python_common/macros.py.j2"),
    title="Kinematics and Jacobians as pure jax.numpy functions (jit, vmap and grad compose with them)",
    description="Each function takes one configuration q of shape (n,) and the parameters as keyword floats; use\n"
                "jax.vmap for batches. Results are float32 unless jax_enable_x64 is on, then float64.",
    nan_policy="NaN and infinite inputs give NaN outputs; shapes are checked by JAX when it traces.",
    render=python_module_renderer(jax_function, ik_printer=("jax", JaxPrinter)),
    dependencies=("jax",),
    batched=False,
    language="Python/JAX",
    runtime="jax.py",
)
