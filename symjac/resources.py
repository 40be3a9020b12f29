"""Locating and rendering the jinja2 templates shipped with symjac.

The top-level ``templates/`` folder of the source tree is copied into the wheel as ``symjac/templates`` (hatchling
``force-include``). An installed package finds it through :mod:`importlib.resources`; an editable install, where
that copy does not exist, falls back to the checkout's ``templates/`` beside the package.

Templates emit LaTeX, source code and HTML. An HTML template (its name ends in ``.html.j2``) escapes every value it
prints, exactly as :func:`html.escape` does (quotes included, so a page reads the same as the markup built beside it
in Python); a value that already is HTML says so in the template with ``|safe``. Every other template prints its
values as they are.
"""

from __future__ import annotations

import html
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
import markupsafe

__all__ = ["render_template", "templates_dir"]


def templates_dir() -> Path:
    """The folder holding the ``*.j2`` templates, installed copy first, then the source checkout."""
    installed = resources.files("symjac").joinpath("templates")
    if installed.is_dir():
        return Path(str(installed))
    checkout = Path(__file__).resolve().parent.parent / "templates"
    if checkout.is_dir():
        return checkout
    raise FileNotFoundError("symjac templates not found: the installation is incomplete (reinstall symjac)")


HTML_SUFFIX = ".html.j2"
"""Templates whose name ends like this are HTML and escape what they print."""


@cache
def environment(escaping: bool = False) -> jinja2.Environment:
    """A jinja2 environment: strict about undefined names, whitespace-tidy, output kept byte-stable.

    ``escaping`` gives the one for HTML templates (see the module docstring); the other serves LaTeX and source code.
    """
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=escaping,
        finalize=_escaped if escaping else None,
    )


def _escaped(value: Any) -> markupsafe.Markup:
    """A printed value as HTML: markup (``|safe``) as it is, anything else through :func:`html.escape`."""
    if isinstance(value, markupsafe.Markup):
        return value
    return markupsafe.Markup(html.escape(str(value)))


def render_template(name: str, **data: Any) -> str:
    """Render template ``name`` (e.g. ``"documents/latex_document.tex.j2"``) with ``data``; HTML escapes values."""
    return environment(name.endswith(HTML_SUFFIX)).get_template(name).render(**data)
