r"""Yoshikawa's manipulability and its gradient: numerically for any arm, in closed form for square Jacobians.

The manipulability of the task rows :math:`J` (m x n, m <= n) is :math:`w = \sqrt{\det(J J^T)}`, the product of
the singular values. Its gradient follows from the kinematic Hessian (:func:`symjac.kinematics.acceleration.hessian`),
:math:`H_k = \partial J / \partial q_k`:

.. math::
    \frac{\partial w}{\partial q_k} = \frac{w}{2}\operatorname{tr}\bigl((J J^T)^{-1}(H_k J^T + J H_k^T)\bigr)
                                    = w \operatorname{tr}(J^+ H_k),

with :math:`J^+ = J^T (J J^T)^{-1}`. With the SVD :math:`J = \sum_i \sigma_i u_i v_i^T` this reads
:math:`\partial w / \partial q_k = \sum_i (\prod_{j \ne i} \sigma_j)\, u_i^T H_k v_i`, which stays accurate as a
singular value shrinks (:func:`manipulability_gradient`).

**At a singular configuration** (w = 0) the gradient does not exist: near a simple singularity w behaves like
:math:`|t|` across it (for a square J, :math:`w = |\det J|`), so no single vector is its derivative there.
:func:`manipulability_gradient` raises :class:`~symjac.errors.ArgumentError` rather than return a misleading
vector; step off the singularity (any direction increases w) or use a damped measure.

**Square Jacobians, in closed form.** For m = n, :math:`w = |\det J|` and the factored determinant
(:func:`symjac.analysis.singularity.determinant.determinant`), :math:`\det J = c \prod_i f_i^{m_i}`, gives

.. math:: \nabla \log w = \nabla \log |\det J| = \sum_i m_i \frac{\nabla f_i}{f_i},

one *barrier term* per singular factor, each growing without bound as its own singularity is approached (the
PUMA 560's wrist factor :math:`s_5` gives :math:`\cot\theta_5` in the :math:`\theta_5` component). Following one
term moves the arm away from that singularity alone; following the total maximises :math:`\log w`
(:func:`log_det_gradient`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import Determinant, determinant
from symjac.analysis.spaces import task_rows
from symjac.errors import ArgumentError
from symjac.kinematics.acceleration import hessian
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import ROW_NAMES, Point, point_vector, rows_from_names
from symjac.kinematics.memo import frame_of, memoized
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.ends import end_point
from symjac.model.robot import Robot
from symjac.symbolic.simplify import simplify_matrix

__all__ = [
    "BarrierTerm",
    "LogDetGradient",
    "ManipulabilityGradient",
    "Rows",
    "log_det_gradient",
    "manipulability_gradient",
]

Rows = str | Sequence[str] | Sequence[int]
"""Task rows: names from :data:`~symjac.kinematics.jacobian.ROW_NAMES` (a sequence or one comma-separated string) or
indices."""


def _resolve_rows(chain: Chain, rows: Rows | None, point: tuple[sp.Expr, ...]) -> tuple[int, ...]:
    """Row indices 0..5, validated; the arm's :func:`~symjac.analysis.spaces.task_rows` when ``rows`` is None."""
    if rows is None:
        chosen = task_rows(chain, list(point))
    elif isinstance(rows, str) or all(isinstance(r, str) for r in rows):
        chosen = rows_from_names(rows if isinstance(rows, str) else [str(r) for r in rows])
    else:
        indices = [int(r) if isinstance(r, int | np.integer) and not isinstance(r, bool) else -1 for r in rows]
        if not indices or any(not 0 <= r < 6 for r in indices) or len(set(indices)) != len(indices):
            raise ArgumentError(f"rows must be distinct names from {', '.join(ROW_NAMES)} or indices 0..5, "
                                f"got {list(rows)}")
        chosen = tuple(indices)
    if len(chosen) > chain.robot.n_coordinates:
        names = ", ".join(ROW_NAMES[r] for r in chosen)
        n = chain.robot.n_coordinates
        raise ArgumentError(f"{chain.robot.name} has {n} coordinates, so {len(chosen)} rows ({names}) have "
                            f"det(J J^T) = 0 everywhere; choose at most {n} rows")
    return chosen


def _default_point(chain: Chain, point: Point | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    return point_vector(chain, end_point(chain) if point is None else point)


# --- numeric ---------------------------------------------------------------------------------------------------


class ManipulabilityGradient(NamedTuple):
    r"""The manipulability :math:`w` at one configuration and its gradient (unpacks as ``w, dw = ...``).

    Parameters
    ----------
    value : float
        :math:`w = \sqrt{\det(J J^T)}` of the chosen rows.
    gradient : numpy.ndarray, shape (n,)
        :math:`\partial w / \partial q`.
    """

    value: float
    gradient: np.ndarray


def _numeric_hessian(chain: Chain, q: np.ndarray, frame: Frame, point: tuple[sp.Expr, ...]) -> np.ndarray:
    """The (6, n, n) kinematic Hessian at ``q`` (parameters at their defaults), compiled once per frame and point."""
    n = chain.robot.n_coordinates
    return np.asarray(_compiled_hessian(chain, frame, point)(q), dtype=float).reshape(6, n, n)


@memoized(frame=frame_of, point=point_vector)
def _compiled_hessian(chain: Chain, frame: Frame, point: Point) -> Callable[..., Any]:
    """The raw Hessian, flattened to 6 x n^2, lambdified over q with the parameters at their defaults."""
    n = chain.robot.n_coordinates
    H = hessian(chain, frame, point, simplify=False)
    flat = sp.Matrix(6, n * n, list(H.reshape(6 * n * n))).xreplace(chain.robot.defaults)
    return sp.lambdify([list(chain.robot.q)], flat, modules="numpy", cse=True)


def manipulability_gradient(
    robot: Robot | Chain,
    q: Sequence[float],
    frame: Frame = 0,
    point: Point | None = None,
    rows: Rows | None = None,
    *,
    tolerance: float | None = None,
) -> ManipulabilityGradient:
    r"""The manipulability :math:`w = \sqrt{\det(J J^T)}` and its gradient :math:`w\,\operatorname{tr}(J^+ H_k)`.

    Parameters
    ----------
    robot : Robot or Chain
    q : sequence of float
        The configuration (parameters at their defaults).
    frame : int, "world" or "tool"
        The frame J is expressed in. It does not change w for all six rows, or whole linear or angular blocks;
        for other row subsets it does, and the gradient is that of the w of exactly ``jacobian(robot, frame,
        point)[rows, :]``.
    point : "wrist", "tool" or sequence of 3, optional
        As for :func:`symjac.kinematics.jacobian`; default the tool point if the robot has a tool, else the wrist (as
        for
        :func:`symjac.analysis.singularity.determinant.determinant`).
    rows : names or indices, optional
        Task rows (at most n); default :func:`symjac.analysis.spaces.task_rows` (all six for arms with six or more
        joints).
    tolerance : float, optional
        Singular values at or below it count as zero; default NumPy's rank rule
        :math:`\sigma_{max} \max(m, n)\,\varepsilon`.

    Returns
    -------
    ManipulabilityGradient
        ``(value, gradient)``, gradient of shape (n,).

    Raises
    ------
    ArgumentError
        For bad rows (unknown, repeated, more than n) or a bad ``q``, and at a singular configuration, where w is 0
        and has no gradient (module docstring).

    Examples
    --------
    >>> from symjac import load_robot
    >>> w, dw = manipulability_gradient(load_robot("planar2r"), [0.0, np.pi / 4])  # w = L1 L2 |s_2|
    >>> round(w, 6), dw.round(6).tolist()  # L1 = 0.5, L2 = 0.4: dw/dtheta2 = L1 L2 c_2
    (0.141421, [0.0, 0.141421])
    """
    chain = as_chain(robot)
    xyz = _default_point(chain, point)
    frame = chain.frame_name(chain.position(frame))
    chosen = list(_resolve_rows(chain, rows, xyz))
    J = numeric_jacobian(chain, q, frame, list(xyz))[chosen]  # validates q
    H = _numeric_hessian(chain, np.asarray(q, dtype=float), frame, xyz)[chosen]
    U, sigma, Vt = np.linalg.svd(J, full_matrices=False)
    limit = float(sigma.max(initial=0.0)) * max(J.shape) * np.finfo(float).eps if tolerance is None else tolerance
    if sigma.min() <= limit:
        raise ArgumentError(f"{chain.robot.name} at q = {list(map(float, q))} is singular on rows "
                            f"{', '.join(ROW_NAMES[r] for r in chosen)} (smallest singular value {sigma.min():.3g}): "
                            f"w = 0 and has no gradient there; step off the singularity")
    # w / sigma_i without dividing: the product of the other singular values
    others = np.array([np.prod(np.delete(sigma, i)) for i in range(sigma.size)])
    # sum_i others_i * u_i^T H_k v_i, for every joint k
    gradient = np.einsum("i,ai,abk,ib->k", others, U, H, Vt)
    return ManipulabilityGradient(float(np.prod(sigma)), gradient)


# --- closed form, square Jacobians -------------------------------------------------------------------------------


@dataclass(frozen=True)
class BarrierTerm:
    r"""One singular factor's share :math:`m\,\nabla f / f` of :math:`\nabla \log|\det J|`.

    Parameters
    ----------
    factor : sympy.Expr
        :math:`f`, a factor of the determinant (its singular condition is f = 0).
    multiplicity : int
        :math:`m`, its power in the determinant.
    gradient : sympy.ImmutableMatrix, shape (n, 1)
        :math:`m\,\partial f / \partial q_k \,/\, f` per joint variable: :math:`\cot u` for :math:`f = \sin u`,
        :math:`-\tan u` for :math:`f = \cos u` (times :math:`\partial u / \partial q_k`), a compact numerator over
        f otherwise.
    """

    factor: sp.Expr
    multiplicity: int
    gradient: sp.ImmutableMatrix


@dataclass(frozen=True)
class LogDetGradient:
    r""":math:`\nabla \log|\det J| = \sum_i m_i \nabla f_i / f_i` for a square Jacobian, term by term.

    Parameters
    ----------
    determinant : Determinant
        The factored determinant it comes from (rows, frame, point, factors).
    variables : tuple of sympy.Symbol
        The joint variables, the order of every gradient.
    terms : tuple of BarrierTerm
        One per factor that depends on the joint variables, in the determinant's order (constant factors, such
        as a link length, add nothing).
    total : sympy.ImmutableMatrix, shape (n, 1)
        The sum of the terms: :math:`\nabla \log w = \nabla w / w`.
    """

    determinant: Determinant
    variables: tuple[sp.Symbol, ...]
    terms: tuple[BarrierTerm, ...]
    total: sp.ImmutableMatrix

    def term(self, factor: sp.Expr | str) -> BarrierTerm:
        """The term of one factor, given as an expression or as it prints (``"sin(theta5)"``)."""
        for candidate in self.terms:
            if candidate.factor == factor or str(candidate.factor) == str(factor):
                return candidate
        known = ", ".join(str(t.factor) for t in self.terms)
        raise ArgumentError(f"{factor} is not a singular factor here; the factors are {known}")


def _barrier(factor: sp.Expr, multiplicity: int, variables: Sequence[sp.Symbol],
             layout: Callable[[sp.Matrix], sp.Matrix]) -> sp.ImmutableMatrix:
    if isinstance(factor, sp.sin | sp.cos):
        (u,) = factor.args
        ratio = sp.cot(u) if isinstance(factor, sp.sin) else -sp.tan(u)
        return sp.ImmutableMatrix([multiplicity * ratio * u.diff(v) for v in variables])
    numerators = layout(sp.Matrix([multiplicity * factor.diff(v) for v in variables]))
    return sp.ImmutableMatrix([sp.factor_terms(numerator) / factor for numerator in numerators])


@memoized(point=_default_point, rows=_resolve_rows)
def log_det_gradient(
    chain: Chain,
    rows: Rows | None = None,
    frame: Frame | None = None,
    point: Point | None = None,
) -> LogDetGradient:
    r"""The gradient of :math:`\log|\det J|` in closed form, one barrier term per singular factor.

    .. math:: \nabla \log|\det J| = \sum_i m_i \frac{\nabla f_i}{f_i}, \qquad \det J = c \prod_i f_i^{m_i}

    For a square J this is :math:`\nabla w / w` with :math:`w = |\det J|` the manipulability, so
    ``w * total`` is the numeric gradient of :func:`manipulability_gradient`.

    Parameters
    ----------
    robot : Robot or Chain
    rows, frame, point
        As for :func:`symjac.analysis.singularity.determinant.determinant` (whose memoized factorisation this reuses);
        rows may also be given by name. There must be as many rows as joints.

    Returns
    -------
    LogDetGradient

    Raises
    ------
    ArgumentError
        When the rows do not make a square Jacobian (a redundant arm, or a wrong number of rows): choose n rows,
        or use :func:`manipulability_gradient`, which works for any number of rows up to n.

    Examples
    --------
    >>> from symjac import load_robot
    >>> result = log_det_gradient(load_robot("planar2r"))  # det J = L1 L2 s_2
    >>> result.term("sin(theta2)").gradient.T
    Matrix([[0, cot(theta2)]])
    """
    chosen: tuple[int, ...] = rows  # type: ignore[assignment]  # normalised by @memoized, like point
    n = chain.robot.n_coordinates
    if len(chosen) != n:
        names = ", ".join(ROW_NAMES[r] for r in chosen)
        raise ArgumentError(f"{chain.robot.name}: log|det J| needs a square Jacobian, but rows {names} and "
                            f"{n} coordinates make it {len(chosen)} x {n}; choose {n} rows, or use "
                            f"manipulability_gradient (numeric, any number of rows up to {n})")
    det = determinant(chain, chosen, frame, point)
    if det.coefficient == 0:
        raise ArgumentError(f"the Jacobian of {chain.robot.name} on rows {', '.join(det.row_names)} is "
                            f"singular everywhere, so log|det J| has no gradient")
    variables = tuple(chain.robot.q)
    bases = chain.all_angle_bases()

    def layout(matrix: sp.Matrix) -> sp.Matrix:
        return simplify_matrix(matrix, bases)

    terms = tuple(BarrierTerm(factor, multiplicity, _barrier(factor, multiplicity, variables, layout))
                  for factor, multiplicity in det.factors if factor.free_symbols & set(variables))
    total = sp.zeros(len(variables), 1)
    for term in terms:
        total += term.gradient
    return LogDetGradient(det, variables, terms, sp.ImmutableMatrix(total))
