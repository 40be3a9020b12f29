"""Singular solutions checked against the joint limits (issue 14 point 6), from the CLI and the API.

A solution outside the limits is still listed, marked "outside"; a factor whose every solution is outside is "not
reachable within the joint limits"; a curve is sampled over the other joints and may be "partly" inside.
"""

from __future__ import annotations

import json
import math

import sympy as sp

from symjac import LimitStatus, load_robot, singularities
from symjac.analysis.singularity.joint_limits import limit_status
from symjac.analysis.singularity.solve import Solution
from symjac.cli.main import main

RP_ARM = """name = "rp_arm"
convention = "standard"

[[joints]]
type = "revolute"
alpha = "pi/2"
limits = [-1.5, 1.5]

[[joints]]
type = "prismatic"
d = 0.05
{limits}
"""


def _factors(tmp_path, capsys, limits: str, *options: str) -> list[dict]:
    path = tmp_path / "rp.toml"
    path.write_text(RP_ARM.format(limits=limits), encoding="utf-8")
    assert main(["singularities", str(path), "--rows", "v_x,v_y", *options, "--format", "json"]) == 0
    return json.loads(capsys.readouterr().out)["factors"]


def test_a_prismatic_zero_outside_the_limits_is_marked_unreachable(tmp_path, capsys):
    (factor,) = _factors(tmp_path, capsys, "limits = [0.1, 0.6]")
    assert factor["solutions"] == ["Eq(d2, -1/20)"]  # still listed
    assert factor["solution_limits"] == ["outside"]
    assert factor["reachable_within_limits"] is False
    assert factor["limits_words"] == "Not reachable within the joint limits: d2 = -1/20 is outside them."


def test_a_zero_inside_the_limits_is_reachable(tmp_path, capsys):
    (factor,) = _factors(tmp_path, capsys, "limits = [-0.1, 0.6]")
    assert factor["solution_limits"] == ["inside"]
    assert factor["reachable_within_limits"] is True
    assert factor["limits_words"] == "Joint limits: d2 = -1/20 is inside them."


def test_without_limits_nothing_is_claimed(tmp_path, capsys):
    (factor,) = _factors(tmp_path, capsys, "")
    assert factor["solution_limits"] == ["unlimited"]
    assert factor["reachable_within_limits"] is True
    assert factor["limits_words"] == ""


def test_captions_say_it_in_words(tmp_path, capsys):
    path = tmp_path / "rp.toml"
    path.write_text(RP_ARM.format(limits="limits = [0.1, 0.6]"), encoding="utf-8")
    for style in ("latex", "pretty"):
        assert main(["singularities", str(path), "--rows", "v_x,v_y", "--format", style]) == 0
        assert "Not reachable within the joint limits" in capsys.readouterr().out, style


def test_stanford_d3_is_outside_its_limits():
    report = singularities(load_robot("stanford"))
    by_expression = {str(f.expression): f for f in report.factors}
    assert by_expression["d3"].limits == (LimitStatus.OUTSIDE,)  # the file limits d3 to [0.3, 1.3]
    assert by_expression["d3"].reachable is False
    assert by_expression["sin(theta2)"].limits == (LimitStatus.UNLIMITED, LimitStatus.UNLIMITED)
    assert by_expression["sin(theta2)"].reachable is True


def test_revolute_values_wrap_and_curves_are_sampled():
    robot = load_robot("stanford")  # no limits on theta1, theta2; d3 in [0.3, 1.3]
    t1, d3 = sp.symbols("theta1 d3", real=True)
    assert limit_status(robot, Solution(d3, sp.Rational(1, 2))) is LimitStatus.INSIDE
    assert limit_status(robot, Solution(d3, sp.sin(t1))) is LimitStatus.PARTLY  # sin(theta1) in [-1, 1]
    assert limit_status(robot, Solution(d3, sp.sin(t1) / 4 + 1)) is LimitStatus.INSIDE
    assert limit_status(robot, Solution(d3, sp.sin(t1) / 4 - 1)) is LimitStatus.OUTSIDE
    assert limit_status(robot, Solution(t1, sp.pi)) is LimitStatus.UNLIMITED
    puma = load_robot("puma560")  # theta5 in [-100, 100] degrees
    t5 = sp.Symbol("theta5", real=True)
    assert limit_status(puma, Solution(t5, sp.pi)) is LimitStatus.OUTSIDE
    assert limit_status(puma, Solution(t5, 2 * sp.pi + sp.Rational(1, 2))) is LimitStatus.INSIDE  # modulo 2 pi
    assert limit_status(puma, Solution(t5, sp.Float(-100 * math.pi / 180 - 1e-3))) is LimitStatus.OUTSIDE
    assert limit_status(puma, Solution(t5, sp.acos(3 + sp.sin(t1)))) is LimitStatus.UNKNOWN  # never real
