"""The ``"text"`` target (a worked example of the seam): the lowered assignments as plain text."""

from __future__ import annotations

from collections.abc import Mapping

from symjac.codegen.backends.text.printer import TextPrinter
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, ModuleDescription
from symjac.codegen.lower import symbol_names
from symjac.resources import render_template

__all__ = ["BACKEND"]


def render(description: ModuleDescription, backend: Backend) -> Mapping[str, str]:
    """One text file: every function's assignments and outputs."""
    assert description.chain is not None
    functions = []
    for function in description.functions:
        names = symbol_names(description.chain.robot, function.lowered, set())
        printer = TextPrinter(names.mapping)
        functions.append({
            "name": function.name, "shape": function.shape,
            "assignments": [*((names.mapping[sine], f"sin({printer.doprint(angle)})") for sine, _, angle
                              in function.lowered.angles),
                            *((names.mapping[cosine], f"cos({printer.doprint(angle)})") for _, cosine, angle
                              in function.lowered.angles),
                            *((names.mapping[s], printer.doprint(e)) for s, e in function.lowered.temporaries)],
            "outputs": [printer.doprint(e) for e in function.lowered.outputs],
        })
    text = render_template(backend.template, module=description, functions=functions)
    return {backend.files[0].format(robot=description.robot): text}


BACKEND = Backend(
    name="text", order=9, summary="assignments as text", emits="one text file", title="Lowered assignments",
    description="", nan_policy="", identifiers=PYTHON_IDENTIFIERS, files=("{robot}.txt",),
    templates=("text/assignments.txt.j2",), render=render,
)
