r"""Trigonometric simplification of kinematic expressions: one exact normal form, then a compact layout.

Kinematic expressions are polynomials in the sines and cosines of joint angles (and in lengths and prismatic
variables). SymPy's general ``simplify``/``trigsimp`` search that space blindly and are slow on robot Jacobians.
This module exploits the structure instead:

1. **Angle basis** (:class:`~symjac.symbolic.angles.AngleBasis`). Pick angles :math:`\psi_j`, integer combinations
   of the joint angles, in which the result should read; for parallel joints these are the textbook sums
   (:math:`\theta_2 + \theta_3`, giving :math:`c_{23}`). The chain chooses them per frame
   (see :meth:`symjac.kinematics.chain.Chain.angle_basis`).
2. **Polynomial image** (:mod:`symjac.symbolic.trigpoly`). Every :math:`\sin`/:math:`\cos` of a joint-angle
   combination is expanded in the basis,
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

import functools
from collections.abc import Callable, Sequence

import sympy as sp
from sympy.polys.rings import PolyElement

from symjac.progress import report
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.layout import expanded_expr, nested_expr
from symjac.symbolic.nested import has_intermediates, named
from symjac.symbolic.trigpoly import TrigImage, image_of, product_image

__all__ = ["is_identity", "printed_ops", "simplify_expr", "simplify_matrix", "simplify_product", "trig_normal_form"]


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
    _, (difference,) = image_of([sp.sympify(left) - sp.sympify(right)], basis)
    return not difference


def simplify_expr(expr: sp.Expr, basis: AngleBasis, *, nested: bool = True) -> sp.Expr:
    """Simplify one expression: normal form in ``basis``, laid out nested (default) or expanded."""
    return simplify_matrix(sp.Matrix([expr]), basis, nested=nested)[0]


def printed_ops(expr: sp.Expr) -> int:
    r"""Operations as the result is read: like ``count_ops``, but a sine or cosine counts as one symbol.

    Textbook shorthand prints :math:`\sin(\theta_1 + \dots + \theta_k)` as :math:`s_{1 \dots k}`, so the sum
    inside does not make an entry longer; counting it would prefer, for a long run of parallel joints, relative angles
    that factor a long sine out over the plain sum :math:`\sum_k L_k s_{1 \dots k}`.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> printed_ops(2 * sp.sin(t1 + t2) + sp.cos(t1))
    2
    """
    if expr.is_Atom or isinstance(expr, sp.sin | sp.cos):
        return 0
    if isinstance(expr, sp.Add | sp.Mul):
        return len(expr.args) - 1 + sum(printed_ops(arg) for arg in expr.args)
    return 1 + sum(printed_ops(arg) for arg in expr.args)


def simplify_matrix(
    matrix: sp.MatrixBase, basis: AngleBasis | Sequence[AngleBasis], *, nested: bool = True
) -> sp.Matrix:
    """Simplify every entry of ``matrix`` (see the module docstring).

    With several bases, each entry is written in every one of them and the form with the fewest operations is
    kept (the first basis wins ties). All entries written in one basis share one polynomial ring.
    """
    if has_intermediates(matrix):  # nested (generic geometry): no textbook form to find
        return sp.Matrix(matrix)
    bases = [basis] if isinstance(basis, AngleBasis) else list(basis)
    image, polys = image_of(list(matrix), bases[0])
    return _laid_out(image, polys, (matrix.rows, matrix.cols), bases[1:], nested)


def simplify_product(
    factors: Sequence[sp.MatrixBase], basis: AngleBasis | Sequence[AngleBasis], *, nested: bool = True
) -> sp.Matrix:
    r"""``simplify_matrix(F_1 * F_2 * ... * F_m)``, the product taken on normal forms (:func:`product_image`).

    The result is the same matrix; the raw product is never built (frame changes of long chains, where a chain of
    rotations multiplies a Jacobian, spent most of their time in SymPy's own products).

    Examples
    --------
    >>> t = sp.Symbol("theta1", real=True)
    >>> R = sp.Matrix([[sp.cos(t), -sp.sin(t)], [sp.sin(t), sp.cos(t)]])
    >>> simplify_product([R, R], AngleBasis.of([t]))[1, 0]
    2*sin(theta1)*cos(theta1)
    """
    if any(has_intermediates(factor) for factor in factors):  # nested: multiplied as they are, each product named
        return functools.reduce(lambda a, b: (sp.Matrix(a) * sp.Matrix(b)).applyfunc(named), factors)
    bases = [basis] if isinstance(basis, AngleBasis) else list(basis)
    image, polys, shape = product_image(factors, bases[0])
    return _laid_out(image, polys, shape, bases[1:], nested)


def _laid_out(image: TrigImage, polys: Sequence[PolyElement], shape: tuple[int, int],
              other_bases: Sequence[AngleBasis], nested: bool) -> sp.Matrix:
    """Normal forms laid out as a matrix, each entry in the shortest of its first basis and ``other_bases``."""
    layout: Callable[[PolyElement, TrigImage], sp.Expr] = nested_expr if nested else expanded_expr
    best = [layout(poly, image) for poly in polys]
    if other_bases:
        # The other bases start from the first one's result, not from the raw products: the normal form is unique,
        # so it is the same, and the first result is a small fraction of the raw tree (a long parallel run has n + 1
        # bases: planar 16R went from 0.3 s to a few ms per basis).
        start = list(best)
        best_ops = [printed_ops(expr) for expr in best]
        for number, candidate in enumerate(other_bases, start=2):
            report(f"simplifying: angle basis {number} of {len(other_bases) + 1}")
            image, polys = image_of(start, candidate)
            for index, poly in enumerate(polys):
                expr = layout(poly, image)
                ops = printed_ops(expr)
                if ops < best_ops[index]:
                    best[index], best_ops[index] = expr, ops
    return sp.Matrix(*shape, best)
