"""In-process tests of the ``symjac`` command line (``symjac.cli.main.main``)."""

from __future__ import annotations

import json

import pytest
import sympy as sp
from marks import marked

from symjac.cli.main import main
from symjac.model.io import catalog, load_robot, robot_to_toml

BMATRIX = r"\begin{bmatrix}"


def assert_one_line_error(status: int, out: str, err: str) -> None:
    assert status == 2
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("symjac: error: "), err
    assert "Traceback" not in err


# --- robots -------------------------------------------------------------------------------------------------


def test_robots_lists_the_whole_catalog(cli):
    out = cli.ok("robots")
    robots = catalog()
    lines = out.splitlines()
    assert len(lines) == len(robots) >= 2
    for line, (name, description) in zip(lines, robots.items(), strict=True):
        assert line.split()[0] == name
        assert line.rstrip().endswith(description.rstrip())


# --- jacobian -----------------------------------------------------------------------------------------------


def test_jacobian_planar2r_latex(cli):
    line = cli.latex_line("jacobian", "planar2r")
    assert line.startswith(r"{}^{0}J = " + BMATRIX)
    assert line.endswith(r"\end{bmatrix}")
    assert "s_{12}" in line
    assert "c_{12}" in line


def test_jacobian_in_another_frame(cli):
    base = cli.latex_line("jacobian", "planar2r")
    frame1 = cli.latex_line("jacobian", "planar2r", "--frame", "1")
    assert frame1.startswith(r"{}^{1}J = " + BMATRIX)
    assert frame1.split(" = ", 1)[1] != base.split(" = ", 1)[1]


def test_jacobian_in_the_tool_frame(cli):
    line = cli.latex_line("jacobian", "planar3r", "--frame", "tool")
    assert line.startswith(r"{}^{\mathrm{tool}}J = " + BMATRIX)  # frame names upright
    # Expressed in the last frame, the velocity of a planar arm depends only on the relative angles.
    assert "s_{1}" not in line
    assert "c_{1}" not in line


def test_jacobian_tool_point_differs_from_wrist_point(cli):
    wrist = cli.latex_line("jacobian", "planar3r", "--point", "flange")
    tool = cli.latex_line("jacobian", "planar3r", "--point", "tool")
    assert cli.latex_line("jacobian", "planar3r") == tool  # the default: the end of the chain
    assert cli.latex_line("jacobian", "planar3r", "--point", "wrist") == wrist != tool
    assert "L_{3}" in tool
    assert "L_{3}" not in wrist


def test_jacobian_explicit_point_equals_tool_point(cli):
    tool = cli.latex_line("jacobian", "planar3r", "--point", "tool")
    explicit = cli.latex_line("jacobian", "planar3r", "--point", "L3,0,0")
    assert explicit == tool


def test_jacobian_cross_product_equals_differentiation(cli):
    differentiation = cli.ok("jacobian", "puma560", "--method", "differentiation")
    cross_product = cli.ok("jacobian", "puma560", "--method", "cross_product")
    assert cross_product == differentiation
    assert cli.ok("jacobian", "puma560") == differentiation  # the default method


def test_jacobian_pretty_uses_unicode_shorthand(cli):
    out = cli.ok("jacobian", "planar2r", "--format", "pretty")
    assert "c₁₂" in out
    assert "s₁₂" in out
    assert "\\" not in out  # no LaTeX


def test_jacobian_json(cli):
    latex = cli.latex_line("jacobian", "planar3r", "--frame", "tool")
    data = json.loads(cli.ok("jacobian", "planar3r", "--frame", "tool", "--format", "json"))
    assert {"robot", "frame", "method", "shape", "entries", "latex"} <= data.keys()
    assert data["robot"] == "planar3r"
    assert data["frame"] == "tool"
    assert data["method"] == "differentiation"
    assert data["shape"] == [6, 3]
    entries = data["entries"]
    assert len(entries) == 6
    assert all(len(row) == 3 and all(isinstance(cell, str) for cell in row) for row in entries)
    assert data["latex"] == latex


def test_jacobian_json_entries_are_the_matrix(cli):
    data = json.loads(cli.ok("jacobian", "planar2r", "--format", "json"))
    assert data["frame"] == 0
    assert data["shape"] == [6, 2]
    L1, L2, t1, t2 = sp.symbols("L1 L2 theta1 theta2")
    J = sp.Matrix([[sp.sympify(cell) for cell in row] for row in data["entries"]])
    expected = sp.Matrix([
        [-L1 * sp.sin(t1) - L2 * sp.sin(t1 + t2), -L2 * sp.sin(t1 + t2)],
        [L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2), L2 * sp.cos(t1 + t2)],
        [0, 0], [0, 0], [0, 0], [1, 1],
    ])
    assert (J - expected).applyfunc(sp.simplify) == sp.zeros(6, 2)


def test_jacobian_json_shape_of_a_six_joint_arm(cli):
    data = json.loads(cli.ok("jacobian", "puma560", "--format", "json"))
    assert data["shape"] == [6, 6]
    assert len(data["entries"]) == 6
    assert all(len(row) == 6 for row in data["entries"])


def test_jacobian_numeric_substitutes_the_parameters(cli):
    symbolic = cli.latex_line("jacobian", "puma560")
    assert "a_{2}" in symbolic
    numeric = cli.latex_line("jacobian", "puma560", "--numeric")
    assert "0.4318" in numeric
    assert "a_{2}" not in numeric
    assert "d_{4}" not in numeric


def test_jacobian_standalone_is_a_latex_document(cli):
    out = cli.ok("jacobian", "planar2r", "--standalone")
    assert out.lstrip().startswith("%")  # the generated-by comment
    assert r"\documentclass" in out
    assert r"\begin{document}" in out
    assert out.rstrip().endswith(r"\end{document}")
    assert out.index(r"\documentclass") < out.index(r"\begin{document}") < out.index(BMATRIX)
    assert "planar2r" in out
    assert "s_{12}" in out
    assert "{{" not in out  # no unrendered template placeholders
    assert "{%" not in out


# --- show and fk --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("fmt", ["latex", "pretty", "json"])
def test_show_stanford(cli, fmt):
    out = cli.ok("show", "stanford", "--format", fmt)
    if fmt == "json":
        data = json.loads(out)
        assert data["robot"] == "stanford"
        assert len(data["parameter_table"]) == 6
        assert data["dh_table"] == data["parameter_table"]  # the old key, deprecated
        assert {f"T_{i - 1}_{i}" for i in range(1, 7)} <= data["transforms"].keys()
        assert all(len(m) == 4 and all(len(row) == 4 for row in m) for m in data["transforms"].values())
    elif fmt == "pretty":
        assert "stanford" in out
        assert "prismatic" in out
        assert "T_0_1 =" in out
        assert "c₁" in out
    else:
        assert r"\begin{array}" in out
        assert r"{}^{0}_{1}T = " + BMATRIX in out
        assert r"{}^{5}_{6}T = " + BMATRIX in out


@pytest.mark.parametrize("fmt", ["latex", "pretty", "json"])
def test_fk_puma560(cli, fmt):
    out = cli.ok("fk", "puma560", "--format", fmt)
    if fmt == "json":
        data = json.loads(out)
        assert data["robot"] == "puma560"
        assert data["source"] == 0
        assert data["target"] == 6
        assert len(data["entries"]) == 4
        assert data["entries"][3] == ["0", "0", "0", "1"]
        assert data["latex"].startswith(r"{}^{0}_{6}T = " + BMATRIX)  # named as the Jacobian's is
    elif fmt == "pretty":
        assert out.startswith("Pose of frame {6} in frame {0}: the end of the chain, its origin the flange")
        assert "\nT_0_6 =\n" in out
        assert "c₂₃" in out
    else:
        lines = out.splitlines()
        assert len(lines) == 1
        assert lines[0].startswith(r"{}^{0}_{6}T = " + BMATRIX)
        assert "c_{23}" in lines[0]


@pytest.mark.parametrize("command", ["show", "fk"])
def test_show_and_fk_standalone(cli, command):
    out = cli.ok(command, "planar2r", "--standalone")
    assert r"\documentclass" in out
    assert out.rstrip().endswith(r"\end{document}")


def test_fk_numeric(cli):
    out = cli.ok("fk", "planar2r", "--numeric")
    assert "0.5" in out
    assert "0.4" in out
    assert "L_{1}" not in out


# --- output files ---------------------------------------------------------------------------------------------


def test_output_file_is_written_and_stdout_is_empty(cli, tmp_path):
    expected = cli.ok("jacobian", "planar2r")
    target = tmp_path / "J.tex"
    status, out, err = cli.run("jacobian", "planar2r", "-o", str(target))
    assert (status, out, err) == (0, "", "")
    assert target.read_text(encoding="utf-8") == expected
    assert sorted(p.name for p in tmp_path.iterdir()) == ["J.tex"]  # no temporary file left behind


def test_output_file_replaces_an_existing_file(cli, tmp_path):
    target = tmp_path / "fk.json"
    target.write_text("old", encoding="utf-8")
    status, out, _ = cli.run("fk", "planar2r", "--format", "json", "--output", str(target))
    assert (status, out) == (0, "")
    assert json.loads(target.read_text(encoding="utf-8"))["robot"] == "planar2r"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fk.json"]


def test_output_file_relative_to_the_working_directory(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, _ = cli.run("robots", "-o", "robots.txt")
    assert (status, out) == (0, "")
    assert (tmp_path / "robots.txt").read_text(encoding="utf-8").startswith(next(iter(catalog())))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["robots.txt"]


# --- robot files ------------------------------------------------------------------------------------------------


def test_robot_file_path_works_as_robot(cli, tmp_path):
    path = tmp_path / "my_arm.toml"
    path.write_text(robot_to_toml(load_robot("planar2r")), encoding="utf-8")
    from_file = cli.latex_line("jacobian", str(path))
    assert from_file == cli.latex_line("jacobian", "planar2r")
    data = json.loads(cli.ok("show", str(path), "--format", "json"))
    assert data["robot"] == "planar2r"


def test_hand_written_robot_file(cli, tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(
        'name = "arm"\nconvention = "standard"\n\n[parameters]\nl = 2.5\n\n'
        '[[joints]]\ntype = "revolute"\nalpha = 0\na = "l"\nd = 0\ntheta = 0\n',
        encoding="utf-8",
    )
    line = cli.latex_line("jacobian", str(path))
    assert line.startswith(r"{}^{0}J = " + BMATRIX)
    assert "l s_{1}" in line
    assert "2.5" in cli.latex_line("jacobian", str(path), "--numeric")


# --- errors -------------------------------------------------------------------------------------------------


MALFORMED_TOML = 'name = "arm"\n[[joints]\ntype = "revolute"\n'

ERROR_CASES = {
    "unknown robot": ["jacobian", "no_such_robot"],
    "unknown robot for show": ["show", "no_such_robot"],
    "missing robot file": ["fk", "missing.toml"],
    "frame out of range": ["jacobian", "puma560", "--frame", "9"],
    "negative frame": ["jacobian", "puma560", "--frame", "-1"],
    "frame not a number": ["jacobian", "puma560", "--frame", "x"],
    "point with two coordinates": ["jacobian", "planar3r", "--point", "1,2"],
    "point with four coordinates": ["jacobian", "planar3r", "--point", "1,2,3,4"],
    "point with code": ["jacobian", "planar3r", "--point", "__import__('os'),0,0"],
    "point with unknown name": ["jacobian", "planar3r", "--point", "x,0,0"],
    "point with empty coordinate": ["jacobian", "planar3r", "--point", "1,,0"],
    "point unparsable": ["jacobian", "planar3r", "--point", "1,2,("],
    "point named nowhere": ["jacobian", "planar3r", "--point", "elbow"],
    "steps with a screw Jacobian": ["jacobian", "planar3r", "--steps", "--kind", "space"],
    "wrench with five entries": ["torques", "planar2r", "--wrench", "1,2,3,4,5"],
    "wrench with code": ["torques", "planar2r", "--wrench", "1,2,3,4,5,__import__('os')"],
    "configuration of the wrong length": ["torques", "planar2r", "--q", "0.1"],
    "configuration with a parameter": ["torques", "planar2r", "--q", "L1,0"],
}


@pytest.mark.parametrize("argv", ERROR_CASES.values(), ids=ERROR_CASES.keys())
def test_errors_are_one_line_and_exit_2(cli, tmp_path, monkeypatch, argv):
    monkeypatch.chdir(tmp_path)
    assert_one_line_error(*cli.run(*argv))
    # With -o, nothing is written: neither the output file nor a temporary file.
    target = tmp_path / "out.tex"
    assert_one_line_error(*cli.run(*argv, "-o", str(target)))
    assert list(tmp_path.iterdir()) == []


def test_error_mentions_what_is_wrong(cli):
    _, _, err = cli.run("jacobian", "no_such_robot")
    assert "no_such_robot" in err
    assert "puma560" in err  # lists the known robots
    _, _, err = cli.run("jacobian", "puma560", "--frame", "9")
    assert "9" in err
    _, _, err = cli.run("jacobian", "planar3r", "--point", "__import__('os'),0,0")
    assert "--point" in err


@pytest.mark.parametrize("text", [
    MALFORMED_TOML,
    'name = "arm"\n',  # no convention, no joints
    'name = "arm"\nconvention = "standard"\njoints = []\n',
    'name = "arm"\nconvention = "sideways"\n[[joints]]\ntype = "revolute"\nalpha = 0\na = 0\nd = 0\ntheta = 0\n',
    'name = "arm"\nconvention = "standard"\n[[joints]]\ntype = "revolute"\nalpha = 0\na = "L9"\nd = 0\ntheta = 0\n',
    'name = "arm"\nconvention = "standard"\n[[joints]]\ntype = "revolute"\nalpha = "__import__(\'os\')"\n'
    'a = 0\nd = 0\ntheta = 0\n',
], ids=["invalid toml", "no joints key", "empty joints", "bad convention", "unknown parameter", "code in field"])
def test_malformed_robot_file(cli, tmp_path, text):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    status, out, err = cli.run("jacobian", str(path))
    assert_one_line_error(status, out, err)
    assert "bad.toml" in err  # the message names the file
    target = tmp_path / "J.tex"
    assert_one_line_error(*cli.run("jacobian", str(path), "-o", str(target)))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_unreadable_robot_file(cli, tmp_path):
    path = tmp_path / "binary.toml"
    path.write_bytes(b"\xff\xfe\x00garbage")
    assert_one_line_error(*cli.run("fk", str(path)))


def test_failed_run_keeps_an_existing_output_file(cli, tmp_path):
    target = tmp_path / "J.tex"
    target.write_text("previous result\n", encoding="utf-8")
    assert_one_line_error(*cli.run("jacobian", "puma560", "--frame", "9", "-o", str(target)))
    assert target.read_text(encoding="utf-8") == "previous result\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["J.tex"]


def test_output_into_a_missing_directory(cli, tmp_path):
    target = tmp_path / "no" / "such" / "dir" / "J.tex"
    assert_one_line_error(*cli.run("jacobian", "planar2r", "-o", str(target)))
    assert list(tmp_path.iterdir()) == []


def test_output_onto_a_directory_leaves_no_temporary_file(cli, tmp_path):
    (tmp_path / "J.tex").mkdir()
    assert_one_line_error(*cli.run("jacobian", "planar2r", "-o", str(tmp_path / "J.tex")))
    assert [p.name for p in tmp_path.iterdir()] == ["J.tex"]
    assert list((tmp_path / "J.tex").iterdir()) == []


# --- argparse usage errors ------------------------------------------------------------------------------------


@pytest.mark.parametrize("argv", [
    [],
    ["no_such_command"],
    ["jacobian"],
    ["jacobian", "planar2r", "--format", "html"],
    ["jacobian", "planar2r", "--method", "guess"],
    ["robots", "--no-such-option"],
], ids=["no command", "unknown command", "missing robot", "bad format", "bad method", "unknown option"])
def test_usage_errors_exit_2(capsys, argv):
    with pytest.raises(SystemExit) as excinfo:
        main(argv)
    assert excinfo.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert len(err.splitlines()) == 1 and err.startswith("symjac: error: ") and "--help" in err, err


def test_version(capsys):
    with pytest.raises(SystemExit) as excinfo:
        main(["--version"])
    assert excinfo.value.code == 0
    assert capsys.readouterr().out.startswith("symjac ")


def test_help(capsys):
    with pytest.raises(SystemExit) as excinfo:
        main(["jacobian", "--help"])
    assert excinfo.value.code == 0
    out = capsys.readouterr().out
    assert "--frame" in out
    assert "--point" in out


# --- propagation steps and torques ----------------------------------------------------------------------------


@pytest.mark.parametrize("robot", marked(["stanford", "puma560"]))
def test_velocity_propagation_steps_print_every_frame_then_the_jacobian(cli, robot):
    lines = cli.ok("jacobian", robot, "--method", "velocity_propagation", "--steps").splitlines()
    n = load_robot(robot).n_coordinates
    assert len(lines) == 2 * (n + 1) + 1
    for k in range(n + 1):
        assert lines[2 * k].startswith(rf"{{}}^{{{k}}}\omega_{{{k}}} = {BMATRIX}")
        assert lines[2 * k + 1].startswith(rf"{{}}^{{{k}}}v_{{{k}}} = {BMATRIX}")
    assert r"\dot{\theta}_{1}" in lines[2]
    assert lines[-1].startswith(rf"{{}}^{{0}}J = {BMATRIX}")
    assert lines[-1] == cli.latex_line("jacobian", robot)


def test_force_propagation_steps_run_from_the_tip_and_end_with_the_torques(cli):
    lines = cli.ok("jacobian", "stanford", "--method", "force_propagation", "--steps", "--frame", "6").splitlines()
    assert lines[0] == rf"{{}}^{{6}}f_{{6}} = {BMATRIX}f_{{x}}\\f_{{y}}\\f_{{z}}\end{{bmatrix}}"
    assert lines[-3].startswith(r"{}^{0}n_{0} = ")
    assert lines[-2].startswith(r"\tau = ")
    assert "d_{3}" in lines[-2]


def test_steps_at_the_tool_tip_end_in_the_tool_frame(cli):
    out = cli.ok("jacobian", "planar3r", "--method", "velocity_propagation", "--steps", "--point", "tool")
    assert r"{}^{\mathrm{T}}v_{T} = " in out  # frame names upright
    out = cli.ok("jacobian", "planar3r", "--method", "velocity_propagation", "--steps", "--point", "0,L3,0")
    assert r"{}^{3}v_{P} = " in out


def test_steps_in_pretty_and_json_and_numeric(cli):
    out = cli.ok("jacobian", "planar2r", "--method", "velocity_propagation", "--steps", "--format", "pretty")
    assert "ω_2 (in frame 2) =" in out
    assert "L₁⋅θ̇₁" in out  # the rate of joint 1 in Unicode, after the length
    data = json.loads(cli.ok("jacobian", "planar2r", "--method", "force_propagation", "--steps", "--format",
                         "json"))
    assert data["steps"][-1]["latex"].startswith(r"\tau = ")
    assert data["steps"][-1]["name"] == "tau" and len(data["steps"][-1]["entries"]) == 2  # entries, not only LaTeX
    out = cli.ok("jacobian", "planar2r", "--method", "velocity_propagation", "--steps", "--numeric")
    assert "L_{1}" not in out and "0.5" in out


def test_torques_symbolic_in_textbook_form(cli):
    line = cli.latex_line("torques", "planar2r")
    assert line.startswith(r"\tau = ")
    assert "f_{x}" in line and "n_{z}" in line and "s_{12}" in line


def test_torques_numeric_with_a_wrench_and_a_configuration(cli):
    data = json.loads(cli.ok("torques", "planar2r", "--wrench", "1,0,0,0,0,0", "--q", "pi/2,0", "--format",
                         "json"))
    assert [float(t) for t in data["torques"]] == pytest.approx([-0.9, -0.4])
    # the stretched-out arm holds a force along itself with no torque (the lecture slides)
    data = json.loads(cli.ok("torques", "planar2r", "--wrench", "0,2,0,0,0,0", "--q", "pi/2,0", "--format",
                         "json"))
    assert [float(t) for t in data["torques"]] == pytest.approx([0, 0], abs=1e-12)


def test_torques_in_another_frame_and_point(cli):
    tool = cli.latex_line("torques", "planar3r", "--frame", "tool", "--point", "tool")
    wrist = cli.latex_line("torques", "planar3r", "--frame", "tool", "--point", "flange")
    assert tool != wrist and cli.latex_line("torques", "planar3r", "--frame", "tool") == tool  # default: the end
    assert "L_{3}" in tool and "L_{3}" not in wrist


def test_jacobian_with_a_representation_prints_e_and_its_own_singularities(capsys):
    assert main(["jacobian", "puma560", "--representation", "zyz"]) == 0
    out = capsys.readouterr().out
    assert r"\frac{c_{\alpha}}{s_{\beta}}" in out
    assert r"Representation singularity (not kinematic): $s_{\beta} = 0$, that is $\beta = 0$ or $\beta = \pi$" in out
    assert main(["jacobian", "puma560", "--representation", "quaternion", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["E"]) == 7 and data["coordinates"][:3] == ["x", "y", "z"]
    assert main(["jacobian", "puma560", "--representation", "zyz", "--frame", "3"]) == 2
    assert "fixed frame" in capsys.readouterr().err


# --- JSON keys stay as they were before the printing layer was split out ----------------------------------------

META = {"symjac", "robot", "convention", "joint_variables", "parameters"}
JSON_KEYS = {
    ("singularities", "articulated3r"): META | {"rows", "frame", "point", "redundant", "row_minors", "row_choice",
                                                "determinant", "minors", "zero_minors", "sets", "factors"},
    ("jacobian", "planar2r"): META | {"frame", "point", "at", "method", "shape", "rows", "columns", "entries",
                                      "latex"},
    ("show", "stanford"): META | {"parameter_table", "dh_table", "transforms"},
}


@pytest.mark.parametrize(("command", "robot"), sorted(JSON_KEYS))
def test_json_output_round_trips_with_the_same_keys(cli, command, robot):
    out = cli.ok(command, robot, "--format", "json")
    data = json.loads(out)
    assert set(data) == JSON_KEYS[command, robot]
    assert json.dumps(data, indent=2) + "\n" == out
    if command == "singularities":
        assert set(data["determinant"]) == {"expression", "coefficient", "factors", "columns", "rows", "frame"}
        for factor in data["factors"]:
            assert set(factor) == {"expression", "multiplicity", "kind", "reason", "solutions", "existence",
                                   "exists_for_defaults", "sample", "evidence", "lost_direction", "lost", "self_motion",
                                   "self_motion_words", "solution_limits", "reachable_within_limits",
                                   "limits_words"}
        kinds = {factor["kind"] for factor in data["factors"]}
        assert kinds == {"parameter", "elbow", "shoulder"}
        (elbow,) = [factor for factor in data["factors"] if factor["kind"] == "elbow"]
        assert elbow["lost"].startswith("cannot") and len(elbow["lost_direction"]) == len(data["rows"])


def test_no_handler_branches_on_the_format():
    """A handler parses, calls the API and builds a document; only main's renderer looks at --format."""
    import inspect

    import symjac.cli.main as cli

    handlers = {handler for handler, _, _ in cli.COMMANDS.values()}
    handlers |= {cli._representation, cli._derivative, cli._propagation}
    assert len(handlers) > 10
    for handler in handlers:
        assert "args.format" not in inspect.getsource(handler), handler.__name__


def test_printing_package_exports_a_sorted_all():
    import symjac.printing as printing

    # constants first, then classes and functions, as in symjac.__all__ (ruff's RUF022 order)
    assert printing.__all__ == sorted(printing.__all__, key=lambda name: (not name.isupper(), name))
    assert all(hasattr(printing, name) for name in printing.__all__)
    assert {"latex", "pretty", "propagation_steps", "singularity_summary", "render"} <= set(printing.__all__)


def test_numbers_read_as_written(cli):
    """--numeric rounds to --digits after the exact derivation; decimals from files print as written."""
    assert "0.432" in cli.latex_line("jacobian", "puma560", "--numeric", "--digits", "3")
    assert "0.4318" in cli.latex_line("jacobian", "puma560", "--numeric")  # default: 4 significant digits
    fk = cli.latex_line("fk", "ur5.urdf")
    assert "0.089159" in fk and "89159" not in fk.replace("0.089159", "")
    status, _out, err = cli.run("jacobian", "planar2r", "--digits", "3")
    assert status == 2 and "--digits needs --numeric" in err


def test_representation_json_has_the_multiplied_out_jacobian(cli):
    data = json.loads(cli.ok("jacobian", "planar2r", "--representation", "zyz", "--format", "json"))
    assert len(data["J_x"]) == 6 and data["latex"].startswith(r"J_x = E(x)\,J_0 = ")
