"""The arm geometry closed-form IK is decided on: axes at home reproduce every catalog robot's forward kinematics, and
the predicates are identities in the parameters, not tests within a tolerance."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest
import sympy
from scipy.spatial.transform import Rotation

from symjac import load_robot, robot_from_toml
from symjac.analysis.inverse_kinematics import arm_geometry, reduced_geometry
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import ArgumentError
from symjac.model.io import catalog

CATALOG = sorted(catalog())


def product_of_exponentials(geometry, q):
    """FK about the axes, built independently: SciPy rotations about (h, p), translations along h."""
    numbers = geometry.robot.defaults
    pose = np.eye(4)
    for h, p, kind, value in zip(geometry.axes, geometry.points, geometry.kinds, q, strict=True):
        h = np.array(h.subs(numbers), dtype=float).ravel()
        p = np.array(p.subs(numbers), dtype=float).ravel()
        motion = np.eye(4)
        if kind == "prismatic":
            motion[:3, 3] = value * h
        else:
            rotation = Rotation.from_rotvec(value * h).as_matrix()
            motion[:3, :3], motion[:3, 3] = rotation, p - rotation @ p
        pose = pose @ motion
    return pose @ np.array(geometry.home.subs(numbers), dtype=float)


@pytest.mark.parametrize("name", CATALOG)
def test_product_of_exponentials_is_the_robots_forward_kinematics(name):
    robot = load_robot(name)
    geometry = arm_geometry(robot)
    model = numeric_model(robot.uncoupled, backend="numpy")  # coupled joints: the chain of independent joints
    generator = np.random.default_rng(46)
    for axis in geometry.axes:
        assert sympy.simplify(axis.dot(axis) - 1) == 0
    for _ in range(20):
        q = generator.uniform(-2.0, 2.0, robot.n_joints)
        assert np.abs(product_of_exponentials(geometry, q) - model.fk(q)).max() < 1e-12


def test_the_pose_frame_is_frame_0_without_the_base():
    text = (
        'name = "based"\nconvention = "standard"\n[base]\nxyz = [1, 2, 3]\nrpy = [0, 0, 0.5]\n'
        '[[joints]]\ntype = "revolute"\na = 0.5\n[[joints]]\ntype = "revolute"\na = 0.4\n')
    robot = robot_from_toml(text)
    geometry = arm_geometry(robot)
    q = np.array([0.3, -0.7])
    assert np.abs(product_of_exponentials(geometry, q) - numeric_model(robot, backend="numpy").fk(q)).max() < 1e-12
    assert sympy.Matrix([[sympy.Rational(9, 10), 0, 0]]) == geometry.home[:3, 3].T


def test_puma_facts_are_identities_in_its_parameters():
    geometry = arm_geometry(load_robot("puma560"))
    a2, a3, d3, d4 = sympy.symbols("a2 a3 d3 d4", real=True)
    centre = geometry.intersection(3, 4, 5)
    assert centre is not None and centre.free_symbols == {a2, a3, d3, d4}
    assert sympy.simplify(centre - sympy.Matrix([a2 + a3, d3, -d4])) == sympy.zeros(3, 1)
    assert geometry.parallel(1, 2) and not geometry.parallel(0, 1)
    assert geometry.intersection(0, 1) == sympy.zeros(3, 1)
    assert geometry.intersection(1, 2) is None  # parallel axes meet nowhere
    assert geometry.intersection(2, 3) is None and "0.0203 apart" in geometry.why_not_meet(2, 3)
    assert geometry.why_not_meet(3, 4, 5) == "the axes of joints 4, 5 and 6 meet in one point"


def test_axes_that_miss_by_a_little_do_not_meet():
    text = _puma_with(joint=5, a="0.0001")
    geometry = arm_geometry(robot_from_toml(text))
    assert geometry.intersection(3, 4, 5) is None
    assert "0.0001 apart" in geometry.why_not_meet(3, 4, 5)


def test_axes_that_meet_only_at_the_defaults_do_not_meet():
    text = _puma_with(joint=5, a="e5", parameter="e5 = 0")
    geometry = arm_geometry(robot_from_toml(text))
    assert geometry.intersection(3, 4, 5) is None
    assert "for some values only" in geometry.why_not_meet(3, 4, 5)


def _puma_with(*, joint: int, a: str, parameter: str = "") -> str:
    """The PUMA 560's file with joint ``joint``'s (1-based) ``a`` replaced; inertial data left out."""
    source = resources.files("symjac.robots").joinpath("puma560.toml").read_text(encoding="utf-8")
    blocks = source.split("[[joints]]")
    head = blocks[0].replace("[parameters]\n", f"[parameters]\n{parameter}\n" if parameter else "[parameters]\n")
    joints = []
    for number, block in enumerate(blocks[1:], start=1):
        block = block.split("[joints.drive]")[0].split("[joints.inertial]")[0]
        if number == joint:
            block = block.replace("\na = 0\n", f'\na = "{a}"\n')
        joints.append(block)
    return head + "".join(f"[[joints]]{block}" for block in joints)


def test_reduced_geometry_of_the_iiwa_keeps_its_spherical_shoulder_and_wrist():
    robot = load_robot("iiwa7")
    geometry = reduced_geometry(robot, 3)
    assert geometry.joints == (0, 1, 3, 4, 5, 6) and geometry.free_joint == 3 and geometry.free_index == 2
    assert geometry.intersection(0, 1) is not None
    assert geometry.intersection(4, 5, 6) is not None
    theta3 = robot.joint_variables[2]
    assert theta3 in geometry.axis(3).free_symbols
    q = np.array([0.2, -0.4, 0.9, 1.1, -0.3, 0.5, 0.7])
    numbers = {theta3: q[2]}
    reduced = type(geometry)(robot, tuple(h.subs(numbers) for h in geometry.axes),
                             tuple(p.subs(numbers) for p in geometry.points), geometry.kinds,
                             geometry.home.subs(numbers))
    model = numeric_model(robot, backend="numpy")
    assert np.abs(product_of_exponentials(reduced, np.delete(q, 2)) - model.fk(q)).max() < 1e-12


def test_bad_joint_numbers_are_refused():
    geometry = arm_geometry(load_robot("puma560"))
    with pytest.raises(ArgumentError, match=r"joint 7 \(0-based\) is not one of"):
        geometry.axis(7)
    with pytest.raises(ArgumentError, match="two axes or more"):
        geometry.intersection(3)
    with pytest.raises(ArgumentError, match="free_joint must be a joint number from 1 to 6, got 7"):
        reduced_geometry(load_robot("puma560"), 7)
    with pytest.raises(ArgumentError, match="from 1 to 6, got 0"):
        reduced_geometry(load_robot("puma560"), 0)
