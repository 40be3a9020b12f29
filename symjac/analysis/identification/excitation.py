r"""Exciting trajectories for identification: finite Fourier series per joint and their condition number.

Joint j follows a finite Fourier series of L harmonics of the base pulsation :math:`\omega_f` (Swevers, Ganseman,
Tükel, De Schutter and Van Brussel, 1997), periodic with period :math:`2\pi/\omega_f`:

.. math::
    q_j(t) &= q_{0,j} + \sum_{l=1}^{L} \frac{a_{jl}}{\omega_f l} \sin(\omega_f l t)
                                 - \frac{b_{jl}}{\omega_f l} \cos(\omega_f l t), \\
    \dot q_j(t) &= \sum_{l=1}^{L} a_{jl} \cos(\omega_f l t) + b_{jl} \sin(\omega_f l t), \\
    \ddot q_j(t) &= \sum_{l=1}^{L} -a_{jl} \omega_f l \sin(\omega_f l t) + b_{jl} \omega_f l \cos(\omega_f l t).

The coefficients are an array of shape (n, 2, L): ``coefficients[j, 0, l - 1]`` is :math:`a_{jl}`,
``coefficients[j, 1, l - 1]`` is :math:`b_{jl}`. The trajectory is linear in them and in :math:`q_0`, so limits on
positions, rates and accelerations at the sample times are linear constraints. The quality of a trajectory is the
condition number of the base regressor stacked along it (:func:`excitation_condition`); :func:`optimise_excitation`
lowers it with SciPy's SLSQP (SciPy is optional: ``pip install 'symjac[identification]'``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from symjac.analysis.identification.workflow import stack
from symjac.errors import ArgumentError

__all__ = ["Excitation", "excitation_condition", "fourier_basis", "fourier_trajectory", "optimise_excitation"]


def _coefficients(coefficients: ArrayLike) -> np.ndarray:
    array = np.asarray(coefficients, dtype=float)
    if array.ndim != 3 or array.shape[1] != 2 or array.shape[0] == 0 or array.shape[2] == 0:
        raise ArgumentError(
            f"Fourier coefficients must have shape (joints, 2, harmonics), got {np.shape(coefficients)}")
    return array


def fourier_basis(harmonics: int, base_frequency: float, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""The series' basis at the sample times: position, rate and acceleration, each of shape (N, 2 L).

    With ``c = coefficients.reshape(n, 2 L)`` (all :math:`a_{jl}`, then all :math:`b_{jl}`), the trajectory is
    ``q = q0 + B_q @ c.T``, ``qdot = B_qd @ c.T``, ``qddot = B_qdd @ c.T``: linear in the coefficients.

    Parameters
    ----------
    harmonics : int
        L, the number of harmonics.
    base_frequency : float
        :math:`\omega_f` in rad/s (the period is :math:`2\pi/\omega_f`).
    t : array_like, shape (N,)
        Sample times in s.

    Returns
    -------
    tuple of numpy.ndarray, each of shape (N, 2 L)
        ``B_q``, ``B_qd``, ``B_qdd``.
    """
    if harmonics < 1:
        raise ArgumentError(f"a Fourier series needs at least one harmonic, got {harmonics}")
    if not np.isfinite(base_frequency) or base_frequency <= 0:
        raise ArgumentError(f"the base frequency must be positive (rad/s), got {base_frequency}")
    times = np.asarray(t, dtype=float).reshape(-1)
    pulsations = base_frequency * np.arange(1, harmonics + 1)
    angle = times[:, np.newaxis] * pulsations
    sin, cos = np.sin(angle), np.cos(angle)
    return (np.hstack([sin / pulsations, -cos / pulsations]), np.hstack([cos, sin]),
            np.hstack([-sin * pulsations, cos * pulsations]))


def fourier_trajectory(
    coefficients: ArrayLike, base_frequency: float, q0: ArrayLike, t: ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""Positions, rates and accelerations of a finite Fourier series per joint (Swevers' form).

    .. math:: q_j(t) = q_{0,j} + \sum_{l=1}^{L} \frac{a_{jl}}{\omega_f l}\sin(\omega_f l t)
                       - \frac{b_{jl}}{\omega_f l}\cos(\omega_f l t)

    Parameters
    ----------
    coefficients : array_like, shape (n, 2, L)
        :math:`a_{jl}` in ``[j, 0, l - 1]`` and :math:`b_{jl}` in ``[j, 1, l - 1]`` (rad/s or m/s).
    base_frequency : float
        :math:`\omega_f` in rad/s.
    q0 : array_like, shape (n,)
        The offsets :math:`q_{0,j}`.
    t : array_like, shape (N,)
        Sample times in s.

    Returns
    -------
    tuple of numpy.ndarray, each of shape (N, n)
        q, qdot, qddot.

    Examples
    --------
    >>> q, qd, qdd = fourier_trajectory([[[1.0], [0.0]]], 2.0, [0.1], [0.0])
    >>> float(q[0, 0]), float(qd[0, 0]), float(qdd[0, 0])
    (0.1, 1.0, 0.0)
    """
    array = _coefficients(coefficients)
    joints, _, harmonics = array.shape
    offsets = np.asarray(q0, dtype=float).reshape(-1)
    if offsets.shape[0] != joints:
        raise ArgumentError(f"q0 must have one entry per joint ({joints}), got {offsets.shape[0]}")
    flat = array.reshape(joints, 2 * harmonics)
    B_q, B_qd, B_qdd = fourier_basis(harmonics, base_frequency, t)
    return offsets + B_q @ flat.T, B_qd @ flat.T, B_qdd @ flat.T


def excitation_condition(
    base_regressor_function: Callable[..., Any],
    coefficients: ArrayLike,
    base_frequency: float,
    q0: ArrayLike,
    t: ArrayLike,
    *,
    parameters: Mapping[str, float] | None = None,
) -> float:
    r"""The condition number of the base regressor stacked along a Fourier trajectory.

    .. math:: \kappa = \sigma_{\max}(W_s) / \sigma_{\min}(W_s), \quad
              W_s = [Y_b(q(t_k), \dot q(t_k), \ddot q(t_k))]_{k=1..N}

    Parameters
    ----------
    base_regressor_function : callable
        ``f(q, qdot, qddot, **parameters)``, as :func:`~symjac.analysis.identification.workflow.stack` takes it.
    coefficients, base_frequency, q0, t
        The trajectory, as :func:`fourier_trajectory` takes it.
    parameters : mapping, optional
        Keyword arguments for every call of the regressor function.

    Returns
    -------
    float
        :math:`\kappa \ge 1`; infinite when the trajectory leaves a parameter unexcited.
    """
    q, qdot, qddot = fourier_trajectory(coefficients, base_frequency, q0, t)
    singular = np.linalg.svd(stack(base_regressor_function, q, qdot, qddot, parameters=parameters), compute_uv=False)
    return float(singular[0] / singular[-1]) if singular[-1] > 0 else float("inf")


@dataclass(frozen=True)
class Excitation:
    r"""The result of :func:`optimise_excitation`: the optimised trajectory and its condition numbers.

    ``coefficients`` are the Fourier coefficients (n x 2 x L), ``q0`` the offsets (optimised unless they were given),
    ``base_frequency`` :math:`\omega_f` in rad/s; ``condition_number`` is the stacked regressor's along the optimised
    trajectory at the sample times and ``initial_condition_number`` the same at the start; ``success`` and
    ``message`` are SciPy's.
    """

    coefficients: np.ndarray
    q0: np.ndarray
    base_frequency: float
    condition_number: float
    initial_condition_number: float
    success: bool
    message: str

    def trajectory(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, rates and accelerations at the times ``t`` (:func:`fourier_trajectory`)."""
        return fourier_trajectory(self.coefficients, self.base_frequency, self.q0, t)


def _limits(name: str, value: ArrayLike | None, joints: int, default: float) -> np.ndarray:
    if value is None:
        return np.full(joints, default)
    array = np.broadcast_to(np.asarray(value, dtype=float), (joints,)).copy()
    if np.any(np.isnan(array)):
        raise ArgumentError(f"{name} must be numbers (inf for no limit)")
    return array


def optimise_excitation(
    base_regressor_function: Callable[..., Any],
    joints: int,
    harmonics: int,
    base_frequency: float,
    t: ArrayLike,
    *,
    q0: ArrayLike | None = None,
    lower: ArrayLike | None = None,
    upper: ArrayLike | None = None,
    velocity_limit: ArrayLike | None = None,
    acceleration_limit: ArrayLike | None = None,
    initial: ArrayLike | None = None,
    seed: int = 0,
    max_iterations: int = 100,
    parameters: Mapping[str, float] | None = None,
) -> Excitation:
    r"""Fourier coefficients (and offsets) that lower the condition number of the stacked base regressor.

    Minimises :math:`\log\kappa(W_s)` over the coefficients (and :math:`q_0` unless given) with SciPy's SLSQP,
    subject to ``lower <= q(t_k) <= upper``, :math:`|\dot q(t_k)| \le` ``velocity_limit`` and
    :math:`|\ddot q(t_k)| \le` ``acceleration_limit`` at the sample times (linear constraints, exact gradients).

    Parameters
    ----------
    base_regressor_function : callable
        ``f(q, qdot, qddot, **parameters)``, best a vectorised one (a generated ``numpy`` module's).
    joints, harmonics : int
        n and L.
    base_frequency : float
        :math:`\omega_f` in rad/s.
    t : array_like, shape (N,)
        The sample times the condition number and the limits are evaluated at.
    q0 : array_like, shape (n,), optional
        Fixed offsets; by default optimised, starting midway between the limits (0 where there are none).
    lower, upper, velocity_limit, acceleration_limit : array_like, shape (n,) or scalar, optional
        Limits per joint (none by default; positions are then kept within :math:`\pm\pi` of the offsets).
    initial : array_like, shape (n, 2, L), optional
        Starting coefficients; by default random (``seed``) and scaled inside the limits.
    seed : int
        Seed of the random start.
    max_iterations : int
        SLSQP's iteration limit.
    parameters : mapping, optional
        Keyword arguments for every call of the regressor function.

    Returns
    -------
    Excitation
        The coefficients, offsets and condition numbers before and after.

    Raises
    ------
    ImportError
        When SciPy is not installed.
    """
    try:
        from scipy.optimize import minimize
    except ImportError as error:  # an optional extra: everything else in identification is NumPy only
        raise ImportError("optimise_excitation needs SciPy: pip install 'symjac[identification]' (or scipy); "
                          "excitation_condition works without it") from error
    B_q, B_qd, B_qdd = fourier_basis(harmonics, base_frequency, t)
    width = 2 * harmonics
    low, high = _limits("lower", lower, joints, -np.inf), _limits("upper", upper, joints, np.inf)
    if np.any(low >= high):
        raise ArgumentError("every lower limit must be below its upper limit")
    fixed = q0 is not None
    middle = np.where(np.isfinite(low) & np.isfinite(high), (low + high) / 2, np.where(np.isfinite(low), low + 1.0,
                      np.where(np.isfinite(high), high - 1.0, 0.0)))
    offsets = np.asarray(q0, dtype=float).reshape(joints) if fixed else middle
    low = np.where(np.isfinite(low), low, offsets - np.pi)
    high = np.where(np.isfinite(high), high, offsets + np.pi)
    speed = _limits("velocity_limit", velocity_limit, joints, np.inf)
    acceleration = _limits("acceleration_limit", acceleration_limit, joints, np.inf)

    def unpack(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        coefficients = x[: joints * width].reshape(joints, 2, harmonics)
        return coefficients, (offsets if fixed else x[joints * width:])

    # Every constraint row is a_row . x + c_row >= 0 (one per joint, sample and bound), built once.
    blocks, constants = [], []
    size = joints * width + (0 if fixed else joints)
    for j in range(joints):
        for basis, bound_low, bound_high, offset_term in ((B_q, low[j], high[j], True), (B_qd, -speed[j], speed[j],
                                                          False), (B_qdd, -acceleration[j], acceleration[j], False)):
            for sign, bound in ((1.0, bound_low), (-1.0, bound_high)):
                if not np.isfinite(bound):
                    continue
                rows = np.zeros((basis.shape[0], size))
                rows[:, j * width:(j + 1) * width] = sign * basis
                constant = np.full(basis.shape[0], -sign * bound)
                if offset_term:
                    if fixed:
                        constant += sign * offsets[j]
                    else:
                        rows[:, joints * width + j] = sign
                blocks.append(rows)
                constants.append(constant)
    A, c = np.vstack(blocks), np.concatenate(constants)

    if initial is None:
        start = np.random.default_rng(seed).standard_normal((joints, 2, harmonics))
    else:
        start = _coefficients(initial).copy()
    x0 = np.concatenate([start.reshape(-1), [] if fixed else offsets])
    slack = A @ x0 + c
    if np.any(slack < 0):  # shrink the coefficients towards the offsets (feasible there) until every limit holds
        homogeneous = A[:, : joints * width] @ x0[: joints * width]
        margin = -(c + A[:, joints * width:] @ x0[joints * width:]) if not fixed else -c
        ratios = np.where(homogeneous < 0, margin / np.minimum(homogeneous, -1e-300), np.inf)
        x0[: joints * width] *= 0.9 * max(min(1.0, float(np.min(ratios))), 0.0)

    def objective(x: np.ndarray) -> float:
        coefficients, offs = unpack(x)
        kappa = excitation_condition(base_regressor_function, coefficients, base_frequency, offs, t,
                                     parameters=parameters)
        return float(np.log(kappa)) if np.isfinite(kappa) else 1e3

    initial_kappa = float(np.exp(objective(x0)))
    result = minimize(objective, x0, method="SLSQP",
                      constraints=[{"type": "ineq", "fun": lambda x: A @ x + c, "jac": lambda x: A}],
                      options={"maxiter": max_iterations})
    coefficients, offs = unpack(np.asarray(result.x, dtype=float))
    return Excitation(
        coefficients=coefficients.copy(), q0=np.array(offs, dtype=float), base_frequency=float(base_frequency),
        condition_number=excitation_condition(base_regressor_function, coefficients, base_frequency, offs, t,
                                              parameters=parameters),
        initial_condition_number=initial_kappa, success=bool(result.success), message=str(result.message),
    )
