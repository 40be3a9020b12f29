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

# The pipeline's stages, bottom to top: a module may import from its own stage or one below, never above (data flows
# one way). Modules directly under ``symjac/`` (errors, files, resources, progress, _version, the robot catalog's
# data) are the foundation below every stage; the package root and ``__main__`` sit on top.
STAGES: list[tuple[str, ...]] = [
    ("symbolic",),
    ("model",),
    ("kinematics",),
    ("analysis",),
    ("printing", "drawing"),
    ("quantities",),
    ("report", "codegen", "solvers", "teaching", "sweeps"),
    ("cli",),
]


def _floor(module: str) -> int:
    parts = module.split(".")
    if module in ("symjac", "symjac.__main__"):
        return len(STAGES) + 1
    for level, stage in enumerate(STAGES, start=1):
        if parts[1] in stage:
            return level
    assert len(parts) == 2 or parts[1] == "robots", (
        f"{module} sits in a folder that is no pipeline stage: add the folder to STAGES in tests/test_structure.py")
    return 0


def test_every_folder_is_a_stage():
    folders = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()} - {"robots"}
    staged = {name for stage in STAGES for name in stage}
    assert folders == staged, (
        f"folders without a stage: {sorted(folders - staged)}; stages without a folder: {sorted(staged - folders)}")


def _modules() -> list[str]:
    names = ["symjac"]
    for info in pkgutil.walk_packages([str(PACKAGE)], prefix="symjac."):
        if info.name != "symjac.__main__":  # importing it runs the command line
            names.append(info.name)
    return sorted(names)


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
    for name in symjac.__all__:  # the root imports its names on first use
        assert not inspect.ismodule(getattr(symjac, name)), name
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
