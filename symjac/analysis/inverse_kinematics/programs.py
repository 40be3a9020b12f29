r"""The symbolic executor of a closed-form plan: one straight-line program of formulas per branch.

Each step's subproblem is solved in symbols (the ``*_symbolic`` functions of
:mod:`~symjac.analysis.inverse_kinematics.subproblems`) on the step's arguments, which are written in the pose symbols,
the robot's parameters, the definitions' symbols and the earlier joints' variables. Every square root's argument
becomes an assigned symbol of its own (``Delta1``, ``Delta2``, ...), listed in the program's ``conditions``: the
branch exists where each is ``>= 0``. A sum of squares is no condition (it is never negative), and generated code
takes its root unclamped: the PUMA's ``Delta3 = q4_x^2 + q4_y^2`` (``sin(theta5)^2``) is accurate to rounding at
``theta5 = 1e-8``, where clamping below rounding noise would set ``theta5 = 0``. Each small expression is simplified
on its own, so the formulas stay readable: for the PUMA 560, ``theta1`` comes out as the textbook
``atan2(py, px) - atan2(d3, -+sqrt(Delta1))`` with ``Delta1 = px^2 + py^2 - d3^2``.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass
from typing import Any

import sympy

from symjac.analysis.inverse_kinematics import subproblems
from symjac.analysis.inverse_kinematics.plan import Plan, Step, branch_choices, branch_names

__all__ = ["BranchProgram", "branch_programs"]


@dataclass(frozen=True)
class BranchProgram:
    """The formulas of one branch, in order: definitions, intermediates, square-root arguments, joint variables.

    ``conditions`` are the assigned symbols that must be ``>= 0`` for the branch to exist (each square root's
    argument); generated code clamps one within ``-tolerance`` of zero to zero and drops the branch below.
    """

    branch: tuple[str, ...]
    assignments: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    conditions: tuple[sympy.Symbol, ...]


SIMPLIFY_LIMIT = 200
"""Expressions with more operations than this are expanded only: simplify costs minutes on them, and nobody reads
them (the last wrist joint of a 7-joint arm with its redundancy parameter)."""


def _simple(expr: sympy.Expr) -> sympy.Expr:
    expanded = sympy.expand(expr)
    if sympy.count_ops(expanded) > SIMPLIFY_LIMIT:
        return expanded
    return sympy.factor_terms(sympy.simplify(expanded))


def _positive_factor(expr: sympy.Expr) -> bool:
    """A factor known to be positive where the branch exists: a positive number or a condition's square root."""
    if expr.is_number:
        return bool(expr.is_positive)
    return isinstance(expr, sympy.Pow) and expr.exp.is_positive and expr.base.is_Symbol \
        and expr.base.name.startswith("Delta")


def _atan2(y: sympy.Expr, x: sympy.Expr) -> sympy.Expr:
    """``atan2(y, x)`` with each argument simplified and their common positive factors cancelled."""
    y, x = _simple(y), _simple(x)
    if y != 0 and x != 0:
        factors_y, factors_x = sympy.Mul.make_args(sympy.factor_terms(y)), sympy.Mul.make_args(sympy.factor_terms(x))
        shared = [f for f in factors_y if f in factors_x and _positive_factor(f)]
        if shared:
            scale = sympy.Mul(*shared)
            y, x = sympy.simplify(y / scale), sympy.simplify(x / scale)
    return sympy.atan2(y, x)


def _tidy(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with each ``atan2`` tidied on its own (a whole-expression simplify mangles atan2)."""
    return expr.replace(lambda e: isinstance(e, sympy.atan2), lambda e: _atan2(*e.args))


@dataclass(frozen=True)
class _SolvedStep:
    step: Step
    intermediates: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    solutions: tuple[tuple[sympy.Expr, ...], ...]
    conditions: tuple[sympy.Symbol, ...]


def _named_arguments(step: Step, variables: set[sympy.Symbol],
                     intermediates: list[tuple[sympy.Symbol, sympy.Expr]]) -> dict[str, Any]:
    """The step's arguments, those that depend on earlier joints given names of their own (``q4_x`` ...)."""
    first = step.joints[0] + 1
    arguments: dict[str, Any] = {}
    for name, value in step.arguments.items():
        if isinstance(value, sympy.MatrixBase):
            matrix = sympy.Matrix(value)
            if matrix.free_symbols & variables:
                entries = []
                for axis, entry in zip("xyz", matrix, strict=True):
                    entry = _simple(entry)
                    if sympy.count_ops(entry) > 2:  # short entries (0, sin(theta3)) stay written out
                        symbol = sympy.Symbol(f"{name}{first}_{axis}", real=True)
                        intermediates.append((symbol, entry))
                        entry = symbol
                    entries.append(entry)
                matrix = sympy.Matrix(entries)
            arguments[name] = matrix
        elif sympy.sympify(value).free_symbols & variables:
            symbol = sympy.Symbol(f"{name}{first}", real=True)
            intermediates.append((symbol, _simple(value)))
            arguments[name] = symbol
        else:
            arguments[name] = value
    return arguments


def _never_negative(expr: sympy.Expr) -> bool:
    """A sum of squares, each times a positive number."""
    return all(all(factor.is_positive or (factor.is_Pow and factor.exp.is_even) for factor in sympy.Mul.make_args(term))
               for term in sympy.Add.make_args(expr))


def _rooted(expr: sympy.Expr) -> bool:
    return any(power.exp == sympy.S.Half for power in expr.atoms(sympy.Pow))


def _solve(step: Step, counter: itertools.count, variables: set[sympy.Symbol]) -> _SolvedStep:  # type: ignore[type-arg]
    solve = getattr(subproblems, f"{step.subproblem}_symbolic")
    intermediates: list[tuple[sympy.Symbol, sympy.Expr]] = []
    result = solve(**_named_arguments(step, variables, intermediates))
    roots: dict[sympy.Expr, sympy.Symbol] = {}
    conditions: list[sympy.Symbol] = []

    def named(root: sympy.Pow) -> sympy.Expr:
        argument = _simple(root.base)
        if argument.is_number or (argument.is_Pow and argument.exp == 2):  # a constant or a square: no condition
            return sympy.sqrt(argument)
        if argument not in roots:
            symbol = sympy.Symbol(f"Delta{next(counter)}", real=True)
            roots[argument] = symbol
            intermediates.append((symbol, argument))
            if not _never_negative(argument):
                conditions.append(symbol)
        return sympy.sqrt(roots[argument])

    cosines: dict[sympy.Expr, sympy.Symbol] = {}

    def named_cosine(value: sympy.Expr) -> sympy.Expr:
        """``value`` with each long cosine side of a half angle ``atan2(sqrt(D), N)`` named ``N<k>``, in ``D`` too."""
        for angle in sorted(value.atoms(sympy.atan2), key=sympy.default_sort_key):
            y, x = angle.args
            if _rooted(y) and not _rooted(x) and sympy.count_ops(x) > 6 and x.free_symbols - variables:
                if x not in cosines:
                    cosines[x] = sympy.Symbol(f"N{step.joints[0] + 1}{'_' * len(cosines)}", real=True)
                    intermediates.append((cosines[x], _simple(x)))
                value = value.xreplace({x: cosines[x]})
        return value

    solutions = []
    for solution in result.solutions:
        solutions.append(tuple(
            _tidy(named_cosine(value).replace(lambda e: isinstance(e, sympy.Pow) and e.exp == sympy.S.Half, named))
            for value in solution))
    return _SolvedStep(step, tuple(intermediates), tuple(solutions), tuple(conditions))


@functools.lru_cache(maxsize=32)
def _solved(plan: Plan) -> tuple[_SolvedStep, ...]:
    counter = itertools.count(1)
    variables = set(plan.robot.joint_variables)
    return tuple(_solve(step, counter, variables) for step in plan.steps)


def branch_programs(plan: Plan) -> tuple[BranchProgram, ...]:
    """One :class:`BranchProgram` per branch of ``plan`` (the product of its steps' solution counts), in symbols.

    The assignments use the robot's own parameter symbols (no defaults) and the plan's definition symbols; a joint
    variable is assigned once its step has run, and later formulas use it by name.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.analysis.inverse_kinematics import closed_form_plan
    >>> programs = branch_programs(closed_form_plan(load_robot("puma560")))
    >>> len(programs), programs[0].branch
    (8, ('shoulder right', 'elbow down', 'no flip'))
    """
    solved = _solved(plan)
    variables = plan.robot.joint_variables
    programs = []
    for choice in branch_choices(plan.steps, [len(s.solutions) for s in solved]):
        assignments: list[tuple[sympy.Symbol, sympy.Expr]] = list(plan.definitions)
        conditions: list[sympy.Symbol] = []
        for step, index in zip(solved, choice, strict=True):
            assignments.extend(step.intermediates)
            conditions.extend(step.conditions)
            assignments.extend((variables[j], value) for j, value in zip(step.step.joints, step.solutions[index],
                                                                         strict=True))
        programs.append(BranchProgram(branch_names(plan.steps, choice), tuple(assignments), tuple(conditions)))
    return tuple(programs)
