r"""The base parameters: the fewest combinations of the standard parameters that the torques determine, in closed form.

Some columns of the regressor :math:`Y` are zero (a parameter with no effect on any torque: those of link 1 other
than :math:`ZZ_1` when joint 1 turns about a vertical axis) and others are combinations of the rest, as functions of
:math:`q, \dot q, \ddot q`: :math:`Y_d = \sum_k c_{dk} Y_k`, with coefficients :math:`c_{dk}` in the geometry. Keeping
the independent columns :math:`K` and putting every dependent parameter into the kept ones gives

.. math::
    Y\pi = \sum_{k \in K} Y_k \pi_k + \sum_d Y_d \pi_d = \sum_{k \in K} Y_k \Bigl(\pi_k + \sum_d c_{dk}\pi_d\Bigr)
    = Y_b\,\pi_b,

the base parameters :math:`\pi_{b,k} = \pi_k + \sum_d c_{dk}\pi_d`, named after the standard parameter they extend
with an ``R`` before the link number where something was added (``XXR2 = XX2 - YY2``, ``MR1 = M1 + M2``) and plainly
where nothing was (``XY2``). How many there are is the rank of :math:`Y` as a function, checked with numbers.

Which columns to keep follows the grouping rules of Khalil and co-workers: link by link, a tip-side link's parameter
goes into its predecessor's, and within a revolute link :math:`YY_j, MZ_j, M_j` are the ones given up, within a
prismatic one its inertia entries. Here that is a greedy scan: the columns ordered base link first and, within each
link, those to keep first (:func:`preferred_order`), a column kept when it is independent of the columns kept before
it. The scan runs on numbers (the regressor at :math:`2p` random motions, :math:`p` the number of parameters, for
the robot's geometric values and, as a guard against special values, for random ones: the set of larger rank
decides); each coefficient :math:`c_{dk}` is then solved for exactly and checked on every monomial of the polynomial
image (:mod:`.dependence`), so the result holds for every value of the geometric parameters, with no tolerance.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import sympy as sp

from symjac.analysis.dynamics.bodies import result_bases
from symjac.analysis.identification.dependence import (
    ColumnTable,
    Samples,
    column_table,
    exact_combination,
    sample_values,
)
from symjac.analysis.identification.regressor import Regressor
from symjac.errors import SymjacError
from symjac.kinematics.chain import as_chain
from symjac.model.robot import JointType, Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.layout import expanded_expr
from symjac.symbolic.nested import has_intermediates, lambdify_cse

__all__ = ["BaseParameters", "base_name", "base_parameters", "preferred_order"]

_KEEP_FIRST = {  # per joint type, a link's parameters from the most to the least worth keeping (module docstring)
    True: ("XX", "XY", "XZ", "YZ", "ZZ", "MX", "MY", "YY", "MZ", "M"),
    False: ("MX", "MY", "MZ", "M", "XX", "XY", "XZ", "YY", "YZ", "ZZ"),
}
_DRIVES = ("Ia", "Fv", "Fc", "Fo")  # after the link's ten: the armature goes into ZZR1 where it is ZZ1's column
_NAME = re.compile(r"^([A-Za-z]+?)(\d+)$")
_INDEPENDENT = 1e-7  # a column's part outside the span of those kept, relative to its size, above which it is kept
_SUPPORT = 1e-8  # a least-squares coefficient (columns scaled to unit size) below which it is taken as zero


@dataclass(frozen=True)
class BaseParameters:
    r"""The base parameters of a regressor (module docstring): :math:`Y\pi = Y_b\pi_b` exactly.

    Parameters
    ----------
    symbols : tuple of sympy.Symbol
        The base parameters, in the order of the standard parameters they extend (``XXR2``, or ``XY2`` when nothing
        was added).
    expressions : tuple of sympy.Expr
        Each base parameter as a combination of standard parameters, coefficients in the geometric parameters.
    matrix : sympy.ImmutableMatrix
        The base regressor :math:`Y_b`, one row per coordinate and one column per base parameter: the kept columns
        of :math:`Y`.
    rank : int
        The numeric rank of :math:`Y` stacked over random samples: equal to the number of base parameters.
    unidentifiable : tuple of sympy.Symbol
        The standard parameters whose columns are identically zero (no effect on any torque).
    grouped : dict
        Each dependent standard parameter (nonzero column) with its column as a combination of kept ones, written in
        their symbols: ``{M2: L2*MX2 - L2**2*ZZ2 + ...}`` reads :math:`Y_{M_2} = L_2 Y_{MX_2} - L_2^2 Y_{ZZ_2} + \dots`.
    standard : tuple of sympy.Symbol
        The standard parameter each base parameter extends (its column of :math:`Y`).
    """

    symbols: tuple[sp.Symbol, ...]
    expressions: tuple[sp.Expr, ...]
    matrix: sp.ImmutableMatrix
    rank: int
    unidentifiable: tuple[sp.Symbol, ...]
    grouped: dict[sp.Symbol, sp.Expr]
    standard: tuple[sp.Symbol, ...]

    def values(self, standard_values: Mapping[sp.Symbol, sp.Expr]) -> dict[sp.Symbol, sp.Expr]:
        """The base parameters' values for values of the standard ones (those missing count as zero)."""
        given = {**{p: sp.S.Zero for p in (*self.standard, *self.grouped)}, **standard_values}
        return {b: sp.expand(e.xreplace(given)) for b, e in zip(self.symbols, self.expressions, strict=True)}


def base_name(name: str, grouped: bool) -> str:
    """A base parameter's name: the standard name with ``R`` before the link number when something was grouped in.

    Examples
    --------
    >>> base_name("XX2", True), base_name("XY2", False), base_name("Ia1", True)
    ('XXR2', 'XY2', 'IaR1')
    """
    match = _NAME.match(name)
    if not grouped:
        return name
    return f"{match.group(1)}R{match.group(2)}" if match else f"{name}R"


def preferred_order(names: Sequence[str], robot: Robot) -> list[int]:
    """The columns in the order the greedy scan visits them: base link first, within a link those to keep first.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.analysis.identification import standard_parameters
    >>> names = [s.name for s in standard_parameters(load_robot("planar2r"))]
    >>> [names[i] for i in preferred_order(names, load_robot("planar2r"))][:10]
    ['XX1', 'XY1', 'XZ1', 'YZ1', 'ZZ1', 'MX1', 'MY1', 'YY1', 'MZ1', 'M1']
    """
    def key(position: int) -> tuple[int, int, int]:
        match = _NAME.match(names[position])
        if match is None:
            return (robot.n_joints + 1, 0, position)
        prefix, link = match.group(1), int(match.group(2))
        revolute = 1 <= link <= robot.n_joints and robot.joints[link - 1].type is JointType.REVOLUTE
        ranks = (*_KEEP_FIRST[revolute], *_DRIVES)
        return (link, ranks.index(prefix) if prefix in ranks else len(ranks), position)

    return sorted(range(len(names)), key=key)


def _motion_symbols(regressor: Regressor) -> frozenset[sp.Symbol]:
    robot = regressor.robot
    gravity = sp.sympify(regressor.gravity.magnitude).free_symbols
    return frozenset((*robot.coordinates, *robot.coordinate_rates, *robot.coordinate_accelerations, *gravity))


def _motion_samples(regressor: Regressor, rng: np.random.Generator, count: int) -> dict[sp.Symbol, np.ndarray]:
    """Random values of the motion: angles in (-pi, pi), lengths in (-1, 1), rates and accelerations N(0, 1)."""
    robot = regressor.robot
    motion: dict[sp.Symbol, np.ndarray] = {}
    for q, kind in zip(robot.coordinates, robot.coordinate_types, strict=True):
        motion[q] = rng.uniform(-np.pi, np.pi, count) if kind is JointType.REVOLUTE else rng.uniform(-1, 1, count)
    for symbol in (*robot.coordinate_rates, *robot.coordinate_accelerations):
        motion[symbol] = rng.normal(size=count)
    for symbol in sp.sympify(regressor.gravity.magnitude).free_symbols:
        motion[symbol] = rng.uniform(5, 15, count)
    return motion


def _sample_sets(table: ColumnTable, regressor: Regressor, seed: int) -> list[np.ndarray]:
    """The generators' values at 2p random motions, for the robot's geometric values and for random ones."""
    rng = np.random.default_rng(seed)
    motion = _motion_samples(regressor, rng, max(2 * len(regressor.parameters), 8))
    geometry = sorted(set().union(*(table.image.back(i).free_symbols for i in range(len(table.image.gens))))
                      - set(motion), key=sp.default_sort_key)
    defaults = regressor.robot.defaults
    chosen, scattered = {}, {}
    for symbol in geometry:
        default = float(defaults[symbol]) if symbol in defaults else None
        spread = rng.uniform(0.5, 1.5)
        chosen[symbol] = default if default is not None else spread
        scattered[symbol] = default * spread if default else rng.uniform(0.2, 1.0)
    return [sample_values(table, {**motion, **values}) for values in (chosen, scattered)]


def _unit_columns(matrix: np.ndarray) -> np.ndarray:
    norms = np.linalg.norm(matrix, axis=0)
    return matrix / np.where(norms > 0, norms, 1.0)


def _greedy_basis(units: np.ndarray, kept: Sequence[int]) -> np.ndarray:
    """An orthonormal basis of the kept columns by Gram-Schmidt in their order (twice, for the digits)."""
    basis = np.zeros((units.shape[0], 0))
    for k in kept:
        v = units[:, k] - basis @ (basis.T @ units[:, k])
        v = v - basis @ (basis.T @ v)
        basis = np.column_stack([basis, v / np.linalg.norm(v)])
    return basis


def _greedy(matrix: np.ndarray, order: Sequence[int], zero: Sequence[int]) -> list[int]:
    """The columns kept by the greedy scan on numbers alone."""
    units, basis, kept = _unit_columns(matrix), np.zeros((matrix.shape[0], 0)), []
    for j in order:
        if j in zero:
            continue
        v = units[:, j] - basis @ (basis.T @ units[:, j])
        v = v - basis @ (basis.T @ v)
        if np.linalg.norm(v) > _INDEPENDENT:
            basis = np.column_stack([basis, v / np.linalg.norm(v)])
            kept.append(j)
    return kept


Dependence = dict[int, dict[int, sp.Expr]]  # dependent column -> {kept column: coefficient}


def _scan(table: ColumnTable, samples: Samples, order: Sequence[int]) -> tuple[list[int], list[int], Dependence]:
    """Kept columns, zero columns, and each dependent column's exact coefficients on the kept ones."""
    units = _unit_columns(samples.matrix)
    basis = np.zeros((units.shape[0], 0))
    kept: list[int] = []
    zero: list[int] = []
    dependent: Dependence = {}
    for j in order:
        if table.is_zero(j):
            zero.append(j)
            continue
        v = units[:, j] - basis @ (basis.T @ units[:, j])
        v = v - basis @ (basis.T @ v)
        found = None
        if np.linalg.norm(v) <= _INDEPENDENT and kept:  # kept columns = basis R, R triangular: solve R w = basis^T u
            weights = np.linalg.solve(basis.T @ units[:, kept], basis.T @ units[:, j])  # (lstsq: 0.4 s when loaded)
            support = sorted(k for k, w in zip(kept, weights, strict=True) if abs(w) > _SUPPORT)
            found = exact_combination(table, samples, j, support)
            if found is None and len(support) < len(kept):  # a coefficient that vanishes at these values
                found = exact_combination(table, samples, j, sorted(kept))
        if found is None:  # independent (or not exactly dependent after all: kept, and the rank check will tell)
            basis = np.column_stack([basis, v / max(np.linalg.norm(v), 1e-300)])
            kept.append(j)
        else:
            dependent[j] = {k: sp.factor_terms(expanded_expr(table.in_image(numerator), table.image)
                                               / expanded_expr(table.in_image(denominator), table.image))
                            for k, (numerator, denominator) in found.items()}
    return kept, zero, dependent


def _exact(regressor: Regressor, order: Sequence[int], seed: int) -> tuple[list[int], list[int], Dependence, int]:
    """Kept, zero and dependent columns and the numeric rank, with exact coefficients (module docstring)."""
    robot = regressor.robot
    # the angles the regressor is laid out in (theta2 + theta3 of the PUMA as one angle): fewer terms than theta_i
    bases = result_bases(as_chain(robot))
    revolute = [q for q, kind in zip(robot.coordinates, robot.coordinate_types, strict=True)
                if kind is JointType.REVOLUTE]
    table = column_table(regressor.matrix, bases[0] if bases else AngleBasis.of(revolute), _motion_symbols(regressor))
    sets = [Samples(table, values) for values in _sample_sets(table, regressor, seed)]
    zero = [j for j in range(len(table.columns)) if table.is_zero(j)]
    counts = [len(_greedy(s.matrix, order, zero)) for s in sets]
    samples = sets[int(np.argmax(counts))]  # the robot's values unless they are special (a lower rank)
    kept, zero, dependent = _scan(table, samples, order)
    return kept, zero, dependent, int(np.linalg.matrix_rank(_unit_columns(samples.matrix)))  # no vectors: fast


def _number(value: float) -> sp.Expr:
    """A coefficient found in floating point: an exact rational where one with a small denominator is that close."""
    fraction = Fraction(value).limit_denominator(10_000)
    if abs(float(fraction) - value) <= 1e-9 * max(1.0, abs(value)):
        return sp.Rational(fraction.numerator, fraction.denominator)
    return sp.Float(value, 12)


def _floating(regressor: Regressor, order: Sequence[int], seed: int
              ) -> tuple[list[int], list[int], Dependence, int]:
    """:func:`_exact` for a nested regressor (generic geometry, its numbers floats): coefficients by least squares.

    Its columns are numbers times functions of the motion; their combinations are found at 2p random motions and
    written as exact rationals where they are (:func:`_number`), else as floats.
    """
    rng = np.random.default_rng(seed)
    count = max(2 * len(regressor.parameters), 8)
    motion = _motion_samples(regressor, rng, count)
    defaults = regressor.robot.defaults
    geometry = sorted(regressor.matrix.free_symbols - set(motion), key=sp.default_sort_key)
    f = sp.lambdify([*motion, *geometry], regressor.matrix, "numpy", cse=lambdify_cse)
    fixed = [float(defaults.get(symbol, 1)) for symbol in geometry]
    stacked = np.vstack([np.array(f(*(values[i] for values in motion.values()), *fixed), dtype=float)
                         for i in range(count)])
    norms = np.linalg.norm(stacked, axis=0)
    zero = [j for j in range(stacked.shape[1])
            if all(e == 0 for e in regressor.matrix[:, j]) or norms[j] <= 1e-11 * norms.max()]
    kept = _greedy(stacked, order, zero)
    units = _unit_columns(stacked)
    Q = _greedy_basis(units, kept)
    R = Q.T @ units[:, kept]
    dependent: Dependence = {}
    for j in sorted(set(range(stacked.shape[1])) - set(kept) - set(zero)):
        weights = np.linalg.solve(R, Q.T @ units[:, j])
        dependent[j] = {k: _number(w * norms[j] / norms[k]) for k, w in zip(kept, weights, strict=True)
                        if abs(w) > _SUPPORT}
    nonzero = sorted(set(range(units.shape[1])) - set(zero))  # float junk (1e-19 qdot^2) is no effect
    return kept, zero, dependent, int(np.linalg.matrix_rank(units[:, nonzero]))


def base_parameters(regressor: Regressor, *, seed: int = 0) -> BaseParameters:
    r"""The base parameters of ``regressor`` in closed form, with the base regressor (module docstring).

    Parameters
    ----------
    regressor : Regressor
        :func:`~symjac.analysis.identification.regressor.regressor` of the arm.
    seed : int
        Seed of the random samples that choose the columns (the result is exact whatever the seed).

    Returns
    -------
    BaseParameters
        With ``matrix * symbols == regressor.matrix * regressor.parameters`` exactly.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.analysis.dynamics import Gravity
    >>> from symjac.analysis.identification import regressor
    >>> base = base_parameters(regressor(load_robot("planar2r"), Gravity(direction=(0, -1, 0))))
    >>> for symbol, expression in zip(base.symbols, base.expressions):
    ...     print(symbol, "=", expression)
    ZZR1 = -L1**2*M1 - L1**2*M2 + ZZ1
    MXR1 = L1*M1 + L1*M2 + MX1
    MY1 = MY1
    ZZR2 = -L2**2*M2 + ZZ2
    MXR2 = L2*M2 + MX2
    MY2 = MY2
    """
    robot = regressor.robot
    names = regressor.names
    order = preferred_order(names, robot)
    route = _floating if has_intermediates(regressor.matrix) or regressor.matrix.has(sp.Float) else _exact
    kept, zero, dependent, rank = route(regressor, order, seed)
    if rank != len(kept):
        raise SymjacError(f"{robot.name}: the regressor's numeric rank is {rank} but {len(kept)} columns came out "
                          f"independent; try another seed")
    kept.sort()
    parameters = regressor.parameters
    additions: dict[int, list[sp.Expr]] = {k: [] for k in kept}
    grouped: dict[sp.Symbol, sp.Expr] = {}
    for d in sorted(dependent):
        terms = []
        for k, c in sorted(dependent[d].items()):
            additions[k].append(c * parameters[d])
            terms.append(c * parameters[k])
        grouped[parameters[d]] = sp.Add(*terms)
    symbols = tuple(sp.Symbol(base_name(names[k], bool(additions[k])), real=True) for k in kept)
    expressions = tuple(parameters[k] + sp.Add(*additions[k]) for k in kept)
    return BaseParameters(symbols, expressions, sp.ImmutableMatrix(regressor.matrix[:, kept]), rank,
                          tuple(parameters[j] for j in sorted(zero)), grouped, tuple(parameters[k] for k in kept))
