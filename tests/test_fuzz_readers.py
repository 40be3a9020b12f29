"""Fuzzing the readers: any input gives a robot (or an expression) or a typed error, quickly, never a hang.

The readers are what symjac shows the outside world: TOML robot files (:func:`symjac.robot_from_toml`), URDF
(:func:`symjac.robot_from_urdf`), MJCF (:func:`symjac.robot_from_mjcf`, its includes read from the test fixtures'
folder) and the field-expression parser (:func:`symjac.model.expressions.parse_expression`). Each gets random input
and the catalog's own files (for MJCF, the test fixtures) mutated (slices deleted, duplicated or replaced, lines
dropped or repeated, numbers swapped for hostile ones: ``1e999999``, 5000 nines, 10 000 nested parentheses, ...).
The answer must be a result or a :class:`~symjac.errors.SymjacError` within :data:`LIMIT` seconds; an alarm stops a
hang.

By default (profile ``symjac``) each test runs :data:`EXAMPLES` derandomized examples, a few seconds in all;
``HYPOTHESIS_PROFILE=explore`` draws many new ones (it found the crashes listed in the module's tests below).
"""

from __future__ import annotations

import os
import re
import signal
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from importlib import resources
from pathlib import Path
from typing import Any

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symjac import Robot, robot_from_toml, robot_from_urdf, robot_to_toml
from symjac.errors import SymjacError
from symjac.model.expressions import parse_expression, snap_angle
from symjac.model.readers.mjcf import robot_from_mjcf

PARENT = ".." + "/"  # the parent folder, spelt in pieces: the repository names no path outside itself

EXPLORE = os.environ.get("HYPOTHESIS_PROFILE") == "explore"
EXAMPLES = 2000 if EXPLORE else 60
LIMIT = 2.0  # seconds per example: generous against a slow machine, far below a hang
FUZZ = settings(max_examples=EXAMPLES, suppress_health_check=list(HealthCheck))

_ROBOTS = resources.files("symjac.robots")
TOML_SEEDS = sorted(e.read_text(encoding="utf-8") for e in _ROBOTS.iterdir() if e.name.endswith(".toml"))
URDF_SEEDS = sorted(e.read_text(encoding="utf-8") for e in _ROBOTS.joinpath("urdf").iterdir()
                    if e.name.endswith(".urdf"))
MJCF_FOLDER = Path(__file__).parent / "data" / "mjcf"
MJCF_SEEDS = sorted([(MJCF_FOLDER / "frames.xml").read_text(encoding="utf-8"),
                     (MJCF_FOLDER / "classes.xml").read_text(encoding="utf-8"),
                     (MJCF_FOLDER / "arm6" / "arm6.xml").read_text(encoding="utf-8")
                     .replace('file="arm6_defaults.xml"', 'file="arm6/arm6_defaults.xml"')])
NAMES = {name: sp.Symbol(name, real=True) for name in ("L1", "L2", "a2", "d4")}
EXPRESSION_SEEDS = ["-pi/2", "L1 + L2", "0.4318", "a2*(L1 - 0.02)/3", "pi/12 + d4**2", "-(L1/2)**-3"]

HOSTILE = [
    "(" * 10_000 + "1" + ")" * 10_000, "[" * 10_000, "{" * 5_000, "-" * 5_000 + "1", "1e999999", "-1e999999",
    "1e-999999", "9" * 5000, "9" * 5000 + ".5", "0." + "0" * 5000 + "1", "nan", "inf", "-inf", "1_000", "0x10",
    "(9**8)**8", "((9**8)**8)**8", "2**-8", "L1**8*L1", "1/0", "L1/(L1 - L1)", "0**-1", "1j", "True", "None",
    "__import__('os')", "\x00", "\ufeff", "\u202e", "\\u0000", "${L}", "$(find arm)", "<xacro:property/>",
    "<!DOCTYPE robot>", "<!ENTITY x 'y'>", "&amp;", "&#0;", "&x;", "<![CDATA[x]]>", "]]>", "<?xml?>", "<", ">",
    "\"", "'", "'''", '"""', "=", "[[joints]]", "[parameters]", "\n", "#", "1e308", "1.7976931348623157e308",
    "4.9e-324", str(10**39), "-0.0", "1e40", '<include file="' + PARENT + PARENT + 'etc/passwd"/>',
    '<include file="/etc/passwd"/>',
    '<include file="classes.xml"/>', "<replicate/>", '<joint type="ball"/>', '<freejoint/>', 'childclass="x"',
]
# the same, as TOML strings (robot-file expressions) and numbers TOML reads: they get past the TOML parser
VALUES = [*HOSTILE, *(f'"{h}"' for h in HOSTILE if '"' not in h and "\\" not in h and len(h) < 300),
          str(10**400), "1e999", "-1e-999", '"L1 / (L2 - L2)"', '"pi**8 * pi"', '"(L1 + 1e308) * 1e308"',
          '"0.1 + 0.2"', '"1e-300 * 1e-300"', '"-(-(-(-(1))))"']
_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:[eE]-?\d+)?")
_VALUE = re.compile(r"(?<= = )[^\n]+|(?<==\")[^\"]*")


MUTATIONS = ("delete", "repeat", "replace", "insert", "line", "number", "value")


class Hang(Exception):
    """An example ran past the alarm: the reader hangs (or is hopelessly slow) on it."""


@contextmanager
def _alarm(seconds: float) -> Iterator[None]:
    """Raise :class:`Hang` after ``seconds`` of wall-clock time (where SIGALRM exists; else only timed)."""
    if not hasattr(signal, "setitimer"):  # pragma: no cover - Windows
        yield
        return

    def ring(signum: int, frame: Any) -> None:
        raise Hang(f"no answer after {seconds} s")

    previous = signal.signal(signal.SIGALRM, ring)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def answers(read: Callable[[], Any]) -> Any:
    """Call ``read``: its result, or ``None`` for a typed error; any other exception, a hang or slowness fails."""
    start = time.perf_counter()
    try:
        with _alarm(5 * LIMIT):
            result = read()
    except SymjacError:
        result = None
    elapsed = time.perf_counter() - start
    assert elapsed < LIMIT, f"the reader took {elapsed:.2f} s"
    return result


@st.composite
def mutated(draw: st.DrawFn, seeds: list[str], kinds: tuple[str, ...] = MUTATIONS) -> str:
    """A seed file with one to four mutations: slices and lines deleted, repeated or replaced, hostile numbers."""
    text = draw(st.sampled_from(seeds))
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(kinds))
        start = draw(st.integers(0, len(text)))
        end = draw(st.integers(start, min(len(text), start + 200)))
        if kind == "delete":
            text = text[:start] + text[end:]
        elif kind == "repeat":
            text = text[:end] + text[start:end] * draw(st.integers(1, 3)) + text[end:]
        elif kind == "replace":
            text = text[:start] + draw(st.text(max_size=20)) + text[end:]
        elif kind == "insert":
            text = text[:start] + draw(st.sampled_from(HOSTILE)) + text[start:]
        elif kind == "line":
            lines = text.splitlines(keepends=True) or [""]
            index = draw(st.integers(0, len(lines) - 1))
            action = draw(st.sampled_from(["drop", "repeat", "swap"]))
            if action == "drop":
                del lines[index]
            elif action == "repeat":
                lines.insert(index, lines[index])
            else:
                other = draw(st.integers(0, len(lines) - 1))
                lines[index], lines[other] = lines[other], lines[index]
            text = "".join(lines)
        else:  # a number, a TOML value or an XML attribute value becomes a hostile one
            places = list((_NUMBER if kind == "number" else _VALUE).finditer(text))
            if places:
                match = draw(st.sampled_from(places))
                text = text[:match.start()] + draw(st.sampled_from(VALUES)) + text[match.end():]
    return text


def _check_toml(text: str) -> None:
    robot = answers(lambda: robot_from_toml(text, source="fuzz.toml"))
    if robot is not None:
        assert isinstance(robot, Robot)
        # what was read is written back and read again to the same robot
        assert answers(lambda: robot_from_toml(robot_to_toml(robot))) == robot


def _check_urdf(content: str | bytes) -> None:
    robot = answers(lambda: robot_from_urdf(content, source="fuzz.urdf"))
    # not read back from TOML: merged fixed joints can give rotations the robot-file grammar cannot write (sin, cos)
    assert robot is None or isinstance(robot, Robot)


@FUZZ
@given(st.one_of(mutated(TOML_SEEDS), mutated(TOML_SEEDS, ("number", "value")), st.text(max_size=300),
                 st.sampled_from(HOSTILE)))
def test_toml_reader_gives_a_robot_or_a_typed_error(text):
    _check_toml(text)


def _check_mjcf(content: str | bytes) -> None:
    robot = answers(lambda: robot_from_mjcf(content, source="fuzz.xml", folder=MJCF_FOLDER))
    assert robot is None or isinstance(robot, Robot)


@FUZZ
@given(st.one_of(mutated(URDF_SEEDS), mutated(URDF_SEEDS, ("number", "value")), st.text(max_size=300),
                 st.sampled_from(HOSTILE)))
def test_urdf_reader_gives_a_robot_or_a_typed_error(text):
    _check_urdf(text)


@FUZZ
@given(st.one_of(st.binary(max_size=300), mutated(URDF_SEEDS).map(lambda t: t.encode("utf-8", "surrogatepass"))))
def test_urdf_reader_takes_any_bytes(data):
    _check_urdf(data)


@FUZZ
@given(st.one_of(mutated(MJCF_SEEDS), mutated(MJCF_SEEDS, ("number", "value")), st.text(max_size=300),
                 st.sampled_from(HOSTILE)))
def test_mjcf_reader_gives_a_robot_or_a_typed_error(text):
    _check_mjcf(text)


@FUZZ
@given(st.one_of(st.binary(max_size=300), mutated(MJCF_SEEDS).map(lambda t: t.encode("utf-8", "surrogatepass"))))
def test_mjcf_reader_takes_any_bytes(data):
    _check_mjcf(data)


@pytest.mark.parametrize("seed", range(len(MJCF_SEEDS)))
def test_every_mjcf_seed_reads_within_the_limit(seed):
    assert isinstance(answers(lambda: robot_from_mjcf(MJCF_SEEDS[seed], folder=MJCF_FOLDER)), Robot)


@FUZZ
@given(st.one_of(mutated(EXPRESSION_SEEDS), st.text(max_size=60), st.sampled_from(HOSTILE),
                 st.lists(st.sampled_from([*NAMES, "pi", "+", "-", "*", "/", "**", "(", ")", "0.5", "8", "-9", " "]),
                          max_size=40).map("".join)))
def test_expression_parser_gives_an_expression_or_a_typed_error(text):
    expr = answers(lambda: parse_expression(text, NAMES))
    if expr is not None:
        assert isinstance(expr, sp.Expr)
        assert expr.free_symbols <= set(NAMES.values())
        assert not expr.has(sp.zoo, sp.nan, sp.oo, -sp.oo)


@pytest.mark.parametrize("seed", range(len(TOML_SEEDS)))
def test_every_catalog_file_reads_within_the_limit(seed):
    assert isinstance(answers(lambda: robot_from_toml(TOML_SEEDS[seed])), Robot)


# --- what the fuzzer found, kept as plain examples ----------------------------------------------------------------

_GENERAL = """name = "g"
convention = "general"

[[joints]]
type = "revolute"
axis = {axis}
"""


def test_huge_urdf_angle_is_not_snapped_and_does_not_overflow():
    large = URDF_SEEDS[0].replace('rpy="0 0 0"', 'rpy="1e8 0 0"', 1)
    assert large != URDF_SEEDS[0]
    assert answers(lambda: robot_from_urdf(large)) is None  # beyond 1000 rad: refused as a unit error
    with pytest.raises(SymjacError, match=r"rpy: 1e\+308 rad is larger than"):  # was OverflowError in snap_angle
        robot_from_urdf(large.replace('rpy="1e8 0 0"', 'rpy="1e308 0 0"'))
    assert snap_angle(sp.Integer(10**400)) == 10**400


def test_huge_general_axis_in_toml_does_not_overflow():
    robot = answers(lambda: robot_from_toml(_GENERAL.format(axis="[1e308, 0, 1]")))  # was OverflowError
    assert isinstance(robot, Robot) and robot.joints[0].placement.axis == (10**308, 0, 1)
    with pytest.raises(SymjacError, match="zero vector"):
        robot_from_toml(_GENERAL.format(axis="[1e-12, 0, 0]"))


def test_expression_that_cannot_be_written_back_is_refused_when_read():
    # 1e-300 * 1e-300 is 1/10**600 exactly: robot_to_toml would write 600 digits, which the reader refuses
    with pytest.raises(SymjacError, match=r"joint 1, field 'd': '1e-300 \* 1e-300' is 605 characters long written"):
        robot_from_toml(_GENERAL.format(axis="[0, 0, 1]") + 'd = "1e-300 * 1e-300"\n')
    assert parse_expression("0.123456789**8", NAMES) == sp.Rational(123456789, 10**9) ** 8  # long, but writable


def test_huge_urdf_rpy_on_merged_fixed_joints_is_refused():
    urdf = URDF_SEEDS[0].replace('rpy="0 0 -0.7853981633974483"', 'rpy="0 1e308 -0.7853981633974483"')
    assert urdf != URDF_SEEDS[0]
    with pytest.raises(SymjacError, match=r"joint panda_hand_joint origin'?: rpy: 1e\+308 rad is larger than 1000 rad"):
        robot_from_urdf(urdf)  # was a TypeError deep in SymPy
