"""The catalog and loading robots by name, path or text (symjac.model.io)."""

from __future__ import annotations

import dataclasses
import math
import re

import pytest
import sympy as sp
from robot_mappings import (
    CATALOG,
    EXPECTED,
    L1,
    L2,
    PLANAR,
    d3,
    load_robot_from_text,
)

from symjac.errors import RobotFileError, SymjacError, UnknownRobotError
from symjac.model.io import catalog, load_robot, robot_from_toml
from symjac.model.robot import (
    Convention,
    JointType,
    Robot,
)

# --------------------------------------------------------------------------------------------- catalog and load_robot


def test_catalog_lists_the_built_in_robots():
    robots = catalog()
    assert set(EXPECTED) <= set(robots)
    assert list(robots) == sorted(robots)
    for name, description in robots.items():
        assert isinstance(description, str)
        assert description, f"{name} has no description"


def placement_values(placement) -> list[sp.Expr]:
    """The numbers of a joint's placement: a DH row's alpha and a, or the entries of a screw and its point."""
    values = []
    for field in dataclasses.fields(placement):
        value = getattr(placement, field.name)
        if field.compare and isinstance(value, sp.Expr):
            values.append(value)
        elif field.compare and isinstance(value, tuple):
            values.extend(value)
    return values


@pytest.mark.parametrize("name", CATALOG)
def test_every_catalog_robot_loads(name):
    robot = load_robot(name)
    assert isinstance(robot, Robot)
    assert robot.name == name
    assert robot.source == f"{name}.toml"
    assert robot.description == catalog()[name]
    assert robot.n_joints >= robot.n_coordinates == len(robot.q) >= 1
    assert (robot.coupling is None) == (robot.n_joints == robot.n_coordinates)
    for parameter in robot.parameters:
        assert isinstance(parameter.default, sp.Rational)
    for joint in robot.joints:
        for value in (*placement_values(joint.placement), joint.d, joint.theta):
            assert value.free_symbols <= set(robot.parameter_symbols)
            assert math.isfinite(float(value.subs(robot.defaults)))


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_catalog_robot_shapes(name):
    dof, convention, prismatic, has_base, has_tool = EXPECTED[name]
    robot = load_robot(name)
    assert robot.n_joints == dof
    assert robot.convention == convention
    assert tuple(j.index for j in robot.joints if not j.is_revolute) == prismatic
    assert (robot.base is not None) == has_base
    assert (robot.tool is not None) == has_tool


def test_stanford_arm():
    robot = load_robot("stanford")
    assert [str(v) for v in robot.q] == ["theta1", "theta2", "d3", "theta4", "theta5", "theta6"]
    assert robot.joints[2].type is JointType.PRISMATIC
    assert robot.joints[2].limits == (sp.Rational(3, 10), sp.Rational(13, 10))
    assert robot.joints[2].offset == d3


def test_puma560_parameters_and_limits():
    robot = load_robot("puma560")
    a2, d4 = sp.symbols("a2 d4", real=True)
    assert robot.defaults[a2] == sp.Rational(2159, 5000)
    assert robot.defaults[d4] == sp.Rational(2159, 5000)
    assert robot.joints[1].placement.alpha == -sp.pi / 2
    assert robot.joints[0].limits == (-8 * sp.pi / 9, 8 * sp.pi / 9)
    assert robot.joints[2].placement.a == a2


def test_ur5_is_standard_dh():
    robot = load_robot("ur5")
    assert robot.convention is Convention.STANDARD
    assert robot.joints[0].placement.alpha == sp.pi / 2
    assert robot.defaults[sp.Symbol("a3", real=True)] == sp.Rational(-1569, 4000)


def test_panda_has_a_tool():
    robot = load_robot("panda")
    assert robot.n_joints == 7
    assert robot.tool is not None
    assert robot.tool.xyz == (0, 0, sp.Symbol("dF", real=True))
    assert robot.tool.rpy == (0, 0, 0)
    assert all(joint.limits is not None for joint in robot.joints)


def test_scara_prismatic_joint():
    robot = load_robot("scara")
    assert robot.joints[2].variable == d3
    assert robot.joints[2].limits == (sp.Rational(-3, 20), 0)


def test_load_robot_from_a_path(tmp_path):
    path = tmp_path / "myarm.toml"
    path.write_text(PLANAR, encoding="utf-8")
    for argument in (path, str(path)):
        robot = load_robot(argument)
        assert robot.name == "myarm"
        assert robot.source == str(path)
        assert robot.n_joints == 2
        assert robot.joints[1].limits == (-3, 3)
        assert robot.defaults == {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5)}


def test_load_robot_from_a_path_with_another_suffix(tmp_path):
    path = tmp_path / "myarm.robot"
    path.write_text(PLANAR, encoding="utf-8")
    assert load_robot(str(path)).name == "myarm"


def test_load_robot_from_a_relative_toml_path(tmp_path, monkeypatch):
    (tmp_path / "myarm.toml").write_text(PLANAR, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert load_robot("myarm.toml").name == "myarm"


def test_catalog_name_wins_over_a_file_of_the_same_name(tmp_path, monkeypatch):
    (tmp_path / "puma560").write_text(PLANAR, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert load_robot("puma560").name == "puma560"


def test_invalid_toml_names_the_file(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('name = "arm"\nconvention = \n', encoding="utf-8")
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}: invalid TOML")) as info:
        load_robot(path)
    assert info.value.source == str(path)


def test_invalid_robot_in_a_file_names_file_joint_and_field(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text(PLANAR.replace('a = "L2"', 'a = "L3"'), encoding="utf-8")
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}, joint 2, field 'a': unknown name 'L3'")):
        load_robot(path)


def test_file_that_is_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(PLANAR.replace("two links", "zwei Glieder \xe4").encode("latin-1"))
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}: cannot read file")):
        load_robot(path)


def test_hostile_file_is_rejected_without_running(tmp_path):
    target = tmp_path / "pwned_symjac"
    path = tmp_path / "evil.toml"
    path.write_text(PLANAR.replace('a = "L1"', f"a = \"__import__('os').system('touch {target}')\""), "utf-8")
    with pytest.raises(RobotFileError, match="joint 1, field 'a'"):
        load_robot(path)
    assert not target.exists()


CLIMBING_NAME = "../puma560"  # outside-the-repository: allowed (a catalog name that must be refused)


@pytest.mark.parametrize("name", ["no_such_robot", "PUMA560", "puma", "", CLIMBING_NAME, "robots/puma560"])
def test_unknown_robot_name(name):
    with pytest.raises(UnknownRobotError, match="neither a built-in robot") as info:
        load_robot(name)
    assert isinstance(info.value, SymjacError)
    assert isinstance(info.value, LookupError)
    assert "puma560" in str(info.value)  # the catalog is listed


def test_missing_file_and_directory_are_unknown_robots(tmp_path):
    with pytest.raises(UnknownRobotError):
        load_robot(tmp_path / "missing.toml")
    with pytest.raises(UnknownRobotError):
        load_robot(str(tmp_path / "missing.toml"))
    with pytest.raises(UnknownRobotError):
        load_robot(tmp_path)


def test_robot_from_toml_default_source():
    with pytest.raises(RobotFileError, match=r"^<string>: invalid TOML"):
        robot_from_toml("name = ")
    with pytest.raises(RobotFileError, match=r"^<string>, field 'convention'"):
        robot_from_toml('name = "arm"\n[[joints]]\ntype = "revolute"\n')


def test_robot_from_toml_with_source():
    robot = robot_from_toml(PLANAR, source="inline")
    assert robot.source == "inline"
    assert robot == load_robot_from_text(PLANAR)
