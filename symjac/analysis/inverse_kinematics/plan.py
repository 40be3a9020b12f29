r"""The plan of a closed-form inverse kinematics: what the families build and executors, printers and generators read.

A :class:`Plan` lists named intermediates (``definitions``, e.g. the wrist centre from the target pose) and then
:class:`Step` values in order: each solves one or two joints by one geometric subproblem (the function of that name in
:mod:`~symjac.analysis.inverse_kinematics.subproblems`), its keyword arguments given as SymPy expressions in the target
pose's entries (:data:`POSE_SYMBOLS`), the robot's parameters, the definitions' symbols and the variables of joints
solved in earlier steps. A step with ``m`` solutions splits every branch into ``m``; the plan has at most the product
of those counts.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from symjac.errors import ArgumentError
from symjac.model.robot import Robot

__all__ = ["POSE_SYMBOLS", "SUBPROBLEMS", "Plan", "Step", "branch_choices", "branch_names", "pose_matrix",
           "solution_order"]

POSE_SYMBOLS: tuple[sympy.Symbol, ...] = sympy.symbols("r11 r12 r13 r21 r22 r23 r31 r32 r33 px py pz", real=True)
"""The target pose's entries as real symbols: the rotation ``r11 .. r33`` row by row, then the position."""

SUBPROBLEMS: dict[str, int] = {
    "rotation_to_point": 1,
    "two_rotations_to_point": 2,
    "rotation_to_distance": 2,
    "rotation_to_plane": 2,
    "slide_to_point": 1,
    "slide_to_distance": 2,
}
"""The subproblems a step may name, with the most solutions each has."""


def pose_matrix() -> sympy.Matrix:
    """The target pose as a 4 x 4 matrix of :data:`POSE_SYMBOLS` (last row ``0 0 0 1``)."""
    r11, r12, r13, r21, r22, r23, r31, r32, r33, px, py, pz = POSE_SYMBOLS
    return sympy.Matrix([[r11, r12, r13, px], [r21, r22, r23, py], [r31, r32, r33, pz], [0, 0, 0, 1]])


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: executors cache per plan
class Step:
    """One subproblem of a plan.

    ``joints`` are the robot joints (0-based) it solves, one or two (two rotations to a point: first the joint
    turned last, as the subproblem's ``theta1``); ``subproblem`` the numeric function's name; ``arguments`` its
    keyword arguments as SymPy expressions or 3 x 1 matrices; ``statement`` one sentence saying what it solves and
    how; ``branches`` the names of its solutions in the subproblem's order (empty for one solution); ``swapped_by``
    the position in the plan's steps of an earlier step whose second solution swaps this step's two names (the elbow
    after the shoulder: turning the shoulder over turns the arm over, and the bend that put the elbow above the line
    from shoulder to wrist then puts it below), else None; ``merged`` the index in ``branches`` of the name a solution
    carries when the step's two solutions coincide (then no swap applies: the stretched elbow has one name on both
    shoulders; a wrist at ``q5 = 0`` is "no flip" by the rule ``q5 >= 0``).

    For words about a pose, ``subject`` names what the step puts in place ("the wrist centre") and ``reach`` how the
    step fails when it cannot: ``"elbow"`` (the subject beyond the stretched arm or closer in than the folded arm),
    ``"offset"`` (an offset keeps the subject at least some distance from the step's axis, or from the shoulder
    for a slide), ``""`` (any other step: the target out of that joint's range).
    """

    joints: tuple[int, ...]
    subproblem: str
    arguments: Mapping[str, sympy.Expr | sympy.Matrix]
    statement: str
    branches: tuple[str, ...] = ()
    swapped_by: int | None = None
    merged: int = 0
    subject: str = ""
    reach: str = ""

    def __post_init__(self) -> None:
        if self.subproblem not in SUBPROBLEMS:
            raise ArgumentError(f"plan step for joints {[j + 1 for j in self.joints]}: unknown subproblem "
                             f"{self.subproblem!r} (known: {', '.join(SUBPROBLEMS)})")
        if self.branches and len(self.branches) != SUBPROBLEMS[self.subproblem]:
            raise ArgumentError(f"plan step for joints {[j + 1 for j in self.joints]}: {len(self.branches)} branch "
                             f"names for a subproblem with {SUBPROBLEMS[self.subproblem]} solutions")

    @property
    def solution_count(self) -> int:
        """The most solutions this step has."""
        return SUBPROBLEMS[self.subproblem]


def branch_names(steps: Sequence[Step], choices: Sequence[int], merged: Sequence[bool] = ()) -> tuple[str, ...]:
    """The branch names of the solution that took solution ``choices[i]`` (0-based) of each step ``steps[i]``.

    The one place the names are decided, for the numeric executor and the symbolic programs alike: a step's names in
    its subproblem's order, the two swapped when its ``swapped_by`` step took its second solution. Where
    ``merged[i]`` is true the step's two solutions coincided and it carries ``steps[i].branches[steps[i].merged]``.
    """
    names: list[str] = []
    for i, (step, index) in enumerate(zip(steps, choices, strict=True)):
        if step.branches and i < len(merged) and merged[i]:
            names.append(step.branches[step.merged])
        elif step.branches:
            swap = step.swapped_by is not None and choices[step.swapped_by] == 1
            names.append(step.branches[1 - index if swap and len(step.branches) == 2 else index])
    return tuple(names)


def solution_order(steps: Sequence[Step], choices: Sequence[int], count: int) -> tuple[int, ...]:
    """The order in which step ``steps[len(choices)]`` takes its ``count`` solutions after the earlier ``choices``.

    The solution named ``branches[merged]`` comes first, so that where the two coincide and only the first is kept
    (the numeric executor's one solution, generated code dropping a row equal to an earlier one) it carries that name
    on every branch of the earlier steps.
    """
    step = steps[len(choices)]
    if count != 2 or len(step.branches) != 2:
        return tuple(range(count))
    swap = step.swapped_by is not None and choices[step.swapped_by] == 1
    first = 1 - step.merged if swap else step.merged
    return (first, 1 - first)


def branch_choices(steps: Sequence[Step], counts: Sequence[int]) -> list[tuple[int, ...]]:
    """Every branch as the solution index each step takes, in the order the executor and the programs list them.

    ``counts[i]`` is the number of solutions of ``steps[i]``; each step's solutions come in :func:`solution_order`.
    """
    branches: list[tuple[int, ...]] = [()]
    for count in counts:
        branches = [(*choices, index) for choices in branches for index in solution_order(steps, choices, count)]
    return branches


@dataclass(frozen=True, eq=False)
class Plan:
    """A closed-form inverse kinematics of ``robot``: the family, why it applies, and the steps.

    ``reasons`` are the exact facts that decide the family (sentences); ``definitions`` named intermediates
    ``(symbol, expression)`` in pose symbols and parameters, evaluated first; ``controlled`` what of the pose the
    plan reaches (``"the whole pose"``); ``free_joint`` the number (1-based) of the joint whose value is an
    input, for a 7-joint arm, else None.
    """

    robot: Robot
    family: str
    reasons: tuple[str, ...]
    definitions: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    steps: tuple[Step, ...]
    controlled: str = "the whole pose"
    free_joint: int | None = None

    @property
    def max_solutions(self) -> int:
        """The product of the steps' solution counts: the most solutions one pose can have."""
        return math.prod(step.solution_count for step in self.steps)

    @property
    def solved_joints(self) -> tuple[int, ...]:
        """The joints (0-based) the steps solve, in the order they solve them."""
        return tuple(j for step in self.steps for j in step.joints)
