"""Generated dynamics (``dynamics=True``) in every target, against an independent numeric Newton-Euler and pinocchio.

The reference is the tests' exact numeric Newton-Euler (``reference_dynamics.NumericDynamics``: spatial vectors in
{0} from the robot's frames, nothing of symjac's dynamics), at inertial parameters other than the modules' defaults
(they are parameters of the module: the reference gets a robot whose defaults are those values) and, for the
catalog's PUMA 560, its published numbers. Every target must agree with it to 1e-9: tau, M, g, C qdot, the bias
forces, and forward dynamics inverting it; the self-test's potential energy V (g = dV/dq) too (python, numpy, c).
The UR5, read from its URDF, is compared with pinocchio. Each module's own self-test passes, and fails when any one
of its dynamics functions (or V) is corrupted; modules are byte-deterministic, ruff-clean, and the C and C++ ones
compile with -Wall -Wextra -Werror.
"""

from __future__ import annotations

import dataclasses
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from generated_dynamics import (
    COMPILED,
    GRAVITY,
    PYTHON_FAMILY,
    CompiledModule,
    PythonModule,
    close,
    elbow,
    import_module,
    inertials,
    reference,
)

from symjac import robot_from_mapping
from symjac.cli.main import main
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.errors import NoInertialDataError
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.model.io import load_robot, robot_to_toml

REPO = Path(__file__).resolve().parent.parent
FUNCTIONS = ("inverse_dynamics", "mass_matrix", "coriolis_matrix", "bias_forces", "gravity_torques",
             "forward_dynamics")


ROBOTS = {"elbow": elbow, "planar2r": lambda: with_symbolic_inertials(load_robot("planar2r")),
          "puma560": lambda: dataclasses.replace(load_robot("puma560"), drives=())}
"""Symbolic inertial parameters (a spatial 3R arm, the planar 2R arm) and published numbers (the PUMA 560's rigid
bodies: its motors' friction would drop the self-test's dynamics check; drives are tested in test_drives)."""


# --- the modules, one per robot and target ----------------------------------------------------------------------------

DYNAMICS_SHIM = """\
void inverse_dynamics_(const double *q, const double *p, const double *a, const double *b, double *out)
{ store(inverse_dynamics(vector(q), vector(a), vector(b), parameters(p)), out); }
void forward_dynamics_(const double *q, const double *p, const double *a, const double *b, double *out)
{ store(forward_dynamics(vector(q), vector(a), vector(b), parameters(p)), out); }
void coriolis_matrix_(const double *q, const double *p, const double *a, double *out)
{ store(coriolis_matrix(vector(q), vector(a), parameters(p)), out); }
void bias_forces_(const double *q, const double *p, const double *a, double *out)
{ store(bias_forces(vector(q), vector(a), parameters(p)), out); }
void mass_matrix_(const double *q, const double *p, double *out)
{ store(mass_matrix(vector(q), parameters(p)), out); }
void gravity_torques_(const double *q, const double *p, double *out)
{ store(gravity_torques(vector(q), parameters(p)), out); }
"""


class Python(PythonModule):
    """A Python-family dynamics module, results flattened."""

    def __init__(self, folder: Path, robot, target: str):
        super().__init__(folder, robot, target, dynamics=True)

    def call(self, name: str, *inputs, parameters: dict[str, float]) -> np.ndarray:
        return super().call(name, *inputs, parameters=parameters).ravel()


class Compiled(CompiledModule):
    """A c99 or cpp dynamics module (``CPP_SHIM`` with the dynamics functions), results flattened."""

    def __init__(self, folder: Path, robot, target: str):
        super().__init__(folder, robot, target, DYNAMICS_SHIM, dynamics=True)

    def call(self, name: str, *inputs, parameters: dict[str, float]) -> np.ndarray:
        size = self.n * self.n if name in ("mass_matrix", "coriolis_matrix") else self.n
        return self.run(name, inputs, parameters, size)

    def selftest(self) -> int:
        return int(self.library[f"{self.prefix}selftest"]()) if self.prefix else 0


@pytest.fixture(scope="module")
def modules(tmp_path_factory):
    """Every target's module of every robot, made once: ``modules(robot name, target)``."""
    made: dict[tuple[str, str], Python | Compiled] = {}
    robots = {name: make() for name, make in ROBOTS.items()}

    def get(name: str, target: str):
        if (name, target) not in made:
            folder = tmp_path_factory.mktemp(f"{name}_{target}")
            kind = Compiled if target in COMPILED else Python
            made[(name, target)] = kind(folder, robots[name], target)
        return made[(name, target)], robots[name]

    return get


@pytest.mark.parametrize("target", PYTHON_FAMILY + COMPILED)
@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_every_function_agrees_with_a_numeric_newton_euler(modules, name, target):
    module, robot = modules(name, target)
    n = robot.n_coordinates
    values = inertials(n) if robot.parameters and name != "puma560" else {}
    exact = reference(robot, values)
    rng = np.random.default_rng(44)
    for _ in range(3):
        q, qdot, qddot = (rng.uniform(-1.5, 1.5, n) for _ in range(3))
        tau, g = exact.tau(q, qdot, qddot), exact.g(q)
        close(module.call("inverse_dynamics", q, qdot, qddot, parameters=values), tau)
        close(module.call("mass_matrix", q, parameters=values), exact.M(q))
        close(module.call("gravity_torques", q, parameters=values), g)
        close(module.call("bias_forces", q, qdot, parameters=values), exact.C_qd(q, qdot) + g)
        C = module.call("coriolis_matrix", q, qdot, parameters=values).reshape(n, n)
        close(C @ qdot, exact.C_qd(q, qdot))
        close(module.call("forward_dynamics", q, qdot, tau, parameters=values), qddot)


@pytest.mark.parametrize("target", ("python", "numpy", "c"))
@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_the_self_tests_potential_energy_agrees_with_a_numeric_one(modules, name, target):
    """The self-test's V(q) (g = dV/dq) is sum_k m_k g z_k, the centres of mass from plain NumPy kinematics.

    The planar 2R arm moves in a horizontal plane (V constant: its centres' heights); the elbow and the PUMA do not.
    """
    module, robot = modules(name, target)
    values = inertials(robot.n_coordinates) if name != "puma560" else {}
    exact = reference(robot, values)
    for q in np.random.default_rng(7).uniform(-1.5, 1.5, (3, robot.n_coordinates)):
        close(module.call("_potential_energy", q, parameters=values), exact.V(q))
        close(module.call("_potential_energy", q, parameters={**values, "g": 2 * GRAVITY}), 2 * exact.V(q))


@pytest.mark.parametrize("target", ("python", "numpy"))
def test_gravity_is_a_parameter(modules, target):
    module, _ = modules("elbow", target)
    assert module.module.PARAMETERS["g"] == GRAVITY
    q = np.array([0.3, -0.7, 1.1])
    values = inertials(3)
    earth = module.call("gravity_torques", q, parameters=values)
    assert np.abs(earth).max() > 1.0
    close(module.call("gravity_torques", q, parameters={**values, "g": 2 * GRAVITY}), 2 * earth)
    close(module.call("gravity_torques", q, parameters={**values, "g": 0.0}), np.zeros(3))


@pytest.mark.parametrize("target", PYTHON_FAMILY)
def test_the_self_test_passes_and_fails_for_any_corrupted_function(modules, target):
    module, _ = modules("elbow", target)
    generated = module.module
    assert generated.selftest() <= 1e-6
    # JAX's functions are checked as NumPy's (one corruption is enough there); CasADi's return its own matrices
    corrupted_kinds = {"jax": ("coriolis_matrix",), "casadi": ()}.get(target, FUNCTIONS)
    checks = generated._CHECKS
    for corrupted in corrupted_kinds:
        right = getattr(generated, corrupted)

        def wrong(*args, _function=right, **keywords):
            value = _function(*args, **keywords)
            return value + 1e-3 * (np.arange(np.size(value)) == 1).reshape(np.shape(value))

        generated._CHECKS = tuple((routine, tuple(wrong if f is right else f for f in functions), rows)
                                  for routine, functions, rows in checks)
        try:
            with pytest.raises(AssertionError, match="self-test error"):
                generated.selftest()
        finally:
            generated._CHECKS = checks
    if target == "casadi":
        return
    right = generated._potential_energy  # g = dV/dq: V tilted along q_2 by 1e-3 (a constant would go unnoticed)
    generated._CHECKS = tuple((routine, tuple(f if f is not right else lambda q, **keywords: right(q, **keywords)
                                              + 1e-3 * np.asarray(q, dtype=float)[..., 1] for f in functions), rows)
                              for routine, functions, rows in checks)
    try:
        with pytest.raises(AssertionError, match="self-test error"):
            generated.selftest()
    finally:
        generated._CHECKS = checks


@pytest.mark.parametrize("target", COMPILED)
def test_the_compiled_self_test_passes(modules, target):
    module, _ = modules("elbow", target)
    assert module.selftest() == 0


@pytest.mark.parametrize("target", PYTHON_FAMILY + COMPILED)
def test_modules_are_deterministic_and_python_ones_ruff_clean(modules, target, tmp_path):
    module, robot = modules("planar2r", target)
    assert render_files(describe(ModuleRequest(robot, target, dynamics=True))) == module.files
    if target in PYTHON_FAMILY and shutil.which("ruff") is not None:
        result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"),
                                 str(module.path)], capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stdout


def test_without_the_option_nothing_changes():
    robot = ROBOTS["planar2r"]()
    text = next(iter(render_files(describe(ModuleRequest(robot, "python"))).values()))
    assert "inverse_dynamics" not in text and "cholesky" not in text.lower() and '"g":' not in text


def test_a_robot_without_inertial_data_is_refused_naming_its_links(capsys, tmp_path):
    planar = load_robot("planar2r")
    bare = dataclasses.replace(planar, parameters=planar.geometric_parameters, inertials=())
    with pytest.raises(NoInertialDataError, match="links 1, 2 have no inertial data"):
        describe(ModuleRequest(bare, "python", dynamics=True))
    (tmp_path / "bare.toml").write_text(robot_to_toml(bare), encoding="utf-8")
    assert main(["codegen", str(tmp_path / "bare.toml"), "--dynamics"]) != 0
    error = capsys.readouterr().err.strip()
    assert "links 1, 2 have no inertial data" in error and len(error.splitlines()) == 1
    named_g = robot_from_mapping({"name": "arm", "convention": "standard", "parameters": {"g": 1.0},
                                  "joints": [{"type": "revolute", "a": "g"}]})
    with pytest.raises(ValueError, match="the parameter 'g' has the name of gravity's magnitude"):
        describe(ModuleRequest(with_symbolic_inertials(named_g), "python", dynamics=True))


# --- a real arm with its published numbers, against pinocchio --------------------------------------------------------

@pytest.mark.external
def test_the_ur5_agrees_with_pinocchio(tmp_path):
    pin = pytest.importorskip("pinocchio")
    from collection import example_robots

    path = example_robots() / "ur_description" / "urdf" / "ur5_robot.urdf"
    robot = load_robot(str(path), tip_link="tool0")
    model = pin.buildModelFromUrdf(str(path))
    data = model.createData()
    index = [model.joints[model.getJointId(joint.name)].idx_q for joint in robot.joints]
    assert index == list(range(model.nq))
    rng = np.random.default_rng(5)
    for target in ("python", "c", "c99"):
        module = (Compiled if target in COMPILED else Python)(tmp_path, robot, target)
        for _ in range(2):
            q, qdot, qddot = (rng.uniform(-1.5, 1.5, 6) for _ in range(3))
            close(module.call("inverse_dynamics", q, qdot, qddot, parameters={}),
                   pin.rnea(model, data, q, qdot, qddot))
            M = pin.crba(model, data, q)
            close(module.call("mass_matrix", q, parameters={}), np.triu(M) + np.triu(M, 1).T)
            close(module.call("gravity_torques", q, parameters={}), pin.computeGeneralizedGravity(model, data, q))
            close(module.call("coriolis_matrix", q, qdot, parameters={}),
                   pin.computeCoriolisMatrix(model, data, q, qdot))
            tau = rng.uniform(-5, 5, 6)
            close(module.call("forward_dynamics", q, qdot, tau, parameters={}),
                   pin.aba(model, data, q, qdot, tau), 1e-8)


def test_a_coupled_robot_is_in_its_coordinates():
    """theta4 = -(theta2 + theta3): tau_q = C^T tau(theta, C qdot, C qddot), M_q = C^T M C, against the free arm."""
    data = {"name": "arm", "convention": "modified", "parameters": {"L": 0.5},
            "joints": [{"type": "revolute", "alpha": a, "a": "L"} for a in (0, "pi/2", 0, 0)]}
    free = with_symbolic_inertials(robot_from_mapping(data))
    data["joints"][3]["coupled"] = "-(theta2 + theta3)"
    coupled = with_symbolic_inertials(robot_from_mapping(data))
    modules = {}
    for name, robot in (("free", free), ("coupled", coupled)):
        modules[name] = {}
        exec(compile(next(iter(render_files(describe(ModuleRequest(robot, "python", dynamics=True))).values())),
                     name, "exec"), modules[name])
    C = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, -1]], dtype=float)
    values = inertials(4)
    rng = np.random.default_rng(3)
    for _ in range(3):
        q, qdot, qddot = (rng.uniform(-1.5, 1.5, 3) for _ in range(3))
        tau = np.array(modules["free"]["inverse_dynamics"](C @ q, C @ qdot, C @ qddot, **values))
        close(modules["coupled"]["inverse_dynamics"](q, qdot, qddot, **values), C.T @ tau)
        M = np.array(modules["free"]["mass_matrix"](C @ q, **values))
        close(modules["coupled"]["mass_matrix"](q, **values), C.T @ M @ C)
        close(modules["coupled"]["forward_dynamics"](q, qdot, C.T @ tau, **values), qddot)
    assert modules["coupled"]["selftest"]() <= 1e-6


ARM_FILE = """name = "arm2"
convention = "standard"

[parameters]
L1 = 0.5
L2 = 0.4
m2 = 1.5

[[joints]]
type = "revolute"
alpha = "pi/2"
a = "L1"
[joints.inertial]
mass = 2.0
com = ["-L1/2", 0, 0]
ixx = 0.01
iyy = 0.05
izz = 0.05

[[joints]]
type = "revolute"
a = "L2"
[joints.inertial]
mass = "m2"
com = ["-L2/2", 0, 0]
ixx = 0.005
iyy = "m2*L2**2/12"
izz = "m2*L2**2/12"
"""


def test_the_command_line_writes_a_dynamics_module(tmp_path, capsys):
    """Inertial data from a robot file (numbers and expressions over its parameters): m2 is a module parameter."""
    (tmp_path / "arm2.toml").write_text(ARM_FILE)
    output = tmp_path / "arm2.py"
    assert main(["codegen", str(tmp_path / "arm2.toml"), "--dynamics", "-o", str(output)]) == 0
    module = import_module(output)
    assert "--dynamics" in output.read_text().split('"""', 1)[0]  # the header's command regenerates it
    assert module.selftest() <= 1e-6 and set(module.PARAMETERS) - {"g"} == {"L1", "L2", "m2"}
    q, zero = np.array([0.2, -0.4]), np.zeros(2)
    heavier = np.array(module.mass_matrix(q, m2=3.0)) - np.array(module.mass_matrix(q))
    assert np.abs(heavier).max() > 1e-3  # the mass is a parameter, not a number baked in
    close(module.inverse_dynamics(q, zero, zero), module.gravity_torques(q))
