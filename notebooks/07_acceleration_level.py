# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 7. Acceleration-level kinematics: the Hessian, $\dot J$ and the gradient of manipulability
#
# **What you will learn**
#
# * that the hand's acceleration is $\ddot x = J\ddot q + \dot J\dot q$, and that the second term (the *bias
#   acceleration*) is there even when no joint accelerates: centripetal and Coriolis terms of the links;
# * how symjac writes $\partial J/\partial q_k$ (the kinematic Hessian) and $\dot J$ in closed form, as cross
#   products of the Jacobian's own columns, and why the derivative of a Jacobian written in a *moving* frame is
#   a different matrix;
# * resolved-acceleration control of a planar 2R arm, with and without the bias term;
# * the gradient of manipulability, one barrier term per singular factor, and gradient ascent that moves an arm
#   away from a singularity.

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symjac import (
    bias_acceleration,
    forward_kinematics,
    hessian,
    hessian_slice,
    jacobian,
    jacobian_derivative,
    joint_rate_symbols,
    latex,
    load_robot,
    log_det_gradient,
    manipulability_gradient,
)
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The planar 2R arm
#
# Differentiate the hand velocity $\dot x = J(q)\,\dot q$ once more in time. The product rule gives two terms:
# $\ddot x = J\ddot q + \dot J\dot q$, where $\dot J = \sum_k (\partial J/\partial q_k)\,\dot q_k$. For the 2R arm
# in its base frame:

# %%
planar = load_robot("planar2r")
J = jacobian(planar)[:2, :]
Jdot = jacobian_derivative(planar)[:2, :]
bias = bias_acceleration(planar)[:2, :]
display(Math(r"J = " + latex(J)))
display(Math(r"\dot J = " + latex(Jdot)))
display(Math(r"\dot J\,\dot q = " + latex(bias)))

# %% [markdown]
# Read the bias term link by link: the first link turns at $\dot\theta_1$, so its tip has a centripetal
# acceleration $L_1\dot\theta_1^2$ pointing back along the link ($-L_1 [c_1, s_1]$); the second link turns at
# $\dot\theta_1 + \dot\theta_2$ and contributes $L_2(\dot\theta_1 + \dot\theta_2)^2$ along itself. No joint
# accelerates, yet the hand does.
#
# ### The Hessian
#
# Each slice $\partial J/\partial q_k$ is built from the columns $J_j = [v_j; \omega_j]$ alone: for $k < j$ it is
# $[\omega_k \times v_j;\ \omega_k \times \omega_j]$ (joint $k$ swings joint $j$'s axis and lever arm), for
# $k \ge j$ it is $[\omega_j \times v_k;\ 0]$. The linear part is symmetric: it is $\partial^2 x/\partial q_j
# \partial q_k$.

# %%
H = hessian(planar)
for k, q in enumerate(planar.q):
    display(Math(rf"\frac{{\partial J}}{{\partial {sp.latex(q)}}} = " + latex(hessian_slice(H, k)[:2, :])))

# %% [markdown]
# ### Fixed frame or moving frame?
#
# $\dot J$ of the Jacobian written in frame {0} is what $\ddot x = J\ddot q + \dot J\dot q$ needs. The Jacobian
# written in frame {2}, ${}^2J = \mathrm{diag}({}^2_0R, {}^2_0R)\,{}^0J$, turns with the arm, so its derivative has an
# extra term, $-[\omega_2]_\times\,{}^2J$. For the 2R arm, ${}^2J$ does not depend on $\theta_1$ at all, and its
# derivative shows only $\dot\theta_2$:

# %%
display(Math(r"\frac{d}{dt}\,{}^2J = " + latex(jacobian_derivative(planar, frame=2)[:2, :])))

# %% [markdown]
# ## Resolved-acceleration control
#
# To make the hand follow a path $x_d(t)$, command the joint accelerations that produce the desired hand
# acceleration plus a PD correction, *after subtracting the bias*:
#
# $$\ddot q = J^{-1}\big(\ddot x_d + K_d(\dot x_d - \dot x) + K_p(x_d - x) - \dot J\dot q\big).$$
#
# The tracking error then obeys $\ddot e + K_d\dot e + K_p e = 0$ exactly. Leave out $\dot J\dot q$ and the
# centripetal terms act as a disturbance the PD part has to fight. We compile the symbolic results to NumPy once.

# %%
rates = joint_rate_symbols(planar)
values = {s: float(v) for s, v in planar.defaults.items()}

x_of = sp.lambdify([planar.q], forward_kinematics(planar)[:2, 3].xreplace(values), "numpy")
J_of = sp.lambdify([planar.q], J.xreplace(values), "numpy")
bias_of = sp.lambdify([planar.q, rates], bias.xreplace(values), "numpy")


def desired(t):
    """A circle of radius 0.15 around (0.55, 0.2), once every 2 s: position, velocity, acceleration."""
    w = np.pi
    c, s = np.cos(w * t), np.sin(w * t)
    return (np.array([0.55 + 0.15 * c, 0.2 + 0.15 * s]), np.array([-0.15 * w * s, 0.15 * w * c]),
            np.array([-0.15 * w * w * c, -0.15 * w * w * s]))


def acceleration(t, q, qdot, with_bias, kp=25.0, kd=10.0):
    """The commanded joint accelerations at time t in state (q, qdot)."""
    x_d, xdot_d, xddot_d = desired(t)
    Jq = np.array(J_of(q), dtype=float)
    x, xdot = np.array(x_of(q), dtype=float).ravel(), Jq @ qdot
    command = xddot_d + kd * (xdot_d - xdot) + kp * (x_d - x)
    if with_bias:
        command = command - np.array(bias_of(q, qdot), dtype=float).ravel()
    return np.linalg.solve(Jq, command)


def simulate(with_bias, dt=2e-3, duration=4.0):
    """Integrate the arm (a double integrator in the joints) with classical Runge-Kutta; the tracking error."""
    state = np.array([0.3, 1.2, 0.0, 0.0])  # q, qdot: the hand starts off the circle, at rest

    def f(t, s):
        return np.concatenate([s[2:], acceleration(t, s[:2], s[2:], with_bias)])

    times = np.arange(int(duration / dt) + 1) * dt
    errors = []
    for t in times:
        errors.append(np.linalg.norm(desired(t)[0] - np.array(x_of(state[:2]), dtype=float).ravel()))
        k1 = f(t, state)
        k2 = f(t + dt / 2, state + dt / 2 * k1)
        k3 = f(t + dt / 2, state + dt / 2 * k2)
        k4 = f(t + dt, state + dt * k3)
        state = state + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return times, np.array(errors)


t, error_with = simulate(with_bias=True)
_, error_without = simulate(with_bias=False)
fig, ax = plt.subplots(figsize=(7, 4))
ax.semilogy(t, error_with, label="with the bias term")
ax.semilogy(t, error_without, label="without it")
ax.set_xlabel("time (s)")
ax.set_ylabel("tracking error (m)")
ax.legend()
fig.savefig(OUTPUT / "07_resolved_acceleration.png", dpi=100)
print(f"error after 4 s: {error_with[-1]:.2e} m with the bias term, {error_without[-1]:.2e} m without")

# %% [markdown]
# With the bias term the error decays exactly as the PD gains prescribe, $e(t) \propto (1 + 5t)\,e^{-5t}$; without
# it, the centripetal terms leave a steady error of about a centimetre around the circle.

# %% [markdown]
# ## The gradient of manipulability
#
# Manipulability $w = \sqrt{\det(J J^T)}$ vanishes at a singularity. Its gradient tells which joint motion raises
# it fastest, and it too comes from the Hessian: $\partial w/\partial q_k = w\,\mathrm{tr}(J^+\,\partial J/\partial
# q_k)$. For a square Jacobian the logarithm is simpler still. With the factored determinant
# $\det J = c\,\prod_i f_i^{m_i}$,
#
# $$\frac{\partial \log|\det J|}{\partial q} = \sum_i m_i \frac{\nabla f_i}{f_i},$$
#
# one *barrier term* per singular factor, which grows without bound as its own singularity approaches. For the
# PUMA 560:

# %%
puma = load_robot("puma560")
barrier = log_det_gradient(puma)
for term in barrier.terms:
    display(Math(rf"f = {latex(term.factor)}: \quad \frac{{\nabla f}}{{f}} = " + latex(term.gradient.T)))

# %% [markdown]
# The wrist factor $s_5$ gives $\cot\theta_5$ in the $\theta_5$ slot and nothing else: pushing along that term alone
# moves the wrist away from its singularity without touching the elbow or the shoulder. Now climb the full
# gradient from a configuration close to the wrist singularity ($\theta_5 = 0.05$), in small normalised steps:

# %%
q = np.array([0.2, -0.6, 0.3, 0.4, 0.05, 0.0])
history = []
for _ in range(60):
    w, gradient = manipulability_gradient(puma, q)
    history.append((w, q[4]))
    q = q + 0.05 * gradient / np.linalg.norm(gradient)
history = np.array(history)
fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.5))
left.plot(history[:, 0])
left.set_xlabel("step")
left.set_ylabel("manipulability w")
right.plot(history[:, 1])
right.set_xlabel("step")
right.set_ylabel("theta5 (rad)")
fig.tight_layout()
fig.savefig(OUTPUT / "07_manipulability_ascent.png", dpi=100)
print(f"w grew from {history[0, 0]:.2e} to {history[-1, 0]:.2e}; theta5 from {history[0, 1]:.2f} "
      f"to {history[-1, 1]:.2f} rad")

# %% [markdown]
# Nearly every step goes into $\theta_5$: near the wrist singularity its barrier term $\cot\theta_5$ dominates the
# gradient. It fades as $\theta_5$ approaches $\pi/2$ (where $s_5 = 1$ is largest), the elbow and shoulder terms
# finish the climb, and the ascent settles at a local maximum of $w$ (the small wiggle is the fixed step length).
#
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. Write the $x$ component of the planar 2R arm's bias acceleration $\dot J\dot q$ in frame {0} (use the rate
#    symbols `joint_rate_symbols(planar)`).
# 2. The planar 2R arm's determinant is $L_1 L_2 s_2$. What is its barrier term $\partial \log|\det J| /
#    \partial\theta_2$?
# 3. The 2R arm is stretched out ($\theta_1 = \theta_2 = 0$) and turns as a whole at $\dot\theta_1 = 1$ rad/s,
#    $\dot\theta_2 = 0$. How large is the hand's acceleration (in m/s^2, with the default lengths) when no joint
#    accelerates?

# %%
L1, L2 = sp.symbols("L1 L2", real=True)
theta1, theta2 = planar.q
thetadot1, thetadot2 = rates
answer_1 = ...  # your answer here
check(answer_1, bias_acceleration(planar)[0], planar)

# %%
answer_2 = ...  # your answer here
check(answer_2, log_det_gradient(planar).total[1], planar)

# %%
answer_3 = ...  # your answer here
stretched = bias_acceleration(planar).xreplace({**values, theta1: 0, theta2: 0, thetadot1: 1, thetadot2: 0})
check(answer_3, float(sp.sqrt(stretched[0] ** 2 + stretched[1] ** 2)))
print("all answers correct")
