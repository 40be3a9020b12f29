"""Generated modules from the user's side: stable function names, and a header command that works when pasted.

The first Jacobian requested is always ``jacobian`` (``hessian``, ... with ``acceleration=True``); the others are
``jacobian_<frame>_<point>[_r<rows>]``. The header's "regenerate it with" text is run as a user would paste it: the
shell command from the folder it was run in, the Python call after ``import symjac``.
"""

from __future__ import annotations

import shlex

import numpy as np
import pytest

from symjac import load_robot
from symjac.cli.main import main
from symjac.codegen import JacobianRequest, ModuleRequest, describe, generate, render_files
from symjac.model.robot_file import robot_from_mapping

ARM = """name = "my_arm"
convention = "standard"

[parameters]
a1 = 0.3
a2 = 0.25

[[joints]]
type = "revolute"
alpha = 0
a = "a1"

[[joints]]
type = "revolute"
alpha = 0
a = "a2"
"""


def _namespace(source: str) -> dict:
    namespace: dict = {}
    exec(compile(source, "generated.py", "exec"), namespace)
    return namespace


def _header_command(text: str) -> tuple[str, list[str]]:
    """The text under "regenerate it with:" as pasted (comment marks removed), and the note lines after it."""
    lines = text.splitlines()
    start = lines.index("# Generated code, do not edit; regenerate it with:") + 1
    body = []
    for line in lines[start:]:
        if not line.startswith("#   "):
            break
        body.append(line[4:])
    notes = [line for line in body if line.startswith("(")]
    command = "\n".join(line for line in body if not line.startswith("("))
    return command.replace(" \\\n", " "), notes  # a shell line continued with a backslash


def test_first_jacobian_keeps_its_name_when_a_frame_is_added():
    robot = load_robot("planar2r")
    two = _namespace(generate(robot, "python", frames=(0, 1), acceleration=True))
    alone = _namespace(generate(robot, "python", frames=0, acceleration=True))
    frame_1 = _namespace(generate(robot, "python", frames=1))
    q, qdot = [0.3, -1.1], [0.5, 0.7]
    assert two["jacobian"](q, L1=0.45) == alone["jacobian"](q, L1=0.45)  # the README's call keeps working
    assert two["jacobian_1_flange"](q) == frame_1["jacobian"](q)  # planar2r has no tool: its end is the flange
    assert two["jacobian"](q) != two["jacobian_1_flange"](q)
    for kind in ("hessian", "bias_acceleration", "manipulability_gradient", "joint_torques", "manipulability"):
        assert kind in two["__all__"] and f"{kind}_1_flange" in two["__all__"], kind
    assert two["bias_acceleration"](q, qdot) == alone["bias_acceleration"](q, qdot)
    assert "jacobian_0_flange" not in two


def test_other_requests_are_named_by_frame_point_and_rows():
    robot = load_robot("planar2r")
    requests = [JacobianRequest("tool", "wrist", (0, 1)), JacobianRequest(0), JacobianRequest(0, (1, 0, 0)),
                JacobianRequest(1, "wrist", (0, 1))]
    names = _namespace(generate(robot, "python", jacobians=requests))["__all__"]
    assert {"jacobian", "jacobian_0_flange", "jacobian_0_p1", "jacobian_1_wrist_r01"} <= set(names)
    assert "jacobian_tool_wrist_r01" not in names
    with pytest.raises(ValueError, match="requested twice"):
        generate(robot, "python", jacobians=[JacobianRequest(0), JacobianRequest(1), JacobianRequest(0)])


def test_pasted_shell_command_regenerates_the_same_bytes(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my_arm.toml").write_text(ARM, encoding="utf-8")
    assert main(["codegen", "my_arm.toml", "--target", "numpy", "--frame", "0", "--frame", "1", "--point", "0.1,0,0",
                 "-o", "arm.py"]) == 0
    first = (tmp_path / "arm.py").read_bytes()
    command, notes = _header_command(first.decode())
    assert notes == ["(in the folder it was run in)"]  # relative paths: say from where
    (tmp_path / "arm.py").unlink()
    words = shlex.split(command)
    assert words[:3] == ["symjac", "codegen", "my_arm.toml"]
    assert main(words[1:]) == 0
    assert (tmp_path / "arm.py").read_bytes() == first


def test_pasted_python_call_regenerates_the_same_text(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my_arm.toml").write_text(ARM, encoding="utf-8")
    cases = [(load_robot("my_arm.toml"), ["(in the folder it was run in)"]),
             (load_robot(str(tmp_path / "my_arm.toml")), []),
             (load_robot("planar2r"), [])]
    for robot, expected_notes in cases:
        text = generate(robot, "python", frames=(0, 1))
        call, notes = _header_command(text)
        assert notes == expected_notes
        one_line = call.replace("(\n    ", "(")  # a call too wide for one line is cut after a parenthesis
        assert one_line.startswith(f'symjac.generate(symjac.load_robot("{robot.source}"'
                                   if robot.name == "my_arm" else 'symjac.generate(symjac.load_robot("planar2r")')
        namespace: dict = {}
        exec(f"import symjac\ntext = {call}", namespace)
        assert namespace["text"] == text


def test_a_robot_from_a_mapping_is_named_robot_in_the_header():
    robot = robot_from_mapping({"name": "two", "convention": "standard",
                                "joints": [{"type": "revolute", "a": 1}, {"type": "prismatic"}]})
    text = generate(robot, "python")
    call, notes = _header_command(text)
    assert call.startswith("symjac.generate(robot, ")
    assert notes == ["(robot: the Robot given to symjac.generate, from a mapping)"]
    namespace: dict = {"robot": robot}
    exec(f"import symjac\ntext = {call}", namespace)
    assert namespace["text"] == text
    assert np.allclose(_namespace(text)["jacobian"]([0.2, 0.1])[0], [-np.sin(0.2), 0.0])


@pytest.mark.parametrize("target", ["python", "c99"])
@pytest.mark.parametrize("repeat", [1, 4])
def test_a_robot_file_at_a_long_path_still_generates(tmp_path, target, repeat):
    """The header's regenerating call names the file's absolute path: a call too wide for one line is cut after a
    parenthesis (it stays Python), a path wider than a line into pieces; no line is ever too wide."""
    folder = tmp_path / ("long_folder_" * repeat)
    folder.mkdir()
    (folder / "my_arm.toml").write_text(ARM, encoding="utf-8")
    files = render_files(describe(ModuleRequest(load_robot(str(folder / "my_arm.toml")), target)))
    assert all(len(line) <= 120 for text in files.values() for line in text.splitlines())
    if target == "python" and len(str(folder / "my_arm.toml")) < 100:  # the quoted path fits on its line
        (text,) = files.values()
        call, _ = _header_command(text)
        namespace: dict = {}
        exec(f"import symjac\ntext = {call}", namespace)
        assert namespace["text"] == text
