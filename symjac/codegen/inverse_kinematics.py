r"""Closed-form inverse kinematics for generated code: every branch program as one straight-line function.

The closed form of an arm (:func:`~symjac.analysis.inverse_kinematics.closed_form.branch_programs`) is a tuple of
branch programs, each an ordered list of assignments ``symbol = expression`` in the pose symbols, the robot's
parameters and earlier symbols, with the *conditions*: assigned symbols that must not be negative (each is the
argument of a square root). Generated code evaluates all of them at once:

1. **Shared across branches.** The branches are walked in order; every assignment's value, with the symbols before it
   replaced by the shared names already given, gets one name for all branches that compute the same value (the
   wrist centre, the shoulder angle both elbow branches share). One CSE then runs over everything
   (:func:`~symjac.codegen.cse.eliminate_common`).
2. **Conditions clamped.** A condition's raw value is an output of its own; what later assignments read is the
   value, or 0 where it is below :data:`IK_NOISE` (:class:`IKClamp`), so a square root never sees a negative number
   and a pose exactly at a singularity gives exact angles. At run time a branch whose condition lies
   below ``-tolerance`` is dropped, one within the tolerance is kept with the value clamped to 0 (the two branches
   of a square root then coincide).
3. **Selection** (written by each target around the straight line): a branch is kept when its conditions pass and
   every joint value is finite (a NaN pose, a division by zero at a singular pose), revolute angles are wrapped to
   (-pi, pi], and an angle outside the joint's limits is replaced by its 2 pi shift when that one is inside; the kept
   solutions are written in branch order into a fixed array of :attr:`InverseKinematics.max_solutions` rows, and
   their count is returned.

The outputs of the lowered function (:class:`~symjac.codegen.lower.LoweredFunction`, input ``pose``: the first three
rows of the 4 x 4 pose, row-major) are the distinct condition values first, then each branch's joint values.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import sympy as sp

from symjac.codegen.coupled import coordinates_of_joints
from symjac.codegen.cse import eliminate_common
from symjac.codegen.ik_numeric import NUMERIC_IK_TARGETS
from symjac.codegen.lower import LoweredFunction
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain, as_chain
from symjac.kinematics.memo import memoized
from symjac.model.robot import Robot

__all__ = [
    "IK_EXPORTS",
    "IK_NOISE",
    "IK_TOLERANCE",
    "POSE_ENTRIES",
    "Q_FREE",
    "BranchProgramLike",
    "IKAtan2",
    "IKClamp",
    "IKCosine",
    "IKInverse",
    "InverseKinematics",
    "closed_or_numeric",
    "ik_listing",
    "inverse_kinematics_of",
    "lower_branch_programs",
    "lowered_inverse_kinematics",
    "pose_symbols",
]

IK_TOLERANCE = 1e-9
"""The default ``tolerance`` of every generated ``inverse_kinematics``: how far below 0 a condition may lie and
still count as 0 (as :func:`~symjac.analysis.inverse_kinematics.closed_form.solve_plan`'s default)."""

IK_EXPORTS = ("IK_BRANCHES", "IK_MAX_SOLUTIONS", "IK_TOLERANCE", "inverse_kinematics")
"""The names a Python-family module with inverse kinematics exports besides its other functions."""

Q_FREE = sp.Symbol("q_free", real=True)
"""The given joint's value in a closed form that takes one joint as given (a 7-joint arm's redundancy parameter): the
argument ``q_free`` of every target's ``inverse_kinematics``, right after the pose."""

POSE_ENTRIES = ("r11", "r12", "r13", "px", "r21", "r22", "r23", "py", "r31", "r32", "r33", "pz")
"""The pose symbols in the order of the first twelve entries of a row-major 4 x 4 pose (the last row is ignored)."""


class BranchProgramLike(Protocol):
    """What lowering reads of a branch program (``closed_form.BranchProgram`` of the inverse kinematics)."""

    @property
    def branch(self) -> tuple[str, ...]: ...  # noqa: D102

    @property
    def assignments(self) -> tuple[tuple[sp.Symbol, sp.Expr], ...]: ...  # noqa: D102

    @property
    def conditions(self) -> tuple[sp.Symbol, ...]: ...  # noqa: D102


@dataclass(frozen=True)
class InverseKinematics:
    """The closed form of a robot's inverse kinematics as one lowered function, with what selection needs.

    ``lowered`` has the input ``pose`` (:data:`POSE_ENTRIES`) and the outputs: the ``n_conditions`` distinct
    condition values, then each branch's ``n`` joint values. ``branch_conditions[b]`` indexes the condition values
    branch ``b`` needs; ``branches`` name the branches (``("shoulder left", "elbow up")``); ``revolute`` says which
    joints are angles (wrapped to (-pi, pi]).
    """

    lowered: LoweredFunction
    family: str
    branches: tuple[tuple[str, ...], ...]
    branch_conditions: tuple[tuple[int, ...], ...]
    n_conditions: int
    n: int
    revolute: tuple[bool, ...]
    free_joint: int | None = None
    free_variable: str = ""

    @property
    def max_solutions(self) -> int:
        """The number of branches: the most solutions a pose can have, the rows of the solutions array."""
        return len(self.branches)

    @property
    def branch_names(self) -> tuple[str, ...]:
        """Each branch's names joined: ``"shoulder left, elbow up"`` (``"the only branch"`` for none)."""
        return tuple(", ".join(names) or "the only branch" for names in self.branches)

    def joint_output(self, branch: int, joint: int) -> int:
        """The index among the lowered outputs of ``joint``'s value in ``branch``."""
        return self.n_conditions + branch * self.n + joint


def pose_symbols() -> tuple[sp.Symbol, ...]:
    """The plan's ``POSE_SYMBOLS`` in :data:`POSE_ENTRIES` order (the first three rows of the pose, row-major)."""
    from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS

    by_name = {symbol.name: symbol for symbol in POSE_SYMBOLS}
    return tuple(by_name[name] for name in POSE_ENTRIES)


def lower_branch_programs(programs: Sequence[BranchProgramLike], joints: Sequence[sp.Symbol],
                          parameters: Sequence[sp.Symbol], revolute: Sequence[bool], family: str = "",
                          free_joint: int | None = None, coordinates: Sequence[sp.Expr] | None = None
                          ) -> InverseKinematics:
    """Lower ``programs`` (one per branch) to one straight-line function of the pose and the ``parameters``.

    ``joints`` are the joint variables every program must assign (their last assignment is the branch's value).
    An expression reading a symbol that is neither a pose symbol, a parameter nor assigned before it is refused.
    With ``free_joint`` (a joint number, 1-based) that joint's variable is an input instead (renamed
    :data:`Q_FREE`, a second input of the lowered function), and its value is copied into every branch.
    ``coordinates`` (default: ``joints``) are what each branch outputs, as expressions of the joint variables: a
    coupled robot's coordinates (:func:`~symjac.codegen.coupled.coordinates_of_joints`); ``revolute`` says which of
    them are angles.
    """
    outputs = tuple(joints if coordinates is None else coordinates)
    if not programs:
        raise CodegenError("inverse kinematics: the closed form has no branch")
    free: dict[sp.Symbol, sp.Symbol] = {} if free_joint is None else {joints[free_joint - 1]: Q_FREE}
    known = set(pose_symbols()) | set(parameters) | set(free.values())
    sharing = _Sharing()
    share = sharing.share
    condition_values: list[sp.Expr] = []
    branch_conditions: list[tuple[int, ...]] = []
    joint_values: list[sp.Expr] = []
    for program in programs:
        values: dict[sp.Symbol, sp.Expr] = dict(free)
        indices: list[int] = []
        for symbol, expr in program.assignments:
            expr = sp.sympify(expr).xreplace(free)
            unknown = sorted(str(s) for s in expr.free_symbols - known - set(values))
            if unknown:
                raise CodegenError(f"inverse kinematics, branch {', '.join(program.branch) or '(only)'}: "
                                   f"{symbol} = {expr} reads {', '.join(unknown)}, neither a pose symbol, a "
                                   "parameter nor assigned before")
            value = share(sharing.rewritten(expr.xreplace(values)))
            if symbol in program.conditions:
                if value not in condition_values:
                    condition_values.append(value)
                indices.append(condition_values.index(value))
                value = share(IKClamp(value))
            values[symbol] = value
        missing = [str(j) for j in joints if j not in values]
        if missing:
            raise CodegenError(f"inverse kinematics, branch {', '.join(program.branch) or '(only)'}: no value for "
                               f"{', '.join(missing)}")
        branch_conditions.append(tuple(sorted(set(indices))))
        joint_values += [share(sp.sympify(c).xreplace(values)) for c in outputs]
    flat = [*condition_values, *joint_values]

    def snapped(y: sp.Expr, x: sp.Expr) -> sp.Expr:
        return IKAtan2(y, x, x**2 + y**2)

    definitions = [(symbol, value.replace(sp.atan2, snapped)) for symbol, value in sharing.definitions]
    flat = [value.replace(sp.atan2, snapped) for value in flat]
    temporaries, reduced = eliminate_common(flat, _needed(definitions, flat))
    temporaries = _needed(temporaries, reduced)
    op_count = sum(int(sp.count_ops(e)) for _, e in temporaries) + sum(int(sp.count_ops(e)) for e in reduced)
    inputs = (("pose", pose_symbols()), *((("q_free", (Q_FREE,)),) if free else ()))
    lowered = LoweredFunction(inputs, (), tuple(temporaries), tuple(reduced),
                              tuple(flat), (len(flat),), op_count, f"closed form ({family})" if family else
                              "closed form")
    return InverseKinematics(lowered, family, tuple(tuple(p.branch) for p in programs), tuple(branch_conditions),
                             len(condition_values), len(outputs), tuple(revolute), free_joint,
                             "" if free_joint is None else str(joints[free_joint - 1]))


class IKInverse(sp.Function):
    """``IKInverse(r)``: ``1 / r`` where ``r`` exceeds :data:`IK_NOISE`, else 0 (``r``: an atan2's arguments' length).

    ``sin(atan2(y, x)) = y / r`` and ``cos(atan2(y, x)) = x / r`` with ``r = sqrt(x^2 + y^2)``: generated code
    computes one inverse and two products instead of a sine and a cosine. Where ``r = 0``, ``atan2(0, 0) = 0``:
    the sine ``y IKInverse(r)`` is 0 and the cosine (:class:`IKCosine`) 1.
    """

    nargs = 1


IK_NOISE = 1e-14
"""Rounding noise: a condition below it is taken as 0 exactly where it is used (1 - c^2 for a cosine c rounded to 1
is a few 1e-16, whose square root, 1e-8, would move a pose exactly at a singularity by that much), and an atan2
whose arguments are shorter is 0 (rounding errors would pick any angle there)."""


class IKClamp(sp.Function):
    """``IKClamp(d)``: a condition ``d`` where it exceeds :data:`IK_NOISE`, else 0 (never negative)."""

    nargs = 1


class IKAtan2(sp.Function):
    """``IKAtan2(y, x, r2)``: ``atan2(y, x)`` where ``r2 = x^2 + y^2`` exceeds :data:`IK_NOISE` squared, else 0.

    At a singular pose the arguments of an atan2 vanish and their rounding errors would pick any angle; 0 is the
    representative the closed form's later steps are written for (with :class:`IKInverse`'s sine 0 and cosine 1).
    """

    nargs = 3


class IKCosine(sp.Function):
    """``IKCosine(x, inverse)``: ``x inverse`` where ``inverse > 0``, else 1 (the cosine of ``atan2(0, 0) = 0``)."""

    nargs = 2


class _Sharing:
    """Values named once across branches, and the sines and cosines of angles made of ``atan2`` without trigonometry."""

    def __init__(self) -> None:
        self.definitions: list[tuple[sp.Symbol, sp.Expr]] = []
        self.by_value: dict[sp.Expr, sp.Expr] = {}
        self.value_of: dict[sp.Symbol, sp.Expr] = {}
        self.units: dict[sp.Expr, tuple[sp.Expr, sp.Expr] | None] = {}
        self.names = sp.numbered_symbols("_ik", real=True)

    def share(self, value: sp.Expr) -> sp.Expr:
        """The one name of ``value`` (a symbol or a number is its own)."""
        if value.is_Symbol or value.is_Number:
            return value
        if value not in self.by_value:
            symbol = next(self.names)
            self.definitions.append((symbol, value))
            self.by_value[value] = symbol
            self.value_of[symbol] = value
        return self.by_value[value]

    def rewritten(self, expr: sp.Expr) -> sp.Expr:
        """``expr`` with its sines and cosines of angles made of atan2s as ratios (:class:`IKInverse`).

        An ``atan2`` whose first argument reads as negated is written negated (``atan2(-y, x) = -atan2(y, x)``, also
        where both vanish: 0 stays the representative), so that branches differing by that sign share it. The angles
        whose sine and cosine become ratios are atan2s, their sums and differences, and multiples of pi. An even
        power of a square root is the power of its argument.
        """

        def atan2(y: sp.Expr, x: sp.Expr) -> sp.Expr:
            if y.could_extract_minus_sign():
                return -atan2(-y, x)
            return sp.atan2(y, x)

        def trig(function: type, angle: sp.Expr) -> sp.Expr:
            unit = self.unit(angle)
            if unit is None:
                return function(angle)
            return self.share(unit[0] if function is sp.sin else unit[1])

        def squared(power: sp.Pow) -> sp.Expr:  # sqrt(x)**(2 k) = x**k, where the root was given a name
            root = self.value_of.get(power.base)
            if root is not None and root.is_Pow and root.exp == sp.S.Half and power.exp.is_Integer \
                    and int(power.exp) % 2 == 0:
                return root.base ** (int(power.exp) // 2)  # type: ignore[no-any-return]
            return power

        expr = expr.replace(lambda e: e.is_Pow and e.base in self.value_of, squared)
        expr = expr.replace(sp.atan2, atan2)
        return expr.replace(sp.sin, lambda a: trig(sp.sin, a)).replace(sp.cos, lambda a: trig(sp.cos, a))

    def unit(self, angle: sp.Expr) -> tuple[sp.Expr, sp.Expr] | None:
        """``(sin(angle), cos(angle))`` without a sine or cosine, or None when ``angle`` is not made of atan2s."""
        if angle in self.units:
            return self.units[angle]
        found: tuple[sp.Expr, sp.Expr] | None = None
        if angle.is_Symbol and angle in self.value_of:
            found = self.unit(self.value_of[angle])
        elif isinstance(angle, sp.atan2):
            y, x = angle.args
            inverse = self.share(IKInverse(self.share(sp.sqrt(x**2 + y**2))))
            found = (self.share(y * inverse), self.share(IKCosine(x, inverse)))
        elif angle.is_Mul and angle.args[0] == -1 and len(angle.args) == 2:
            inner = self.unit(angle.args[1])
            found = None if inner is None else (-inner[0], inner[1])
        elif angle.is_number and (angle / sp.pi).is_Integer:
            found = (sp.sin(angle), sp.cos(angle))
        elif angle.is_Add:
            first, rest = angle.args[0], sp.Add(*angle.args[1:])
            a, b = self.unit(first), self.unit(rest)
            if a is not None and b is not None:
                found = (self.share(sp.expand(a[0] * b[1] + a[1] * b[0])),
                         self.share(sp.expand(a[1] * b[1] - a[0] * b[0])))
        self.units[angle] = found
        return found


def _needed(definitions: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
            ) -> list[tuple[sp.Symbol, sp.Expr]]:
    """The ``definitions`` the ``outputs`` read, directly or through others, in their order (no unused temporary)."""
    needed = set().union(*(sp.sympify(e).free_symbols for e in outputs))
    kept = []
    for symbol, expr in reversed(definitions):
        if symbol in needed:
            kept.append((symbol, expr))
            needed |= expr.free_symbols
    return kept[::-1]


@memoized()
def lowered_inverse_kinematics(chain: Chain, free_joint: int | None = None) -> InverseKinematics:
    """The robot's closed form (its plan's branch programs) lowered; NoClosedFormError for an arm without one.

    Its solutions are in the robot's coordinates (a coupled robot's joint values written as its coordinates, as
    every other generated function takes them).

    With ``free_joint`` (a joint number, 1-based) the closed form with that joint given (``closed_form_plan(robot,
    free_joint=...)``): its value is the input ``q_free`` (:data:`Q_FREE`).
    """
    from symjac.analysis.inverse_kinematics import branch_programs, closed_form_plan

    robot = chain.robot
    if free_joint is not None and (isinstance(free_joint, bool) or not isinstance(free_joint, int)
                                   or not 1 <= free_joint <= robot.n_joints):
        raise CodegenError(f"inverse kinematics: free_joint is a joint number, 1 to {robot.n_joints} for "
                           f"{robot.name}, got {free_joint!r}")
    plan = closed_form_plan(robot, free_joint=free_joint)
    if plan.free_joint != free_joint:
        raise CodegenError(f"inverse kinematics: the closed form of {robot.name} takes joint "
                           f"{plan.free_joint} as given; ask for it with free_joint")
    revolute = tuple(kind.value == "revolute" for kind in robot.coordinate_types)
    return lower_branch_programs(branch_programs(plan), robot.joint_variables,
                                 tuple(p.symbol for p in robot.geometric_parameters),
                                 revolute, plan.family, plan.free_joint, coordinates_of_joints(robot))


def inverse_kinematics_of(robot: Robot | Chain, free_joint: int | None = None) -> InverseKinematics:
    """:func:`lowered_inverse_kinematics` of a robot or chain."""
    return lowered_inverse_kinematics(as_chain(robot), free_joint)


def closed_or_numeric(chain: Chain, target: str, asked: bool, free_joint: int | None = None
                      ) -> tuple[InverseKinematics | None, bool]:
    """The closed form when ``asked`` and the arm has one; else whether the numeric solver stands in for it.

    An arm without a closed form gets the numeric solver (``inverse_kinematics_numeric``, with a seed) in the
    targets that have it (:data:`~symjac.codegen.ik_numeric.NUMERIC_IK_TARGETS`); in another target its
    :class:`~symjac.errors.NoClosedFormError` (which says why, and points to the numeric solver) propagates, as it
    does with ``free_joint`` (the closed form with that joint given, which the numeric solver does not stand in for).
    """
    from symjac.errors import NoClosedFormError

    if not asked:
        if free_joint is not None:
            raise CodegenError("free_joint is the given joint of the closed-form inverse kinematics: ask for "
                               "inverse_kinematics too")
        return None, False
    try:
        return inverse_kinematics_of(chain, free_joint), False
    except NoClosedFormError:
        if target not in NUMERIC_IK_TARGETS or free_joint is not None:
            raise
        return None, True


def ik_listing(ik: InverseKinematics | None) -> tuple[tuple[str, str], ...]:
    """The module docstring's line for ``inverse_kinematics``, or none without it."""
    if ik is None:
        return ()
    given = "" if ik.free_joint is None else f" and joint {ik.free_joint}'s value q_free"
    return (("inverse_kinematics", f"Every closed-form solution ({ik.family or 'closed form'}) for a pose{given}, at "
             f"most {ik.max_solutions} (branches {'; '.join(ik.branch_names)}), and their count."),)
