r"""Trigonometric simplification of kinematic expressions: one exact normal form, then a compact layout.

Kinematic expressions are polynomials in the sines and cosines of joint angles (and in lengths and prismatic
variables). SymPy's general ``simplify``/``trigsimp`` search that space blindly and are slow on robot Jacobians.
This module exploits the structure instead:

1. **Angle basis.** Pick angles :math:`\psi_j`, integer combinations of the joint angles, in which the result should
   read; for parallel joints these are the textbook sums (:math:`\theta_2 + \theta_3`, giving :math:`c_{23}`). The
   chain chooses them per frame (see :meth:`symjac.chain.Chain.angle_basis`).
2. **Polynomial image.** Every :math:`\sin`/:math:`\cos` of a joint-angle combination is expanded in the basis,
   :math:`\cos(\sum_j m_j\psi_j) + i\sin(\sum_j m_j\psi_j) = \prod_j (C_j + i S_j)^{m_j}`, with :math:`S_j, C_j`
   independent polynomial generators (sparse polynomials over the rationals, which are fast).
3. **Reduction** modulo :math:`S_j^2 + C_j^2 - 1`. These generators form a Groebner basis (their leading terms
   :math:`S_j^2` are coprime), so the remainder is a *unique normal form*: two expressions are equal as functions of
   the joint angles exactly when their normal forms are equal. No :math:`s^2 + c^2` can survive it.
4. **Layout.** The normal form is written back as a nested sum, greedily factoring out the generator shared by the
   most terms (base joints first on ties), which yields Craig-style forms such as
   :math:`c_1 (a_2 c_2 + a_3 c_{23} - d_4 s_{23}) - d_3 s_1` with few operations.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

__all__ = ["AngleBasis", "is_identity", "simplify_expr", "simplify_matrix", "trig_normal_form"]


@dataclass(frozen=True)
class AngleBasis:
    r"""Angles :math:`\psi_j = \sum_k M_{jk}\,\theta_k` (integer, invertible :math:`M`) that results are written in.

    Parameters
    ----------
    variables : tuple of sympy.Symbol
        The joint angles :math:`\theta_k` (revolute joint variables).
    angles : tuple of sympy.Expr
        The basis angles, each an integer combination of ``variables`` plus a constant offset (a joint's
        ``theta`` offset, so that :math:`\theta_1 - 1/5` stays one angle instead of doubling every term); as many
        as there are variables.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> basis = AngleBasis((t1, t2), (t1, t1 + t2))
    >>> simplify_expr(sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2), basis)
    cos(theta1 + theta2)
    """

    variables: tuple[sp.Symbol, ...]
    angles: tuple[sp.Expr, ...]
    _inverse: sp.Matrix = field(init=False, repr=False, compare=False)
    _offsets: sp.Matrix = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if len(self.angles) != len(self.variables):
            raise ValueError(f"need {len(self.variables)} basis angles, got {len(self.angles)}")
        matrix = sp.Matrix([[angle.coeff(v) for v in self.variables] for angle in self.angles])
        if self.variables and (any(not entry.is_Integer for entry in matrix) or abs(matrix.det()) != 1):
            raise ValueError(f"basis angles {self.angles} are not a unimodular combination of {self.variables}")
        object.__setattr__(self, "_inverse", matrix.inv() if self.variables else sp.zeros(0, 0))
        offsets = [sp.expand(angle - sum(c * v for c, v in zip(row, self.variables, strict=True)))
                   for angle, row in zip(self.angles, matrix.tolist(), strict=True)]
        if any(offset.free_symbols & set(self.variables) for offset in offsets):
            raise ValueError(f"basis angles {self.angles} are not linear in {self.variables}")
        object.__setattr__(self, "_offsets", sp.Matrix(offsets))

    @classmethod
    def of(cls, variables: Iterable[sp.Symbol]) -> AngleBasis:
        """The trivial basis: each joint angle on its own."""
        variables = tuple(variables)
        return cls(variables, variables)

    def decompose(self, argument: sp.Expr) -> tuple[tuple[int, ...], sp.Expr] | None:
        r"""Write ``argument`` as :math:`\sum_j m_j \psi_j + c`; ``None`` if it is not linear in the variables."""
        coefficients = [argument.coeff(v) for v in self.variables]
        constant = sp.expand(argument - sum(c * v for c, v in zip(coefficients, self.variables, strict=True)))
        if constant.free_symbols & set(self.variables) or not all(c.is_Rational for c in coefficients):
            return None
        multiples = sp.Matrix([coefficients]) * self._inverse
        if not all(m.is_Integer for m in multiples):
            return None
        if self._offsets:
            constant = sp.expand(constant - (multiples * self._offsets)[0])
        return tuple(int(m) for m in multiples), constant


@dataclass
class _Image:
    """The polynomial ring an expression lives in, and the way back to SymPy expressions.

    Generators, in ring order: :math:`S_j, C_j` of each basis angle, :math:`S_k, C_k` of each constant angle (an
    angle free of joint variables: a twist, an offset, a parameter), then the remaining atoms.
    """

    basis: AngleBasis
    constant_angles: list[sp.Expr]
    atoms: list[sp.Expr]
    relations: list[tuple[int, int]] = field(default_factory=list)  # (index of sqrt(n) generator, n)

    @property
    def angle_count(self) -> int:
        """Angles with a sine/cosine generator pair: basis angles first, then constant angles."""
        return len(self.basis.angles) + len(self.constant_angles)

    @cached_property
    def ring_and_gens(self) -> tuple[Any, tuple[PolyElement, ...]]:
        count = 2 * self.angle_count + len(self.atoms)
        names = [f"g{i}" for i in range(count)]
        polynomial_ring, *gens = ring(names, QQ, order="lex") if names else ring("g0", QQ, order="lex")
        return polynomial_ring, tuple(gens)

    @property
    def gens(self) -> tuple[PolyElement, ...]:
        return self.ring_and_gens[1]

    def sine(self, j: int) -> PolyElement:
        return self.gens[2 * j]

    def cosine(self, j: int) -> PolyElement:
        return self.gens[2 * j + 1]

    @cached_property
    def back(self) -> list[sp.Expr]:
        """Generator index -> SymPy expression."""
        exprs: list[sp.Expr] = []
        for angle in (*self.basis.angles, *self.constant_angles):
            exprs += [sp.sin(angle), sp.cos(angle)]
        return exprs + list(self.atoms)

    @cached_property
    def ideal(self) -> list[PolyElement]:
        """S^2 + C^2 - 1 per angle, g^2 - n per sqrt(n): a Groebner basis (leading monomials pairwise coprime)."""
        pythagoras = [self.sine(j) ** 2 + self.cosine(j) ** 2 - 1 for j in range(self.angle_count)]
        offset = 2 * self.angle_count
        return pythagoras + [self.gens[offset + i] ** 2 - n for i, n in self.relations]


def _is_joint_trig(expr: sp.Expr, variables: frozenset[sp.Symbol]) -> bool:
    return isinstance(expr, sp.sin | sp.cos) and bool(expr.args[0].free_symbols & variables)


def _angle_terms(argument: sp.Expr) -> list[tuple[sp.Expr, int]]:
    """Split a constant angle into terms with a sign, each term not starting with a minus (``-b + 1/5``)."""
    terms = []
    for term in sp.Add.make_args(argument):
        terms.append((-term, -1) if term.could_extract_minus_sign() else (term, 1))
    return terms


def _is_constant_angle(term: sp.Expr) -> bool:
    """Whether sin and cos of ``term`` stay unevaluated (``pi/3`` evaluates to radicals and is not an angle here)."""
    return isinstance(sp.sin(term), sp.sin) and isinstance(sp.cos(term), sp.cos)


def _collect_atoms(exprs: Sequence[sp.Expr], basis: AngleBasis) -> tuple[list[sp.Expr], list[sp.Expr]]:
    """Constant angles (trig arguments free of joint variables, split into terms) and the remaining atoms.

    Everything that is not built from + * ** and trig of angles becomes a generator of its own.
    """
    variables = frozenset(basis.variables)
    angles: dict[sp.Expr, None] = {}
    atoms: dict[sp.Expr, None] = {}
    seen: set[sp.Expr] = set()

    def visit(expr: sp.Expr) -> None:
        if expr in seen:
            return
        seen.add(expr)
        if expr.is_Rational:
            return
        if isinstance(expr, sp.Add | sp.Mul):
            for arg in expr.args:
                visit(arg)
        elif isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp > 0:
            visit(expr.base)
        elif _is_joint_trig(expr, variables):
            decomposed = basis.decompose(expr.args[0])
            if decomposed is None:
                atoms[expr] = None
            else:
                visit_constant_angle(decomposed[1])
        elif isinstance(expr, sp.sin | sp.cos):
            visit_constant_angle(expr.args[0])
        else:
            atoms[expr] = None

    def visit_constant_angle(argument: sp.Expr) -> None:
        for term, _ in _angle_terms(argument):
            if _is_constant_angle(term):
                angles[term] = None
            else:  # sin and cos of pi/3 are radicals: their atoms (sqrt(3)) are generators too
                visit(sp.cos(term))
                visit(sp.sin(term))

    for expr in exprs:
        visit(sp.sympify(expr))
    return sorted(angles, key=sp.default_sort_key), sorted(atoms, key=sp.default_sort_key)


def _image(exprs: Sequence[sp.Expr], basis: AngleBasis) -> tuple[_Image, list[PolyElement]]:
    constant_angles, atoms = _collect_atoms(exprs, basis)
    image = _Image(basis, constant_angles, atoms)
    offset = 2 * image.angle_count
    for i, atom in enumerate(atoms):
        if isinstance(atom, sp.Pow) and atom.base.is_Integer and atom.exp == sp.S.Half:
            image.relations.append((i, int(atom.base)))
    atom_index = {atom: offset + i for i, atom in enumerate(atoms)}
    angle_index = {angle: len(basis.angles) + k for k, angle in enumerate(constant_angles)}
    polynomial_ring, gens = image.ring_and_gens
    variables = frozenset(basis.variables)
    memo: dict[sp.Expr, PolyElement] = {}
    trig_memo: dict[tuple[int, ...], tuple[PolyElement, PolyElement]] = {}

    def exponential(multiples: tuple[int, ...]) -> tuple[PolyElement, PolyElement]:
        """(cos, sin) of sum m_j psi_j as polynomials, from prod (C_j + i S_j)^m_j."""
        if multiples not in trig_memo:
            real, imaginary = polynomial_ring.one, polynomial_ring.zero
            for j, m in enumerate(multiples):
                sign = 1 if m > 0 else -1
                for _ in range(abs(m)):
                    c, s = image.cosine(j), sign * image.sine(j)
                    real, imaginary = real * c - imaginary * s, real * s + imaginary * c
            trig_memo[multiples] = (real, imaginary)
        return trig_memo[multiples]

    def constant_exponential(argument: sp.Expr) -> tuple[PolyElement, PolyElement]:
        """(cos, sin) of a constant angle, by the addition formula over its terms."""
        real, imaginary = polynomial_ring.one, polynomial_ring.zero
        for term, sign in _angle_terms(argument):
            if term in angle_index:
                c, s = image.cosine(angle_index[term]), sign * image.sine(angle_index[term])
            else:
                c, s = convert(sp.cos(term)), sign * convert(sp.sin(term))
            real, imaginary = real * c - imaginary * s, real * s + imaginary * c
        return real, imaginary

    def convert(expr: sp.Expr) -> PolyElement:
        if expr in memo:
            return memo[expr]
        if expr.is_Rational:
            result = polynomial_ring(QQ(int(expr.p), int(expr.q)))
        elif expr in atom_index:
            result = gens[atom_index[expr]]
        elif isinstance(expr, sp.Add):
            result = polynomial_ring.zero
            for arg in expr.args:
                result += convert(arg)
        elif isinstance(expr, sp.Mul):
            result = polynomial_ring.one
            for arg in expr.args:
                result *= convert(arg)
        elif isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp > 0:
            result = convert(expr.base) ** int(expr.exp)
        elif isinstance(expr, sp.sin | sp.cos):
            decomposed = basis.decompose(expr.args[0]) if _is_joint_trig(expr, variables) else None
            if decomposed is None:  # a constant angle (a joint angle that does not decompose is an atom)
                cos_part, sin_part = constant_exponential(expr.args[0])
            else:
                multiples, constant = decomposed
                cos_part, sin_part = exponential(multiples)
                if constant != 0:
                    c, s = constant_exponential(constant)
                    cos_part, sin_part = cos_part * c - sin_part * s, sin_part * c + cos_part * s
            result = cos_part if isinstance(expr, sp.cos) else sin_part
        else:  # pragma: no cover - every other node was made an atom by _collect_atoms
            raise TypeError(f"cannot convert {expr!r}")
        memo[expr] = result
        return result

    polys = [_reduce(convert(sp.sympify(expr)), image) for expr in exprs]
    return image, polys


def _reduce(poly: PolyElement, image: _Image) -> PolyElement:
    r"""The remainder of ``poly`` modulo :attr:`_Image.ideal`, term by term.

    The leading monomials of the ideal's generators are single powers (:math:`S_j^2`, :math:`g^2`), so the remainder
    is what rewriting :math:`S_j^{2k+r} = S_j^r (1 - C_j^2)^k` and :math:`g^{2k+r} = n^k g^r` in every term leaves.
    This is the same unique normal form SymPy's general ``rem`` computes, without its quadratic leading-term search
    (measured: 10 of 13 s of a 5-joint Jacobian went into ``rem``).
    """
    sines = [2 * j for j in range(image.angle_count)]
    roots = [(2 * image.angle_count + i, n) for i, n in image.relations]
    if not any(m[s] >= 2 for m in poly.itermonoms() for s in sines) and not any(
            m[g] >= 2 for m in poly.itermonoms() for g, _ in roots):
        return poly
    zero = image.ring_and_gens[0].domain.zero
    terms: dict[tuple[int, ...], Any] = {}
    for monomial, coefficient in poly.iterterms():
        exponents = list(monomial)
        for g, n in roots:
            if exponents[g] >= 2:
                coefficient *= n ** (exponents[g] // 2)
                exponents[g] %= 2
        # (1 - C^2)^k for every sine reduced, multiplied out: a list of (extra cosine exponents, factor)
        expansion: list[tuple[dict[int, int], int]] = [({}, 1)]
        for s in sines:
            if exponents[s] >= 2:
                k = exponents[s] // 2
                exponents[s] %= 2
                expansion = [({**extra, s + 1: extra.get(s + 1, 0) + 2 * m}, factor * (-1) ** m * math.comb(k, m))
                             for extra, factor in expansion for m in range(k + 1)]
        for extra, factor in expansion:
            reduced = list(exponents)
            for index, power in extra.items():
                reduced[index] += power
            key = tuple(reduced)
            terms[key] = terms.get(key, zero) + coefficient * factor
    return image.ring_and_gens[0].from_dict({m: c for m, c in terms.items() if c})


def trig_normal_form(expr: sp.Expr, basis: AngleBasis) -> sp.Expr:
    """The unique expanded normal form of ``expr`` in ``basis`` (sines reduced to degree at most one)."""
    return simplify_matrix(sp.Matrix([expr]), basis, nested=False)[0]


def is_identity(left: sp.Expr, right: sp.Expr, basis: AngleBasis) -> bool:
    """Whether ``left == right`` holds identically in the joint angles (exact, via the normal form).

    Examples
    --------
    >>> t = sp.Symbol("theta1", real=True)
    >>> is_identity(sp.sin(t) ** 2, 1 - sp.cos(t) ** 2, AngleBasis.of([t]))
    True
    """
    _, (difference,) = _image([sp.sympify(left) - sp.sympify(right)], basis)
    return not difference


def simplify_expr(expr: sp.Expr, basis: AngleBasis, *, nested: bool = True) -> sp.Expr:
    """Simplify one expression: normal form in ``basis``, laid out nested (default) or expanded."""
    return simplify_matrix(sp.Matrix([expr]), basis, nested=nested)[0]


def simplify_matrix(
    matrix: sp.MatrixBase, basis: AngleBasis | Sequence[AngleBasis], *, nested: bool = True
) -> sp.Matrix:
    """Simplify every entry of ``matrix`` (see the module docstring).

    With several bases, each entry is written in every one of them and the form with the fewest operations is
    kept (the first basis wins ties). All entries written in one basis share one polynomial ring.
    """
    bases = [basis] if isinstance(basis, AngleBasis) else list(basis)
    layout: Callable[[PolyElement, _Image], sp.Expr] = _nested_expr if nested else _expanded_expr
    entries = list(matrix)
    best: list[sp.Expr] = []
    best_ops: list[int] = []
    for candidate in bases:
        image, polys = _image(entries, candidate)
        for index, poly in enumerate(polys):
            expr = layout(poly, image)
            if index == len(best):
                best.append(expr)
                best_ops.append(sp.count_ops(expr) if len(bases) > 1 else 0)
            else:
                ops = sp.count_ops(expr)
                if ops < best_ops[index]:
                    best[index], best_ops[index] = expr, ops
    return sp.Matrix(matrix.rows, matrix.cols, best)


def _monomial_expr(monomial: tuple[int, ...], image: _Image) -> sp.Expr:
    return sp.Mul(*[image.back[i] ** e for i, e in enumerate(monomial) if e])


def _coefficient_expr(coefficient: Any) -> sp.Rational:
    return sp.Rational(int(coefficient.numerator), int(coefficient.denominator))


def _expanded_expr(poly: PolyElement, image: _Image) -> sp.Expr:
    return sp.Add(*[_coefficient_expr(c) * _monomial_expr(m, image) for m, c in poly.terms()])


def _nested_expr(poly: PolyElement, image: _Image) -> sp.Expr:
    return _nest(list(poly.terms()), image)


def _nest(terms: list[tuple[tuple[int, ...], Any]], image: _Image) -> sp.Expr:
    """Greedy multivariate Horner: factor out the generator shared by most terms, recurse on both parts."""
    if len(terms) <= 1:
        return sp.Add(*[_coefficient_expr(c) * _monomial_expr(m, image) for m, c in terms])
    counts: dict[int, int] = {}
    for monomial, _ in terms:
        for i, e in enumerate(monomial):
            if e:
                counts[i] = counts.get(i, 0) + 1
    best = max(counts, key=lambda i: (counts[i], -i), default=None)
    if best is None or counts[best] < 2:
        return sp.Add(*[_coefficient_expr(c) * _monomial_expr(m, image) for m, c in terms])
    inside, outside = [], []
    for monomial, coefficient in terms:
        if monomial[best]:
            reduced = list(monomial)
            reduced[best] -= 1
            inside.append((tuple(reduced), coefficient))
        else:
            outside.append((monomial, coefficient))
    inner = _nest(inside, image)
    factor = image.back[best]
    # keep a leading minus outside the parentheses: -c1*(x + y) rather than c1*(-x - y)
    negated = isinstance(inner, sp.Add) and inner.could_extract_minus_sign()
    product = -(factor * (-inner)) if negated else factor * inner
    return product + _nest(outside, image)
