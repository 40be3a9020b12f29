r"""The data behind the report's pictures: manipulability over two joints, singular curves, rates along a path.

A *plane* is two joints varied over a grid while the others stay fixed. Over it, the manipulability of the task
rows analysed by the singularity report is :math:`w = |\det J|` (square) or :math:`\sqrt{\det J J^T}` (redundant).
The singular curves come from the solved factors (:func:`symjac.analysis.singularity.solve.solve_factor`), not from the
grid: a solution :math:`c_a q_a + c_b q_b + k = r(q_b)` (the right side free of :math:`q_a`) is the exact curve
:math:`q_a = (r(q_b) - c_b q_b - k) / c_a`, evaluated on a fine parameter grid and repeated every :math:`2\pi` for
revolute joints. Only a factor with no such solved form is given by its exact values on a fine grid, whose zero
contour is drawn.

The plane is the pair of joints showing the most solved singular sets (a curve across both joints counts more than
a line in one), the other joints fixed where the factors not involving the plane are farthest from zero. The path
crosses one solved curve along the solved joint, and the commanded velocity is the direction lost there (the left
singular vector of the smallest singular value), so the exact joint rates :math:`J^{-1}\dot x` grow like
:math:`1/|t|` at the crossing (:func:`symjac.analysis.inverse_rates.rates_along_path`).
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.inverse_rates import PathRates, rates_along_path
from symjac.analysis.singularity.redundant import SingularSet, set_joints
from symjac.analysis.singularity.sets import Condition
from symjac.analysis.singularity.singularities import SingularFactor, SingularityReport
from symjac.analysis.singularity.solve import Solution
from symjac.kinematics.chain import Frame
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.robot import JointType, Robot

__all__ = ["Curve", "ManipulabilityMap", "SetMark", "SingularPath", "manipulability_map", "singular_path"]

_KIND_ORDER = ("elbow", "shoulder", "wrist", "other")


@dataclass(frozen=True)
class Curve:
    """Where ``factor`` vanishes in the plane: exact points of its solved ``solutions`` or its values on a grid."""

    factor: SingularFactor
    solutions: tuple[Solution, ...]  # the solutions drawn exactly (empty: the zero contour of ``values``)
    points: tuple[np.ndarray, np.ndarray] | None  # x, y with nan between pieces (solved form)
    values: np.ndarray | None  # the exact factor on the fine grid (no solved form): its zero contour is the curve
    crossing: tuple[float, float] | None  # a point to cross the curve at: simply singular, near the centre


@dataclass(frozen=True)
class SetMark:
    """Where a redundant arm's singular set ``number`` (1-based, as in the report) lies in the plane.

    ``vertical`` and ``horizontal`` hold lines :math:`x = c` and :math:`y = c` (one condition on a plane joint),
    ``points`` the crossings of two such conditions; ``crossing`` is where a path crosses the set.
    """

    number: int
    vertical: tuple[float, ...] = ()
    horizontal: tuple[float, ...] = ()
    points: tuple[tuple[float, float], ...] = ()
    crossing: tuple[float, float] | None = None


@dataclass(frozen=True)
class ManipulabilityMap:
    """Manipulability over a grid of joints ``joints`` (0-based), the others at ``configuration``."""

    joints: tuple[int, int]
    configuration: tuple[float, ...]
    x: np.ndarray
    y: np.ndarray
    w: np.ndarray  # shape (len(y), len(x))
    measure: str  # "|det J|" or "sqrt(det(J J^T))"
    curves: tuple[Curve, ...]
    rows: tuple[int, ...]
    frame: Frame
    point: tuple[sp.Expr, sp.Expr, sp.Expr]
    sets: tuple[SetMark, ...] = ()  # a redundant arm's singular sets lying in the plane, the simplest first


@dataclass(frozen=True)
class SingularPath:
    """A straight path in the plane through a singular configuration, and the joint rates along it."""

    t: np.ndarray  # path parameter, the singular configuration at t = 0
    configurations: np.ndarray  # (m, n)
    xdot: np.ndarray  # commanded velocity on the analysed rows
    rows: tuple[int, ...]
    rates: PathRates
    curve: Curve | None
    set_mark: SetMark | None = None  # the redundant arm's singular set crossed, if any


def _bounds(robot: Robot, coordinate: int) -> tuple[float, float]:
    if robot.coordinate_types[coordinate] is JointType.REVOLUTE:
        return -math.pi, math.pi
    spec = next((j for j in robot.joints if j.variable == robot.q[coordinate]), None)  # its own joint, if any
    if spec is not None and spec.limits is not None:
        return float(spec.limits[0]), float(spec.limits[1])
    return -1.0, 1.0


def _linear(lhs: sp.Expr, q: Sequence[sp.Symbol]) -> dict[sp.Symbol, sp.Expr] | None:
    """Coefficients of ``lhs`` as a linear form in the joint variables (key 1: the constant), or ``None``."""
    try:
        poly = sp.Poly(lhs, *q)
    except sp.PolynomialError:
        return None
    if poly.total_degree() > 1:
        return None
    coefficients = {v: poly.coeff_monomial(v) for v in q}
    coefficients[sp.S.One] = poly.coeff_monomial(1)
    return coefficients


def _parametric(robot: Robot, solution: Solution, a: sp.Symbol, b: sp.Symbol,
                fixed: dict[sp.Symbol, sp.Expr]) -> tuple[sp.Symbol, sp.Symbol, sp.Expr] | None:
    """``(solved, along, expression)``: the solution as ``solved = expression(along)``, exactly, if it can be."""
    coefficients = _linear(solution.lhs, robot.q)
    if coefficients is None:
        return None
    rhs = solution.rhs.xreplace(fixed)
    lhs_rest = sum((c * v for v, c in coefficients.items() if v not in (a, b)), sp.S.Zero).xreplace(fixed)
    for solved, along in ((a, b), (b, a)):
        c = coefficients[solved]
        if c != 0 and not rhs.has(solved):
            return solved, along, (rhs - coefficients[along] * along - lhs_rest) / c
    return None


def _score(robot: Robot, report: SingularityReport, a: int, b: int) -> int:
    q = robot.q
    score = 0
    for factor in _plotted(report):
        involved = {q[a], q[b]} & factor.expression.free_symbols
        if not involved:
            continue
        solved = any(_parametric(robot, s, q[a], q[b], {}) for s in factor.solutions)
        score += (2 * len(involved)) if solved else 1
    return score


def _plotted(report: SingularityReport) -> list[SingularFactor]:
    return [f for f in report.factors if f.solutions and f.exists_for_defaults is not False]


def _plane(robot: Robot, report: SingularityReport) -> tuple[int, int]:
    revolute = [i for i, kind in enumerate(robot.coordinate_types) if kind is JointType.REVOLUTE]
    candidates = revolute if len(revolute) >= 2 else list(range(robot.n_coordinates))
    pairs = list(itertools.combinations(candidates, 2))
    return max(pairs, key=lambda pair: (_score(robot, report, *pair), -pair[1], -pair[0]))


def _fixed(robot: Robot, report: SingularityReport, plane: tuple[int, int], seed: int) -> list[float]:
    """The other joints' values: where the factors not involving the plane are farthest from zero."""
    generator = random.Random(seed)
    plane_symbols = {robot.q[i] for i in plane}
    away = [f.expression.xreplace(robot.defaults) for f in _plotted(report)
            if not f.expression.free_symbols & plane_symbols]
    best: tuple[float, list[float]] | None = None
    for _ in range(24):
        values = [generator.uniform(-2.0, 2.0) if kind is JointType.REVOLUTE
                  else generator.uniform(*_bounds(robot, i)) for i, kind in enumerate(robot.coordinate_types)]
        substitution = dict(zip(robot.q, values, strict=True))
        margin = min((abs(float(f.xreplace(substitution))) for f in away), default=1.0)
        if best is None or margin > best[0] + 1e-12:
            best = (margin, values)
    assert best is not None
    return best[1]


def _simplest_set(report: SingularityReport) -> SingularSet | None:
    """The singular set with the fewest conditions, then joints, among those that exist for the defaults."""
    shown = [s for s in report.sets if s.sample is not None]
    return min(shown, key=lambda s: (len(s.conditions), len(set_joints(s)), report.sets.index(s)), default=None)


def _set_plane(robot: Robot, report: SingularityReport, simplest: SingularSet) -> tuple[int, int]:
    """The two joints of the simplest set, or its one joint and the one that shows most other sets with it."""
    joints = set_joints(simplest)
    if len(joints) >= 2:
        return joints[0], joints[1]
    j = joints[0]
    others = [k for k in range(robot.n_coordinates) if k != j]
    best = max(others, key=lambda k: (sum(set(set_joints(s)) <= {j, k} for s in report.sets), -abs(k - j), -k))
    return (j, best) if j < best else (best, j)


def _constant_values(condition: Condition, variable: sp.Symbol, bounds: tuple[float, float],
                     robot: Robot) -> list[float] | None:
    """The values ``variable`` takes on ``condition`` when they are constants, within ``bounds``; else ``None``."""
    values = []
    for solution in condition.solutions:
        if solution.lhs != variable or solution.rhs.free_symbols & set(robot.q):
            return None
        value = float(solution.rhs.xreplace(robot.defaults))
        shifted = (value + 2 * math.pi * k for k in (-1, 0, 1))
        values += [v for v in shifted if bounds[0] - 1e-9 <= v <= bounds[1] + 1e-9]
    return values


def _set_marks(robot: Robot, report: SingularityReport, plane: tuple[int, int],
               configuration: Sequence[float]) -> tuple[SetMark, ...]:
    """Every singular set given by constant values of the plane's joints, as lines or points, the simplest first."""
    marks = []
    variables = [robot.q[k] for k in plane]
    bounds = [_bounds(robot, k) for k in plane]
    for number, singular_set in enumerate(report.sets, start=1):
        if not set(set_joints(singular_set)) <= set(plane) or singular_set.sample is None:
            continue
        lines: list[list[float]] = [[], []]
        for condition in singular_set.conditions:
            axis = next(a for a in (0, 1) if condition.expression.has(variables[a]))
            values = _constant_values(condition, variables[axis], bounds[axis], robot)
            if values is None:
                break
            lines[axis] += values
        else:
            if lines[0] and lines[1]:
                points = tuple((x, y) for x in lines[0] for y in lines[1])
                marks.append(SetMark(number, points=points, crossing=points[0]))
            elif lines[0] or lines[1]:
                axis = 0 if lines[0] else 1
                other = float(configuration[plane[1 - axis]])
                crossing = (lines[0][0], other) if axis == 0 else (other, lines[1][0])
                marks.append(SetMark(number, tuple(lines[0]), tuple(lines[1]), crossing=crossing))
    simplest = _simplest_set(report)
    first = None if simplest is None else report.sets.index(simplest) + 1
    return tuple(sorted(marks, key=lambda mark: mark.number != first))


def _measure(J: np.ndarray) -> float:
    if J.shape[0] == J.shape[1]:
        return abs(float(np.linalg.det(J)))
    return math.sqrt(max(float(np.linalg.det(J @ J.T)), 0.0))


def _function(expr: sp.Expr, variable: sp.Symbol) -> Callable[[np.ndarray], np.ndarray]:
    compiled = sp.lambdify([variable], expr, modules="numpy")
    return lambda values: np.broadcast_to(np.asarray(compiled(values), dtype=float), values.shape)


def _crossing(inside: list[np.ndarray], centre: np.ndarray,
              rank_margin: Callable[[np.ndarray], float]) -> tuple[float, float]:
    """The point of a curve to cross: simply singular (no other singular set through it), then near the centre."""
    step = max(1, len(inside) // 240)
    best = max(inside[::step], key=lambda p: (round(rank_margin(p), 3), -float(np.hypot(*(p - centre)))))
    return float(best[0]), float(best[1])


def _curve(robot: Robot, factor: SingularFactor, plane: tuple[int, int], fixed: dict[sp.Symbol, sp.Expr],
           grids: tuple[np.ndarray, np.ndarray], rank_margin: Callable[[np.ndarray], float]) -> Curve | None:
    a, b = (robot.q[i] for i in plane)
    if not factor.expression.free_symbols & {a, b}:
        return None
    bounds = [_bounds(robot, i) for i in plane]
    centre = np.array([sum(bound) / 2 for bound in bounds])
    xs: list[np.ndarray] = []
    ys: list[np.ndarray] = []
    inside: list[np.ndarray] = []
    drawn = []
    for solution in factor.solutions:
        form = _parametric(robot, solution, a, b, fixed)
        if form is None:
            continue
        drawn.append(solution)
        solved, along, expression = form
        axis = 0 if solved == a else 1
        parameter = np.linspace(*bounds[1 - axis], 1601)
        with np.errstate(invalid="ignore", divide="ignore"):
            values = _function(expression, along)(parameter)
        values = np.where(np.isfinite(values), values, np.nan)
        jumps = np.flatnonzero(np.abs(np.diff(values)) > math.pi) + 1  # a branch cut of atan2: not part of the curve
        values, parameter = np.insert(values, jumps, np.nan), np.insert(parameter, jumps, np.nan)
        shifts = (-2, -1, 0, 1, 2) if robot.coordinate_types[plane[axis]] is JointType.REVOLUTE else (0,)
        for shift in shifts:
            shifted = values + 2 * math.pi * shift
            pair = (shifted, parameter) if axis == 0 else (parameter, shifted)
            xs += [pair[0], np.array([np.nan])]
            ys += [pair[1], np.array([np.nan])]
            low, high = bounds[axis]
            keep = np.isfinite(shifted) & (shifted >= low) & (shifted <= high)
            inside += [np.array(p) for p in zip(pair[0][keep], pair[1][keep], strict=True)]
    if drawn:
        crossing = _crossing(inside, centre, rank_margin) if inside else None
        return Curve(factor, tuple(drawn), (np.concatenate(xs), np.concatenate(ys)), None, crossing)
    exact = sp.lambdify([a, b], factor.expression.xreplace(fixed), modules="numpy")
    X, Y = np.meshgrid(*grids)
    return Curve(factor, (), None, np.broadcast_to(np.asarray(exact(X, Y), dtype=float), X.shape), None)


def manipulability_map(robot: Robot, report: SingularityReport, size: int = 121, fine: int = 601,
                       seed: int = 0) -> ManipulabilityMap | None:
    """Manipulability over a grid of two joints with the exact singular curves; ``None`` for a one-joint arm."""
    if robot.n_coordinates < 2:
        return None
    simplest = _simplest_set(report)
    if simplest is not None and simplest.sample is not None:  # a redundant arm: the simplest singular set in view
        plane, configuration = _set_plane(robot, report, simplest), list(simplest.sample)
    else:
        plane = _plane(robot, report)
        configuration = _fixed(robot, report, plane, seed)
    det = report.determinant
    rows = list(det.rows)
    bounds = [_bounds(robot, i) for i in plane]
    x, y = (np.linspace(*bound, size) for bound in bounds)
    w = np.empty((size, size))
    q = np.array(configuration, dtype=float)
    for i, value_y in enumerate(y):
        for j, value_x in enumerate(x):
            q[plane[0]], q[plane[1]] = value_x, value_y
            w[i, j] = _measure(numeric_jacobian(robot, q.tolist(), det.frame, det.point)[rows, :])
    fixed = {v: sp.Float(value) for k, (v, value) in enumerate(zip(robot.q, configuration, strict=True))
             if k not in plane}
    fixed.update(robot.defaults)
    grids = (np.linspace(*bounds[0], fine), np.linspace(*bounds[1], fine))

    def rank_margin(point: np.ndarray) -> float:
        """The second smallest singular value of J at ``point`` of the plane, relative to the largest."""
        q[plane[0]], q[plane[1]] = point
        sigma = np.linalg.svd(numeric_jacobian(robot, q.tolist(), det.frame, det.point)[rows, :], compute_uv=False)
        return float(sigma[-2] / sigma[0]) if len(sigma) > 1 else 1.0

    curves = [curve for factor in _plotted(report)
              if (curve := _curve(robot, factor, plane, fixed, grids, rank_margin)) is not None]
    measure = "|det J|" if len(rows) == robot.n_coordinates else "sqrt(det(J J^T))"
    marks = _set_marks(robot, report, plane, configuration) if simplest is not None else ()
    return ManipulabilityMap(plane, tuple(configuration), x, y, w, measure, tuple(curves), det.rows, det.frame,
                             det.point, marks)


def singular_path(robot: Robot, plane: ManipulabilityMap, points: int = 200, half_length: float = 0.5) -> SingularPath:
    """A path across the first solved curve (elbow first), or a redundant arm's simplest singular set in the plane.

    The path is commanded along the direction lost where it crosses.
    """
    solved = [c for c in plane.curves if c.crossing is not None]
    solved.sort(key=lambda c: _KIND_ORDER.index(str(c.factor.kind)) if str(c.factor.kind) in _KIND_ORDER else 9)
    curve = solved[0] if solved else None
    mark = plane.sets[0] if plane.sets and plane.sets[0].crossing is not None else None
    q0 = np.array(plane.configuration, dtype=float)
    if mark is not None and mark.crossing is not None:
        q0[plane.joints[0]], q0[plane.joints[1]] = mark.crossing
        along = 0 if mark.vertical or mark.points else 1
    elif curve is not None and curve.crossing is not None:
        q0[plane.joints[0]], q0[plane.joints[1]] = curve.crossing
        along = 0 if curve.solutions[0].lhs.has(robot.q[plane.joints[0]]) else 1
    else:  # no solved curve: through the smallest manipulability on the grid
        i, j = np.unravel_index(int(np.argmin(plane.w)), plane.w.shape)
        q0[plane.joints[0]], q0[plane.joints[1]] = plane.x[j], plane.y[i]
        along = 0
    t = np.linspace(-half_length, half_length, points)
    configurations = np.tile(q0, (points, 1))
    configurations[:, plane.joints[along]] += t
    J = numeric_jacobian(robot, q0.tolist(), plane.frame, plane.point)[list(plane.rows), :]
    u = np.linalg.svd(J)[0][:, -1]
    u = np.where(np.abs(u) < 1e-12, 0.0, u if u[np.argmax(np.abs(u))] > 0 else -u)
    rates = rates_along_path(robot, configurations, u.tolist(), rows=plane.rows, frame=plane.frame, point=plane.point)
    return SingularPath(t, configurations, u, plane.rows, rates, None if mark else curve, mark)
