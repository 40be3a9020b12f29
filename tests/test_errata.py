"""Every transcribed formula of the course notes against the derivation: the recorded verdict must be what an exact
comparison gives, every erratum's corrected form must hold, and the sheet lists exactly the errata."""

from __future__ import annotations

import pytest

from symjac.cli.main import main
from symjac.teaching.errata import DOCUMENTS, compare, comparisons, errata_sheet, formulas, summary

FORMULAS = formulas()


@pytest.mark.parametrize("formula", FORMULAS, ids=[f.id for f in FORMULAS])
def test_recorded_verdict_is_what_the_derivation_says(formula):
    result = compare(formula)
    assert result.verdict == formula.verdict, (
        f"{formula.id}: entries {result.differing} differ; derived {result.derived.tolist()}")
    if formula.verdict == "erratum":
        assert result.differing, "the printed form of an erratum must fail"
        assert result.corrected_holds, "the corrected form of an erratum must hold exactly"
        assert formula.why
    else:
        assert not result.differing
        assert (formula.verdict == "convention") == bool(formula.convention)


def test_every_document_is_covered():
    counts = summary(comparisons())
    assert set(counts) == set(DOCUMENTS)
    assert all(count["checked"] > 0 for count in counts.values()), counts


def test_sheet_lists_exactly_the_errata(capsys):
    results = comparisons()
    sheet = errata_sheet("markdown")
    errata = [r for r in results if r.verdict == "erratum"]
    rows = [line for line in sheet.split("## Errata")[1].split("## Convention notes")[0].splitlines()
            if line.startswith("| 0")]
    assert len(rows) == len(errata) >= 1
    for row, result in zip(rows, errata, strict=True):
        assert result.formula.where in row and result.formula.why in row
    assert main(["errata"]) == 0
    assert capsys.readouterr().out == sheet


def test_latex_sheet_escapes_text():
    tex = errata_sheet("latex")
    assert tex.startswith(r"\documentclass") and tex.rstrip().endswith(r"\end{document}")
    assert r"R\_x(-pi/2)" in tex  # underscores in the words are escaped


def test_an_altered_print_is_caught():
    formula = FORMULAS[0]
    assert compare(formula).differing  # the known misprint
    assert compare(formula.__class__(**{**formula.__dict__, "printed": formula.corrected})).differing == ()


def test_the_readable_columns_of_0_6T_in_4_96_are_listed_as_an_erratum(capsys):
    """(4.96) prints X for the first two columns of 0_6T; the third (z6) is readable and drops c5 in rows 1 and 2."""
    formula = next(f for f in FORMULAS if f.where.endswith("eq. (4.96)"))
    assert formula.args == {"source": 0, "target": 6, "columns": [3, 4]}
    result = compare(formula)
    assert result.verdict == "erratum" and result.differing == ((1, 1), (2, 1))  # z6, rows 1 and 2; row 3 holds
    assert result.corrected_holds
    assert main(["errata"]) == 0
    assert "eq. (4.96)" in capsys.readouterr().out.split("## Errata")[1].split("## Convention notes")[0]
