"""URDF import and general (origin + axis) chains: against the catalog's DH robots, hostile files, random chains."""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import time
from importlib import resources

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import evaluate, finite_difference_jacobian, frames, random_configuration
from strategies import general_robots

from symjac import (
    Convention,
    RobotFileError,
    UnknownRobotError,
    chain_of,
    forward_kinematics,
    jacobian,
    load_robot,
    robot_from_mapping,
    robot_from_toml,
    robot_to_toml,
)
from symjac.model.expressions import snap_angle
from symjac.model.io import urdf_catalog
from symjac.model.urdf import robot_from_urdf

PANDA_URDF = resources.files("symjac.robots").joinpath("urdf", "panda.urdf").read_text(encoding="utf-8")

# The vendor's DH frame {0} of the UR5 ("base" in ur_description) is base_link turned by pi about z
# (their base_link-base_fixed_joint, rpy 0 0 -pi); tool0 is the DH flange frame {6}.
UR5_BASE = np.diag([-1.0, -1.0, 1.0, 1.0])


def world_jacobian_at_flange(robot, q):
    """6 x n Jacobian of the flange (the tool frame if any, else {n}) in the robot's world frame, numerically."""
    point = "tool" if robot.tool is not None else "wrist"
    return evaluate(jacobian(robot, frame="world", point=point), robot, q)


@pytest.mark.parametrize(("dh_name", "urdf_name", "tip", "base"), [
    ("panda", "panda.urdf", "panda_link8", np.eye(4)),
    ("ur5", "ur5.urdf", None, UR5_BASE),
])
def test_urdf_robot_matches_catalog_dh_robot_at_the_flange(dh_name, urdf_name, tip, base):
    dh, urdf = load_robot(dh_name), load_robot(urdf_name, tip_link=tip)
    assert urdf.convention is Convention.GENERAL and urdf.n_joints == dh.n_joints
    rotate = np.kron(np.eye(2), base[:3, :3])
    rng = np.random.default_rng(7)
    for _ in range(5):
        q = random_configuration(dh, rng)
        np.testing.assert_allclose(frames(dh, q)[-1], base @ frames(urdf, q)[-1], atol=1e-12)
        symbolic_pose = evaluate(chain_of(urdf).transform("world", "tool"), urdf, q)
        np.testing.assert_allclose(symbolic_pose, frames(urdf, q)[-1], atol=1e-12)
        np.testing.assert_allclose(world_jacobian_at_flange(dh, q), rotate @ world_jacobian_at_flange(urdf, q),
                                   atol=1e-12)


def test_panda_urdf_link_frames_are_the_dh_frames():
    dh, urdf = load_robot("panda"), load_robot("panda.urdf", tip_link="panda_link8")
    assert [j.name for j in urdf.joints] == [f"panda_joint{i}" for i in range(1, 8)]
    assert urdf.joints[3].limits == (sp.Rational(-30718, 10000), sp.Rational(-698, 10000))
    q = random_configuration(dh, np.random.default_rng(1))
    for k in range(8):
        np.testing.assert_allclose(frames(dh, q)[k + 1], frames(urdf, q)[k + 1], atol=1e-12)


def test_default_tip_is_the_only_leaf_and_fixed_joints_fold_into_the_tool():
    robot = load_robot("panda.urdf")
    tool = robot.tool
    assert tool is not None and tool.xyz == (0, 0, sp.Rational(107, 1000)) and tool.rpy == (0, 0, -sp.pi / 4)


def test_ur5_urdf_exact_numbers_and_snapped_angles():
    robot = load_robot("ur5.urdf")
    shoulder = robot.joints[1]
    assert shoulder.placement.origin.xyz == (0, sp.Rational(13585, 100000), 0)
    assert shoulder.placement.origin.rpy == (0, sp.pi / 2, 0)
    assert shoulder.placement.axis == (0, 1, 0)
    assert robot.joints[2].limits == (-sp.pi, sp.pi)
    J = jacobian(robot)
    assert not J.atoms(sp.Float)


def test_snap_angle_only_within_tolerance():
    assert snap_angle(sp.Rational(0.7853981633974483)) == sp.pi / 4
    assert snap_angle(sp.Rational(-2.617993877991494)) == -5 * sp.pi / 6
    assert snap_angle(sp.Rational(1, 10)) == sp.Rational(1, 10)
    assert snap_angle(sp.Rational(15708, 10000)) == sp.Rational(15708, 10000)  # 3.7e-6 away: kept


def test_general_robot_round_trips_through_toml():
    robot = load_robot("ur5.urdf")
    again = robot_from_toml(robot_to_toml(robot))
    assert again == robot


def test_urdf_catalog_lists_the_built_in_files():
    assert set(urdf_catalog()) == {"gripper.urdf", "panda.urdf", "ur5.urdf"}
    assert all(urdf_catalog().values())


# --- the chain between two links --------------------------------------------------------------------------------

def _arm(extra: str = "", joint2: str = "revolute") -> str:
    return f"""<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3"/></joint>
  <joint name="j2" type="{joint2}"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/><axis xyz="0 -1 0"/><limit lower="0" upper="0.5"/></joint>
  <joint name="flange" type="fixed"><parent link="l2"/><child link="tip"/><origin xyz="0.1 0 0"/></joint>
  {extra}
</robot>"""


FINGERS = """
  <link name="finger_a"/><link name="finger_b"/>
  <joint name="fa" type="prismatic"><parent link="l2"/><child link="finger_a"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04"/></joint>
  <joint name="fb" type="prismatic"><parent link="l2"/><child link="finger_b"/><axis xyz="0 -1 0"/>
    <limit lower="0" upper="0.04"/><mimic joint="fa"/></joint>
  <link name="cam"/><joint name="cam_mount" type="floating"><parent link="base"/><child link="cam"/></joint>
"""


def test_branches_with_mimic_and_floating_joints_are_ignored():
    robot = robot_from_urdf(_arm(FINGERS), source="arm.urdf", tip_link="tip")
    assert [j.name for j in robot.joints] == ["j1", "j2"]
    assert robot.joints[1].placement.axis == (0, -1, 0)


def test_several_leaves_are_listed():
    with pytest.raises(RobotFileError, match=r"arm\.urdf: choose tip_link: .*finger_a, finger_b, tip"):
        robot_from_urdf(_arm(FINGERS), source="arm.urdf")


def test_mimic_of_a_joint_off_the_chain_makes_that_joint_a_coordinate():
    robot = robot_from_urdf(_arm(FINGERS), source="arm.urdf", tip_link="finger_b")
    t1, t2, _ = robot.joint_variables
    fa = sp.Symbol("fa", real=True)
    assert robot.q == (t1, t2, fa) and robot.joint_values == (t1, t2, fa)
    # finger b slides (no angular part) exactly as its own joint would, one for one with fa
    J, J_joints = jacobian(robot, simplify=True), jacobian(robot.uncoupled, simplify=True)
    assert J[:, 2] == J_joints[:, 2].xreplace({robot.joint_variables[2]: fa}) and J[3:, 2] == sp.zeros(3, 1)
    assert J[:3, 2] != sp.zeros(3, 1)


@pytest.mark.parametrize("kind", ["floating", "planar"])
def test_floating_and_planar_joints_on_the_chain_are_refused(kind):
    with pytest.raises(RobotFileError, match=rf"joint j2.*{kind} joints are not supported"):
        robot_from_urdf(_arm(joint2=kind))


def test_continuous_joint_has_no_limits():
    robot = robot_from_urdf(_arm(joint2="continuous"))
    assert robot.joints[1].limits is None and robot.joints[1].is_revolute


def test_base_and_tip_links_choose_a_sub_chain():
    robot = robot_from_urdf(_arm(), base_link="l1", tip_link="l2")
    assert robot.n_joints == 1
    assert robot.tool.rpy == (-sp.pi / 2, 0, 0)  # turns frame {1} (z on the axis -y) back to the link frame l2
    with pytest.raises(RobotFileError, match="tip_link 'base' is not below base_link 'l1'"):
        robot_from_urdf(_arm(), base_link="l1", tip_link="base")
    with pytest.raises(RobotFileError, match="base_link 'nowhere' is not a link"):
        robot_from_urdf(_arm(), base_link="nowhere")
    with pytest.raises(RobotFileError, match="no revolute, continuous or prismatic joint"):
        robot_from_urdf(_arm(), base_link="l2", tip_link="tip")


def test_prismatic_joint_with_negative_axis_matches_finite_differences():
    robot = robot_from_urdf(_arm(joint2="prismatic"))
    assert not robot.joints[1].is_revolute and robot.joints[1].limits == (0, sp.Rational(1, 2))
    q = np.array([0.3, 0.2])
    for frame in (0, 1, 2, "tool"):
        J = evaluate(jacobian(robot, frame=frame, point="tool"), robot, q)
        tool_point = np.array(robot.tool.matrix[:3, 3].subs(robot.defaults), dtype=float).ravel()
        expected = finite_difference_jacobian(robot, q, frame, tool_point)
        np.testing.assert_allclose(J, expected, atol=1e-8)


# --- hostile and malformed files --------------------------------------------------------------------------------

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
<!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
<!ENTITY lol9 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">]>
<robot name="&lol9;"><link name="a"/></robot>"""

EXTERNAL_ENTITY = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<robot name="arm"><link name="&secret;"/></robot>"""

HOSTILE = {
    "billion laughs": (BILLION_LAUGHS, "entity declarations"),
    "external entity": (EXTERNAL_ENTITY, "entity declarations"),
    "doctype only": ('<!DOCTYPE robot SYSTEM "http://example.com/robot.dtd"><robot name="a"/>', "DOCTYPE"),
    "undefined entity": ('<robot name="a"><link name="&secret;"/></robot>', "invalid XML"),
    "not xml": ("robot: arm", "invalid XML"),
    "truncated": ('<robot name="a"><link name="b"', "invalid XML"),
    "wrong root": ('<sdf><link name="a"/></sdf>', "root element must be <robot>"),
    "utf-16": ('<?xml version="1.0" encoding="UTF-16"?><robot name="a"/>', "only UTF-8"),
    "missing link": (_arm().replace('<link name="l2"/>', ""), "child link 'l2' is not defined"),
    "missing parent element": (_arm().replace('<parent link="l1"/>', ""), r"joint j2.*missing <parent"),
    "duplicate link": (_arm().replace('<link name="tip"/>', '<link name="tip"/><link name="tip"/>'),
                       "defined twice"),
    "two parents": (_arm('<joint name="x" type="fixed"><parent link="base"/><child link="l2"/></joint>'),
                    "child of two joints"),
    "loop": (_arm().replace('<parent link="base"/><child link="l1"/>', '<parent link="tip"/><child link="l1"/>'),
             "loop"),
    "unknown joint type": (_arm(joint2="ball"), "unknown joint type 'ball'"),
    "unknown type on a branch": (_arm('<link name="x"/><joint name="odd" type="spherical"><parent link="base"/>'
                                      '<child link="x"/></joint>'), "unknown joint type 'spherical'"),
    "nan": (_arm().replace('xyz="0.4 0 0"', 'xyz="nan 0 0"'), r"joint j2 origin.*finite number, got 'nan'"),
    "inf angle": (_arm().replace('rpy="1.5707963267948966 0 0"', 'rpy="inf 0 0"'), "finite number"),
    "huge exponent": (_arm().replace('xyz="0.4 0 0"', 'xyz="1e999999999 0 0"'), "finite number"),
    "long number": (_arm().replace('xyz="0.4 0 0"', f'xyz="{"1" * 5000} 0 0"'), "number too long"),
    "two numbers": (_arm().replace('xyz="0.4 0 0"', 'xyz="0.4 0"'), "expected 3 numbers"),
    "zero axis": (_arm().replace('<axis xyz="0 -1 0"/>', '<axis xyz="0 0 0"/>'), "zero vector"),
    "no links": ('<robot name="a"/>', "no links"),
    "binary": (b"\x00\x01<robot/>", "NUL"),
    "latin-1 bytes": ('<robot name="\xe9"/>'.encode("latin-1"), "not UTF-8"),
}


@pytest.mark.parametrize("case", sorted(HOSTILE))
def test_hostile_or_malformed_urdf_gives_a_typed_error_quickly(case, tmp_path):
    content, message = HOSTILE[case]
    path = tmp_path / "arm.urdf"
    path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))
    start = time.perf_counter()
    with pytest.raises(RobotFileError, match=message) as info:
        load_robot(path)
    assert time.perf_counter() - start < 2
    assert str(info.value).startswith(str(path))


@pytest.mark.parametrize("name", ["arm.xml", "arm", "arm.txt", "arm.toml"])
def test_urdf_is_recognised_by_its_content_whatever_its_name(name, tmp_path):
    path = tmp_path / name
    text = _arm(FINGERS).removeprefix('<?xml version="1.0"?>')  # a declaration must come first: keep it out
    path.write_bytes(b"\xef\xbb\xbf\n  " + text.encode("utf-8"))  # a byte order mark and blank space first
    robot = load_robot(path, tip_link="tip")
    assert [joint.name for joint in robot.joints] == ["j1", "j2"]
    assert robot.source == str(path)


def test_cli_reads_a_urdf_saved_as_xml(capsys, tmp_path):
    from symjac.cli.main import main

    path = tmp_path / "arm.xml"
    path.write_text(_arm(), encoding="utf-8")
    assert main(["show", str(path), "--format", "pretty"]) == 0
    assert "general chain" in capsys.readouterr().out


XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
XACRO = {
    "xacro element": f'<robot name="a" {XACRO_NS}><xacro:property name="L" value="0.4"/><link name="b"/></robot>',
    "undeclared prefix": '<robot name="a"><xacro:property name="L" value="0.4"/><link name="b"/></robot>',
    "xacro attribute": _arm().replace('<robot name="arm">', f'<robot name="arm" {XACRO_NS}>').replace(
        '<link name="tip"/>', '<link name="tip" xacro:if="1"/>'),
    "substitution": _arm().replace('xyz="0.4 0 0"', 'xyz="${L} 0 0"'),
    "find": _arm().replace('<link name="tip"/>', '<link name="tip"><visual><geometry><mesh '
                                                 'filename="$(find arm)/tip.stl"/></geometry></visual></link>'),
}


@pytest.mark.parametrize("case", sorted(XACRO))
@pytest.mark.parametrize(("name", "output"), [("arm.urdf.xacro", "arm.urdf"), ("arm.xacro", "arm.urdf"),
                                              ("arm.urdf", "arm_expanded.urdf")])
def test_xacro_file_is_refused_with_a_command_that_keeps_the_input(case, name, output, tmp_path):
    path = tmp_path / name
    path.write_text(XACRO[case], encoding="utf-8")
    with pytest.raises(RobotFileError, match=re.escape(f"{path}: this is a xacro file")) as info:
        load_robot(path)
    # -o, never "> out": a shell redirection onto the input would empty it before xacro reads it
    assert f"run `xacro {path} -o {tmp_path / output}` first and load {tmp_path / output}" in str(info.value)
    assert "finite number" not in str(info.value)


def test_the_xacro_command_is_quoted_and_never_overwrites_a_file(tmp_path):
    folder = tmp_path / "my robot;rm -rf x"
    folder.mkdir()
    path = folder / "arm.xacro"
    path.write_text(XACRO["substitution"], encoding="utf-8")
    (folder / "arm.urdf").write_text("an older expansion the user keeps", encoding="utf-8")
    with pytest.raises(RobotFileError) as info:
        load_robot(path)
    command = re.search(r"run `([^`]*)`", str(info.value)).group(1)
    assert shlex.split(command) == ["xacro", str(path), "-o", str(folder / "arm_expanded.urdf")]


def test_the_xacro_command_given_expands_the_file_into_a_new_one(tmp_path):
    path = tmp_path / "arm.urdf"
    source = _arm().replace('<robot name="arm">', f'<robot name="arm" {XACRO_NS}>').replace(
        '<link name="base"/>', '<xacro:property name="L" value="0.4"/><link name="base"/>').replace(
        'xyz="0.4 0 0"', 'xyz="${L} 0 0"')
    path.write_text(source, encoding="utf-8")
    with pytest.raises(RobotFileError) as info:
        load_robot(path)
    command = shlex.split(re.search(r"run `([^`]*)`", str(info.value)).group(1))
    xacro = shutil.which("xacro")
    assert xacro is not None, "the test extra installs xacro (PyPI), the command the hint names"
    subprocess.run([xacro, *command[1:]], cwd=tmp_path, check=True, capture_output=True)
    assert path.read_text(encoding="utf-8") == source  # the input is untouched
    expanded = load_robot(command[-1])
    assert expanded.n_joints == robot_from_urdf(_arm()).n_joints
    assert sp.simplify(forward_kinematics(expanded) - forward_kinematics(robot_from_urdf(_arm()))) == sp.zeros(4, 4)


@pytest.mark.parametrize("place", ["comment", "text"])
def test_substitutions_in_comments_and_text_are_plain_urdf(place):
    # files written by xacro keep commented-out macros with ${prefix}: they are plain URDF
    extra = {"comment": '<!-- <link name="${prefix}link_eef"/> <xacro:macro name="m"/> -->',
             "text": '<gazebo>${not_an_attribute}</gazebo>'}[place]
    robot = robot_from_urdf(_arm().replace('<link name="tip"/>', f'<link name="tip"/>{extra}'))
    assert robot.n_joints == 2


def test_xacro_namespace_alone_is_plain_urdf():
    # xacro leaves xmlns:xacro on the <robot> of the URDF files it writes: such a file is expanded already
    robot = robot_from_urdf(_arm().replace('<robot name="arm">', '<robot name="arm" xmlns:xacro="x">'))
    assert robot.n_joints == 2


@pytest.mark.parametrize(("lower", "upper"), [("3", "-3"), ("0.5", "0.5"), ("0.1", "0")])
def test_reversed_urdf_limits_are_refused_naming_file_and_joint(lower, upper, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(_arm().replace('lower="-3" upper="3"', f'lower="{lower}" upper="{upper}"'), encoding="utf-8")
    expected = f"{path}, field 'joint j1 limit': 'limits' must be finite with lower < upper, got "
    with pytest.raises(RobotFileError, match=re.escape(expected + f"[{float(lower)}, {float(upper)}]")):
        load_robot(path)
    toml = robot_to_toml(load_robot("planar2r")).replace('type = "revolute"', f'type = "revolute"\nlimits = '
                                                         f'[{lower}, {upper}]', 1)
    with pytest.raises(RobotFileError, match=re.escape("'limits' must be finite with lower < upper, got ")):
        robot_from_toml(toml)  # the TOML reader says it in the same words


def test_urdf_zero_limits_mean_no_limits():
    robot = robot_from_urdf(_arm().replace('lower="-3" upper="3"', 'lower="0" upper="0"'))
    assert robot.joints[0].limits is None and robot.joints[1].limits == (0, sp.Rational(1, 2))


@pytest.mark.parametrize("encoding", ["ISO-8859-1", "iso-8859-1", "latin1", "US-ASCII", "utf-8"])
def test_declared_latin_1_and_ascii_files_are_read(encoding, tmp_path):
    text = _arm().replace('<?xml version="1.0"?>', f'<?xml version="1.0" encoding="{encoding}"?>')
    if encoding != "US-ASCII":
        text = text.replace('name="j2"', 'name="coude_\xe9"')
    path = tmp_path / "arm.urdf"
    path.write_bytes(text.encode("ascii" if encoding == "US-ASCII" else
                                 "utf-8" if encoding == "utf-8" else "latin-1"))
    robot = load_robot(path)
    assert robot.joints[1].name == ("j2" if encoding == "US-ASCII" else "coude_\xe9")


def test_unknown_urdf_name_is_an_unknown_robot():
    with pytest.raises(UnknownRobotError, match=re.escape("panda.urdf, ur5.urdf")):
        load_robot("kuka.urdf")


def test_links_apply_to_urdf_only():
    with pytest.raises(RobotFileError, match="URDF and MJCF files only"):
        load_robot("puma560", tip_link="x")


def test_cli_reads_a_urdf_file(capsys, tmp_path):
    from symjac.cli.main import main

    path = tmp_path / "arm.urdf"
    path.write_text(_arm(), encoding="utf-8")
    assert main(["fk", str(path), "--format", "pretty"]) == 0
    assert "T_0_tool" in capsys.readouterr().out
    assert main(["show", "ur5.urdf", "--format", "pretty"]) == 0
    out = capsys.readouterr().out
    assert "general chain" in out and "[0, pi/2, 0]" in out
    assert main(["show", "ur5.urdf"]) == 0
    assert r"\text{axis} & d_i & \theta_i" in capsys.readouterr().out


# --- random general chains ----------------------------------------------------------------------------------------

SETTINGS = settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(robot=general_robots(max_joints=5), data=st.data())
@pytest.mark.slow
def test_general_chain_jacobian_matches_finite_differences(robot, data):
    n = robot.n_joints
    frame = data.draw(st.sampled_from(["world", *range(n + 1), "tool"]), label="frame")
    point = "tool" if robot.tool is not None else "wrist"
    coordinates = None
    if point == "tool":
        coordinates = np.array(robot.tool.matrix[:3, 3].subs(robot.defaults), dtype=float).ravel()
    method = data.draw(st.sampled_from(["differentiation", "cross_product", "velocity_propagation",
                                        "force_propagation"]), label="method")
    J = jacobian(robot, frame=frame, point=point, method=method)
    q = random_configuration(robot, np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed")))
    np.testing.assert_allclose(evaluate(J, robot, q), finite_difference_jacobian(robot, q, frame, coordinates),
                               atol=1e-6)


@SETTINGS
@given(robot=general_robots(max_joints=5))
def test_general_chain_round_trips_through_toml(robot):
    assert robot_from_toml(robot_to_toml(robot)) == robot


def test_alignment_frames_put_z_on_the_joint_axis():
    robot = load_robot("ur5.urdf")
    chain = chain_of(robot)
    # joint 2 (axis y of shoulder_link turned by pitch pi/2): z_2 in frame {1} is the y-axis of frame {1}
    assert list(chain.rotation(1, 2)[:, 2]) == [0, 1, 0]
    assert chain.parallel_groups == ((1,), (2, 3, 4), (5,), (6,))


def test_prismatic_joint_turned_about_its_axis_does_not_duplicate_a_basis_angle():
    """Regression (found by hypothesis): an origin rotated about z before a prismatic joint gave two basis angles
    theta1 and theta1 + pi/2 for one joint angle."""
    robot = robot_from_mapping({"name": "g", "convention": "general", "parameters": {"L": 0.35}, "joints": [
        {"type": "revolute"}, {"type": "prismatic", "xyz": [0, 0, 0], "rpy": [0, 0, "pi/2"]}]})
    for frame in ("world", 0, 1, 2):
        J = jacobian(robot, frame=frame)
        assert list(J[:, 1]) == [0, 0, 1, 0, 0, 0]
