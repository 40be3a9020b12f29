"""Locating and rendering the jinja2 templates shipped with symjac.

The top-level ``templates/`` folder of the source tree is copied into the wheel as ``symjac/templates`` (hatchling
``force-include``). An installed package finds it through :mod:`importlib.resources`; an editable install, where
that copy does not exist, falls back to the checkout's ``templates/`` beside the package.
"""

from __future__ import annotations

from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2

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


@cache
def environment() -> jinja2.Environment:
    """The one jinja2 environment: strict about undefined names, whitespace-tidy, output kept byte-stable."""
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,  # templates emit LaTeX and Python source, never HTML
    )


def render_template(name: str, **data: Any) -> str:
    """Render template ``name`` (for example ``"documents/latex_document.tex.j2"``) with ``data``."""
    return environment().get_template(name).render(**data)
