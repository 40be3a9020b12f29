r"""A secondary task for redundant arms, moved along the self-motion so the pose stays where it is.

A solution ``q`` of a redundant arm (n > 6 joints) lies on a manifold of configurations with the same pose. The
gradient projection method climbs a secondary objective ``h(q)`` along it: with the (weighted) Jacobian ``J`` and its
pseudo-inverse ``J^+``, the step::

    dq = alpha (I - J^+ J) grad h(q)

moves no point of the tool to first order (``J dq = 0``, since ``J J^+ J = J``). The second-order drift is taken
back by Gauss-Newton corrections ``q <- q + J^+ e(q)`` until the pose error is within the tolerance again; a step
is kept only when it both restores the pose and increases ``h``, else ``alpha`` is halved. Nothing is random, so the
result is deterministic. The objectives (:data:`NULL_SPACE_TASKS`):

- ``"limits"``: the distance from the joint limits, ``h(q) = -sum_i ((q_i - c_i) / (u_i - l_i))^2`` over the joints
  with limits ``[l_i, u_i]`` (``c_i`` the middle of the range), ``dh/dq_i = -2 (q_i - c_i) / (u_i - l_i)^2``;
- ``"manipulability"``: Yoshikawa's ``w(q) = sqrt(det(J J^T))``, its gradient by central differences (step 1e-6).

:func:`self_motion_dimension` says whether a solution is one of a continuum at all, and of what dimension: that of
a redundant arm (``n - m`` for ``m`` controlled pose components, where the Jacobian has full rank ``m``), or of any
arm at a singular pose where a continuum opens up (a spherical wrist with its middle joint at 0: ``theta4 +
theta6`` fixed, one dimension). Where the Jacobian loses rank, rank alone decides nothing (at the edge of the
workspace two solutions merge into one isolated one and the rank drops too), so each direction in which the
Jacobian is (nearly) singular is tried: a step of ``h = 1e-3`` along it both ways, pulled back onto the pose by
Gauss-Newton, must stay at least ``h / 2`` from the solution for the direction to count.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["NULL_SPACE_TASKS", "limit_distance", "manipulability", "refine_in_null_space", "self_motion_dimension"]

NULL_SPACE_TASKS = ("limits", "manipulability")
"""The secondary objectives :func:`refine_in_null_space` climbs."""

Vector = Callable[[np.ndarray], np.ndarray]


def limit_distance(q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> float:
    """``-sum ((q_i - c_i) / (u_i - l_i))^2`` over the joints with finite limits: 0 at the middle, larger is better."""
    finite = np.isfinite(lower) & np.isfinite(upper)
    middle, span = (lower + upper) / 2.0, upper - lower
    return -float(np.sum(((q[finite] - middle[finite]) / span[finite]) ** 2))


def manipulability(j: np.ndarray) -> float:
    """Yoshikawa's ``sqrt(det(J J^T))`` of a wide (or square) Jacobian."""
    return float(np.sqrt(max(0.0, float(np.linalg.det(j @ j.T)))))


def refine_in_null_space(q: np.ndarray, task: str, error: Vector, jacobian: Vector, project: Vector,
                         converged: Callable[[np.ndarray], bool], lower: np.ndarray, upper: np.ndarray, *,
                         iterations: int = 40, largest_step: float = 0.2) -> np.ndarray:
    """Climb ``task`` (one of :data:`NULL_SPACE_TASKS`) from the solution ``q`` along its self-motion.

    ``error`` and ``jacobian`` are the solver's weighted pose error and Jacobian, ``project`` its map into the
    limits, ``converged`` its test of an error. At most ``iterations`` projected gradient steps, each at most
    ``largest_step`` (rad or m) in any joint; returns a configuration that still satisfies ``converged`` and whose
    objective is at least that of ``q``.
    """
    if task == "limits":
        def objective(x: np.ndarray) -> float:
            return limit_distance(x, lower, upper)

        def gradient(x: np.ndarray) -> np.ndarray:
            finite = np.isfinite(lower) & np.isfinite(upper)
            g = np.zeros(len(x))
            g[finite] = -2.0 * (x[finite] - (lower[finite] + upper[finite]) / 2.0) / (upper - lower)[finite] ** 2
            return g
    else:
        def objective(x: np.ndarray) -> float:
            return manipulability(jacobian(x))

        def gradient(x: np.ndarray) -> np.ndarray:
            unit = np.eye(len(x)) * 1e-6
            return np.array([(objective(x + u) - objective(x - u)) / 2e-6 for u in unit])

    value = objective(q)
    for _ in range(iterations):
        j = jacobian(q)
        direction = (np.eye(len(q)) - np.linalg.pinv(j) @ j) @ gradient(q)
        size = float(np.max(np.abs(direction)))
        if size < 1e-9:
            break
        alpha = min(1.0, largest_step / size)
        while alpha * size > 1e-7:
            trial = _restore(project(q + alpha * direction), error, jacobian, project, converged)
            if trial is not None and objective(trial) > value + 1e-12:
                q, value = trial, objective(trial)
                break
            alpha /= 2.0
        else:
            break
    return q


def self_motion_dimension(q: np.ndarray, error: Vector, jacobian: Vector, converged: Callable[[np.ndarray], bool],
                          *, singular: float = 1e-3, step: float = 1e-3) -> int:
    """The dimension of the set of configurations reaching the same pose around the solution ``q`` (0: isolated).

    ``error``, ``jacobian`` and ``converged`` are the solver's (weighted; rows of weight 0 do not count). Where the
    Jacobian has full row rank ``m`` (no singular value below ``singular`` times the largest), the set is a manifold
    of dimension ``n - m`` (the implicit function theorem). Where it has not (or a row vanishes: it may vanish
    here only), each direction of its null space and each with a singular value below that is tried: ``q +- step``
    along it, pulled back onto the pose by at most 8 Gauss-Newton steps, must reach the pose again at least
    ``step / 2`` from ``q`` both ways.
    """
    full = np.asarray(jacobian(q), dtype=float)
    j = full[np.any(full != 0.0, axis=1)]  # the controlled rows (and any that vanish here)
    n, rows = j.shape[1], j.shape[0]
    if rows == 0:
        return n
    _, values, directions = np.linalg.svd(j)
    weak = [k for k, value in enumerate(values) if value <= singular * max(values[0], 1e-300)]
    if not weak and rows == len(full):  # full row rank: the implicit function theorem
        return max(n - rows, 0)
    candidates = [*weak, *range(len(values), n)]
    return sum(all(_moved(q + sign * step * directions[k], error, jacobian, converged, q, step / 2.0)
                   for sign in (1.0, -1.0)) for k in candidates)


def _moved(q: np.ndarray, error: Vector, jacobian: Vector, converged: Callable[[np.ndarray], bool],
           origin: np.ndarray, distance: float) -> bool:
    """Whether Gauss-Newton from ``q`` reaches the pose at least ``distance`` from ``origin``."""
    back = _restore(q, error, jacobian, lambda x: x, converged, rcond=1e-8)
    return back is not None and float(np.linalg.norm(back - origin)) >= distance


def _restore(q: np.ndarray, error: Vector, jacobian: Vector, project: Vector,
             converged: Callable[[np.ndarray], bool], rcond: float = 1e-15) -> np.ndarray | None:
    """Gauss-Newton corrections ``q <- q + J^+ e`` back onto the pose (at most 8), or None when they fail."""
    for _ in range(8):
        e = error(q)
        if converged(e):
            return q
        q = project(q + np.linalg.pinv(jacobian(q), rcond=rcond) @ e)
    return q if converged(error(q)) else None
