"""Which parametrized cases are ``slow`` or ``external`` (markers declared in pyproject.toml).

The fast loop, ``pytest -m "not slow and not external"``, runs every parametrized check on an allow-list of light
robots, one per structural class (:data:`LIGHT_ROBOTS`), and on the Python targets; every other built-in robot is
slow, so a robot added to the catalog later joins the whole suite (``.ci/run``) and not the fast loop. The compiled
targets are external.
"""

from __future__ import annotations

from collections.abc import Iterable
from importlib import resources
from typing import Any

import pytest

from symjac.codegen import BACKENDS

LIGHT_ROBOTS = {
    "planar": "planar2r",
    "standard DH": "planar2r",
    "modified DH": "articulated3r",
    "spherical wrist": "stanford",
    "prismatic": "stanford",
    "URDF/general": "gripper.urdf",
    "product of exponentials": "ur5_poe",
    "coupled": "palletizer",
}
"""The fast loop's robot per structural class. The only standard-DH arm with a spherical wrist is the 7-joint iiwa7,
so planar2r stands for standard DH and stanford (modified DH: RRP and a spherical wrist) for the wrist and the
prismatic joint; gripper.urdf is a general-convention arm with a mimic joint; ur5_poe and palletizer are the
catalog's only PoE and coupled (TOML) robots."""


def _built_in_robots() -> frozenset[str]:
    """Names ``load_robot`` accepts for the robots shipped in ``symjac/robots``: a TOML file's stem, the file name
    of one in a subfolder (``panda.urdf``); read from the folder so that a robot added later is known."""
    names = set()
    folder = resources.files("symjac.robots")
    for entry in folder.iterdir():
        if entry.is_file() and entry.name.endswith(".toml"):
            names.add(entry.name.removesuffix(".toml"))
        elif entry.is_dir() and not entry.name.startswith(("_", ".")):
            names.update(e.name for e in entry.iterdir() if e.is_file() and not e.name.startswith(("_", ".")))
    return frozenset(names)


BUILT_IN_ROBOTS = _built_in_robots()
"""Every built-in robot name: the catalog's and the bundled robot files'."""

HEAVY_ROBOTS = BUILT_IN_ROBOTS - frozenset(LIGHT_ROBOTS.values())
"""Built-in robots outside the allow-list: their parametrized cases are slow."""

COMPILED_TARGETS = frozenset({"c", "c99"})
"""Code generation targets that need a C compiler: external."""

_ParameterSet = type(pytest.param(None))

PYTHON_TARGETS = tuple(name for name, spec in BACKENDS.items() if spec.language == "Python")
"""Targets that write a Python module (the checks that import the generated module run over these)."""


def marked(cases: Iterable[Any], keep: Iterable[str] = ()) -> list[Any]:
    """``cases`` for ``pytest.mark.parametrize``: a case naming a built-in robot outside :data:`LIGHT_ROBOTS` is
    slow, one naming a compiled target is external (a case is a value, a tuple of values or a ``pytest.param``; its
    ids stay what pytest would have made).

    ``keep`` names robots that stay in the fast loop for this one check, where its subject needs an arm outside the
    allow-list (a redundant arm for the redundancy checks); say why where it is used.
    """
    heavy = HEAVY_ROBOTS - frozenset(keep)
    result = []
    for case in cases:
        given = isinstance(case, _ParameterSet)  # a pytest.param: its values, marks and id are kept
        values = case.values if given else case if isinstance(case, tuple) else (case,)
        marks = [mark for mark, names in ((pytest.mark.slow, heavy), (pytest.mark.external, COMPILED_TARGETS))
                 if any(isinstance(value, str) and value in names for value in values)]
        if given and marks:
            case = pytest.param(*values, marks=(*case.marks, *marks), id=case.id)
        elif marks:
            case = pytest.param(*values, marks=marks)
        result.append(case)
    return result
