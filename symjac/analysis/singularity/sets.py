r"""The singular sets of a redundant arm: where every square minor of its Jacobian vanishes at once.

An arm with more joints than task rows (:math:`m \times n`, :math:`n > m`) loses rank exactly where all its
:math:`m \times m` minors vanish together, since by the Cauchy-Binet formula
:math:`\det J J^T = \sum_S \det(J_S)^2` over the sets :math:`S` of :math:`m` columns. Each minor is already factored
(:func:`symjac.analysis.singularity.determinant.determinant`), so wherever the arm is singular, every minor has a
vanishing factor, and the singular set is a union of *components*, each a conjunction
:math:`f_1 = 0 \wedge \dots \wedge f_k = 0` of minor factors (or of single solution branches of them, such as
:math:`\theta_4 = 0` of :math:`s_4 = 0`) on which every minor vanishes.

:func:`singular_conditions` finds the minimal components:

1. every factor that depends on the joints is solved (:func:`symjac.analysis.singularity.solve.solve_factor`); a
   *condition* is a factor with all its branches, or one branch alone when the factor has several;
2. every conjunction of one to three conditions, each solved for a different joint, is sampled at random points
   (the other joints uniform, the parameters within 20 % of their defaults) and kept when every minor vanishes there
   (relative to its size at random configurations, to :data:`RELATIVE_ZERO`): a polynomial identity checked at
   random points, as in the Schwartz-Zippel lemma. All conjunctions are evaluated at once, as arrays;
3. a conjunction is dropped when a kept one contains it (fewer conditions, or a branch of its condition).

The conditions and their solutions are exact; only the test of which conjunctions make the arm singular is
numerical, and the tests check each reported set against the smallest singular value of :math:`J`.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import Determinant
from symjac.analysis.singularity.solve import Solution, alternative_solutions, branch_solutions, solve_factor
from symjac.kinematics.chain import Chain
from symjac.model.robot import JointType

__all__ = ["RELATIVE_ZERO", "Condition", "condition_samples", "singular_conditions", "unsolved_factors"]

RELATIVE_ZERO = 1e-7
"""A minor counts as zero at a point when it is this small relative to its median size at random configurations."""

_SAMPLES = 12  # random points per conjunction (each condition's branch drawn at random for each)
_MOST_CONDITIONS = 3  # conjunctions of up to this many conditions are tried
_PROJECTION_STEPS = 25  # Gauss-Newton steps onto a conjunction the branch formulas cannot place
_SOLVE_OPS = 40  # larger factors are solved for their last joint only, unlaid (solve_factor takes seconds on them)


@dataclass(frozen=True)
class Condition:
    r"""``expression = 0``, with its solution branches (each ``lhs = rhs``) and when they exist at all."""

    expression: sp.Expr
    solutions: tuple[Solution, ...]
    existence: sp.Expr | None

    @functools.cached_property
    def branches(self) -> frozenset[tuple[sp.Expr, sp.Expr]]:
        """The solutions as (lhs, rhs) pairs; two conditions with the same branches are the same set."""
        return frozenset((s.lhs, s.rhs) for s in self.solutions)


@dataclass(frozen=True)
class _Branch:
    """A solution compiled: the joint it sets (0-based) and its value as a function of (q, parameters)."""

    joint: int
    value: object  # a NumPy function of the coordinates then the parameters


def _pick(solution: Solution, variables: Sequence[sp.Symbol]) -> int | None:
    """The joint a solution is solved for: the latest in its left side, absent from its right side, coefficient 1."""
    if solution.lhs.atoms(sp.Function) or not solution.lhs.free_symbols <= set(variables):
        return None
    candidates = [variables.index(v) for v in solution.lhs.free_symbols if not solution.rhs.has(v)]
    if not candidates:
        return None
    pick = max(candidates)
    return pick if sp.expand(solution.lhs).coeff(variables[pick]) == 1 else None


def unsolved_factors(chain: Chain, minors: Sequence[Determinant]) -> tuple[sp.Expr, ...]:
    """The joint factors of ``minors`` that could not be solved for one joint, so no condition of the search."""
    return _conditions(chain, minors)[1]


def _conditions(chain: Chain, minors: Sequence[Determinant],
                every_joint: bool = False) -> tuple[list[Condition], tuple[sp.Expr, ...]]:
    """Every joint factor of the minors solved, and each branch of a factor with several; equal sets merged.

    Also the factors left out because no solution for one joint was found. With ``every_joint``, a factor is also
    solved for each other joint it can be solved for (one condition per joint), so that it can join a condition on
    its best joint.
    """
    variables = set(chain.robot.q)
    skipped: list[sp.Expr] = []
    found: dict[frozenset[tuple[sp.Expr, sp.Expr]], Condition] = {}
    factors = dict.fromkeys(f for minor in minors for f, _ in minor.factors if f.free_symbols & variables)
    for factor in factors:
        if sp.count_ops(factor) <= _SOLVE_OPS:
            solutions, existence = solve_factor(chain, factor)
        else:
            solutions, existence = branch_solutions(chain, factor), None
        if not solutions or any(_pick(s, chain.robot.q) is None for s in solutions):
            skipped.append(factor)
            continue
        readings = [(solutions, existence)]
        if every_joint and sp.count_ops(factor) <= _SOLVE_OPS:
            readings += _other_joints(chain, factor, solutions)
        for solved, exists in readings:
            candidates = [Condition(factor, solved, exists)]
            if len(solved) > 1:
                candidates += [Condition(s.lhs - s.rhs, (s,), exists) for s in solved]
            for condition in candidates:
                found.setdefault(condition.branches, condition)
    ordered = sorted(found.values(), key=lambda c: (len(c.expression.free_symbols & variables),
                                                    sp.count_ops(c.expression), sp.default_sort_key(c.expression)))
    return ordered, tuple(skipped)


def _other_joints(chain: Chain, factor: sp.Expr, solutions: Sequence[Solution]
                  ) -> list[tuple[tuple[Solution, ...], sp.Expr | None]]:
    """The best solution of ``factor = 0`` for each joint other than that of ``solutions``."""
    variables = chain.robot.q
    taken = {_pick(s, variables) for s in solutions}
    readings = []
    for solved, existence in alternative_solutions(chain, factor):
        joints = {_pick(s, variables) for s in solved}
        if None not in joints and len(joints) == 1 and not joints & taken:
            taken |= joints
            readings.append((solved, existence))
    return readings


def _implies(small: Sequence[Condition], large: Sequence[Condition]) -> bool:
    """Whether the set of ``small`` lies in that of ``large``: each condition of ``large`` holds by one of ``small``."""
    return all(any(s.branches <= condition.branches for s in small) for condition in large)


class _Sampler:
    """Random points on conjunctions of conditions, and the minors' factors evaluated there, all as arrays."""

    def __init__(self, chain: Chain, minors: Sequence[Determinant], seed: int, project: bool = False) -> None:
        robot = chain.robot
        self.project = project  # points the branch formulas cannot place are projected onto the conditions
        self.angles = [kind is not JointType.PRISMATIC for kind in robot.coordinate_types]
        self.variables = list(robot.q)
        self.parameters = [p.symbol for p in robot.geometric_parameters]
        arguments = [*self.variables, *self.parameters]
        self.generator = np.random.default_rng(seed)
        joint_factors = [[f for f, _ in minor.factors if f.free_symbols & set(self.variables)] for minor in minors]
        self.minor_factors = [[_compiled(f, tuple(arguments)) for f in fs] for fs in joint_factors]
        self.arguments = arguments
        self.defaults = np.array([float(p.default) for p in robot.geometric_parameters])
        q, p = self.random_points(64)
        with np.errstate(all="ignore"):
            self.scales = [[_median_size(g, q, p) for g in gs] for gs in self.minor_factors]
        self.compiled: dict[tuple[sp.Expr, sp.Expr], _Branch] = {}
        self.scales_of: dict[sp.Expr, float] = {}

    def random_points(self, count: int, defaults: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """Joint values uniform in [-2.5, 2.5]; parameters within 20 % of their defaults (or at them).

        Each parameter also moves by up to 5 % of the largest default, so a parameter whose default is zero is
        varied too: a set that needs it to be zero is a special design, not found as a general one.
        """
        q = self.generator.uniform(-2.5, 2.5, (count, len(self.variables)))
        shape = (count, len(self.parameters))
        if defaults:
            return q, np.broadcast_to(self.defaults, shape).copy()
        typical = float(np.abs(self.defaults).max(initial=0.0)) or 1.0
        spread = self.generator.uniform(-0.05, 0.05, shape) * typical
        return q, self.defaults * self.generator.uniform(0.8, 1.2, shape) + spread

    def branch(self, solution: Solution) -> _Branch:
        key = (solution.lhs, solution.rhs)
        if key not in self.compiled:
            joint = _pick(solution, self.variables)
            assert joint is not None  # conditions were filtered by _pick
            value = solution.rhs - (solution.lhs - self.variables[joint])
            self.compiled[key] = _Branch(joint, _compiled(value, tuple(self.arguments)))
        return self.compiled[key]

    def place(self, conjunctions: Sequence[Sequence[Condition]], q: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Move each row of ``q`` onto its conjunction (row r belongs to conjunction r // samples); valid rows."""
        samples = len(q) // len(conjunctions)
        rows: dict[tuple[sp.Expr, sp.Expr], list[int]] = {}
        for index, conjunction in enumerate(conjunctions):
            for condition in conjunction:  # each condition's branch drawn on its own: every combination is met
                picks = self.generator.integers(0, len(condition.solutions), samples)
                for k in range(samples):
                    solution = condition.solutions[int(picks[k])]
                    rows.setdefault((solution.lhs, solution.rhs), []).append(index * samples + k)
        solutions = {(s.lhs, s.rhs): s for c in {c for cs in conjunctions for c in cs} for s in c.solutions}
        with np.errstate(all="ignore"):
            for _ in range(max(len(c) for c in conjunctions)):  # later conditions may feed earlier ones
                for key, chosen in rows.items():
                    branch, chosen_rows = self.branch(solutions[key]), np.array(chosen)
                    q[chosen_rows, branch.joint] = _evaluate(branch.value, q[chosen_rows], p[chosen_rows])
            valid = np.all(np.isfinite(q), axis=1)
            for key, chosen in rows.items():
                branch, chosen_rows = self.branch(solutions[key]), np.array(chosen)
                value = _evaluate(branch.value, q[chosen_rows], p[chosen_rows])
                valid[chosen_rows] &= np.abs(_wrap(value - q[chosen_rows, branch.joint])) < 1e-9
        if self.project:
            for index, conjunction in enumerate(conjunctions):
                failed = index * samples + np.flatnonzero(~valid[index * samples:(index + 1) * samples])
                if len(failed):
                    q[failed] = self.generator.uniform(-2.5, 2.5, (len(failed), q.shape[1]))
                    valid[failed] = self.projected(conjunction, q, p, failed)
        return valid

    def projected(self, conjunction: Sequence[Condition], q: np.ndarray, p: np.ndarray, rows: np.ndarray) -> np.ndarray:
        r"""Move ``q[rows]`` onto every condition of ``conjunction`` by Gauss-Newton steps; which rows arrived.

        Each step solves :math:`G \Delta q = -g` in the least-squares, least-norm sense (:math:`G` the conditions'
        gradients by central differences); a branch condition on an angle is measured modulo :math:`2\pi`. Used
        where the branch formulas feed each other in a circle (:math:`c_{234} = 0` solved for :math:`\theta_4`
        and a factor solved for :math:`\theta_2` in terms of :math:`\theta_4`).
        """
        functions = [(_compiled(c.expression, tuple(self.arguments)), self.wrapped(c)) for c in conjunction]
        x, parameters = q[rows], p[rows]

        def residuals(points: np.ndarray) -> np.ndarray:
            values = [_evaluate(f, points, parameters) for f, _ in functions]
            return np.stack([_wrap(v) if wrap else v for v, (_, wrap) in zip(values, functions, strict=True)], 1)

        step = 1e-6
        with np.errstate(all="ignore"):
            for _ in range(_PROJECTION_STEPS):
                g = np.nan_to_num(residuals(x), nan=0.0, posinf=0.0, neginf=0.0)
                gradient = np.nan_to_num(np.stack([(residuals(x + step * e) - residuals(x - step * e)) / (2 * step)
                                                   for e in np.eye(x.shape[1])], axis=2), nan=0.0, posinf=0.0,
                                         neginf=0.0)
                x = x - np.einsum("kji,ki->kj", np.linalg.pinv(gradient), g)
                x = np.where(np.isfinite(x), x, 0.0)
            scales = np.array([self.scale(c.expression) for c in conjunction])
            arrived = np.all(np.abs(residuals(x)) <= RELATIVE_ZERO * scales, axis=1)
        q[rows] = x
        return arrived

    def wrapped(self, condition: Condition) -> bool:
        """Whether a condition is one branch ``angle - value`` of a factor (measured modulo 2 pi)."""
        (solution, *others) = condition.solutions
        if others or condition.expression != solution.lhs - solution.rhs:
            return False
        joint = _pick(solution, self.variables)
        return joint is not None and self.angles[joint]

    def contained(self, inner: Sequence[Condition], outer: Sequence[Condition]) -> bool:
        """Whether random points on ``inner`` all satisfy every condition of ``outer``.

        A condition holds where its expression vanishes relative to its size at random configurations (its branch
        formulas are no test: they are undefined where the expression vanishes for every value of the solved
        joint).
        """
        q, p = self.random_points(4 * _SAMPLES)
        valid = self.place([tuple(inner)], q, p)
        if valid.sum() < 2:
            return False
        q, p = q[valid], p[valid]
        with np.errstate(all="ignore"):
            for condition in outer:
                function = _compiled(condition.expression, tuple(self.arguments))
                if not np.all(np.abs(_evaluate(function, q, p)) <= RELATIVE_ZERO * self.scale(condition.expression)):
                    return False
        return True

    def on(self, conjunction: Sequence[Condition], q: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Rows of ``q`` where every condition of ``conjunction`` holds (a branch of an angle modulo 2 pi)."""
        result = np.ones(len(q), dtype=bool)
        with np.errstate(all="ignore"):
            for condition in conjunction:
                value = _evaluate(_compiled(condition.expression, tuple(self.arguments)), q, p)
                value = _wrap(value) if self.wrapped(condition) else value
                result &= np.abs(value) <= 1e3 * RELATIVE_ZERO * self.scale(condition.expression)
        return result

    def scale(self, expr: sp.Expr) -> float:
        """The median size of ``expr`` at random configurations and parameters (kept per expression)."""
        if expr not in self.scales_of:
            q, p = self.random_points(64)
            with np.errstate(all="ignore"):
                self.scales_of[expr] = _median_size(_compiled(expr, tuple(self.arguments)), q, p)
        return self.scales_of[expr]

    def singular(self, q: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Rows where every minor has a factor that vanishes (relative to its size at random configurations)."""
        result = np.ones(len(q), dtype=bool)
        with np.errstate(all="ignore"):
            for factors, scales in zip(self.minor_factors, self.scales, strict=True):
                vanishes = np.zeros(len(q), dtype=bool)
                for g, scale in zip(factors, scales, strict=True):
                    vanishes |= np.abs(_evaluate(g, q, p)) <= RELATIVE_ZERO * scale
                result &= vanishes
        return result


@functools.lru_cache(maxsize=512)
def _compiled(expr: sp.Expr, arguments: tuple[sp.Symbol, ...]) -> object:
    """``expr`` as a NumPy function of ``arguments`` (kept: the search and the explanation ask for the same ones)."""
    return sp.lambdify(arguments, expr, modules="numpy")


def _evaluate(function: object, q: np.ndarray, p: np.ndarray) -> np.ndarray:
    values = function(*q.T, *p.T)  # type: ignore[operator]
    return np.broadcast_to(np.real_if_close(np.asarray(values, dtype=complex)), (len(q),)).real \
        if np.iscomplexobj(values) else np.broadcast_to(np.asarray(values, dtype=float), (len(q),))


def _wrap(angle: np.ndarray) -> np.ndarray:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def _median_size(function: object, q: np.ndarray, p: np.ndarray) -> float:
    sizes = np.abs(_evaluate(function, q, p))
    finite = sizes[np.isfinite(sizes)]
    return float(np.median(finite)) or 1.0 if finite.size else 1.0


def singular_conditions(chain: Chain, minors: Sequence[Determinant], seed: int = 0,
                        every_joint: bool = False) -> tuple[tuple[Condition, ...], ...]:
    """The minimal conjunctions of conditions on which every minor in ``minors`` vanishes (see the module docstring).

    Minors that vanish identically are left out by the caller; ordered by number of conditions, then joints.
    ``every_joint`` also tries each factor solved for its other joints (a short arm's few minors).
    """
    sampler = _Sampler(chain, minors, seed, project=every_joint)
    conditions, _ = _conditions(chain, minors, every_joint)
    picks = {c.branches: {_pick(s, sampler.variables) for s in c.solutions} for c in conditions}
    kept: list[tuple[Condition, ...]] = []
    for size in range(1, _MOST_CONDITIONS + 1):  # size by size: a superset of a kept set is not even tried
        candidates = []
        for conjunction in itertools.combinations(conditions, size):
            joints = [picks[c.branches] for c in conjunction]
            if any(a & b for a, b in itertools.combinations(joints, 2)):
                continue
            if not any(_implies(conjunction, found) for found in kept):
                candidates.append(conjunction)
        if not candidates:
            continue
        q, p = sampler.random_points(len(candidates) * _SAMPLES)
        valid = sampler.place(candidates, q, p)
        singular = sampler.singular(q, p) | ~valid
        valid_count = valid.reshape(len(candidates), _SAMPLES).sum(axis=1)
        holds = singular.reshape(len(candidates), _SAMPLES).all(axis=1) & (valid_count >= 3)
        for conjunction, ok in zip(candidates, holds, strict=True):
            if ok and not any(_implies(conjunction, found) for found in kept):
                kept.append(conjunction)
    kept = [c for c in kept if not any(other is not c and _implies(c, other) for other in kept)]
    # a conjunction can hold a smaller one without saying so (cos(theta3) = 0 with a factor that then reads
    # sin(theta2) (...) = 0): drop every set whose points all satisfy an earlier kept one
    minimal: list[tuple[Condition, ...]] = []
    for conjunction in kept:
        if not any(sampler.contained(conjunction, other) for other in minimal):
            minimal = [other for other in minimal if not sampler.contained(other, conjunction)] + [conjunction]
    kept = _confirmed(sampler, kept) if every_joint else minimal
    variables = set(sampler.variables)
    return tuple(sorted(kept, key=lambda c: (len(c), len(set().union(*(x.expression.free_symbols & variables
                                                                          for x in c))))))


def _confirmed(sampler: _Sampler, kept: Sequence[tuple[Condition, ...]]) -> list[tuple[Condition, ...]]:
    """The sets that fresh points on them confirm: every point singular, not every point on an earlier set.

    Projected points can gather where a conjunction meets a smaller set (the branch formulas of a short arm's
    rewritten factors feed each other), so a set is kept only if its own points show it: all of them singular
    (sound), and not all of them on one set kept before it (a set found again through another reading).
    """
    confirmed: list[tuple[Condition, ...]] = []
    for conjunction in sorted(kept, key=len):
        q, p = sampler.random_points(4 * _SAMPLES)
        valid = sampler.place([conjunction], q, p)
        if valid.sum() < 3:
            continue
        q, p = q[valid], p[valid]
        if not sampler.singular(q, p).all():
            continue
        if any(sampler.on(other, q, p).all() for other in confirmed):
            continue
        confirmed.append(conjunction)
    return confirmed


def condition_samples(chain: Chain, conjunction: Sequence[Condition], count: int, seed: int = 0,
                      defaults: bool = True, project: bool = False) -> np.ndarray:
    """Random configurations on a conjunction (parameters at their defaults); fewer rows where no value exists.

    ``project`` places the points the branch formulas cannot by projection (:meth:`_Sampler.projected`).
    """
    sampler = _Sampler(chain, (), seed, project)
    q, p = sampler.random_points(count, defaults=defaults)
    valid = sampler.place([tuple(conjunction)], q, p)
    return q[valid]
