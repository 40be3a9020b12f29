r"""Angles results are written in, and sines and cosines of angle sums expanded into those of single angles.

An :class:`AngleBasis` names the angles a result should read in (for parallel joints the textbook sums,
:math:`\theta_2 + \theta_3`, giving :math:`c_{23}`); :mod:`symjac.symbolic.simplify` writes results in it. An
:class:`AngleExpansion` goes the other way, for machines: every sine and cosine of a joint-angle combination is
expanded by the addition formulas into the sines and cosines of the joint angles themselves, partial sums nested in
chain order so that common subexpression elimination shares them (generated code then evaluates one ``sin`` and
one ``cos`` per joint).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import sympy as sp
from sympy.core.function import AppliedUndef

from symjac.symbolic.dag import rebuild, with_args

__all__ = ["AngleBasis", "AngleExpansion", "fold_numbers"]


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
    >>> from symjac.symbolic.simplify import simplify_expr
    >>> simplify_expr(sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2), basis)
    cos(theta1 + theta2)
    """

    variables: tuple[sp.Symbol, ...]
    angles: tuple[sp.Expr, ...]
    _inverse: list[dict[int, int]] = field(init=False, repr=False, compare=False)  # sparse rows of M^-1
    _offsets: tuple[sp.Expr, ...] = field(init=False, repr=False, compare=False)
    _decompositions: dict[sp.Expr, tuple[tuple[int, ...], sp.Expr] | None] = field(
        init=False, repr=False, compare=False, default_factory=dict)

    def __post_init__(self) -> None:
        if len(self.angles) != len(self.variables):
            raise ValueError(f"need {len(self.variables)} basis angles, got {len(self.angles)}")
        rows = [self._linear_part(sp.expand(angle)) for angle in self.angles]
        parts = [row for row in rows if row is not None]
        inverse = _integer_inverse([row[0] for row in parts]) if len(parts) == len(rows) else None
        if inverse is None:
            raise ValueError(f"basis angles {self.angles} are not a unimodular combination of {self.variables}")
        object.__setattr__(self, "_inverse", [{j: int(c) for j, c in enumerate(row) if c} for row in inverse])
        object.__setattr__(self, "_offsets", tuple(row[1] for row in parts))

    def _linear_part(self, argument: sp.Expr) -> tuple[list[Fraction], sp.Expr] | None:
        r"""Rational coefficients :math:`c_k` of the variables in ``argument`` and the rest; ``None`` if not linear."""
        index = {v: k for k, v in enumerate(self.variables)}
        coefficients = [Fraction(0)] * len(self.variables)
        rest = []
        for term, coefficient in argument.as_coefficients_dict().items():
            if term in index and coefficient.is_Rational:
                coefficients[index[term]] += Fraction(int(coefficient.p), int(coefficient.q))
            elif term.free_symbols & index.keys():
                return None
            else:
                rest.append(coefficient * term)
        return coefficients, sp.Add(*rest)

    @classmethod
    def of(cls, variables: Iterable[sp.Symbol]) -> AngleBasis:
        """The trivial basis: each joint angle on its own."""
        variables = tuple(variables)
        return cls(variables, variables)

    def decompose(self, argument: sp.Expr) -> tuple[tuple[int, ...], sp.Expr] | None:
        r"""Write ``argument`` as :math:`\sum_j m_j \psi_j + c`; ``None`` if it is not linear in the variables.

        With :math:`\psi = M\theta + o` and :math:`\text{argument} = c^T\theta + r`: :math:`m^T = c^T M^{-1}` and
        :math:`c = r - m^T o`, in exact integer and rational arithmetic.
        """
        if argument not in self._decompositions:
            self._decompositions[argument] = self._decompose(argument)
        return self._decompositions[argument]

    def _decompose(self, argument: sp.Expr) -> tuple[tuple[int, ...], sp.Expr] | None:
        linear = self._linear_part(sp.expand(argument))
        if linear is None:
            return None
        coefficients, constant = linear
        sparse: dict[int, Fraction] = {}  # M^-1 is an integer matrix with few entries per row: add only those
        for c, row in zip(coefficients, self._inverse, strict=True):
            if c:
                for j, entry in row.items():
                    sparse[j] = sparse.get(j, Fraction(0)) + c * entry
        if any(m.denominator != 1 for m in sparse.values()):
            return None
        multiples = [int(sparse.get(j, 0)) for j in range(len(self.variables))]
        offsets = [m * offset for m, offset in zip(multiples, self._offsets, strict=True) if m and offset]
        if offsets:
            constant = sp.expand(constant - sp.Add(*offsets))
        return tuple(multiples), constant



class AngleExpansion:
    r"""Sines and cosines of joint-angle combinations rewritten in those of single joint angles (with offsets).

    .. math:: \sin(\psi_1 + \psi_2) = \sin\psi_1 \cos\psi_2 + \cos\psi_1 \sin\psi_2, \quad
              \cos(\psi_1 + \psi_2) = \cos\psi_1 \cos\psi_2 - \sin\psi_1 \sin\psi_2

    The sine and cosine of each angle :math:`\psi_j` (joint variable plus its constant offset) become the symbols
    ``sines`` and ``cosines`` (``_s{i}``, ``_c{i}`` for joint i).

    Parameters
    ----------
    variables : tuple of sympy.Symbol
        The revolute joint variables.
    angles : tuple of sympy.Expr
        Each variable with its constant offset (``theta2 - pi/2``).
    indices : tuple of int
        The joint number of each variable, for the names of the sine and cosine symbols.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> expansion = AngleExpansion((t1, t2), (t1, t2), (1, 2))
    >>> expansion.expand(sp.cos(t1 + t2))
    _c1*_c2 - _s1*_s2
    """

    def __init__(self, variables: tuple[sp.Symbol, ...], angles: tuple[sp.Expr, ...], indices: tuple[int, ...]):
        self.basis = AngleBasis(variables, angles)
        self.sines = tuple(sp.Symbol(f"_s{i}", real=True) for i in indices)
        self.cosines = tuple(sp.Symbol(f"_c{i}", real=True) for i in indices)
        self.angles = angles
        self.variables = frozenset(variables)
        self._cache: dict[sp.Expr, tuple[sp.Expr, sp.Expr]] = {}

    def sin_cos(self, argument: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
        """``(sin a, cos a)`` with ``a = sum_j m_j psi_j + c`` expanded, partial sums nested in chain order."""
        argument = sp.expand(argument)
        if argument in self._cache:
            return self._cache[argument]
        decomposition = self.basis.decompose(argument) if argument.free_symbols & self.variables else None
        if decomposition is None:
            result = (sp.sin(argument), sp.cos(argument))
        else:
            multiples, constant = decomposition
            sine, cosine = (sp.sin(constant), sp.cos(constant))
            for j, multiple in enumerate(multiples):
                s_j, c_j = (self.sines[j] if multiple > 0 else -self.sines[j]), self.cosines[j]
                for _ in range(abs(multiple)):
                    sine, cosine = sine * c_j + cosine * s_j, cosine * c_j - sine * s_j
            result = (sine, cosine)
        self._cache[argument] = result
        return result

    def expand(self, expr: sp.Expr) -> sp.Expr:
        """``expr`` with every joint-dependent sine/cosine expanded and numeric subexpressions folded to floats."""
        return self.expand_all([expr])[0]

    def expand_all(self, exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
        """:meth:`expand` of each of ``exprs``, every shared subexpression rewritten once (:mod:`~.dag`)."""
        def step(node: sp.Basic, args: tuple[sp.Basic, ...]) -> sp.Basic:
            if isinstance(node, sp.sin | sp.cos) and node.args[0].free_symbols & self.variables:
                return self.sin_cos(node.args[0])[0 if isinstance(node, sp.sin) else 1]
            return with_args(node, args)

        return _fold_all(rebuild(exprs, step))


def _integer_inverse(matrix: list[list[Fraction]]) -> list[list[Fraction]] | None:
    """The inverse of a square rational matrix if both are integer (so the determinant is +-1), else ``None``.

    Basis matrices are sparse with unit entries (cumulative sums of joint angles), so Gauss-Jordan elimination runs
    on sparse integer rows with a pivot of +-1 (no division; about n^2 steps for n joints instead of n^3 rational
    operations, which took seconds per basis at 200 joints); a column without a unit pivot falls back to dense
    elimination over the rationals.
    """
    n = len(matrix)
    if any(c.denominator != 1 for row in matrix for c in row):
        return None
    rows = [({j: int(c) for j, c in enumerate(row) if c}, {i: 1}) for i, row in enumerate(matrix)]
    for col in range(n):
        pivot = next((r for r in range(col, n) if abs(rows[r][0].get(col, 0)) == 1), None)
        if pivot is None:
            return _dense_integer_inverse(matrix)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        left, right = rows[col]
        if left[col] == -1:
            left, right = {j: -c for j, c in left.items()}, {j: -c for j, c in right.items()}
            rows[col] = (left, right)
        for r in range(n):
            factor = rows[r][0].get(col, 0) if r != col else 0
            if factor:
                for source, target in zip((left, right), rows[r], strict=True):
                    for j, c in source.items():
                        value = target.get(j, 0) - factor * c
                        if value:
                            target[j] = value
                        else:
                            target.pop(j, None)
    return [[Fraction(rows[i][1].get(j, 0)) for j in range(n)] for i in range(n)]


def _dense_integer_inverse(matrix: list[list[Fraction]]) -> list[list[Fraction]] | None:
    """:func:`_integer_inverse` by dense Gauss-Jordan elimination over the rationals (any pivot)."""
    n = len(matrix)
    work = [[*row, *(Fraction(int(i == j)) for j in range(n))] for i, row in enumerate(matrix)]
    for col in range(n):
        pivot = next((r for r in range(col, n) if work[r][col]), None)
        if pivot is None:
            return None
        work[col], work[pivot] = work[pivot], work[col]
        lead = work[col][col]
        work[col] = [x / lead for x in work[col]]
        for r in range(n):
            if r != col and work[r][col]:
                factor = work[r][col]
                work[r] = [x - factor * y for x, y in zip(work[r], work[col], strict=True)]
    inverse = [row[n:] for row in work]
    return inverse if all(c.denominator == 1 for row in inverse for c in row) else None


def fold_numbers(expr: sp.Expr) -> sp.Expr:
    """Replace every numeric subexpression that is not a plain number (``sqrt(2)/2``, ``cos(1/5)``) by a float.

    Examples
    --------
    >>> fold_numbers(sp.Symbol("x") * sp.sqrt(2) / 2 + sp.Rational(1, 4))
    0.70710678118654752*x + 1/4
    """
    return _fold_all([expr])[0]


def _fold_all(exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
    """:func:`fold_numbers` of each of ``exprs``, every shared subexpression visited once (:mod:`symjac.symbolic.dag`).

    A node is numeric when it is a number or every argument is numeric (``Expr.is_number``, computed once per node
    here); the largest numeric subexpressions are evaluated to 20 digits and stored as 17-digit floats.
    """
    numeric: dict[int, bool] = {}  # by identity, as in symjac.symbolic.dag

    def step(node: sp.Basic, args: tuple[sp.Basic, ...]) -> sp.Basic:
        if node.is_Atom:
            numeric[id(node)] = bool(node.is_number)
            return node
        numeric[id(node)] = (isinstance(node, sp.Expr) and not isinstance(node, AppliedUndef)
                             and all(numeric[id(arg)] for arg in node.args))
        if numeric[id(node)]:
            return sp.Float(sp.N(node, 20), 17)  # from the exact node: the arguments' floats are not used
        return with_args(node, args)

    return rebuild(exprs, step)
