"""The package keeps its shape: curated ``__all__``s, one-way imports, no private side doors, small modules."""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
from pathlib import Path

import pytest

import symjac

REPO = Path(__file__).resolve().parent.parent
PACKAGE = REPO / "symjac"

# Each module's floor; a module may import modules on its own floor or below, never above (data flows one way:
# model -> chain -> kinematics -> analyses -> outputs). A new module must be given a floor here.
FLOORS: dict[str, int] = {
    # foundations: no robot yet
    "symjac._version": 0, "symjac.errors": 0, "symjac.expressions": 0, "symjac.transforms": 0, "symjac.angles": 0,
    "symjac.trigpoly": 0, "symjac.simplify": 0, "symjac.files": 0, "symjac.resources": 0,
    "symjac.reporting": 0, "symjac.dag": 0, "symjac.limits": 0,
    # the model and its files
    "symjac.robots": 1, "symjac.model": 1, "symjac.robot_file": 1, "symjac.urdf": 1, "symjac.io": 1,
    # derived data
    "symjac.chain": 2,
    # kinematics
    "symjac.jacobian": 3, "symjac.propagation": 3, "symjac.statics": 3, "symjac.numeric": 3, "symjac.convert": 3,
    "symjac.acceleration": 3,
    # analyses
    "symjac.spaces": 4, "symjac.singularity": 4, "symjac.singular": 4, "symjac.rates": 4, "symjac.representations": 4,
    "symjac.exercises": 4,
    "symjac.manipulability": 4,
    # outputs
    "symjac.errata": 5, "symjac.report": 5,
    "symjac.printing": 5, "symjac.codegen": 5, "symjac.cli": 5, "symjac.cli_args": 5, "symjac.cli_output": 5,
    "symjac.__main__": 5,
}


def _modules() -> list[str]:
    names = ["symjac"]
    for info in pkgutil.walk_packages([str(PACKAGE)], prefix="symjac."):
        if info.name != "symjac.__main__":  # importing it runs the command line
            names.append(info.name)
    return sorted(names)


def _floor(module: str) -> int:
    for prefix in sorted(FLOORS, key=len, reverse=True):
        if module == prefix or module.startswith((prefix + ".", prefix + "_")):
            return FLOORS[prefix]
    raise AssertionError(f"{module} has no floor in tests/test_structure.py FLOORS: give it one")


def _source_files() -> list[Path]:
    return sorted(p for folder in ("symjac", "tests", "notebooks", "benchmarks") for p in (REPO / folder).rglob("*.py"))


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(REPO).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path) -> list[tuple[str, str | None, int]]:
    """(module, imported name or None, line) for every import statement of a file, relative ones resolved."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = _module_name(path).rsplit(".", 1)[0] if path.name != "__init__.py" else _module_name(path)
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, None, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                module = f"{base}.{module}" if module else base
            found += [(module, alias.name, node.lineno) for alias in node.names]
    return found


@pytest.mark.parametrize("module_name", _modules())
def test_all_lists_exactly_the_public_names(module_name):
    module = importlib.import_module(module_name)
    exported = getattr(module, "__all__", None)
    assert exported is not None, f"{module_name} has no __all__"
    missing = [name for name in exported if not hasattr(module, name)]
    assert not missing, f"{module_name}.__all__ names what it does not define: {missing}"
    defined = {
        name for name, value in vars(module).items()
        if not name.startswith("_") and (inspect.isfunction(value) or inspect.isclass(value))
        and getattr(value, "__module__", None) == module_name
    }
    unlisted = sorted(defined - set(exported))
    assert not unlisted, f"{module_name} defines public names missing from __all__: {unlisted}"


def test_package_root_exports_every_public_name_it_imports():
    public = {name for name, value in vars(symjac).items()
              if not name.startswith("_") and not inspect.ismodule(value)}
    assert set(symjac.__all__) == public | {"__version__"}


@pytest.mark.parametrize("path", _source_files(), ids=lambda p: str(p.relative_to(REPO)))
def test_no_private_name_crosses_a_module_boundary(path):
    here = _module_name(path)
    offenders = [f"line {line}: from {module} import {name}" for module, name, line in _imports(path)
                 if module.startswith("symjac") and module != here and name is not None
                 and name.startswith("_") and not name.startswith("__")]
    assert not offenders, f"{path.relative_to(REPO)} imports private names: {offenders}"


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.py")), ids=lambda p: str(p.relative_to(REPO)))
def test_imports_flow_one_way(path):
    here = _module_name(path)
    if here == "symjac":
        return  # the package root re-exports everything
    floor = _floor(here)
    for module, _, line in _imports(path):
        if not module.startswith("symjac"):
            continue
        assert module != "symjac", f"{here} line {line} imports the package root (import what it needs directly)"
        assert _floor(module) <= floor, (
            f"{here} (floor {floor}) line {line} imports {module} (floor {_floor(module)}): imports flow one way")


@pytest.mark.parametrize("path", sorted(PACKAGE.rglob("*.py")), ids=lambda p: str(p.relative_to(REPO)))
def test_modules_stay_small(path):
    lines = len(path.read_text(encoding="utf-8").splitlines())
    assert lines <= 420, f"{path.relative_to(REPO)} has {lines} lines: split it by concern"
