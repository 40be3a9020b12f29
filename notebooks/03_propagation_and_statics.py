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
# # 3. Velocity and force propagation, statics, the force/torque sensor
#
# **What you will learn**
#
# * how link velocities are passed outward from the base, one link at a time:
#   ${}^{i+1}\omega_{i+1} = {}^{i+1}_iR\,{}^i\omega_i + \dot\theta_{i+1}\,\hat z$ and
#   ${}^{i+1}v_{i+1} = {}^{i+1}_iR\,({}^iv_i + {}^i\omega_i \times {}^ip_{i+1})$;
# * how a force and moment at the hand are passed inward, ${}^if_i = {}^i_{i+1}R\,{}^{i+1}f_{i+1}$,
#   ${}^in_i = {}^i_{i+1}R\,{}^{i+1}n_{i+1} + {}^ip_{i+1} \times {}^if_i$, and the joint torque is
#   $\tau_i = {}^in_i \cdot \hat z$;
# * that both iterations produce the Jacobian, one as $J$ and the other as $J^T$: $\tau = J^T F$;
# * how to move a force/torque sensor's reading to the tool tip.

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symjac import (
    force_propagation,
    jacobian,
    joint_torques,
    latex,
    load_robot,
    numeric_jacobian,
    velocity_propagation,
    wrench_between,
)
from symjac.printing import propagation_steps
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## Velocity propagation, step by step (planar 3R arm)
#
# `velocity_propagation` runs the outward iteration symbolically; each step is printed as the textbook writes it,
# with the joint rates $\dot\theta_i$ left as symbols.

# %%
robot = load_robot("planar3r")
propagation = velocity_propagation(robot, (0, 0, 0))  # to the origin of {3} (by default: the end, the tool)
for line in propagation_steps(propagation):
    display(Math(line))

# %% [markdown]
# The last step is linear in the joint rates; its coefficient matrix is the Jacobian in the last frame, ${}^3J$.
# It agrees exactly with differentiation (re-expressed in frame {3}) at the same point, the origin of {3}: the
# flange (`jacobian(robot)` alone is at the end of the chain, planar3r's tool point).

# %%
check(propagation.jacobian, jacobian(robot, frame=3, point="flange"), robot)

# %% [markdown]
# ## Force propagation
#
# Now push on the hand with a force $(f_x, f_y)$ and a moment $n_z$ (in frame {3}) and ask which joint torques
# hold it still. The inward iteration answers, and the torques are the rows of ${}^3J^T$ applied to the wrench.

# %%
forces = force_propagation(robot, (0, 0, 0))  # the wrench acts at the origin of {3}, given in {3}
for line in propagation_steps(forces)[-3:]:
    display(Math(line))
check(forces.jacobian, jacobian(robot, frame=3, point="flange"), robot)

# %% [markdown]
# ## $\tau = J^T F$ by virtual work
#
# If the hand moves by $\delta x = J\,\delta q$ against a wrench $F$, the work $F^T \delta x$ must equal the work
# done by the joints, $\tau^T \delta q$, for every $\delta q$: hence $\tau = J^T F$. Check it numerically for the
# PUMA 560 by comparing both sides of the virtual-work identity at a random configuration.

# %%
puma = load_robot("puma560")
rng = np.random.default_rng(0)
q = rng.uniform(-np.pi, np.pi, 6)
F = np.array([0.0, 0.0, -20.0, 0.0, 1.0, 0.0])  # 20 N down, 1 N m about y, at the wrist, in {0}
tau = np.array(joint_torques(puma, wrench=list(F), q=list(q)), dtype=float).ravel()
dq = rng.normal(size=6) * 1e-6
dx = numeric_jacobian(puma, q) @ dq
print("tau . dq =", tau @ dq, "   F . dx =", F @ dx)

# %% [markdown]
# ## The force/torque sensor and the tool tip
#
# A sensor mounted at the wrist measures the wrench in its own frame; a tool sticks out by $L_3$. The wrench the
# tool applies at its tip maps to the sensor frame by
# $\begin{bmatrix} R & 0 \\ \hat p R & R\end{bmatrix}$. For the planar arm with its tool frame:

# %%
W = wrench_between(robot, "tool", 3)
display(Math(r"{}^3F = " + latex(W) + r"\,{}^TF"))

# %% [markdown]
# Either way gives the same joint torques: holding a tip force $F_T$ takes
# $\tau = ({}^TJ_{tip})^T F_T = ({}^3J_{wrist})^T ({}^3_T W F_T)$.

# %%
f_y = sp.Symbol("f_y", real=True)
tip = joint_torques(robot, wrench=[0, f_y, 0, 0, 0, 0], frame="tool", point="tool")
wrist = joint_torques(robot, wrench=list(W * sp.Matrix([0, f_y, 0, 0, 0, 0])), frame=3, point="flange")
check(tip, wrist, robot)
display(Math(r"\tau = " + latex(tip)))

# %% [markdown]
# A picture of how the torque needed to hold a 10 N downward force changes as the elbow bends:

# %%
angles = np.linspace(-np.pi, np.pi, 121)
torques = np.array([np.array(joint_torques(robot, wrench=[0, -10, 0, 0, 0, 0], frame=0, point="tool",
                                           q=[0.0, a, 0.0]), dtype=float).ravel() for a in angles])
fig, ax = plt.subplots(figsize=(7, 4))
for i in range(3):
    ax.plot(angles, torques[:, i], label=f"tau{i + 1}")
ax.set_xlabel("theta2 (rad), theta1 = theta3 = 0")
ax.set_ylabel("N m")
ax.set_title("Joint torques holding 10 N down at the tool tip")
ax.legend()
fig.savefig(OUTPUT / "03_holding_torques.png", dpi=100)

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. For the planar 3R arm, what is $\tau_3$ when the tip (tool point) pushes with $f_y$ along $y$ of the tool
#    frame? (Hint: only the last link's length matters.)
# 2. In the velocity propagation, what is ${}^1\omega_1$?
# 3. True or false: with the arm stretched out ($\theta_2 = \theta_3 = 0$) a force along the arm needs no torque.

# %%
L3 = sp.Symbol("L3", real=True)
answer_1 = ...  # your answer here
check(answer_1, tip[2], robot)

# %%
answer_2 = ...  # your answer here
check(answer_2, propagation.velocities()[1][1], robot)

# %%
stretched = joint_torques(robot, wrench=[1, 0, 0, 0, 0, 0], frame=0, point="tool", q=[0, 0, 0])
answer_3 = ...  # your answer here
check(answer_3, all(abs(float(t)) < 1e-12 for t in stretched))
print("all answers correct")
