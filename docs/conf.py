"""Sphinx configuration of the symjac documentation site.

Build it with ``python -m sphinx -W --keep-going -n -b html docs docs/_build/html`` (the ``docs`` extra installs the
tools). Three things are made at build time by :mod:`symjac_docs` (in ``docs/_ext``), so the site cannot drift from
the code: the API reference from the package's ``__all__`` lists, the tutorials from ``notebooks/``, and the offline
copy of MathJax.
"""

from __future__ import annotations

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))

from symjac_docs import figure_scraper  # noqa: E402

import symjac  # noqa: E402

project = "symjac"
author = "the symjac developers"
copyright = "2026, the symjac developers"
release = symjac.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinxarg.ext",
    "myst_nb",
    "sphinx_gallery.gen_gallery",
    "symjac_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "examples", "gallery/*.ipynb", "sg_execution_times.rst"]
templates_path = ["_templates"]
# Every cross-reference must resolve (-n): to the API reference, or to the module pages behind it. Names of other
# packages (there is no network for their inventories) and the plain words of NumPy-style type descriptions
# ("tuple of n", "optional", "'tool'") are not references.
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(sympy|numpy|np|sp|collections|typing|matplotlib|xarray|dask|distributed|jinja2|argparse|pathlib|"
               r"enum|fractions|concurrent|types|os|io|casadi|jax|scipy)(\..*)?"),
    (r"py:.*", r"(optional|sequence|mapping|iterable|callable|array|array_like|default|of|or|and|shape|length|"
               r"tuple|list|dict|set|frozenset|int|float|str|bool|bytes|complex|object|None|True|False|Path|Any|"
               r"Number|n|m|k|N|T|Self|Callable|Sequence|Mapping|Iterable|Iterator|Hashable|ndarray|Matrix|Expr|"
               r"Symbol|Basic)"),
    (r"py:.*", r"[^A-Za-z_].*|.*[\s\(\)\[\],\"'].*"),  # numbers, quoted values, shapes: "(6, n)", "3 + m"
    (r"py:class", r"[a-z_][a-z_0-9]*|[A-Z][a-z]+(-[a-z]+)+"),  # words of a type description: "floats", "Roll-pitch-yaw"
    (r"py:class", r"(re|xml|mpl_toolkits|PIL)\..*|Figure|Axes|Axes3D|Style|Index"),
    (r"py:.*", r"(importlib|ast|html|random|shlex|json|tomllib|itertools|functools|math|subprocess)(\..*)?"),
    (r"py:.*", r"(.*\.)?_[A-Za-z].*|symjac(\.\w+)*\.[A-Z]|[A-Z]"),  # private names are not documented; type variables
]
suppress_warnings = ["config.cache"]  # sphinx-gallery's configuration holds functions; the build cache still works

# --- the API reference -------------------------------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"show-inheritance": True}  # members: by the class template, the module pages
# Types are linked from the annotations in the signatures; the NumPy-style type text of a docstring ("array of
# shape (n, 6)") stays prose, so its words are never taken for names.
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autodoc_member_order = "bysource"
autoclass_content = "class"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
napoleon_use_param = False
napoleon_use_keyword = False
add_module_names = False

# --- math, offline ------------------------------------------------------------------------------------------------
# MathJax 2 from Debian's libjs-mathjax, copied into _static/mathjax by symjac_docs (SVG output: no web fonts).
mathjax_path = "mathjax/MathJax.js?config=TeX-AMS_SVG"
mathjax2_config = {
    "tex2jax": {
        "inlineMath": [["\\(", "\\)"]],
        "displayMath": [["\\[", "\\]"]],
        "processEscapes": True,
        "ignoreClass": "document",
        "processClass": "math|output_area",
    },
}

# --- tutorials: the notebooks, executed once and cached -----------------------------------------------------------
nb_execution_mode = "cache"
nb_execution_cache_path = str(DOCS / "_build" / ".jupyter_cache")
nb_execution_timeout = 300
nb_execution_in_temp = True
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_ipywidgets_js: dict[str, dict[str, str]] = {}  # no widget scripts from a CDN: the site works offline (no kernel)
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
# Markdown a notebook displays (the captions of a singularity report) is read as MyST, so its $...$ is typeset.
nb_render_markdown_format = "myst"
myst_heading_anchors = 3

# --- the gallery: scripts in docs/examples, run at build time -----------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib", figure_scraper),
    "capture_repr": (),  # figures are shown by the scrapers, not as text
}

# --- HTML ---------------------------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"symjac {release}"
html_static_path: list[str] = []
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 6,
}
html_show_sourcelink = False
