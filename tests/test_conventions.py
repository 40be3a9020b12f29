"""Conventions are plug-ins: the registry, the robot-file mapping of each, and a chain that knows none of them."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from reference import end_of_chain, finite_difference_jacobian, random_configuration

from symjac import Chain, catalog, load_robot, numeric_jacobian, robot_from_mapping, robot_to_mapping, urdf_catalog
from symjac.errors import RobotFileError
from symjac.model.conventions import PLUGINS, joint_forms, plugin
from symjac.model.conventions.base import JointForm
from symjac.model.robot import Convention
from symjac.printing.tables import column_html, column_latex, column_text, parameter_table_latex, table_headings
from symjac.report.content import parameter_table_html
from symjac.symbolic.transforms import Motion

CHAIN_SOURCE = Path(__file__).resolve().parent.parent / "symjac" / "kinematics" / "chain.py"


def samples(convention: Convention) -> list:
    """Robots in ``convention``: a small one any convention reads, the catalog's and the URDF files' robots in it."""
    rows = [{"type": "revolute"}, {"type": "prismatic", "d": "L1", "theta": "pi/3", "limits": [0, 1]}]
    data = {"name": "small", "convention": convention.value, "parameters": {"L1": 0.5}, "joints": rows}
    if convention == "poe":  # screws and a home pose instead of offsets
        data["joints"] = [{"type": "revolute", "axis": [0, 0, 1], "point": ["L1", 0, 0]},
                          {"type": "prismatic", "screw": [0, 0, 0, 0, 0, 1], "limits": [0, 1]}]
        data["home"] = {"xyz": ["L1", 0, "L1"], "rpy": [0, 0, "pi/3"]}
    small = robot_from_mapping(data)
    robots = [load_robot(name) for name in catalog()] + [load_robot(name) for name in urdf_catalog()]
    return [small] + [robot for robot in robots if robot.convention is convention]


def test_an_unknown_convention_is_refused_in_one_line_naming_file_and_field():
    data = {"name": "arm", "convention": "hartenberg", "joints": [{"type": "revolute"}]}
    with pytest.raises(RobotFileError, match=r"^arm\.toml, field 'convention': .*, got 'hartenberg'$") as error:
        robot_from_mapping(data, source="arm.toml")
    assert "\n" not in str(error.value)
    assert all(f"'{convention}'" in str(error.value) for convention in PLUGINS)
    with pytest.raises(ValueError, match="not a registered convention"):
        plugin("hartenberg")
    with pytest.raises(ValueError, match="not a convention"):
        Convention("hartenberg")


def test_every_registered_convention_names_itself():
    assert set(PLUGINS) >= {Convention.STANDARD, Convention.MODIFIED, Convention.GENERAL}
    for convention, spec in PLUGINS.items():
        assert spec.convention is convention and Convention(convention.value) is convention
        assert spec.table_name and spec.columns


@pytest.mark.parametrize("convention", list(PLUGINS), ids=str)
def test_each_convention_round_trips_through_the_robot_file_mapping(convention):
    robots = samples(convention)
    assert robots, f"no sample robot in the {convention} convention"
    for robot in robots:
        data = robot_to_mapping(robot)
        again = robot_from_mapping(data, source="again")
        assert again == robot
        assert [joint.name for joint in again.joints] == [joint.name for joint in robot.joints]
        assert robot_to_mapping(again) == data


def test_a_convention_field_outside_its_plugin_is_refused():
    data = {"name": "arm", "convention": "standard", "joints": [{"type": "revolute", "axis": [0, 1, 0]}]}
    allowed = r"allowed: a, alpha, coupled, d, limits"
    with pytest.raises(RobotFileError, match=r"joint 1: unknown key\(s\) 'axis'; " + allowed):
        robot_from_mapping(data)


def test_chain_knows_no_convention():
    tree = ast.parse(CHAIN_SOURCE.read_text())
    names = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    attributes = {node.attr for node in ast.walk(tree) if isinstance(node, ast.Attribute)}
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) for alias in node.names}
    modules = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, str)}
    assert "Convention" not in names | imported
    assert "convention" not in attributes
    assert not {"alpha", "placement", "origin", "axis"} & attributes
    assert not {"standard", "modified", "general"} & strings
    assert all(not module.startswith("symjac.model.conventions.") or module == "symjac.model.conventions.base"
               for module in modules if module)


def test_a_joint_form_with_motions_on_both_sides_is_refused():
    turn = Motion("R", "x", sp.pi / 2)
    with pytest.raises(ValueError, match="not both"):
        JointForm((turn,), sp.S.Zero, sp.S.Zero, (turn,))


@pytest.mark.parametrize("convention, frames", [("standard", [0, 1, 2]), ("modified", [1, 2, 3])])
def test_axis_frames_and_parallel_axes_come_from_the_joint_forms(convention, frames):
    # twists 0 and pi are parallel and anti-parallel, a symbolic twist is not parallel, pi/2 is not either
    twists = ["0", "pi", "tw"] if convention == "standard" else ["pi/2", "0", "pi"]
    rows = [{"type": "revolute", "alpha": twist, "a": 1} for twist in twists]
    if convention == "modified":
        rows.append({"type": "revolute", "alpha": "tw", "a": 1})
    robot = robot_from_mapping({"name": "arm", "convention": convention, "parameters": {"tw": 0}, "joints": rows})
    chain = Chain(robot)
    assert [chain.axis_frame(i) for i in range(1, 4)] == frames
    groups = ((1, 2, 3),) if convention == "standard" else ((1, 2, 3), (4,))
    assert chain.parallel_groups == groups
    assert all(isinstance(form, JointForm) for form in joint_forms(robot))


def test_html_and_latex_tables_share_the_plugins_columns():
    for name in ("puma560", "ur5.urdf"):
        robot = load_robot(name)
        latex_table, html_table = parameter_table_latex(robot), parameter_table_html(robot)
        for column in table_headings(robot):
            assert column_latex(column) in latex_table and f"<th>{column_html(column)}</th>" in html_table
            assert column_text(column)
        assert html_table.count("<tr>") == latex_table.count(r"\\") + 1 == robot.n_joints + 1


def test_every_convention_gives_the_reference_jacobian():
    rng = np.random.default_rng(25)
    for convention in PLUGINS:
        for robot in samples(convention)[1:4]:
            q = random_configuration(robot, rng)
            expected = finite_difference_jacobian(robot, q, point=end_of_chain(robot))  # the default point
            assert np.allclose(numeric_jacobian(robot, q), expected, atol=1e-6), robot.name
