"""``symjac report``: one self-contained HTML page, checked structurally, numerically and in a real browser.

The browser test renders the PUMA 560 page and a URDF arm's page in headless Chromium: a copy of each page gets a
test-only script that writes what it measured (page width against the window, MathML and SVG counts, ``merror``
elements, whether ``<math>`` is laid out as MathML) into the DOM, which ``--dump-dom`` prints. A screenshot of each
page goes to ``$SYMJAC_ARTIFACTS`` (default ``tests/artifacts/``). Without Chromium the test is skipped (``.ci/run``
installs it).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from marks import marked

from symjac import load_robot
from symjac.analysis.manipulability_map import manipulability_map, singular_path
from symjac.analysis.singularity.singularities import singularities
from symjac.cli.main import main
from symjac.errors import SymjacError
from symjac.report import derivation_report
from symjac.report.figures import map_svg
from tests import reference

ARTIFACTS = Path(os.environ.get("SYMJAC_ARTIFACTS", Path(__file__).parent / "artifacts"))

VOID = {"meta", "br", "img", "input", "link", "hr", "wbr", "col", "area", "base", "source", "track", "embed"}


class _Pages(dict):
    """Report pages by robot, each written when a test first asks for it (the fast loop asks for fewer)."""

    def __init__(self, folder: Path):
        super().__init__()
        self.folder = folder

    def __missing__(self, name: str) -> Path:
        if name == "puma560":  # through the API
            page = self.folder / "puma560.html"
            page.write_text(derivation_report(load_robot("puma560"), "puma560"), encoding="utf-8")
        else:  # through the command line
            page = self.folder / f"{name.removesuffix('.urdf')}.html"
            assert main(["report", name, "-o", str(page)]) == 0
        self[name] = page
        return page


@pytest.fixture(scope="module")
def pages(tmp_path_factory) -> dict[str, Path]:
    """The PUMA 560 page (through the API), the UR5 URDF and iiwa7 pages (through the command line)."""
    return _Pages(tmp_path_factory.mktemp("report"))


class _Checker(HTMLParser):
    """Every element closed in order; every src/href kept local."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.stack: list[str] = []
        self.problems: list[str] = []
        self.links: list[str] = []
        self.tags: dict[str, int] = {}

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags[tag] = self.tags.get(tag, 0) + 1
        self.links += [value or "" for name, value in attrs if name in ("src", "href", "xlink:href")]
        if tag not in VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags[tag] = self.tags.get(tag, 0) + 1
        self.links += [value or "" for name, value in attrs if name in ("src", "href", "xlink:href")]

    def handle_endtag(self, tag: str) -> None:
        if not self.stack or self.stack[-1] != tag:
            self.problems.append(f"</{tag}> closes {self.stack[-1] if self.stack else 'nothing'}")
            return
        self.stack.pop()


@pytest.mark.parametrize("name", marked(["puma560", "ur5.urdf"], keep=["ur5.urdf"]))  # ur5.urdf: a URDF page
def test_page_is_well_formed_and_self_contained(pages, name):
    text = pages[name].read_text(encoding="utf-8")
    checker = _Checker()
    checker.feed(text)
    checker.close()
    assert not checker.problems and not checker.stack, (checker.problems[:5], checker.stack[-5:])
    assert all(link.startswith(("#", "data:")) for link in checker.links), [
        link[:60] for link in checker.links if not link.startswith(("#", "data:"))]
    assert not re.search(r"(src|href)\s*=\s*[\"']?\s*(https?:)?//", text)
    assert "<script" not in text and "@import" not in text and "url(http" not in text
    assert "mfenced" not in text and "merror" not in text
    assert checker.tags["svg"] == 2 + text.count('<figure class="arm">') and checker.tags["math"] > 40
    assert checker.tags["table"] >= 2
    # the arm drawings' parts keep their ids apart (matplotlib's own ids, figure_1 or the glyphs' DejaVuSans-11,
    # repeat from one SVG to the next, with the same content)
    ids = re.findall(r'\sid="(arm-[^"]+)"', text)
    assert ids and len(ids) == len(set(ids))
    table = {"puma560": "Modified Denavit-Hartenberg table", "ur5.urdf": "General chain (URDF-style origin and axis)"}
    for words in (table[name], "Forward kinematics", "All four methods agree",
                  "Singular configurations", "drawn exactly from its solutions", "Joint rates"):
        assert words in text, words
    assert "<msub><mi>c</mi><mn>23</mn></msub>" in text  # textbook shorthand c_23


def test_page_is_deterministic(pages, tmp_path):
    again = tmp_path / "again.html"
    assert main(["report", "ur5.urdf", "-o", str(again)]) == 0
    assert again.read_bytes() == pages["ur5.urdf"].read_bytes()


def test_the_tip_link_chooses_a_urdf_chain(gripper, tmp_path, capsys):
    assert main(["report", gripper, "-o", str(tmp_path / "x.html")]) == 2
    assert "choose --tip-link" in capsys.readouterr().err
    assert main(["report", gripper, "--tip-link", "finger_a", "-o", "-"]) == 0
    text = capsys.readouterr().out
    assert "gripper_arm: derivation report" in text and text.count("<svg") == 2 + text.count('<figure class="arm">')


def test_user_strings_are_escaped(tmp_path, capsys):
    planar = (Path(__file__).parent.parent / "symjac" / "robots" / "planar2r.toml").read_text(encoding="utf-8")
    odd = re.sub(r'(?m)^description = .*$', 'description = "<script>alert(1)</script> & <b>more</b>"', planar)
    path = tmp_path / "odd<&>.toml"
    path.write_text(odd, encoding="utf-8")
    assert main(["report", str(path), "-o", "-"]) == 0
    text = capsys.readouterr().out
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &lt;b&gt;more&lt;/b&gt;" in text
    assert "odd&lt;&amp;&gt;.toml" in text
    assert "<script" not in text and "<b>more" not in text and "odd<&>" not in text
    checker = _Checker()
    checker.feed(text)
    assert not checker.problems and not checker.stack


@pytest.mark.parametrize(("argv", "message"), [
    (["report", "nosuch"], "'nosuch' is neither a built-in robot"),
    (["report", "planar2r", "-o", "/nonexistent-dir/page.html"], "/nonexistent-dir/page.html: No such file"),
])
def test_bad_input_gives_one_clean_line(capsys, argv, message):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.splitlines()) == 1 and err.startswith("symjac: error: ") and message in err


def test_the_singular_curves_are_the_solved_factors_and_the_rates_blow_up_at_them():
    robot = load_robot("puma560")
    report = singularities(robot)
    plane = manipulability_map(robot, report, size=21)
    assert plane is not None and plane.joints == (1, 2)  # theta2 and theta3: the elbow and shoulder factors
    assert {str(curve.factor.kind) for curve in plane.curves} == {"elbow", "shoulder"}
    fixed = {v: value for k, (v, value) in enumerate(zip(robot.q, plane.configuration, strict=True))
             if k not in plane.joints}
    a, b = (robot.q[k] for k in plane.joints)
    for curve in plane.curves:
        assert curve.solutions and curve.points is not None  # drawn from the solved form, not a contour
        factor = sp.lambdify([a, b], curve.factor.expression.xreplace({**fixed, **robot.defaults}))
        x, y = curve.points
        shown = np.isfinite(x) & np.isfinite(y) & (np.abs(x) <= math.pi) & (np.abs(y) <= math.pi)
        assert shown.sum() > 100
        assert np.max(np.abs(factor(x[shown], y[shown]))) < 1e-12
    path = singular_path(robot, plane)
    exact = np.nan_to_num(np.abs(path.rates.exact), nan=np.inf).max(axis=1)
    assert exact[len(exact) // 2] > 100 * max(exact[0], exact[-1])  # grows like 1/|t| at the crossing
    assert np.abs(path.rates.damped).max() < 50


def test_a_redundant_arm_maps_its_simplest_singular_set_and_crosses_it():
    robot = load_robot("iiwa7")
    report = singularities(robot)
    plane = manipulability_map(robot, report, size=21)
    assert plane is not None and 3 in plane.joints  # the elbow set sin(theta4) = 0 is the simplest
    (mark,) = plane.sets
    assert report.sets[mark.number - 1].conditions[0].expression == sp.sin(robot.q[3])
    lines = mark.vertical if plane.joints[0] == 3 else mark.horizontal
    assert sorted(lines) == pytest.approx([-math.pi, 0.0, math.pi])
    # on the map, the manipulability vanishes along the set's lines and nowhere else on the grid
    axis_values = plane.x if plane.joints[0] == 3 else plane.y
    rows = np.isclose(np.abs(axis_values), 0) | np.isclose(np.abs(axis_values), math.pi)
    w = plane.w if plane.joints[0] != 3 else plane.w.T
    assert w[rows].max() < 1e-9 and w[~rows].min() > 1e-4
    path = singular_path(robot, plane)
    assert path.set_mark == mark
    middle = len(path.t) // 2
    sigma = [np.linalg.svd(reference.finite_difference_jacobian(robot, q), compute_uv=False)[-1]
             for q in path.configurations]
    assert min(sigma) < 1e-2 * max(sigma)
    minimum_norm = np.nan_to_num(np.abs(path.rates.exact), nan=np.inf).max(axis=1)
    assert np.isfinite(minimum_norm[0]) and minimum_norm[middle] > 50 * max(minimum_norm[0], minimum_norm[-1])
    assert np.abs(path.rates.damped).max() < 50
    J = reference.finite_difference_jacobian(robot, path.configurations[0], frame=plane.frame)
    assert np.allclose(J @ path.rates.exact[0], path.xdot, atol=1e-6)  # the minimum-norm rates do the job
    assert np.allclose(path.rates.exact[0], np.linalg.pinv(J) @ path.xdot, atol=1e-6)


def test_a_redundant_arms_page_shows_its_sets_and_self_motion(pages):
    text = pages["iiwa7"].read_text(encoding="utf-8")
    assert "4 singular sets" in text and "singular set 1: " in text
    assert "keeps one self-motion" in text and "minimum-norm rates" in text
    assert text.count('class="arm"') == 5  # home and one figure per singular set


def test_a_missing_matplotlib_is_a_clear_error(monkeypatch):
    robot = load_robot("planar2r")
    plane = manipulability_map(robot, singularities(robot), size=5)
    assert plane is not None
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    with pytest.raises(SymjacError, match=r"pip install 'symjac\[report\]'"):
        map_svg(plane, ("a", "b"))


PROBE = """<script>
(function () {
  var root = document.documentElement, width = window.innerWidth, wide = [];
  document.querySelectorAll("body *").forEach(function (e) {
    var r = e.getBoundingClientRect();
    if (r.right > width + 0.5 && wide.length < 5) wide.push(e.tagName + " right " + Math.round(r.right));
  });
  var maths = document.querySelectorAll("math"), empty = 0;
  maths.forEach(function (m) { if (m.getBoundingClientRect().width < 1) empty++; });
  var arms = document.querySelectorAll("figure.arm svg"), shown = 0;
  arms.forEach(function (svg) {  // drawn: the figure has a size on the page and so do its links and an axis
    var links = svg.querySelector('g[id$="-links"]'), frame = svg.querySelector('g[id*="-frame-"]');
    if (svg.getBoundingClientRect().width > 150 && links && links.getBoundingClientRect().height > 5
        && frame && frame.getBoundingClientRect().width > 0) shown++;
  });
  var out = {scrollWidth: root.scrollWidth, innerWidth: width, math: maths.length, emptyMath: empty,
             arms: arms.length, armsShown: shown,
             arrows: document.querySelectorAll('figure.arm g[id$="-arrow"]').length,
             svg: document.querySelectorAll("svg").length, merror: document.querySelectorAll("merror").length,
             mathDisplay: maths.length ? getComputedStyle(maths[0]).display : "", wide: wide,
             height: root.scrollHeight, text: document.body.innerText.length};
  var pre = document.createElement("pre");
  pre.id = "symjac-probe";
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
</script>"""


def _chromium() -> str | None:
    return next((path for name in ("chromium", "chromium-browser") if (path := shutil.which(name))), None)


def _browser(binary: str, *arguments: str) -> subprocess.CompletedProcess[str]:
    with tempfile.TemporaryDirectory() as profile:  # a fresh, empty profile: nothing from earlier runs
        command = [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                   "--disable-background-networking", "--disable-component-update", "--disable-sync",
                   f"--user-data-dir={profile}", "--window-size=1280,2000", *arguments]
        return subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)


@pytest.mark.parametrize("name", ["puma560", "ur5.urdf", "iiwa7"])
@pytest.mark.external
def test_the_page_renders_in_chromium(pages, tmp_path, name):
    binary = _chromium()
    if binary is None:
        pytest.skip("chromium is not installed (.ci/run installs it: apt-get install chromium)")
    page = pages[name]
    probed = tmp_path / "probed.html"
    probed.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
    result = _browser(binary, "--dump-dom", probed.as_uri())
    found = re.search(r'<pre id="symjac-probe">(.*?)</pre>', result.stdout)
    assert found, result.stderr[-2000:]
    seen = json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert seen["merror"] == 0 and seen["emptyMath"] == 0, seen
    assert seen["math"] > 40 and seen["svg"] == 2 + seen["arms"] and seen["text"] > 2000, seen
    assert seen["height"] > 2000, seen
    # the arm at home and at each solved singular configuration, each with its lost direction
    assert seen["arms"] == seen["armsShown"] == 1 + seen["arrows"] and seen["arrows"] >= 2, seen
    assert "math" in seen["mathDisplay"], seen  # laid out as MathML, not as unknown inline elements
    assert seen["scrollWidth"] <= seen["innerWidth"] and not seen["wide"], seen  # nothing wider than the page
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    screenshot = ARTIFACTS / f"report-{name.replace('.', '-')}.png"
    screenshot.unlink(missing_ok=True)
    _browser(binary, f"--screenshot={screenshot}", page.as_uri())
    assert screenshot.is_file() and screenshot.stat().st_size > 20_000


@pytest.mark.parametrize("name", marked(["puma560", "stanford", "ur5_poe"]))
def test_the_arrow_at_the_tool_is_the_lost_direction_in_the_world(name):
    from symjac import numeric_jacobian
    from symjac.report.page import lost_arrow

    robot = load_robot(name)
    report = singularities(robot)
    drawn, kinds = 0, set()
    for factor in report.factors:
        arrow = lost_arrow(robot, report, factor)
        if arrow is None:
            continue
        drawn += 1
        direction, shown = arrow
        q = np.array(factor.sample)
        # the whole lost direction, turned into the world: no joint rate moves the arm along it
        R = reference.frames(robot, q)[reference.frame_index(robot, report.frame)][:3, :3]
        u = np.concatenate([R @ factor.lost_direction.full[:3], R @ factor.lost_direction.full[3:]])
        J = numeric_jacobian(robot, q.tolist(), "world", report.determinant.point)
        assert np.abs(u @ J).max() < 1e-9
        half = u[3:] if shown == "angular" else u[:3]
        np.testing.assert_allclose(direction, half / np.linalg.norm(half), atol=1e-9)
        rows = J[3:] if shown == "angular" else J[:3]
        lost_alone = np.abs(direction @ rows).max() < 1e-7
        assert lost_alone == (shown != "mixed"), (name, factor.expression, shown)
        kinds.add(shown)
    assert drawn >= 2
    if name == "puma560":  # the elbow and the shoulder lose a translation; the wrist a translation with a turn
        assert kinds == {"linear", "mixed"}


# --- the dynamics section -------------------------------------------------------------------------------------------

ROD_ARM = """\
name = "rod_arm"
description = "A planar 2R arm of two slender rods"
convention = "standard"

[parameters]
L1 = 0.5
L2 = 0.4
m1 = 2.0
m2 = 1.5

[[joints]]
type = "revolute"
a = "L1"
[joints.inertial]
mass = "m1"
com = ["-L1/2", 0, 0]
iyy = "m1*L1**2/12"
izz = "m1*L1**2/12"

[[joints]]
type = "revolute"
a = "L2"
[joints.inertial]
mass = "m2"
com = ["-L2/2", 0, 0]
iyy = "m2*L2**2/12"
izz = "m2*L2**2/12"
"""


@pytest.fixture(scope="module")
def rod_page(tmp_path_factory) -> Path:
    """The report of :data:`ROD_ARM`, an arm with inertial data, through the command line."""
    folder = tmp_path_factory.mktemp("rod")
    (folder / "rod_arm.toml").write_text(ROD_ARM, encoding="utf-8")
    assert main(["report", str(folder / "rod_arm.toml"), "-o", str(folder / "rod_arm.html")]) == 0
    return folder / "rod_arm.html"


def test_the_dynamics_section_shows_m_g_and_tau(rod_page):
    text = rod_page.read_text(encoding="utf-8")
    section = text[text.index('<section id="dynamics">'):]
    section = section[:section.index("</section>")]
    assert '<a href="#dynamics">Dynamics</a>' in text
    for words in ("Mass matrix M(q)", "Gravity torques g(q)", "Joint torques tau", "gravity g along -z0"):
        assert words in section, words
    assert '<mover accent="true"><mi>&#952;</mi><mo>&#168;</mo></mover><mn>1</mn>' in section  # theta-double-dot_1
    assert "<msub><mi>c</mi><mn>2</mn></msub>" in section  # shorthand: M12 holds L1 lc2 c2


def test_a_part_nobody_could_read_is_named_not_printed(monkeypatch):
    from symjac.model.io import robot_from_toml
    from symjac.report import dynamics

    robot = robot_from_toml(ROD_ARM, "rod_arm.toml")
    assert "Mass matrix M(q)" in dynamics.dynamics_html(robot)
    monkeypatch.setattr(dynamics, "READABLE_CHARACTERS", 60)  # longer than g, shorter than M
    text = dynamics.dynamics_html(robot)
    assert "Mass matrix M(q)" not in text and "Gravity torques g(q)" in text
    assert "The mass matrix M of this arm runs to more than 60 characters" in text
    assert "symjac codegen rod_arm --dynamics" in text


def test_an_arm_without_inertial_data_says_which_links_lack_it():
    from symjac.report.dynamics import dynamics_html

    planar = load_robot("planar2r")
    text = dynamics_html(dataclasses.replace(planar, parameters=planar.geometric_parameters, inertials=()))
    assert text.count("<p") == 1 and "links 1, 2 have no inertial data" in text and "--symbolic-inertials" in text


@pytest.mark.external
def test_the_dynamics_section_renders_in_chromium(rod_page, tmp_path):
    binary = _chromium()
    if binary is None:
        pytest.skip("chromium is not installed (.ci/run installs it: apt-get install chromium)")
    probed = tmp_path / "probed.html"
    probed.write_text(rod_page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
    result = _browser(binary, "--dump-dom", probed.as_uri())
    found = re.search(r'<pre id="symjac-probe">(.*?)</pre>', result.stdout)
    assert found, result.stderr[-2000:]
    seen = json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert seen["merror"] == 0 and seen["emptyMath"] == 0, seen
    assert seen["scrollWidth"] <= seen["innerWidth"] and not seen["wide"], seen
