"""The MJCF reader on its own: exact numbers, MJCF's rules (degrees, defaults, includes, sites), refusals, hostility.

MuJoCo itself checks the poses and Jacobians of the same fixtures in ``tests/test_mjcf_mujoco.py``; here the reader's
numbers are compared with what the file says, computed by hand, and every refusal is one line naming file and element.
"""

from __future__ import annotations

import json
import re
import time
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symjac.cli.main import main
from symjac.errors import RobotFileError
from symjac.kinematics.chain import forward_kinematics
from symjac.kinematics.numeric import numeric_at
from symjac.model.io import load_robot
from symjac.model.readers import reader_for
from symjac.model.readers.mjcf import MAX_MJCF_BYTES, mjcf_model, robot_from_mjcf
from symjac.model.readers.mjcf_xml import MAX_MJCF_INCLUDES

PARENT = ".." + "/"  # the parent folder, spelt in pieces: the repository names no path outside itself

DATA = Path(__file__).parent / "data" / "mjcf"


def _mjcf(bodies: str, head: str = "", tail: str = "") -> str:
    return f'<mujoco model="t">{head}<worldbody>{bodies}</worldbody>{tail}</mujoco>'


TWO = _mjcf('<body name="l1" pos="0 0 0.5"><joint name="j1" axis="0 0 1" range="-90 90"/>'
            '<body name="l2" pos="0.4 0 0"><joint name="j2" axis="0 1 0"/><site name="tip" pos="0.3 0 0"/>'
            '</body></body>')


def _write(folder: Path, name: str, text: str | bytes) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(text.encode("utf-8") if isinstance(text, str) else text)
    return path


# --- what is read, exactly -------------------------------------------------------------------------------------

def test_mjcf_is_chosen_by_content_and_reads_exactly(tmp_path):
    path = _write(tmp_path, "arm.xml", TWO)
    assert reader_for(TWO.encode(), str(path)).name == "MJCF"
    robot = load_robot(path)
    assert [joint.name for joint in robot.joints] == ["j1", "j2"]
    assert robot.joints[0].limits == (-sp.pi / 2, sp.pi / 2)  # MJCF's default unit is the degree
    assert robot.joints[1].limits is None  # no range: no limits (autolimits)
    assert robot.joints[0].placement.origin.xyz == (0, 0, sp.Rational(1, 2))
    assert robot.tool.xyz == (0, 0, 0)  # the tip is the only leaf body, l2 (the tool turns {2}'s z back to z)
    with_site = load_robot(path, tip_site="tip")
    assert with_site.tool.xyz == (sp.Rational(3, 10), 0, 0) and with_site.tool.rpy == (sp.pi / 2, 0, 0)
    assert load_robot(path, tip_link="tip") == with_site  # a site name is accepted as the tip


def test_angles_in_degrees_and_radians_are_exact():
    degrees = robot_from_mjcf(_mjcf('<body euler="0 0 30"><joint range="-45 120" ref="15"/></body>'))
    radians = robot_from_mjcf(_mjcf('<body euler="0 0 0.5235987755982988"><joint range="-0.7853981633974483 '
                                    '2.0943951023931953" ref="0.2617993877991494"/></body>',
                                    '<compiler angle="radian"/>'))
    assert degrees.joints[0].limits == radians.joints[0].limits == (-sp.pi / 4, 2 * sp.pi / 3)
    assert degrees == radians  # the ref turns the origin back by pi/12: the same exact placement
    assert degrees.joints[0].placement.origin.rpy == (0, 0, sp.pi / 12)


def test_quaternions_are_normalised_exactly_and_stay_rational():
    robot = robot_from_mjcf(_mjcf('<body quat="1 0 0 1"><joint/></body><body quat="2 1 0 0" pos="1 0 0"><joint/>'
                                  '</body>'), tip_link="body2")
    three, four = sp.Rational(3, 5), sp.Rational(4, 5)  # (2, 1, 0, 0): cos = 3/5, sin = 4/5 about x, no root
    rotation = robot.joints[0].placement.origin.matrix[:3, :3]
    assert rotation == sp.Matrix([[1, 0, 0], [0, three, -four], [0, four, three]])
    turned = robot_from_mjcf(_mjcf('<body quat="1 0 0 1"><joint/></body>'))
    assert turned.joints[0].placement.origin.rpy == (0, 0, sp.pi / 2)
    assert robot_from_mjcf(_mjcf('<body quat="2000 0 0 2000"><joint/></body>')) == turned  # no length: no metres


@pytest.mark.parametrize(("orientation", "expected"), [
    ('axisangle="0 0 1 90"', sp.Matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]])),
    ('xyaxes="0 1 0 -1 0 0"', sp.Matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]])),
    ('xyaxes="0 2 0 -3 7 0"', sp.Matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]])),  # y made orthogonal, both unit
    ('zaxis="1 0 0"', sp.Matrix([[0, 0, 1], [0, 1, 0], [-1, 0, 0]])),
    ('zaxis="0 0 -3"', sp.diag(1, -1, -1)),  # MuJoCo's half turn about x
    ('euler="90 0 90"', sp.Matrix([[0, -1, 0], [0, 0, -1], [1, 0, 0]])),  # x then the new z
])
def test_every_orientation_form(orientation, expected):
    robot = robot_from_mjcf(_mjcf(f'<body {orientation}><joint/></body>'))
    assert sp.simplify(robot.joints[0].placement.origin.matrix[:3, :3] - expected) == sp.zeros(3, 3)


def test_fixed_axis_euler_sequence():
    moving = robot_from_mjcf(_mjcf('<body euler="90 0 90"><joint/></body>', '<compiler eulerseq="xyz"/>'))
    fixed = robot_from_mjcf(_mjcf('<body euler="90 0 90"><joint/></body>', '<compiler eulerseq="XYZ"/>'))
    rz_rx = sp.Matrix([[0, 0, 1], [1, 0, 0], [0, 1, 0]])  # about x first, then about the fixed z
    assert fixed.joints[0].placement.origin.matrix[:3, :3] == rz_rx
    assert moving.joints[0].placement.origin.matrix[:3, :3] != rz_rx


def test_a_hinge_off_the_body_origin_turns_about_its_own_axis():
    robot = robot_from_mjcf(_mjcf('<body pos="1 0 0"><joint axis="0 0 1" pos="0.5 0 0"/>'
                                  '<site name="s" pos="0.5 0 0"/></body>'), tip_site="s")
    T = numeric_at(robot, forward_kinematics(robot, target="tool"), [1.3])
    np.testing.assert_allclose(T[:3, 3], [1.5, 0, 0], atol=1e-15)  # the site is on the axis: it stays put


def test_slide_joints_and_several_joints_in_one_body():
    robot = robot_from_mjcf(_mjcf('<body><joint name="x" type="slide" axis="2 0 0" ref="0.1"/>'
                                  '<joint name="y" type="slide" axis="0 1 0" range="0 0.3"/>'
                                  '<joint name="turn" axis="0 0 1" pos="0 0.1 0"/><site name="s" pos="0 0.1 0"/>'
                                  '</body>'),
                            tip_site="s")
    assert [joint.type.value for joint in robot.joints] == ["prismatic", "prismatic", "revolute"]
    assert robot.joints[1].limits == (0, sp.Rational(3, 10))
    T = numeric_at(robot, forward_kinematics(robot, target="tool"), [0.4, 0.2, 0.7])
    np.testing.assert_allclose(T[:3, 3], [0.4 - 0.1, 0.3, 0], atol=1e-15)  # qpos minus ref along the unit axis


def test_inertials_are_read_and_a_body_without_one_has_none():
    text = _mjcf('<body><joint/><inertial pos="0 0 0.1" mass="2" fullinertia="1 2 3 0.1 0 0"/>'
                 '<body pos="1 0 0"><joint/></body></body>')
    first, second = robot_from_mjcf(text).inertials
    assert first.mass == 2 and first.com == (0, 0, sp.Rational(1, 10)) and second is None
    assert first.inertia == sp.Matrix([[1, sp.Rational(1, 10), 0], [sp.Rational(1, 10), 2, 0], [0, 0, 3]])
    # MuJoCo ignores <inertial> when told to take the inertia from the geoms, which symjac does not read
    from_geoms = robot_from_mjcf(text.replace('model="t">', 'model="t"><compiler inertiafromgeom="true"/>'))
    assert all(inertial is None for inertial in from_geoms.inertials)


def test_bad_inertial_data_names_the_body():
    """Refused in one line naming the MJCF body (a negative mass); kept with a warning where no rigid body has it."""
    from symjac.errors import InertialWarning

    body = '<body name="arm"><joint/><inertial pos="0 0 0" mass="{m}" diaginertia="{d}"/></body>'
    with pytest.raises(RobotFileError, match=r"link arm inertial.*the mass -2 is negative"):
        robot_from_mjcf(_mjcf(body.format(m=-2, d="1 1 1")))
    with pytest.warns(InertialWarning, match=r"link arm: the principal moments 1, 1, 3 break the triangle"):
        assert robot_from_mjcf(_mjcf(body.format(m=2, d="1 1 3"))).inertials[0].mass == 2


def test_fixture_classes_includes_and_coupling():
    robot = load_robot(DATA / "classes.xml", tip_site="fingertip")
    assert [joint.name for joint in robot.joints] == ["a1", "a2", "a3", "a4", "a5"]
    assert [joint.limits for joint in robot.joints] == [(-sp.Rational(5, 2), sp.Rational(5, 2)), (-3, 3), None,
                                                        (-1, 1), (-1, 1)]
    assert [joint.placement.axis for joint in robot.joints] == [(0, 1, 0), (1, 0, 0), (0, 1, 0), (0, 1, 1), (1, 0, 0)]
    theta4, theta5 = robot.joint_variables[3:]
    # MuJoCo's q5 - r5 = 0.1 - 0.5 (q4 - r4) with r4 = 0.2 (class finger) and r5 = -0.3: q5 = -q4/2 - 1/10
    assert sp.expand(robot.joint_values[4]) == -theta4 / 2 - sp.Rational(1, 10)
    assert theta5 not in robot.q


def test_scene_with_a_free_object_beside_the_arm(tmp_path):
    scene = DATA / "arm6" / "scene.xml"
    with pytest.raises(RobotFileError, match=r"choose tip_link: .* box, wrist_3; or end it at a site with tip_site "
                                             r"\(flange\)$"):
        load_robot(scene)
    in_scene, alone = load_robot(scene, tip_link="wrist_3"), load_robot(DATA / "arm6" / "arm6.xml")
    assert (in_scene.name, alone.name) == ("arm6_scene", "arm6")  # the model's name, not the included file's
    assert (in_scene.joints, in_scene.tool, in_scene.inertials) == (alone.joints, alone.tool, alone.inertials)
    with pytest.raises(RobotFileError, match=r"field 'joint box_free': free joint 'box_free' \(body box\): a free "
                                             r"joint lets the body float: choose a base_link at or below this body"):
        load_robot(scene, tip_link="box")
    assert mjcf_model(scene.read_bytes(), str(scene), scene.parent).refused.keys() == {"box_free"}


def test_the_command_line_reads_mjcf_with_a_tip_site(capsys):
    arm = str(DATA / "arm6" / "scene.xml")
    assert main(["jacobian", arm, "--tip-site", "flange", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["shape"] == [6, 6]
    assert main(["fk", arm, "--tip-site", "nowhere"]) != 0
    assert capsys.readouterr().err.strip() == f"symjac: error: {arm}: site 'nowhere' is not a site of this model " \
                                              f"(sites: flange)"
    assert main(["fk", "puma560", "--tip-site", "flange"]) != 0
    assert capsys.readouterr().err.strip() == ("symjac: error: puma560.toml: --tip-site applies to MJCF files only, "
                                               "not to a TOML robot file")
    assert main(["fk", arm, "--tip-site", "flange", "--tip-link", "wrist_3"]) != 0
    assert "give --tip-link or --tip-site, not both" in capsys.readouterr().err


# --- refusals and hostile input: one line naming file and element -----------------------------------------------

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
<!ENTITY lol9 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">]>
<mujoco model="&lol9;"><worldbody/></mujoco>"""

REFUSED = {
    "billion laughs": (BILLION_LAUGHS, "entity declarations"),
    "external entity": ('<!DOCTYPE m [<!ENTITY s SYSTEM "file:///etc/passwd">]><mujoco model="&s;"/>', "DOCTYPE"),
    "not xml": ("<mujoco><worldbody>", "invalid XML"),
    "utf-16": ('<?xml version="1.0" encoding="UTF-16"?><mujoco/>', "only UTF-8"),
    "nan": (TWO.replace('pos="0.4 0 0"', 'pos="nan 0 0"'), r"body l2 in body l1 pos'?: expected a finite number"),
    "inf": (TWO.replace('range="-90 90"', 'range="-inf 90"'), "joint j1 range'?: expected a finite number"),
    "huge length": (TWO.replace('pos="0.4 0 0"', 'pos="4e9 0 0"'), "larger than 1000 m"),
    "huge angle": (TWO.replace('range="-90 90"', 'range="-9e8 90"'), "too large an angle in degrees"),
    "long number": (TWO.replace('pos="0.4 0 0"', f'pos="{"1" * 500} 0 0"'), "number too long"),
    "two numbers": (TWO.replace('pos="0.4 0 0"', 'pos="0.4 0"'), "expected 3 numbers"),
    "two orientations": (TWO.replace('pos="0.4 0 0"', 'pos="0.4 0 0" quat="1 0 0 0" euler="0 0 0"'),
                         r"more than one orientation given \(quat, euler\)"),
    "zero quaternion": (TWO.replace('pos="0.4 0 0"', 'quat="0 0 0 0"'), "quaternion must not be zero"),
    "huge quaternion": (TWO.replace('pos="0.4 0 0"', 'quat="1e12 0 0 0"'), r"quat'?: 1e\+12 is larger than 1e\+09"),
    "zero axis": (TWO.replace('axis="0 1 0"', 'axis="0 0 0"'), "joint j2 axis'?: the axis must not be the zero"),
    "ball": (TWO.replace('<joint name="j2" axis="0 1 0"/>', '<joint name="j2" type="ball"/>'),
             r"ball joint 'j2' \(body l2\): a ball joint turns about three axes"),
    "unknown type": (TWO.replace('<joint name="j2"', '<joint name="j2" type="spherical"'), "unknown joint type"),
    "unknown class": (TWO.replace('<joint name="j2"', '<joint name="j2" class="nope"'), "class 'nope' is not defined"),
    "unknown childclass": (TWO.replace('<body name="l2"', '<body name="l2" childclass="nope"'), "'nope' is not def"),
    "reversed range": (TWO.replace('range="-90 90"', 'range="90 -90"'), "lower < upper"),
    "limited without autolimits": (TWO.replace('model="t">', 'model="t"><compiler autolimits="false"/>'),
                                   "needs <compiler autolimits"),
    "bad unit": (TWO.replace('<mujoco model="t">', '<mujoco model="t"><compiler angle="grad"/>'), "'degree' or"),
    "bad eulerseq": (TWO.replace('<mujoco model="t">', '<mujoco model="t"><compiler eulerseq="xyw"/>'), "eulerseq"),
    "joint in worldbody": (_mjcf('<joint name="j"/>'), "joints belong in bodies"),
    "replicate": (_mjcf('<replicate count="3"><body><joint/></body></replicate>'), "<replicate> is not read"),
    "fullinertia turned": (_mjcf('<body><joint/><inertial mass="1" quat="0 1 0 0" fullinertia="1 1 1 0 0 0"/></body>'),
                           "fullinertia takes no orientation"),
    "nonlinear coupling": (TWO, "polycoef is not linear"),
    "locked joint": (TWO, r"joint 'j2' is locked \(no joint2\)"),
    "include without a folder": (_mjcf("", '<include file="x.xml"/>'), "needs the model's folder"),
}
EQUALITIES = {"nonlinear coupling": '<equality><joint joint1="j2" joint2="j1" polycoef="0 1 0.5 0 0"/></equality>',
              "locked joint": '<equality><joint joint1="j2"/></equality>'}


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_refused_input_is_one_line_naming_the_file(case):
    text, message = REFUSED[case]
    text = text.replace("</mujoco>", EQUALITIES.get(case, "") + "</mujoco>")
    start = time.perf_counter()
    with pytest.raises(RobotFileError, match=message) as info:
        robot_from_mjcf(text, source="arm.xml", tip_link="l2" if "l2" in text else None)
    assert time.perf_counter() - start < 2
    assert str(info.value).startswith("arm.xml") and "\n" not in str(info.value)


def test_includes_outside_the_folder_loops_and_repeats_are_refused(tmp_path):
    _write(tmp_path, "secret.xml", "<mujoco><worldbody/></mujoco>")
    model = tmp_path / "model"
    cases = {
        PARENT + "secret.xml": "outside the model's folder",
        str(tmp_path / "secret.xml"): "outside the model's folder",
        "link.xml": "outside the model's folder",  # a symbolic link leading out
        "loop.xml": "included twice",
        "missing.xml": "does not exist",
        "broken.xml": r"\(included broken.xml\): invalid XML",
        "robot.xml": "root element must be <mujoco>, got <robot>",
        "x" * 5000 + ".xml": "cannot read included file 'x{200}': File name too long",  # found by the fuzzer
    }
    _write(model, "loop.xml", '<mujoco><include file="loop.xml"/></mujoco>')
    _write(model, "broken.xml", "<mujoco>")
    _write(model, "robot.xml", "<robot/>")
    (model / "link.xml").symlink_to(tmp_path / "secret.xml")
    for name, message in cases.items():
        path = _write(model, "arm.xml", _mjcf("", f'<include file="{name}"/>'))
        with pytest.raises(RobotFileError, match=message) as info:
            load_robot(path)
        assert str(info.value).startswith(str(path)), name


def test_include_limits(tmp_path):
    many = "".join(f'<include file="p{i}.xml"/>' for i in range(MAX_MJCF_INCLUDES + 1))
    for i in range(MAX_MJCF_INCLUDES + 1):
        _write(tmp_path, f"p{i}.xml", "<mujoco/>")
    with pytest.raises(RobotFileError, match=f"more than {MAX_MJCF_INCLUDES} <include> elements"):
        load_robot(_write(tmp_path, "arm.xml", _mjcf("", many)))
    _write(tmp_path, "big.xml", "<mujoco>" + " " * (MAX_MJCF_BYTES // 2 + 10) + "</mujoco>")
    _write(tmp_path, "big2.xml", "<mujoco>" + " " * (MAX_MJCF_BYTES // 2 + 10) + "</mujoco>")
    with pytest.raises(RobotFileError, match=f"included files hold more than {MAX_MJCF_BYTES} bytes"):
        load_robot(_write(tmp_path, "arm.xml", _mjcf("", '<include file="big.xml"/><include file="big2.xml"/>')))
    huge = _write(tmp_path, "huge.xml", "<mujoco>" + " " * MAX_MJCF_BYTES + "</mujoco>")
    with pytest.raises(RobotFileError, match=f"^{huge}: file larger than {MAX_MJCF_BYTES} bytes, the limit that"):
        load_robot(huge)


def test_tip_choices_are_checked():
    with pytest.raises(RobotFileError, match="give tip_link or tip_site, not both"):
        robot_from_mjcf(TWO, tip_link="l2", tip_site="tip")
    with pytest.raises(RobotFileError, match=r"site 'hand' is not a site of this model \(sites: tip\)"):
        robot_from_mjcf(TWO, tip_site="hand")
    with pytest.raises(RobotFileError, match="tip_link 'hand' is neither a body nor a site of this model"):
        robot_from_mjcf(TWO, tip_link="hand")


def test_a_gripper_coupled_beside_the_chain_does_not_stop_the_arm():
    # Menagerie's Panda couples its fingers with a joint equality (default polycoef "0 1 0 0 0") on two branches
    gripper = _mjcf('<body name="arm"><joint name="j1"/><body name="hand" pos="0 0 0.1">'
                    '<body name="left"><joint name="f1" type="slide" axis="0 1 0" range="0 0.04"/></body>'
                    '<body name="right" quat="0 0 0 1"><joint name="f2" type="slide" axis="0 1 0" range="0 0.04"/>'
                    '</body></body></body>', tail='<equality><joint joint1="f1" joint2="f2"/></equality>')
    assert [joint.name for joint in robot_from_mjcf(gripper, tip_link="hand").joints] == ["j1"]
    assert [joint.name for joint in robot_from_mjcf(gripper, tip_link="right").joints] == ["j1", "f2"]
    # the follower on the chain, its leader beside it: the leader is a coordinate of its own, as for URDF
    left = robot_from_mjcf(gripper, tip_link="left")
    assert [str(q) for q in left.q] == ["theta1", "f2"] and [joint.name for joint in left.joints] == ["j1", "f1"]


def test_a_tip_that_is_neither_a_body_nor_a_site_names_both_lists(cli, tmp_path):
    path = tmp_path / "bl.xml"
    path.write_text('<mujoco><worldbody><body name="a"><joint name="j"/><site name="s"/></body></worldbody>'
                    '</mujoco>', encoding="utf-8")
    expected = "'nosuch' is neither a body nor a site of this model (bodies: a, world; sites: s)"
    with pytest.raises(RobotFileError, match=re.escape(f"tip_link {expected}")):
        robot_from_mjcf(path.read_text(), source=str(path), tip_link="nosuch")
    assert cli.one_line_error("fk", str(path), "--tip-link", "nosuch") == \
        f"symjac: error: {path}: --tip-link {expected}"
