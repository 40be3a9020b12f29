r"""Solving one factor of a determinant: joint values where it vanishes, and when they exist at all.

A factor linear in the sine and cosine of one basis angle :math:`\psi`, :math:`A\cos\psi + B\sin\psi + C = 0`, gives

.. math:: \psi = \operatorname{atan2}(B, A) \pm \arccos\frac{-C}{\sqrt{A^2 + B^2}},
          \quad\text{which exists where } A^2 + B^2 - C^2 \ge 0,

with :math:`A, B, C` functions of the other joints (a curve in joint space) or constants (isolated values such as
:math:`\theta_2 \in \{0, \pi\}`). The existence condition on the parameters (:math:`L_2 + L_3 \ge L_1`) is the
maximum of :math:`A^2 + B^2 - C^2` over the other joints being non-negative.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.kinematics.chain import Chain, as_chain
from symjac.model.robot import JointType, Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.layout import expanded_expr, nested_expr
from symjac.symbolic.trigpoly import TrigImage, image_of, reduce_image

__all__ = ["Solution", "alternative_solutions", "branch_solutions", "nonnegative_condition", "solution_sample",
           "solve_factor"]


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


def _linear_forms(factor: sp.Expr, bases: Sequence[AngleBasis], nested: bool = True) -> list[_Linear]:
    """Every way of reading ``factor`` as linear in the sine and cosine of one basis angle (laid out or expanded)."""
    layout = nested_expr if nested else expanded_expr
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
            slack = reduce_image(A**2 + B**2 - C**2, image) if nested else ring.zero
            forms.append(_Linear(angle, layout(A, image), layout(B, image), layout(C, image),
                                 layout(slack, image), image, A, B))
    return forms


def _angle_equation(angle: sp.Expr, values: Sequence[sp.Expr]) -> tuple[Solution, ...]:
    r"""``angle = value`` for each value, in the joint variable: ``-theta1 = v`` becomes ``theta1 = -v``.

    An angle that is one joint variable and its constant DH offset is solved for the variable, the numeric values
    brought into :math:`(-\pi, \pi]`: :math:`\theta_3 + \pi/2 = \pi/2` is :math:`\theta_3 = 0`.
    """
    offset, varying = angle.as_independent(*angle.free_symbols, as_Add=True)
    if offset != 0 and (varying.is_Symbol or (-varying).is_Symbol):
        angle, values = varying, [_principal(v - offset) for v in values]
    if angle.could_extract_minus_sign():
        angle, values = -angle, [_principal(-v) if offset != 0 else -v for v in values]
    return tuple(dict.fromkeys(Solution(angle, _tidy_angle(v)) for v in values))  # acos(1) = -acos(1): one


def _principal(value: sp.Expr) -> sp.Expr:
    r"""A numeric angle brought into :math:`(-\pi, \pi]` (an expression of other joints is left as it is)."""
    if not value.is_number:
        return value
    turns = sp.floor(((value + sp.pi) / (2 * sp.pi)).evalf())
    value = sp.nsimplify(value - 2 * sp.pi * turns) if value.has(sp.Float) else value - 2 * sp.pi * turns
    return sp.pi if value == -sp.pi else value


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
        return nonnegative_condition(slack)
    for linear in _linear_forms(slack, [form.image.basis]):
        if linear.A.free_symbols & variables or linear.B.free_symbols & variables or \
                linear.C.free_symbols & variables:
            continue
        return nonnegative_condition(linear.C + sp.sqrt(linear.A**2 + linear.B**2))
    return None


def _square_roots(plus: sp.Expr, minus: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    r"""``(p, m)`` for ``p**2 >= m**2`` when both sides are squares of positive expressions, else the sides as given.

    :math:`a_2^2 + 2 a_2 \sqrt{a_3^2 + d_4^2} + a_3^2 + d_4^2 \ge a_1^2` reads :math:`a_2 + \sqrt{a_3^2 + d_4^2} \ge
    a_1` (positive lengths). A square :math:`(a + r)^2` is recognised from its cross term :math:`2 a r`, with
    :math:`r` a square root the sum holds (or no root: :math:`(a + b)^2` from the term :math:`2ab`).
    """
    right = sp.sqrt(minus)
    if isinstance(right, sp.Pow) and right.exp == sp.S.Half:  # not a perfect square
        return plus, minus
    for term in sp.Add.make_args(sp.expand(plus)):
        coefficient, rest = term.as_coeff_Mul()
        if coefficient != 2:
            continue
        factors = sp.Mul.make_args(rest)
        if len(factors) != 2:
            continue
        candidate = factors[0] + factors[1]
        if candidate.is_positive and sp.expand(candidate**2 - plus) == 0:
            return candidate, right
    return plus, minus


def nonnegative_condition(expr: sp.Expr) -> sp.Expr:
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
        plus, minus = _square_roots(plus, minus)
        return sp.Ge(plus.xreplace(back), minus.xreplace(back), evaluate=False)
    return sp.Ge(value.xreplace(back), 0, evaluate=False)


def solve_factor(
    robot: Robot | Chain, factor: sp.Expr
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
    chain = as_chain(robot)
    robot = chain.robot
    variables = frozenset(robot.q)
    present = factor.free_symbols & variables
    if not present:
        return (), None
    prismatic = [c for c, kind in zip(robot.q, robot.coordinate_types, strict=True)
                 if kind is JointType.PRISMATIC and c in present]
    for d in prismatic:
        polynomial = sp.Poly(factor, d)
        if polynomial.degree() == 1 and not any(isinstance(a, sp.sin | sp.cos) and a.has(d)
                                                for a in factor.atoms(sp.Function)):
            a, b = polynomial.all_coeffs()
            return (Solution(d, sp.simplify(-b / a)),), sp.true
    ranked = _ranked_solutions(chain, factor, prismatic)
    if not ranked:
        return (Solution(factor, sp.S.Zero),), None
    return ranked[0]


def alternative_solutions(robot: Robot | Chain, factor: sp.Expr
                          ) -> tuple[tuple[tuple[Solution, ...], sp.Expr | None], ...]:
    r"""Every closed-form solution of ``factor = 0`` found, best first (:func:`solve_factor` returns the first).

    A factor such as :math:`a_2 c_2 + a_3 c_{23} + d_5 c_{234}` can be solved for several joints; a singular set
    where it holds together with :math:`c_{234} = 0` needs it solved for another joint than :math:`\theta_4`.
    """
    chain = as_chain(robot)
    present = factor.free_symbols & frozenset(chain.robot.q)
    prismatic = [c for c, kind in zip(chain.robot.q, chain.robot.coordinate_types, strict=True)
                 if kind is JointType.PRISMATIC and c in present]
    return tuple(_ranked_solutions(chain, factor, prismatic)) if present else ()


def _ranked_solutions(chain: Chain, factor: sp.Expr, prismatic: Sequence[sp.Symbol]
                      ) -> list[tuple[tuple[Solution, ...], sp.Expr | None]]:
    """The solutions of every reading of ``factor`` as linear in one angle's sine and cosine, best first."""
    variables = frozenset(chain.robot.q)
    scored: list[tuple[tuple[int, ...], int, tuple[Solution, ...], sp.Expr | None]] = []
    for form in _linear_forms(factor, chain.all_angle_bases()):
        if prismatic and any(expr.has(*prismatic) for expr in (form.A, form.B)):
            continue
        solutions = _solutions(form)
        if any(s.rhs.free_symbols & s.lhs.free_symbols for s in solutions):
            continue  # solved "for" a joint that is on both sides (another angle of the basis holds it): no solution
        existence = _existence(form, variables)
        others = sum(bool(e.free_symbols & variables) for e in (form.A, form.B, form.C))
        status = 0 if existence is sp.true else 1 if existence is not None else 2
        compound = len(solutions[0].lhs.free_symbols)  # solve for one joint angle rather than a sum when possible
        score = (status, compound, others, int(sum(sp.count_ops(s.rhs) for s in solutions)))
        scored.append((score, len(scored), solutions, existence))
    return [(solutions, existence) for _, _, solutions, existence in sorted(scored, key=lambda item: item[:2])]


def branch_solutions(robot: Robot | Chain, factor: sp.Expr) -> tuple[Solution, ...]:
    r"""The solutions of ``factor = 0`` for the last joint angle it is linear in, fast and without layout.

    :func:`solve_factor` tries every angle in every basis, lays each out and decides when it exists, which takes
    seconds on a large factor (a redundant arm's minors); this takes the plain angles and expanded coefficients.
    ``()`` when the factor is linear in no joint angle.

    Examples
    --------
    >>> from symjac import load_robot
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> branch_solutions(load_robot("planar2r"), sp.sin(t2))
    (Solution(lhs=theta2, rhs=0), Solution(lhs=theta2, rhs=pi))
    """
    chain = as_chain(robot)
    variables = set(chain.robot.q)
    forms = [form for form in _linear_forms(factor, chain.all_angle_bases()[:1], nested=False)
             if len(form.angle.free_symbols & variables) == 1]
    return _solutions(forms[-1]) if forms else ()


def solution_sample(robot: Robot | Chain, solution: Solution, generator: random.Random) -> list[float] | None:
    r"""A random configuration satisfying ``solution`` (other joints random, parameters at their defaults).

    The joint of ``solution.lhs`` latest in the chain is solved for: :math:`q_k = \mathrm{rhs} - (\mathrm{lhs} - q_k)`
    at uniform random other joints in [-2.5, 2.5]; ``None`` when 20 draws give no real value (the solution does not
    exist for the default parameters).
    """
    robot = as_chain(robot).robot
    variables = list(robot.q)
    for _ in range(20):
        values = {v: sp.Float(generator.uniform(-2.5, 2.5)) for v in variables}
        target = solution.lhs
        solved = [v for v in variables if target.has(v) and not solution.rhs.has(v)]
        if not solved:
            return None
        pick = max(solved, key=lambda v: variables.index(v))
        rhs = solution.rhs.xreplace({**{v: values[v] for v in variables if v != pick}, **robot.defaults})
        rest = (target - pick).xreplace({**{v: values[v] for v in variables if v != pick}, **robot.defaults})
        if rest.has(pick):
            return None  # an implicit surface (the factor itself = 0): not solved for one joint
        value = sp.N(rhs - rest)
        if value.is_real and value.is_finite:
            values[pick] = value
            return [float(values[v]) for v in variables]
    return None
