"""The numeric runtimes of generated code (``templates/runtime/``), tested on their own, and the description's seams.

Each runtime file is imported (Python) or compiled (C) by itself and checked against ``numpy.linalg``: determinants
(with pivoting and exact zeros), the Gauss-Jordan and Cholesky solves, the manipulability of square, wide and tall
Jacobians and its gradient against central differences. Every generated module of a family carries the sections
of its runtime it uses unchanged, and no template holds an elimination loop.
"""

from __future__ import annotations

import ast
import importlib.util
import subprocess
import types
import warnings
from pathlib import Path

import numpy as np
import pytest

from symjac import load_robot
from symjac.codegen import BACKENDS, ModuleDescription, ModuleRequest, describe, render_files
from symjac.codegen.runtime import RUNTIMES, runtime_source
from symjac.errors import CodegenError

REPO = Path(__file__).resolve().parent.parent
RUNTIME = REPO / "templates" / "runtime"


def _module(name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(f"runtime_{name}", RUNTIME / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


PY = _module("python")
NP = _module("numpy")


def _spd(rng: np.random.Generator, n: int) -> np.ndarray:
    A = rng.normal(size=(n, n))
    return A @ A.T + n * np.eye(n)


@pytest.mark.parametrize("n", [1, 2, 3, 6, 7])
def test_the_python_determinant_and_solves_agree_with_numpy(n):
    rng = np.random.default_rng(n)
    for _ in range(5):
        A = rng.normal(size=(n, n))
        assert PY._determinant(A.tolist()) == pytest.approx(np.linalg.det(A), rel=1e-10, abs=1e-12)
        B = rng.normal(size=(n, 3))
        np.testing.assert_allclose(PY._solve(A.tolist(), B.tolist()), np.linalg.solve(A, B), rtol=1e-8, atol=1e-10)
        M, b = _spd(rng, n), rng.normal(size=n)
        np.testing.assert_allclose(PY._cholesky_solve(M.tolist(), b.tolist()), np.linalg.solve(M, b), rtol=1e-10)
        np.testing.assert_allclose(NP._cholesky_solve(M, b), np.linalg.solve(M, b), rtol=1e-10)


def test_forward_dynamics_solves_m_qddot_equals_tau_minus_the_bias_forces():
    rng = np.random.default_rng(11)
    M, bias, tau = _spd(rng, 4), rng.normal(size=4), rng.normal(size=4)
    expected = np.linalg.solve(M, tau - bias)
    np.testing.assert_allclose(PY._forward_dynamics(M.tolist(), bias.tolist(), tau.tolist()), expected, rtol=1e-10)
    batch = np.stack([M, 2 * M])
    np.testing.assert_allclose(NP._forward_dynamics(batch, bias, tau), [expected, expected / 2], rtol=1e-10)


def test_the_determinant_pivots_and_is_zero_exactly_for_a_zero_column():
    assert PY._determinant([[0.0, 1.0], [1.0, 0.0]]) == -1.0  # a zero first pivot: rows swapped, sign flipped
    assert PY._determinant([[1.0, 0.0], [2.0, 0.0]]) == 0.0


def test_the_cholesky_solve_refuses_a_matrix_that_is_not_positive_definite():
    with pytest.raises(ValueError, match="not positive definite"):
        PY._cholesky_solve([[1.0, 2.0], [2.0, 1.0]], [1.0, 0.0])
    with pytest.raises(np.linalg.LinAlgError):
        NP._cholesky_solve(np.array([[1.0, 2.0], [2.0, 1.0]]), np.array([1.0, 0.0]))


def test_the_numpy_cholesky_solve_takes_batches():
    rng = np.random.default_rng(3)
    M = np.stack([_spd(rng, 4) for _ in range(5)])
    b = rng.normal(size=(5, 4))
    np.testing.assert_allclose(NP._cholesky_solve(M, b), np.linalg.solve(M, b[..., None])[..., 0], rtol=1e-10)


@pytest.mark.parametrize("shape", [(3, 3), (2, 4), (6, 7), (5, 3)])
def test_the_manipulability_and_its_gradient_agree_with_numpy_and_central_differences(shape):
    r"""J(q) = A + sum_m q_m B_m has H[:, :, m] = B_m; w = sqrt(det(J J^T)) (or J^T J, or |det J|)."""
    rows, n = shape
    rng = np.random.default_rng(rows * 10 + n)
    A, B = rng.normal(size=(rows, n)), rng.normal(size=(n, rows, n))

    def J(q):
        return A + np.einsum("m,mij->ij", q, B)

    H = np.moveaxis(B, 0, -1)  # H[i, j, m]
    q = rng.normal(size=n) * 0.1
    gram = J(q) @ J(q).T if rows <= n else J(q).T @ J(q)
    w = np.sqrt(np.linalg.det(gram)) if rows != n else abs(np.linalg.det(J(q)))
    assert PY._manipulability(J(q).tolist()) == pytest.approx(w, rel=1e-10)
    assert NP._manipulability(J(q)) == pytest.approx(w, rel=1e-10)
    step = 1e-6
    expected = [(NP._manipulability(J(q + step * e)) - NP._manipulability(J(q - step * e))) / (2 * step)
                for e in np.eye(n)]
    np.testing.assert_allclose(PY._manipulability_gradient(J(q).tolist(), H.tolist()), expected, rtol=1e-5,
                               atol=1e-7)
    np.testing.assert_allclose(NP._manipulability_gradient(J(q), H), expected, rtol=1e-5, atol=1e-7)


def test_the_gradient_is_zero_where_the_manipulability_vanishes():
    J = np.array([[1.0, 2.0], [2.0, 4.0]])
    H = np.ones((2, 2, 2))
    assert PY._manipulability_gradient(J.tolist(), H.tolist()) == (0.0, 0.0)
    np.testing.assert_array_equal(NP._manipulability_gradient(J, H), [0.0, 0.0])


def test_each_runtime_has_its_mark_and_imports_nothing_of_symjac():
    for name in RUNTIMES:
        text = runtime_source(name)
        assert "symjac." not in text and "import symjac" not in text, name
    with pytest.raises(CodegenError, match="unknown runtime"):
        runtime_source("fortran.f90")


@pytest.mark.parametrize("target", [t for t, b in BACKENDS.items() if b.runtime])
def test_every_generated_module_carries_its_runtime_unchanged(target):
    description = describe(ModuleRequest(load_robot("planar2r"), target, acceleration=True))
    text = "\n".join(render_files(description).values())
    own = {"sincos"} if target in ("numpy", "c") else set()  # their printers' angle lines call _sincos
    assert runtime_source(BACKENDS[target].runtime, description.runtime_sections | own) in text


def test_no_template_holds_an_elimination_loop():
    """Pivots, eliminations and factorizations live in the runtimes; the templates only lay data out."""
    for path in (REPO / "templates").rglob("*.j2"):
        if "documents" in path.parts:
            continue
        text = path.read_text(encoding="utf-8").lower()
        for code in ("pivot =", "factor =", "linalg.det(", "linalg.solve(", "ca.det(", ".determinant(", "partialpivlu",
                     ".llt(", "cholesky("):
            assert code not in text, f"{path.relative_to(REPO)} computes with {code!r}"


# --- the description: data without a Chain, one kind of argument, a leaf module for names ------------------------

def test_the_description_carries_no_chain_and_describe_takes_a_request():
    robot = load_robot("planar2r")
    description = describe(ModuleRequest(robot, "python"))
    assert "chain" not in ModuleDescription.__dataclass_fields__
    assert description.coordinate_symbols == tuple(robot.q)
    assert description.parameter_symbols == tuple(p.symbol for p in robot.geometric_parameters)
    with pytest.warns(DeprecationWarning, match="ModuleRequest"):
        old = describe(robot, "python")
    assert old == description
    with pytest.raises(CodegenError, match="ModuleRequest alone"):
        describe(ModuleRequest(robot), "python")


def test_the_names_module_is_a_leaf_of_codegen():
    tree = ast.parse((REPO / "symjac" / "codegen" / "names.py").read_text(encoding="utf-8"))
    imported = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module}
    assert not any(name.startswith("symjac.codegen") for name in imported)
    for path in (REPO / "symjac" / "codegen").rglob("*.py"):  # no import hidden inside a function
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef):
                inner = [n for n in ast.walk(node) if isinstance(n, ast.ImportFrom)]
                assert not [n for n in inner if (n.module or "").startswith("symjac.codegen")], path


def test_the_robot_loader_reads_the_catalog_once(monkeypatch):
    import symjac.codegen.provenance as provenance

    provenance._catalog_names.cache_clear()
    calls = []
    real = provenance.catalog
    monkeypatch.setattr(provenance, "catalog", lambda: calls.append(1) or real())
    for target in ("python", "numpy"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            describe(ModuleRequest(load_robot("planar2r"), target))
    assert len(calls) <= 1
    provenance._catalog_names.cache_clear()


# --- the C runtime, compiled by itself -----------------------------------------------------------------------------

C_TEST = r"""
#include <stdio.h>
#include "c99.h"
int main(void)
{
    double a[9] = {0, 1, 2, 1, 0, 3, 4, -3, 8};
    double m[9] = {4, 2, 0.4, 2, 5, 1, 0.4, 1, 3};
    double b[3] = {1, -2, 0.5};
    double x[3];
    double J[6] = {1, 2, 0.5, -1, 0.3, 2};
    double H[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5};
    double g[3];
    const double d = sj_determinant(a, 3, 3);
    const int ok = sj_cholesky_solve(m, b, 3, x);
    const double w = sj_manipulability(J, 2, 3);
    sj_manipulability_gradient(J, H, 2, 3, g);
    printf("%.17g %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", d, ok, x[0], x[1], x[2], w, g[0], g[1], g[2]);
    return 0;
}
"""


@pytest.mark.external  # a C compiler
def test_the_c_runtime_compiles_alone_and_agrees_with_numpy(tmp_path):
    import shutil

    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed")
    (tmp_path / "c99.h").write_text("#include <math.h>\n#include <stddef.h>\n#include <string.h>\n"
                                    "typedef double real;\n#define SJ_DIM 6\n" + runtime_source("c99.h"))
    (tmp_path / "main.c").write_text(C_TEST)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Wno-unused-function",
                    "main.c", "-o", "main", "-lm"], cwd=tmp_path, check=True, capture_output=True, text=True)
    values = [float(v) for v in subprocess.run([str(tmp_path / "main")], check=True, capture_output=True,
                                                text=True).stdout.split()]
    a = np.array([[0, 1, 2], [1, 0, 3], [4, -3, 8]], dtype=float)
    m = np.array([[4, 2, 0.4], [2, 5, 1], [0.4, 1, 3]])
    J = np.array([[1, 2, 0.5], [-1, 0.3, 2]])
    H = np.array([1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0, 0, 0.5, 0, 0, 0, 0.5]).reshape(2, 3, 3)
    assert values[0] == pytest.approx(np.linalg.det(a), rel=1e-12)
    assert values[1] == 1
    np.testing.assert_allclose(values[2:5], np.linalg.solve(m, [1, -2, 0.5]), rtol=1e-12)
    assert values[5] == pytest.approx(NP._manipulability(J), rel=1e-12)
    np.testing.assert_allclose(values[6:9], NP._manipulability_gradient(J, H), rtol=1e-10)


CPP_TEST = r"""
#include <cstdio>
#include "eigen.hpp"
int main()
{
    using namespace symjac_runtime_test::runtime;
    Eigen::Matrix<double, 2, 3> J;
    J << 1, 2, 0.5, -1, 0.3, 2;
    std::array<Eigen::Matrix<double, 2, 3>, 3> H;
    for (int m = 0; m < 3; m++) {
        H[m].setZero();
    }
    H[0](0, 0) = 1; H[1](0, 1) = 1; H[2](0, 2) = 1; H[0](1, 0) = 0.5; H[1](1, 1) = 0.5; H[2](1, 2) = 0.5;
    Eigen::Matrix3d M;
    M << 4, 2, 0.4, 2, 5, 1, 0.4, 1, 3;
    bool ok = false;
    const Eigen::Vector3d x = cholesky_solve(M, Eigen::Vector3d(1, -2, 0.5), &ok);
    const Eigen::Vector3d g = manipulability_gradient(J, H);
    const Eigen::Matrix<double, 3, 2> tall = J.transpose();
    std::printf("%.17g %.17g %d %.17g %.17g %.17g %.17g %.17g %.17g\n", manipulability(J), manipulability(tall), ok,
                x(0), x(1), x(2), g(0), g(1), g(2));
    return 0;
}
"""


@pytest.mark.external  # a C++ compiler and Eigen
def test_the_eigen_runtime_compiles_alone_and_agrees_with_numpy(tmp_path):
    import shutil

    if shutil.which("g++") is None or not Path("/usr/include/eigen3/Eigen/Dense").is_file():
        pytest.skip("g++ or Eigen's headers (Debian libeigen3-dev) are missing")
    (tmp_path / "eigen.hpp").write_text((RUNTIME / "eigen.hpp").read_text())
    (tmp_path / "main.cpp").write_text(CPP_TEST)
    subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-I/usr/include/eigen3", "main.cpp", "-o",
                    "main"], cwd=tmp_path, check=True, capture_output=True, text=True)
    values = [float(v) for v in subprocess.run([str(tmp_path / "main")], check=True, capture_output=True,
                                                text=True).stdout.split()]
    J = np.array([[1, 2, 0.5], [-1, 0.3, 2]])
    H = np.zeros((2, 3, 3))
    for m in range(3):
        H[0, m, m], H[1, m, m] = 1.0, 0.5
    M = np.array([[4, 2, 0.4], [2, 5, 1], [0.4, 1, 3]])
    assert values[0] == pytest.approx(NP._manipulability(J), rel=1e-12)
    assert values[1] == pytest.approx(NP._manipulability(J.T), rel=1e-12)
    assert values[2] == 1
    np.testing.assert_allclose(values[3:6], np.linalg.solve(M, [1, -2, 0.5]), rtol=1e-12)
    np.testing.assert_allclose(values[6:9], NP._manipulability_gradient(J, H), rtol=1e-10)


@pytest.mark.parametrize("family", ["jax", "casadi"])
def test_the_jax_and_casadi_runtimes_agree_with_numpy(family):
    pytest.importorskip(family)
    module = _module(family)
    rng = np.random.default_rng(5)
    for rows, n in [(3, 3), (2, 4), (5, 3)]:
        J, H = rng.normal(size=(rows, n)), rng.normal(size=(rows, n, n))
        M, b = _spd(rng, n), rng.normal(size=n)
        if family == "jax":
            w, gradient = module._manipulability(J), module._manipulability_gradient(J, H)
            x = module._cholesky_solve(M, b)
        else:
            import casadi as ca

            q = ca.SX.sym("q", n)
            J_q = ca.DM(J) + sum((ca.DM(H[:, :, m]) * q[m] for m in range(n)), ca.SX.zeros(rows, n))
            w_q = module._manipulability(J_q, q)
            f = ca.Function("f", [q], [w_q, module._manipulability_gradient(J_q, ca.SX.zeros(rows, n * n), q)])
            w, gradient = (np.array(v).ravel() for v in f(np.zeros(n)))
            x = np.array(ca.Function("s", [], [module._cholesky_solve(ca.SX(M), ca.SX(b))])()["o0"]).ravel()
        assert float(np.ravel(w)[0]) == pytest.approx(float(NP._manipulability(J)), rel=1e-6)
        np.testing.assert_allclose(np.ravel(gradient), NP._manipulability_gradient(J, H), rtol=1e-5, atol=1e-8)
        np.testing.assert_allclose(np.ravel(x), np.linalg.solve(M, b), rtol=1e-5)


# --- templates lay data out: the kinds table decides, not the templates ----------------------------------------------

QUANTITIES = ("jacobian", "hessian", "torques", "manipulability", "forward_kinematics", "bias")


def test_no_template_branches_on_a_kind_or_names_a_quantity():
    for path in (REPO / "templates").rglob("*.j2"):
        if "documents" in path.parts:
            continue
        text = path.read_text(encoding="utf-8")
        assert "kind ==" not in text and "kind !=" not in text, path
        for word in QUANTITIES:
            assert word not in text.lower(), f"{path.relative_to(REPO)} names {word}"


def test_every_function_is_documented_from_the_kinds_table():
    import sympy as sp

    from symjac.codegen.kinds import KINDS

    t2 = sp.Symbol("theta2", real=True)
    description = describe(ModuleRequest(load_robot("planar2r"), "python", acceleration=True, frames=(0, "tool"),
                                         scalars={"reach": 2 * t2}))
    for function in (*description.functions, *description.derived):
        assert function.returns, function.name
        assert function.kind in KINDS
    # 6 x 2 Jacobians: not square, so no determinant
    assert [d.kind for d in description.derived] == ["manipulability", "manipulability_gradient"] * 2
    listed = [name for name, _ in description.listing]
    assert listed[0] == "forward_kinematics" and listed[-1] == "reach" and "_kinematics" not in listed
    assert [check.routine for check in description.checks] == ["pose", "jacobian", "jacobian", "acceleration",
                                                                "acceleration"]
