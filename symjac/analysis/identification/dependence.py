r"""Linear dependence between the columns of a regressor, found with numbers and solved exactly.

A regressor's entries are polynomials in the *motion* (the sines and cosines of the angles, the rates, the
accelerations, prismatic joint variables, gravity's magnitude) whose coefficients are polynomials in the *geometry*
(lengths such as ``a2``, sines and cosines of constant twists). In the polynomial image
(:mod:`~symjac.symbolic.trigpoly`) each entry has a unique normal form, so column :math:`j` of :math:`Y` becomes a
table :math:`A_j`: one row per (row of :math:`Y`, motion monomial), the entry a polynomial in the geometry.
Column :math:`d` depends on columns :math:`K` exactly when :math:`A_d = \sum_{k \in K} c_k A_k` in every row of the
table, with :math:`c_k` in the field of rational functions of the geometry: that is a linear system, solved here
exactly (:func:`exact_combination`). Which columns to try, and which rows of the table to solve with, are chosen
with numbers (:class:`Samples`): the table evaluated at random motions and one set of geometric values.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyElement, ring

from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import has_intermediates, inline
from symjac.symbolic.trigpoly import TrigImage, image_of, reduce_image

__all__ = ["ColumnTable", "Samples", "column_table", "exact_combination", "sample_values"]

Key = tuple[int, tuple[int, ...]]  # (row of Y, exponents of the motion generators)


@dataclass(frozen=True)
class ColumnTable:
    """Each column of a regressor as a table {(row, motion monomial): polynomial in the geometry} (module docstring).

    ``motion`` and ``geometry`` are the indices of the image's generators of each kind. The coefficient polynomials
    live in a ring of their own, ``ring``, whose generators are the geometry's (in that order): the exact solve then
    works with a handful of generators rather than the image's fifty.
    """

    image: TrigImage
    rows: int
    motion: tuple[int, ...]
    geometry: tuple[int, ...]
    ring: Any
    columns: tuple[dict[Key, PolyElement], ...]

    def is_zero(self, column: int) -> bool:
        """Whether column ``column`` is identically zero (its parameter has no effect at all)."""
        return not self.columns[column]

    def in_image(self, poly: PolyElement) -> PolyElement:
        """A coefficient polynomial as an element of the image's ring."""
        width = len(self.image.gens)
        terms = {}
        for monomial, coefficient in poly.iterterms():
            full = [0] * width
            for g, e in zip(self.geometry, monomial, strict=False):  # no geometry: one unused generator
                full[g] = e
            terms[tuple(full)] = coefficient
        return self.image.ring_and_gens[0].from_dict(terms)

    def reduced(self, poly: PolyElement) -> PolyElement:
        """``poly`` modulo the geometry's relations (sin^2 + cos^2 = 1 of constant angles, sqrt(n)^2 = n)."""
        if not self.relations or not poly:
            return poly
        reduced = reduce_image(self.in_image(poly), self.image)
        return self.ring.from_dict({tuple(m[g] for g in self.geometry): c for m, c in reduced.iterterms()})

    @property
    def relations(self) -> bool:
        """Whether the geometry's generators obey relations (constant angles, square roots)."""
        return bool(self.image.constant_angles or self.image.relations)


def _exact_entries(matrix: sp.MatrixBase) -> list[sp.Expr]:
    """The entries written out (a nested regressor's intermediates inlined) with floats made exact rationals."""
    entries = list(matrix)
    if has_intermediates(matrix):
        entries = inline(entries)
    return [sp.nsimplify(e, rational=True) if e.has(sp.Float) else sp.sympify(e) for e in entries]


def column_table(matrix: sp.MatrixBase, basis: AngleBasis, motion: frozenset[sp.Symbol]) -> ColumnTable:
    """The table of every column of ``matrix`` (module docstring).

    ``basis`` holds the angles of the revolute coordinates (any unimodular basis: the normal form is unique in each);
    ``motion`` every symbol of the motion (coordinates, rates, accelerations, gravity's magnitude). A generator whose
    expression holds one of them belongs to the motion, the others (constant angles, lengths, numbers such as
    sqrt(2)) to the geometry.
    """
    rows, cols = matrix.shape
    image, polys = image_of(_exact_entries(matrix), basis)
    count = len(image.gens)
    moving = tuple(i for i in range(count) if image.back(i).free_symbols & motion)
    geometry = tuple(i for i in range(count) if i not in set(moving))
    small = ring([f"h{i}" for i in range(max(len(geometry), 1))], QQ, order="lex")[0]
    tables: list[dict[Key, dict[tuple[int, ...], Any]]] = [{} for _ in range(cols)]
    pad = (0,) * (1 - len(geometry)) if not geometry else ()
    for index, poly in enumerate(polys):
        row, column = divmod(index, cols)
        table = tables[column]
        for monomial, coefficient in poly.iterterms():
            key = (row, tuple(monomial[g] for g in moving))
            rest = tuple(monomial[g] for g in geometry) + pad
            terms = table.setdefault(key, {})
            terms[rest] = terms.get(rest, QQ.zero) + coefficient
    columns = tuple({key: small.from_dict(terms) for key, terms in table.items()} for table in tables)
    return ColumnTable(image, rows, moving, geometry, small, columns)


def sample_values(table: ColumnTable, values: Mapping[sp.Symbol, np.ndarray | float]) -> np.ndarray:
    """Every generator's value for each sample, ``(samples, generators)``, given every symbol's value(s)."""
    count = max((np.size(v) for v in values.values()), default=1)
    symbols = sorted(values, key=sp.default_sort_key)
    arguments = [np.broadcast_to(np.asarray(values[s], dtype=float), (count,)) for s in symbols]
    out = np.empty((count, len(table.image.gens)))
    for index in range(len(table.image.gens)):
        expression = table.image.back(index)
        if expression in values:
            out[:, index] = np.broadcast_to(np.asarray(values[expression], dtype=float), (count,))
        else:
            function = sp.lambdify(symbols, expression, "numpy")
            out[:, index] = np.broadcast_to(np.asarray(function(*arguments), dtype=float), (count,))
    return out


def _value(poly: PolyElement, point: np.ndarray) -> float:
    """A polynomial of the image at one point (one value per generator)."""
    total = 0.0
    for monomial, coefficient in poly.iterterms():
        term = float(coefficient)
        for g, e in enumerate(monomial):
            if e:
                term *= point[g] ** e
        total += term
    return total


class Samples:
    """The columns' numbers: each column stacked over the samples, and its table's coefficients at one geometry.

    ``matrix`` is ``(rows * samples, columns)``, the regressor at every sample (rows of one sample together), for the
    geometric values the generators take in ``point_values`` (constant over the samples).
    """

    def __init__(self, table: ColumnTable, point_values: np.ndarray):
        self.table = table
        point = point_values[0, list(table.geometry)] if table.geometry else np.zeros(1)
        self.coefficients = [{key: _value(poly, point) for key, poly in column.items()} for column in table.columns]
        samples, columns = point_values.shape[0], len(table.columns)
        motion = point_values[:, list(table.motion)]
        blocks = []
        for row in range(table.rows):  # Y at every sample = (monomials at the samples) x (coefficients), row by row
            keys = sorted({key for column in self.coefficients for key in column if key[0] == row})
            position = {key: i for i, key in enumerate(keys)}
            exponents = np.array([key[1] for key in keys], dtype=int).reshape(len(keys), len(table.motion))
            monomials = np.ones((samples, len(keys)))
            for g in range(len(table.motion)):
                top = int(exponents[:, g].max(initial=0))
                if top:  # each power once, then gathered (elementwise ** over the table took 0.3 s a row)
                    powers = motion[:, g:g + 1] ** np.arange(top + 1)
                    monomials *= powers[:, exponents[:, g]]
            at, of, values = [], [], []
            for j, column in enumerate(self.coefficients):
                for key, value in column.items():
                    if key[0] == row:
                        at.append(position[key])
                        of.append(j)
                        values.append(value)
            A = np.zeros((len(keys), columns))
            A[at, of] = values
            blocks.append(monomials @ A)
        self.matrix = np.stack(blocks, axis=1).reshape(samples * table.rows, columns)


def _rows_for(samples: Samples, support: Sequence[int], keys: Sequence[Key]) -> list[int] | None:
    """``len(support)`` rows of the table in which the support's columns are independent (at the sampled geometry)."""
    B = np.array([[samples.coefficients[k].get(key, 0.0) for k in support] for key in keys])
    chosen: list[int] = []
    basis: list[np.ndarray] = []
    norms = np.linalg.norm(B, axis=1)
    scale = float(norms.max()) if len(norms) else 0.0
    for r in np.argsort(-norms, kind="stable"):
        if len(chosen) == len(support) or norms[r] <= 1e-12 * scale:
            break
        v = B[r] / norms[r]
        for _ in range(2):  # Gram-Schmidt, twice for the digits
            for u in basis:
                v = v - (u @ v) * u
        if np.linalg.norm(v) > 1e-8:
            basis.append(v / np.linalg.norm(v))
            chosen.append(int(r))
    return chosen if len(chosen) == len(support) else None


def exact_combination(table: ColumnTable, samples: Samples, target: int,
                      support: Sequence[int]) -> dict[int, tuple[PolyElement, PolyElement]] | None:
    r"""Column ``target`` as :math:`\sum_k c_k\,\text{column}_k` over ``support``, exactly, or None if it is not.

    Each :math:`c_k` is returned as (numerator, denominator), polynomials in the geometry. The system is solved on
    ``len(support)`` rows of the tables chosen with numbers (:func:`_rows_for`), by Gaussian elimination over the
    rational functions of the geometry with pivots chosen by their values at the sampled geometry; the solution is
    then checked on every row, modulo :math:`S^2 + C^2 = 1` of constant angles (:func:`reduce_image`).
    """
    field = table.ring.to_field()
    zero = table.ring.zero
    columns = table.columns
    keys = sorted(set(columns[target]).union(*(columns[k] for k in support)))
    if not support:
        return {} if not columns[target] else None
    chosen = _rows_for(samples, support, keys)
    if chosen is None:
        return None
    n = len(support)
    system = [[field(columns[k].get(keys[r], zero)) for k in support] + [field(columns[target].get(keys[r], zero))]
              for r in chosen]
    numbers = np.array([[samples.coefficients[k].get(keys[r], 0.0) for k in support]
                        + [samples.coefficients[target].get(keys[r], 0.0)] for r in chosen])
    for col in range(n):  # elimination, pivots by size at the sampled geometry (exact and numeric in step)
        pivot = col + int(np.argmax(np.abs(numbers[col:, col])))
        if abs(numbers[pivot, col]) < 1e-12 * max(1.0, float(np.abs(numbers).max())):
            return None
        system[col], system[pivot] = system[pivot], system[col]
        numbers[[col, pivot]] = numbers[[pivot, col]]
        for r in range(n):
            if r != col and system[r][col]:
                factor = system[r][col] / system[col][col]
                system[r] = [a - factor * b for a, b in zip(system[r], system[col], strict=True)]
                numbers[r] -= numbers[r, col] / numbers[col, col] * numbers[col]
    solution = [system[i][n] / system[i][i] for i in range(n)]
    denominator = table.ring.one  # the check, on every row, over one common denominator (no gcd per row)
    for c in solution:
        if c:
            denominator = denominator.lcm(c.denom)
    numerators = [c.numer * denominator.exquo(c.denom) if c else zero for c in solution]
    for key in keys:
        residual = denominator * columns[target].get(key, zero)
        for numerator, k in zip(numerators, support, strict=True):
            entry = columns[k].get(key)
            if entry is not None and numerator:
                residual -= numerator * entry
        if residual and table.reduced(residual):
            return None
    found = {}
    for c, k in zip(solution, support, strict=True):
        numerator = table.reduced(c.numer) if c else zero
        if numerator:
            found[k] = (numerator, c.denom)
    return found
