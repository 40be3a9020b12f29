"""Degrees are never silent (issue 42, point 4): implausible radians are refused; ``--q`` has one syntax everywhere."""

from __future__ import annotations

import math
from importlib import resources

import pytest
import sympy as sp

from symjac.cli.args import configuration_values, parse_configuration
from symjac.errors import ArgumentError, RobotFileError
from symjac.model.bounds import MAX_TURN, MAX_URDF_LIMIT, turn_problem, urdf_turn_problem
from symjac.model.io import catalog, load_robot
from symjac.model.robot_file import robot_from_mapping

TWO_R = {"name": "two", "convention": "standard", "parameters": {"L1": 1, "L2": 0.5},
         "joints": [{"type": "revolute", "a": "L1"}, {"type": "revolute", "a": "L2"}]}


def _with(joint: dict | None = None, **top: object) -> dict:
    data = {**TWO_R, **top, "joints": [dict(TWO_R["joints"][0]), {**TWO_R["joints"][1], **(joint or {})}]}
    return data


# --- 1. implausible radians are refused, one line naming the file, the joint and the field --------------------------

REFUSED = {
    "alpha = -90": (_with({"alpha": -90}), "alpha"),
    "theta offset 180": (_with({"theta": 180}), "theta"),
    "theta offset as an expression": (_with({"theta": "3*pi"}), "theta"),
    "revolute limits +-170": (_with({"limits": [-170, 170]}), "limits"),
    "general rpy 90": ({"name": "g", "convention": "general",
                        "joints": [{"type": "revolute"}, {"type": "revolute", "rpy": [0, 90, 0]}]}, "rpy"),
}


@pytest.mark.parametrize(("data", "field"), REFUSED.values(), ids=REFUSED.keys())
def test_an_angle_of_more_than_a_turn_in_radians_is_refused(data, field):
    with pytest.raises(RobotFileError) as caught:
        robot_from_mapping(data, source="arm.toml")
    message = str(caught.value)
    assert len(message.splitlines()) == 1
    assert message.startswith("arm.toml, joint 2, field '")
    assert field in caught.value.field
    assert 'angle_unit = "deg"' in message


def test_base_and_tool_rpy_are_checked_too():
    with pytest.raises(RobotFileError, match=r"field 'tool.rpy'.*angle_unit = \"deg\""):
        robot_from_mapping(_with(tool={"rpy": [0, 0, 180]}), source="arm.toml")


@pytest.mark.parametrize("data", [_with({"alpha": -90}, angle_unit="deg"), _with({"limits": [-170, 170]},
                                                                                 angle_unit="deg")])
def test_the_same_numbers_in_a_file_in_degrees_are_read(data):
    robot = robot_from_mapping(data)
    assert robot.angle_unit == "deg"
    joint = robot.joints[1]
    assert joint.placement.alpha == -sp.pi / 2 or joint.limits == (-sp.Rational(17, 18) * sp.pi,
                                                                   sp.Rational(17, 18) * sp.pi)


@pytest.mark.parametrize("value", [2 * math.pi, 6.2832, -6.2832, "2*pi", "-2*pi"])
def test_a_full_turn_rounded_up_passes(value):
    lower = value if value in (-6.2832, "-2*pi") else -1
    robot = robot_from_mapping(_with({"alpha": value, "limits": [lower, 6.2832]}))
    assert robot.angle_unit == "rad"


def test_prismatic_limits_are_lengths_not_angles():
    data = _with()
    data["joints"][1] = {"type": "prismatic", "limits": [0, 20]}
    assert robot_from_mapping(data).joints[1].limits == (0, 20)


def test_the_bounds_themselves():
    assert math.isclose(MAX_TURN, 2 * math.pi + 0.01)
    assert turn_problem(6.29) is None and turn_problem(6.3) is not None
    assert urdf_turn_problem(6.98, limit=True) is None  # a wrist of +-400 degrees
    assert urdf_turn_problem(MAX_URDF_LIMIT + 0.01, limit=True) is not None
    assert urdf_turn_problem(7.0) is not None  # an rpy entry: one turn


def _urdf(rpy: str = "0 0 0", limits: str = 'lower="-3.1416" upper="3.1416"', kind: str = "revolute") -> str:
    return f"""<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j1" type="{kind}"><parent link="a"/><child link="b"/><origin xyz="0 0 0.1" rpy="{rpy}"/>
      <axis xyz="0 0 1"/><limit {limits} effort="1" velocity="1"/></joint></robot>"""


@pytest.mark.parametrize(("text", "where"), [(_urdf(rpy="0 90 0"), "origin"),
                                             (_urdf(limits='lower="-170" upper="170"'), "limit")])
def test_urdf_degrees_are_refused_with_a_urdf_message(tmp_path, text, where):
    path = tmp_path / "arm.urdf"
    path.write_text(text)
    with pytest.raises(RobotFileError) as caught:
        load_robot(str(path))
    message = str(caught.value)
    assert len(message.splitlines()) == 1
    assert "arm.urdf" in message and "j1" in message and where in message
    assert "URDF angles are in radians" in message and "angle_unit" not in message


@pytest.mark.parametrize("text", [_urdf(limits='lower="-6.2832" upper="6.2832"'),
                                  _urdf(limits='lower="-6.98" upper="6.98"'),  # ABB's axis 6: +-400 degrees
                                  _urdf(kind="continuous", limits=""), _urdf(rpy="3.14159 -1.5708 6.2832")])
def test_real_urdf_angles_pass(tmp_path, text):
    path = tmp_path / "arm.urdf"
    path.write_text(text)
    assert load_robot(str(path)).n_joints == 1


# --- 2. every catalog robot is accepted ------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(catalog()))
def test_every_catalog_robot_is_accepted(name):
    assert load_robot(name).angle_unit in ("rad", "deg")


@pytest.mark.parametrize("name", sorted(p.name for p in resources.files("symjac.robots").joinpath("urdf").iterdir()
                                        if p.name.endswith(".urdf")))
def test_every_catalog_urdf_is_accepted(name):
    path = resources.files("symjac.robots").joinpath("urdf", name)
    with resources.as_file(path) as file:
        try:
            robot = load_robot(str(file))
        except RobotFileError as error:  # a tree with several leaves needs --tip-link: not an angle problem
            assert "rad is more than" not in str(error), error
        else:
            assert robot.angle_unit == "rad"


# --- 3. --q: one syntax for every command, plain numbers in the file's unit ----------------------------------------

DEG_FILE = """name = "deg2r"
convention = "standard"
angle_unit = "deg"
[parameters]
L1 = 1
L2 = 0.5
[[joints]]
type = "revolute"
a = "L1"
[[joints]]
type = "revolute"
a = "L2"
"""


@pytest.fixture
def deg_file(tmp_path):
    path = tmp_path / "deg2r.toml"
    path.write_text(DEG_FILE)
    return str(path)


def test_the_robot_remembers_its_unit_outside_equality(deg_file):
    robot = load_robot(deg_file)
    assert robot.angle_unit == "deg"
    assert robot == robot_from_mapping({**TWO_R, "name": "deg2r"})  # the unit is where it came from, not what it is


@pytest.mark.parametrize(("text", "expected"), [("30deg,pi/4", [sp.pi / 6, sp.pi / 4]), ("0.5rad,-1", [0.5, -1]),
                                                ("pi/2, -pi/4", [sp.pi / 2, -sp.pi / 4])])
def test_the_shared_syntax_in_radians(capsys, text, expected):
    robot = load_robot("planar2r")
    assert [sp.nsimplify(v) for v in configuration_values(text, robot)] == [sp.nsimplify(e) for e in expected]
    assert capsys.readouterr().err == ""  # a robot in radians: nothing to note


def test_plain_numbers_are_degrees_in_a_degree_file_and_a_note_says_so(capsys, deg_file):
    robot = load_robot(deg_file)
    assert configuration_values("0,30", robot) == [0, sp.pi / 6]
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "--q 30 read in degrees" in err and 'angle_unit = "deg"' in err
    assert parse_configuration("pi/6,0.5rad", robot) == [pytest.approx(math.pi / 6), 0.5]
    assert capsys.readouterr().err == ""  # radians said explicitly: nothing to note


def test_a_prismatic_coordinate_takes_no_angle_unit():
    robot = load_robot("scara")
    q = ["0"] * robot.n_coordinates
    index = next(i for i, kind in enumerate(robot.coordinate_types) if kind.value == "prismatic")
    for unit in ("deg", "rad"):
        q[index] = f"0.1{unit}"
        with pytest.raises(ArgumentError, match="is a length"):
            configuration_values(",".join(q), robot)


def test_torques_and_draw_take_the_same_q(cli, deg_file, tmp_path):
    wrench = ("--wrench", "1,0,0,0,0,0", "--format", "pretty")
    by_degrees = cli.ok("torques", deg_file, "--q", "30deg,0", *wrench)  # refused before issue 42
    assert by_degrees == cli.ok("torques", deg_file, "--q", "pi/6,0", *wrench)
    status, out, err = cli.run("torques", deg_file, "--q", "30,0", *wrench)
    assert status == 0 and out == by_degrees and "read in degrees" in err
    status, _, err = cli.run("draw", deg_file, "--q", "30,0", "-o", str(tmp_path / "arm.png"))
    assert status == 0 and "--q 30 read in degrees" in err
    assert cli.run("draw", "planar2r", "--q", "30deg,pi/4", "-o", str(tmp_path / "arm2.png"))[0] == 0
