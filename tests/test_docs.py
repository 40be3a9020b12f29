"""The documentation site: built with warnings as errors, read in a real browser, complete, its programs compiled.

The site is built once per session (``python -m sphinx -W --keep-going -n``) unless ``SYMJAC_DOCS_HTML`` names one
already built, as ``.ci/run`` does right after its own build. Headless Chromium opens the index, the page of
:func:`symjac.jacobian` and a tutorial, lets MathJax run, and reports what it typeset and every link; each internal
link must lead to an existing page and anchor.
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from urllib.parse import unquote, urldefrag

import pytest

import symjac

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))

PROBE = """<script>
window.addEventListener("load", function () {
  function report() {
    var maths = document.querySelectorAll("span.math, div.math");
    var out = {
      math: maths.length,
      typeset: document.querySelectorAll("span.MathJax_SVG, div.MathJax_SVG_Display").length,
      errors: document.querySelectorAll(".MathJax_Error, merror, .MathJax_SVG merror").length,
      raw: /\\\\\\(|\\\\\\[/.test(document.body.innerText),
      links: Array.prototype.map.call(document.querySelectorAll("a[href]"), function (a) {
        return a.getAttribute("href"); })
    };
    var pre = document.createElement("pre");
    pre.id = "symjac-probe";
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  if (window.MathJax && MathJax.Hub) { MathJax.Hub.Queue(report); } else { report(); }
});
</script>"""


@pytest.fixture(scope="session")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    built = os.environ.get("SYMJAC_DOCS_HTML")
    if built and (Path(built) / "index.html").is_file():
        return Path(built).resolve()
    pytest.importorskip("sphinx")
    from sphinx.errors import ConfigError
    from symjac_docs import mathjax_source

    try:
        mathjax_source()
    except ConfigError as missing:
        pytest.skip(f"{missing} (.ci/run installs it)")
    output = tmp_path_factory.mktemp("site")
    result = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q", "-b", "html",
                             str(DOCS), str(output)], capture_output=True, text=True, timeout=1800, check=False)
    assert result.returncode == 0, result.stderr[-4000:]
    return output


def test_every_public_name_has_its_place_in_the_reference():
    """The generator puts every name of every package ``__all__`` on a stage page (or, for ``codegen.lower``,
    which shares its name with its module, on that module's page)."""
    import importlib.util

    from symjac_docs import STAGES, identity, public_names

    listed = {name for names in public_names().values() for name in names}
    assert {f"symjac.{name}" for name in symjac.__all__} <= listed
    identities = {identity(name) for name in listed}
    for stage, _, _ in STAGES:
        if stage == "errors":
            continue
        package = importlib.import_module(f"symjac.{stage}")
        for name in getattr(package, "__all__", ()):
            qualified = f"symjac.{stage}.{name}"
            assert identity(qualified) in identities or importlib.util.find_spec(qualified), qualified


@pytest.mark.slow
@pytest.mark.external
def test_every_public_name_appears_in_the_built_reference(site: Path):
    import importlib

    from sphinx.util.inventory import InventoryFile

    with open(site / "objects.inv", "rb") as stream:
        inventory = InventoryFile.load(stream, "", lambda base, path: path)
    names = {name for entries in inventory.values() for name in entries}
    for package_name in ["symjac"] + [f"symjac.{stage}" for stage in ("printing", "drawing", "codegen", "report",
                                                                      "sweeps")]:
        package = importlib.import_module(package_name)
        for name in package.__all__:
            value = getattr(package, name)
            homes = {f"{package_name}.{name}", f"symjac.{name}"}
            if getattr(value, "__qualname__", None):
                homes.add(f"{value.__module__}.{value.__qualname__}")
            assert homes & names, f"{package_name}.{name} is not in the API reference"


def _chromium() -> str | None:
    return next((path for name in ("chromium", "chromium-browser") if (path := shutil.which(name))), None)


def _rendered(binary: str, page: Path, tmp_path: Path) -> dict:
    probed = page.with_name(f"{page.stem}.probe.html")
    probed.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
    try:
        profile = tmp_path / "profile"
        result = subprocess.run([binary, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                                 "--disable-background-networking", "--disable-component-update",
                                 f"--user-data-dir={profile}", "--allow-file-access-from-files",
                                 "--virtual-time-budget=30000", "--window-size=1280,2000", "--dump-dom",
                                 probed.as_uri()], capture_output=True, text=True, timeout=120, check=False)
    finally:
        probed.unlink()
    found = re.search(r'<pre id="symjac-probe"[^>]*>(.*?)</pre>', result.stdout, flags=re.S)
    assert found, result.stderr[-2000:]
    return json.loads(html.unescape(found.group(1)))


def _broken_links(site: Path, page: Path, links: list[str]) -> list[str]:
    broken = []
    for link in links:
        if re.match(r"^[a-z][a-z0-9+.-]*:", link):  # http:, https:, mailto: lead out of the site
            continue
        path, fragment = urldefrag(link)
        target = (page.parent / unquote(path)).resolve() if path else page
        if target.is_dir():
            target = target / "index.html"
        inside = target.is_file() and site.resolve() in target.parents
        if not inside or (fragment and f'id="{fragment}"' not in target.read_text(encoding="utf-8")):
            broken.append(link)
    return broken


@pytest.mark.parametrize("page", ["index.html", "api/generated/symjac.jacobian.html",
                                  "tutorials/notebooks/01_differential_motion_2r.html"])
@pytest.mark.slow
@pytest.mark.external
def test_the_page_is_typeset_and_its_links_resolve(site: Path, page: str, tmp_path: Path):
    binary = _chromium()
    if binary is None:
        pytest.skip("chromium is not installed (.ci/run installs it: apt-get install chromium)")
    seen = _rendered(binary, site / page, tmp_path)
    assert seen["math"] > 0, seen  # each of these pages has math
    assert seen["typeset"] >= seen["math"] and seen["errors"] == 0, seen
    assert not seen["raw"], "TeX source is visible on the page"
    assert len(seen["links"]) > 10, seen
    assert _broken_links(site, site / page, seen["links"]) == []


def _code(page: str, language: str) -> str:
    (block,) = re.findall(rf"^```{language}\n(.*?)^```", (DOCS / page).read_text(encoding="utf-8"), re.M | re.S)
    return block


@pytest.mark.external
def test_the_c99_page_program_compiles_and_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    from symjac.cli.main import main

    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed (.ci/run installs it)")
    monkeypatch.chdir(tmp_path)
    assert main(["codegen", "puma560", "--target", "c99", "-o", "puma560_c99"]) == 0
    (tmp_path / "main.c").write_text(_code("targets/c99.md", "c"), encoding="utf-8")
    build = subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2", "-I",
                            "puma560_c99", "main.c", "puma560_c99/puma560.c", "-lm", "-o", "main"],
                           capture_output=True, text=True, check=False)
    assert build.returncode == 0, build.stderr
    run = subprocess.run(["./main"], capture_output=True, text=True, check=False)
    assert run.returncode == 0 and "det J" in run.stdout, run.stdout + run.stderr


@pytest.mark.external
def test_the_cpp_page_program_compiles_and_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    from symjac.cli.main import main

    if shutil.which("g++") is None or not Path("/usr/include/eigen3/Eigen/Dense").is_file():
        pytest.skip("g++ or Eigen's headers are not installed (.ci/run installs them)")
    monkeypatch.chdir(tmp_path)
    assert main(["codegen", "puma560", "--target", "cpp", "-o", "puma560.hpp"]) == 0
    (tmp_path / "main.cpp").write_text(_code("targets/cpp.md", "cpp"), encoding="utf-8")
    build = subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-O2", "-I", "/usr/include/eigen3",
                            "main.cpp", "-o", "main"], capture_output=True, text=True, check=False)
    assert build.returncode == 0, build.stderr
    run = subprocess.run(["./main"], capture_output=True, text=True, check=False)
    assert run.returncode == 0 and "det J" in run.stdout, run.stdout + run.stderr
