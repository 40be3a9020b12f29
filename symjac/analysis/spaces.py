r"""Rank, null space and range of a Jacobian, numerically (SVD) or exactly, and the task rows an arm controls.

At a configuration :math:`q`, :math:`J(q)` maps joint rates to the twist :math:`[v; \omega]`. Its four fundamental
subspaces say what the arm can and cannot do there: the *range* holds the motions it can make, the *left null space*
the directions it cannot move in (equally, by :math:`\tau = J^T F`, the wrenches it holds with zero joint torque),
the *null space* the joint motions that move nothing (self-motion), and the *rank* how many independent directions
remain. :func:`jacobian_spaces` computes them by SVD, :func:`symbolic_spaces` exactly with some joints fixed.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import Point, jacobian, point_vector
from symjac.kinematics.memo import memoized
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.ends import end_point
from symjac.model.robot import Robot

__all__ = [
    "JacobianSpaces",
    "SymbolicSpaces",
    "jacobian_spaces",
    "symbolic_spaces",
    "task_rows",
]


# --- rank, null space, range ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class JacobianSpaces:
    r"""The four fundamental subspaces of a numeric Jacobian, from its SVD :math:`J = U \Sigma V^T`.

    ``null_space`` (columns: joint motions that move nothing), ``range_space`` (columns: Cartesian motions the arm
    can make), ``left_null_space`` (columns: Cartesian directions it cannot move in, which are also the wrenches it
    holds with zero joint torque, :math:`J^T F = 0`). ``manipulability`` is :math:`\sqrt{\det(J J^T)}`, the product of
    the singular values; ``condition_number`` is :math:`\sigma_{max}/\sigma_{min}` (infinite at a singularity).
    """

    singular_values: np.ndarray
    rank: int
    tolerance: float
    null_space: np.ndarray
    range_space: np.ndarray
    left_null_space: np.ndarray

    @property
    def manipulability(self) -> float:
        r""":math:`w = \sqrt{\det(J J^T)} = \prod_i \sigma_i` (for rows <= columns)."""
        return float(np.prod(self.singular_values))

    @property
    def condition_number(self) -> float:
        r""":math:`\sigma_{max} / \sigma_{min}`; ``inf`` when the smallest singular value is zero."""
        smallest = float(self.singular_values[-1]) if self.singular_values.size else 0.0
        return math.inf if smallest <= self.tolerance else float(self.singular_values[0] / smallest)


def jacobian_spaces(J: np.ndarray, tolerance: float | None = None) -> JacobianSpaces:
    r"""Rank and the null, range and left-null spaces of a numeric matrix ``J`` (orthonormal bases, by SVD).

    The default ``tolerance`` is NumPy's ``matrix_rank`` rule, :math:`\sigma_{max} \max(m, n)\,\varepsilon`.

    Examples
    --------
    >>> spaces = jacobian_spaces(np.array([[1.0, 1.0], [0.0, 0.0]]))
    >>> spaces.rank, spaces.left_null_space.ravel().round(6).tolist()
    (1, [0.0, 1.0])
    """
    J = np.asarray(J, dtype=float)
    if J.ndim != 2:
        raise ArgumentError(f"a Jacobian must be a 2-d array, got shape {J.shape}")
    U, sigma, Vt = np.linalg.svd(J)
    if tolerance is None:
        tolerance = float(sigma.max(initial=0.0)) * max(J.shape) * np.finfo(float).eps
    rank = int(np.sum(sigma > tolerance))
    return JacobianSpaces(sigma, rank, tolerance, Vt[rank:].T, U[:, :rank], U[:, rank:])


@dataclass(frozen=True)
class SymbolicSpaces:
    """Rank and bases (as columns) of the null, range and left-null spaces of a Jacobian, exact."""

    jacobian: sp.Matrix
    rank: int
    null_space: sp.Matrix
    range_space: sp.Matrix
    left_null_space: sp.Matrix


def symbolic_spaces(
    robot: Robot | Chain,
    values: Mapping[sp.Symbol, sp.Expr],
    rows: Sequence[int] | None = None,
    frame: Frame = 0,
    point: Point | None = None,
) -> SymbolicSpaces:
    r"""The exact subspaces of the Jacobian with some joint variables fixed, e.g. at a singular configuration.

    ``values`` maps joint variables (and, optionally, parameters) to values; the others stay symbolic. Practical for
    small arms and sparse frames; use :func:`jacobian_spaces` on :func:`numeric_jacobian` otherwise. The rank is the
    generic rank over the remaining symbols.

    Examples
    --------
    >>> from symjac import load_robot
    >>> robot = load_robot("planar2r")
    >>> spaces = symbolic_spaces(robot, {robot.q[1]: 0}, frame=2)
    >>> spaces.rank, spaces.left_null_space.T
    (1, Matrix([[1, 0]]))
    """
    chain = as_chain(robot)
    robot = chain.robot
    if point is None:
        point = end_point(robot)
    point_xyz = point_vector(robot, point)
    chosen = list(task_rows(chain, point_xyz) if rows is None else rows)
    J = jacobian(chain, frame=frame, point=point_xyz)[chosen, :].xreplace(dict(values))
    J = sp.Matrix(J.rows, J.cols, [sp.factor_terms(sp.trigsimp(entry)) for entry in J])

    def columns(vectors: list[sp.Matrix], size: int) -> sp.Matrix:
        if not vectors:
            return sp.zeros(size, 0)
        return sp.Matrix.hstack(*[v.applyfunc(lambda e: sp.factor_terms(sp.simplify(e))) for v in vectors])

    return SymbolicSpaces(J, J.rank(simplify=True), columns(J.nullspace(simplify=True), J.cols),
                          columns(J.columnspace(simplify=True), J.rows),
                          columns(J.T.nullspace(simplify=True), J.rows))


# --- task rows and frames ----------------------------------------------------------------------------------------


@memoized(point=point_vector)
def task_rows(chain: Chain, point: Point | None = None) -> tuple[int, ...]:
    r"""The rows of the basic Jacobian an arm controls: all six for n >= 6, else n independent rows.

    Rows identically zero in frame {0} are dropped (a planar arm never moves along z); of the rest, rows are taken in
    the order :math:`v_x, v_y, v_z, \omega_x, \omega_y, \omega_z` while they add rank at a generic configuration.
    This gives x, y for a planar 2R arm, x, y, :math:`\omega_z` for a planar 3R arm and the position rows for a
    3-joint positioning arm.
    """
    return _task_rows(chain, point)  # type: ignore[arg-type]  # normalised by @memoized


def _task_rows(chain: Chain, point: tuple[sp.Expr, ...]) -> tuple[int, ...]:
    robot = chain.robot
    if robot.n_coordinates >= 6:
        return tuple(range(6))
    J = jacobian(chain, frame=0, point=point)
    generator = random.Random(20261122)
    samples = [[generator.uniform(-math.pi, math.pi) for _ in range(robot.n_coordinates)] for _ in range(2)]
    numeric = [numeric_jacobian(chain, q, 0, point) for q in samples]
    rows: list[int] = []
    for row in range(6):
        if all(entry == 0 for entry in J[row, :]):
            continue
        candidate = [*rows, row]
        if all(np.linalg.matrix_rank(N[candidate, :], tol=1e-9) == len(candidate) for N in numeric):
            rows = candidate
        if len(rows) == robot.n_coordinates:
            return tuple(rows)
    raise ArgumentError(f"{robot.name}: its {robot.n_coordinates} coordinates control only {len(rows)} "
                        "independent task rows")
