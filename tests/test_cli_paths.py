"""The paths around the main job (issue 14): output paths, URDF chains, one-line failures, options that say no."""

from __future__ import annotations

import json
import os
import stat
import threading

import pytest

import symjac.kinematics.jacobian
from symjac import write_module
from symjac.cli.main import main
from symjac.errors import RobotFileError
from symjac.model.io import catalog, load_robot, urdf_catalog

FK_PLANAR2R = ["fk", "planar2r", "--format", "pretty"]


@pytest.fixture
def expected(cli, capsys: pytest.CaptureFixture[str]) -> str:
    """What ``symjac fk planar2r --format pretty`` prints on stdout."""
    status, out, _ = cli.run(*FK_PLANAR2R)
    assert status == 0 and out.startswith("Pose of frame {2} in frame {0}") and "\nT_0_2 =\n" in out
    return out


@pytest.fixture
def umask_027():
    previous = os.umask(0o027)
    yield
    os.umask(previous)


# --- 1. -o output paths ---------------------------------------------------------------------------------------------


def test_dash_means_stdout(cli, tmp_path, monkeypatch, expected):
    monkeypatch.chdir(tmp_path)
    assert cli.run(*FK_PLANAR2R, "-o", "-") == (0, expected, "")
    assert list(tmp_path.iterdir()) == []  # no file named "-"
    assert cli.run(*FK_PLANAR2R, "-o", "./-") == (0, "", "")  # unless asked for
    assert (tmp_path / "-").read_text(encoding="utf-8") == expected


def test_new_files_follow_the_umask_for_o_and_write_module_alike(cli, tmp_path, umask_027, expected):
    assert cli.run(*FK_PLANAR2R, "-o", str(tmp_path / "fk.txt")) == (0, "", "")
    assert cli.run("codegen", "planar2r", "-o", str(tmp_path / "cli_module.py")) == (0, "", "")
    write_module(tmp_path / "api_module.py", "x = 1\n")
    for name in ("fk.txt", "cli_module.py", "api_module.py"):
        assert stat.S_IMODE((tmp_path / name).stat().st_mode) == 0o640, name
    assert (tmp_path / "fk.txt").read_text(encoding="utf-8") == expected


def test_a_replaced_file_is_a_new_file_with_the_old_mode(cli, tmp_path, expected):
    target = tmp_path / "fk.txt"
    target.write_text("old\n", encoding="utf-8")
    target.chmod(0o604)
    before = target.stat().st_ino
    assert cli.run(*FK_PLANAR2R, "-o", str(target)) == (0, "", "")
    assert target.read_text(encoding="utf-8") == expected
    assert stat.S_IMODE(target.stat().st_mode) == 0o604
    assert target.stat().st_ino != before  # renamed into place, so a reader never sees half a file
    assert [p.name for p in tmp_path.iterdir()] == ["fk.txt"]


@pytest.mark.parametrize("existing", [True, False], ids=["to a file", "dangling"])
def test_a_symlink_is_written_through_and_stays_a_link(cli, tmp_path, expected, existing):
    real = tmp_path / "real" / "fk.txt"
    real.parent.mkdir()
    if existing:
        real.write_text("old\n", encoding="utf-8")
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    assert cli.run(*FK_PLANAR2R, "-o", str(link)) == (0, "", "")
    assert link.is_symlink() and link.readlink() == real
    assert real.read_text(encoding="utf-8") == expected
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["fk.txt", "link.txt", "real"]


def test_a_fifo_is_written_through_not_replaced(cli, tmp_path, expected):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    received: list[str] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_text(encoding="utf-8")), daemon=True)
    reader.start()
    assert cli.run(*FK_PLANAR2R, "-o", str(fifo)) == (0, "", "")
    reader.join(timeout=10)
    assert received == [expected]
    assert stat.S_ISFIFO(fifo.stat().st_mode)
    assert [p.name for p in tmp_path.iterdir()] == ["pipe"]


def test_a_process_stream_is_written_through(tmp_path, expected):
    # /dev/stdout is /proc/self/fd/1; with stdout redirected to a file, that resolves to the file, and renaming over
    # it would leave the text where the shell's descriptor no longer points. The test uses its own descriptor under
    # /proc/self/fd rather than /dev/stdout, so that a regression can never replace a node in /dev.
    redirected = tmp_path / "stdout.txt"
    with open(redirected, "w", encoding="utf-8") as stream:
        status = main([*FK_PLANAR2R, "-o", f"/proc/self/fd/{stream.fileno()}"])
        written = os.fstat(stream.fileno())
    assert status == 0
    assert written.st_ino == redirected.stat().st_ino
    assert redirected.read_text(encoding="utf-8") == expected


def test_a_directory_is_refused_in_one_line(cli, tmp_path):
    line = cli.one_line_error(*FK_PLANAR2R, "-o", str(tmp_path))
    assert line == f"symjac: error: {tmp_path}: is a directory, not a file"
    assert list(tmp_path.iterdir()) == []


def test_errors_name_the_users_path_not_the_temporary_file(cli, tmp_path, monkeypatch):
    def full_disk(source, destination):
        raise OSError(28, "No space left on device", source, destination)

    monkeypatch.setattr(os, "replace", full_disk)
    target = tmp_path / "fk.txt"
    line = cli.one_line_error(*FK_PLANAR2R, "-o", str(target))
    assert line == f"symjac: error: {target}: No space left on device"
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(OSError, match="No space") as caught:
        write_module(target, "x = 1\n")
    assert caught.value.filename == str(target) and caught.value.filename2 is None


def test_missing_folder_names_the_path(cli, tmp_path):
    target = tmp_path / "missing" / "fk.txt"
    assert cli.one_line_error(*FK_PLANAR2R, "-o", str(target)) == \
        f"symjac: error: {target}: No such file or directory"


# --- 2. --base-link / --tip-link on every command that takes ROBOT --------------------------------------------------

COMMANDS = {
    "show": [], "fk": [], "jacobian": [], "hessian": [], "torques": [], "singularities": [], "codegen": [],
    "convert": ["--to", "toml"],
}


@pytest.mark.parametrize("command", COMMANDS)
def test_every_robot_command_takes_the_urdf_chain(cli, gripper, command):
    line = cli.one_line_error(command, gripper, *COMMANDS[command])
    assert "choose --tip-link" in line and "finger_a, finger_b" in line
    status, out, err = cli.run(command, gripper, *COMMANDS[command], "--tip-link", "finger_a")
    assert (status, err) == (0, "") and out
    status, out, err = cli.run(command, gripper, *COMMANDS[command], "--base-link", "l1", "--tip-link",
                           "flange")
    assert (status, err) == (0, "") and out


def test_the_links_decide_the_chain(cli, gripper):
    def data(*argv: str) -> dict:
        status, out, err = cli.run(*argv, "--format", "json")
        assert (status, err) == (0, "")
        return json.loads(out)

    to_flange = data("fk", gripper, "--tip-link", "flange")
    to_finger = data("fk", gripper, "--tip-link", "finger_a")
    # finger_a sits 0.02 along the flange's y and 0.05 along its z: the orientation is the same, the position is not
    assert [row[:3] for row in to_flange["entries"]] == [row[:3] for row in to_finger["entries"]]
    assert [row[3] for row in to_flange["entries"]] != [row[3] for row in to_finger["entries"]]
    assert data("jacobian", gripper, "--tip-link", "flange")["shape"] == [6, 2]
    assert data("jacobian", gripper, "--base-link", "l1", "--tip-link", "flange")["shape"] == [6, 1]


@pytest.mark.parametrize("option", ["--tip-link", "--base-link"])
@pytest.mark.parametrize("command", COMMANDS)
def test_links_are_refused_for_a_toml_robot(cli, command, option):
    line = cli.one_line_error(command, "planar2r", *COMMANDS[command], option, "tip")
    assert line == f"symjac: error: {option} applies to URDF and MJCF files only; 'planar2r' is not one"


# A URDF whose links are called like the options: base_link (the most common URDF link name) and tip_link.
NAMED_LIKE_OPTIONS = """<robot name="arm"><link name="base_link"/><link name="tip_link"/><link name="{odd}"/>
  <link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1"/></joint>
  <joint name="j2" type="fixed"><parent link="l1"/><child link="tip_link"/><origin xyz="0.5 0 0"/></joint>
  <joint name="j3" type="fixed"><parent link="l1"/><child link="{odd}"/></joint></robot>"""


@pytest.mark.parametrize(("options", "expected"), [
    ((), "choose --tip-link: the links without children below 'base_link' are tip_link, {odd}"),
    (("--tip-link", "nowhere"), "--tip-link 'nowhere' is not a link of this robot (links: base_link, l1, tip_link, "
                                "{odd})"),
    (("--base-link", "tip_link", "--tip-link", "base_link"), "--tip-link 'base_link' is not below --base-link "
                                                             "'tip_link'"),
])
def test_error_text_keeps_the_users_link_names(cli, tmp_path, options, expected):
    path = tmp_path / "arm.urdf"
    path.write_text(NAMED_LIKE_OPTIONS, encoding="utf-8")
    assert cli.one_line_error("fk", str(path), *options) == f"symjac: error: {path}: {expected}"
    # from Python, the arguments are named as Python names them, and the link names are the same
    with pytest.raises(RobotFileError) as info:
        load_robot(path, **{option[2:].replace("-", "_"): value
                            for option, value in zip(options[::2], options[1::2], strict=True)})
    python = expected.replace("--tip-link", "tip_link").replace("--base-link", "base_link")
    assert str(info.value) == f"{path}: {python}"


def test_help_names_all_three_kinds_of_robot(capsys):
    for command in COMMANDS:
        with pytest.raises(SystemExit):
            main([command, "--help"])
        text = " ".join(capsys.readouterr().out.split())
        assert "a robot file (TOML robot file, URDF" in text and "--tip-link" in text and "--base-link" in text, command


# --- 3. every failure is one line -----------------------------------------------------------------------------------


def test_a_huge_integer_in_a_robot_file_is_one_line_naming_file_and_field(cli, tmp_path):
    path = tmp_path / "huge.toml"
    path.write_text('name = "huge"\nconvention = "standard"\n\n[parameters]\nL1 = ' + "1" * 5000 + "\n\n"
                    '[[joints]]\ntype = "revolute"\nalpha = 0\na = "L1"\nd = 0\ntheta = 0\n', encoding="utf-8")
    line = cli.one_line_error("fk", str(path))
    assert line.startswith(f"symjac: error: {path}, field 'L1': integer with 5000 digits on line 5")


def test_ctrl_c_during_a_derivation_is_one_line_and_status_130(cli, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(symjac.kinematics.jacobian, "jacobian", interrupted)
    try:
        result = cli.run("jacobian", "planar2r")
    except KeyboardInterrupt:  # pragma: no cover - only when the CLI lets it through
        pytest.fail("Ctrl-C escaped symjac.cli.main.main")
    assert result == (130, "", "symjac: interrupted\n")


@pytest.mark.parametrize(("error", "message"), [
    (ValueError("Exceeds the limit (4300 digits)\nfor integer string conversion"),
     "ValueError: Exceeds the limit (4300 digits) for integer string conversion"),
    (RecursionError("maximum recursion depth exceeded"), "the input is nested too deeply to process"),
    (ZeroDivisionError("division by zero"), "ZeroDivisionError: division by zero"),
])
def test_unexpected_errors_are_one_line(cli, monkeypatch, error, message):
    def failing(*args, **kwargs):
        raise error

    monkeypatch.setattr(symjac.kinematics.jacobian, "jacobian", failing)
    assert cli.one_line_error("jacobian", "planar2r") == f"symjac: error: {message}"
    monkeypatch.setenv("SYMJAC_TRACEBACK", "1")  # a developer can still see where it came from
    with pytest.raises(type(error)):
        main(["jacobian", "planar2r"])


def test_a_closed_stdout_ends_quietly(capsys, monkeypatch):
    read_end, write_end = os.pipe()
    os.close(read_end)  # as `| head -1` does once it has its line
    with open(write_end, "w", encoding="utf-8") as closed:
        monkeypatch.setattr("sys.stdout", closed)
        status = main(["show", "planar2r"])
        monkeypatch.undo()
    assert status == 141
    assert capsys.readouterr().err == ""


# --- 4. messages a person understands -------------------------------------------------------------------------------


def test_q_says_plainly_what_it_takes(cli):
    line = cli.one_line_error("torques", "planar2r", "--q", "L1,0")
    assert "none declared" not in line
    assert line == ("symjac: error: --q takes numbers and expressions with pi only (joint angles in radians, "
                    "prismatic offsets in metres), got 'L1'")
    assert cli.run("torques", "planar2r", "--q", "pi/2, -pi/4")[0] == 0


def test_wrench_takes_parameter_names(cli):
    status, out, _ = cli.run("torques", "planar2r", "--wrench", "L1,0,0,0,0,0", "--format", "pretty")
    assert status == 0 and "L₁" in out


@pytest.mark.parametrize("command", ["codegen", "singularities"])
def test_a_repeated_row_is_named(cli, command):
    line = cli.one_line_error(command, "planar2r", "--rows", "v_x,v_y,v_x")
    assert line == "symjac: error: --rows: rows must not repeat: v_x is given twice in v_x, v_y, v_x"


@pytest.mark.parametrize(("argv", "message"), [
    (["jacobian", "planar2r", "--position", "cylindrical"], "--position needs --representation"),
    (["jacobian", "planar2r", "--standalone", "--format", "json"],
     "--standalone applies to --format latex only, not --format json"),
    (["fk", "planar2r", "--standalone", "--format", "pretty"],
     "--standalone applies to --format latex only, not --format pretty"),
    (["jacobian", "planar2r", "--derivative", "--method", "cross_product"],
     "--method cross_product does not apply with --derivative"),
    (["jacobian", "planar2r", "--representation", "zyz", "--method", "velocity_propagation"],
     "--method velocity_propagation does not apply with --representation"),
    (["jacobian", "planar2r", "--representation", "zyz", "--steps"], "--steps does not apply with --representation"),
    (["jacobian", "planar2r", "--steps", "--kind", "body"], "--kind body does not take --steps"),
])
def test_options_that_would_be_ignored_are_refused(cli, argv, message):
    assert cli.one_line_error(*argv).startswith(f"symjac: error: {message}")


def test_position_with_a_representation_still_works(cli):
    status, out, err = cli.run("jacobian", "articulated3r", "--representation", "zyz", "--position",
                           "cylindrical", "--format", "json")
    assert (status, err) == (0, "") and "cylindrical" in out


def test_robot_descriptions_speak_to_a_user():
    for name, description in {**catalog(), **urdf_catalog()}.items():
        assert "seed" not in description and "section" not in description, name
        assert "\n" not in description and 20 < len(description) <= 120, name
