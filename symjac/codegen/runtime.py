"""The numeric runtimes: one static source per language family, of which each generated module carries what it uses.

The linear algebra a generated module needs (LU determinant, Gauss-Jordan and Cholesky solves, the manipulability
and its gradient) and its self-test driver live in ``templates/runtime/`` as ordinary source files of their
language, tested on their own, not in the templates: ``python.py`` (standard library), ``numpy.py`` (the NumPy
family: numpy, lambdify, c), ``jax.py``, ``casadi.py``, ``c99.h`` (C99, the standard library only) and
``eigen.hpp`` (C++ on Eigen). A generated module stays standalone: the part of the file after its runtime mark is
copied into it (a Python runtime's imports and docstring above the mark are the module's own; a header's include
guard and includes likewise).

That part is cut into *sections* by comment lines ``---- runtime section: NAME ----`` or
``---- runtime section: NAME; needs: OTHER, ... ----`` (after the language's comment sign). The text before the
first section line and every section named ``core`` (the self-test driver, the pose and Jacobian checks, input
validation) go into every module; another section only when the module uses it: a derived function's routine
(``determinant``, ``manipulability``, ``manipulability_gradient``), a self-test check (``acceleration``) or, for a
target, a routine its printer calls (``sincos``), with every section those need. The section lines themselves are
not copied, and the sections keep the file's order, so a module's runtime is the file's with unused parts left out.
"""

from __future__ import annotations

import functools
import re

from symjac.errors import CodegenError
from symjac.resources import templates_dir

__all__ = ["CORE", "CORE_CHECKS", "RUNTIMES", "runtime_source", "section_names"]

RUNTIMES: tuple[str, ...] = ("python.py", "numpy.py", "jax.py", "casadi.py", "c99.h", "eigen.hpp")
"""The runtime files in ``templates/runtime/``, one per language family."""

MARK = "---- runtime: everything below is copied into every generated module of the target ----"
"""The line (after its language's comment sign) that starts the part a generated module carries."""

END = "---- end of runtime ----"
"""The line that ends it, where the file goes on (a C++ test namespace closes after it); else the file's end."""

CORE = "core"
"""The name of the sections every module carries (as the text before the first section line)."""

CORE_CHECKS = frozenset({"pose", "jacobian"})
"""The self-test checks every runtime's core holds: a module asking for them needs no section."""

_SECTION = re.compile(r"^\W*---- runtime section: (?P<name>\w+)(?:; needs: (?P<needs>[\w, ]+))? ----\W*$")


@functools.cache
def _sections(name: str) -> tuple[tuple[str, frozenset[str], str], ...]:
    """Runtime ``name`` after its mark as (section, what it needs, text) in file order, the leading core first."""
    if name not in RUNTIMES:
        raise CodegenError(f"internal error: unknown runtime {name!r}; the runtimes are {', '.join(RUNTIMES)}")
    text = (templates_dir() / "runtime" / name).read_text(encoding="utf-8")
    head, mark, body = text.partition(MARK)
    if not mark:
        raise CodegenError(f"internal error: templates/runtime/{name} has no runtime mark")
    del head  # the file's own docstring and imports
    body = body.split("\n", 1)[1]
    if END in body:
        body = body.partition(END)[0].rsplit("\n", 1)[0]  # without the comment line that holds the end mark
    sections: list[tuple[str, frozenset[str], list[str]]] = [(CORE, frozenset(), [])]
    for line in body.split("\n"):
        match = _SECTION.match(line)
        if match:
            needs = frozenset(word.strip() for word in (match["needs"] or "").split(",") if word.strip())
            sections.append((match["name"], needs, []))
        else:
            sections[-1][2].append(line)
    return tuple((section, needs, "\n".join(lines).strip("\n")) for section, needs, lines in sections)


def section_names(name: str) -> frozenset[str]:
    """The sections runtime ``name`` has (``core`` among them)."""
    return frozenset(section for section, _, _ in _sections(name))


@functools.cache
def runtime_source(name: str, used: frozenset[str] | None = None) -> str:
    """The text of runtime ``name`` after its mark: the core and the sections in ``used`` with what they need.

    ``used`` names sections (and :data:`CORE_CHECKS`, which the core holds); ``None`` takes every section (the
    whole runtime, as its tests read it). Sections are separated as the file's functions are: two blank lines in
    Python, one in C and C++.

    Raises
    ------
    CodegenError
        For an unknown runtime or section, or a runtime file without its mark (an incomplete installation).
    """
    sections = _sections(name)
    known = section_names(name)
    wanted = set(known if used is None else used - CORE_CHECKS) | {CORE}
    unknown = sorted(wanted - known)
    while not unknown:
        needed = set().union(*(needs for section, needs, _ in sections if section in wanted)) - wanted
        if not needed:
            break
        unknown = sorted(needed - known)
        wanted |= needed
    if unknown:
        raise CodegenError(f"internal error: templates/runtime/{name} has no section {', '.join(unknown)}; "
                           f"its sections are {', '.join(sorted(known))}")
    separator = "\n\n\n" if name.endswith(".py") else "\n\n"
    return separator.join(text for section, _, text in sections if section in wanted and text) + "\n"

