"""Redundant arms: minors in final form, and the singular sets checked against the smallest singular value of J."""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from marks import marked

from symjac import load_robot, robot_from_mapping, singularities
from symjac.analysis.singularity.sets import condition_samples
from symjac.analysis.spaces import numeric_jacobian
from symjac.cli.main import main
from symjac.kinematics.chain import as_chain
from symjac.symbolic.layout import nested_expr
from symjac.symbolic.trigfactor import trig_factor_list
from symjac.symbolic.trigpoly import image_of

t = sp.symbols("theta1:8", real=True)
s = [sp.sin(x) for x in t]
c = [sp.cos(x) for x in t]
d3, d5, d7 = sp.symbols("d3 d5 d7", real=True)


def _sigma(robot, q, report):
    det = report.determinant
    J = numeric_jacobian(robot, q, det.frame, det.point)[list(det.rows), :]
    sigma = np.linalg.svd(J, compute_uv=False)
    return sigma[-1] / sigma[0]


def _factors(minor):
    return minor.coefficient, dict(minor.factors)


# --- final form --------------------------------------------------------------------------------------------------


def test_iiwa_minors_are_in_final_form():
    report = singularities(load_robot("iiwa7"))
    minors = {next(k for k in range(7) if k not in m.columns) + 1: m for m in report.minors}
    assert _factors(minors[1]) == (-1, {d3: 1, d5: 2, c[2]: 1, s[3]: 2, s[5]: 1})
    assert _factors(minors[2]) == (-1, {d3: 1, d5: 2, s[1]: 1, s[2]: 1, s[3]: 2, s[5]: 1})
    assert _factors(minors[6]) == (1, {d3: 2, d5: 1, s[1]: 1, s[3]: 2, s[4]: 1, s[5]: 1})
    assert _factors(minors[7]) == (1, {d3: 2, d5: 1, c[4]: 1, s[1]: 1, s[3]: 2})
    coefficient, factors = _factors(minors[3])
    assert factors.pop(d3) == factors.pop(d5) == factors.pop(s[3]) == factors.pop(s[5]) == 1
    (rest,) = factors  # one factor left: d5 c2 c3 s4 - s2 (d3 + d5 c4), up to sign
    assert sp.expand(coefficient * rest - (d5 * c[1] * c[2] * s[3] - s[1] * (d3 + d5 * c[3]))) == 0
    assert minors[4].expression == 0 and minors[4].factors == ()


def test_a_zero_minor_says_why_it_vanishes():
    report = singularities(load_robot("iiwa7"))
    (zero,) = report.zero_minors
    assert zero.columns == (0, 1, 2, 4, 5, 6) and zero.rank == 5
    assert zero.concurrent == ((0, 1, 2), (4, 5, 6))
    data = json.loads(_run(["singularities", "iiwa7", "--format", "json"]))
    (entry,) = data["zero_minors"]
    assert entry["columns"] == [1, 2, 3, 5, 6, 7] and "line through the two points" in entry["reason"]


def _pythagorean_sums(expr):
    """Sums that hold c^2 - 1, 1 - s^2 or s^2 + c^2 of one angle: what a final form writes as -s^2, c^2 or 1."""
    found = []
    for node in sp.preorder_traversal(expr):
        if not isinstance(node, sp.Add):
            continue
        squares = {(type(t.base), t.base.args[0]) for t in node.args
                   if isinstance(t, sp.Pow) and isinstance(t.base, sp.sin | sp.cos) and t.exp == 2}
        ones = any(t.is_Number and abs(t) == 1 for t in node.args)
        for kind, angle in squares:
            if ones or ((sp.cos if kind is sp.sin else sp.sin), angle) in squares:
                found.append(node)
    return found


def test_the_final_form_check_can_fail():
    assert _pythagorean_sums(d3 * (c[4] ** 2 - 1) + s[1])
    assert _pythagorean_sums(s[4] ** 2 + c[4] ** 2 + d5)
    assert not _pythagorean_sums(d3 * s[4] ** 2 + c[4])


@pytest.mark.parametrize("name", marked(["panda", "iiwa7"], keep=["iiwa7"]))  # the fast loop's redundant arm
def test_no_minor_factor_is_a_product_or_keeps_a_pythagorean_sum(name):
    for minor in singularities(load_robot(name)).minors:
        for factor, _ in minor.factors:
            assert not isinstance(factor, sp.Mul | sp.Pow), factor
            assert not _pythagorean_sums(factor), factor


@pytest.mark.slow  # the Panda's analysis; the fast loop checks the minors' final form on the iiwa
def test_panda_minors_split_where_they_factor():
    report = singularities(load_robot("panda"))
    minors = {next(k for k in range(7) if k not in m.columns) + 1: m for m in report.minors}
    # locking joint 6 or 7 leaves a product of two factors in theta4 (and theta6) besides s2 s5 or c5 s2
    assert len(minors[6].factors) == 4 and len(minors[7].factors) == 4
    assert {s[1], s[4]} <= set(dict(minors[6].factors)) and {s[1], c[4]} <= set(dict(minors[7].factors))


def test_trig_factoring_recovers_products_the_normal_form_hides():
    a, b = sp.symbols("a b", real=True)
    from symjac.symbolic.angles import AngleBasis

    basis = AngleBasis.of(list(t[:4]))
    for expr, expected in [(s[2] * (a * c[2] + b * s[2]), {s[2], a * c[2] + b * s[2]}),
                           (c[3] ** 2 - 1, {s[3]}),
                           (a * s[1] * (c[3] ** 2 - 1) * c[0], {a, s[1], s[3], c[0]})]:
        image, (poly,) = image_of([expr], basis)
        _, factors = trig_factor_list(poly, image)
        assert {nested_expr(f, image) for f, _ in factors} == expected


# --- singular sets -----------------------------------------------------------------------------------------------


def test_iiwa_has_four_singular_sets_classified():
    report = singularities(load_robot("iiwa7"))
    found = {frozenset(cond.expression for cond in singular_set.conditions): str(singular_set.kind)
             for singular_set in report.sets}
    assert found == {frozenset({s[3]}): "elbow", frozenset({s[1], s[5]}): "alignment",
                     frozenset({s[1], c[2]}): "shoulder", frozenset({s[5], c[4]}): "wrist"}
    for singular_set in report.sets:
        assert len(singular_set.null_space) == 2 and len(singular_set.regular_null_space) == 1
        assert singular_set.lost_direction is not None and singular_set.reachable


def _check_sets(robot, report, seed=0, off_threshold=1e-5):
    """sigma_min ~ 0 at random points on each set, and clearly not 0 a little off it."""
    generator = np.random.default_rng(seed)
    checked = 0
    for singular_set in report.sets:
        if singular_set.sample is None:
            continue
        points = condition_samples(as_chain(robot), singular_set.conditions, 6, seed=seed)
        assert len(points), singular_set.conditions
        for q in points:
            assert _sigma(robot, q, report) < 1e-10, (singular_set.conditions, q)
            off = q + generator.normal(0, 0.05, q.shape)
            assert _sigma(robot, off, report) > off_threshold, (singular_set.conditions, off)
            checked += 1
    return checked


def _residual(robot, singular_set, q):
    """How far ``q`` is from satisfying every condition: the largest |factor| relative to its size elsewhere."""
    def at(values):
        return {**robot.defaults, **{v: sp.Float(float(x)) for v, x in zip(robot.q, values, strict=True)}}

    worst = 0.0
    for condition in singular_set.conditions:
        value = abs(complex(sp.sympify(condition.expression).xreplace(at(q)).evalf()))
        scale = max(abs(complex(sp.sympify(condition.expression).xreplace(at(np.full(len(q), 0.7))).evalf())), 1e-3)
        worst = max(worst, value / scale)
    return worst


def _scan(robot, report, starts=12, seed=1):
    """Singular configurations found by minimising sigma_min / sigma_max from random starts (SciPy)."""
    from scipy.optimize import minimize

    generator = np.random.default_rng(seed)
    found = []
    for _ in range(starts):
        q0 = generator.uniform(-2.5, 2.5, robot.n_coordinates)
        result = minimize(lambda q: _sigma(robot, q, report), q0, method="Nelder-Mead",
                          options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000, "maxfev": 20000})
        if result.fun < 1e-7:
            found.append(result.x)
    return found


@pytest.mark.parametrize("name", marked(["iiwa7", "panda"], keep=["iiwa7"]))
def test_reported_sets_are_singular_and_no_singular_point_lies_outside_them(name):
    robot = load_robot(name)
    report = singularities(robot)
    assert _check_sets(robot, report) >= 6
    points = _scan(robot, report)
    assert points, "the scan found no singular configuration"
    for q in points:
        assert min(_residual(robot, singular_set, q) for singular_set in report.sets) < 1e-3, q


REDUNDANT_JOINTS = st.fixed_dictionaries({
    "type": st.just("revolute"), "alpha": st.sampled_from([0, "pi/2", "-pi/2"]),
    "a": st.sampled_from([0, 0, 0.3, "L"]), "d": st.sampled_from([0, 0, 0.25, "L"]), "theta": st.just(0)})


@pytest.mark.slow  # four whole 7-joint analyses; the fast loop keeps the iiwa's sets
@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(convention=st.sampled_from(["standard", "modified"]),
       joints=st.lists(REDUNDANT_JOINTS, min_size=7, max_size=7))
def test_random_seven_joint_chains_sets_are_singular_and_complete(convention, joints):
    robot = robot_from_mapping({"name": "random7", "convention": convention, "parameters": {"L": 0.35},
                                "joints": joints})
    report = singularities(robot)
    if all(minor.coefficient == 0 for minor in report.minors):  # singular everywhere: nothing to find
        assert report.zero_minors and max(zero.rank for zero in report.zero_minors) < 6
        return
    _check_sets(robot, report, off_threshold=1e-8)  # other sets may pass near a random arm's
    for q in _scan(robot, report, starts=4):  # with no set reported, any singular point found fails here
        assert report.sets and min(_residual(robot, singular_set, q) for singular_set in report.sets) < 1e-3, q


def test_the_sets_do_not_depend_on_the_seed():
    robot = load_robot("iiwa7")
    lists = [[tuple(c.expression for c in singular_set.conditions) for singular_set in
              singularities(as_chain(robot).__class__(robot), seed=seed).sets] for seed in range(3)]
    assert lists[0] == lists[1] == lists[2]


def test_every_combination_of_branches_is_tried():
    """Minors s2, s3 and c2 - c3 vanish together only where theta2 = theta3 (both 0 or both pi), not on s2 = s3 = 0."""
    from symjac.analysis.singularity.determinant import Determinant
    from symjac.analysis.singularity.sets import singular_conditions

    chain = as_chain(load_robot("planar3r"))
    point = (sp.S.Zero,) * 3
    minors = [Determinant(sp.S.One, ((f, 1),), (0,), 0, point, (k,)) for k, f in enumerate([s[1], s[2], c[1] - c[2]])]
    found = singular_conditions(chain, minors)
    assert found and all({cond.expression for cond in conjunction} != {s[1], s[2]} for conjunction in found)
    for conjunction in found:
        for q in condition_samples(chain, conjunction, 8):
            assert abs(np.sin(q[1])) < 1e-9 and abs(np.cos(q[1]) - np.cos(q[2])) < 1e-9


def test_an_arm_singular_everywhere_says_so():
    text = _run(["singularities", "planar3r", "--rows", "v_x,v_z", "--format", "pretty"])
    assert "singular at every configuration" in text and "identically zero" in text


# --- output ------------------------------------------------------------------------------------------------------


def _run(argv):
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(argv) == 0
    return buffer.getvalue()


def test_json_lists_the_sets_with_conditions_solutions_kind_and_explanation():
    data = json.loads(_run(["singularities", "iiwa7", "--format", "json"]))
    sets = data["sets"]
    assert len(sets) == 4
    elbow = next(entry for entry in sets if entry["kind"] == "elbow")
    assert elbow["conditions"] == ["sin(theta4) = 0"]
    assert elbow["solutions"] == [["theta4 = 0", "theta4 = pi"]]
    assert "stretched out or folded back" in elbow["explanation"]
    for entry in sets:
        for condition in entry["conditions"]:
            expr, zero = condition.split(" = ")
            names = {str(symbol) for symbol in sp.sympify(expr).free_symbols}
            assert zero == "0" and names <= {str(x) for x in (*t, d3, d5, d7)}
        assert len(entry["null_space"]) == 2 and len(entry["regular_null_space"]) == 1


def test_pretty_and_latex_list_the_sets():
    pretty = _run(["singularities", "iiwa7", "--format", "pretty"])
    assert "4 singular sets" in pretty and "Set 1: s₄ = 0 (elbow)" in pretty
    latex = _run(["singularities", "iiwa7"])
    assert "s_{4} = 0" in latex and "identically zero" in latex
