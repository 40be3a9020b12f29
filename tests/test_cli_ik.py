"""``symjac ik``: the pose in four forms, the solutions read back from JSON and checked, LaTeX that compiles, errors."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from symjac import load_robot, pose_from_rpy
from symjac.analysis.inverse_kinematics.poses import quaternion_from_pose, rpy_from_pose
from symjac.kinematics.chain import forward_kinematics
from symjac.kinematics.numeric import numeric_at
from symjac.model.ends import last_frame

Q = "0.3,0.5,-0.2"


def fk(name: str, q) -> np.ndarray:
    robot = load_robot(name)
    return numeric_at(robot, forward_kinematics(robot, 0, last_frame(robot)), list(map(float, q)))


def numbers(values) -> str:
    return ",".join(repr(float(v)) for v in np.ravel(values))


def test_json_solutions_reach_the_pose(cli):
    data = cli.json("ik", "planar3r", "--q", Q, "--method", "numeric")
    pose = fk("planar3r", [0.3, 0.5, -0.2])
    assert np.allclose(data["pose"], pose, atol=1e-12)
    assert data["method"] == "numeric" and data["robot"] == "planar3r"
    assert data["controlled"] == "x, y and the rotation about z"
    assert len(data["solutions"]) == 2  # elbow up and down, the last joint making up the orientation
    for solution in data["solutions"]:
        assert np.allclose(fk("planar3r", solution["q"]), pose, atol=1e-9)
        assert solution["within_limits"] is True and solution["position_error"] < 1e-9
    assert any(np.allclose(s["q"], [0.3, 0.5, -0.2], atol=1e-8) for s in data["solutions"])


def test_the_four_forms_of_a_pose_agree(cli):
    pose = fk("planar3r", [0.3, 0.5, -0.2])
    rpy, wxyz = rpy_from_pose(pose), quaternion_from_pose(pose)
    forms = [["--q", Q], ["--pose", numbers(pose)], ["--pose", numbers(pose[:3])],
             ["--position", numbers(pose[:3, 3]), "--rpy", numbers(rpy)],
             ["--position", numbers(pose[:3, 3]), "--quaternion", numbers(wxyz)]]
    answers = [cli.json("ik", "planar3r", "--method", "numeric", *form) for form in forms]
    for data in answers:
        assert np.allclose(data["pose"], pose, atol=1e-12)
        assert np.allclose([s["q"] for s in data["solutions"]], [s["q"] for s in answers[0]["solutions"]], atol=1e-8)


def test_rpy_in_degrees_and_with_pi(cli):
    data = cli.json("ik", "planar2r", "--position", "0.6,0.3,0", "--rpy", "0,0,90deg")
    same = cli.json("ik", "planar2r", "--position", "0.6,0.3,0", "--rpy", "0,0,pi/2")
    assert np.allclose(data["pose"], pose_from_rpy([0.6, 0.3, 0], [0, 0, np.pi / 2]), atol=1e-15)
    assert data["pose"] == same["pose"]


def test_pretty_and_latex_print_the_table_and_the_notes(cli):
    pretty = cli.ok("ik", "planar2r", "--position", "0.6,0.3,0", "--rpy", "0,0,0", "--format", "pretty")
    assert "Inverse kinematics of planar2r: 2 solutions" in pretty and "Q =" in pretty
    assert "2 solutions in closed form (planar 2R). Why: the axes of joints 1 and 2 are parallel." in pretty
    assert "Row 1: elbow down; within the joint limits; forward kinematics misses the position by" in pretty
    assert "it does not set z (fixed by the arm's geometry); the orientation" in pretty
    latex = cli.ok("ik", "planar2r", "--position", "0.6,0.3,0", "--rpy", "0,0,0", "--digits", "3")
    assert r"Q = \begin{bmatrix}" in latex and latex.count("% Row ") == 2
    assert r"T = \begin{bmatrix}1 & 0 & 0 & 0.6\\" in latex


def test_without_limits_every_solution_is_kept_and_flagged(cli):
    data = cli.json("ik", "planar3r", "--q", Q, "--no-within-limits", "--method", "numeric")
    assert data["solutions"] and all("within_limits" in s for s in data["solutions"])


def test_an_unreachable_pose_is_an_answer_not_an_error(cli):
    data = cli.json("ik", "planar2r", "--position", "2,0,0", "--rpy", "0,0,0")
    assert data["solutions"] == [] and data["unreachable"] and data["distance"] == pytest.approx(2.0 - 0.9)
    numeric = cli.json("ik", "planar2r", "--position", "2,0,0", "--rpy", "0,0,0", "--method", "numeric")
    assert numeric["solutions"] == [] and "closest configuration reached" in numeric["unreachable"]
    assert numeric["distance"] == pytest.approx(2.0 - 0.9, abs=1e-3)  # the closest configuration the search reached


@pytest.mark.parametrize(("argv", "message"), [
    (["planar2r"], "ik needs the pose: --pose T, --position X,Y,Z with --rpy or --quaternion, or --q Q"),
    (["planar2r", "--q", "0,0", "--pose", numbers(np.eye(4))], "ik takes one pose, got --pose and --q"),
    (["puma560", "--position", "0.5,0,0"], "--position alone is a target for an arm that sets no orientation; "
     "puma560 sets its orientation too: add --rpy or --quaternion"),
    (["planar2r", "--position", "0.5,0,0", "--rpy", "0,0,0", "--quaternion", "1,0,0,0"],
     "--position takes one of --rpy and --quaternion, not both"),
    (["planar2r", "--q", "0,0", "--rpy", "0,0,0"], "--rpy goes with --position, not with --q"),
    (["planar2r", "--position", "0.5,0,0", "--quaternion", "1,0,0,1"],
     "--quaternion: the quaternion (w, x, y, z) must have unit length, got length 1.41421"),
    (["planar2r", "--position", "0.5,0,0", "--rpy", "0,0"], "--rpy needs 3 comma-separated values, got 2 in '0,0'"),
    (["planar2r", "--position", "0.5,0,0", "--rpy", "0,0,x"], "--rpy takes numbers and expressions with pi only"),
    (["planar2r", "--pose", "1,0,0"], "--pose needs 16 comma-separated values, got 3 in '1,0,0'"),
    (["planar2r", "--pose", numbers(2 * np.eye(4))], "--pose: the last row of a pose is [0, 0, 0, 1]"),
    (["planar2r", "--pose", numbers(np.diag([1, 1, 1.1, 1]))], "--pose: the rotation block is not orthonormal"),
    (["no_such_robot", "--q", "0,0"], "no_such_robot"),
    (["planar2r", "--q", "0,0", "--free-joint", "2"], "--free-joint needs --free-value (the value of that joint)"),
    (["planar2r", "--q", "0,0", "--restarts", "-1"], "--restarts must be 0 or more, got -1"),
    (["planar2r", "--q", "0,0", "--numeric"], "--numeric does not apply to ik: the solutions are numbers already"),
    (["iiwa7", "--q", "0,0,0,-1,0,1,0", "--free-value", "0.3", "--free-joint", "8"],
     "--free-joint is a joint number, 1 to 7 for iiwa7, got 8"),
    (["puma560", "--q", "0,0,0,0,0,0", "--free-value", "0.3"],
     "--free-value gives a redundant arm's closed form one joint's value; puma560 has 6 joints"),
    (["iiwa7", "--q", "0,0,0,-1,0,1,0", "--free-value", "0.3", "--method", "numeric"],
     "--free-value gives a redundant arm's closed form one joint's value: it does not apply with --method numeric"),
    (["iiwa7", "--q", "0,0,0,-1,0,1,0", "--method", "closed_form"],
     "a redundant arm's closed form takes one joint's value: --free-value V (joint 1's, or --free-joint K for "
     "joint K)"),
    (["planar2r", "--derivation", "--pose", "1,0,0"], "--pose needs 16 comma-separated values"),
    (["iiwa7", "--q", "0,0,0,-1,0,1,0", "--free-value", "0.3", "--free-joint", "5"],
     "--free-value gives a redundant arm's closed form one joint's value, and iiwa7 with --free-joint 5 has none: "
     "iiwa7 with joint 5 given: no closed-form family fits"),
    (["panda", "--q", "0,0,0,-1,0,1,0", "--free-value", "0.3"],
     "--free-value gives a redundant arm's closed form one joint's value, and panda has none: panda: no joint"),
    (["panda", "--q", "0,0,0,-1,0,1,0", "--free-value", "0.3"], "without --free-value, --method auto"),
    (["planar2r", "--q", "0,0", "--derivation", "--method", "numeric"], "--derivation prints a closed form"),
    (["palletizer", "--q", "0.3,0.4,0.5,0.2", "--method", "numeric"], "palletizer's joints are coupled"),
])
def test_each_mistake_is_one_line(cli, argv, message):
    line = cli.one_line_error("ik", *argv)
    assert message in line, line


@pytest.mark.parametrize(("option", "argv"), [
    ("--position", ["--position", "nan,0,0", "--rpy", "0,0,0"]),
    ("--rpy", ["--position", "0,0,0", "--rpy", "0,inf,0"]),
    ("--quaternion", ["--position", "0,0,0", "--quaternion", "nan,0,0,1"]),
    ("--pose", ["--pose", ",".join(["nan"] * 16)]),
    ("--rpy", ["--position", "0,0,0", "--rpy", "0,0,1e999"]),  # a number, but too large to be finite
])
def test_a_nan_pose_is_one_line_naming_its_option(cli, option, argv):
    line = cli.one_line_error("ik", "planar2r", *argv)
    assert line.startswith(f"symjac: error: {option} takes finite numbers, got "), line
    assert "joint angles" not in line  # the configuration's wording belongs to --q


def test_a_position_alone_is_enough_for_an_arm_that_sets_no_orientation(cli):
    data = cli.json("ik", "planar2r", "--position", "0.5,0.3,0")
    assert len(data["solutions"]) == 2 and data["uncontrolled"] == ""  # no orientation asked, none to differ from
    assert data["position_alone"] and not cli.json("ik", "planar2r", "--q", "0.1,0.2")["position_alone"]
    out = cli.run("ik", "planar2r", "--position", "0.5,0.3,0", "--format", "pretty")[1]
    assert "Only a position was given: the rotation in T is the identity, standing in for the orientation" in out
    for solution in data["solutions"]:
        assert np.allclose(fk("planar2r", solution["q"])[:3, 3], [0.5, 0.3, 0], atol=1e-12)


def test_the_derivation_needs_no_pose(cli):
    code, out, _ = cli.run("ik", "puma560", "--derivation")
    assert code == 0 and "atan2" in out
    assert cli.run("ik", "puma560", "--derivation", "--q", "0.1,0.2,0.3,0.4,0.5,0.6")[1] == out  # the same steps
    code, out, _ = cli.run("ik", "iiwa7", "--derivation", "--free-joint", "3", "--format", "pretty")
    assert code == 0 and "joint 3 is given" in out
    code, out, _ = cli.run("ik", "iiwa7", "--derivation", "--format", "pretty")
    assert code == 0 and "joint 1 is given" in out  # the first joint whose value leaves a closed form


@pytest.mark.external
@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed; .ci/run installs it")
def test_the_standalone_latex_compiles(cli, tmp_path):
    from tests.test_latex_compile import compile_tex

    for name, q in (("puma560", "0.3,-0.5,0.4,0.2,0.6,-0.1"), ("planar2r", "0.2,0.9"),
                    ("panda", "0.1,0.2,0.3,-1.5,0.2,1,0.3")):
        path = tmp_path / f"{name}_ik.tex"
        path.write_text(cli.ok("ik", name, "--q", q, "--standalone"), encoding="utf-8")
        assert compile_tex(path) == [], name


def test_derivation_prints_the_closed_forms_steps(cli):
    from symjac.analysis.inverse_kinematics import closed_form_plan
    from symjac.printing import render
    from symjac.printing.ik_derivation import ik_derivation_document

    out = cli.ok("ik", "puma560", "--q", "0.4,-0.6,0.3,0.5,0.7,-0.2", "--derivation")
    assert out == render(ik_derivation_document(closed_form_plan(load_robot("puma560"))), "latex")


def test_derivation_of_an_arm_without_a_closed_form_says_why(cli):
    line = cli.one_line_error("ik", "panda", "--q", "0.1,0.2,0.3,-1.5,0.2,1,0.3", "--derivation")
    assert line.startswith("symjac: error: panda: no closed-form family fits")


def test_seed_rng_and_restarts_reach_the_numeric_solver(cli):
    near = cli.json("ik", "puma560", "--q", "0.4,-0.6,0.3,0.5,0.7,-0.2", "--method", "numeric", "--restarts", "0",
                    "--seed", "0.41,-0.59,0.31,0.49,0.71,-0.21")
    assert len(near["solutions"]) == 1  # one start, from the seed, converging to the configuration beside it
    assert np.allclose(near["solutions"][0]["q"], [0.4, -0.6, 0.3, 0.5, 0.7, -0.2], atol=1e-9)
    first = cli.json("ik", "puma560", "--q", "0.4,-0.6,0.3,0.5,0.7,-0.2", "--method", "numeric", "--rng", "5")
    again = cli.json("ik", "puma560", "--q", "0.4,-0.6,0.3,0.5,0.7,-0.2", "--method", "numeric", "--rng", "5")
    assert first["solutions"] == again["solutions"] and first["why"] == "numeric: asked for"


@pytest.mark.parametrize(("argv", "hint"), [
    (["iiwa7", "--method", "closed_form"],
     "; a redundant arm's closed form takes one joint's value: --free-value V (joint 1's, or --free-joint K for "
     "joint K)"),
    (["panda", "--method", "closed_form"], "; use the numeric solver (--method auto or numeric)"),
    (["panda", "--method", "closed_form", "--free-value", "0.2", "--free-joint", "4"],
     "; use the numeric solver (without --free-value, --method auto or numeric)"),
])
def test_no_closed_form_ends_with_the_command_lines_options(cli, argv, hint):
    line = cli.one_line_error("ik", *argv, "--q", "0,0.3,0,-1,0,1,0.2")
    assert line.endswith(hint), line
    assert "free_value=V" not in line and "method='auto'" not in line  # Python's hint is not passed on


def test_an_unreachable_pose_states_its_distance_once(cli):
    out = cli.run("ik", "planar2r", "--position", "5,0,0", "--format", "pretty")[1]
    assert "No solution: " in out and " m out)" not in out
