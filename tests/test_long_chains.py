"""Long chains stay exact and compact: every method against finite differences, and the planar arm's closed form."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from reference import evaluate, finite_difference_jacobian, random_configuration

from symjac import Chain, ResultTooLargeError, jacobian, robot_from_mapping
from symjac.cli.main import main
from symjac.kinematics.jacobian import METHODS
from symjac.model.urdf import robot_from_urdf
from symjac.progress import reporting_to
from symjac.symbolic import size as limits
from symjac.symbolic.simplify import simplify_matrix, simplify_product

LENGTH = sp.Rational(1, 10)


def planar(n):
    joints = [{"type": "revolute", "alpha": 0, "a": 0.1} for _ in range(n)]
    return robot_from_mapping({"name": f"planar{n}", "convention": "standard", "joints": joints})


def snake(n):
    joints = [{"type": "revolute", "alpha": "pi/2" if i % 2 else "-pi/2", "a": "L"} for i in range(n)]
    return robot_from_mapping({"name": f"snake{n}", "convention": "standard", "parameters": {"L": 0.1},
                               "joints": joints})


@pytest.mark.parametrize("method", METHODS)
def test_planar_12r_entries_are_sums_of_cumulative_sines(method):
    """-J[0, j] = sum_{k >= j} L sin(theta_1 + ... + theta_k), J[1, j] the same with cosines, exactly."""
    robot = planar(12)
    J = jacobian(Chain(robot), method=method)
    theta = [joint.variable for joint in robot.joints]
    for j in range(12):
        sines = sum(LENGTH * sp.sin(sum(theta[:k + 1])) for k in range(j, 12))
        cosines = sum(LENGTH * sp.cos(sum(theta[:k + 1])) for k in range(j, 12))
        assert sp.expand(J[0, j]) == -sines
        assert sp.expand(J[1, j]) == cosines
        assert list(J[2:, j]) == [0, 0, 0, 1]


@pytest.mark.parametrize("robot", [planar(12), snake(12)], ids=["planar12", "snake12"])
@pytest.mark.slow
def test_long_chains_match_finite_differences_by_every_method(robot):
    chain = Chain(robot)
    q = random_configuration(robot, np.random.default_rng(12))
    expected = finite_difference_jacobian(robot, q, 0, None)
    first = jacobian(chain, method="differentiation")
    np.testing.assert_allclose(evaluate(first, robot, q), expected, atol=1e-6)
    for method in METHODS[1:]:
        assert jacobian(chain, method=method) == first, method  # one normal form, so exactly equal


def test_long_derivations_report_their_stages():
    stages = []
    with reporting_to(stages.append):
        jacobian(Chain(planar(4)), method="velocity_propagation")
    assert "velocity propagation, link 4 of 4" in stages
    assert any(stage.startswith("simplifying") for stage in stages)


@pytest.mark.parametrize("frame", [0, 3, 6, "tool"])
def test_cross_product_in_any_frame_equals_differentiation(frame):
    """The cross-product method reads each column in {k} or in the axis frame (by the turns it spans): both exact."""
    robot = robot_from_mapping({"name": "mixed6", "convention": "standard", "parameters": {"L": 0.1},
                                "tool": {"xyz": [0, 0, "L"]},
                                "joints": [{"type": "revolute", "alpha": alpha, "a": "L"}
                                           for alpha in ("pi/2", 0, "-pi/2", "pi/2", 0, 0)]})
    chain = Chain(robot)
    assert jacobian(chain, frame, method="cross_product") == jacobian(chain, frame, method="differentiation")


def test_middle_frame_keeps_a_long_snake_short():
    """Frame {0} of a 3-D snake grows about 1.8x per joint; its middle frame spans half the chain each way."""
    chain = Chain(snake(8))
    size = {frame: sum(len(sp.Add.make_args(sp.expand(e))) for e in jacobian(chain, frame, method="cross_product"))
            for frame in (0, 4)}
    assert size[4] < size[0] / 3


def test_simplify_product_is_simplify_matrix_of_the_product():
    chain = Chain(snake(5))
    factors = [chain.transform(k, k + 1) for k in range(5)]
    bases = chain.angle_bases(0)
    assert simplify_product(factors, bases) == simplify_matrix(sp.Matrix(chain.transform(0, 5)), bases)
    with pytest.raises(ValueError, match="cannot multiply a 4 x 4 by a 3 x 3"):
        simplify_product([factors[0], sp.eye(3)], bases)


def test_results_too_large_to_write_out_are_refused_early(monkeypatch):
    monkeypatch.setattr(limits, "TERM_LIMIT", 100)
    with pytest.raises(ResultTooLargeError, match="more than 100 terms") as raised:
        Chain(snake(8)).simplified_transform(0, 8)  # the product on normal forms
    assert raised.value.limit == 100 and raised.value.terms > 100
    assert "--frame K --method cross_product" in str(raised.value)


@pytest.mark.parametrize("method", ["differentiation", "velocity_propagation"])
def test_public_results_too_large_to_write_out_come_from_the_nested_chain(monkeypatch, method):
    """Past the term limit a public quantity is derived nested (named intermediates) instead of being refused."""
    expected = jacobian(Chain(snake(8)), method=method)
    monkeypatch.setattr(limits, "TERM_LIMIT", 100)
    chain = Chain(snake(8))
    J = jacobian(chain, method=method)
    assert "nested_twin" in chain.__dict__ and chain.nested_twin.nested
    values = {symbol: 0.1 * k + 0.2 for k, symbol in enumerate(sorted(expected.free_symbols, key=str))}
    assert np.allclose(np.array(J.subs(values), dtype=float), np.array(expected.subs(values), dtype=float))


def test_the_command_line_prints_a_huge_result_nested(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(limits, "TERM_LIMIT", 100)
    path = tmp_path / "snake8.toml"
    path.write_text('name = "snake8"\nconvention = "standard"\n[parameters]\nL = 0.1\n'
                    + "".join(f'[[joints]]\ntype = "revolute"\nalpha = "{"pi/2" if i % 2 else "-pi/2"}"\na = "L"\n'
                              for i in range(8)))
    assert main(["fk", str(path), "--format", "json"]) == 0
    assert capsys.readouterr().err == ""


def test_term_limit_lowers_the_limit_within_its_block_only():
    with limits.term_limit(100), limits.term_limit(1000):  # the lower of the nested limits holds
        assert limits.current_term_limit() == 100
        with pytest.raises(ResultTooLargeError, match="more than 100 terms"):
            Chain(snake(8)).simplified_transform(0, 8)
    assert limits.current_term_limit() == limits.TERM_LIMIT
    Chain(snake(8)).simplified_transform(0, 8)  # refused in the block, derived outside it


def test_link_transforms_are_simplified_in_their_own_joint_angle_only(monkeypatch):
    """`symjac show` on 200 joints took minutes building a 200-angle basis per link; one angle per link suffices."""
    def refuse(self, frame):
        raise AssertionError("a basis of every joint angle was built for one link")

    chain = Chain(snake(60))
    monkeypatch.setattr(Chain, "angle_bases", refuse)
    T = chain.simplified_transform(29, 30)
    theta = chain.robot.joints[29].variable
    assert T.free_symbols - {theta} <= set(chain.robot.parameter_symbols)
    assert sp.simplify(T - chain.transform(29, 30)) == sp.zeros(4, 4)
    assert T[0, 0] == sp.cos(theta) and T[0, 3] == sp.Symbol("L", real=True) * sp.cos(theta)


def test_a_long_chain_is_announced_before_fk_but_shown_at_once(tmp_path, capsys):
    path = tmp_path / "planar45.toml"
    path.write_text('name = "planar45"\nconvention = "standard"\n'
                    + '[[joints]]\ntype = "revolute"\nalpha = 0\na = 0.1\n' * 45)
    assert main(["show", str(path), "--format", "pretty"]) == 0
    shown = capsys.readouterr()
    assert shown.err == "" and "T_44_45" in shown.out
    assert main(["fk", str(path), "--format", "pretty"]) == 0
    error = capsys.readouterr().err
    assert error.startswith("symjac: note: planar45 has 45 joints") and "Narrow the request" in error


def test_a_general_link_keeps_its_turn_about_z_inside_one_cosine():
    """A URDF joint whose origin turns pi/6 about a parallel axis: ``cos(theta3 + pi/6)``, as in the full basis."""
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
        f'<origin xyz="{0.1 * i} 0 0" rpy="0 0 {yaw}"/><axis xyz="0 0 1"/><limit lower="-3" upper="3"/></joint>'
        for i, yaw in ((1, 0), (2, 0), (3, 0.5235987755982988)))
    links = "".join(f'<link name="l{i}"/>' for i in range(4))
    robot = robot_from_urdf(f'<robot name="yawed">{links}{joints}</robot>')
    theta3 = robot.joints[2].variable
    T = Chain(robot).simplified_transform(2, 3)
    assert T[0, 0] == sp.cos(theta3 + sp.pi / 6) and T[1, 0] == sp.sin(theta3 + sp.pi / 6)
