"""The progress line of the command line: one rewritten line on a terminal's stderr, nothing anywhere else."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import time
import warnings

import pytest

from symjac import load_robot
from symjac.cli import output
from symjac.cli.main import main
from symjac.kinematics.chain import Chain, clear_caches
from symjac.kinematics.jacobian import jacobian
from symjac.progress import report, reporting_to, within

CLEAR = "\r\x1b[K"


class Terminal(io.StringIO):
    """A stderr that says it is a terminal."""

    def isatty(self) -> bool:
        return True


@pytest.fixture
def prompt(monkeypatch):
    """The progress line without its two-second delay, redrawn often, and every stage kept a moment so it shows."""
    monkeypatch.setattr(output, "PROGRESS_DELAY", 0.0)
    monkeypatch.setattr(output, "PROGRESS_INTERVAL", 0.002)
    listen = output._ProgressLine.listen

    def slow_listen(self, stage):
        listen(self, stage)
        time.sleep(0.01)

    monkeypatch.setattr(output._ProgressLine, "listen", slow_listen)


def _drawn(stream: io.StringIO) -> None:
    """Wait until the line has been drawn once."""
    deadline = time.monotonic() + 5
    while "symjac" not in stream.getvalue() and time.monotonic() < deadline:
        time.sleep(0.002)


def _run(argv, stderr, monkeypatch, capsys):
    clear_caches()  # derive again, so that stages are reported
    capsys.readouterr()
    monkeypatch.setattr(sys, "stderr", stderr)
    status = main(argv)
    monkeypatch.setattr(sys, "stderr", sys.__stderr__)
    return status, capsys.readouterr().out


def test_progress_line_on_a_terminal_only_and_stdout_unchanged(prompt, monkeypatch, capsys):
    terminal, pipe = Terminal(), io.StringIO()
    status, shown = _run(["jacobian", "planar3r"], terminal, monkeypatch, capsys)
    assert status == 0
    written = terminal.getvalue()
    assert written.startswith("\rsymjac jacobian: ")
    assert "Jacobian of planar3r in frame 0, building frame {3} of 3" in written
    assert "\n" not in written  # one line, rewritten in place
    assert written.endswith(CLEAR)  # and gone at the end
    status, piped = _run(["jacobian", "planar3r"], pipe, monkeypatch, capsys)
    assert status == 0
    assert pipe.getvalue() == ""  # not a terminal: nothing at all
    assert shown == piped != ""


def test_the_line_waits_for_the_delay(monkeypatch):
    monkeypatch.setattr(output, "PROGRESS_DELAY", 60.0)
    monkeypatch.setattr(output, "PROGRESS_INTERVAL", 0.002)
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with output.progress_line("fk"):
        report("link 1 of 2")
        time.sleep(0.05)
    assert terminal.getvalue() == ""  # a quick command shows nothing


def test_other_lines_clear_the_progress_line_first(prompt, monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with output.progress_line("jacobian"):
        report("link 1 of 2")
        _drawn(terminal)
        print("symjac: warning: something", file=sys.stderr)
    before, _, after = terminal.getvalue().partition("symjac: warning: something\n")
    assert before.endswith(CLEAR) and "link 1 of 2" in before
    assert after in ("", CLEAR) or after.endswith(CLEAR)
    assert sys.stderr is terminal  # put back


def test_warnings_of_a_command_clear_the_line(prompt, monkeypatch, capsys):
    terminal = Terminal()

    def warn(args):
        report("stage before the warning")
        _drawn(terminal)
        warnings.warn("careful", stacklevel=1)
        return ""

    monkeypatch.setitem(sys.modules["symjac.cli.main"].COMMANDS, "robots", (warn, "", lambda sub, name: None))
    status, _ = _run(["robots"], terminal, monkeypatch, capsys)
    assert status == 0
    before, _, _ = terminal.getvalue().partition("symjac: warning: careful\n")
    assert "stage before the warning" in before and before.endswith(CLEAR)


@pytest.mark.parametrize("error", [KeyboardInterrupt, RuntimeError])
def test_the_line_is_cleared_on_errors_and_ctrl_c(prompt, monkeypatch, error):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with pytest.raises(error), output.progress_line("jacobian"):
        report("joint 3 of 20")
        _drawn(terminal)
        raise error
    assert terminal.getvalue().endswith(CLEAR)
    assert sys.stderr is terminal


def test_interrupted_command_clears_before_its_message(prompt, monkeypatch, capsys):
    terminal = Terminal()

    def interrupted(args):
        report("joint 3 of 20")
        _drawn(terminal)
        raise KeyboardInterrupt

    monkeypatch.setitem(sys.modules["symjac.cli.main"].COMMANDS, "robots", (interrupted, "", lambda sub, name: None))
    status, _ = _run(["robots"], terminal, monkeypatch, capsys)
    assert status == 130
    assert terminal.getvalue().endswith(CLEAR + "symjac: interrupted\n")


def test_a_long_line_is_cut_to_the_terminal_keeping_the_stage(prompt, monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with output.progress_line("jacobian"), within("x" * 200):
        report("joint 3 of 20")
        _drawn(terminal)
    lines = [line.removesuffix("\x1b[K") for line in terminal.getvalue().split("\r") if line.strip("\x1b[K")]
    assert all(len(line) < 80 for line in lines)
    assert lines[-1].endswith("joint 3 of 20")


def test_nested_and_raw_derivations_report_links_and_joints():
    stages: list[str] = []
    with reporting_to(stages.append), within("Jacobian"):
        jacobian(Chain(load_robot("planar3r")), 0, simplify=False)
    assert "Jacobian" in stages
    assert "Jacobian, building frame {3} of 3" in stages
    assert "Jacobian, differentiation, joint 3 of 3" in stages
    stages.clear()
    with reporting_to(stages.append):
        Chain(load_robot("planar3r"), nested=True).transform(0, 3)
    assert [stage for stage in stages if stage.startswith("building")] == [
        "building frame {1} of 3", "building frame {2} of 3", "building frame {3} of 3"]


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_a_real_terminal(tmp_path):
    """The command run with stderr on a pseudo-terminal and stdout on a pipe: the line, then nothing left."""
    leader, follower = os.openpty()
    script = ("import sys; from symjac.cli import output; output.PROGRESS_DELAY = 0.0; "
              "output.PROGRESS_INTERVAL = 0.01; "
              "from symjac.cli.main import main; sys.exit(main(['jacobian', 'planar3r']))")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    with os.fdopen(leader, "rb", buffering=0) as terminal:
        done = subprocess.run([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=follower, env=env,
                              timeout=120, check=False)
        os.close(follower)
        written = b""
        while True:
            try:
                chunk = terminal.read(4096)
            except OSError:  # Linux: the follower is closed, nothing more to read
                break
            if not chunk:
                break
            written += chunk
    assert done.returncode == 0
    assert b"L_{1}" in done.stdout
    assert written.startswith(b"\rsymjac jacobian: ")
    assert b"\n" not in written  # one line, rewritten in place
    assert written.endswith(CLEAR.encode())
