"""The closed-form executors: bad poses, unreachable poses with their distance, singular poses with their continuum,
limits, and the symbolic programs agreeing with the numeric executor."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import sympy

from symjac import load_robot
from symjac.analysis.inverse_kinematics import (
    POSE_SYMBOLS,
    Step,
    branch_programs,
    closed_form_plan,
    pose_matrix,
    seed_bounds,
    solve_plan,
)
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import ArgumentError


def _arm(name):
    robot = load_robot(name)
    return robot, closed_form_plan(robot), numeric_model(robot, backend="numpy")


def test_pose_symbols_and_matrix():
    assert [str(s) for s in POSE_SYMBOLS] == ["r11", "r12", "r13", "r21", "r22", "r23", "r31", "r32", "r33", "px", "py",
                                              "pz"]
    assert all(s.is_real for s in POSE_SYMBOLS)
    assert pose_matrix()[1, 3] == POSE_SYMBOLS[10] and pose_matrix()[3, :] == sympy.Matrix([[0, 0, 0, 1]])


def test_bad_poses_get_one_line_errors():
    _, plan, _ = _arm("puma560")
    pose = np.eye(4)
    pose[1, 3] = math.nan
    with pytest.raises(ArgumentError, match=r"puma560: the pose has entries that are not finite numbers at \(2, 4\)"):
        solve_plan(plan, pose)
    with pytest.raises(ArgumentError, match="must be a 4 x 4 matrix, got shape"):
        solve_plan(plan, np.eye(3))
    with pytest.raises(ArgumentError, match="rotation block is not a rotation"):
        solve_plan(plan, 2 * np.eye(4))
    iiwa = closed_form_plan(load_robot("iiwa7"), free_joint=3)
    with pytest.raises(ArgumentError, match="takes joint 3 as given; pass its value as free_value"):
        solve_plan(iiwa, np.eye(4))
    with pytest.raises(ArgumentError, match="unknown subproblem 'rotate'"):
        Step((0,), "rotate", {}, "")


JARGON = ("delta", "cos", "gamma", "subproblem", "rotation to", "slide to", "two rotations", "sqrt", "A^2", "=",
          "fails", "out of reach")


def _in_words(unreachable, distance):
    """The message names no subproblem quantity and states the distance once."""
    assert not any(word in unreachable for word in JARGON), unreachable
    assert unreachable.count(f"{distance:.4g}") == 1, unreachable


def test_a_wrist_centre_just_beyond_reach_is_unreachable_by_that_much():
    robot, plan, _ = _arm("puma560")
    a2, a3, d3, d4 = (float(robot.defaults[sympy.Symbol(n, real=True)]) for n in ("a2", "a3", "d3", "d4"))
    reach = math.hypot(d3, a2 + math.hypot(a3, d4))  # the farthest wrist centre from the shoulder
    direction = np.array([0.6, 0.0, 0.8])
    for beyond in (1e-3, 0.05):
        pose = np.eye(4)
        pose[:3, 3] = (reach + beyond) * direction
        result = solve_plan(plan, pose)
        assert result.solutions == ()
        assert result.unreachable == (f"the wrist centre is {result.distance:.4g} beyond the reach of "
                                      "the arm stretched at joint 3")
        _in_words(result.unreachable, result.distance)
        # the distance is measured across axis 2: sqrt(r^2 - d3^2) grows by about r / sqrt(r^2 - d3^2) per metre
        across = math.sqrt((reach + beyond) ** 2 - d3**2) - math.sqrt(reach**2 - d3**2)
        assert result.distance == pytest.approx(across, rel=1e-6)
    inside = np.eye(4)
    inside[:3, 3] = (reach - 1e-3) * direction
    assert len(solve_plan(plan, inside).solutions) == 8


def test_a_wrist_centre_inside_the_shoulder_cylinder_is_unreachable():
    robot, plan, _ = _arm("puma560")
    d3 = float(robot.defaults[sympy.Symbol("d3", real=True)])
    pose = np.eye(4)
    pose[:3, 3] = [0.5 * d3, 0.0, 0.3]
    result = solve_plan(plan, pose)
    assert result.solutions == () and result.distance == pytest.approx(0.5 * d3, rel=1e-9)
    assert result.unreachable == (f"the wrist centre is {0.5 * d3:.4g} too close to axis 1: the arm's "
                                  f"offset keeps it at least {d3:.4g} from that axis")
    _in_words(result.unreachable, result.distance)


def test_a_wrist_centre_on_the_shoulder_cylinder_merges_the_shoulders_and_says_so():
    robot, plan, model = _arm("puma560")
    d3 = float(robot.defaults[sympy.Symbol("d3", real=True)])
    pose = np.eye(4)
    pose[:3, 3] = [0.6 * d3, 0.8 * d3, 0.3]  # the wrist centre (the flange) d3 from axis 1: as close as it comes
    result = solve_plan(plan, pose)
    assert len(result.solutions) == 4 and len({round(float(s.q[0]), 9) for s in result.solutions}) == 1
    note = f"the wrist centre {d3:.4g} from axis 1, as close as it comes: shoulder right and shoulder left coincide"
    assert all(s.branch[0] == "shoulder right" and note in s.singular for s in result.solutions)
    assert np.abs(model.fk(np.array([s.q for s in result.solutions])) - pose).max() < 1e-9


def test_the_wrist_singularity_is_a_continuum_with_theta4_plus_theta6_fixed():
    _, plan, model = _arm("puma560")
    q = np.array([0.4, -0.8, 0.6, 0.9, 0.0, -0.3])
    pose = model.fk(q)
    result = solve_plan(plan, pose)
    assert result.solutions
    for solution in result.solutions:
        assert np.abs(model.fk(solution.q) - pose).max() < 1e-10
    singular = [s for s in result.solutions if s.singular]
    assert singular, "no solution describes the continuum"
    for solution in singular:
        assert solution.q[3] == 0.0
        assert "theta4 + theta6 = " in solution.singular or "theta4 - theta6 = " in solution.singular
    fixed = next(s for s in singular if np.allclose(s.q[:3], q[:3]))
    assert "theta4 + theta6" in fixed.singular  # axes 4 and 6 point the same way at theta5 = 0
    value = float(fixed.singular.split("= ")[1].split(" ")[0])
    assert value == pytest.approx(math.remainder(q[3] + q[5], 2 * math.pi), abs=1e-6)
    for t in (0.5, -1.2, 2.9):  # along the stated continuum the pose stays
        moved = fixed.q + np.array([0, 0, 0, t, 0, -t])
        assert np.abs(model.fk(moved) - pose).max() < 1e-10
    # q5 = 0 is "no flip" by the rule q5 >= 0, and the flip there is the same continuum: the note says they coincide
    assert all("no flip" in s.branch and "wrist flip and no flip coincide" in s.singular for s in singular)


def test_the_shoulder_singularity_of_the_irb_is_a_continuum_in_theta1():
    robot, plan, model = _arm("irb140")
    d6 = float(robot.defaults[sympy.Symbol("d6", real=True)])

    def configuration(q3):
        return np.array([0.0, -0.6, q3, 0.0, 0.5, 0.0])

    def wrist_x(q3):  # the wrist centre is d6 behind the flange along its z-axis; the arm stays in the x-z plane
        pose = model.fk(configuration(q3))
        return pose[0, 3] - d6 * pose[0, 2]

    low, high = -3.0, 0.8  # bisection for the elbow angle that puts the wrist centre on axis 1
    assert wrist_x(low) * wrist_x(high) < 0
    for _ in range(100):
        middle = (low + high) / 2
        low, high = (middle, high) if wrist_x(low) * wrist_x(middle) > 0 else (low, middle)
    pose = model.fk(configuration(low))
    result = solve_plan(plan, pose)
    stated = "theta1 takes every value; shown at 0 (the joints solved after it, theta3, theta2, theta4, theta5, theta6"
    assert result.solutions and all(s.singular.startswith(stated + ", follow it)") for s in result.solutions)
    merged = "the wrist centre on axis 1, as close as it comes: shoulder right and shoulder left coincide"
    assert all(s.singular.endswith(merged) and s.branch[0] == "shoulder right" for s in result.solutions)
    for solution in result.solutions:
        assert np.abs(model.fk(solution.q) - pose).max() < 1e-9


def test_a_configuration_outside_the_limits_is_kept_and_flagged():
    robot, plan, model = _arm("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.6, 0.1])
    result = solve_plan(plan, model.fk(q))
    inside = [s for s in result.solutions if s.within_limits]
    outside = [s for s in result.solutions if not s.within_limits]
    assert any(np.allclose(s.q, q) for s in inside) and outside
    lower, upper = seed_bounds(robot)
    for solution in outside:
        assert np.any(solution.q < lower - 1e-9) or np.any(solution.q > upper + 1e-9)
    for solution in result.solutions:
        assert np.all(solution.q > -math.pi - 1e-12) or solution.within_limits


def test_a_plan_controlling_less_than_the_pose_says_how_far_the_rest_is():
    _, plan, model = _arm("puma560")
    position_only = dataclasses.replace(plan, steps=plan.steps[:3], controlled="the position of the wrist centre")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.6, 0.1])
    result = solve_plan(position_only, model.fk(q))
    assert len(result.solutions) == 4 and "controls the position of the wrist centre only" in result.uncontrolled
    assert result.uncontrolled_distance == pytest.approx(0.0, abs=1e-12)  # the wrist centre is the flange
    assert solve_plan(plan, model.fk(q)).uncontrolled == ""


@pytest.mark.parametrize("name", ["puma560", "stanford", "irb140"])
def test_the_symbolic_programs_agree_with_the_numeric_executor(name):
    robot, plan, model = _arm(name)
    programs = branch_programs(plan)
    assert len(programs) == plan.max_solutions
    compiled = []
    for program in programs:
        symbols = [s for s, _ in program.assignments]
        compiled.append([sympy.lambdify([*POSE_SYMBOLS, *symbols], e.subs(robot.defaults), "math")
                         for _, e in program.assignments])
    generator = np.random.default_rng(3)
    for _ in range(20):
        q = generator.uniform(*seed_bounds(robot))
        pose = model.fk(q)
        numeric = {s.branch: s.q for s in solve_plan(plan, pose).solutions}
        for program, function in zip(programs, compiled, strict=True):
            values = _run(program, function, pose)
            if values is None:
                assert program.branch not in numeric
                continue
            q_symbolic = np.array([values[v] for v in robot.joint_variables])
            difference = np.angle(np.exp(1j * (q_symbolic - numeric[program.branch])))
            assert np.abs(np.where([j.is_revolute for j in robot.joints], difference,
                                   q_symbolic - numeric[program.branch])).max() < 1e-8


def _run(program, functions, pose):
    """A program evaluated in order; None when a condition is negative (the branch does not exist)."""
    inputs = [*pose[:3, :3].ravel(), *pose[:3, 3]]
    names = [s for s, _ in program.assignments]
    values = dict.fromkeys(names, 0.0)
    for (symbol, _), function in zip(program.assignments, functions, strict=True):
        value = function(*inputs, *(values[s] for s in names))
        if symbol in program.conditions:
            if value < -1e-9:
                return None
            value = max(value, 0.0)
        values[symbol] = value
    return values


def test_the_puma_programs_read_like_the_textbook():
    plan = closed_form_plan(load_robot("puma560"))
    program = branch_programs(plan)[0]
    assignments = dict(program.assignments)
    px, py = POSE_SYMBOLS[9], POSE_SYMBOLS[10]
    d3 = sympy.Symbol("d3", real=True)
    theta1 = assignments[load_robot("puma560").joint_variables[0]]
    delta = next(s for s in program.conditions if s in theta1.free_symbols)
    assert sympy.expand(assignments[delta] - (px**2 + py**2 - d3**2)) == 0
    assert theta1 == sympy.atan2(py, px) - sympy.atan2(d3, -sympy.sqrt(delta))  # shoulder right
    assert dict(branch_programs(plan)[4].assignments)[load_robot("puma560").joint_variables[0]] == (
        sympy.atan2(py, px) - sympy.atan2(d3, sympy.sqrt(delta)))  # shoulder left
    assert all(sympy.count_ops(e) < 200 for _, e in program.assignments)


def test_configurations_at_their_limits_are_within_limits():
    robot, plan, model = _arm("puma560")
    lower, upper = seed_bounds(robot)
    for q in (lower.copy(), upper.copy()):
        q[4] = 0.5  # off the wrist singularity
        result = solve_plan(plan, model.fk(q))
        # the same angles modulo 2 pi (a limit beyond pi is reported as its (-pi, pi] alias when that is inside)
        match = [s for s in result.solutions if np.abs(np.angle(np.exp(1j * (s.q - q)))).max() < 1e-9]
        assert match and match[0].within_limits


def test_the_stanford_wrist_centre_at_the_shoulder_is_out_of_reach_by_its_offset():
    robot, plan, _ = _arm("stanford")
    d2 = float(robot.defaults[sympy.Symbol("d2", real=True)])
    result = solve_plan(plan, np.eye(4))  # the wrist centre (the flange) at the shoulder point
    assert result.solutions == () and result.distance == pytest.approx(d2, rel=1e-12)
    assert result.unreachable == (f"the wrist centre is {d2:.4g} too close to the shoulder: the line of "
                                  f"the slide (joint 3) passes {d2:.4g} from it")


def test_the_stretched_elbow_has_one_elbow_solution_per_shoulder():
    robot, plan, model = _arm("puma560")
    a3, d4 = (float(robot.defaults[sympy.Symbol(n, real=True)]) for n in ("a3", "d4"))
    theta3 = math.atan2(a3, d4) - math.pi / 2  # the forearm (a3, -d4 in frame 3) along the upper arm: full reach
    q = np.array([0.3, -0.4, theta3, 0.2, 0.6, 0.1])
    pose = model.fk(q)
    farther = model.fk(q + np.array([0, 0, 1e-3, 0, 0, 0]))[:3, 3]
    assert np.linalg.norm(farther) < np.linalg.norm(pose[:3, 3])  # the reach is largest there
    result = solve_plan(plan, pose)
    assert len(result.solutions) == 4  # the one elbow solution has one name on both shoulders, and says why
    assert {s.branch[:2] for s in result.solutions} == {("shoulder right", "elbow down"),
                                                        ("shoulder left", "elbow down")}
    assert all("elbow stretched: elbow down and elbow up coincide" in s.singular for s in result.solutions)
    assert np.abs(model.fk(np.array([s.q for s in result.solutions])) - pose).max() < 1e-9
    assert any(np.abs(np.angle(np.exp(1j * (s.q - q)))).max() < 1e-6 for s in result.solutions)
