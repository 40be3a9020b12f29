"""The output layer, the one place for words and formats: LaTeX, pretty text, JSON, parameter tables and sentences.

Analyses return data; these modules print it. :mod:`.latex` and :mod:`.pretty` print SymPy objects in textbook
shorthand, :mod:`.tables` each convention's parameter table (DH parameters, screw axes, origins and axes),
:mod:`.prose` every sentence, :mod:`.steps` propagation steps, :mod:`.summary` singularity reports, :mod:`.json`
JSON-ready data, and :mod:`.document` lays any result out as LaTeX (bare or a standalone document, whose long
results :mod:`.latex_layout` breaks to fit the page), pretty text or JSON. :mod:`.results` builds the document of
each result, for the command line and the report alike.
"""

from importlib import import_module as _import_module
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

# The two printers by name, imported now: importing a submodule later binds its name here, and ``latex`` and
# ``pretty`` must stay the functions, not the modules of the same names (both are cheap once SymPy is loaded).
from symjac.printing.latex import TextbookLatexPrinter, latex
from symjac.printing.pretty import TextbookPrettyPrinter, pretty

_HOME = {
    "FORMATS": "document", "Block": "document", "Document": "document", "Equation": "document",
    "ParameterTable": "document",
    "render": "document", "singularity_data": "json", "shorthand_indices": "shorthand",
    "textbook_factors": "shorthand", "propagation_steps": "steps", "step_equations": "steps",
    "singularity_blocks": "summary", "singularity_summary": "summary",
}
"""Each re-exported name and its module, imported on first use (PEP 562): a command loads only the printers it
uses (``symjac jacobian`` no JSON or page-layout code)."""

__all__ = [
    "FORMATS",
    "Block",
    "Document",
    "Equation",
    "ParameterTable",
    "TextbookLatexPrinter",
    "TextbookPrettyPrinter",
    "latex",
    "pretty",
    "propagation_steps",
    "render",
    "shorthand_indices",
    "singularity_blocks",
    "singularity_data",
    "singularity_summary",
    "step_equations",
    "textbook_factors",
]


def __getattr__(name: str) -> _Any:
    """Import a re-exported name on first use (its module stays loaded, the name is kept here)."""
    if name == "DHTable":  # the name before the convention-neutral one
        from symjac.printing.document import DHTable

        return DHTable
    module = _HOME.get(name)
    if module is None:
        raise AttributeError(f"module 'symjac.printing' has no attribute {name!r}")
    value = getattr(_import_module(f"symjac.printing.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


if _TYPE_CHECKING:
    from symjac.printing.document import FORMATS, Block, Document, Equation, ParameterTable, render
    from symjac.printing.json import singularity_data
    from symjac.printing.shorthand import shorthand_indices, textbook_factors
    from symjac.printing.steps import propagation_steps, step_equations
    from symjac.printing.summary import singularity_blocks, singularity_summary
