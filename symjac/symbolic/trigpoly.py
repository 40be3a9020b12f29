r"""The polynomial image of kinematic expressions, where trigonometric identities become exact algebra.

Every :math:`\sin`/:math:`\cos` of a joint-angle combination is expanded in an angle basis,
:math:`\cos(\sum_j m_j\psi_j) + i\sin(\sum_j m_j\psi_j) = \prod_j (C_j + i S_j)^{m_j}`, with :math:`S_j, C_j`
independent generators of a sparse polynomial ring over the rationals. Reducing modulo :math:`S_j^2 + C_j^2 - 1`
(:func:`reduce_image`; the generators form a Groebner basis) gives a *unique normal form*.
:mod:`symjac.symbolic.layout` lays normal forms out for people; determinants and singular factors are computed on the
image directly.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

from symjac.errors import NoClosedFormError, ResultTooLargeError
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import Intermediate
from symjac.symbolic.size import current_term_limit

__all__ = ["TrigImage", "image_of", "product_image", "reduce_image"]


@dataclass
class TrigImage:
    """The polynomial ring an expression lives in, and the way back to SymPy expressions.

    Generators, in ring order: :math:`S_j, C_j` of each basis angle, :math:`S_k, C_k` of each constant angle (an
    angle free of joint variables: a twist, an offset, a parameter), then the remaining atoms.
    """

    basis: AngleBasis
    constant_angles: list[sp.Expr]
    atoms: list[sp.Expr]
    relations: list[tuple[int, int]] = field(default_factory=list)  # (index of sqrt(n) generator, n)
    _back: dict[int, sp.Expr] = field(default_factory=dict, repr=False)
    #: Expressions already laid out from this image, by layout (:mod:`symjac.symbolic.layout`): sub-sums met again
    #: are built once.
    layouts: dict[str, dict[Any, Any]] = field(default_factory=dict, repr=False, compare=False)

    @property
    def angle_count(self) -> int:
        """Angles with a sine/cosine generator pair: basis angles first, then constant angles."""
        return len(self.basis.angles) + len(self.constant_angles)

    @cached_property
    def ring_and_gens(self) -> tuple[Any, tuple[PolyElement, ...]]:
        """The polynomial ring (lex order over QQ) and its generators."""
        count = 2 * self.angle_count + len(self.atoms)
        names = [f"g{i}" for i in range(count)]
        polynomial_ring, *gens = ring(names, QQ, order="lex") if names else ring("g0", QQ, order="lex")
        return polynomial_ring, tuple(gens)

    @property
    def gens(self) -> tuple[PolyElement, ...]:
        """The generators, in ring order."""
        return self.ring_and_gens[1]

    def sine(self, j: int) -> PolyElement:
        """The generator :math:`S_j` of angle j."""
        return self.gens[2 * j]

    def cosine(self, j: int) -> PolyElement:
        """The generator :math:`C_j` of angle j."""
        return self.gens[2 * j + 1]

    def back(self, index: int) -> sp.Expr:
        """The SymPy expression of generator ``index``, built when first asked for.

        A long chain's ring has hundreds of generators and a link uses two of them: building every sine and cosine of
        every basis angle up front took most of ``symjac show`` on a 200-joint arm.
        """
        if index not in self._back:
            angles = len(self.basis.angles) + len(self.constant_angles)
            if index < 2 * angles:
                k, basis_count = index // 2, len(self.basis.angles)
                angle = self.basis.angles[k] if k < basis_count else self.constant_angles[k - basis_count]
                self._back[index] = sp.cos(angle) if index % 2 else sp.sin(angle)
            else:
                self._back[index] = self.atoms[index - 2 * angles]
        return self._back[index]

    @cached_property
    def ideal(self) -> list[PolyElement]:
        """The relations S^2 + C^2 - 1 per angle and g^2 - n per sqrt(n), a Groebner basis (coprime leading terms)."""
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
    seen: dict[int, sp.Expr] = {}  # by identity: see image_of

    def visit(expr: sp.Expr) -> None:
        if id(expr) in seen:
            return
        seen[id(expr)] = expr
        if expr.is_Rational:
            return
        if isinstance(expr, Intermediate):  # a nested result: its written-out form has no normal form worth having
            raise NoClosedFormError()
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


def image_of(exprs: Sequence[sp.Expr], basis: AngleBasis) -> tuple[TrigImage, list[PolyElement]]:
    """The ring of ``exprs`` in ``basis`` and each expression's normal form in it (one ring for all).

    Examples
    --------
    >>> from symjac.symbolic.layout import expanded_expr
    >>> t = sp.Symbol("theta1", real=True)
    >>> image, (poly,) = image_of([sp.cos(2 * t)], AngleBasis.of([t]))
    >>> expanded_expr(poly, image)
    2*cos(theta1)**2 - 1
    """
    constant_angles, atoms = _collect_atoms(exprs, basis)
    image = TrigImage(basis, constant_angles, atoms)
    offset = 2 * image.angle_count
    for i, atom in enumerate(atoms):
        if isinstance(atom, sp.Pow) and atom.base.is_Integer and atom.exp == sp.S.Half:
            image.relations.append((i, int(atom.base)))
    atom_index = {atom: offset + i for i, atom in enumerate(atoms)}
    angle_index = {angle: len(basis.angles) + k for k, angle in enumerate(constant_angles)}
    polynomial_ring, gens = image.ring_and_gens
    variables = frozenset(basis.variables)
    limit = current_term_limit()
    # Subexpressions are remembered by identity, each kept alive next to its image so that its id stays its own:
    # chain products share subtrees, and a dictionary keyed by the expressions themselves compares equal but
    # distinct trees node by node, as trees, which was measured at 51 of 84 s for a planar 16R arm.
    memo: dict[int, tuple[sp.Expr, PolyElement]] = {}
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
        if id(expr) in memo:
            return memo[id(expr)][1]
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
                result = reduce_image(result * convert(arg), image)
        elif isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp > 0:
            base, result = convert(expr.base), polynomial_ring.one
            for _ in range(int(expr.exp)):
                result = reduce_image(result * base, image)
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
        if len(result) > limit:
            raise ResultTooLargeError(len(result), limit)
        memo[id(expr)] = (expr, result)
        return result

    polys, total = [], 0
    for expr in exprs:
        polys.append(reduce_image(convert(sp.sympify(expr)), image))
        total += len(polys[-1])
        if total > limit:
            raise ResultTooLargeError(total, limit)
    return image, polys


def product_image(
    factors: Sequence[sp.MatrixBase], basis: AngleBasis
) -> tuple[TrigImage, list[PolyElement], tuple[int, int]]:
    r"""The normal form of the matrix product :math:`F_1 F_2 \cdots F_m`, multiplied in the image.

    Each factor is converted on its own (one ring for all) and the product is taken right to left on normal forms,
    reducing every entry after each step. This is :func:`image_of` of the product without ever building the product
    as a SymPy tree: raw SymPy products re-sort and re-flatten every partial sum (a 30-joint arm spent a third of
    its time there) and hand the conversion a tree much larger than the result.

    Returns the image, the entries of the product row by row, and its shape.

    Examples
    --------
    >>> from symjac.symbolic.layout import expanded_expr
    >>> t = sp.Symbol("theta1", real=True)
    >>> R = sp.Matrix([[sp.cos(t), -sp.sin(t)], [sp.sin(t), sp.cos(t)]])
    >>> image, polys, shape = product_image([R.T, R], AngleBasis.of([t]))
    >>> [expanded_expr(poly, image) for poly in polys], shape
    ([1, 0, 0, 1], (2, 2))
    """
    if not factors:
        raise ValueError("product_image needs at least one factor")
    for left, right in itertools.pairwise(factors):
        if left.cols != right.rows:
            raise ValueError(f"cannot multiply a {left.rows} x {left.cols} by a {right.rows} x {right.cols} matrix")
    image, polys = image_of([entry for factor in factors for entry in factor], basis)
    matrices, start = [], 0
    for factor in factors:
        flat = polys[start:start + factor.rows * factor.cols]
        matrices.append([flat[r * factor.cols:(r + 1) * factor.cols] for r in range(factor.rows)])
        start += factor.rows * factor.cols
    product = matrices[-1]
    for matrix in reversed(matrices[:-1]):
        product = _multiply(matrix, product, image)
    return image, [entry for row in product for entry in row], (factors[0].rows, factors[-1].cols)


def _multiply(
    left: list[list[PolyElement]], right: list[list[PolyElement]], image: TrigImage
) -> list[list[PolyElement]]:
    """The product of two matrices of normal forms, reduced (zero entries, most of a rotation's block, skipped)."""
    zero = image.ring_and_gens[0].zero
    limit = current_term_limit()
    columns = range(len(right[0]))
    product, total = [], 0
    for row in left:
        terms = [(a, right[k]) for k, a in enumerate(row) if a]
        entries = []
        for j in columns:
            entry = zero
            for a, right_row in terms:
                if right_row[j]:
                    entry += a * right_row[j]
            entries.append(reduce_image(entry, image))
            total += len(entries[-1])
            if total > limit:
                raise ResultTooLargeError(total, limit)
        product.append(entries)
    return product


def reduce_image(poly: PolyElement, image: TrigImage) -> PolyElement:
    r"""The remainder of ``poly`` modulo :attr:`TrigImage.ideal`, term by term.

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
