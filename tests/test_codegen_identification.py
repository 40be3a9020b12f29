"""Generated regressors (``identification=True``) in every target, against an independent numeric Newton-Euler.

The standard parameters are computed here from the inertial data by hand (mass, first moments m c, the inertia about
the link origin I_c + m (|c|^2 E - c c^T)), and the regressor times them must give the tests' own numeric
Newton-Euler (``reference_dynamics.NumericDynamics``) at inertial values other than the module's defaults; the base
regressor times the base parameters (their expressions evaluated at those values) too. Each module names the columns
in order (``REGRESSOR_PARAMETERS``, ``BASE_PARAMETERS``; C: arrays of strings), its self-test passes and fails when a
regressor is corrupted, and modules are deterministic, ruff-clean and compile with -Wall -Wextra -Werror.
"""

from __future__ import annotations

import ctypes
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from generated_dynamics import (
    COMPILED,
    PYTHON_FAMILY,
    CompiledModule,
    PythonModule,
    close,
    elbow,
    import_module,
    inertials,
    reference,
)

from symjac.analysis.identification import regressor
from symjac.analysis.identification.base import base_parameters
from symjac.cli.main import main
from symjac.codegen import ModuleRequest, describe, generate, render_files
from symjac.kinematics.chain import chain_of
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.model.io import load_robot

REPO = Path(__file__).resolve().parent.parent
ROBOTS = {"elbow": elbow, "planar2r": lambda: with_symbolic_inertials(load_robot("planar2r"))}


def standard_vector(robot, values: dict[str, float]) -> np.ndarray:
    """The standard parameters XX..ZZ (about the link origin), MX, MY, MZ, M of every link, computed by hand."""
    defaults = {p.name: float(p.default) for p in robot.parameters} | values
    entries = []
    for k in range(1, robot.n_joints + 1):
        m = defaults[f"m{k}"]
        c = np.array([defaults[f"c{axis}{k}"] for axis in "xyz"])
        I_c = np.array([[defaults[f"I{a}{b}{k}"] if f"I{a}{b}{k}" in defaults else defaults[f"I{b}{a}{k}"]
                         for b in "xyz"] for a in "xyz"])
        I_o = I_c + m * (c @ c * np.eye(3) - np.outer(c, c))
        entries += [I_o[0, 0], I_o[0, 1], I_o[0, 2], I_o[1, 1], I_o[1, 2], I_o[2, 2], *(m * c), m]
    return np.array(entries)


def base_vector(robot, values: dict[str, float]) -> np.ndarray:
    """The base parameters' expressions evaluated at the standard vector (and the geometric defaults)."""
    base = base_parameters(regressor(robot))
    pi = {s: sp.Float(v) for s, v in zip(regressor(robot).parameters, standard_vector(robot, values), strict=True)}
    geometry = {p.symbol: p.default for p in robot.parameters}
    return np.array([float(sp.sympify(e).xreplace(pi).xreplace(geometry)) for e in base.expressions])


class Python(PythonModule):
    """A Python-family identification module and its column names (regressor, base regressor)."""

    def __init__(self, folder: Path, robot, target: str):
        super().__init__(folder, robot, target, identification=True)
        self.names = (tuple(self.module.REGRESSOR_PARAMETERS), tuple(self.module.BASE_PARAMETERS))


IDENTIFICATION_SHIM = """\
void regressor_(const double *q, const double *p, const double *a, const double *b, double *out)
{ store(regressor(vector(q), vector(a), vector(b), parameters(p)), out); }
void base_regressor_(const double *q, const double *p, const double *a, const double *b, double *out)
{ store(base_regressor(vector(q), vector(a), vector(b), parameters(p)), out); }
const char *regressor_name_(int k) { return regressor_parameters[k]; }
const char *base_name_(int k) { return base_parameters[k]; }
int regressor_count_(void) { return static_cast<int>(regressor_parameters.size()); }
int base_count_(void) { return static_cast<int>(base_parameters.size()); }
"""


class Compiled(CompiledModule):
    """A c99 or cpp identification module and its column names (read from the library)."""

    def __init__(self, folder: Path, robot, target: str):
        super().__init__(folder, robot, target, IDENTIFICATION_SHIM, identification=True)
        Y = regressor(robot)
        self.names = (self._names("regressor", len(Y.names)),
                      self._names("base", len(base_parameters(Y).symbols)))

    def _names(self, which: str, count: int) -> tuple[str, ...]:
        if self.target == "c99":  # the arrays' lengths are macros; the test knows them from the API
            constant = "regressor_parameters" if which == "regressor" else "base_parameters"
            values = (ctypes.c_char_p * count).in_dll(self.library, f"{self.prefix}{constant}")
            return tuple(values[k].decode() for k in range(count))
        getter, counter = getattr(self.library, f"{which}_name_"), getattr(self.library, f"{which}_count_")
        getter.restype = ctypes.c_char_p
        return tuple(getter(k).decode() for k in range(counter()))

    def call(self, name: str, *inputs, parameters: dict[str, float]) -> np.ndarray:
        columns = len(self.names[0] if name == "regressor" else self.names[1])
        return self.run(name, inputs, parameters, self.n * columns).reshape(self.n, columns)


@pytest.fixture(scope="module")
def modules(tmp_path_factory):
    """Every target's module of every robot, made once: ``modules(robot name, target)``."""
    made: dict[tuple[str, str], Python | Compiled] = {}
    robots = {name: make() for name, make in ROBOTS.items()}

    def get(name: str, target: str):
        if (name, target) not in made:
            folder = tmp_path_factory.mktemp(f"{name}_{target}")
            made[(name, target)] = (Compiled if target in COMPILED else Python)(folder, robots[name], target)
        return made[(name, target)], robots[name]

    return get


@pytest.mark.parametrize("target", PYTHON_FAMILY + COMPILED)
@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_the_regressors_times_the_parameters_give_a_numeric_newton_euler(modules, name, target):
    module, robot = modules(name, target)
    Y = regressor(robot)
    base = base_parameters(Y)
    assert module.names == (Y.names, tuple(s.name for s in base.symbols))
    n = robot.n_coordinates
    values = inertials(n)
    exact = reference(robot, values)
    pi, pi_b = standard_vector(robot, values), base_vector(robot, values)
    rng = np.random.default_rng(45)
    for _ in range(3):
        q, qdot, qddot = (rng.uniform(-1.5, 1.5, n) for _ in range(3))
        tau = exact.tau(q, qdot, qddot)
        Y_q = module.call("regressor", q, qdot, qddot, parameters=values).reshape(n, len(pi))
        Y_b = module.call("base_regressor", q, qdot, qddot, parameters=values).reshape(n, len(pi_b))
        close(Y_q @ pi, tau)
        close(Y_b @ pi_b, tau)
    # the regressors do not read the inertial parameters: other values give the same matrices
    assert np.array_equal(module.call("regressor", q, qdot, qddot, parameters=values),
                          module.call("regressor", q, qdot, qddot, parameters={}))


@pytest.mark.parametrize("target", PYTHON_FAMILY)
def test_the_self_test_checks_both_regressors(modules, target):
    module, _ = modules("elbow", target)
    generated = module.module
    assert generated.selftest() <= 1e-6
    assert [functions for routine, functions, _ in generated._CHECKS if routine == "identification"] == [
        (generated.inverse_dynamics, generated.regressor, generated._standard_values),
        (generated.inverse_dynamics, generated.base_regressor, generated._base_values)]
    if target == "casadi":  # its functions return CasADi matrices; the Python family's corruption is enough
        return
    checks = generated._CHECKS
    for corrupted in (generated.regressor, generated.base_regressor):
        def wrong(*args, _function=corrupted, **keywords):
            value = np.asarray(_function(*args, **keywords))
            return value + 1e-3 * (np.arange(value.size) < value.shape[-1]).reshape(value.shape)  # row 1

        generated._CHECKS = tuple((routine, tuple(wrong if f is corrupted else f for f in functions), rows)
                                  for routine, functions, rows in checks)
        try:
            with pytest.raises(AssertionError, match="self-test error"):
                generated.selftest()
        finally:
            generated._CHECKS = checks


def test_the_c99_self_test_passes_with_the_identification_check(modules):
    module, _ = modules("elbow", "c99")
    assert "sj_check_identification" in module.files["elbow.c"]
    assert int(module.library["elbow_selftest"]()) == 0


@pytest.mark.parametrize("target", PYTHON_FAMILY + COMPILED)
def test_modules_are_deterministic_and_python_ones_ruff_clean(modules, target):
    module, robot = modules("planar2r", target)
    assert render_files(describe(ModuleRequest(robot, target, identification=True))) == module.files
    if target in PYTHON_FAMILY and shutil.which("ruff") is not None:
        result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"),
                                 str(module.path)], capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stdout


def test_the_command_line_and_the_header_say_identification(tmp_path):
    robot = ROBOTS["planar2r"]()
    source = generate(robot, "python", identification=True)
    assert "identification=True" in source and "def regressor(" in source and "def base_regressor(" in source
    assert "def regressor(" not in generate(robot, "python", dynamics=True)
    path = tmp_path / "arm.py"
    assert main(["codegen", "planar2r", "--identification", "--target", "numpy", "-o", str(path)]) == 0
    module = import_module(path)
    assert module.BASE_PARAMETERS == ("ZZR1", "ZZR2", "MXR2", "MY2") and module.selftest() <= 1e-6


def test_a_coupled_robots_base_regressor_has_full_rank_in_its_coordinates(tmp_path):
    """The palletizer's parallelogram (theta4 = -(theta2 + theta3)) groups more parameters than its joints would."""
    robot = load_robot("palletizer")
    path = tmp_path / "palletizer.py"
    path.write_text(generate(robot, "numpy", identification=True))
    module = import_module(path)
    assert module.selftest() <= 1e-6
    in_coordinates = base_parameters(regressor(robot))  # of C^T Y: fewer than the joints' own base parameters
    assert tuple(s.name for s in in_coordinates.symbols) == module.BASE_PARAMETERS
    assert len(in_coordinates.symbols) < len(base_parameters(regressor(chain_of(robot).joint_chain)).symbols)
    rng = np.random.default_rng(2)
    n = robot.n_coordinates
    samples = [rng.uniform(-1.0, 1.0, (60, n)) for _ in range(3)]
    W = np.vstack([module.base_regressor(*(s[k] for s in samples)) for k in range(60)])
    assert np.linalg.matrix_rank(W) == len(module.BASE_PARAMETERS) < len(module.REGRESSOR_PARAMETERS)
