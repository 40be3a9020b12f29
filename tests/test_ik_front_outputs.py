"""Inverse kinematics drawn (``symjac draw --ik-pose``) and in the report (its section: method, table, drawings)."""

from __future__ import annotations

import base64
import re

import numpy as np
import pytest

from symjac import inverse_kinematics, load_robot, pose_from_rpy
from symjac.cli.drawing import ik_pose
from symjac.drawing.geometry import arm_pose
from symjac.drawing.solutions import draw_solutions
from symjac.errors import ArgumentError

pytest.importorskip("matplotlib")


def test_each_solution_is_a_panel_reaching_the_target():
    robot = load_robot("planar2r")
    result = inverse_kinematics(robot, pose_from_rpy([0.6, 0.3, 0.0], [0, 0, 0]))
    figure = draw_solutions(robot, result)
    assert len(figure.axes) == len(result.solutions) == 2
    for number, (axes, solution) in enumerate(zip(figure.axes, result.solutions, strict=True), start=1):
        assert axes.get_title() == ", ".join(solution.branch) and solution.branch[0].startswith("elbow")
        target = next(line for line in axes.lines if line.get_gid() == f"panel{number}-target-x")
        start = np.array([target.get_data_3d()[k][0] for k in range(3)])
        assert np.allclose(start, arm_pose(robot, solution.q).tool[:3, 3], atol=1e-9)  # the arm's tip is there


def test_nothing_to_draw_is_one_line():
    robot = load_robot("planar2r")
    result = inverse_kinematics(robot, pose_from_rpy([2.0, 0.0, 0.0], [0, 0, 0]))
    with pytest.raises(ArgumentError, match=r"planar2r: no solution to draw \(the tool point is 1\.1 "
                                             r"beyond the reach"):
        draw_solutions(robot, result)


def test_draw_ik_pose_writes_one_panel_per_solution(cli, tmp_path):
    out = tmp_path / "elbows.svg"
    assert cli.run("draw", "planar2r", "--ik-pose", "0.6,0.3,0,0,0,0", "-o", str(out)) == (0, "", "")
    svg = out.read_text(encoding="utf-8")
    assert set(re.findall(r'id="(panel\d)-target-x"', svg)) == {"panel1", "panel2"}


@pytest.mark.parametrize(("text", "expected"), [
    ("0.6,0.3,0,0,0,1.5", pose_from_rpy([0.6, 0.3, 0], [0, 0, 1.5])),
    ("0.6,0.3,0,1,0,0,0", pose_from_rpy([0.6, 0.3, 0], [0, 0, 0])),
    ("1,0,0,0.6,0,1,0,0.3,0,0,1,0", pose_from_rpy([0.6, 0.3, 0], [0, 0, 0])),
    ("0.6,0.3,0", [0.6, 0.3, 0.0]),  # a position alone, for an arm that sets no orientation
])
def test_the_ik_pose_forms(text, expected):
    assert np.allclose(ik_pose(text, load_robot("planar2r")), expected, atol=1e-15)


@pytest.mark.parametrize(("argv", "message"), [
    (["--ik-pose", "0.6,0.3,0,0,0"], "--ik-pose takes 6 numbers (x,y,z,roll,pitch,yaw), 7 (x,y,z,w,qx,qy,qz), 12"),
    (["--ik-pose", "0.6,0.3,0,2,0,0,0"], "--ik-pose: the quaternion (w, x, y, z) must have unit length, got length 2"),
    (["--ik-pose", "0.6,0.3,0,0,0,0", "--q", "0,0"], "--ik-pose draws the solutions it finds: --q does not apply"),
])
def test_draw_ik_pose_mistakes_are_one_line(cli, tmp_path, argv, message):
    line = cli.one_line_error("draw", "planar2r", *argv, "-o", str(tmp_path / "x.svg"))
    assert message in line, line


def test_the_report_section_shows_the_method_the_table_and_each_branch():
    from symjac.report.inverse_kinematics import example_configuration, inverse_kinematics_html

    robot = load_robot("planar2r")
    text = inverse_kinematics_html(robot)
    q = example_configuration(robot)
    assert "The arm sets x and y; it does not set z" in text
    rows = re.findall(r"<tr><td>(\d)</td><td>(-?[\d.]+)</td><td>(-?[\d.]+)</td>", text)
    assert len(rows) == 2 and '<figure class="arm">' not in text and "<svg" not in text  # the page's own figures
    assert any(np.allclose([float(a), float(b)], q, atol=1e-4) for _, a, b in rows)  # the configuration it came from
    (png,) = re.findall(r'<img src="data:image/png;base64,([^"]+)"', text)
    assert base64.b64decode(png).startswith(b"\x89PNG") and "1: elbow down; 2: elbow up" in text


def test_the_page_has_the_section(cli, tmp_path):
    page = tmp_path / "page.html"
    assert cli.run("report", "planar2r", "-o", str(page)) == (0, "", "")
    text = page.read_text(encoding="utf-8")
    assert '<section id="inverse-kinematics">' in text and '<a href="#inverse-kinematics">' in text


def test_draw_ik_pose_says_how_many_more_leave_the_limits_and_draws_them_when_asked(cli, tmp_path):
    robot = load_robot("puma560")
    pose = ",".join(repr(v) for v in (0.5, 0.2, 0.3, 0.0, 1.5, 0.0))
    kept = inverse_kinematics(robot, ik_pose(pose, robot))
    assert kept.outside_limits > 0 and kept.solutions  # this pose has solutions on both sides of the limits
    within, every = tmp_path / "within.svg", tmp_path / "every.svg"
    assert cli.run("draw", "puma560", "--ik-pose", pose, "-o", str(within))[0] == 0
    assert cli.run("draw", "puma560", "--ik-pose", pose, "--no-within-limits", "-o", str(every))[0] == 0
    panels = [len(set(re.findall(r'id="(panel\d+)-target-x"', path.read_text()))) for path in (within, every)]
    assert panels == [len(kept.solutions), len(kept.solutions) + kept.outside_limits]
    title = f"{kept.outside_limits} more outside (--no-within-limits draws them)".replace("--", "- -")  # SVG comment
    assert title in within.read_text()
    assert "outside limits" in every.read_text()  # a panel's title says so


def test_draw_ik_pose_position_alone_is_refused_for_an_arm_that_sets_its_orientation(cli, tmp_path):
    line = cli.one_line_error("draw", "puma560", "--ik-pose", "0.5,0.2,0.3", "-o", str(tmp_path / "x.svg"))
    assert "--ik-pose x,y,z is a target for an arm that sets no orientation; puma560 sets its orientation" in line
