"""Robot readers as plug-ins: the format is chosen by content, unknown files get one line, a new reader plugs in.

Also the shared kinematic tree's inertial data: each chain link's URDF ``<inertial>`` (fixed bodies folded in) lands in
symjac's frame {i} so that its centre of mass and tensor, carried to frame {0} by symjac's ``T_0_i``, agree with the
same bodies placed in {0} by composing the URDF origins by hand in NumPy.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symjac.analysis.dynamics import gravity_torques
from symjac.cli.main import main
from symjac.errors import ArgumentError, ImpossibleInertiaError, InertialWarning, RobotFileError
from symjac.kinematics.chain import forward_kinematics
from symjac.kinematics.numeric import numeric_at
from symjac.model import readers
from symjac.model.io import load_robot
from symjac.model.readers import LinksNotApplicableError, Reader, reader_for, xml_root
from symjac.model.readers.tree import (
    JointLimits,
    KinematicTree,
    TreeJoint,
    TreeJointType,
    TreeLink,
    robot_from_tree,
)
from symjac.model.readers.urdf import MAX_URDF_BYTES, tree_from_urdf
from symjac.model.urdf import robot_from_urdf

ARM = """<?xml version="1.0"?>
<!-- a two-joint arm -->
<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="2.5" effort="40"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/><axis xyz="0 -1 0"/><limit velocity="3"/></joint>
</robot>
"""

TOML = """name = "planar"
convention = "standard"

[[joints]]
type = "revolute"
alpha = 0
a = 1
d = 0
"""


def _write(tmp_path: Path, name: str, content: str | bytes) -> Path:
    path = tmp_path / name
    path.write_bytes(content.encode("utf-8") if isinstance(content, str) else content)
    return path


# --- the format is chosen by content ------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["arm.urdf", "arm.xml", "arm.toml", "arm.txt", "arm"])
def test_urdf_content_is_read_as_urdf_whatever_the_name(tmp_path, name):
    robot = load_robot(_write(tmp_path, name, ARM))
    assert [joint.name for joint in robot.joints] == ["j1", "j2"]


@pytest.mark.parametrize("name", ["planar.toml", "planar.urdf", "planar.xml", "planar"])
def test_toml_content_is_read_as_toml_whatever_the_name(tmp_path, name):
    robot = load_robot(_write(tmp_path, name, "# a comment first\n\n" + TOML))
    assert robot.name == "planar" and robot.n_joints == 1


def test_a_urdf_file_named_like_a_catalog_robot_is_the_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, "puma560", ARM)
    assert load_robot("puma560").name == "arm"


UNKNOWN = {
    "collada": ("arm.xml", '<?xml version="1.0"?>\n<!-- a COLLADA scene -->\n<COLLADA version="1.4.1"/>',
                "root element <COLLADA>"),
    "sdf with a doctype": ("arm.sdf", '<!DOCTYPE sdf [<!ENTITY x "y">]><sdf version="1.6"/>', "root element <sdf>"),
    "binary": ("arm.bin", b"\x7fELF\x00\x01\x02", "binary data"),
    "text": ("arm.txt", "hello: this is no robot\n", "text that is neither TOML nor XML"),
    "empty": ("arm", " \n", "an empty file"),
    "latin-1": ("arm.dat", 'robot = "\xe9"'.encode("latin-1") + b"\xff" * 10, "binary data"),
}


@pytest.mark.parametrize("case", sorted(UNKNOWN))
def test_a_file_no_reader_claims_is_one_line_naming_the_formats(tmp_path, case):
    name, content, what = UNKNOWN[case]
    path = _write(tmp_path, name, content)
    with pytest.raises(RobotFileError) as info:
        load_robot(path)
    assert str(info.value) == f"{path}: not a robot file symjac reads ({what}); formats: MJCF, TOML robot file, URDF"


def test_the_command_line_says_it_in_one_line(tmp_path, capsys):
    path = _write(tmp_path, "arm.xml", '<sdf version="1.9"/>')
    assert main(["fk", str(path)]) != 0
    err = capsys.readouterr().err
    assert err.strip().splitlines() == [
        f"symjac: error: {path}: not a robot file symjac reads (root element <sdf>); formats: MJCF, TOML robot file, "
        "URDF"]


def test_a_suffix_sends_what_no_reader_claims_to_its_reader(tmp_path):
    # the reader of the suffix says what is wrong, in its own words
    with pytest.raises(RobotFileError, match="root element must be <robot>, got <sdf>"):
        load_robot(_write(tmp_path, "arm.urdf", "<sdf/>"))
    with pytest.raises(RobotFileError, match="invalid TOML"):
        load_robot(_write(tmp_path, "arm.toml", "robot: arm\n"))
    with pytest.raises(RobotFileError, match="invalid XML"):
        load_robot(_write(tmp_path, "empty.urdf", ""))
    with pytest.raises(RobotFileError, match="the file is empty"):
        load_robot(_write(tmp_path, "empty.toml", ""))


def test_xml_root_skips_the_prolog_and_stays_fast_on_hostile_heads():
    assert xml_root(b'\xef\xbb\xbf <?xml version="1.0"?><!-- <mujoco> --><!DOCTYPE robot [<!ENTITY a "b">]>\n'
                    b"<robot name='a'>") == "robot"
    assert xml_root(b"<xacro:macro name='m'/>") == "xacro:macro"
    assert xml_root(b"name = 1") is None and xml_root(b"") is None
    hostile = [b"<!DOCTYPE " + b"[" * 60_000, b"<!--" + b"-" * 60_000, b"<?" + b"?" * 60_000,
               b"<!DOCTYPE a [" + b"]" * 60_000]
    start = time.perf_counter()
    for head in hostile:
        xml_root(head)
        with pytest.raises(RobotFileError, match="not a robot file"):
            reader_for(head, "x")
    assert time.perf_counter() - start < 1


def test_the_size_limit_is_the_readers_and_is_checked_before_reading(tmp_path):
    [urdf] = [reader for reader in readers.readers() if reader.name == "URDF"]
    assert urdf.max_bytes == MAX_URDF_BYTES == 5_000_000
    path = _write(tmp_path, "big.xml", "<robot name='a'>" + " " * MAX_URDF_BYTES + "</robot>")
    with pytest.raises(RobotFileError, match=f"^{path}: file larger than 5000000 bytes, the limit that keeps "
                                             f"runaway files out .*: raise it with max_bytes "
                                             r"\(--max-bytes on the command line\) to read it$"):
        load_robot(path)
    # raised, the same file is read (and refused for what it holds, not for its size)
    with pytest.raises(RobotFileError, match="the robot has no links"):
        load_robot(path, max_bytes=2 * MAX_URDF_BYTES)
    # lowered, a small file is refused, by the whole-file check and by the parser's own
    small = _write(tmp_path, "small.urdf", "<robot name='a'><link name='b'/></robot>")
    with pytest.raises(RobotFileError, match="file larger than 10 bytes"):
        load_robot(small, max_bytes=10)
    with pytest.raises(RobotFileError, match="file larger than 10 bytes"):
        robot_from_urdf(small.read_text(), max_bytes=10)


@pytest.mark.parametrize("value", [0, -1, 2.5, True, "big"])
def test_a_size_limit_that_is_no_positive_whole_number_is_refused(value, tmp_path):
    with pytest.raises(ArgumentError, match=f"max_bytes must be a positive whole number of bytes, got {value!r}"):
        load_robot(_write(tmp_path, "a.urdf", "<robot name='a'/>"), max_bytes=value)


def test_the_command_line_raises_the_size_limit(tmp_path, capsys):
    path = _write(tmp_path, "big.urdf", ARM.replace("</robot>", " " * MAX_URDF_BYTES + "</robot>"))
    assert main(["fk", str(path), "--format", "json"]) != 0
    assert "raise it with max_bytes (--max-bytes on the command line)" in capsys.readouterr().err
    assert main(["fk", str(path), "--format", "json", "--max-bytes", str(2 * MAX_URDF_BYTES)]) == 0


# --- base_link and tip_link: a typed error, for every tree reader ---------------------------------------------------

def test_links_for_a_robot_that_is_no_tree_are_a_typed_error(tmp_path):
    with pytest.raises(LinksNotApplicableError, match="tip_link apply to URDF and MJCF files only") as info:
        load_robot(_write(tmp_path, "planar.toml", TOML), tip_link="x")
    assert info.value.formats == "URDF and MJCF"
    with pytest.raises(LinksNotApplicableError):
        load_robot("puma560", base_link="x")


# --- a throwaway reader plugs in --------------------------------------------------------------------------------

def _read_chain_text(content: bytes, source: str, *, base_link=None, tip_link=None):
    """``CHAIN name`` then one joint per line: ``name type parent child x y z ax ay az``."""
    lines = content.decode("utf-8").splitlines()
    joints, links = [], ["base"]
    for line in lines[1:]:
        name, kind, parent, child, *numbers = line.split()
        x, y, z, ax, ay, az = (float(v) for v in numbers)
        from symjac.model.expressions import exact_number
        from symjac.model.robot import FixedTransform

        joints.append(TreeJoint(name, TreeJointType(kind), parent, child,
                                FixedTransform(xyz=tuple(exact_number(v) for v in (x, y, z))),
                                tuple(exact_number(v) for v in (ax, ay, az))))
        links.append(child)
    tree = KinematicTree(lines[0].split()[1], tuple(TreeLink(name) for name in links), tuple(joints))
    return robot_from_tree(tree, source, base_link=base_link, tip_link=tip_link)


CHAIN = Reader("CHAIN", lambda head: head.startswith(b"CHAIN "), _read_chain_text, tree=True, suffixes=(".chain",))
CHAIN_TEXT = """CHAIN arm
j1 revolute base l1 0 0 0.5 0 0 1
j2 revolute l1 l2 0.4 0 0 0 1 0
f1 fixed l2 flange 0.3 0 0 1 0 0
f2 fixed l1 camera 0 0.1 0 1 0 0
"""


@pytest.fixture
def chain_reader():
    readers.register(CHAIN)
    yield CHAIN
    readers.unregister(CHAIN.name)


def test_a_new_reader_works_end_to_end(chain_reader, tmp_path, capsys):
    path = _write(tmp_path, "arm.txt", CHAIN_TEXT)
    robot = load_robot(path, tip_link="flange")
    assert [joint.name for joint in robot.joints] == ["j1", "j2"] and robot.source == str(path)
    urdf = robot_from_urdf("""<robot name="arm"><link name="base"/><link name="l1"/><link name="l2"/>
        <link name="flange"/><link name="camera"/>
        <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5"/>
          <axis xyz="0 0 1"/></joint>
        <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.4 0 0"/>
          <axis xyz="0 1 0"/></joint>
        <joint name="f1" type="fixed"><parent link="l2"/><child link="flange"/><origin xyz="0.3 0 0"/></joint>
        <joint name="f2" type="fixed"><parent link="l1"/><child link="camera"/><origin xyz="0 0.1 0"/></joint>
        </robot>""", source=str(path), tip_link="flange")
    assert robot == urdf  # the same tree gives the same robot, whichever reader read it
    # the shared tree logic speaks for the new reader too
    with pytest.raises(RobotFileError, match="choose tip_link: the links without children below 'base' are "
                                             "camera, flange"):
        load_robot(path)
    assert load_robot(path, base_link="l1", tip_link="flange").n_joints == 1
    # and the command line's link options apply to it
    assert main(["fk", str(path), "--tip-link", "flange", "--format", "json"]) == 0
    assert '"entries"' in capsys.readouterr().out
    with pytest.raises(LinksNotApplicableError, match="apply to URDF, MJCF and CHAIN files only"):
        load_robot(_write(tmp_path, "planar.toml", TOML), tip_link="flange")
    assert main(["fk", "planar2r", "--base-link", "l1"]) != 0
    assert capsys.readouterr().err.strip() == ("symjac: error: --base-link applies to URDF, MJCF and CHAIN files only; "
                                               "'planar2r' is not one")


def test_without_its_reader_the_file_is_refused(tmp_path):
    path = _write(tmp_path, "arm.txt", CHAIN_TEXT)
    with pytest.raises(RobotFileError, match="text that is neither TOML nor XML"):
        load_robot(path)


# --- what the tree keeps: names and limits ------------------------------------------------------------------------

def test_the_tree_keeps_names_and_every_limit():
    tree = tree_from_urdf(ARM, "arm.urdf")
    j1, j2 = tree.joints
    assert (j1.name, j1.type, j2.type) == ("j1", TreeJointType.REVOLUTE, TreeJointType.CONTINUOUS)
    assert j1.limits == JointLimits(-1, 1, sp.Rational(5, 2), 40)
    assert j2.limits == JointLimits(None, None, 3, None)  # a continuous joint has no position limits
    robot = robot_from_urdf(ARM)
    assert [(joint.name, joint.limits) for joint in robot.joints] == [("j1", (-1, 1)), ("j2", None)]


# --- inertial data in symjac's frames -----------------------------------------------------------------------------

INERTIAL = """<robot name="massive">
  <link name="base"><inertial><mass value="9"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>
  <link name="l1"><inertial><origin xyz="0.01 0.02 0.15" rpy="0.3 -0.2 0.1"/><mass value="2.5"/>
    <inertia ixx="0.03" ixy="0.001" ixz="-0.002" iyy="0.025" iyz="0.003" izz="0.01"/></inertial></link>
  <link name="mid"/>
  <link name="l2"><inertial><origin xyz="0.2 -0.01 0.03" rpy="0 0.4 0"/><mass value="1.5"/>
    <inertia ixx="0.002" iyy="0.02" izz="0.021" ixy="0.0005"/></inertial></link>
  <link name="sensor"><inertial><origin xyz="0.01 0 0.02"/><mass value="0.3"/>
    <inertia ixx="0.0001" iyy="0.0002" izz="0.00015"/></inertial></link>
  <link name="l3"><inertial><origin xyz="0 0.05 0.1"/><mass value="0.8"/>
    <inertia ixx="0.004" iyy="0.004" izz="0.001"/></inertial></link>
  <link name="tool"><inertial><mass value="0.2"/><inertia ixx="0.0002" iyy="0.0002" izz="0.0002"/></inertial></link>
  <link name="finger"><inertial><mass value="5"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.3" rpy="0 0 0.2"/>
    <axis xyz="0 0.6 0.8"/></joint>
  <joint name="fix" type="fixed"><parent link="l1"/><child link="mid"/><origin xyz="0.05 0 0.2" rpy="0.5 0 0"/></joint>
  <joint name="j2" type="revolute"><parent link="mid"/><child link="l2"/><origin xyz="0 0.1 0" rpy="0 0 -0.7"/>
    <axis xyz="1 0 0"/></joint>
  <joint name="mount" type="fixed"><parent link="l2"/><child link="sensor"/><origin xyz="0.1 0.05 0" rpy="0 1.2 0"/>
  </joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><origin xyz="0.3 0 0" rpy="0.1 0.2 0.3"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.4"/></joint>
  <joint name="flange" type="fixed"><parent link="l3"/><child link="tool"/><origin xyz="0 0 0.12"/></joint>
  <joint name="grip" type="prismatic"><parent link="l3"/><child link="finger"/><axis xyz="1 0 0"/></joint>
</robot>"""


def _rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp_, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    Ry = np.array([[cp, 0, sp_], [0, 1, 0], [-sp_, 0, cp]])
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return Rz @ Ry @ Rx


def _pose(xyz=(0, 0, 0), rpy=(0, 0, 0), R=None) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = _rpy(*rpy) if R is None else R
    T[:3, 3] = xyz
    return T


def _motion(axis, value: float, prismatic: bool) -> np.ndarray:
    """Rodrigues' rotation about (or a translation along) a unit axis, independent of symjac's alignment."""
    u = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    if prismatic:
        return _pose(u * value)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return _pose(R=np.eye(3) + np.sin(value) * K + (1 - np.cos(value)) * K @ K)


def _bodies_in_base(q: np.ndarray) -> dict[int, list[tuple[float, np.ndarray, np.ndarray]]]:
    """For chain links 1..3, (mass, centre in {0}, tensor about the centre in {0}) of each body, from the URDF."""
    T_l1 = _pose((0, 0, 0.3), (0, 0, 0.2)) @ _motion((0, 0.6, 0.8), q[0], False)
    T_mid = T_l1 @ _pose((0.05, 0, 0.2), (0.5, 0, 0))
    T_l2 = T_mid @ _pose((0, 0.1, 0), (0, 0, -0.7)) @ _motion((1, 0, 0), q[1], False)
    T_sensor = T_l2 @ _pose((0.1, 0.05, 0), (0, 1.2, 0))
    T_l3 = T_l2 @ _pose((0.3, 0, 0), (0.1, 0.2, 0.3)) @ _motion((0, -1, 0), q[2], True)
    T_tool = T_l3 @ _pose((0, 0, 0.12))

    def body(T_link, xyz, rpy, mass, tensor):
        T = T_link @ _pose(xyz, rpy)
        return mass, T[:3, 3], T[:3, :3] @ np.asarray(tensor) @ T[:3, :3].T

    I1 = [[0.03, 0.001, -0.002], [0.001, 0.025, 0.003], [-0.002, 0.003, 0.01]]
    I2 = [[0.002, 0.0005, 0], [0.0005, 0.02, 0], [0, 0, 0.021]]
    return {1: [body(T_l1, (0.01, 0.02, 0.15), (0.3, -0.2, 0.1), 2.5, I1)],
            2: [body(T_l2, (0.2, -0.01, 0.03), (0, 0.4, 0), 1.5, I2),
                body(T_sensor, (0.01, 0, 0.02), (0, 0, 0), 0.3, np.diag([1e-4, 2e-4, 1.5e-4]))],
            3: [body(T_l3, (0, 0.05, 0.1), (0, 0, 0), 0.8, np.diag([4e-3, 4e-3, 1e-3])),
                body(T_tool, (0, 0, 0), (0, 0, 0), 0.2, np.diag([2e-4] * 3)),
                body(T_l3, (0, 0, 0), (0, 0, 0), 5, np.eye(3))]}  # the finger, off the chain, held at zero


def test_urdf_inertials_land_in_symjacs_link_frames():
    robot = robot_from_urdf(INERTIAL, tip_link="tool")
    assert robot.n_joints == 3 and all(inertial is not None for inertial in robot.inertials)
    # plain rational numbers (a tensor turned by a generic angle has no textbook form): cheap and writable
    assert all(v.is_Rational for inertial in robot.inertials for v in (inertial.mass, *inertial.com, *inertial.inertia))
    rng = np.random.default_rng(40)
    for q in rng.uniform(-1, 1, size=(3, 3)):
        expected = _bodies_in_base(q)
        for i, inertial in enumerate(robot.inertials, start=1):
            T_0_i = numeric_at(robot, forward_kinematics(robot, 0, i), list(q))
            R, p = T_0_i[:3, :3], T_0_i[:3, 3]
            com = np.array(inertial.com, dtype=float)
            inertia = np.array(inertial.inertia, dtype=float)
            masses = np.array([m for m, _, _ in expected[i]])
            centre = sum(m * c for m, c, _ in expected[i]) / masses.sum()
            # the parallel-axis theorem, written out here for the fixed bodies folded into a link
            about_centre = sum(tensor + m * (np.dot(c - centre, c - centre) * np.eye(3)
                                             - np.outer(c - centre, c - centre)) for m, c, tensor in expected[i])
            assert float(inertial.mass) == pytest.approx(masses.sum(), abs=1e-12)
            np.testing.assert_allclose(R @ com + p, centre, atol=1e-12)
            np.testing.assert_allclose(R @ inertia @ R.T, about_centre, atol=1e-12)


def test_links_without_inertial_data_have_none_and_bad_data_names_the_link():
    assert robot_from_urdf(ARM).inertials == (None, None)
    bad = INERTIAL.replace('<mass value="1.5"/>', '<mass value="-1.5"/>')
    with pytest.raises(RobotFileError, match="field 'link l2 inertial': the mass -3/2 is negative"):
        robot_from_urdf(bad, tip_link="tool")
    triangle = INERTIAL.replace('ixx="0.004" iyy="0.004" izz="0.001"', 'ixx="0.001" iyy="0.001" izz="0.004"')
    with pytest.warns(InertialWarning, match=r"link l3: .*triangle inequality.*\(kept as given; the dynamics refuse"):
        kept = robot_from_urdf(triangle, tip_link="tool")  # CAD exports round into this: the file still reads
    assert kept.inertials[2] is not None
    no_finger = triangle.replace('<mass value="5"/><inertia ixx="1" iyy="1" izz="1"/>',
                                 '<mass value="0"/><inertia ixx="0" iyy="0" izz="0"/>')  # else link 3 is a body
    with pytest.warns(InertialWarning):
        refused = robot_from_urdf(no_finger, tip_link="tool")
    with pytest.raises(ImpossibleInertiaError, match=r"^massive: link 3 \(moved by joint j3\): .*triangle inequality"):
        gravity_torques(refused)
    # the base's data is not used, so not checked; a finger behind a moving joint off the chain rides with link 3
    assert robot_from_urdf(INERTIAL.replace('<mass value="9"/>', '<mass value="-9"/>'), tip_link="tool").n_joints == 3
    with pytest.raises(RobotFileError, match=r"link finger inertial.*negative"):
        robot_from_urdf(INERTIAL.replace('<mass value="5"/>', '<mass value="-5"/>'), tip_link="tool")
    with pytest.raises(RobotFileError, match=r"link l1 inertial.*needs <mass"):
        robot_from_urdf(INERTIAL.replace('<mass value="2.5"/>', ""), tip_link="tool")


def test_the_command_line_says_a_kept_inertial_in_one_warning_line(tmp_path, capsys):
    path = tmp_path / "arm.urdf"
    path.write_text(INERTIAL.replace('ixx="0.004" iyy="0.004" izz="0.001"', 'ixx="0.001" iyy="0.001" izz="0.004"'),
                    encoding="utf-8")
    assert main(["fk", str(path), "--tip-link", "tool"]) == 0
    out, err = capsys.readouterr()
    assert out.strip()  # the pose is printed: a kept inertial does not stop the kinematics
    assert err.count("\n") == 1 and err.startswith("symjac: warning: ")
    assert "link l3: the principal moments" in err and err.rstrip().endswith("(kept as given; the dynamics refuse it)")


def test_urdf_inertials_agree_with_the_general_robot_file_frames():
    # a general robot file gives inertial data in the joint's child link frame, as URDF does: a single body's
    # centre is written back as the URDF gave it, and the file reads back to the same robot
    from symjac.model.io import robot_from_toml, robot_to_toml

    robot = robot_from_urdf(INERTIAL, tip_link="tool")
    text = robot_to_toml(robot)
    assert "com = [0.01, 0.02, 0.15]" in text
    assert robot_from_toml(text) == robot


def test_a_toml_file_with_a_byte_order_mark_reads(tmp_path):
    plain, marked = tmp_path / "plain.toml", tmp_path / "marked.toml"
    plain.write_text(TOML, encoding="utf-8")
    marked.write_bytes(b"\xef\xbb\xbf" + TOML.encode("utf-8"))  # as some editors save UTF-8
    assert load_robot(marked) == load_robot(plain)


@pytest.mark.parametrize("kind", ["urdf", "mjcf"])
def test_a_tree_of_more_links_than_a_robot_has_is_refused_before_it_is_built(kind):
    n = readers.MAX_TREE_LINKS + 1
    if kind == "urdf":
        links = "".join(f'<link name="l{i}"/>' for i in range(n))
        text, read = f'<robot name="a">{links}</robot>', robot_from_urdf
    else:
        from symjac.model.readers.mjcf import robot_from_mjcf

        bodies = "".join(f'<body name="b{i}">' for i in range(n)) + '<joint name="j"/>' + "</body>" * n
        text, read = f"<mujoco><worldbody>{bodies}</worldbody></mujoco>", robot_from_mjcf
    start = time.perf_counter()
    with pytest.raises(RobotFileError, match=f"{n} links \\(bodies\\) is more than the 5000 a robot tree may have"):
        read(text)
    assert time.perf_counter() - start < 5  # refused before any exact arithmetic: a second even on a loaded machine


def test_a_deep_chain_is_checked_for_loops_in_time_that_grows_with_its_size():
    # the walk to the root stops at links known to reach it: 5000 nested fixed links, each walked once
    n = readers.MAX_TREE_LINKS - 1
    links = "".join(f'<link name="l{i}"/>' for i in range(n + 1))
    joints = "".join(f'<joint name="f{i}" type="fixed"><parent link="l{i}"/><child link="l{i + 1}"/></joint>'
                     for i in range(n))
    tree = tree_from_urdf(f'<robot name="a">{links}{joints}</robot>')
    with pytest.raises(RobotFileError, match="no revolute, continuous or prismatic joint"):
        robot_from_tree(tree, "deep.urdf")
