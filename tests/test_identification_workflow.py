"""The identification workflow: stacking, (weighted) least squares with its statistics, Fourier excitation."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from symjac.analysis.identification import (
    excitation_condition,
    fourier_basis,
    fourier_trajectory,
    identify,
    joint_weights,
    optimise_excitation,
    stack,
)
from symjac.errors import ArgumentError


def toy_regressor(q, qd, qdd):
    """A vectorised 2-joint 'base regressor', (..., 2) -> (..., 2, 5), linear in 5 parameters."""
    q, qd, qdd = (np.asarray(a, dtype=float) for a in (q, qd, qdd))
    Y = np.zeros((*q.shape[:-1], 2, 5))
    Y[..., 0, 0] = qdd[..., 0]
    Y[..., 0, 1] = qd[..., 0]
    Y[..., 0, 2] = np.sin(q[..., 0]) + np.cos(q[..., 1]) * qdd[..., 1]
    Y[..., 1, 2] = np.cos(q[..., 1]) * qdd[..., 0]
    Y[..., 1, 3] = qdd[..., 1] + qd[..., 0] ** 2 * np.sin(q[..., 1])
    Y[..., 1, 4] = np.cos(q[..., 0] + q[..., 1])
    return Y


def per_sample_regressor(q, qd, qdd):
    """The same regressor one sample at a time with the math module, as the plain-Python target writes it."""
    return [[qdd[0], qd[0], math.sin(q[0]) + math.cos(q[1]) * qdd[1], 0.0, 0.0],
            [0.0, 0.0, math.cos(q[1]) * qdd[0], qdd[1] + qd[0] ** 2 * math.sin(q[1]), math.cos(q[0] + q[1])]]


@pytest.fixture
def samples():
    rng = np.random.default_rng(3)
    return tuple(rng.uniform(-2, 2, (40, 2)) for _ in range(3))


# --- stacking ---------------------------------------------------------------------------------------------------

def test_stack_orders_rows_sample_major_and_agrees_for_batched_and_per_sample_functions(samples):
    q, qd, qdd = samples
    batched = stack(toy_regressor, q, qd, qdd)
    assert batched.shape == (80, 5)
    np.testing.assert_allclose(batched[2 * 7 + 1], toy_regressor(q[7], qd[7], qdd[7])[1])  # sample 7, joint 2
    np.testing.assert_allclose(stack(per_sample_regressor, q, qd, qdd), batched, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(stack(toy_regressor, q, qd, qdd, vectorised=False), batched)


def test_stack_passes_parameters_and_refuses_bad_shapes(samples):
    q, qd, qdd = samples
    scaled = stack(lambda q, qd, qdd, k=1.0: k * toy_regressor(q, qd, qdd), q, qd, qdd, parameters={"k": 2.0})
    np.testing.assert_allclose(scaled, 2 * stack(toy_regressor, q, qd, qdd))
    with pytest.raises(ArgumentError, match="one shape"):
        stack(toy_regressor, q, qd[:5], qdd)
    with pytest.raises(ArgumentError, match=r"expected \(2, b\)"):
        stack(lambda q, qd, qdd: [1.0, 2.0], q, qd, qdd)


# --- least squares ----------------------------------------------------------------------------------------------

def test_noise_free_data_gives_the_parameters_back_exactly(samples):
    truth = np.array([1.5, -0.3, 2.0, 0.7, -4.0])
    Y = stack(toy_regressor, *samples)
    result = identify(Y, Y @ truth, names=[f"p{i}" for i in range(5)])
    np.testing.assert_allclose(result.parameters, truth, rtol=1e-12)
    assert result.residual_rms < 1e-12 and result.rank == 5
    assert result.condition_number == pytest.approx(np.linalg.cond(Y))
    assert result.as_dict()["p4"] == pytest.approx(-4.0)
    three_d = identify(Y.reshape(40, 2, 5), (Y @ truth).reshape(40, 2))  # unstacked arrays are stacked here
    np.testing.assert_allclose(three_d.parameters, truth, rtol=1e-12)


def test_deviations_of_the_mean_computed_by_hand():
    # One parameter, the mean of 1, 2, 3, 4: estimate 2.5, residual squares 5, sigma^2 = 5/3, variance 5/12.
    result = identify(np.ones((4, 1)), [1.0, 2.0, 3.0, 4.0])
    assert result.parameters[0] == pytest.approx(2.5)
    assert result.residual_variance == pytest.approx(5 / 3)
    assert result.standard_deviations[0] == pytest.approx(math.sqrt(5 / 12))
    assert result.relative_deviations[0] == pytest.approx(100 * math.sqrt(5 / 12) / 2.5)
    assert result.residual_rms == pytest.approx(math.sqrt(5 / 4))


def test_two_parameters_ordinary_and_weighted_by_hand():
    Y, tau = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [1.0, 1.0, 3.0]
    # Ordinary: Y^T Y = [[2, 1], [1, 2]], Y^T tau = [4, 4] -> 4/3 each; residuals (-1/3, -1/3, 1/3), sigma^2 = 1/3,
    # covariance (1/3) (1/3) [[2, -1], [-1, 2]]; the condition number sqrt(3 / 1).
    ordinary = identify(Y, tau)
    np.testing.assert_allclose(ordinary.parameters, [4 / 3, 4 / 3])
    np.testing.assert_allclose(ordinary.covariance, np.array([[2, -1], [-1, 2]]) / 9)
    np.testing.assert_allclose(ordinary.standard_deviations, [math.sqrt(2) / 3] * 2)
    assert ordinary.condition_number == pytest.approx(math.sqrt(3))
    # Weights (1, 1, 4): Y^T W Y = [[5, 4], [4, 5]], Y^T W tau = [13, 13] -> 13/9 each; weighted residual squares
    # 16/81 + 16/81 + 4 * 1/81 = 4/9 over 1 degree of freedom; covariance (4/9) (1/9) [[5, -4], [-4, 5]];
    # sqrt(W) Y = [[1, 0], [0, 1], [2, 2]] has singular values 3 and 1.
    weighted = identify(Y, tau, weights=[1.0, 1.0, 4.0])
    np.testing.assert_allclose(weighted.parameters, [13 / 9, 13 / 9])
    assert weighted.residual_variance == pytest.approx(4 / 9)
    np.testing.assert_allclose(weighted.covariance, np.array([[5, -4], [-4, 5]]) * 4 / 81)
    np.testing.assert_allclose(weighted.standard_deviations, [math.sqrt(20) / 9] * 2)
    np.testing.assert_allclose(weighted.residuals, [-4 / 9, -4 / 9, 1 / 9])
    assert weighted.condition_number == pytest.approx(3.0)


def test_noisy_data_lands_within_the_stated_confidence(samples):
    rng = np.random.default_rng(11)
    truth = np.array([1.5, -0.3, 2.0, 0.7, -4.0])
    q, qd, qdd = (np.repeat(a, 25, axis=0) + rng.normal(0, 0.3, (1000, 2)) for a in samples)
    Y = stack(toy_regressor, q, qd, qdd)
    noise = np.column_stack([rng.normal(0, 0.01, 1000), rng.normal(0, 0.2, 1000)]).reshape(-1)
    ordinary = identify(Y, Y @ truth + noise)
    assert np.all(np.abs(ordinary.parameters - truth) < 4 * ordinary.standard_deviations)
    weights = joint_weights(Y, Y @ truth + noise, joints=2)
    assert weights[0] / weights[1] == pytest.approx((0.2 / 0.01) ** 2, rel=0.15)  # the noise variances' ratio
    weighted = identify(Y, Y @ truth + noise, weights)
    assert np.all(np.abs(weighted.parameters - truth) < 4 * weighted.standard_deviations)
    assert weighted.residual_variance == pytest.approx(1.0, rel=0.1)  # the weights whiten the noise
    # Joint 1's parameters are measured through the quiet joint: weighting makes them sharper.
    assert weighted.standard_deviations[0] < 0.5 * ordinary.standard_deviations[0]


def test_bad_systems_are_refused_with_a_reason(samples):
    Y = stack(toy_regressor, *samples)
    with pytest.raises(ArgumentError, match="rank 4 for 5 parameters"):
        identify(np.column_stack([Y[:, :4], Y[:, 0] + Y[:, 1]]), np.zeros(80))
    with pytest.raises(ArgumentError, match="80 rows but the torques give 79"):
        identify(Y, np.zeros(79))
    with pytest.raises(ArgumentError, match="positive"):
        identify(Y, np.zeros(80), weights=np.r_[np.ones(79), -1.0])
    with pytest.raises(ArgumentError, match="no noise"):
        joint_weights(Y, Y @ np.ones(5), joints=2)


# --- Fourier excitation -----------------------------------------------------------------------------------------

def test_fourier_series_derivatives_match_central_differences():
    rng = np.random.default_rng(5)
    coefficients, q0, w = rng.normal(size=(3, 2, 4)), rng.normal(size=3), 0.7
    t = np.linspace(0, 9, 31)
    q, qd, qdd = fourier_trajectory(coefficients, w, q0, t)
    h = 1e-5
    plus, minus = fourier_trajectory(coefficients, w, q0, t + h), fourier_trajectory(coefficients, w, q0, t - h)
    np.testing.assert_allclose(qd, (plus[0] - minus[0]) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(qdd, (plus[1] - minus[1]) / (2 * h), atol=1e-8)
    # The series written out term by term for joint 2, and the period 2 pi / w.
    a, b = coefficients[1]
    written = q0[1] + sum(a[k] / (w * (k + 1)) * np.sin(w * (k + 1) * t) - b[k] / (w * (k + 1))
                          * np.cos(w * (k + 1) * t) for k in range(4))
    np.testing.assert_allclose(q[:, 1], written, atol=1e-12)
    np.testing.assert_allclose(fourier_trajectory(coefficients, w, q0, t + 2 * np.pi / w)[0], q, atol=1e-12)


def test_fourier_arguments_are_checked():
    with pytest.raises(ArgumentError, match=r"shape \(joints, 2, harmonics\)"):
        fourier_trajectory(np.ones((2, 3)), 1.0, [0, 0], [0.0])
    with pytest.raises(ArgumentError, match="one entry per joint"):
        fourier_trajectory(np.ones((2, 2, 1)), 1.0, [0.0], [0.0])
    with pytest.raises(ArgumentError, match="base frequency must be positive"):
        fourier_basis(2, 0.0, [0.0])


def test_excitation_condition_is_the_stacked_regressors():
    rng = np.random.default_rng(2)
    coefficients, t = rng.normal(size=(2, 2, 3)), np.linspace(0, 10, 50)
    q, qd, qdd = fourier_trajectory(coefficients, 0.6, [0.1, -0.2], t)
    expected = np.linalg.cond(stack(toy_regressor, q, qd, qdd))
    assert excitation_condition(toy_regressor, coefficients, 0.6, [0.1, -0.2], t) == pytest.approx(expected)
    still = np.zeros((2, 2, 3))  # no motion excites no inertia
    assert excitation_condition(toy_regressor, still, 0.6, [0.1, -0.2], t) == math.inf


def test_optimised_excitation_is_better_conditioned_and_within_its_limits():
    pytest.importorskip("scipy")
    t = np.linspace(0, 2 * np.pi / 0.5, 60, endpoint=False)
    result = optimise_excitation(toy_regressor, 2, 3, 0.5, t, lower=[-1.0, -0.5], upper=[1.0, 1.5],
                                 velocity_limit=2.0, acceleration_limit=[3.0, 4.0], seed=1, max_iterations=60)
    assert result.condition_number < 0.8 * result.initial_condition_number
    q, qd, qdd = result.trajectory(t)
    assert np.all(q >= np.array([-1.0, -0.5]) - 1e-6) and np.all(q <= np.array([1.0, 1.5]) + 1e-6)
    assert np.all(np.abs(qd) <= 2.0 + 1e-6) and np.all(np.abs(qdd) <= np.array([3.0, 4.0]) + 1e-6)
    assert result.condition_number == pytest.approx(
        excitation_condition(toy_regressor, result.coefficients, 0.5, result.q0, t))


def test_optimisation_without_scipy_says_what_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "scipy.optimize", None)
    with pytest.raises(ImportError, match=r"symjac\[identification\]"):
        optimise_excitation(toy_regressor, 2, 1, 1.0, [0.0, 1.0])
