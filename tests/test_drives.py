"""Drive data (armature, viscous and Coulomb friction): reading, writing back, errors, and their place in the dynamics.

Readers: robot files' ``[joints.drive]``, URDF ``<dynamics damping friction>`` and MJCF ``armature``, ``damping``,
``frictionloss`` (checked against MuJoCo's own compiled model, default classes included). Dynamics: Newton-Euler,
Euler-Lagrange and the mass matrix agree with the drives in, on a plain and a coupled arm, and the generated
modules compute what the API does. pinocchio's armature is checked in test_dynamics_pinocchio, the Robotics
Toolbox's motor model on the PUMA 560 in test_catalog_dynamics.
"""

from __future__ import annotations

import dataclasses
import importlib.util

import numpy as np
import pytest
import sympy as sp

from symjac import robot_from_mapping, robot_from_toml, robot_to_toml
from symjac.analysis.dynamics import (
    coriolis_matrix,
    dynamics_defaults,
    euler_lagrange,
    friction_torques,
    gravity_torques,
    mass_matrix,
    newton_euler,
    newton_euler_mass_matrix,
)
from symjac.errors import RobotFileError
from symjac.model.drive import Drive
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.model.io import load_robot

ARM = """name = "arm"
convention = "standard"

[parameters]
Jm = 0.0002

[[joints]]
type = "revolute"
a = 1
[joints.drive]
motor_inertia = "Jm"
gear_ratio = -62.6111
viscous = 0.5
coulomb = 0.25

[[joints]]
type = "revolute"
a = 0.5
[joints.drive]
armature = 0.1
"""


def test_a_robot_file_reads_its_drives_and_writes_them_back_exactly():
    robot = robot_from_toml(ARM, "arm.toml")
    Jm = sp.Symbol("Jm", real=True)
    first, second = robot.drives
    assert first == Drive(Jm * sp.Rational(626111, 10000) ** 2, sp.Rational(1, 2), sp.Rational(1, 4))
    assert second == Drive(armature=sp.Rational(1, 10))
    text = robot_to_toml(robot)
    assert 'motor_inertia = "Jm"' in text and "gear_ratio = -62.6111" in text  # written as given
    again = robot_from_toml(text, "again.toml")
    assert again == robot and again.drives == robot.drives
    assert robot != dataclasses.replace(robot, drives=())  # drives are part of the robot
    assert dataclasses.replace(robot, drives=(Drive(), None)).drives == (None, None)  # a zero drive is none


@pytest.mark.parametrize(("entry", "message"), [
    ("viscous = -1", "joint 2, field 'drive': the viscous friction -1 is negative"),
    ("motor_inertia = 0.1", "joint 2, field 'drive.gear_ratio': 'motor_inertia' needs 'gear_ratio'"),
    ("armature = 1\nmotor_inertia = 1\ngear_ratio = 2", "give either 'armature' or 'motor_inertia'"),
    ("damping = 1", "unknown key\\(s\\) 'damping'; allowed: armature, motor_inertia, gear_ratio, viscous, coulomb"),
    ('coulomb = "1/0"', "joint 2, field 'drive.coulomb': division by zero"),
    ('armature = "Jm - 1"', "joint 2, field 'drive': the armature Jm - 1 is negative"),
])
def test_bad_drive_data_is_refused_in_one_line_naming_file_and_joint(entry, message):
    with pytest.raises(RobotFileError, match=f"^arm.toml, {message}" if "joint" in message else message) as error:
        robot_from_toml(ARM.replace("armature = 0.1", entry), "arm.toml")
    assert "\n" not in str(error.value) and str(error.value).startswith("arm.toml, joint 2")


URDF = """<robot name="two"><link name="base"/><link name="l1"/><link name="l2"/>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1"/><dynamics damping="0.7" friction="0.3"/></joint>
<joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/>{second}</joint>
</robot>"""


def test_urdf_dynamics_damping_and_friction_are_viscous_and_coulomb_friction(tmp_path):
    path = tmp_path / "two.urdf"
    path.write_text(URDF.format(second='<dynamics damping="0"/>'))
    robot = load_robot(str(path))
    assert robot.drives == (Drive(viscous=sp.Rational(7, 10), coulomb=sp.Rational(3, 10)), None)
    path.write_text(URDF.format(second='<dynamics friction="-2"/>'))
    with pytest.raises(RobotFileError, match=r"two.urdf, field 'joint j2 dynamics': the Coulomb friction -2 is "):
        load_robot(str(path))


MJCF = """<mujoco model="arm"><default><joint damping="0.4" armature="0.02"/>
  <default class="wrist"><joint frictionloss="0.3" armature="0.01"/></default></default>
<worldbody><body name="l1"><joint name="j1" axis="0 0 1"/>
  <inertial pos="0.2 0 0" mass="1" diaginertia="0.01 0.02 0.02"/>
  <body name="l2" pos="0.4 0 0"><joint name="j2" class="wrist" axis="0 1 0" damping="0.6"/>
    <inertial pos="0.1 0 0" mass="0.5" diaginertia="0.01 0.01 0.01"/>
    <body name="l3" pos="0.3 0 0"><joint name="j3" axis="1 0 0" damping="0" armature="0"/>
      <inertial pos="0.1 0 0" mass="0.2" diaginertia="0.01 0.01 0.01"/></body></body></body></worldbody></mujoco>"""


def test_mjcf_armature_damping_and_frictionloss_as_mujoco_compiles_them(tmp_path):
    mujoco = pytest.importorskip("mujoco")
    path = tmp_path / "arm.xml"
    path.write_text(MJCF)
    model = mujoco.MjModel.from_xml_string(MJCF)
    robot = load_robot(str(path))
    for drive, k in zip(robot.drives, range(model.nv), strict=True):
        ours = (0.0, 0.0, 0.0) if drive is None else tuple(float(v) for v in (drive.armature, drive.viscous,
                                                                                   drive.coulomb))
        assert ours == pytest.approx((model.dof_armature[k], model.dof_damping[k], model.dof_frictionloss[k]))
    assert robot.drives[2] is None and robot.drives[1] == Drive(sp.Rational(1, 100), sp.Rational(3, 5),
                                                                sp.Rational(3, 10))
    # MuJoCo's own mass matrix includes the armature, its passive force is the viscous friction
    data = mujoco.MjData(model)
    evaluate = _numeric(robot, mass_matrix(robot, simplify=False), friction_torques(robot))
    rng = np.random.default_rng(11)
    for _ in range(2):
        data.qpos[:], data.qvel[:] = rng.uniform(-1.5, 1.5, 3), rng.uniform(-1.5, 1.5, 3)
        mujoco.mj_forward(model, data)
        full = np.zeros((3, 3))
        try:
            mujoco.mj_fullM(model, data, full)  # MuJoCo 4
        except TypeError:  # earlier versions: (model, out, qM)
            mujoco.mj_fullM(model, full, data.qM)
        M, F = evaluate(*data.qpos, *data.qvel, *np.zeros(3))
        np.testing.assert_allclose(M, full, atol=1e-12)
        viscous = np.array([float(d.viscous) if d is not None else 0.0 for d in robot.drives]) * data.qvel
        np.testing.assert_allclose(-data.qfrc_passive, viscous, atol=1e-12)
        np.testing.assert_allclose(F.ravel() - viscous, [0, 0.3 * np.sign(data.qvel[1]), 0], atol=1e-12)
    path.write_text(MJCF.replace('damping="0.6"', 'damping="-0.6"'))
    with pytest.raises(RobotFileError, match=r"arm.xml, field 'joint j2': the viscous friction -3/5 is negative$"):
        load_robot(str(path))


def _arm(coupled: bool = False):
    """A spatial 3R arm with symbolic inertial parameters and a drive on each joint (joint 3 coupled to 2 if asked)."""
    joints = [{"type": "revolute", "alpha": "pi/2", "d": "d1", "drive": {"armature": "Ia1", "viscous": 1.5,
                                                                          "coulomb": 0.7}},
              {"type": "revolute", "a": "a2", "drive": {"armature": 0.2, "coulomb": 0.4}},
              {"type": "revolute", "a": "a3", "drive": {"viscous": 0.3, "armature": 0.05}}]
    if coupled:
        joints[2]["coupled"] = "-theta2 / 2"
    return with_symbolic_inertials(robot_from_mapping({
        "name": "elbow", "convention": "standard", "joints": joints,
        "parameters": {"d1": 0.3, "a2": 0.4, "a3": 0.35, "Ia1": 0.8}}))


def _numeric(robot, *matrices):
    numbers = {s: float(v) for s, v in dynamics_defaults(robot).items()}
    args = [*robot.q, *robot.coordinate_rates, *robot.coordinate_accelerations, *numbers]
    functions = [sp.lambdify(args, sp.Matrix(m), modules="numpy") for m in matrices]
    return lambda *x: [np.array(f(*x, *numbers.values()), dtype=float) for f in functions]


@pytest.mark.parametrize("coupled", [False, True])
def test_newton_euler_lagrange_and_the_mass_matrix_agree_with_the_drives_in(coupled):
    arm = _arm(coupled)
    rigid = dataclasses.replace(arm, drives=())
    tau = newton_euler(arm, simplify=False).torques
    M = mass_matrix(arm, simplify=False)
    raw = {"simplify": False}
    evaluate = _numeric(arm, tau, euler_lagrange(arm, **raw), M, newton_euler_mass_matrix(arm, **raw),
                        coriolis_matrix(arm, **raw), gravity_torques(arm, **raw), friction_torques(arm),
                        mass_matrix(rigid, **raw), coriolis_matrix(rigid, **raw))
    C_map = np.array([[1, 0], [0, 1], [0, -0.5]]) if coupled else np.eye(3)
    Ia = C_map.T @ np.diag([0.8, 0.2, 0.05]) @ C_map
    rng = np.random.default_rng(3)
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-2, 2, arm.n_coordinates) for _ in range(3))
        t, t_el, M_, M_ne, C, g, F, M_rigid, C_rigid = evaluate(*q, *qd, *qdd)
        theta_dot = C_map @ qd
        friction = C_map.T @ (np.array([1.5, 0, 0.3]) * theta_dot + np.array([0.7, 0.4, 0]) * np.sign(theta_dot))
        np.testing.assert_allclose(t.ravel(), t_el.ravel(), atol=1e-10)
        np.testing.assert_allclose(M_, M_ne, atol=1e-12)
        np.testing.assert_allclose(M_ - M_rigid, Ia, atol=1e-12)  # the armature, C^T diag(Ia) C
        np.testing.assert_allclose(C, C_rigid, atol=1e-12)  # friction is no Coriolis force
        np.testing.assert_allclose(F.ravel(), friction, atol=1e-12)
        np.testing.assert_allclose(t.ravel(), M_ @ qdd + C @ qd + g.ravel() + friction, atol=1e-10)


def test_smooth_coulomb_friction_is_tanh_of_the_rate_over_eps():
    arm = _arm()
    rate = arm.coordinate_rates[0]
    smooth = newton_euler(arm, simplify=False, friction="smooth", eps=0.01).torques
    difference = sp.expand(smooth[0] - newton_euler(arm, simplify=False).torques[0])
    assert difference == sp.expand(sp.Rational(7, 10) * (sp.tanh(100 * rate) - sp.sign(rate)))
    with pytest.raises(ValueError, match="friction='smooth' needs eps"):
        friction_torques(arm, "smooth")


@pytest.mark.parametrize(("target", "coupled"), [("python", False), ("numpy", False), ("numpy", True)])
def test_generated_dynamics_include_the_drives(tmp_path, target, coupled):
    """inverse_dynamics, mass_matrix and forward_dynamics of every strategy against the API's own numbers."""
    from symjac.codegen import ModuleRequest, describe, render_files

    arm = _arm(coupled)
    tau, M = (np.asarray(v) for v in (newton_euler(arm, simplify=False).torques, mass_matrix(arm, simplify=False)))
    evaluate = _numeric(arm, sp.Matrix(tau), sp.Matrix(M))
    rng = np.random.default_rng(5)
    q, qd, qdd = (rng.uniform(-1, 1, arm.n_coordinates) for _ in range(3))
    expected_tau, expected_M = evaluate(*q, *qd, *qdd)
    for strategy in ("fastest", "raw"):
        (name, text), = render_files(describe(ModuleRequest(arm, target, dynamics=True, strategy=strategy))).items()
        path = tmp_path / f"{strategy}_{name}"
        path.write_text(text)
        spec = importlib.util.spec_from_file_location(f"drives_{target}_{strategy}_{coupled}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        np.testing.assert_allclose(np.ravel(module.inverse_dynamics(q, qd, qdd)), expected_tau.ravel(), atol=1e-10)
        np.testing.assert_allclose(np.ravel(module.mass_matrix(q)), expected_M.ravel(), atol=1e-12)
        np.testing.assert_allclose(np.ravel(module.forward_dynamics(q, qd, expected_tau.ravel())), qdd, atol=1e-10)
        assert module.selftest() < 1e-6


def test_generated_c99_dynamics_with_friction_compile_cleanly_and_agree(tmp_path):
    """sign(qdot) written as comparisons: gcc -Wall -Wextra -Werror -pedantic, then the torques through ctypes."""
    import ctypes
    import shutil
    import subprocess

    from symjac.codegen import ModuleRequest, describe, render_files

    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed")
    arm = _arm()
    description = describe(ModuleRequest(arm, "c99", dynamics=True))
    for name, text in render_files(description).items():
        (tmp_path / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-O1", "-fPIC", "-shared",
                    "elbow.c", "-o", "lib.so", "-lm"], cwd=tmp_path, check=True, capture_output=True, text=True)
    library = ctypes.CDLL(str(tmp_path / "lib.so"))
    parameters = np.array([value for _, value in description.parameters])
    rng = np.random.default_rng(9)
    q, qd, qdd = (rng.uniform(-1, 1, 3) for _ in range(3))
    out = np.zeros(3)
    pointer = ctypes.POINTER(ctypes.c_double)
    library.elbow_inverse_dynamics(*(np.ascontiguousarray(a).ctypes.data_as(pointer)
                                     for a in (q, parameters, qd, qdd, out)))
    expected, = _numeric(arm, newton_euler(arm, simplify=False).torques)(*q, *qd, *qdd)
    np.testing.assert_allclose(out, expected.ravel(), atol=1e-10)
