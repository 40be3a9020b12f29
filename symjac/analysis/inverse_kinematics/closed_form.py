r"""Closed-form inverse kinematics: the plan of an arm (:func:`closed_form_plan`) and its numeric executor.

:func:`closed_form_plan` decides the arm's family exactly from its axes at home
(:mod:`~symjac.analysis.inverse_kinematics.geometry`) by trying the builders in :data:`FAMILIES` in order;
:func:`solve_plan` runs a plan on a numeric pose: each step's arguments are evaluated (compiled once per plan with
``lambdify``), the numeric subproblem returns all its solutions, and every branch goes on to the next step. Where a
subproblem leaves an angle free (a point on the axis: a singular pose) the angle is set to 0 and
:attr:`Solution.singular` says which combination of joints is fixed instead. The symbolic
executor, :func:`branch_programs` (from :mod:`.programs`), writes the same steps as formulas.

Angles are wrapped to ``(-pi, pi]``; when that value is outside the joint's limits but a ``2 pi`` shift is inside,
the shifted value is reported. Solutions outside the limits are kept with ``within_limits=False``.
"""

from __future__ import annotations

import functools
import math
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy

from symjac.analysis.inverse_kinematics import subproblems
from symjac.analysis.inverse_kinematics.geometry import ArmGeometry, arm_geometry, reduced_geometry
from symjac.analysis.inverse_kinematics.notes import continuum_note, merged_note, motion, unreachable_note
from symjac.analysis.inverse_kinematics.parallel_axes import three_parallel_axes_plan
from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS, Plan, Step, branch_names, solution_order
from symjac.analysis.inverse_kinematics.planar import (
    articulated_plan,
    cylindrical_plan,
    palletizer_plan,
    planar_plan,
    scara_plan,
    spherical_arm_plan,
)
from symjac.analysis.inverse_kinematics.programs import BranchProgram, branch_programs
from symjac.analysis.inverse_kinematics.spherical_wrist import spherical_wrist_plan
from symjac.errors import ArgumentError, NoClosedFormError
from symjac.model.robot import Robot

__all__ = ["FAMILIES", "BranchProgram", "ClosedFormResult", "Solution", "branch_programs", "closed_form_plan",
           "solve_plan"]

FAMILIES: tuple[Callable[[ArmGeometry], Plan | None], ...] = (
    spherical_wrist_plan,
    three_parallel_axes_plan,
    planar_plan,
    scara_plan,
    articulated_plan,
    palletizer_plan,
    spherical_arm_plan,
    cylindrical_plan,
)
"""The family builders :func:`closed_form_plan` tries in order: each returns a plan, or None when the arm is not of
its family."""


@functools.lru_cache(maxsize=32)
def closed_form_plan(robot: Robot, *, free_joint: int | None = None) -> Plan:
    """The closed-form inverse kinematics of ``robot``: the first family of :data:`FAMILIES` that fits it, exactly.

    With ``free_joint`` (a joint number, 1-based) that joint's value is an input (the redundancy parameter of a
    7-joint arm) and the arm that remains is solved.

    Raises
    ------
    NoClosedFormError
        When no family fits; the message says why (which axes miss, by how much at the defaults).

    Examples
    --------
    >>> from symjac import load_robot
    >>> plan = closed_form_plan(load_robot("puma560"))
    >>> plan.family, plan.max_solutions
    ('spherical wrist', 8)
    """
    geometry = arm_geometry(robot) if free_joint is None else reduced_geometry(robot, free_joint)
    for family in FAMILIES:
        plan = family(geometry)
        if plan is not None:
            return plan
    raise NoClosedFormError(reason=_why_none(geometry))


_FAMILY_NAMES = ("spherical wrist", "three parallel axes", "planar 2R or 3R", "SCARA", "articulated 3R", "palletizer",
                 "spherical arm", "cylindrical")


def _why_none(geometry: ArmGeometry) -> str:
    robot, joints = geometry.robot, geometry.joints
    given = "" if geometry.free_joint is None else f" with joint {geometry.free_joint} given"
    facts = [f"{len(joints)} joints remain"] if len(joints) != 6 else []
    if len(joints) == 7:
        facts[0] = ("7 joints, one more than a pose fixes (give one joint's value as the redundancy parameter to solve "
                    "the six that remain)")
    if len(joints) >= 3:
        facts.append(geometry.why_not_meet(*joints[-3:]))
        facts.append(geometry.why_not_meet(*joints[:3]))
        if geometry.intersection(*joints[:3]) is not None and geometry.intersection(*joints[-3:]) is not None:
            facts[-1] += (" as well, so they cannot change the distance from that point to the wrist: the arm has a "
                          "continuum of solutions or none")
    return (f"{robot.name}{given}: no closed-form family fits (tried: {', '.join(_FAMILY_NAMES)}): "
            + "; ".join(facts) + "; use the numeric solver")


@dataclass(frozen=True)
class Solution:
    """One solution: every joint's value, the branch names along the way, and whether it is within the limits.

    ``singular`` describes the continuum at a singular pose (``"theta4 + theta6 = 0.73 is fixed; theta4 shown at
    0"``) and the steps whose two solutions coincide there (``"elbow stretched: elbow down and elbow up coincide"``),
    joined by ``"; "``; empty elsewhere.
    """

    q: np.ndarray
    branch: tuple[str, ...]
    within_limits: bool
    singular: str = ""


@dataclass(frozen=True)
class ClosedFormResult:
    """Every solution of a plan at one pose; without one, ``unreachable`` says why and ``distance`` how far out.

    ``unreachable`` names the point of the arm that cannot be placed, in the arm's words, with that distance once:
    ``"the wrist centre is 0.05 beyond the reach of the arm stretched at joint 3"``.

    For a plan that controls less than the whole pose, ``uncontrolled`` says how far the pose the solutions reach is
    from the target when it differs (``uncontrolled_distance``: the position error, in length units).
    """

    plan: Plan
    solutions: tuple[Solution, ...]
    unreachable: str = ""
    distance: float = 0.0
    uncontrolled: str = ""
    uncontrolled_distance: float = 0.0


@dataclass(frozen=True)
class _Branch:
    values: list[float]  # the joint values solved so far, in the steps' order
    choices: tuple[int, ...]  # the solution each step took
    merged: tuple[bool, ...]  # whether each step's two solutions coincided
    singular: tuple[tuple[int, int], ...]  # (step, joint) of each joint that took every value
    notes: tuple[str, ...]  # the merged steps' notes


@dataclass(frozen=True)
class _CompiledStep:
    step: Step
    function: Callable[..., Any]
    layout: tuple[tuple[str, int], ...]  # argument name and its size (1 or 3), in the function's output order
    call: Callable[..., subproblems.AngleSolutions]


@dataclass(frozen=True)
class _Compiled:
    definitions: Callable[..., Any]
    steps: tuple[_CompiledStep, ...]
    positions: tuple[int, ...]  # the robot joint of each solved value, in the order the steps solve them
    limits: tuple[tuple[float, float] | None, ...]
    revolute: tuple[bool, ...]
    axes: tuple[tuple[np.ndarray, np.ndarray, str], ...]  # (h, p, kind) of every robot joint at home, numbers
    home: np.ndarray


_COMPILED: weakref.WeakKeyDictionary[Plan, _Compiled] = weakref.WeakKeyDictionary()


def _compiled(plan: Plan) -> _Compiled:
    if plan not in _COMPILED:
        _COMPILED[plan] = _compile(plan)
    return _COMPILED[plan]


def _compile(plan: Plan) -> _Compiled:
    robot = plan.robot
    numbers = robot.defaults
    variables = robot.joint_variables
    free = () if plan.free_joint is None else (variables[plan.free_joint - 1],)
    inputs = [*POSE_SYMBOLS, *free]
    definitions = [symbol for symbol, _ in plan.definitions]
    values: list[sympy.Expr] = []
    for _, expr in plan.definitions:  # a definition may use earlier ones: write them in
        values.append(sympy.sympify(expr).xreplace(numbers).xreplace(dict(zip(definitions, values, strict=False))))
    define = sympy.lambdify(inputs, values, modules="math")
    steps = []
    solved: list[sympy.Symbol] = []
    for step in plan.steps:
        layout: list[tuple[str, int]] = []
        flat: list[sympy.Expr] = []
        for name, value in step.arguments.items():
            entries = list(value) if isinstance(value, sympy.MatrixBase) else [value]
            layout.append((name, len(entries)))
            flat.extend(sympy.sympify(e).xreplace(numbers) for e in entries)
        function = sympy.lambdify(inputs + definitions + solved, flat, modules="math", cse=True)
        steps.append(_CompiledStep(step, function, tuple(layout), getattr(subproblems, step.subproblem)))
        solved.extend(variables[j] for j in step.joints)
    limits = tuple(None if joint.limits is None else (float(joint.limits[0].subs(numbers)),
                                                      float(joint.limits[1].subs(numbers))) for joint in robot.joints)
    geometry = arm_geometry(robot)
    axes = tuple((np.array(h.subs(numbers), dtype=float).ravel(), np.array(p.subs(numbers), dtype=float).ravel(), kind)
                 for h, p, kind in zip(geometry.axes, geometry.points, geometry.kinds, strict=True))
    return _Compiled(define, tuple(steps), tuple(variables.index(symbol) for symbol in solved),
                     limits, tuple(kind == "revolute" for kind in geometry.kinds), axes,
                     np.array(geometry.home.subs(numbers), dtype=float))


def _arguments(compiled: _CompiledStep, values: Sequence[float]) -> dict[str, Any]:
    flat = compiled.function(*values)
    arguments: dict[str, Any] = {}
    at = 0
    for name, size in compiled.layout:
        arguments[name] = flat[at] if size == 1 else tuple(flat[at:at + size])  # tuples: the subproblems' fast path
        at += size
    return arguments


def _run(compiled: _CompiledStep, arguments: dict[str, Any], tolerance: float) -> tuple[subproblems.AngleSolutions,
                                                                                        bool]:
    """The step's solutions, and whether its first joint is free (a continuum: its value is the representative 0)."""
    if compiled.step.subproblem == "two_rotations_to_point":
        k1, r = arguments["k1"], arguments.get("intersection") or (0.0, 0.0, 0.0)
        q = [a - b for a, b in zip(arguments["q"], r, strict=True)]
        length_squared = q[0] ** 2 + q[1] ** 2 + q[2] ** 2
        across_squared = length_squared - (k1[0] * q[0] + k1[1] * q[1] + k1[2] * q[2]) ** 2
        if math.sqrt(max(across_squared, 0.0)) <= tolerance * max(1.0, math.sqrt(length_squared)):
            # the target is on the first axis: that angle is free; the second alone takes p to q
            second = subproblems.rotation_to_point(arguments["k2"], arguments["p"], arguments["q"],
                                                   arguments.get("intersection"), tolerance)
            if not second.solutions:
                return second, False
            return subproblems.AngleSolutions(((0.0, second.solutions[0][0]),), "first angle free", True), True
    result = compiled.call(**arguments, tolerance=tolerance)
    return result, result.every_angle


def solve_plan(plan: Plan, pose: Any, *, free_value: float | None = None, tolerance: float = 1e-9) -> ClosedFormResult:
    r"""Every solution of ``plan`` at the 4 x 4 ``pose`` (frame {0}, as ``numeric_model(robot).fk(q)`` returns it).

    With a plan for a 7-joint arm (``plan.free_joint``), ``free_value`` is that joint's value. Each step's
    subproblem returns all its solutions (two where a square root has two signs) and each branch goes on; at a
    singular pose a free joint is shown at 0 and the solution's ``singular`` says what is fixed. ``tolerance`` is
    the subproblems' relative tolerance for existence (a square root's argument within it of zero is one solution).

    Raises
    ------
    ArgumentError
        For a pose that is not 4 x 4 (or 3 x 4) finite numbers with a rotation block, or a missing ``free_value``.
    """
    robot = plan.robot
    matrix = np.asarray(pose, dtype=float)
    if matrix.shape not in ((4, 4), (3, 4)):
        raise ArgumentError(f"inverse kinematics of {robot.name}: the pose must be a 4 x 4 matrix, got shape "
                            f"{matrix.shape}")
    if not np.all(np.isfinite(matrix[:3])):
        bad = [f"({i + 1}, {j + 1})" for i, j in zip(*np.nonzero(~np.isfinite(matrix[:3])), strict=True)]
        raise ArgumentError(f"inverse kinematics of {robot.name}: the pose has entries that are not finite numbers "
                            f"at {', '.join(bad)}")
    deviation = float(np.abs(matrix[:3, :3] @ matrix[:3, :3].T - np.eye(3)).max())
    if deviation > 1e-6 or np.linalg.det(matrix[:3, :3]) < 0:
        raise ArgumentError(f"inverse kinematics of {robot.name}: the pose's rotation block is not a rotation "
                            f"(R R^T differs from I by {deviation:.3g}, or det R < 0)")
    free: list[float] = []
    if plan.free_joint is not None:
        if free_value is None or not math.isfinite(free_value):
            raise ArgumentError(f"inverse kinematics of {robot.name}: the plan takes joint {plan.free_joint} as "
                                f"given; pass its value as free_value (a finite number), got {free_value!r}")
        free = [float(free_value)]
    compiled = _compiled(plan)
    inputs = [*matrix[:3, :3].ravel().tolist(), *matrix[:3, 3].tolist(), *free]
    inputs += list(compiled.definitions(*inputs))
    branches: list[_Branch] = [_Branch([], (), (), (), ())]
    failure: tuple[float, str] | None = None
    for number, step in enumerate(compiled.steps):
        grown = []
        for branch in branches:
            arguments = _arguments(step, inputs + branch.values)
            result, free_angle = _run(step, arguments, tolerance)
            if not result.solutions:
                distance, why = unreachable_note(step.step, arguments)
                if failure is None or distance < failure[0]:
                    failure = (distance, why)
                continue
            merged = len(step.step.branches) == 2 and len(result.solutions) == 1
            notes = (*branch.notes, merged_note(step.step, arguments)) if merged else branch.notes
            singular = (*branch.singular, (number, step.step.joints[0])) if free_angle else branch.singular
            for index in solution_order(plan.steps, branch.choices, len(result.solutions)):
                grown.append(_Branch(branch.values + list(result.solutions[index]), (*branch.choices, index),
                                     (*branch.merged, merged), singular, notes))
        branches = grown
    if not branches:
        distance, why = failure or (0.0, "no branch")
        return ClosedFormResult(plan, (), why, distance)
    solutions = tuple(_solution(plan, compiled, branch, free) for branch in branches)
    if plan.controlled == "the whole pose":
        return ClosedFormResult(plan, solutions)
    uncontrolled, distance = _uncontrolled(plan, compiled, solutions[0].q, matrix, tolerance)
    return ClosedFormResult(plan, solutions, uncontrolled=uncontrolled, uncontrolled_distance=distance)


def _forward(compiled: _Compiled, q: np.ndarray) -> np.ndarray:
    """The tool pose at ``q`` by the product of exponentials about the numeric axes at home."""
    moved = np.eye(4)
    for (h, p, kind), value in zip(compiled.axes, q, strict=True):
        moved = moved @ motion(h, p, kind, float(value))
    return moved @ compiled.home


def _uncontrolled(plan: Plan, compiled: _Compiled, q: np.ndarray, target: np.ndarray,
                  tolerance: float) -> tuple[str, float]:
    reached = _forward(compiled, q)
    position = float(np.linalg.norm(reached[:3, 3] - target[:3, 3]))
    cosine = (np.trace(reached[:3, :3].T @ target[:3, :3]) - 1.0) / 2.0
    angle = math.degrees(math.acos(min(1.0, max(-1.0, cosine))))
    if position <= tolerance * max(1.0, float(np.linalg.norm(target[:3, 3]))) and angle <= math.degrees(tolerance):
        return "", 0.0
    return (f"the arm controls {plan.controlled} only: the target differs from what it reaches by {position:.6g} in "
            f"position and {angle:.6g} deg in orientation", position)


def _wrapped(value: float, limits: tuple[float, float] | None) -> tuple[float, bool]:
    angle = math.remainder(value, 2 * math.pi)
    if angle == -math.pi:
        angle = math.pi
    if limits is None:
        return angle, True
    for candidate in (angle, angle - 2 * math.pi, angle + 2 * math.pi):
        if limits[0] - 1e-12 <= candidate <= limits[1] + 1e-12:
            return candidate, True
    return angle, False


def _solution(plan: Plan, compiled: _Compiled, branch: _Branch, free: list[float]) -> Solution:
    robot = plan.robot
    q = np.zeros(robot.n_joints)
    q[list(compiled.positions)] = branch.values
    if plan.free_joint is not None:
        q[plan.free_joint - 1] = free[0]
    inside = True
    for j in range(robot.n_joints):
        if compiled.revolute[j]:
            q[j], ok = _wrapped(float(q[j]), compiled.limits[j])
        else:
            limits = compiled.limits[j]
            ok = limits is None or limits[0] - 1e-12 <= q[j] <= limits[1] + 1e-12
        inside = inside and ok
    notes = [continuum_note([str(v) for v in robot.joint_variables], _lines(compiled, q), compiled.revolute, q, joint,
                            [j for later in plan.steps[number + 1:] for j in later.joints])
             for number, joint in branch.singular]
    names = branch_names(plan.steps, branch.choices, branch.merged)
    return Solution(q, names, inside, "; ".join([*notes, *branch.notes]))


def _lines(compiled: _Compiled, q: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every joint's axis at ``q`` (direction, point), by the product of exponentials."""
    lines = []
    moved = np.eye(4)
    for j, (h, p, kind) in enumerate(compiled.axes):
        lines.append((moved[:3, :3] @ h, moved[:3, :3] @ p + moved[:3, 3]))
        moved = moved @ motion(h, p, kind, float(q[j]))
    return lines
