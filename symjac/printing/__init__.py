"""The output layer, the one place for words and formats: LaTeX, pretty text, JSON, DH tables and sentences.

Analyses return data; these modules print it. :mod:`.latex` and :mod:`.pretty` print SymPy objects in textbook
shorthand, :mod:`.tables` DH tables, :mod:`.prose` every sentence, :mod:`.steps` propagation steps,
:mod:`.summary` singularity reports, :mod:`.json` JSON-ready data, and :mod:`.document` lays any result out as
LaTeX (bare or a standalone document, whose long results :mod:`.layout` breaks to fit the page), pretty text or JSON.
"""

from symjac.printing.document import FORMATS, Block, DHTable, Document, Equation, render
from symjac.printing.json import singularity_data
from symjac.printing.latex import TextbookLatexPrinter, latex
from symjac.printing.pretty import TextbookPrettyPrinter, pretty
from symjac.printing.shorthand import shorthand_indices, textbook_factors
from symjac.printing.steps import propagation_steps, step_equations
from symjac.printing.summary import singularity_blocks, singularity_summary

__all__ = [
    "FORMATS",
    "Block",
    "DHTable",
    "Document",
    "Equation",
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
