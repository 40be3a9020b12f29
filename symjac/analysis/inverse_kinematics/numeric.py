r"""Numeric inverse kinematics: Levenberg-Marquardt on a compiled forward kinematics and Jacobian.

The solver works on any object with ``fk(q)`` (a 4 x 4 pose of the tool point in the base frame) and
``jacobian(q)`` (6 x n, linear velocity of that point then angular velocity, both in the base frame), such as
:func:`symjac.codegen.numeric_model.numeric_model` of the robot with its default frame and point.

The error and its cost, with weights ``W = diag(w_p I, w_o I)``::

    e(q) = W [p* - p(q); log(R* R(q)^T)]        (log: the rotation vector of the remaining rotation, base frame)
    E(q) = e^T e

A step solves the damped normal equations with an error-dependent damping (Sugihara's Levenberg-Marquardt: the
damping shrinks with the error, so the last steps are Gauss-Newton steps and converge fast)::

    (J_W^T J_W + lambda I) dq = J_W^T e,    J_W = W J,    lambda = mu (E / 2 + 1e-3)

with ``mu`` halved after an accepted step (the cost fell) and multiplied by 4 after a rejected one. Once
``E < 1e-6`` the step ``v`` gains Transtrum and Sethna's geodesic acceleration, which follows the curved valleys of
the cost near a singular solution::

    f_vv = (2 / h) ((f(q + h v) - f(q)) / h - J v),  h = 0.1;    (J_W^T J_W + lambda I) a = -J_W^T f_vv
    dq = v + a / 2      (only when 2 |a| <= 0.75 |v|)

Each start descends without limits first (revolute joints without limits wrapped to (-pi, pi]); a solution it
reaches is shifted by 2 pi k into the limits (the same pose), and when a joint does not fit, the descent goes on from
the configuration clipped into them with the limits respected: joints clipped to them after each step, and a joint
that sits at a limit and whose step would push it past held still (the step solved again without it). That is for
redundant arms (more joints than weighted error components) only: an arm without self-motion has isolated
solutions, and one outside the limits has none inside them nearby, so the start is abandoned. A start that
stalls (the
cost has not fallen below 0.9 times its reference value for ``stall`` accepted or rejected steps while ``E > 1e-10``)
is abandoned early, and the solver restarts from a seed drawn uniformly within the limits (from ``rng``, as
TRAC-IK restarts, so the result is deterministic). The restarts also collect several distinct solutions; for
redundant arms a null-space task (:mod:`symjac.analysis.inverse_kinematics.null_space`) may then move each solution
away from the joint limits or towards more manipulability without changing the pose.

Two solutions are the same when every prismatic joint agrees and every revolute angle agrees modulo 2 pi, to
``max(1e-6, 10 sqrt(tolerance))`` (1e-4: where two solutions merge, at the edge of the workspace, each start stops
at its own side of the merged one, about ``sqrt(tolerance)`` away):
a joint whose limits span more than 2 pi is reported once, wrapped to (-pi, pi] and shifted by 2 pi into its limits
where that fits, never as several aliases. Each solution says whether it is isolated or one sample of a continuum
(``continuum_dimension``, :func:`~symjac.analysis.inverse_kinematics.null_space.self_motion_dimension`): a redundant
arm's self-motion, or a singular pose's (a wrist with its middle joint at 0). The solutions found on a continuum are
samples of it, as many as the starts happened to land on, not a count of distinct solutions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import sympy

from symjac.analysis.inverse_kinematics.null_space import (
    NULL_SPACE_TASKS,
    refine_in_null_space,
    self_motion_dimension,
)
from symjac.errors import ArgumentError
from symjac.model.robot import Robot

__all__ = ["KinematicModel", "NumericSolution", "NumericSolutions", "seed_bounds", "solve_numeric"]


class KinematicModel(Protocol):
    """What the solver needs: the tool pose and the base-frame Jacobian at that point."""

    def fk(self, q: Any) -> Any:
        """The 4 x 4 pose of the tool point in the base frame at ``q``."""

    def jacobian(self, q: Any) -> Any:
        """The 6 x n Jacobian at ``q``: linear velocity of the tool point, then angular velocity, base frame."""


@dataclass(frozen=True)
class NumericSolution:
    """One converged configuration with its final error norms, the iterations it took and which start found it.

    ``continuum_dimension`` is 0 for an isolated solution, else the dimension ``d`` of the set of configurations
    around ``q`` that reach the same pose (``n - rank J`` at ``q``, :func:`.self_motion_dimension`): ``q`` is then
    one sample of a ``d``-dimensional self-motion.
    """

    q: np.ndarray
    position_error: float
    orientation_error: float
    iterations: int
    start: int = 0
    continuum_dimension: int = 0


class NumericSolutions(list[NumericSolution]):
    """The solutions :func:`solve_numeric` found (a list), and ``closest`` when none converged.

    ``closest`` is the configuration closest to the pose that the search reached (within the limits when they are
    respected), with its unweighted position (m) and orientation (rad) errors; None when there are solutions. A
    search that found nothing proves nothing: the pose is probably, not certainly, out of reach.
    """

    closest: NumericSolution | None = None

    @property
    def continuum_dimension(self) -> int:
        """The largest ``continuum_dimension`` of the solutions: 0 when each is isolated (or there are none).

        When it is not 0, the solutions on a continuum are samples of it, not a count of distinct solutions.
        """
        return max((s.continuum_dimension for s in self), default=0)


def _rotation_vector(r: np.ndarray) -> np.ndarray:
    """The axis times angle of the rotation matrix ``r`` (robust near 0 and pi)."""
    cos = min(1.0, max(-1.0, (np.trace(r) - 1.0) / 2.0))
    skew = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    angle = float(np.arccos(cos))
    if angle < 1e-6:
        return skew / 2.0
    if np.pi - angle > 1e-4:
        return skew * (angle / (2.0 * np.sin(angle)))
    b = (r + np.eye(3)) / 2.0  # near pi: the axis from the symmetric part
    axis = b[int(np.argmax(np.diag(b)))]
    axis = axis / np.linalg.norm(axis)
    if axis @ skew < 0:
        axis = -axis
    return axis * angle


def _pose(pose: Any) -> np.ndarray:
    try:
        t = np.asarray(pose, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ArgumentError(f"solve_numeric: the pose is not a numeric 4 x 4 matrix ({exc})") from None
    if t.shape != (4, 4):
        raise ArgumentError(f"solve_numeric: the pose must be 4 x 4, got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        raise ArgumentError("solve_numeric: the pose contains NaN or infinite entries")
    r = t[:3, :3]
    if (not np.allclose(t[3], [0, 0, 0, 1], atol=1e-9) or not np.allclose(r @ r.T, np.eye(3), atol=1e-6)
            or np.linalg.det(r) < 0):
        raise ArgumentError("solve_numeric: the pose is not a rigid transform (rotation block not orthonormal "
                            "with determinant +1, or last row not [0, 0, 0, 1])")
    return t


def _float(value: Any, robot: Robot) -> float:
    expr = sympy.sympify(value)
    return float(expr.subs(robot.defaults) if expr.free_symbols else expr)


def _limits(robot: Robot) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lower and upper bounds per joint (-inf/inf when free) and which joints wrap (revolute without limits)."""
    lower, upper, wrap = [], [], []
    for joint in robot.joints:
        limits = None if joint.continuous else joint.limits
        if limits is None:
            lower.append(-np.inf)
            upper.append(np.inf)
            wrap.append(bool(joint.is_revolute))
        else:
            lower.append(_float(limits[0], robot))
            upper.append(_float(limits[1], robot))
            wrap.append(False)
    return np.array(lower), np.array(upper), np.array(wrap)


def seed_bounds(robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    """Where seeds are drawn: the joint limits, +-pi for free revolute joints, +-1 for free prismatic ones."""
    lower, upper, wrap = _limits(robot)
    return (np.where(np.isfinite(lower), lower, np.where(wrap, -np.pi, -1.0)),
            np.where(np.isfinite(upper), upper, np.where(wrap, np.pi, 1.0)))




def solve_numeric(robot: Robot, pose: Any, model: KinematicModel, *, seed: Any = None, rng: int = 0,
                  restarts: int = 8, position_weight: float = 1.0, orientation_weight: float = 1.0,
                  tolerance: float = 1e-10, max_iterations: int = 100, respect_limits: bool = True,
                  until_found: int = 64, stall: int = 4, null_space: str | None = None) -> NumericSolutions:
    r"""Configurations of ``robot`` whose tool reaches ``pose`` (4 x 4), found by Levenberg-Marquardt.

    ``model`` gives ``fk`` and ``jacobian`` (base frame, at the tool point), for example
    ``numeric_model(robot)``. The first start is ``seed`` when given, then ``restarts`` seeds drawn within the
    limits (+-pi for free revolute joints, +-1 for free prismatic ones) from ``numpy.random.default_rng(rng)``.
    When none of these converges, further seeds are drawn until one does or ``until_found`` starts in all
    have been tried: ``restarts=1`` is one call from one random seed that returns the first solution it finds.
    A start converges when both the weighted (``w_p``, ``w_o``) position and orientation error norms fall below
    ``tolerance``; it is abandoned after ``max_iterations`` steps or when it stalls (``stall`` steps without the
    cost falling by 10 %). Solutions closer than ``max(1e-6, 10 sqrt(tolerance))`` (rad or m; revolute
    angles compared modulo 2 pi) to an earlier one are dropped; each says whether it is one sample of a continuum
    (``continuum_dimension``). ``null_space``
    ("limits" or "manipulability", arms with more than six joints) moves each solution along the self-motion to
    that secondary task's optimum (:func:`~symjac.analysis.inverse_kinematics.null_space.refine_in_null_space`).
    An unreachable pose gives an empty list whose ``closest`` (:class:`NumericSolutions`) is the configuration
    with the smallest cost reached over all starts, polished by one more descent within the limits (without the
    early stop).
    """
    target = _pose(pose)
    n = len(robot.joints)
    if null_space is not None and null_space not in NULL_SPACE_TASKS:
        raise ArgumentError(f"solve_numeric: null_space must be one of {', '.join(NULL_SPACE_TASKS)} or None, "
                            f"got {null_space!r}")
    lower, upper, wrap = limits = _limits(robot)
    low, high = seed_bounds(robot)  # seeds within the limits also when they are not respected
    if not respect_limits:
        lower, upper = np.full(n, -np.inf), np.full(n, np.inf)
    generator = np.random.default_rng(rng)
    starts = [] if seed is None else [np.asarray(seed, dtype=float).reshape(n)]
    primary = len(starts) + restarts
    weights = np.array([position_weight] * 3 + [orientation_weight] * 3)

    def error(q: np.ndarray) -> np.ndarray:
        t = np.asarray(model.fk(q), dtype=float)
        return weights * np.concatenate([target[:3, 3] - t[:3, 3], _rotation_vector(target[:3, :3] @ t[:3, :3].T)])

    def jacobian(q: np.ndarray) -> np.ndarray:
        return weights[:, None] * np.asarray(model.jacobian(q), dtype=float)

    def project(q: np.ndarray) -> np.ndarray:
        return np.where(wrap, _wrapped(q), np.clip(q, lower, upper))

    def converged(e: np.ndarray) -> bool:
        return max(float(np.linalg.norm(e[:3])), float(np.linalg.norm(e[3:]))) <= tolerance

    revolute = np.array([bool(joint.is_revolute) for joint in robot.joints])
    unbounded = np.full(n, np.inf)

    def free(q: np.ndarray) -> np.ndarray:
        return np.where(wrap, _wrapped(q), q)

    redundant = n > 3 * ((position_weight != 0) + (orientation_weight != 0))
    same = max(1e-6, 10.0 * float(np.sqrt(tolerance)))  # closer solutions are one
    found = NumericSolutions()
    nearest: tuple[float, np.ndarray, int, int] | None = None  # cost, clipped configuration, steps, start
    for index in range(max(primary, until_found)):
        if found and index >= primary:
            break
        start = starts[index] if index < len(starts) else generator.uniform(low, high)
        q, e, iterations = _descend(free(start), error, jacobian, free, converged, -unbounded, unbounded,
                                    max_iterations, stall)
        if converged(e):
            q, inside = _into_limits(q, lower, upper, revolute)
            if not inside and not redundant:  # isolated solutions (no self-motion to clip along): restart
                e = np.full(6, np.inf)
            elif not inside:  # a solution outside the limits: go on from it clipped into them, the limits respected
                q, e, more = _descend(project(q), error, jacobian, project, converged, lower, upper,
                                      max_iterations, stall)
                iterations += more
        if not converged(e):
            clipped = _into_limits(q, lower, upper, revolute)[0]
            cost = float(np.sum(error(clipped) ** 2))
            if nearest is None or cost < nearest[0]:
                nearest = (cost, clipped, iterations, index)
            continue
        if null_space is not None and n > 6:
            q = refine_in_null_space(q, null_space, error, jacobian, project, converged, lower, upper)
        q = _canonical(q, limits[0], limits[1], revolute)
        e = error(q)
        if converged(e) and all(np.max(np.abs(_difference(q, s.q, revolute))) > same for s in found):
            found.append(NumericSolution(q, float(np.linalg.norm(e[:3])), float(np.linalg.norm(e[3:])), iterations,
                                         index, self_motion_dimension(q, error, jacobian, converged)))
    if not found and nearest is not None:
        q, e, more = _descend(nearest[1], error, jacobian, project, converged, lower, upper, max_iterations,
                              max_iterations)  # no early stop: as close as it gets
        if converged(e):  # the closest configuration's descent within the limits reached the pose after all
            q = _canonical(q, limits[0], limits[1], revolute)
            found.append(NumericSolution(q, float(np.linalg.norm(e[:3])), float(np.linalg.norm(e[3:])),
                                         nearest[2] + more, nearest[3],
                                         self_motion_dimension(q, error, jacobian, converged)))
            return found
        if float(e @ e) > nearest[0]:
            q = nearest[1]
        t = np.asarray(model.fk(q), dtype=float)
        found.closest = NumericSolution(
            q, float(np.linalg.norm(target[:3, 3] - t[:3, 3])),
            float(np.linalg.norm(_rotation_vector(target[:3, :3] @ t[:3, :3].T))), nearest[2] + more, nearest[3])
    return found


def _descend(q: np.ndarray, error: Any, jacobian: Any, project: Any, converged: Any, lower: np.ndarray,
             upper: np.ndarray, max_iterations: int, stall: int) -> tuple[np.ndarray, np.ndarray, int]:
    """One start of Levenberg-Marquardt with Sugihara's damping: the configuration, its error and the steps taken."""
    e = error(q)
    cost = reference = float(e @ e)
    mu, stalled = 1.0, 0
    for iteration in range(max_iterations):
        if converged(e):
            return q, e, iteration
        j, damping = jacobian(q), mu * (0.5 * cost + 1e-3)
        step, free = _step(j, e, damping, q, lower, upper)
        if cost < 1e-6:  # the end-game: geodesic acceleration, for the curved valleys near a singular solution
            curvature = -20.0 * ((error(q + 0.1 * step) - e) / 0.1 + j @ step)  # f_vv, step h = 0.1
            jf, acceleration = j[:, free], np.zeros(len(q))
            acceleration[free] = np.linalg.solve(jf.T @ jf + damping * np.eye(int(free.sum())), -jf.T @ curvature)
            if 2.0 * np.linalg.norm(acceleration) <= 0.75 * np.linalg.norm(step):
                step = step + acceleration / 2.0
        trial = project(q + step)
        e_trial = error(trial)
        c_trial = float(e_trial @ e_trial)
        if c_trial < cost:
            q, e, cost, mu = trial, e_trial, c_trial, max(mu / 2.0, 1e-6)
        else:
            mu *= 4.0
        if cost < 0.9 * reference or cost < 1e-10:  # near a solution slow progress is no stall
            reference, stalled = cost, 0
        else:
            stalled += 1
            if stalled >= stall:
                return q, e, iteration + 1
    return q, e, max_iterations


def _wrapped(q: Any) -> Any:
    """Angles wrapped to (-pi, pi], those already in it unchanged (no rounding)."""
    return np.where((q > np.pi) | (q <= -np.pi), np.pi - np.mod(np.pi - q, 2 * np.pi), q)


def _into_limits(q: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                 revolute: np.ndarray) -> tuple[np.ndarray, bool]:
    """``q`` with each angle wrapped and shifted by 2 pi k into its limits, and whether every joint fitted.

    A shift changes no pose; an angle no shift fits is clipped to its limits.
    """
    out, inside = q.copy(), True
    for i in range(len(q)):
        value = float(_wrapped(q[i])) if revolute[i] else q[i]
        shifts = (0.0, 2 * np.pi, -2 * np.pi, 4 * np.pi, -4 * np.pi) if revolute[i] else (0.0,)
        fits = [value + shift for shift in shifts if lower[i] <= value + shift <= upper[i]]
        inside &= bool(fits)
        out[i] = fits[0] if fits else min(max(value, lower[i]), upper[i])
    return out, inside


def _step(j: np.ndarray, e: np.ndarray, damping: float, q: np.ndarray, lower: np.ndarray,
          upper: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The damped least-squares step and which joints are free: those at a limit it would push past are held still."""
    free = np.ones(len(q), dtype=bool)
    step = np.zeros(len(q))
    for _ in range(len(q)):
        step = np.zeros(len(q))
        jf = j[:, free]
        step[free] = np.linalg.solve(jf.T @ jf + damping * np.eye(int(free.sum())), jf.T @ e)
        blocked = free & (((q <= lower) & (step < 0)) | ((q >= upper) & (step > 0)))
        if not blocked.any():
            return step, free
        free &= ~blocked
    return step, free


def _canonical(q: np.ndarray, lower: np.ndarray, upper: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Each angle wrapped to (-pi, pi], then shifted by 2 pi k into the joint's limits where that fits (else left)."""
    out = q.copy()
    for i in np.flatnonzero(revolute):
        value = float(_wrapped(q[i]))
        fits = [value + shift for shift in (0.0, 2 * np.pi, -2 * np.pi, 4 * np.pi, -4 * np.pi)
                if lower[i] <= value + shift <= upper[i]]
        canonical = fits[0] if fits else value
        out[i] = q[i] if abs(canonical - q[i]) <= 1e-12 else canonical  # no rounding of an angle already in place
    return out


def _difference(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """``a - b``, revolute entries wrapped to (-pi, pi] (angles equal modulo 2 pi differ by 0)."""
    d = a - b
    return np.where(revolute, np.pi - np.mod(np.pi - d, 2 * np.pi), d)
