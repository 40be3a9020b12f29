"""Writing robots back (symjac.model.robot_file.robot_to_mapping, symjac.model.io.robot_to_toml): round trips
and layout."""

from __future__ import annotations

import re
import tomllib

import pytest
import sympy as sp
from robot_mappings import (
    CATALOG,
    ROTATE_Z,
    minimal,
)

from symjac.model.io import load_robot, robot_from_toml, robot_to_toml
from symjac.model.robot_file import robot_from_mapping, robot_to_mapping

# --------------------------------------------------------------------------------------------- writing back


def matrix_tool_robot():
    return robot_from_mapping(
        minimal(
            description='matrix tool, "quoted"',
            base={"xyz": [0, 0, "L1 + 0.1"], "rpy": [0, "-pi/2", 0]},
            tool={"matrix": ROTATE_Z},
        )
    )


def degree_robot():
    data = {
        "name": "degarm",
        "convention": "modified",
        "angle_unit": "deg",
        "parameters": {"a2": 0.4318, "d3": 0.15005, "q0": 10},
        "joints": [
            {"type": "revolute", "alpha": 0, "a": 0, "d": 0, "theta": 0, "limits": [-160, 160]},
            {"type": "revolute", "alpha": -90, "a": 0, "d": 0, "theta": "q0", "limits": [-225, 45]},
            {"type": "revolute", "alpha": 0, "a": "a2", "d": "d3", "theta": 0},
            {"type": "prismatic", "alpha": 90, "a": 0, "d": 0.1, "theta": 30, "limits": [0, 0.5]},
        ],
        "tool": {"xyz": [0, 0, 0.05], "rpy": [180, 0, 45]},
    }
    return robot_from_mapping(data)


def odd_robot():
    """Things that stress the writer: thirds, tiny and huge numbers, powers, text that needs escaping.

    (Huge parameters stay out of lengths: a length past 1000 m is refused as a unit error.)
    """
    data = {
        "name": "odd",
        "description": 'line one\nline two\ttab "quotes" \\ backslash, unicode θ₁ ✓, DEL \x7f, bell \x07',
        "convention": "standard",
        "parameters": {"L1": 1e-7, "L2": 1e22, "L3": -0.0, "big": 10**30, "third": 0.3333333333333333},
        "joints": [
            {"type": "revolute", "alpha": "1/3", "a": "L1**2/7", "d": "(L1 + L2)**-2", "theta": "-pi/7"},
            {"type": "prismatic", "alpha": "pi/2", "a": "third/big", "d": "-third", "limits": ["1/3", "2/3"]},
            {"type": "revolute", "a": "0.5/(L1 + L2)", "d": "L3*(L1 + L2)*2", "theta": "-1/(pi + 1)"},
        ],
    }
    return robot_from_mapping(data)


EXTRA = {"matrix_tool": matrix_tool_robot, "degrees": degree_robot, "odd": odd_robot}


def all_robots():
    return [pytest.param(lambda name=name: load_robot(name), id=name) for name in CATALOG] + [
        pytest.param(make, id=label) for label, make in EXTRA.items()
    ]


@pytest.mark.parametrize("make", all_robots())
def test_toml_round_trip(make):
    robot = make()
    text = robot_to_toml(robot)
    again = robot_from_toml(text, source="written.toml")
    assert again == robot
    assert again.source == "written.toml"
    assert robot_to_toml(again) == text  # writing is stable


@pytest.mark.parametrize("make", all_robots())
def test_toml_is_the_mapping(make):
    robot = make()
    assert tomllib.loads(robot_to_toml(robot)) == robot_to_mapping(robot)


@pytest.mark.parametrize("make", all_robots())
def test_mapping_round_trip(make):
    robot = make()
    data = robot_to_mapping(robot)
    assert robot_from_mapping(data) == robot
    assert robot_to_mapping(robot_from_mapping(data)) == data


@pytest.mark.parametrize("name", CATALOG)
def test_catalog_file_round_trips_through_a_real_file(name, tmp_path):
    robot = load_robot(name)
    path = tmp_path / f"copy_of_{name}.toml"
    path.write_text(robot_to_toml(robot), encoding="utf-8")
    again = load_robot(path)
    assert again == robot
    assert again.source == str(path)


def test_mapping_is_plain_data_in_radians():
    data = robot_to_mapping(degree_robot())
    assert "angle_unit" not in data
    assert data["joints"][1]["alpha"] == "-pi/2"
    assert data["joints"][0]["limits"] == ["-8*pi/9", "8*pi/9"]
    assert data["joints"][3]["theta"] == "pi/6"
    assert data["joints"][3]["d"] == 0.1
    assert data["joints"][3]["limits"] == [0, 0.5]
    assert data["joints"][1]["theta"] == "pi*q0/180"
    assert data["parameters"] == {"a2": 0.4318, "d3": 0.15005, "q0": 10}
    assert data["tool"] == {"xyz": [0, 0, 0.05], "rpy": ["pi", 0, "pi/4"]}


def test_mapping_layout():
    data = robot_to_mapping(robot_from_mapping(minimal()))
    assert data == {
        "name": "arm",
        "convention": "standard",
        "parameters": {"L1": 1, "L2": 0.5},
        "joints": [
            {"type": "revolute", "alpha": 0, "a": "L1", "d": 0, "theta": 0},
            {"type": "revolute", "alpha": 0, "a": "L2", "d": 0, "theta": 0},
        ],
    }


def test_mapping_of_a_matrix_tool():
    data = robot_to_mapping(matrix_tool_robot())
    assert data["tool"] == {"matrix": [[0, -1, 0, 0.1], [1, 0, 0, 0], [0, 0, 1, "L1"], [0, 0, 0, 1]]}
    assert data["base"] == {"xyz": [0, 0, "L1 + 1/10"], "rpy": [0, "-pi/2", 0]}


def test_toml_layout():
    text = robot_to_toml(load_robot("planar2r"))
    lines = text.splitlines()
    assert lines[0] == 'name = "planar2r"'
    assert lines[1].startswith("description = ")
    assert lines[2] == 'convention = "standard"'
    assert "[parameters]" in lines
    assert lines.count("[[joints]]") == 2
    assert text.endswith("\n")


def test_toml_keeps_exact_decimals():
    text = robot_to_toml(load_robot("puma560"))
    assert "a2 = 0.4318" in text
    assert "d3 = 0.15005" in text


def test_documented_robot_file_example_loads_and_matches_the_catalog_puma():
    from pathlib import Path

    page = Path(__file__).resolve().parent.parent / "docs" / "guide" / "robot_files.md"
    (example,) = [block for block in re.findall(r"```toml\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S)
                  if 'name = "puma560"' in block]
    robot = robot_from_toml(example, source="docs/guide/robot_files.md")
    puma = load_robot("puma560")
    def rows(joints):
        return [(j.placement.alpha, j.placement.a, j.d, j.theta) for j in joints]

    assert rows(robot.joints) == rows(puma.joints)
    assert robot.tool is not None and robot.tool.xyz == (0, 0, sp.Rational(1, 10))
