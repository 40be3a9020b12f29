r"""Identification from measured data: stack the base regressor over samples and solve by least squares.

The base dynamic model is linear in the base parameters, :math:`\tau = Y_b(q, \dot q, \ddot q)\, \pi_b`. Sampled
along a trajectory, the N samples give one tall system (sample-major rows: row ``k * n + j`` is joint j at sample k)

.. math:: \underbrace{\begin{bmatrix} \tau(t_1) \\ \vdots \\ \tau(t_N) \end{bmatrix}}_{\tau_s}
          = \underbrace{\begin{bmatrix} Y_b(t_1) \\ \vdots \\ Y_b(t_N) \end{bmatrix}}_{W_s} \pi_b + \rho,

solved by (weighted) least squares, :math:`\hat\pi = \arg\min \rho^T W \rho`, with :math:`W` a diagonal of row
weights (the inverse variance of each row's noise; ordinary least squares when :math:`W = I`). With
:math:`r` rows and :math:`b` parameters, the residual variance and the parameters' covariance are

.. math:: \hat\sigma^2 = \frac{\hat\rho^T W \hat\rho}{r - b}, \qquad
          \operatorname{cov}(\hat\pi) = \hat\sigma^2 \bigl(W_s^T W W_s\bigr)^{-1},

the standard deviations the square roots of its diagonal, and the relative deviations
:math:`100\, \sigma_{\hat\pi_i} / |\hat\pi_i|` in percent. The condition number of the (weighted) stacked regressor
:math:`W^{1/2} W_s` says how much the noise is amplified: an exciting trajectory keeps it small
(:mod:`symjac.analysis.identification.excitation`). Pure NumPy.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from symjac.errors import ArgumentError

__all__ = ["Identification", "identify", "joint_weights", "stack"]


def _samples(name: str, values: ArrayLike) -> np.ndarray:
    """``values`` as an (N, n) float array (one sample may be given as a vector)."""
    array = np.asarray(values, dtype=float)
    if array.ndim == 1:
        array = array[np.newaxis, :]
    if array.ndim != 2 or array.shape[0] == 0 or array.shape[1] == 0:
        raise ArgumentError(f"{name} must have shape (samples, joints), got shape {np.shape(values)}")
    return array


def stack(
    base_regressor_function: Callable[..., Any],
    q: ArrayLike,
    qdot: ArrayLike,
    qddot: ArrayLike,
    *,
    parameters: Mapping[str, float] | None = None,
    vectorised: bool | None = None,
) -> np.ndarray:
    r"""The regressor stacked over samples: an (N, n, b) array of regressors as one (N n, b) matrix.

    .. math:: W_s = \begin{bmatrix} Y(q_1, \dot q_1, \ddot q_1) \\ \vdots \\ Y(q_N, \dot q_N, \ddot q_N) \end{bmatrix}

    Parameters
    ----------
    base_regressor_function : callable
        ``f(q, qdot, qddot, **parameters)`` giving the n x b regressor: a generated module's ``base_regressor`` or
        ``regressor``. A vectorised one (the ``numpy``, ``c`` and ``jax`` targets) is called once on the whole
        batch and returns shape (N, n, b); a per-sample one (the ``python`` target) is called once per sample.
    q, qdot, qddot : array_like, shape (N, n)
        The samples' coordinates, rates and accelerations (one sample may be a vector).
    parameters : mapping, optional
        Keyword arguments passed on to every call (the robot's geometric parameters, gravity ``g``).
    vectorised : bool, optional
        Whether the function takes the batch at once; by default it is tried on the batch and called per sample
        when that fails or gives the wrong shape.

    Returns
    -------
    numpy.ndarray, shape (N n, b)
        Row ``k n + j`` is joint j's row at sample k, the order of ``tau.reshape(-1)`` for ``tau`` of shape (N, n).

    Examples
    --------
    >>> import numpy as np
    >>> Y = lambda q, qd, qdd: np.array([[qdd[0], np.sin(q[0])]])
    >>> stack(Y, [[0.0], [np.pi / 2]], [[0.0], [0.0]], [[1.0], [2.0]])
    array([[1., 0.],
           [2., 1.]])
    """
    arrays = [_samples(name, value) for name, value in (("q", q), ("qdot", qdot), ("qddot", qddot))]
    if len({array.shape for array in arrays}) != 1:
        raise ArgumentError(
            f"q, qdot and qddot must have one shape, got {', '.join(str(array.shape) for array in arrays)}")
    samples, joints = arrays[0].shape
    keywords = dict(parameters or {})
    batch: np.ndarray | None = None
    if vectorised is not False:
        try:
            batch = np.asarray(base_regressor_function(*arrays, **keywords), dtype=float)
        except (TypeError, ValueError, IndexError):
            if vectorised:
                raise
            batch = None
        if batch is not None and (batch.ndim != 3 or batch.shape[:2] != (samples, joints)):
            if vectorised:
                raise ArgumentError(f"the regressor function gave shape {batch.shape} for {samples} samples of "
                                    f"{joints} joints; expected ({samples}, {joints}, b)")
            batch = None
    if batch is None:
        rows = [np.asarray(base_regressor_function(*(array[k] for array in arrays), **keywords), dtype=float)
                for k in range(samples)]
        if rows[0].ndim != 2 or rows[0].shape[0] != joints:
            raise ArgumentError(f"the regressor function gave shape {rows[0].shape} for one sample of {joints} "
                                f"joints; expected ({joints}, b)")
        batch = np.stack(rows)
    return batch.reshape(samples * joints, batch.shape[2])


@dataclass(frozen=True)
class Identification:
    r"""The result of :func:`identify`: the estimated parameters and how far to trust them.

    ``parameters`` is the least-squares estimate :math:`\hat\pi` (b values); ``covariance`` is
    :math:`\hat\sigma^2 (W_s^T W W_s)^{-1}` (b x b), ``standard_deviations`` the square roots of its diagonal and
    ``relative_deviations`` :math:`100\, \sigma_{\hat\pi_i} / |\hat\pi_i|` in percent (infinite where an estimate is
    exactly 0). ``residual_variance`` is :math:`\hat\sigma^2 = \hat\rho^T W \hat\rho / (r - b)` (0 with no more rows
    than parameters); ``residuals`` the unweighted residual :math:`\tau_s - W_s \hat\pi` in the rows' order and
    ``residual_rms`` its root mean square. ``condition_number`` is the 2-norm condition number of the weighted stacked
    regressor :math:`W^{1/2} W_s`, ``rank`` its numeric rank (always b: a rank-deficient system is refused), and
    ``names`` the parameters' names in order, when given.
    """

    parameters: np.ndarray
    standard_deviations: np.ndarray
    relative_deviations: np.ndarray
    covariance: np.ndarray
    residual_variance: float
    residual_rms: float
    residuals: np.ndarray
    condition_number: float
    rank: int
    names: tuple[str, ...] | None = None

    def as_dict(self) -> dict[str, float]:
        """The estimates by name (``names`` must be set)."""
        if self.names is None:
            raise ArgumentError("this identification has no parameter names: pass names= to identify")
        return dict(zip(self.names, (float(value) for value in self.parameters), strict=True))


def _system(Y_stacked: ArrayLike, tau_stacked: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    Y = np.asarray(Y_stacked, dtype=float)
    if Y.ndim == 3:
        Y = Y.reshape(-1, Y.shape[2])
    if Y.ndim != 2 or 0 in Y.shape:
        raise ArgumentError(f"the stacked regressor must have shape (rows, parameters), got {np.shape(Y_stacked)}")
    tau = np.asarray(tau_stacked, dtype=float).reshape(-1)
    if tau.shape[0] != Y.shape[0]:
        raise ArgumentError(f"the stacked regressor has {Y.shape[0]} rows but the torques give {tau.shape[0]}")
    if not (np.all(np.isfinite(Y)) and np.all(np.isfinite(tau))):
        raise ArgumentError("the stacked regressor and the torques must be finite (found nan or inf)")
    return Y, tau


def identify(
    Y_stacked: ArrayLike,
    tau_stacked: ArrayLike,
    weights: ArrayLike | None = None,
    *,
    names: Sequence[str] | None = None,
) -> Identification:
    r"""Least-squares estimate of the parameters of :math:`\tau_s = W_s \pi + \rho`, with its uncertainty.

    .. math:: \hat\pi = \arg\min_\pi (\tau_s - W_s\pi)^T W (\tau_s - W_s\pi), \qquad
              \operatorname{cov}(\hat\pi) = \hat\sigma^2 (W_s^T W W_s)^{-1}, \quad
              \hat\sigma^2 = \frac{\hat\rho^T W \hat\rho}{r - b}

    Parameters
    ----------
    Y_stacked : array_like, shape (r, b) or (N, n, b)
        The stacked regressor (:func:`stack`); a 3-D array is stacked here.
    tau_stacked : array_like, shape (r,) or (N, n)
        The measured generalised forces, in the same row order.
    weights : array_like, shape (r,), optional
        The diagonal of :math:`W`, one positive weight per row (the inverse of that row's noise variance, e.g. from
        :func:`joint_weights`); ordinary least squares when omitted.
    names : sequence of str, optional
        The parameters' names, kept in the result.

    Returns
    -------
    Identification
        The estimate, its standard and relative deviations, the residual and the condition number.

    Raises
    ------
    ArgumentError
        When the shapes disagree, a weight is not positive, or the stacked regressor is rank deficient (not base
        parameters, or a trajectory that does not excite them all).

    Examples
    --------
    >>> result = identify([[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]], [1.0, 4.0, 3.0])
    >>> result.parameters.round(12), result.residual_rms < 1e-12
    (array([1., 2.]), True)
    """
    Y, tau = _system(Y_stacked, tau_stacked)
    rows, count = Y.shape
    if names is not None and len(names) != count:
        raise ArgumentError(f"{len(names)} names for {count} parameters")
    if weights is None:
        root = np.ones(rows)
    else:
        w = np.asarray(weights, dtype=float).reshape(-1)
        if w.shape[0] != rows:
            raise ArgumentError(f"weights must have one entry per row ({rows}), got {w.shape[0]}")
        if not np.all(np.isfinite(w)) or np.any(w <= 0):
            raise ArgumentError("weights must be positive and finite")
        root = np.sqrt(w)
    A, y = Y * root[:, np.newaxis], tau * root
    singular = np.linalg.svd(A, compute_uv=False)
    rank = int(np.sum(singular > singular[0] * max(A.shape) * np.finfo(float).eps)) if singular[0] > 0 else 0
    if rank < count:
        raise ArgumentError(
            f"the stacked regressor has rank {rank} for {count} parameters: use the base parameters, or a trajectory "
            "that excites them all (more samples, richer motion)")
    estimate = np.linalg.lstsq(A, y, rcond=None)[0]
    weighted = y - A @ estimate
    residuals = tau - Y @ estimate
    variance = float(weighted @ weighted / (rows - count)) if rows > count else 0.0
    covariance = variance * np.linalg.inv(A.T @ A)
    deviations = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.where(estimate != 0, 100.0 * deviations / np.abs(estimate), np.inf)
    return Identification(
        parameters=estimate,
        standard_deviations=deviations,
        relative_deviations=relative,
        covariance=covariance,
        residual_variance=variance,
        residual_rms=float(np.sqrt(np.mean(residuals**2))),
        residuals=residuals,
        condition_number=float(singular[0] / singular[-1]),
        rank=rank,
        names=tuple(names) if names is not None else None,
    )


def joint_weights(Y_stacked: ArrayLike, tau_stacked: ArrayLike, joints: int) -> np.ndarray:
    r"""Row weights for :func:`identify` from each joint's own noise level (Gautier's weighting).

    Each joint's rows are fitted alone by ordinary least squares; their residual variance
    :math:`\hat\sigma_j^2 = \lVert \tau_j - Y_j \hat\pi_j \rVert^2 / (N - b_j)` (:math:`b_j` the rank of that joint's
    rows) gives every row of joint j the weight :math:`1 / \hat\sigma_j^2`, so noisy joints count less.

    Parameters
    ----------
    Y_stacked : array_like, shape (N n, b) or (N, n, b)
        The stacked regressor, sample-major rows (:func:`stack`).
    tau_stacked : array_like, shape (N n,) or (N, n)
        The measured generalised forces.
    joints : int
        n, the generalised forces per sample.

    Returns
    -------
    numpy.ndarray, shape (N n,)
        The weights, in the rows' order.
    """
    Y, tau = _system(Y_stacked, tau_stacked)
    if joints < 1 or Y.shape[0] % joints:
        raise ArgumentError(f"{Y.shape[0]} rows are not a whole number of samples of {joints} joints")
    samples = Y.shape[0] // joints
    weights = np.empty(Y.shape[0])
    for j in range(joints):
        Y_j, tau_j = Y[j::joints], tau[j::joints]
        estimate = np.linalg.lstsq(Y_j, tau_j, rcond=None)[0]
        rank = int(np.linalg.matrix_rank(Y_j))
        if samples <= rank:
            raise ArgumentError(f"joint {j + 1}: {samples} samples do not exceed its {rank} identifiable parameters")
        residual = tau_j - Y_j @ estimate
        variance = float(residual @ residual) / (samples - rank)
        if variance <= (np.finfo(float).eps * max(float(np.linalg.norm(tau_j)), 1.0)) ** 2:
            raise ArgumentError(f"joint {j + 1}: its rows fit exactly (no noise), so no weight can be estimated")
        weights[j::joints] = 1.0 / variance
    return weights
