"""DH conversion: standard <-> modified (exact, symbolic), DH extraction from general chains, `symjac convert`."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from marks import marked
from reference import frames, random_configuration
from strategies import SPECIAL_RPY, general_robots, robots

from symjac import AngleBasis, Chain, Convention, catalog, is_identity, jacobian, load_robot, robot_from_toml
from symjac.cli.main import main
from symjac.kinematics.convert import (
    ConversionError,
    convert,
    dh_from_general,
    modified_from_standard,
    standard_from_modified,
)


def _point(robot):
    return "tool" if robot.tool is not None else "wrist"


def assert_identical(robot, other, *, with_jacobian=True):
    """World-to-tool pose and the world-frame Jacobian at the tool point are identical expressions of q."""
    assert other.q == robot.q
    basis = AngleBasis.of([j.variable for j in robot.joints if j.is_revolute])
    exact, exact_other = Chain(robot, nested=False), Chain(other, nested=False)  # generic twists too: exact algebra
    pairs = [(exact.transform("world", "tool"), exact_other.transform("world", "tool"))]
    if with_jacobian:
        pairs.append((jacobian(exact, frame="world", point=_point(robot), simplify=False),
                      jacobian(exact_other, frame="world", point=_point(other), simplify=False)))
    for left, right in pairs:
        for a, b in zip(left, right, strict=True):
            assert is_identity(a, b, basis), (a, b)


def round_trip(robot):
    if robot.convention is Convention.STANDARD:
        there = modified_from_standard(robot)
        return there, standard_from_modified(there)
    there = standard_from_modified(robot)
    return there, modified_from_standard(there)


DH_CATALOG = [name for name in sorted(catalog())
              if load_robot(name).convention in (Convention.STANDARD, Convention.MODIFIED)]


@pytest.mark.parametrize("name", marked(DH_CATALOG))
def test_catalog_round_trip_is_exact(name):
    robot = load_robot(name)
    there, back = round_trip(robot)
    assert there.convention is not robot.convention and back.convention is robot.convention
    assert_identical(robot, there)
    assert_identical(robot, back, with_jacobian=False)
    if robot.convention is Convention.STANDARD and robot.tool is None:
        assert back == robot  # standard -> modified -> standard gives the very same table


@settings(deadline=None, max_examples=20, suppress_health_check=[HealthCheck.too_slow])
@given(robot=robots(max_joints=5))
def test_random_round_trip_is_exact(robot):
    there, back = round_trip(robot)
    assert_identical(robot, there)
    assert_identical(robot, back)


def test_ur5_modified_table_and_round_trip():
    ur5 = load_robot("ur5")
    modified = convert(ur5, "modified")
    assert [j.placement.alpha for j in modified.joints] == [0, sp.pi / 2, 0, 0, sp.pi / 2, -sp.pi / 2]
    assert [str(j.placement.a) for j in modified.joints] == ["0", "0", "a2", "a3", "0", "0"]
    assert modified.tool is None and modified.base is None
    assert convert(modified, "standard") == ur5
    assert convert(ur5, "standard") is ur5


def test_modified_with_first_twist_moves_into_the_base():
    robot = load_robot("panda")
    standard = standard_from_modified(robot)
    assert standard.base is None  # alpha_0 = a_0 = 0
    assert standard.joints[-1].placement.alpha == 0 and standard.joints[0].placement.alpha == -sp.pi / 2


def test_conversion_refuses_the_wrong_convention():
    with pytest.raises(ConversionError, match="not in the standard convention"):
        modified_from_standard(load_robot("panda"))
    with pytest.raises(ConversionError, match="not in the modified convention"):
        standard_from_modified(load_robot("ur5"))


def test_panda_urdf_gives_the_manufacturer_dh_table():
    extraction = dh_from_general(load_robot("panda.urdf", tip_link="panda_link8"))
    catalog_panda = load_robot("panda")
    found = extraction.robot
    assert not extraction.needs_base and extraction.needs_tool  # the flange offset dF is a tool transform
    for mine, theirs in zip(found.joints, catalog_panda.joints, strict=True):
        for key in ("alpha", "a", "d", "theta"):
            value = getattr(theirs.placement if key in ("alpha", "a") else theirs, key).subs(catalog_panda.defaults)
            assert getattr(mine.placement if key in ("alpha", "a") else mine, key) == value, (mine.index, key)
    assert found.tool.matrix == catalog_panda.tool.matrix.subs(catalog_panda.defaults)


@pytest.mark.parametrize(("name", "tip"), [("panda.urdf", None), ("ur5.urdf", None)])
def test_dh_extraction_is_exact(name, tip):
    general = load_robot(name, tip_link=tip)
    for target in ("modified", "standard"):
        converted = convert(general, target)
        assert converted.convention == target
        assert_identical(general, converted, with_jacobian=target == "modified")


@settings(deadline=None, max_examples=12, suppress_health_check=[HealthCheck.too_slow])
@given(robot=general_robots(max_joints=4, rpy=SPECIAL_RPY))
def test_dh_extraction_of_random_general_chains(robot):
    dh = dh_from_general(robot, substitute_defaults=True).robot
    q = random_configuration(robot, np.random.default_rng(3))
    np.testing.assert_allclose(frames(dh, q)[-1], frames(robot, q)[-1], atol=1e-9)


def test_symbolic_general_chain_is_refused():
    robot = robot_to_general_with_parameter()
    with pytest.raises(ConversionError, match="numeric frames"):
        dh_from_general(robot)


def test_generic_constant_angles_are_refused_quickly():
    from symjac import robot_from_mapping

    robot = robot_from_mapping({"name": "g", "convention": "general",
                                "joints": [{"type": "revolute"}, {"type": "revolute", "rpy": [0.3, 0, 0]}]})
    with pytest.raises(ConversionError, match="its geometry is generic"):
        dh_from_general(robot)


def robot_to_general_with_parameter():
    from symjac import robot_from_mapping

    return robot_from_mapping({"name": "g", "convention": "general", "parameters": {"L": 1},
                               "joints": [{"type": "revolute", "xyz": ["L", 0, 0]}]})


@pytest.mark.parametrize(("robot", "to"), [("ur5", "modified"), ("panda", "standard"), ("panda.urdf", "modified"),
                                           ("ur5.urdf", "toml"), ("stanford", "toml")])
def test_cli_convert_prints_a_robot_file(capsys, robot, to):
    assert main(["convert", robot, "--to", to]) == 0
    text = capsys.readouterr().out
    parsed = robot_from_toml(text)
    expected = load_robot(robot) if to == "toml" else convert(load_robot(robot), to)
    assert parsed == expected


def test_cli_convert_urdf_links(capsys):
    assert main(["convert", "panda.urdf", "--to", "toml", "--tip-link", "panda_link8"]) == 0
    assert robot_from_toml(capsys.readouterr().out).tool.rpy == (0, 0, 0)
    assert main(["convert", "panda.urdf", "--to", "toml", "--tip-link", "nowhere"]) == 2
    assert "--tip-link 'nowhere' is not a link" in capsys.readouterr().err


def test_convert_command_says_when_the_table_needs_a_tool_transform(capsys):
    from symjac.cli.main import main

    assert main(["convert", "ur5.urdf", "--to", "modified"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# ") and "tool transform" in out.splitlines()[0]
