"""Which parametrized cases are ``slow`` or ``external`` (markers declared in pyproject.toml).

The fast loop, ``pytest -m "not slow and not external"``, keeps the light catalog robots and the Python targets of
every parametrized check; the heavy robots and the compiled C target run in the whole suite (``.ci/run``).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import pytest

from symjac.codegen import BACKENDS

HEAVY_ROBOTS = frozenset({"panda", "panda.urdf", "puma560", "ur5", "ur5.urdf"})
"""Robots whose checks take seconds each; planar2r, planar3r, articulated3r, scara, stanford stay in the fast loop."""

COMPILED_TARGETS = frozenset({"c", "c99"})
"""Code generation targets that need a C compiler: external."""

PYTHON_TARGETS = tuple(name for name, spec in BACKENDS.items() if spec.language == "Python")
"""Targets that write a Python module (the checks that import the generated module run over these)."""


def marked(cases: Iterable[Any]) -> list[Any]:
    """``cases`` for ``pytest.mark.parametrize``: a case naming a heavy robot is slow, one naming a compiled target is
    external (a case is a value or a tuple of values; its ids stay what pytest would have made)."""
    result = []
    for case in cases:
        values = case if isinstance(case, tuple) else (case,)
        marks = [mark for mark, names in ((pytest.mark.slow, HEAVY_ROBOTS), (pytest.mark.external, COMPILED_TARGETS))
                 if any(isinstance(value, str) and value in names for value in values)]
        result.append(pytest.param(*values, marks=marks) if marks else case)
    return result
