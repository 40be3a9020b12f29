"""Code generation for long chains: every target renders, passes ruff and its self-test, and agrees with references.

A 14-joint 3-D snake is past every threshold that long chains meet: more joints than fit on one line (wrapped
tuples, unpacking and docstrings), a compact Jacobian larger than ``lower.COMPACT_TERMS`` (skipped), and raw trees
larger than ``cse.TREE_LIMIT`` (shared subexpressions named before CSE). The graph walks of :mod:`symjac.symbolic.dag`
are checked on an expression whose tree has 2**40 nodes: walked as a tree, they would never finish.
"""

from __future__ import annotations

import importlib
import importlib.util
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from marks import PYTHON_TARGETS
from reference import evaluate, finite_difference_jacobian
from sympy.core.cache import clear_cache

from symjac import Chain, jacobian, load_robot, robot_from_mapping
from symjac.codegen import generate, write_module
from symjac.codegen.cse import eliminate_common
from symjac.codegen.printers import check_expression
from symjac.codegen.source_layout import LINE_WIDTH, unpack
from symjac.kinematics.chain import MemoKey
from symjac.symbolic.angles import fold_numbers
from symjac.symbolic.dag import distinct_nodes, free_symbols

REPO = Path(__file__).resolve().parent.parent
lower = importlib.import_module("symjac.codegen.lower")
cse = importlib.import_module("symjac.codegen.cse")


def snake(n):
    joints = [{"type": "revolute", "alpha": "pi/2" if i % 2 else "-pi/2", "a": "L"} for i in range(n)]
    joints[5] = {"type": "prismatic", "alpha": "pi/2", "a": "L", "theta": 0.2}
    return robot_from_mapping({"name": f"snake{n}", "convention": "standard", "parameters": {"L": 0.1},
                               "joints": joints})


def _deep(levels: int) -> tuple[sp.Expr, sp.Symbol, sp.Symbol]:
    """An expression whose tree doubles with every level while its graph grows by a few nodes."""
    x, y = sp.symbols("x y", real=True)
    expr: sp.Expr = sp.sin(x)
    for _ in range(levels):
        expr = expr * (y + sp.sqrt(2) * expr)
    return expr, x, y


def test_graph_walks_visit_each_shared_subexpression_once():
    expr, x, y = _deep(40)
    assert len(distinct_nodes([expr])) < 40 * 4
    assert free_symbols([expr]) == {x, y}
    check_expression(expr)  # sin, +, *, sqrt: all allowed
    folded = fold_numbers(expr)
    nodes = distinct_nodes([folded])
    assert sp.sqrt(2) not in nodes
    assert any(isinstance(node, sp.Float) and float(node) == 2 ** 0.5 for node in nodes)
    assert free_symbols([folded]) == {x, y}


def test_only_expressions_that_are_numbers_are_folded():
    x = sp.Symbol("x")
    undefined = sp.Function("f")(1) * x  # numeric arguments, but not a number: left for lower() to refuse clearly
    assert fold_numbers(undefined) == undefined
    folded = fold_numbers(sp.cos(sp.Rational(1, 5)) * x)
    coefficient, rest = folded.as_coeff_Mul()
    assert rest == x and isinstance(coefficient, sp.Float) and float(coefficient) == pytest.approx(0.9800665778412416)


def test_naming_shared_subexpressions_keeps_the_values(monkeypatch):
    expr, x, y = _deep(6)
    outputs = [expr, expr * x + 1, sp.cos(y)]
    plain = eliminate_common(outputs)
    monkeypatch.setattr(cse, "TREE_LIMIT", 0)
    named = eliminate_common(outputs)
    assert named != plain  # the other path really ran
    assert [s.name for s, _ in named[0]] == [f"_x{k}" for k in range(len(named[0]))]
    point = {x: sp.Float(0.3), y: sp.Float(-0.7)}
    for temporaries, reduced in (plain, named):
        values = dict(point)
        for symbol, value in temporaries:
            values[symbol] = value.xreplace(values).evalf()
        assert [float(e.xreplace(values)) for e in reduced] == pytest.approx(
            [float(e.evalf(subs=point)) for e in outputs], rel=1e-12)


def test_names_depend_on_structure_not_on_which_equal_subtrees_are_one_object(monkeypatch):
    monkeypatch.setattr(cse, "TREE_LIMIT", 0)
    first, x, y = _deep(5)
    clear_cache()
    second, _, _ = _deep(5)  # equal to first, but built anew: other objects
    assert second == first and second is not first
    assert eliminate_common([first * x, second + y]) == eliminate_common([first * x, first + y])


@pytest.mark.parametrize("count", range(1, 40))
def test_unpacking_fits_the_line_width_whatever_the_count(count):
    lines = unpack([f"L{k}" for k in range(1, count + 1)], "parameters", "    ")
    assert all(len(line) <= LINE_WIDTH for line in lines)
    namespace: dict[str, object] = {"parameters": tuple(range(count))}
    exec("\n".join(line[4:] for line in lines), namespace)
    assert [namespace[f"L{k}"] for k in range(1, count + 1)] == list(range(count))


def test_long_parameter_lists_are_wrapped_in_every_target():
    names = [f"length{k:02d}" for k in range(1, 26)]
    joints = [{"type": "revolute", "alpha": 0, "a": " + ".join(names[8 * i:8 * i + 8] or ["1"])} for i in range(4)]
    robot = robot_from_mapping({"name": "many", "convention": "standard", "joints": joints,
                                "parameters": {name: 0.01 for name in names}})
    assert len(robot.parameters) == 25
    chain = Chain(robot)
    for target in ("python", "numpy", "lambdify"):
        namespace: dict[str, object] = {}
        exec(compile(generate(chain, target), f"many_{target}.py", "exec"), namespace)  # lines checked on render
        assert namespace["selftest"](samples=3) < 1e-6  # type: ignore[operator]


def test_puma_module_is_the_same_function_with_shared_subexpressions_named_first(monkeypatch):
    robot = load_robot("puma560")
    usual: dict[str, object] = {}
    exec(compile(generate(robot, "python"), "usual.py", "exec"), usual)
    monkeypatch.setattr(cse, "TREE_LIMIT", 0)
    named: dict[str, object] = {}
    exec(compile(generate(Chain(robot), "python"), "named.py", "exec"), named)
    assert named["selftest"](samples=5) < 1e-6  # type: ignore[operator]
    q = [0.3, -0.4, 1.1, 0.2, -0.9, 0.5]
    for function in ("forward_kinematics", "jacobian"):
        np.testing.assert_allclose(named[function](q), usual[function](q), atol=1e-12)  # type: ignore[operator]


@pytest.fixture(scope="module")
def long_modules(tmp_path_factory):
    """The 14-joint snake generated for every target (one chain: each function is derived once)."""
    folder = tmp_path_factory.mktemp("long")
    chain = Chain(snake(14))
    paths = {}
    for target in PYTHON_TARGETS:
        paths[target] = folder / f"snake14_{target}.py"
        write_module(paths[target], generate(chain, target))
    return chain, paths


@pytest.mark.parametrize("target", PYTHON_TARGETS)
@pytest.mark.slow
def test_a_long_snake_module_passes_its_selftest_and_matches_finite_differences(long_modules, target):
    chain, paths = long_modules
    spec = importlib.util.spec_from_file_location(f"snake14_{target}", paths[target])
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.selftest() < 1e-6
    q = np.random.default_rng(5).uniform(-1, 1, 14)
    J = np.array(module.jacobian(q if target != "python" else list(q)), dtype=float)
    np.testing.assert_allclose(J, finite_difference_jacobian(chain.robot, q, 0, None), atol=1e-6)
    np.testing.assert_allclose(J, evaluate(jacobian(chain, simplify=False), chain.robot, q), atol=1e-12)


@pytest.mark.slow
def test_long_snake_modules_are_ruff_clean_and_skip_the_huge_compact_form(long_modules):
    chain, paths = long_modules
    compact = MemoKey(lower._compact_jacobian.__wrapped__, (0, (0, 0, 0)))
    assert compact in chain._memo and chain._memo[compact] is None  # tried once, too large, remembered
    if shutil.which("ruff") is None:
        pytest.skip("ruff is not installed")
    files = [str(path) for path in paths.values() if path.suffix == ".py"]
    result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"), *files],
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
