"""The numeric runtimes: one static source per language family that every generated module carries.

The linear algebra a generated module needs (LU determinant, Gauss-Jordan and Cholesky solves, the manipulability
and its gradient) and its self-test driver live in ``templates/runtime/`` as ordinary source files of their
language, tested on their own, not in the templates: ``python.py`` (standard library), ``numpy.py`` (the NumPy
family: numpy, lambdify, c), ``jax.py``, ``casadi.py``, ``c99.h`` (C99, the standard library only) and
``eigen.hpp`` (C++ on Eigen). A generated module stays
standalone: the part of the file after its runtime mark is copied into it (a Python runtime's imports and
docstring above the mark are the module's own; a header's include guard and includes likewise).
"""

from __future__ import annotations

import functools

from symjac.errors import CodegenError
from symjac.resources import templates_dir

__all__ = ["RUNTIMES", "runtime_source"]

RUNTIMES: tuple[str, ...] = ("python.py", "numpy.py", "jax.py", "casadi.py", "c99.h", "eigen.hpp")
"""The runtime files in ``templates/runtime/``, one per language family."""

MARK = "---- runtime: everything below is copied into every generated module of the target ----"
"""The line (after its language's comment sign) that starts the part a generated module carries."""

END = "---- end of runtime ----"
"""The line that ends it, where the file goes on (a C++ test namespace closes after it); else the file's end."""


@functools.cache
def runtime_source(name: str) -> str:
    """The text of runtime ``name`` after its mark, without the blank lines around it (read once per process).

    Raises
    ------
    CodegenError
        For an unknown runtime, or a runtime file without its mark (an incomplete installation).
    """
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
    return body.strip("\n") + "\n"
