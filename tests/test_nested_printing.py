"""Nested results (generic geometry) in every format: intermediates named w_1, w_2, ... and defined once.

Generic robots are small robot files written here: a 3-joint standard-DH arm whose results are written out, a
6-joint one with twists near (not at) pi/2 whose results stay nested, and a 4-joint product of exponentials with
calibrated-looking screw axes. The JSON form is checked by evaluating its definitions in order and comparing the
entries with the Python result at a random configuration.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symjac.cli.main import main
from symjac.kinematics.acceleration import hessian
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.screws import body_jacobian
from symjac.model.io import load_robot
from symjac.printing.document import Block, Document, Equation, blocks_as_pairs, render
from symjac.printing.nested import named_document, spare_letter
from symjac.printing.results import jacobian_document
from symjac.report.content import block_html
from symjac.symbolic import nested
from symjac.symbolic.nested import Intermediate, NestedMatrix

GENERIC3 = """\
name = "generic3"
convention = "standard"
[[joints]]
type = "revolute"
a = 0.31
d = 0.12
alpha = 1.2
[[joints]]
type = "revolute"
a = 0.4
d = -0.2
alpha = -0.7
[[joints]]
type = "prismatic"
theta = 0.3
a = 0.1
alpha = 2.1
"""

_SIX = [(0.05, 0.33, 1.5702), (0.44, 0.01, 0.003), (0.035, 0.0, 1.5712), (0.001, 0.42, -1.5699),
        (0.0, 0.002, 1.5705), (0.0, "L6", 0.0)]
GENERIC6 = 'name = "generic6"\nconvention = "standard"\n[parameters]\nL6 = 0.08\n' + "".join(
    f'[[joints]]\ntype = "revolute"\na = {a}\nd = {d if isinstance(d, float) else repr(d).replace(chr(39), chr(34))}'
    f"\nalpha = {alpha}\n" for a, d, alpha in _SIX)

POE4 = """\
name = "generic_poe4"
convention = "poe"
[home]
matrix = [[1, 0, 0, 0.5], [0, 1, 0, 0.1], [0, 0, 1, 0.4], [0, 0, 0, 1]]
[[joints]]
type = "revolute"
screw = [0.6190263091772219, -0.7750329395999144, 0.127005397844115, 0.07750329395999145, 0.06190263091772219, 0.0]
[[joints]]
type = "revolute"
screw = [-0.7495021212057638, -0.5976030246413956, -0.2848108060581902, 0.17928090739241867, -0.2106100960588196, \
-0.02988015123206978]
[[joints]]
type = "revolute"
screw = [-0.9139611574761936, -0.10499553778446424, -0.39198334106199983, 0.028908771403322486, -0.2022914027980678, \
-0.013219438185815401]
[[joints]]
type = "revolute"
screw = [0.9922093782705537, 0.06701414147593458, -0.10502216201452433, -0.032056764691100054, 0.44414372421475745, \
-0.019454105249357125]
"""

NUMBER = re.compile(r"\d+\.\d+")


def long_numbers(text: str) -> list[str]:
    """The decimals in ``text`` with more than 6 significant digits (but 0.9999998, which 6 digits would make 1)."""
    return [n for n in NUMBER.findall(text) if len(n.replace(".", "").lstrip("0")) > 6
            and not float(f"{float(n):.6g}").is_integer()]


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("generic")
    paths = {}
    for name, text in (("generic3", GENERIC3), ("generic6", GENERIC6), ("poe4", POE4)):
        (folder / f"{name}.toml").write_text(text, encoding="utf-8")
        paths[name] = str(folder / f"{name}.toml")
    return paths


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> str:
    assert main(list(argv)) == 0, capsys.readouterr().err
    return capsys.readouterr().out


def evaluated(data: dict, values: dict[str, float]) -> dict[str, float]:
    """Every definition of a JSON result, evaluated in order at ``values`` (joint variables by name)."""
    env = dict(values)
    for name, text in data.get("definitions", []):
        env[name] = _number(text, env)
    return env


def _number(text: str, env: dict[str, float]) -> float:
    expr = sp.sympify(text)
    return float(expr.subs({s: env[s.name] for s in expr.free_symbols}))


def _configuration(robot, seed: int = 7) -> dict[sp.Symbol, float]:
    rng = np.random.default_rng(seed)
    return {q: float(rng.uniform(-2.0, 2.0)) for q in robot.q}


def _json_matrix(data: dict, key: str, env: dict[str, float]) -> np.ndarray:
    return np.array([[_number(entry, env) for entry in row] for row in data[key]], dtype=float)


def test_generic_jacobian_is_nested_and_its_json_round_trips(files, capsys):
    robot = load_robot(files["generic6"])
    J = jacobian(robot)
    assert isinstance(J, NestedMatrix)
    data = json.loads(run(capsys, "jacobian", files["generic6"], "--format", "json"))
    names = [name for name, _ in data["definitions"]]
    assert names == [f"w_{k}" for k in range(1, len(names) + 1)]
    assert any("w_" in entry for row in data["entries"] for entry in row)
    assert any(len(n) > 15 for _, text in data["definitions"] for n in long_numbers(text))  # full precision
    values = _configuration(robot)
    env = evaluated(data, {str(q): v for q, v in values.items()} | {"L6": 0.08})
    expected = np.array(J.subs(robot.defaults).subs(values).evalf(), dtype=float)
    assert np.allclose(_json_matrix(data, "entries", env), expected, atol=1e-12)


def test_body_jacobian_of_a_generic_poe_arm_round_trips(files, capsys):
    robot = load_robot(files["poe4"])
    data = json.loads(run(capsys, "jacobian", files["poe4"], "--kind", "body", "--format", "json"))
    assert data["definitions"]
    values = _configuration(robot, 3)
    env = evaluated(data, {str(q): v for q, v in values.items()})
    expected = np.array(body_jacobian(robot).subs(values).evalf(), dtype=float)
    assert np.allclose(_json_matrix(data, "entries", env), expected, atol=1e-12)


def test_hessian_json_of_a_generic_arm_round_trips(files, capsys):
    robot = load_robot(files["generic6"])
    data = json.loads(run(capsys, "hessian", files["generic6"], "--format", "json"))
    values = _configuration(robot, 5)
    env = evaluated(data, {str(q): v for q, v in values.items()} | {"L6": 0.08})
    H = hessian(robot).subs(robot.defaults)
    q3 = str(robot.q[2])
    expected = np.array([[float(H[i, j, 2].subs(values)) for j in range(6)] for i in range(6)])
    assert np.allclose(_json_matrix(data["slices"], q3, env), expected, atol=1e-12)


@pytest.mark.parametrize("command", [["fk"], ["jacobian", "--frame", "2"], ["jacobian", "--link", "4", "--point",
                                                                                "0.1,0.2,0.3"],
                                     ["hessian"], ["torques"], ["jacobian", "--derivative"]])
def test_latex_and_pretty_define_each_intermediate_once_with_readable_numbers(files, capsys, command, monkeypatch):
    monkeypatch.setattr(nested, "INLINE_LIMIT", 1000)  # every one of these results nested
    tex = run(capsys, command[0], files["generic6"], *command[1:])
    assert r"\text{where } \begin{aligned}[t]" in tex and "w_{1} &= " in tex
    assert not long_numbers(tex)
    defined = re.findall(r"^(w_\{\d+\}) &= ", tex, flags=re.MULTILINE)
    assert len(defined) == len(set(defined))  # each once, in order
    assert defined == [f"w_{{{k}}}" for k in range(1, len(defined) + 1)]
    used = set(re.findall(r"w_\{\d+\}", tex))
    assert used == set(defined)
    text = run(capsys, command[0], files["generic6"], *command[1:], "--format", "pretty")
    assert "\nwhere\nw₁ = " in text
    assert not long_numbers(text)


def test_small_generic_results_are_written_out_with_short_numbers(files, capsys):
    tex = run(capsys, "jacobian", files["generic3"])
    assert "where" not in tex and "w_{" not in tex
    assert "0.644218 s_{2}" in tex and not long_numbers(tex)
    assert "definitions" not in json.loads(run(capsys, "jacobian", files["generic3"], "--format", "json"))


def test_textbook_results_print_as_before(capsys):
    data = json.loads(run(capsys, "jacobian", "puma560", "--format", "json"))
    assert "definitions" not in data
    tex = run(capsys, "jacobian", "planar2r")
    assert "where" not in tex and "gathered" not in tex


def test_the_same_input_prints_the_same_bytes(files, capsys):
    here = run(capsys, "jacobian", files["generic6"], "--frame", "2")
    there = subprocess.run([sys.executable, "-m", "symjac", "jacobian", files["generic6"], "--frame", "2"],
                           capture_output=True, text=True, check=True, cwd=Path(__file__).parent.parent).stdout
    assert here == there


def test_the_letter_avoids_the_robot_s_own_symbols(files, tmp_path, capsys):
    path = tmp_path / "w_arm.toml"
    path.write_text(GENERIC6.replace("L6", "w"), encoding="utf-8")
    tex = run(capsys, "jacobian", str(path))
    assert "u_{1} &= " in tex and not re.search(r"w_\{\d", tex)
    assert spare_letter(["w", "u_3", "theta1"]) == "z"
    assert spare_letter(["w_a", "width"]) == "w"


def test_named_document_numbers_across_equations_and_keeps_plain_ones(files):
    robot = load_robot(files["generic6"])
    J = jacobian(robot)
    x = sp.Symbol("x")
    plain = Document("t", "r", (Block((), (Equation("y", "y", x),)),))
    assert named_document(plain) is plain
    twice = Document("t", "r", (Block((), (Equation("A", "A", J), Equation("B", "B", J))),))
    first, second = named_document(twice).blocks[0].math
    assert first.where and not second.where and first.rhs == second.rhs
    assert not any(isinstance(s, Intermediate) for s in first.rhs.free_symbols)
    assert render(twice, "latex") == render(twice, "latex")


def test_report_html_shows_where_lines(files):
    robot = load_robot(files["generic6"])
    document = named_document(jacobian_document(robot, jacobian(robot), 0, "wrist", "differentiation"))
    html = "".join(block_html(block) for block in document.blocks)
    assert '<p class="note">where</p>' in html and "<msub><mi>w</mi><mi>1</mi></msub>" in html


def test_notebook_pairs_name_the_intermediates(files):
    robot = load_robot(files["generic6"])
    document = jacobian_document(robot, jacobian(robot), 0, "wrist", "differentiation")
    (_, tex), = blocks_as_pairs(document.blocks, "latex")
    (_, text), = blocks_as_pairs(document.blocks, "pretty")
    assert "w_{1} &= " in tex and "\nw₁ = " in text
