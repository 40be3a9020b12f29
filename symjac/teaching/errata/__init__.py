"""Every printed formula of the course notes, checked mechanically against symjac's derivation: an errata sheet.

:func:`formulas` reads the transcriptions (``formulas.toml``), :func:`compare` decides each one exactly, and
:func:`errata_sheet` lists the misprints (where, as printed, corrected, why) and the convention notes, in Markdown
or LaTeX (``symjac errata``).
"""

from symjac.teaching.errata.derive import QUANTITIES, Comparison, compare, derive
from symjac.teaching.errata.formulas import DOCUMENTS, VERDICTS, Formula, formula, formulas, shorthand_names
from symjac.teaching.errata.sheet import SHEET_FORMATS, comparisons, errata_sheet, summary

__all__ = [
    "DOCUMENTS",
    "QUANTITIES",
    "SHEET_FORMATS",
    "VERDICTS",
    "Comparison",
    "Formula",
    "compare",
    "comparisons",
    "derive",
    "errata_sheet",
    "formula",
    "formulas",
    "shorthand_names",
    "summary",
]
