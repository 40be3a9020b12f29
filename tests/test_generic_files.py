"""Generic geometry in robot files: calibrated 6-digit screws read, sizes no robot has refused in one line."""

from __future__ import annotations

import pytest

from symjac import robot_from_mapping, robot_to_mapping
from symjac.errors import RobotFileError

HOME = {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1], [0, 0, 0, 1]]}
# joint 4 of a generated calibrated arm (6 decimals, |q| about 2): refused before for w.v = 1e-6-ish rounding
SCREW = [0.874542, -0.459199, -0.155928, 0.203638, 0.898403, -1.503606]


def poe(screw, **joint):
    return {"name": "cal", "convention": "poe", "home": HOME, "joints": [{"type": "revolute", "screw": screw, **joint}]}


def test_a_six_digit_calibrated_screw_is_read_and_written_back_as_given():
    robot = robot_from_mapping(poe(SCREW))
    assert robot_to_mapping(robot)["joints"][0]["screw"] == SCREW
    assert "sqrt" not in str(robot.joints[0].placement.omega)


def test_a_home_matrix_written_to_six_decimals_is_a_rotation_to_the_file_s_rounding():
    home = {"matrix": [[-0.238138, -0.95533, -0.175031, 0.294132], [0.89799, -0.147918, -0.41441, 0.028422],
                       [0.370008, -0.255862, 0.893101, 0.546713], [0, 0, 0, 1]]}
    robot = robot_from_mapping({**poe(SCREW), "home": home})
    assert robot_to_mapping(robot)["home"]["matrix"][0][:3] == [-0.238138, -0.95533, -0.175031]
    coarse = {"matrix": [[0.7071, -0.7071, 0, 0], [0.7071, 0.7071, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
    with pytest.raises(RobotFileError, match=r"not a rotation \(\|R\^T R - I\| = 2\.\de-05, more than"):
        robot_from_mapping({**poe(SCREW), "home": coarse})


def test_a_real_pitch_is_refused_with_a_short_decimal():
    with pytest.raises(RobotFileError, match=r"joint 1, field 'screw': .*zero pitch.*w.v = -?0\.0\d+ \(more") as info:
        robot_from_mapping(poe([*SCREW[:5], SCREW[5] + 0.01]))
    assert "sqrt" not in str(info.value)


@pytest.mark.parametrize(("convention", "joint", "field"), [
    ("standard", {"a": 1e6}, "a"), ("modified", {"d": -2e3}, "d"), ("standard", {"alpha": 9e4}, "alpha"),
    ("general", {"xyz": [0, 1e6, 0]}, "origin.xyz"), ("general", {"rpy": [0, 0, 1e6]}, "origin.rpy")])
def test_sizes_no_robot_has_are_refused(convention, joint, field):
    degrees = {"angle_unit": "deg"} if field in ("alpha", "origin.rpy") else {}  # else the one-turn rule speaks first
    with pytest.raises(RobotFileError, match=rf"joint 1, field '{field}': .*larger than 1000 (m|rad) in size"):
        robot_from_mapping({"name": "r", "convention": convention, **degrees,
                            "joints": [{"type": "revolute", **joint}]})


def test_a_screw_point_far_away_is_refused():
    with pytest.raises(RobotFileError, match=r"field 'screw': 'screw' entry .* larger than 1000 m"):
        robot_from_mapping(poe([0, 0, 1, 0, -5000, 0]))
