"""Names and limits travel: every target exposes the joint names, types and limits of q, and fills q from names.

The expected tables are read from the robot (its joints, the URDF's limits as written here) and the expected q from
a shuffled name-value list by a dictionary lookup in the test, independently of the generated helpers. The C and
C++ helpers are compiled with a small main; the Python-family modules are imported.
"""

from __future__ import annotations

import importlib.util
import math
import random
import shutil
import subprocess
import types
from pathlib import Path

import numpy as np
import pytest

from symjac import load_robot, robot_from_mapping
from symjac.codegen import CodegenError, ModuleRequest, describe, generate, render_files
from symjac.errors import RobotFileError
from symjac.model.io import robot_from_toml, robot_to_toml
from symjac.model.readers.urdf import robot_from_urdf

PYTHON_TARGETS = ["python", "numpy", "lambdify", "c", "jax", "casadi"]
EIGEN = Path("/usr/include/eigen3")

# Names as a URDF may write them: '/', '-', '.', ':'; a continuous joint (no limits), a prismatic joint, a fixed tip.
ODD_URDF = """<robot name="odd">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tip/frame"/>
  <joint name="arm/base-joint" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="slide.1" type="prismatic"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.2 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.4" effort="1" velocity="1"/></joint>
  <joint name="wrist:roll" type="continuous"><parent link="l2"/><child link="l3"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/></joint>
  <joint name="tool_mount" type="fixed"><parent link="l3"/><child link="tip/frame"/><origin xyz="0 0 0.05"/></joint>
</robot>"""

ODD = {"names": ("arm/base-joint", "slide.1", "wrist:roll"), "types": ("revolute", "prismatic", "continuous"),
       "lower": (-2.5, 0.0, -math.inf), "upper": (2.5, 0.4, math.inf), "tip": "tip/frame",
       "identifiers": ("arm_base_joint", "slide_1", "wrist_roll")}
GRIPPER = {"names": ("yaw", "pitch", "finger_joint"), "types": ("revolute", "revolute", "revolute"),
           "lower": (-math.pi, -math.pi / 2, 0.0), "upper": (math.pi, math.pi / 2, 0.8), "tip": "left_fingertip",
           "identifiers": ("yaw", "pitch", "finger_joint")}


def odd_robot():
    return robot_from_urdf(ODD_URDF, source="odd.urdf")


def _robot(which: str):
    return odd_robot() if which == "odd" else load_robot("gripper.urdf")


def _expected(which: str) -> dict:
    return ODD if which == "odd" else GRIPPER


def _shuffled(names: tuple[str, ...], seed: int) -> tuple[list[str], list[float], list[float]]:
    """A JointState-like list: the robot's joints and two others, shuffled; and q read off it by name."""
    generator = random.Random(seed)
    values = {name: generator.uniform(-1.0, 1.0) for name in (*names, "other_joint", "left_inner_finger_joint")}
    order = list(values)
    generator.shuffle(order)
    return order, [values[name] for name in order], [values[name] for name in names]


def _import(path: Path) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(f"names_{path.parent.name}_{path.stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_description_holds_names_types_limits_and_the_tip_as_the_urdf_writes_them():
    for which in ("odd", "gripper"):
        robot, expected = _robot(which), _expected(which)
        description = describe(ModuleRequest(robot, "c99"))
        entries = description.joint_entries
        assert tuple(e.name for e in entries) == expected["names"]
        assert tuple(e.type for e in entries) == expected["types"]
        assert tuple(e.identifier for e in entries) == expected["identifiers"]
        np.testing.assert_allclose([e.lower for e in entries], expected["lower"], rtol=1e-15)
        np.testing.assert_allclose([e.upper for e in entries], expected["upper"], rtol=1e-15)
        assert description.tip_frame == expected["tip"]
    # the gripper's mimic joint follows finger_joint: it is a joint, not a coordinate
    assert [joint.name for joint in load_robot("gripper.urdf").joints][-1] == "left_inner_finger_joint"


def test_a_robot_file_without_names_names_q_by_its_symbols_and_its_end():
    description = describe(ModuleRequest(load_robot("stanford"), "python"))
    assert description.joint_names == tuple(s.name for s in load_robot("stanford").q)
    assert [e.type for e in description.joint_entries] == [t.value for t in load_robot("stanford").coordinate_types]
    assert description.tip_frame in ("tool", "flange")


@pytest.mark.parametrize("target", PYTHON_TARGETS)
@pytest.mark.parametrize("which", ["odd", "gripper"])
def test_python_modules_expose_the_tables_and_fill_q_from_a_shuffled_name_list(tmp_path, target, which):
    if target in ("jax", "casadi"):
        pytest.importorskip(target)
    robot, expected = _robot(which), _expected(which)
    path = tmp_path / f"{robot.name}.py"
    path.write_text(generate(robot, target))
    module = _import(path)
    assert expected["names"] == module.JOINT_NAMES
    assert expected["types"] == module.JOINT_TYPES
    np.testing.assert_allclose(module.LOWER, expected["lower"], rtol=1e-15)
    np.testing.assert_allclose(module.UPPER, expected["upper"], rtol=1e-15)
    assert expected["tip"] == module.TIP_FRAME
    assert {"JOINT_NAMES", "JOINT_TYPES", "LOWER", "UPPER", "TIP_FRAME", "coordinates"} <= set(module.__all__)
    rtol = 1e-7 if target == "jax" else 0.0  # jax.numpy computes in float32 unless x64 is enabled
    for seed in range(3):
        names, positions, q = _shuffled(expected["names"], seed)
        np.testing.assert_allclose(np.asarray(module.coordinates(names, positions), dtype=float).ravel(), q,
                                   rtol=rtol, atol=0)
        mapping = {name: value for name, value in zip(names, positions, strict=True) if name in expected["names"]}
        np.testing.assert_allclose(np.asarray(module.coordinates(mapping), dtype=float).ravel(), q, rtol=rtol,
                                   atol=0)
    first, *rest = expected["names"]
    with pytest.raises(ValueError, match=f"no value for joint\\(s\\) {first}$"):
        module.coordinates(rest, [0.0] * len(rest))
    with pytest.raises(ValueError, match="unknown joint name\\(s\\) 'elbow'"):
        module.coordinates({**dict.fromkeys(expected["names"], 0.0), "elbow": 1.0})
    with pytest.raises(ValueError, match=f"joint name '{first}' is given twice"):
        module.coordinates([first, *expected["names"]], [0.0] * (len(expected["names"]) + 1))
    with pytest.raises(ValueError, match="2 joint names but 1 positions"):
        module.coordinates(["a", "b"], [0.0])


def test_the_coordinates_of_a_python_module_drive_its_functions(tmp_path):
    robot = odd_robot()
    path = tmp_path / "odd.py"
    path.write_text(generate(robot, "numpy"))
    module = _import(path)
    q = module.coordinates({"wrist:roll": 0.3, "arm/base-joint": -0.2, "slide.1": 0.1})
    np.testing.assert_allclose(module.forward_kinematics(q), module.forward_kinematics([-0.2, 0.1, 0.3]), rtol=0,
                               atol=0)


def test_casadi_limits_bound_an_opti_problem(tmp_path):
    ca = pytest.importorskip("casadi")
    robot = load_robot("gripper.urdf")
    path = tmp_path / "gripper.py"
    path.write_text(generate(robot, "casadi"))
    module = _import(path)
    opti = ca.Opti()
    q = opti.variable(len(module.JOINT_NAMES))
    target = ca.DM([4.0, -4.0, 0.5])  # outside the first two joints' limits
    opti.minimize(ca.sumsqr(q - target))
    opti.subject_to(opti.bounded(ca.DM(module.LOWER), q, ca.DM(module.UPPER)))
    opti.solver("ipopt", {"print_time": False}, {"print_level": 0, "sb": "yes"})
    solution = np.asarray(opti.solve().value(q)).ravel()
    np.testing.assert_allclose(solution, [math.pi, -math.pi / 2, 0.5], atol=1e-6)


def test_headers_say_the_format_and_the_convention():
    urdf = generate(load_robot("ur5.urdf"), "python")
    assert "# Robot: ur5 (6 joints), from the symjac catalog's URDF file ur5.urdf." in urdf
    assert "# Convention: general (fixed origins and joint axes, as URDF and MJCF write them)." in urdf
    assert "general DH" not in urdf
    cpp = generate(load_robot("ur5.urdf"), "cpp")
    assert "// Convention: general (fixed origins and joint axes, as URDF and MJCF write them)." in cpp
    assert "general DH" not in cpp
    assert "// Convention: standard DH." in generate(load_robot("ur5"), "cpp")
    assert " * Convention: modified DH (Craig)." in generate(load_robot("stanford"), "c99")
    assert "# Convention: product of exponentials (PoE)." in generate(load_robot("ur5_poe"), "numpy")
    assert "from URDF file odd.urdf." in generate(odd_robot(), "python")


def test_the_format_is_the_readers_and_a_file_name_never_breaks_a_comment(tmp_path):
    mjcf = Path(__file__).parent / "data" / "mjcf" / "arm6" / "arm6.xml"
    assert "from MJCF file arm6.xml." in generate(load_robot(mjcf), "python")
    # a URDF file called .xml is URDF (the reader says so, not the suffix)
    urdf = tmp_path / "arm.xml"
    urdf.write_text(ODD_URDF, encoding="utf-8")
    assert "from URDF file arm.xml." in generate(load_robot(urdf), "python")
    # a file name with a newline would break out of a header comment: only plain characters remain
    hostile = tmp_path / "x\nimport os; #.urdf"
    hostile.write_text(ODD_URDF, encoding="utf-8")
    for target in ("python", "c99"):
        text = generate(load_robot(hostile), target)
        assert "\nimport os" not in text and "from URDF file x_import_os___.urdf." in text


@pytest.mark.parametrize("bad", ['a"b', "a\\b", "a b", "ä", "a;b", "x" * 65])
def test_a_name_that_is_not_safe_never_reaches_generated_code(bad):
    urdf = ODD_URDF.replace("slide.1", bad.replace('"', "&quot;"))
    for target in ("python", "c99", "cpp"):
        with pytest.raises(CodegenError, match=r"joint name .* cannot appear in generated code"):
            generate(robot_from_urdf(urdf, source="odd.urdf"), target)


def test_names_whose_identifiers_coincide_are_refused():
    urdf = ODD_URDF.replace("slide.1", "arm_base_joint").replace("arm/base-joint", "arm-base-joint")
    with pytest.raises(CodegenError, match="two coordinates have the joint identifier 'arm_base_joint'"):
        generate(robot_from_urdf(urdf, source="odd.urdf"), "c99")


def test_an_unsafe_tip_frame_name_is_refused():
    urdf = ODD_URDF.replace("tip/frame", "tip frame")
    with pytest.raises(CodegenError, match="tip frame name 'tip frame'"):
        generate(robot_from_urdf(urdf, source="odd.urdf"), "python")


def test_a_keyword_as_joint_name_gets_an_identifier_with_a_trailing_underscore():
    robot = robot_from_urdf(ODD_URDF.replace("slide.1", "namespace"), source="odd.urdf")
    assert describe(ModuleRequest(robot, "cpp")).joint_entries[1].identifier == "namespace_"
    assert describe(ModuleRequest(robot, "python")).joint_entries[1].identifier == "namespace"
    assert describe(ModuleRequest(robot, "python")).joint_entries[1].name == "namespace"


C_MAIN = """#include <stdio.h>
#include "{robot}.h"
int main(void)
{{
    const char *names[] = {{{names}}};
    const {robot}_real positions[] = {{{positions}}};
    {robot}_real q[{macro}_N_COORDINATES];
    int k, status = {robot}_coordinates(names, positions, {count}, q);
    printf("%d\\n", status);
    for (k = 0; k < {macro}_N_COORDINATES; k++) {{
        printf("%s %s %.17g %.17g %.17g\\n", {robot}_joint_names[k], {robot}_joint_types[k], (double)q[k],
               (double){robot}_lower[k], (double){robot}_upper[k]);
    }}
    printf("%s %d\\n", {macro}_TIP_FRAME, {macro}_JOINT_{last});
    printf("%d\\n", {robot}_coordinates(names + 1, positions + 1, {count} - 1, q));
    return 0;
}}
"""


def _parse_table(lines: list[str]) -> tuple[list[str], list[str], list[float], list[float], list[float]]:
    rows = [line.split() for line in lines]
    return ([r[0] for r in rows], [r[1] for r in rows], [float(r[2]) for r in rows], [float(r[3]) for r in rows],
            [float(r[4]) for r in rows])


def _check_table(output: str, expected: dict, q: list[float], missing: int) -> None:
    lines = output.splitlines()
    assert lines[0] == "0"
    n = len(expected["names"])
    names, kinds, values, lower, upper = _parse_table(lines[1:1 + n])
    assert tuple(names) == expected["names"]
    assert tuple(kinds) == expected["types"]
    np.testing.assert_allclose(values, q, rtol=1e-15)
    np.testing.assert_allclose(lower, expected["lower"], rtol=1e-15)
    np.testing.assert_allclose(upper, expected["upper"], rtol=1e-15)
    assert lines[1 + n] == f"{expected['tip']} {n - 1}"
    assert lines[2 + n] == str(missing)


def _first_missing(names: list[str], expected: dict) -> int:
    """1 + the index of the first joint the list without its first entry does not name (0: none missing)."""
    rest = set(names[1:])
    return next((i + 1 for i, name in enumerate(expected["names"]) if name not in rest), 0)


@pytest.mark.external  # a C compiler
@pytest.mark.parametrize("which", ["odd", "gripper"])
def test_c99_fills_q_from_a_shuffled_name_list_and_exposes_the_tables(tmp_path, which):
    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed")
    robot, expected = _robot(which), _expected(which)
    for name, text in render_files(describe(ModuleRequest(robot, "c99"))).items():
        (tmp_path / name).write_text(text)
    names, positions, q = _shuffled(expected["names"], 7)
    (tmp_path / "main.c").write_text(C_MAIN.format(
        robot=robot.name, macro=robot.name.upper(), names=", ".join(f'"{n}"' for n in names),
        positions=", ".join(repr(p) for p in positions), count=len(names), last=expected["identifiers"][-1]))
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "main.c", f"{robot.name}.c",
                    "-o", "main", "-lm"], cwd=tmp_path, check=True, capture_output=True, text=True)
    output = subprocess.run([str(tmp_path / "main")], check=True, capture_output=True, text=True).stdout
    _check_table(output, expected, q, _first_missing(names, expected))


CPP_MAIN = """#include <cstdio>
#include <map>
#include <string>
#include <vector>
#include "{robot}.hpp"
int main()
{{
    namespace r = symjac::{robot};
    const std::vector<std::string> names{{{names}}};
    const std::vector<double> positions{{{positions}}};
    Eigen::Matrix<double, r::n_coordinates, 1> q;
    std::printf("%d\\n", r::coordinates(names, positions, q));
    for (int k = 0; k < r::n_coordinates; ++k) {{
        std::printf("%s %s %.17g %.17g %.17g\\n", r::joint_names[k], r::joint_types[k], q(k), r::lower[k],
                    r::upper[k]);
    }}
    std::printf("%s %d\\n", r::tip_frame, r::joint::{last});
    std::printf("%d\\n", r::coordinates(std::vector<std::string>(names.begin() + 1, names.end()),
                                        std::vector<double>(positions.begin() + 1, positions.end()), q));
    std::map<std::string, double> values;
    for (int k = 0; k < r::n_coordinates; ++k) {{
        values[r::joint_names[k]] = 0.25 * k;
    }}
    Eigen::Matrix<double, r::n_coordinates, 1> from_map;
    const int status = r::coordinates(values, from_map);  // before from_map is read: argument order is unspecified
    std::printf("%d %.17g\\n", status, from_map(r::n_coordinates - 1));
    values["not_a_joint"] = 1.0;
    std::printf("%d\\n", r::coordinates(values, from_map));
    return 0;
}}
"""


@pytest.mark.external  # a C++ compiler and Eigen
@pytest.mark.parametrize("which", ["odd", "gripper"])
def test_cpp_fills_q_from_a_shuffled_name_list_or_a_map_and_exposes_the_tables(tmp_path, which):
    if shutil.which("g++") is None or not (EIGEN / "Eigen" / "Dense").is_file():
        pytest.skip("g++ or Eigen's headers are missing")
    robot, expected = _robot(which), _expected(which)
    (tmp_path / f"{robot.name}.hpp").write_text(generate(robot, "cpp"))
    names, positions, q = _shuffled(expected["names"], 11)
    (tmp_path / "main.cpp").write_text(CPP_MAIN.format(
        robot=robot.name, names=", ".join(f'"{n}"' for n in names), positions=", ".join(repr(p) for p in positions),
        last=expected["identifiers"][-1]))
    subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", f"-I{EIGEN}", "main.cpp", "-o", "main"],
                   cwd=tmp_path, check=True, capture_output=True, text=True)
    output = subprocess.run([str(tmp_path / "main")], check=True, capture_output=True, text=True).stdout
    n = len(expected["names"])
    _check_table("\n".join(output.splitlines()[:3 + n]), expected, q, _first_missing(names, expected))
    assert output.splitlines()[3 + n:] == [f"0 {0.25 * (n - 1)!r}", "-1"]


def test_a_dh_robot_file_may_name_its_joints_and_the_names_survive_writing_it_back():
    robot = robot_from_mapping({"name": "named", "convention": "modified", "joints": [
        {"type": "revolute", "name": "waist", "limits": [-1, 2]}, {"type": "prismatic", "alpha": "-pi/2"}]})
    assert [joint.name for joint in robot.joints] == ["waist", ""]
    again = robot_from_toml(robot_to_toml(robot))
    assert [joint.name for joint in again.joints] == ["waist", ""]
    description = describe(ModuleRequest(again, "python"))
    assert description.joint_names == ("waist", "d2")
    assert [(e.type, e.lower, e.upper) for e in description.joint_entries] == [
        ("revolute", -1.0, 2.0), ("prismatic", -math.inf, math.inf)]
    with pytest.raises(RobotFileError, match="'name' must be a string"):
        robot_from_mapping({"name": "named", "convention": "standard", "joints": [{"type": "revolute", "name": 3}]})


def test_the_longest_names_fit_the_line_width_of_every_target():
    long = ["a" * 61 + suffix for suffix in ("/-1", ".:2", "_x3")]
    urdf = ODD_URDF
    for old, new in zip(ODD["names"], long, strict=True):
        urdf = urdf.replace(old, new)
    robot = robot_from_urdf(urdf.replace("tip/frame", "t" * 64), source="odd.urdf")
    for target in ("python", "numpy", "lambdify", "c", "c99", "cpp", "jax", "casadi"):
        text = "".join(render_files(describe(ModuleRequest(robot, target))).values())  # check_layout: 120 columns
        assert all(name in text for name in long)


def _finger_chain(name_length: int) -> str:
    """An arm whose finger on the chain mimics the other finger, beside it; joint names ``name_length`` long."""
    long = "j" * (name_length - 2)
    return f"""<robot name="hand"><link name="base"/><link name="palm"/><link name="left"/><link name="right"/>
  <joint name="{long}_1" type="revolute"><parent link="base"/><child link="palm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1"/></joint>
  <joint name="{long}_l" type="prismatic"><parent link="palm"/><child link="left"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04"/></joint>
  <joint name="{long}_r" type="prismatic"><parent link="palm"/><child link="right"/><axis xyz="0 -1 0"/>
    <origin xyz="0.1 0 0"/><limit lower="-0.01" upper="0.05"/><mimic joint="{long}_l" multiplier="2"/></joint>
</robot>"""


@pytest.mark.parametrize("target", ["python", "numpy", "c", "c99", "cpp", "jax", "casadi", "lambdify"])
def test_a_finger_beside_the_chain_fits_every_header_and_keeps_the_limits_its_follower_implies(target):
    robot = robot_from_urdf(_finger_chain(64), source="hand.urdf", tip_link="right")
    for text in render_files(describe(ModuleRequest(robot, target))).values():
        assert max(len(line) for line in text.splitlines()) <= 120
    # the right finger (limits -0.01 .. 0.05) moves twice the left finger's coordinate: q in [-0.005, 0.025]
    module = generate(robot, "python")
    assert "LOWER = (-1.0, -0.005)" in module and "UPPER = (1.0, 0.025)" in module
