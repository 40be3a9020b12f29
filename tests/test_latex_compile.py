"""Every standalone LaTeX document symjac writes compiles with pdflatex and fits its page.

Each command (show, fk, every Jacobian method with its steps, torques, singularities, representation Jacobians,
``--numeric``, the Hessian and the time derivative) runs on every catalog robot, a URDF robot and a robot whose name,
description and parameters carry underscores and other TeX specials. Documents are generated in-process with
``symjac.cli.main.main`` (two worker processes, one robot's commands per task so the chain's caches serve them all) and
compiled two at a time while the rest are still being derived. A document fails on any TeX error and on any box
more than :data:`TOLERANCE` points too wide or too tall.

pdflatex comes from Debian's texlive-latex-base and texlive-latex-recommended (``.ci/run`` installs them when
missing); without it locally, these tests are skipped and say why.
"""

from __future__ import annotations

import json
import multiprocessing
import re
import shutil
import subprocess
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import pytest
import sympy as sp

from symjac.cli.main import main
from symjac.model.io import catalog
from symjac.printing import Block, Document, Equation, latex_layout, render
from symjac.printing import document as document_module
from symjac.printing.latex_layout import Display
from symjac.symbolic import nested

PDFLATEX = shutil.which("pdflatex")
pytestmark = [pytest.mark.external,
              pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed (Debian: apt-get install "
                                 "texlive-latex-base texlive-latex-recommended); .ci/run installs it")]

TOLERANCE = 3.0  # points; TeX's own \hfuzz is 0.1 pt, a few points are invisible on the page
_BOX = re.compile(r"Overfull \\[hv]box \((\d+(?:\.\d+)?)pt too (?:wide|high)\)")

MY_ARM = """\
name = "my_arm"
description = "My_arm: a test arm with 100% of the #TeX specials & an under_score"
convention = "standard"

[parameters]
link_1 = 0.3
L_2 = 0.25
d_off = 0.089159

[[joints]]
type = "revolute"
alpha = "pi/2"
a = 0
d = "d_off"
theta = 0

[[joints]]
type = "revolute"
alpha = 0
a = "link_1"
d = 0
theta = 0
limits = [-1.5, 1.5]

[[joints]]
type = "prismatic"
alpha = 0
a = "L_2"
d = 0
theta = 0
limits = [0.1, 0.4]
"""

COMMANDS: dict[str, list[str]] = {
    "show": ["show"],
    "show-numeric": ["show", "--numeric"],
    "fk": ["fk"],
    "fk-numeric": ["fk", "--numeric", "--digits", "3"],
    "jacobian": ["jacobian"],
    "jacobian-numeric": ["jacobian", "--numeric"],
    "cross-product": ["jacobian", "--method", "cross_product", "--frame", "2"],
    "velocity-steps": ["jacobian", "--method", "velocity_propagation", "--steps"],
    "force-steps": ["jacobian", "--method", "force_propagation", "--steps"],
    "force-steps-numeric": ["jacobian", "--method", "force_propagation", "--steps", "--numeric"],
    "cross-product-steps": ["jacobian", "--method", "cross_product", "--steps", "--frame", "2"],
    "differentiation-steps": ["jacobian", "--method", "differentiation", "--steps", "--frame", "2"],
    "torques": ["torques"],
    "singularities": ["singularities"],
    "zyz": ["jacobian", "--representation", "zyz"],
    "quaternion-numeric": ["jacobian", "--representation", "quaternion", "--numeric"],
    "hessian": ["hessian"],
    "derivative-steps": ["jacobian", "--derivative", "--steps"],
}
ROBOTS = [*catalog(), "ur5.urdf", "my_arm"]
SLOW_FIRST = ("panda", "ur5.urdf", "ur5", "puma560")  # longest derivations start first, so both workers finish together
DOCUMENTS = [f"{robot}-{name}" for robot in ROBOTS for name in COMMANDS] + ["errata"]


def problems(log: str) -> list[str]:
    """What is wrong with a compiled document, from its pdflatex log: errors, then boxes too wide or too tall."""
    found = [line for line in log.splitlines() if line.startswith("!")]
    found += [f"{match.group(0)}" for match in _BOX.finditer(log) if float(match.group(1)) > TOLERANCE]
    return found


def compile_tex(path: Path) -> list[str]:
    """Run pdflatex on ``path`` (in its folder) and return :func:`problems`, or why it did not run."""
    assert PDFLATEX is not None
    try:
        subprocess.run([PDFLATEX, "-halt-on-error", "-interaction=nonstopmode", "-no-shell-escape", path.name],
                       cwd=path.parent, capture_output=True, timeout=180, check=False)
    except subprocess.TimeoutExpired:
        return ["pdflatex timed out"]
    log = path.with_suffix(".log")
    return problems(log.read_text(encoding="latin-1")) if log.exists() else ["pdflatex wrote no log"]


def _generate(robot: str, folder: str) -> list[tuple[str, int]]:
    """Every command's standalone document for one robot (one process: the chain's caches serve all of them)."""
    source = str(Path(folder) / "my_arm.toml") if robot == "my_arm" else robot
    stem = robot.replace(".", "_")
    statuses = []
    for name, command in COMMANDS.items():
        path = Path(folder) / f"{stem}-{name}.tex"
        statuses.append((f"{robot}-{name}", main([command[0], source, *command[1:], "--standalone", "-o", str(path)])))
    return statuses


@pytest.fixture(scope="module")
def compiled(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[str]]:
    """Each document's problems (``[]`` when it compiled cleanly), keyed ``robot-command``."""
    folder = tmp_path_factory.mktemp("latex")
    (folder / "my_arm.toml").write_text(MY_ARM, encoding="utf-8")
    assert main(["errata", "--format", "latex", "-o", str(folder / "errata.tex")]) == 0
    order = sorted(ROBOTS, key=lambda robot: SLOW_FIRST.index(robot) if robot in SLOW_FIRST else len(SLOW_FIRST))
    results: dict[str, list[str]] = {}
    # Workers come from a fork server, a fresh interpreter: never forked from this process, which may run threads
    # by now (the jax code generation tests start JAX's, and a fork of a threaded process can deadlock).
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("forkserver")) as derive, \
            ThreadPoolExecutor(2) as tex:
        tasks = [derive.submit(_generate, robot, str(folder)) for robot in order]
        compiles = {"errata": tex.submit(compile_tex, folder / "errata.tex")}
        for task in tasks:
            for name, status in task.result():
                if status != 0:
                    results[name] = [f"symjac exited with status {status}"]
                else:
                    compiles[name] = tex.submit(compile_tex, folder / f"{name.replace('.urdf', '_urdf')}.tex")
        results.update({name: future.result() for name, future in compiles.items()})
    return results


@pytest.mark.parametrize("name", DOCUMENTS)
def test_document_compiles_and_fits(compiled, name):
    assert compiled[name] == [], f"{name}.tex: {compiled[name]}"


# --- the check itself can fail ----------------------------------------------------------------------------------


def _render_and_compile(tmp_path: Path, document: Document) -> list[str]:
    path = tmp_path / "doc.tex"
    path.write_text(render(document, "latex", standalone=True), encoding="utf-8")
    return compile_tex(path)


def test_an_unescaped_caption_fails(tmp_path, monkeypatch):
    monkeypatch.setattr(document_module, "escape_text", lambda text: text)  # captions as they were before escaping
    document = Document("a_b", "demo", (Block(("Determinant of rows v_x, v_y:",), ()),))
    assert any("Missing $ inserted" in problem for problem in _render_and_compile(tmp_path, document))


def test_a_matrix_wider_than_the_page_fails_unless_laid_out(tmp_path, monkeypatch):
    x = sp.Symbol("x")
    wide = sp.Matrix([[sum(x**k for k in range(1, 40)) for _ in range(3)]])
    document = Document("wide", "demo", (Block((), (Equation("M", "M", wide),)),))
    assert _render_and_compile(tmp_path, document) == []  # laid out: entries named and broken over lines
    unbroken = lambda lhs, rhs: Display(f"{lhs} = {document_module.latex(rhs)}")  # noqa: E731
    monkeypatch.setattr(latex_layout, "fit_equation", unbroken)  # the layout module, which render imports when used
    assert any("Overfull" in problem for problem in _render_and_compile(tmp_path, document))


# --- a line fits whatever the form of its expression -------------------------------------------------------------
# The Panda's singular condition theta6 - asin(N / D) (sets 4 and 5 of its singularities document) once printed as
# two lines 142 pt too wide: its breaking depended on the layout recognizing a function of a fraction. The TeX side
# is the same on every machine (amsmath and geometry from texlive-latex-base, no optional package, Computer Modern);
# what a line breaks at must not depend on the form either. Hidden in an UnevaluatedExpr the condition prints alike
# but shows the layout no structure: the text fallback (latex_layout.break_tex) alone has to break it.


def _panda_condition(tmp_path: Path) -> sp.Expr:
    path = tmp_path / "panda.json"
    assert main(["singularities", "panda", "--format", "json", "-o", str(path)]) == 0
    conditions = [c for s in json.loads(path.read_text(encoding="utf-8"))["sets"] for c in s["conditions"]]
    condition = max((c for c in conditions if "asin" in c), key=len).removesuffix(" = 0")
    names = {n: sp.Symbol(n, real=True) for n in re.findall(r"[A-Za-z_]\w*", condition)
             if n not in ("asin", "sin", "cos", "pi")}
    return sp.sympify(condition, locals=names)


def test_a_long_condition_fits_when_the_layout_cannot_see_its_form(tmp_path, monkeypatch):
    condition = _panda_condition(tmp_path)
    hidden = sp.UnevaluatedExpr(condition)
    document = Document("panda", "F", (Block(("The condition, then the same with its form hidden:",),
                                             (Equation("F_{4}", "F_4", condition), Equation("F_{4}", "F_4", hidden),
                                              Equation("G", "G", 2 * sp.asin(condition - sp.Symbol("theta6"))))),))
    text = render(document, "latex", standalone=True)
    assert text.count(r"\big/") >= 3 and r"{\left(" not in text.split(r"\section*")[1]
    assert _render_and_compile(tmp_path, document) == []
    monkeypatch.setattr(latex_layout, "break_tex", lambda tex, first=0.0, rest=0.0: [tex])  # without the fallback
    problems = _render_and_compile(tmp_path, document)
    assert problems and all("Overfull" in problem for problem in problems), problems


def test_a_long_equation_among_short_ones_is_split(tmp_path, monkeypatch):
    condition = _panda_condition(tmp_path)
    texts = [r"\theta_{5} = \pi", "F_{5} = " + document_module.latex(sp.UnevaluatedExpr(condition))]
    body = latex_layout.fit_side_by_side(texts)
    assert r"\begin{split}" in body
    path = tmp_path / "gather.tex"
    page = "\\documentclass{article}\n\\usepackage{amsmath}\n\\usepackage[margin=1.5cm, landscape]{geometry}\n"
    path.write_text(f"{page}\\begin{{document}}\n{body}\n\\end{{document}}\n", encoding="utf-8")
    assert compile_tex(path) == []
    monkeypatch.setattr(latex_layout, "break_tex", lambda tex, first=0.0, rest=0.0: [tex])  # without the fallback
    path.write_text(f"{page}\\begin{{document}}\n{latex_layout.fit_side_by_side(texts)}\n\\end{{document}}\n",
                    encoding="utf-8")
    assert any("Overfull" in problem for problem in compile_tex(path))


# --- generic geometry: nested results with "where" lines -------------------------------------------------------

GENERIC6 = 'name = "generic6"\nconvention = "standard"\n' + "".join(
    f'[[joints]]\ntype = "revolute"\na = {a}\nd = {d}\nalpha = {alpha}\n'
    for a, d, alpha in [(0.05, 0.33, 1.5702), (0.44, 0.01, 0.003), (0.035, 0.0, 1.5712), (0.001, 0.42, -1.5699),
                        (0.0, 0.002, 1.5705), (0.0, 0.08, 0.0)])
"""A 6-joint arm with twists near, not at, pi/2: its results stay nested (intermediates w_k and their definitions)."""

GENERIC_COMMANDS = {"fk": ["fk"], "jacobian": ["jacobian"], "frame2": ["jacobian", "--frame", "2"],
                    "hessian": ["hessian"], "torques": ["torques"], "derivative": ["jacobian", "--derivative"]}


@pytest.mark.parametrize("name", GENERIC_COMMANDS)
def test_nested_results_compile_standalone_and_bare(tmp_path, capsys, name, monkeypatch):
    """The standalone document (where-lines in an ``align*``) and the bare lines (``gathered`` blocks) compile."""
    monkeypatch.setattr(nested, "INLINE_LIMIT", 1000)  # every one of these results nested
    robot = tmp_path / "generic6.toml"
    robot.write_text(GENERIC6, encoding="utf-8")
    command = GENERIC_COMMANDS[name]
    standalone = tmp_path / "standalone.tex"
    assert main([command[0], str(robot), *command[1:], "--standalone", "-o", str(standalone)]) == 0
    assert r"w_{1} &= " in standalone.read_text(encoding="utf-8")
    assert main([command[0], str(robot), *command[1:]]) == 0
    bare = capsys.readouterr().out
    assert r"\text{where } \begin{aligned}[t]" in bare
    wrapped = tmp_path / "bare.tex"
    displays = "\n".join(rf"\[ {unit} \]" for unit in _bare_units(bare))
    wrapped.write_text("\\documentclass{article}\n\\usepackage{amsmath}\n\\usepackage[paperwidth=200cm, "
                       "paperheight=200cm]{geometry}\n\\setcounter{MaxMatrixCols}{20}\n\\allowdisplaybreaks\n"
                       f"\\begin{{document}}\n{displays}\n\\end{{document}}\n", encoding="utf-8")
    assert compile_tex(standalone) == []
    assert [p for p in compile_tex(wrapped) if not p.startswith("Overfull")] == []


def _bare_units(text: str) -> list[str]:
    """Bare LaTeX output as the units a reader pastes into a display: one line, or one ``gathered`` block."""
    units: list[str] = []
    inside = False
    for line in text.splitlines():
        if inside:
            units[-1] += "\n" + line
            inside = line != r"\end{gathered}"
        else:
            units.append(line)
            inside = line == r"\begin{gathered}"
    return units


# --- the dynamics: planar2r with symbolic inertial parameters (the catalog loop above has none to derive with) -----


@pytest.mark.parametrize("options", [["--steps", "--gravity=-y"],
                                     ["--mass-matrix", "--coriolis", "--gravity-torques", "--energy", "--torques"],
                                     ["--numeric", "--gravity-torques", "--mass-matrix"]],
                         ids=["steps", "every-part", "numeric"])
def test_the_dynamics_document_compiles_and_fits(tmp_path, options):
    path = tmp_path / "dynamics.tex"
    assert main(["dynamics", "planar2r", "--symbolic-inertials", *options, "--standalone", "-o", str(path)]) == 0
    assert compile_tex(path) == []
