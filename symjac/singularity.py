r"""Singular configurations: the factored determinant of the Jacobian, each factor solved and explained.

A square Jacobian :math:`J(q)` (the task rows an arm controls, see :func:`task_rows`) loses rank exactly where
:math:`\det J = 0`. The determinant is computed on the polynomial image of the simplified Jacobian (sines and
cosines of the basis angles as independent generators, :mod:`symjac.simplify`): a fraction-free determinant over
the polynomial ring, ``factor_list`` into irreducible factors, then each factor reduced modulo
:math:`s^2 + c^2 - 1` and laid out in the angle basis where it is shortest. Factors that reduce to a constant
(:math:`s^2 + c^2`) disappear; what remains reads as in a textbook, e.g. :math:`-L_2 L_3 s_3 (L_1 + L_2 c_2 + L_3
c_{23})`.

The determinant of the selected rows does not depend on the frame it is expressed in (a frame change multiplies it
by the determinant of an orthogonal block, 1), so it is computed in the frame where the Jacobian is most compact.

Each factor :math:`f` is then solved (:func:`solve_factor`): if it is linear in the sine and cosine of one basis
angle :math:`\psi`, :math:`A\cos\psi + B\sin\psi + C = 0` gives

.. math:: \psi = \operatorname{atan2}(B, A) \pm \arccos\frac{-C}{\sqrt{A^2 + B^2}},
          \quad\text{which exists where } A^2 + B^2 - C^2 \ge 0,

with :math:`A, B, C` functions of the other joints (a curve in joint space) or constants (isolated values such as
:math:`\theta_2 \in \{0, \pi\}`). The existence condition on the parameters (:math:`L_2 + L_3 \ge L_1`) is the
maximum of :math:`A^2 + B^2 - C^2` over the other joints being non-negative. Finally, at a sample of each solution
the arm is examined numerically (:func:`jacobian_spaces`) to classify the singularity and to name what it loses.
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from sympy.polys.matrices import DomainMatrix

from symjac.angles import AngleBasis
from symjac.chain import Frame, chain_of
from symjac.errors import ArgumentError, FrameError
from symjac.jacobian import ROW_NAMES, Point, jacobian, point_vector
from symjac.model import Robot
from symjac.numeric import numeric_jacobian
from symjac.simplify import simplify_expr
from symjac.singular_geometry import classify, describe, findings, frame_axes, geometry_at, parallel
from symjac.spaces import jacobian_spaces, task_rows
from symjac.trigpoly import TrigImage, expanded_expr, image_of, nested_expr, reduce_image

__all__ = [
    "Determinant",
    "SingularFactor",
    "SingularityReport",
    "Solution",
    "determinant",
    "report_data",
    "singularities",
    "solve_factor",
]



def _admissible(robot: Robot, rows: tuple[int, ...], frame: Frame) -> bool:
    """Whether re-expressing the Jacobian in ``frame`` keeps the selected rows closed (their determinant unchanged).

    All six rows, or all three linear or angular rows, are closed in every frame; a planar subset (x, y, w_z) only in
    frames rotated about z.
    """
    chosen = set(rows)
    blocks = [set(range(3)), set(range(3, 6))]
    if all(block <= chosen or not block & chosen for block in blocks):
        return True
    R = chain_of(robot).simplified_transform(frame, 0)[:3, :3]
    for block_start in (0, 3):
        inside = [r - block_start for r in rows if block_start <= r < block_start + 3]
        outside = [c for c in range(3) if c not in inside]
        if any(sp.simplify(R[i, j]) != 0 for i in inside for j in outside):
            return False
    return True


def _frame_sign(robot: Robot, rows: tuple[int, ...], frame: Frame) -> int:
    r"""The sign :math:`\det(S\,\mathrm{diag}(R, R)\,S^T) = \pm 1` between the rows' determinant in ``frame`` and {0}.

    It is 1 for all six rows or whole 3-row blocks; a planar subset in a frame whose z-axis is flipped (a twist of
    pi) has -1, and the determinant is reported as in frame {0}.
    """
    q = [0.3 + 0.1 * i for i in range(robot.dof)]
    values = {**dict(zip(robot.q, q, strict=True)), **robot.defaults}
    R = np.array(chain_of(robot).rotation(frame, 0).xreplace(values).evalf(), dtype=float)
    B = np.kron(np.eye(2), R)[np.ix_(rows, rows)]
    return 1 if np.linalg.det(B) > 0 else -1


# --- determinant -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Determinant:
    r"""A factored determinant :math:`\det J = c \prod_i f_i^{m_i}` and where it came from."""

    coefficient: sp.Expr
    factors: tuple[tuple[sp.Expr, int], ...]
    rows: tuple[int, ...]
    frame: Frame
    point: tuple[sp.Expr, sp.Expr, sp.Expr]
    columns: tuple[int, ...]

    @property
    def expression(self) -> sp.Expr:
        """The determinant as one product (unevaluated, so the factors stay visible)."""
        parts = [factor**m if m > 1 else factor for factor, m in self.factors]
        return sp.Mul(self.coefficient, *parts, evaluate=False) if self.coefficient != 1 else sp.Mul(*parts)

    @property
    def row_names(self) -> tuple[str, ...]:
        """Names of the rows used (``v_x`` ... ``omega_z``)."""
        return tuple(ROW_NAMES[r] for r in self.rows)


def _square_jacobian(robot: Robot, frame: Frame, point: tuple[sp.Expr, ...], rows: Sequence[int],
                     columns: Sequence[int], numeric: bool) -> sp.Matrix:
    J = jacobian(robot, frame=frame, point=point).extract(list(rows), list(columns))
    return J.xreplace(robot.defaults) if numeric else J


def _layout(expr: sp.Expr, bases: Sequence[AngleBasis]) -> sp.Expr:
    """The shortest nested form of ``expr`` over ``bases``."""
    forms = [simplify_expr(expr, basis) for basis in bases]
    return min(forms, key=lambda form: (sp.count_ops(form), len(str(form))))


def _best_frame(robot: Robot, rows: tuple[int, ...], point: tuple[sp.Expr, ...]) -> int:
    """The admissible frame in which the selected rows of the Jacobian have the fewest operations."""
    sizes = []
    for frame in range(robot.dof + 1):
        if _admissible(robot, rows, frame):
            J = jacobian(robot, frame=frame, point=point).extract(list(rows), list(range(robot.dof)))
            sizes.append((int(sp.count_ops(J)), frame))
    return min(sizes)[1]


def determinant(
    robot: Robot,
    rows: Sequence[int] | None = None,
    frame: Frame | None = None,
    point: Point | None = None,
    *,
    columns: Sequence[int] | None = None,
    numeric: bool = False,
) -> Determinant:
    r"""The factored determinant of the square Jacobian made of ``rows`` (and ``columns``).

    Parameters
    ----------
    robot : Robot
    rows : sequence of int, optional
        Task rows (0..5 for :math:`v_x .. \omega_z`); default :func:`task_rows`.
    frame : int, optional
        Frame to compute in (the result does not depend on it); default: the admissible frame with the most
        compact Jacobian.
    point : optional
        Reference point (see :func:`symjac.jacobian`); default the tool point if the robot has a tool, else the
        wrist. It matters only when fewer than six rows are used.
    columns : sequence of int, optional
        Joints (0-based columns) to keep, for the minors of a redundant arm; default all.
    numeric : bool
        Substitute the parameters' exact defaults first (factors then hold numbers instead of lengths).

    Examples
    --------
    >>> from symjac import load_robot
    >>> determinant(load_robot("planar2r")).expression
    L1*L2*sin(theta2)
    """
    if point is None:
        point = "tool" if robot.tool is not None else "wrist"
    point_xyz = point_vector(robot, point)
    columns = tuple(range(robot.dof)) if columns is None else tuple(columns)
    rows = task_rows(robot, point_xyz) if rows is None else tuple(rows)
    if len(rows) != len(columns) or not rows:
        raise ArgumentError(f"a determinant needs as many rows as columns, got rows {rows} and columns {columns}")
    if any(not 0 <= r < 6 for r in rows) or len(set(rows)) != len(rows):
        raise ArgumentError(f"rows must be distinct indices 0..5 (v_x .. omega_z), got {rows}")
    if any(not 0 <= c < robot.dof for c in columns) or len(set(columns)) != len(columns):
        raise ArgumentError(f"columns must be distinct joint indices 0..{robot.dof - 1}, got {columns}")
    chain = chain_of(robot)
    if frame is None:
        frame = _best_frame(robot, rows, point_xyz)
    frame = chain.frame_name(chain.position(frame))
    if not _admissible(robot, rows, frame):
        raise FrameError(f"rows {rows} mix with other rows when expressed in frame {frame}; use another frame")
    J = _square_jacobian(robot, frame, point_xyz, rows, columns, numeric)
    coefficient, factors = _factored_determinant(J, chain.angle_basis(frame), chain_of(robot).all_angle_bases())
    return Determinant(coefficient * _frame_sign(robot, rows, frame), factors, rows, frame, point_xyz, columns)


_FACTOR_UNREDUCED_TERMS = 150


def _factored_determinant(
    J: sp.Matrix, basis: AngleBasis, bases: Sequence[AngleBasis]
) -> tuple[sp.Expr, tuple[tuple[sp.Expr, int], ...]]:
    """Fraction-free determinant over the polynomial ring, factored, each factor reduced and laid out."""
    image, polys = image_of(list(J), basis)
    domain = image.ring_and_gens[0].to_domain()
    matrix = DomainMatrix([polys[i * J.cols:(i + 1) * J.cols] for i in range(J.rows)], J.shape, domain)
    value = matrix.det()
    if not value:
        return sp.S.Zero, ()
    # Factoring before the reduction keeps products such as s_3 (a c_3 + b s_3) intact (reducing s_3^2 first would
    # hide the factor s_3); on large determinants (redundant arms' minors) multivariate factoring of the unreduced
    # polynomial can take minutes, so there the reduced polynomial, much smaller, is factored instead.
    if len(value.terms()) > _FACTOR_UNREDUCED_TERMS:
        value = reduce_image(value, image)
    constant, raw_factors = value.factor_list()
    coefficient = _number(constant)
    collected: dict[sp.Expr, int] = {}
    for raw, multiplicity in raw_factors:
        reduced = reduce_image(raw, image)
        if reduced.is_ground:
            coefficient *= _number(reduced.LC) ** multiplicity
            continue
        factor = _layout(nested_expr(reduced, image), bases)
        if factor.could_extract_minus_sign():
            factor, coefficient = -factor, coefficient * (-1) ** multiplicity
        collected[factor] = collected.get(factor, 0) + multiplicity
    ordered = sorted(collected.items(), key=lambda item: (_factor_rank(item[0]), sp.default_sort_key(item[0])))
    return coefficient, tuple(ordered)


def _number(value: Any) -> sp.Rational:
    return sp.Rational(int(value.numerator), int(value.denominator))


def _factor_rank(factor: sp.Expr) -> int:
    """Parameters first, then single sines/cosines, then longer factors (textbook order)."""
    if not any(isinstance(atom, sp.sin | sp.cos) for atom in factor.atoms(sp.Function)):
        return 0
    return 1 if isinstance(factor, sp.sin | sp.cos) else 2


# --- solving a factor ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Solution:
    r"""One family of zeros of a factor: ``lhs = rhs`` (``rhs`` may depend on other joints: a curve)."""

    lhs: sp.Expr
    rhs: sp.Expr

    @property
    def equation(self) -> sp.Eq:
        """The solution as an equation."""
        return sp.Eq(self.lhs, self.rhs, evaluate=False)


@dataclass(frozen=True)
class _Linear:
    """A factor written as A cos(psi) + B sin(psi) + C with A, B, C free of psi."""

    angle: sp.Expr
    A: sp.Expr
    B: sp.Expr
    C: sp.Expr
    slack: sp.Expr  # A^2 + B^2 - C^2, normal form
    image: TrigImage
    image_A: Any  # A and B as polynomials in the image's ring
    image_B: Any


def _linear_forms(factor: sp.Expr, bases: Sequence[AngleBasis]) -> list[_Linear]:
    """Every way of reading ``factor`` as linear in the sine and cosine of one basis angle."""
    forms = []
    for basis in bases:
        image, (poly,) = image_of([factor], basis)
        for j, angle in enumerate(basis.angles):
            s, c = 2 * j, 2 * j + 1
            monomials = list(poly.itermonoms())
            if not any(m[s] or m[c] for m in monomials) or any(m[s] + m[c] > 1 for m in monomials):
                continue
            parts: dict[str, dict[tuple[int, ...], Any]] = {"A": {}, "B": {}, "C": {}}
            for monomial, coefficient in poly.iterterms():
                key = "A" if monomial[c] else "B" if monomial[s] else "C"
                stripped = list(monomial)
                stripped[s] = stripped[c] = 0
                parts[key][tuple(stripped)] = coefficient
            ring = image.ring_and_gens[0]
            A, B, C = (ring.from_dict(parts[k]) if parts[k] else ring.zero for k in "ABC")
            slack = reduce_image(A**2 + B**2 - C**2, image)
            forms.append(_Linear(angle, nested_expr(A, image), nested_expr(B, image), nested_expr(C, image),
                                 nested_expr(slack, image), image, A, B))
    return forms


def _angle_equation(angle: sp.Expr, values: Sequence[sp.Expr]) -> tuple[Solution, ...]:
    """``angle = value`` for each value, with ``-theta1 = v`` turned into ``theta1 = -v``."""
    if angle.could_extract_minus_sign():
        angle, values = -angle, [-v for v in values]
    return tuple(Solution(angle, _tidy_angle(v)) for v in values)


def _tidy_angle(value: sp.Expr) -> sp.Expr:
    """``-atan2(y, x)`` written as ``atan2(-y, x)``, the form a reader expects."""
    def flip(term: sp.Expr) -> sp.Expr:
        if isinstance(term, sp.Mul) and term.args[0] == -1 and len(term.args) == 2 and \
                isinstance(term.args[1], sp.atan2):
            y, x = term.args[1].args
            return sp.atan2(-y, x)
        return term
    return sp.Add(*[flip(term) for term in sp.Add.make_args(value)])


def _solutions(form: _Linear) -> tuple[Solution, ...]:
    A, B, C = form.A, form.B, form.C
    if C == 0:
        base = sp.atan2(-A, B) if A != 0 and B != 0 else (sp.pi / 2 if B == 0 else sp.S.Zero)
        return _angle_equation(form.angle, [base, base + sp.pi if base != sp.pi / 2 else -sp.pi / 2])
    if B == 0:
        value = sp.acos(-C / A)
        return _angle_equation(form.angle, [value, -value])
    if A == 0:
        value = sp.asin(-C / B)
        return _angle_equation(form.angle, [value, sp.pi - value])
    norm = expanded_expr(reduce_image(form.image_A**2 + form.image_B**2, form.image), form.image)
    center, spread = sp.atan2(B, A), sp.acos(-C / sp.sqrt(norm))
    return _angle_equation(form.angle, [center + spread, center - spread])


def _existence(form: _Linear, variables: frozenset[sp.Symbol]) -> sp.Expr | None:
    r"""The condition on the parameters for solutions to exist: :math:`\max (A^2 + B^2 - C^2) \ge 0`.

    ``True`` when it always holds, ``None`` when it could not be decided in closed form (the slack depends on more
    than one other angle, or not linearly).
    """
    slack = form.slack
    if form.C == 0:
        return sp.true
    if not slack.free_symbols & variables:
        return _nonnegative(slack)
    for linear in _linear_forms(slack, [form.image.basis]):
        if linear.A.free_symbols & variables or linear.B.free_symbols & variables or \
                linear.C.free_symbols & variables:
            continue
        return _nonnegative(linear.C + sp.sqrt(linear.A**2 + linear.B**2))
    return None


def _nonnegative(expr: sp.Expr) -> sp.Expr:
    """``expr >= 0`` in its simplest form, assuming positive parameters (lengths); positive factors dropped."""
    positive = {s: sp.Symbol(s.name, positive=True) for s in expr.free_symbols}
    back = {v: k for k, v in positive.items()}
    value = sp.factor(sp.simplify(expr.xreplace(positive)))
    if value.is_nonnegative:
        return sp.true
    if value.is_negative:
        return sp.false
    sign, product = value.as_coeff_Mul()
    factors = [f for f in sp.Mul.make_args(product) if not f.is_positive]
    if len(factors) == 1:
        remaining = sp.expand(sp.sign(sign) * factors[0])
        plus = sp.Add(*[t for t in sp.Add.make_args(remaining) if not t.could_extract_minus_sign()])
        minus = -sp.Add(*[t for t in sp.Add.make_args(remaining) if t.could_extract_minus_sign()])
        return sp.Ge(plus.xreplace(back), minus.xreplace(back), evaluate=False)
    return sp.Ge(value.xreplace(back), 0, evaluate=False)


def solve_factor(
    robot: Robot, factor: sp.Expr
) -> tuple[tuple[Solution, ...], sp.Expr | None]:
    r"""The solutions of ``factor = 0`` in joint space and the condition on the parameters for them to exist.

    Returns ``((), None)`` for a factor free of joint variables, and ``((Solution(factor, 0),), None)`` when the
    factor cannot be solved in closed form (an implicit surface).

    Examples
    --------
    >>> from symjac import load_robot
    >>> L1, L2, t2 = sp.symbols("L1 L2 theta2", real=True)
    >>> solve_factor(load_robot("planar2r"), sp.sin(t2))[0]
    (Solution(lhs=theta2, rhs=0), Solution(lhs=theta2, rhs=pi))
    """
    variables = frozenset(robot.q)
    present = factor.free_symbols & variables
    if not present:
        return (), None
    prismatic = [j.variable for j in robot.joints if not j.is_revolute and j.variable in present]
    for d in prismatic:
        polynomial = sp.Poly(factor, d)
        if polynomial.degree() == 1 and not any(isinstance(a, sp.sin | sp.cos) and a.has(d)
                                                for a in factor.atoms(sp.Function)):
            a, b = polynomial.all_coeffs()
            return (Solution(d, sp.simplify(-b / a)),), sp.true
    best: tuple[tuple[int, ...], tuple[Solution, ...], sp.Expr | None] | None = None
    for form in _linear_forms(factor, chain_of(robot).all_angle_bases()):
        if any(expr.has(*prismatic) for expr in (form.A, form.B)) if prismatic else False:
            continue
        solutions = _solutions(form)
        existence = _existence(form, variables)
        others = sum(bool(e.free_symbols & variables) for e in (form.A, form.B, form.C))
        status = 0 if existence is sp.true else 1 if existence is not None else 2
        compound = len(solutions[0].lhs.free_symbols)  # solve for one joint angle rather than a sum when possible
        score = (status, compound, others, int(sum(sp.count_ops(s.rhs) for s in solutions)))
        if best is None or score < best[0]:
            best = (score, solutions, existence)
    if best is None:
        return (Solution(factor, sp.S.Zero),), None
    return best[1], best[2]


# --- classification ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SingularFactor:
    r"""One factor of :math:`\det J`, solved and explained.

    ``kind`` is ``"wrist"``, ``"elbow"``, ``"shoulder"``, ``"parameter"`` (vanishes only for a special design)
    or ``"other"``; ``reason`` says why. ``sample`` is a configuration on the singular set (parameters at their
    defaults); ``lost_direction`` a Cartesian direction (6-vector in the analysis frame) the arm cannot move in
    there, which is also a wrench it holds with zero joint torque; ``self_motion`` a joint motion that moves nothing
    (:math:`J\dot q = 0`). ``lost_words`` and ``self_motion_words`` say the same in words.
    """

    expression: sp.Expr
    multiplicity: int
    solutions: tuple[Solution, ...]
    existence: sp.Expr | None
    exists_for_defaults: bool | None
    kind: str
    reason: str
    sample: tuple[float, ...] | None = None
    lost_direction: tuple[float, ...] | None = None
    lost_words: str = ""
    self_motion: tuple[float, ...] | None = None
    self_motion_words: str = ""


@dataclass(frozen=True)
class SingularityReport:
    """Everything :func:`singularities` found: the determinant and each factor explained."""

    robot: str
    determinant: Determinant
    factors: tuple[SingularFactor, ...]
    redundant: bool = False
    minors: tuple[Determinant, ...] = ()

    @property
    def frame(self) -> Frame:
        """The frame the analysis (and every lost direction) is expressed in."""
        return self.determinant.frame


def _solution_sample(robot: Robot, solution: Solution, generator: random.Random) -> list[float] | None:
    """A random configuration satisfying ``solution`` (other joints random, parameters at their defaults)."""
    variables = list(robot.q)
    for _ in range(20):
        values = {v: sp.Float(generator.uniform(-2.5, 2.5)) for v in variables}
        target = solution.lhs
        solved = [v for v in variables if target.has(v) and not solution.rhs.has(v)]
        if not solved:
            return None
        pick = max(solved, key=lambda v: variables.index(v))
        rhs = solution.rhs.xreplace({**{v: values[v] for v in variables if v != pick}, **robot.defaults})
        rest = (target - pick).xreplace({v: values[v] for v in variables if v != pick})
        value = sp.N(rhs - rest)
        if value.is_real and value.is_finite:
            values[pick] = value
            return [float(values[v]) for v in variables]
    return None


def singularities(
    robot: Robot,
    rows: Sequence[int] | None = None,
    frame: Frame | None = None,
    point: Point | None = None,
    *,
    numeric: bool = False,
    seed: int = 0,
) -> SingularityReport:
    r"""The singular configurations of ``robot``: :func:`determinant`, every factor solved, classified, explained.

    A redundant arm (more joints than task rows) has no square Jacobian; its report holds the determinants of the
    square minors (one joint locked at a time, :attr:`SingularityReport.minors`), and the arm is singular only where
    all of them vanish together (where the manipulability :math:`\sqrt{\det J J^T}` is zero). Arguments are as
    for :func:`determinant`; ``seed`` fixes the random samples on the singular sets.

    Examples
    --------
    >>> from symjac import load_robot
    >>> report = singularities(load_robot("planar2r"))
    >>> [(f.expression, f.kind) for f in report.factors]
    [(L1, 'parameter'), (L2, 'parameter'), (sin(theta2), 'elbow')]
    """
    if point is None:
        point = "tool" if robot.tool is not None else "wrist"
    point_xyz = point_vector(robot, point)
    chosen = task_rows(robot, point_xyz) if rows is None else tuple(rows)
    if robot.dof > len(chosen):
        minors = tuple(determinant(robot, chosen, frame, point_xyz, columns=[c for c in range(robot.dof) if c != k],
                                   numeric=numeric) for k in range(robot.dof))
        return SingularityReport(robot.name, minors[0], (), redundant=True, minors=minors)
    det = determinant(robot, chosen, frame, point_xyz, numeric=numeric)
    generator = random.Random(seed)
    generic = findings(robot, geometry_at(robot, [generator.uniform(-2.5, 2.5) for _ in robot.q], point_xyz))
    explained = []
    for factor, multiplicity in det.factors:
        explained.append(_explain(robot, det, factor, multiplicity, generic, generator))
    return SingularityReport(robot.name, det, tuple(explained))


def _explain(robot: Robot, det: Determinant, factor: sp.Expr, multiplicity: int, generic: Mapping[str, tuple[str, str]],
             generator: random.Random) -> SingularFactor:
    solutions, existence = solve_factor(robot, factor)
    holds = None if existence is None else bool(existence.xreplace(robot.defaults)) if existence is not sp.true \
        else True
    if not solutions:
        return SingularFactor(factor, multiplicity, (), None, None, "parameter",
                              f"{factor} depends on parameters only: a design with {factor} = 0 would be singular "
                              "everywhere; the default parameters are not", None)
    sample = None
    for solution in solutions:
        sample = _solution_sample(robot, solution, generator)
        if sample is not None:
            break
    factor_joints = {i for i, joint in enumerate(robot.joints) if factor.has(joint.variable)}
    if sample is None:
        kind, reason = classify({}, factor_joints, robot)
        return SingularFactor(factor, multiplicity, solutions, existence, holds, kind, reason)
    geometry = geometry_at(robot, sample, det.point)
    facts = findings(robot, geometry)
    new = {key: text for key, text in facts.items() if key not in generic}
    kind, reason = classify(new, factor_joints, robot)
    J = numeric_jacobian(robot, sample, det.frame, det.point)[list(det.rows), :][:, list(det.columns)]
    spaces = jacobian_spaces(J, tolerance=1e-8 * max(1.0, float(np.abs(J).max())))
    axes = frame_axes(robot, sample, det.frame)
    lost = spaces.left_null_space[:, 0] if spaces.left_null_space.shape[1] else None
    motion = spaces.null_space[:, 0] if spaces.null_space.shape[1] else None
    lost = None if lost is None else _canonical(lost)
    radial = ""
    if lost is not None:
        full = np.zeros(6)
        full[list(det.rows)] = lost
        R_k_0 = np.array(chain_of(robot).rotation(det.frame, 0).xreplace(
            {**dict(zip(robot.q, sample, strict=True)), **robot.defaults}).evalf(), dtype=float)
        reach = R_k_0 @ geometry.points[0][1]
        if np.linalg.norm(full[3:]) < 1e-9 and np.linalg.norm(reach) > 1e-9 and parallel(full[:3], reach, 1e-7):
            radial = " (radially: along the line from the origin of frame {0} to the point)"
    motion = None if motion is None else _canonical(motion)
    lost_words = "" if lost is None else (
        f"cannot {describe(lost, det.rows, axes, ('translate', 'rotate', 'rotating', 'while'))}{radial}, and it "
        f"holds {describe(lost, det.rows, axes, ('a force', 'a moment', 'a moment', 'with'))} with zero joint "
        "torque")
    motion_words = "" if motion is None else "joint rates " + ", ".join(
        f"{float(x):+.3g} on joint {det.columns[i] + 1}" for i, x in enumerate(motion) if abs(x) > 1e-9
    ) + " move nothing"
    return SingularFactor(factor, multiplicity, solutions, existence, holds, kind, reason, tuple(sample),
                          None if lost is None else tuple(float(x) for x in lost), lost_words,
                          None if motion is None else tuple(float(x) for x in motion), motion_words)


def _canonical(vector: np.ndarray) -> np.ndarray:
    """A unit vector with its largest component positive and round-off zeroed."""
    vector = np.where(np.abs(vector) < 1e-12, 0.0, vector)
    return vector if vector[np.argmax(np.abs(vector))] > 0 else -vector


def report_data(report: SingularityReport) -> dict[str, Any]:
    """The report as plain JSON-ready data (expressions as SymPy strings)."""
    det = report.determinant

    def determinant_data(d: Determinant) -> dict[str, Any]:
        return {"expression": sp.sstr(d.expression), "coefficient": sp.sstr(d.coefficient),
                "factors": [[sp.sstr(f), m] for f, m in d.factors], "columns": [c + 1 for c in d.columns]}

    return {
        "rows": list(det.row_names), "frame": det.frame, "point": [sp.sstr(c) for c in det.point],
        "redundant": report.redundant, "determinant": determinant_data(det),
        "minors": [determinant_data(m) for m in report.minors],
        "factors": [{
            "expression": sp.sstr(f.expression), "multiplicity": f.multiplicity, "kind": f.kind, "reason": f.reason,
            "solutions": [sp.sstr(s.equation) for s in f.solutions],
            "existence": None if f.existence is None else sp.sstr(f.existence),
            "exists_for_defaults": f.exists_for_defaults, "sample": f.sample,
            "lost_direction": f.lost_direction, "lost": f.lost_words,
            "self_motion": f.self_motion, "self_motion_words": f.self_motion_words,
        } for f in report.factors],
    }
