"""What the command line builds and imports: JSON only for --format json, each entry printed once, LaTeX too long
for a terminal only with -o, ``--version`` without SymPy, and one document per result for the CLI and the report."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

import symjac.printing.document
import symjac.printing.json
from symjac.analysis.singularity.singularities import singularities
from symjac.kinematics.chain import chain_of
from symjac.kinematics.jacobian import jacobian
from symjac.model.io import load_robot
from symjac.printing.document import LatexTooLargeError, check_latex_size, render
from symjac.printing.latex import latex
from symjac.printing.results import (
    forward_kinematics_document,
    jacobian_document,
    link_transforms,
    singularities_document,
    transforms_document,
)

ROOT = Path(__file__).resolve().parent.parent

# --- JSON only when asked for; each entry printed once ------------------------------------------------------------


def _refuse(*args, **kwargs):
    raise AssertionError("the JSON form was built")


@pytest.mark.parametrize("argv", [
    ["jacobian", "planar2r"],
    ["jacobian", "planar2r", "--format", "pretty"],
    ["jacobian", "planar2r", "--standalone"],
    ["jacobian", "stanford", "--method", "velocity_propagation", "--steps"],
    ["show", "stanford"],
    ["fk", "puma560", "--format", "pretty"],
    ["hessian", "planar2r"],
    ["torques", "planar2r"],
    ["jacobian", "planar2r", "--derivative"],
    ["jacobian", "planar2r", "--representation", "zyz"],
    ["singularities", "planar2r"],
    ["dynamics", "planar2r", "--symbolic-inertials", "--steps", "--mass-matrix"],
])
def test_json_is_built_only_for_format_json(cli, monkeypatch, argv):
    for name in symjac.printing.json.__all__:
        monkeypatch.setattr(symjac.printing.json, name, _refuse)
    cli.ok(*argv)
    status, _out, err = cli.run(*[word for word in argv if word not in ("--standalone", "pretty", "--format")],
                                "--format", "json")
    assert status == 2 and "the JSON form was built" in err  # the patch does catch a JSON build


def test_latex_prints_each_entry_once(cli, monkeypatch):
    printed = []
    original = symjac.printing.document.latex

    def counting(expr, **settings):
        printed.append(expr)
        return original(expr, **settings)

    monkeypatch.setattr(symjac.printing.document, "latex", counting)
    line = cli.latex_line("jacobian", "puma560")
    assert len(printed) == 1 and isinstance(printed[0], sp.MatrixBase)  # the matrix, once, and nothing else
    assert line == r"{}^{0}J = " + original(printed[0])


def test_the_remembering_printer_keeps_floats_of_different_precision_apart():
    x = sp.Symbol("x")
    short, long = sp.Float("0.123456789012", 3), sp.Float("0.123456789012", 12)
    assert latex(sp.Matrix([[short * x, long * x, short * x]])) == (
        r"\begin{bmatrix}0.123 x & 0.123456789012 x & 0.123 x\end{bmatrix}")


# --- LaTeX too long for a terminal ----------------------------------------------------------------------------


def test_latex_over_the_limit_is_refused_in_one_line():
    check_latex_size("x" * symjac.printing.document.LATEX_LIMIT, "ask for less")
    with pytest.raises(LatexTooLargeError, match=r"^the LaTeX is 200 KB, more than 200 KB: .* -o FILE, or ask for"):
        check_latex_size("x" * (symjac.printing.document.LATEX_LIMIT + 1), "ask for less")


def test_a_long_latex_result_is_written_only_with_o(cli, monkeypatch, tmp_path):
    full = cli.ok("jacobian", "puma560", "--standalone")
    monkeypatch.setattr(symjac.printing.document, "LATEX_LIMIT", len(full) - 1)
    for output in ([], ["-o", "-"]):
        line = cli.one_line_error("jacobian", "puma560", "--standalone", *output)
        assert "-o FILE" in line and "--frame K" in line and "--rows" in line and "symjac codegen" in line, line
    path = tmp_path / "puma.tex"
    assert cli.run("jacobian", "puma560", "--standalone", "-o", str(path)) == (0, "", "")
    assert path.read_text(encoding="utf-8") == full
    assert cli.ok("jacobian", "puma560", "--format", "pretty")  # only LaTeX has the limit
    assert json.loads(cli.ok("jacobian", "puma560", "--format", "json"))["latex"]


# --- imports ------------------------------------------------------------------------------------------------------


def _python(code: str) -> str:
    env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT,
                            check=True, timeout=120)
    return result.stdout


def test_version_does_not_import_sympy():
    out = _python("import sys, symjac.cli.main as m\n"
                  "try:\n    m.main(['--version'])\nexcept SystemExit as done:\n    assert done.code == 0\n"
                  "print('sympy' in sys.modules, 'numpy' in sys.modules)")
    assert out.splitlines() == ["symjac 0.1.0".replace("0.1.0", _python("import symjac; print(symjac.__version__)")
                                                      .strip()), "False False"]


def test_python_m_symjac_version_does_not_import_sympy():
    out = _python("import runpy, sys\nsys.argv = ['symjac', '--version']\n"
                  "try:\n    runpy.run_module('symjac', run_name='__main__')\nexcept SystemExit:\n    pass\n"
                  "print('sympy' in sys.modules)")
    assert out.splitlines()[-1] == "False"


def test_the_package_root_is_lazy_and_complete():
    out = _python("import os, sys, symjac\n"
                  "print('sympy' in sys.modules, os.environ['SYMPY_CACHE_SIZE'])\n"
                  "import symjac.printing.latex, symjac.printing.pretty  # submodules named like the printers\n"
                  "from symjac import jacobian, load_robot, latex\n"
                  "print(latex(jacobian(load_robot('planar2r')))[:15])\n"
                  "print(set(symjac.__all__) <= set(dir(symjac)), all(hasattr(symjac, n) for n in symjac.__all__))\n"
                  "print(callable(symjac.latex), callable(symjac.pretty), callable(symjac.printing.latex))")
    assert out.splitlines() == ["False 10000", r"\begin{bmatrix}", "True True", "True True True"]


def test_a_jacobian_loads_no_analysis_code_generator_or_template_engine():
    out = _python("import sys\nfrom symjac.cli.main import main\nmain(['jacobian', 'planar2r'])\n"
                  "print(sorted(m for m in sys.modules if m.startswith(('symjac.analysis', 'symjac.codegen', "
                  "'symjac.report', 'jinja2', 'numpy', 'symjac.printing.json', 'symjac.printing.latex_layout'))))")
    assert out.splitlines()[-1] == "[]"


# --- one document per result, for the command line and the report -------------------------------------------------


@pytest.fixture(scope="module")
def page() -> str:
    from symjac.report import derivation_report

    return derivation_report(load_robot("planar3r"), "planar3r")


def _blocks_in(document, page: str) -> None:
    from symjac.report.content import block_html

    for block in document.blocks:
        assert block_html(block) in page, block


def test_show_and_the_report_print_the_same_transforms(cli, page):
    robot = load_robot("planar3r")
    document = transforms_document(robot, link_transforms(robot))
    assert cli.ok("show", "planar3r", "--format", "pretty") == render(document, "pretty")
    assert len(document.blocks) == robot.n_joints + 2  # the table, each link, the tool
    _blocks_in(document, page)


def test_fk_and_the_report_print_the_same_pose(cli, page):
    robot = load_robot("planar3r")
    T = chain_of(robot).simplified_transform(0, "tool")
    document = forward_kinematics_document(robot, 0, "tool", T)
    assert cli.ok("fk", "planar3r") == render(document, "latex")
    _blocks_in(document, page)


def test_jacobian_and_the_report_print_the_same_jacobian(cli, page):
    robot = load_robot("planar3r")
    document = jacobian_document(robot, jacobian(robot, point="tool"), 0, "tool", "differentiation")
    assert cli.ok("jacobian", "planar3r", "--point", "tool", "--format", "pretty") == render(document, "pretty")
    _blocks_in(document, page)


def test_singularities_and_the_report_print_the_same_report(cli, page):
    robot = load_robot("planar3r")
    document = singularities_document(robot, singularities(robot))
    assert cli.ok("singularities", "planar3r") == render(document, "latex")
    _blocks_in(document, page)


def test_the_program_flushes_everything_before_it_ends_without_teardown(tmp_path):
    def symjac(*argv):
        return subprocess.run([sys.executable, "-m", "symjac", *argv], capture_output=True, text=True, timeout=300)

    shown = symjac("jacobian", "planar2r")
    assert shown.returncode == 0 and shown.stdout.rstrip().endswith(r"\end{bmatrix}")
    written = symjac("jacobian", "planar2r", "-o", str(tmp_path / "J.tex"))
    assert written.returncode == 0 and (tmp_path / "J.tex").read_text() == shown.stdout
    failed = symjac("jacobian", "no_such_robot")
    assert failed.returncode == 2 and failed.stderr.count("\n") == 1 and failed.stderr.startswith("symjac: error:")


def test_a_matrix_too_long_for_the_terminal_stops_printing_early(monkeypatch):
    import importlib

    latex_module = importlib.import_module("symjac.printing.latex")
    J = symjac.jacobian(symjac.load_robot("puma560"))
    printed = []
    original = latex_module.TextbookLatexPrinter._print_Add
    monkeypatch.setattr(latex_module.TextbookLatexPrinter, "_print_Add",
                        lambda self, expr, order=None: printed.append(expr) or original(self, expr, order))
    full = latex_module.latex(J)
    everything = len(printed)
    printed.clear()
    with pytest.raises(latex_module.LatexTooLargeError), latex_module.latex_size_limit(len(full) // 10):
        latex_module.latex(J)
    assert 0 < len(printed) < everything / 2
    with latex_module.latex_size_limit(len(full)):
        assert latex_module.latex(J) == full


def test_a_pretty_caption_writes_an_equation_as_one_line_not_as_sympy_source(cli):
    text = cli.ok("jacobian", "planar3r", "--representation", "rpy", "--format", "pretty")
    caption = next(line for line in text.splitlines() if line.startswith("Representation singularity"))
    assert "Eq(" not in caption and "θ = -π/2 or θ = π/2" in caption


def test_a_function_of_a_long_fraction_breaks_across_lines():
    # a singular condition of the Panda is theta6 - asin(N / D) with N and D of dozens of terms: a \left( ... \right)
    # pair cannot break, so the argument goes in unpaired delimiters that can, and every line fits the page
    from symjac.printing.latex_layout import TEXT_WIDTH, fit_equation, tex_width

    a, b, c = sp.symbols("a b c")
    long_sum = sum(a**k * b * sp.cos(c * k) for k in range(1, 30))
    value = sp.Symbol("theta6") - sp.asin(long_sum / (1 + long_sum.subs(a, c)))
    display = fit_equation("F_{2}", value)
    text = " \\\\\n".join(part for part in (display.main, *display.lines, *display.where) if part)
    assert r"\operatorname{asin}\Bigl(\bigl(" in text and r"\big/ \bigl(" in text and text.count(r"\Bigr)") == 1
    lines = text.split(" \\\\\n")
    assert len(lines) > 3 and all(tex_width(line) <= TEXT_WIDTH for line in lines), [tex_width(x) for x in lines]
