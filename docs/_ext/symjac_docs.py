"""Pages of the symjac site made at build time, so that they follow the code.

* ``api/``: the API reference. Every name of ``symjac.__all__`` goes on the page of the pipeline stage whose
  folder defines it, and every name a sub-package adds in its own ``__all__`` goes on that sub-package's page; each
  page is one ``autosummary`` table, and autosummary writes one page per name.
* ``tutorials/``: the teaching notebooks, copied from ``notebooks/`` (percent scripts, read by jupytext; myst-nb
  executes them and caches the results).
* ``_static/mathjax``: the part of Debian's MathJax 2 (``libjs-mathjax``) that typesets TeX as SVG, so that math is
  rendered without a network. ``SYMJAC_MATHJAX`` names another MathJax 2 folder.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import inspect
import os
import pkgutil
import shutil
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx.errors import ConfigError
from sphinx.pycode import ModuleAnalyzer
from sphinx.util import logging

import symjac

DOCS = Path(__file__).resolve().parent.parent
REPO = DOCS.parent
LOGGER = logging.getLogger(__name__)
_PUBLIC: dict[object, str] = {}
"""Filled at builder-inited: the identity of each public name (see :func:`identity`) -> that name."""

STAGES: list[tuple[str, str, str]] = [
    ("symbolic", "Symbolic tools",
     "Exact simplification in textbook form, the shorthand basis of angles, and the 6 x 6 maps of twists and "
     "wrenches between frames."),
    ("model", "Robots",
     "A robot as data: joints, parameters, conventions (standard and modified DH, general transforms, product of "
     "exponentials), robot files in TOML, URDF and MuJoCo (MJCF) files and the built-in catalog."),
    ("kinematics", "Kinematics",
     "Link transforms and forward kinematics, the basic Jacobian by four methods, statics, screw Jacobians, and the "
     "acceleration level (Hessian, dJ/dt, bias acceleration)."),
    ("analysis", "Analysis",
     "Singular configurations and sets, determinants, the four fundamental spaces, joint rates, representation "
     "Jacobians and the gradient of the manipulability."),
    ("printing", "Printing", "LaTeX and plain text in textbook shorthand (s1, c12, s23)."),
    ("drawing", "Drawing the arm", "The arm in 3-D with its frames, ellipsoids and singular directions "
     "(extra ``draw``)."),
    ("quantities", "Quantities", "Each derived quantity as one spec: its derivation, coupling law, document, "
     "command and codegen kind (the seam new quantities plug into)."),
    ("codegen", "Code generation",
     "Numeric modules from the derived expressions: Python, NumPy, lambdify, a C extension, C99, C++/Eigen, JAX and "
     "CasADi."),
    ("solvers", "Solvers", "Inverse kinematics: every configuration reaching a pose, in closed form where the "
     "geometry has one, else numerically, each solution checked by forward kinematics."),
    ("report", "Report", "The derivation as one HTML page (extra ``report``)."),
    ("sweeps", "Design sweeps", "Singular and dexterity measures over parameter grids, on dask (extra ``sweep``)."),
    ("errors", "Errors and version", "Every error symjac raises derives from :class:`symjac.SymjacError`; each says "
     "what was wrong and where."),
]
"""(folder, title, one-line summary) of each pipeline stage with public names, in pipeline order."""


def public_names() -> dict[str, list[str]]:
    """Qualified public names per stage folder: ``symjac.X`` for the top level, ``symjac.<stage>.X`` for the rest.

    A top-level name goes to the stage that defines it (its ``__module__``, or the module :mod:`symjac` imports it
    from); a sub-package's name that is the same object as a top-level one is not listed twice.
    """
    pages: dict[str, list[str]] = {stage: [] for stage, _, _ in STAGES}
    top_level = set()
    for name in symjac.__all__:
        if name not in symjac._HOME and name != "__version__":
            raise ConfigError(f"symjac.{name} is in symjac.__all__ but not imported under symjac's TYPE_CHECKING block")
        stage = symjac._HOME.get(name, "symjac._version").split(".")[1]
        stage = "errors" if stage in ("_version", "errors") else stage
        if stage not in pages:
            raise ConfigError(f"symjac.{name} comes from symjac.{stage}, which is no stage of the API reference")
        pages[stage].append(f"symjac.{name}")
        top_level.add(identity(f"symjac.{name}"))
    for stage in pages:
        if stage == "errors":  # a module, not a stage folder
            continue
        package = importlib.import_module(f"symjac.{stage}")
        for name in getattr(package, "__all__", ()):
            shadows_module = importlib.util.find_spec(f"symjac.{stage}.{name}") is not None
            if identity(f"symjac.{stage}.{name}") not in top_level and not shadows_module:  # codegen.lower
                pages[stage].append(f"symjac.{stage}.{name}")
    return pages


def _is_code(value: object) -> bool:
    """A class or a function: an object with one identity wherever it is imported (unlike a shared tuple)."""
    return inspect.isclass(value) or inspect.isroutine(value)


def identity(qualified: str) -> object:
    """What makes two public names one object: the identity of a class or function, the home of a constant."""
    package, name = qualified.rsplit(".", 1)
    value = getattr(importlib.import_module(package), name)
    return id(value) if _is_code(value) else (home_module(qualified), name)


def home_module(qualified: str) -> str:
    """The module whose source assigns the public name ``qualified`` (``symjac.X`` or ``symjac.<stage>.X``).

    Imports are followed from module to module (``symjac.codegen`` takes ``STRATEGIES`` from ``.module``, which
    takes it from ``.request``) until one assigns the name.
    """
    package, name = qualified.rsplit(".", 1)
    module = symjac._HOME.get(name, "symjac._version") if package == "symjac" else package
    for _ in range(10):
        source = _module_source(module)
        imported = None
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.ImportFrom) and any(alias.name == name for alias in node.names):
                imported = importlib.util.resolve_name("." * node.level + (node.module or ""), _package_of(module))
        if imported is None:
            return module
        module = imported
    return module


def _module_source(module: str) -> str:
    spec = importlib.util.find_spec(module)
    assert spec is not None and spec.origin is not None, module
    return Path(spec.origin).read_text(encoding="utf-8")


def _package_of(module: str) -> str:
    """The package relative imports of ``module`` start from: itself for a package, else its parent."""
    spec = importlib.util.find_spec(module)
    return module if spec is not None and spec.submodule_search_locations else module.rsplit(".", 1)[0]


def data_docstring(app: Sphinx, what: str, name: str, obj: object, options: Any, lines: list[str]) -> None:
    """A constant's documentation is the docstring under its assignment in its home module, not its type's.

    autodoc looks for that docstring in the module the name is documented under (``symjac``, ``symjac.sweeps``),
    finds none because the name is only imported there, and falls back to the value's class (NumPy's ``ndarray``,
    ``tuple``). This hook reads it where it is written.
    """
    if what != "data" or not name.startswith("symjac."):
        return
    home = home_module(name)
    attribute = name.rsplit(".", 1)[1]
    found = ModuleAnalyzer.for_module(home).find_attr_docs().get(("", attribute))
    lines[:] = list(found) if found else []
    if not found and name.count(".") <= 2 and not inspect.isclass(obj):  # a public constant: symjac(.<stage>).X
        LOGGER.warning(f"{name} has no docstring under its assignment in {home}")


def _write_if_changed(path: Path, text: str) -> Path:
    """Write ``text`` unless the file already holds it (an unchanged file keeps Sphinx's cache valid)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")
    return path


def _remove_others(folder: Path, pattern: str, kept: set[Path]) -> None:
    """Delete the generated files of an earlier build that this one did not write (a renamed module or notebook)."""
    for path in folder.glob(pattern):
        if path not in kept:
            path.unlink()


def write_api_pages(folder: Path) -> None:
    """``api/index.rst`` and one page per stage, each an autosummary table of the stage's public names."""
    pages = public_names()
    index = ["API reference", "=============", "",
             "Every public name, grouped by the stage of the pipeline that defines it: a robot is **modelled**, "
             "its kinematics **derived**, **analysed**, then **printed**, **drawn** or **generated** as code. "
             "On each page the names of the top level come first (``from symjac import jacobian``), then those "
             "imported from the stage's own package (``from symjac.codegen import render_files``).", ""]
    toctree = ["", ".. toctree::", "   :hidden:", ""]
    written = set()
    for stage, title, summary in STAGES:
        index.append(f"* :doc:`{stage}`: {summary}")
        toctree.append(f"   {stage}")
        names = pages[stage]
        body = [title, "=" * len(title), "", summary, ""]
        for module in ("symjac", f"symjac.{stage}"):
            listed = [name.rsplit(".", 1)[1] for name in names if name.rsplit(".", 1)[0] == module]
            if not listed:
                continue
            if module != "symjac":
                body += [f"From ``{module}``", "-" * (len(module) + 9), ""]
            body += [f".. currentmodule:: {module}", "", ".. autosummary::", "   :toctree: generated",
                     "   :nosignatures:", "", *(f"   {name}" for name in listed), ""]
        written.add(_write_if_changed(folder / f"{stage}.rst", "\n".join(body) + "\n"))
    index.append("* :doc:`modules`: every module, with the helpers the public names are built from.")
    toctree.append("   modules")
    written.add(_write_if_changed(folder / "index.rst", "\n".join(index + toctree) + "\n"))
    written.add(folder / "modules.rst")
    _remove_others(folder, "*.rst", written)
    stubs = {folder / "generated" / f"{name}.rst" for names in pages.values() for name in names}
    _remove_others(folder / "generated", "*.rst", stubs)
    write_module_pages(folder)


def modules() -> list[str]:
    """Every public module of the package (private ones, ``_version`` or ``_c_family``, and ``__main__`` left out)."""
    found = ["symjac"]
    for info in pkgutil.walk_packages(symjac.__path__, prefix="symjac."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            found.append(info.name)
    return sorted(found)


def _defined_here(module: Any, name: str) -> bool:
    """Whether ``module`` itself defines ``name`` (a function or class made there, or data assigned there)."""
    value = getattr(module, name)
    if _is_code(value):
        return getattr(value, "__module__", None) == module.__name__
    return module.__name__ != "symjac" and home_module(f"{module.__name__}.{name}") == module.__name__


def documented_constants(module: str, exclude: set[str]) -> list[str]:
    """Public module-level names that carry a docstring under their assignment (limits, tables, formats).

    They are not always in ``__all__`` (nothing imports them elsewhere), yet docstrings refer to them.
    """
    if module == "symjac":
        return []
    found = ModuleAnalyzer.for_module(module).find_attr_docs()
    return sorted(name for scope, name in found if not scope and not name.startswith("_") and name not in exclude)


def write_module_pages(folder: Path) -> None:
    """``api/modules.rst`` and one page per module: its docstring and the names of its ``__all__``.

    The stage pages give the public names; these pages give the rest of the code they refer to (the modules and
    helper classes named in docstrings), so every cross-reference resolves. A name is documented once: a public
    one on its stage page, the others in the module that defines them.
    """
    public = {identity(name) for names in public_names().values() for name in names}
    index = ["All modules", "===========", "",
             "Every module of the package with the names of its ``__all__`` that are not on the stage pages: the "
             "code behind the public names, for readers who want to see how a result is made.", "",
             ".. toctree::", "   :maxdepth: 1", ""]
    written = set()
    for name in modules():
        module = importlib.import_module(name)
        members = [member for member in getattr(module, "__all__", ())
                   if _defined_here(module, member) and identity(f"{name}.{member}") not in public]
        constants = documented_constants(name, exclude=set(members) | set(getattr(module, "__all__", ())))
        members += [constant for constant in constants if identity(f"{name}.{constant}") not in public]
        index.append(f"   modules/{name}")
        title = f"``{name}``"
        options = [f"   :members: {', '.join(members)}", "   :undoc-members:"] if members else ["   :no-members:"]
        body = [title, "=" * len(title), "", f".. automodule:: {name}", *options, ""]
        written.add(_write_if_changed(folder / "modules" / f"{name}.rst", "\n".join(body)))
    _remove_others(folder / "modules", "*.rst", written)
    _write_if_changed(folder / "modules.rst", "\n".join(index) + "\n")


def _lookup(dotted: str) -> Any:
    """The object at a dotted path (``symjac.kinematics.chain.Chain.transform``), or None."""
    parts = dotted.split(".")
    if "__main__" in parts:  # importing it runs the command line
        return None
    for cut in range(len(parts), 0, -1):
        try:
            value: Any = importlib.import_module(".".join(parts[:cut]))
        except Exception:  # any failure to import means: not this path
            continue
        try:
            for attribute in parts[cut:]:
                value = getattr(value, attribute)
        except AttributeError:
            return None
        return value
    return None


def public_reference(app: Sphinx, env: Any, node: Any, contnode: Any) -> Any:
    """Resolve a reference to a public object by any of its paths (``symjac.model.robot.Robot`` is ``symjac.Robot``).

    A docstring names an object where it is defined, or by its short name inside its own module; the site documents
    each object once, under its public name. This finds that name by the object's identity.
    """
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~.")
    places = [target]
    module, owner = node.get("py:module"), node.get("py:class")
    if module:
        places += [f"{module}.{owner}.{target}"] if owner else []
        places += [f"{module}.{target}", f"{module.rsplit('.', 1)[0]}.{target}"]
    public = _PUBLIC
    domain = env.get_domain("py")
    for place in places:
        if not place.startswith("symjac"):
            continue
        for name in _documented_names(public, place):
            found = domain.resolve_any_xref(env, node["refdoc"], app.builder, name, node, contnode)
            if found:
                return found[0][1]
    return _unique_suffix(app, env, domain, node, contnode, target)


def _documented_names(public: dict[object, str], place: str) -> list[str]:
    """Names an object at ``place`` may be documented under.

    Its public name, its name in the module that defines it, or, for a member (a method, a dataclass field), its
    class's names with the member's name appended.
    """
    names = []
    value = _lookup(place)
    if value is not None:
        identity = id(value) if _is_code(value) else (_safe_home(place), place.rsplit(".", 1)[-1])
        names += [public[identity]] if identity in public else []
        if getattr(value, "__module__", None) and getattr(value, "__qualname__", None):
            names.append(f"{value.__module__}.{value.__qualname__}")
    if "." in place:
        head, member = place.rsplit(".", 1)
        names += [f"{owner}.{member}" for owner in _documented_names(public, head)]
    return names


def _safe_home(place: str) -> str | None:
    """:func:`home_module` of a dotted path that may name no module attribute at all."""
    try:
        return home_module(place)
    except Exception:  # a path into a class or an unknown module: no home
        return None


def _unique_suffix(app: Sphinx, env: Any, domain: Any, node: Any, contnode: Any, target: str) -> Any:
    """The object a short name used outside its module means (``:func:`generate``` in a module that mentions it).

    It resolves when exactly one documented object ends with it, or exactly one public one does.
    """
    ends = [full for full in domain.objects if full == target or full.endswith(f".{target}")]
    public = [full for full in ends if full.count(".") == target.count(".") + 1]
    for choices in (ends, public):
        if len(choices) == 1:
            found = domain.resolve_any_xref(env, node["refdoc"], app.builder, choices[0], node, contnode)
            if found:
                return found[0][1]
    return None


EXERCISE = "# your answer here"
"""The placeholder of an exercise cell (see ``notebooks/solutions.py``)."""


def copy_notebooks(folder: Path) -> None:
    """Write each ``notebooks/NN_*.py`` into ``folder`` as a notebook, its exercise cells tagged as failing.

    An exercise cell checks a placeholder answer and raises until the reader fills it in; on the site it shows
    that message (tag ``raises-exception``). The worked answers (``solutions.py``) stay out of the site.
    """
    import jupytext
    from nbformat.v4 import new_code_cell

    folder.mkdir(parents=True, exist_ok=True)
    written = set()
    for path in sorted((REPO / "notebooks").glob("[0-9][0-9]_*.py")):
        notebook = jupytext.reads(path.read_text(encoding="utf-8"), fmt="py:percent")
        for cell in notebook.cells:
            if cell.cell_type == "code" and EXERCISE in cell.source:
                cell.metadata.setdefault("tags", []).append("raises-exception")
        # an unanswered exercise shows its one-line message, not a traceback through the checker
        notebook.cells.insert(0, new_code_cell("%xmode Minimal", metadata={"tags": ["remove-cell"]}))
        written.add(_write_if_changed(folder / f"{path.stem}.ipynb", jupytext.writes(notebook, fmt="ipynb")))
    _remove_others(folder, "*.ipynb", written)


MATHJAX_PARTS = ("MathJax.js", "config/TeX-AMS_SVG.js", "jax/input/TeX", "jax/element", "extensions",
                 "jax/output/SVG/jax.js", "jax/output/SVG/config.js", "jax/output/SVG/autoload",
                 "jax/output/SVG/fonts/TeX")
"""What MathJax 2 needs to typeset TeX as SVG: 2.5 MB of the package's 54 MB."""


def mathjax_source() -> Path:
    """The MathJax 2 folder to copy: ``SYMJAC_MATHJAX`` or Debian's ``libjs-mathjax``."""
    folder = Path(os.environ.get("SYMJAC_MATHJAX", "/usr/share/javascript/mathjax"))
    if not (folder / "MathJax.js").is_file():
        raise ConfigError(f"MathJax 2 not found in {folder}: install Debian's libjs-mathjax, or set SYMJAC_MATHJAX "
                          "to a folder holding MathJax.js")
    return folder


def copy_mathjax(app: Sphinx, exception: Exception | None) -> None:
    """Copy the SVG-typesetting part of MathJax into the built site's ``_static/mathjax``."""
    if exception is not None or app.builder.format != "html":
        return
    source = mathjax_source()
    target = Path(app.outdir) / "_static" / "mathjax"
    for part in MATHJAX_PARTS:
        origin, destination = source / part, target / part
        if origin.is_dir():
            shutil.copytree(origin, destination, dirs_exist_ok=True)
        else:
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(origin, destination)


def figure_scraper(block: Any, block_vars: dict[str, Any], gallery_conf: dict[str, Any]) -> str:
    """sphinx-gallery scraper for figures that pyplot does not hold: :func:`symjac.draw` returns a figure of its own.

    Every matplotlib ``Figure`` among the example's variables is saved once, as PNG, into the gallery's images.
    """
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    seen = block_vars.setdefault("symjac_figures", set())
    paths = []
    for value in list(block_vars["example_globals"].values()):
        managed = getattr(getattr(value, "canvas", None), "manager", None) is not None  # pyplot's: its own scraper
        if isinstance(value, Figure) and not managed and id(value) not in seen:
            seen.add(id(value))
            path = next(block_vars["image_path_iterator"])
            value.savefig(path, dpi=100)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


def generate_pages(app: Sphinx, config: Any) -> None:
    """Write the API pages and the tutorials before Sphinx looks for its sources (autosummary reads the pages)."""
    write_api_pages(DOCS / "api")
    copy_notebooks(DOCS / "tutorials" / "notebooks")


def remember_public_names(app: Sphinx) -> None:
    """Keep the map from objects to their public names for :func:`public_reference`; check MathJax for HTML."""
    if app.builder.format == "html":
        mathjax_source()  # fail early, before minutes of building, when MathJax is missing
    _PUBLIC.clear()
    for names in reversed(public_names().values()):
        _PUBLIC.update({identity(name): name for name in names})


def setup(app: Sphinx) -> dict[str, Any]:
    """Register the page generators (before autosummary reads the API pages) and the MathJax copy."""
    app.connect("config-inited", generate_pages)
    app.connect("builder-inited", remember_public_names)
    app.connect("build-finished", copy_mathjax)
    app.connect("autodoc-process-docstring", data_docstring)
    app.connect("missing-reference", public_reference)
    return {"version": symjac.__version__, "parallel_read_safe": True, "parallel_write_safe": True}
