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
# # 1. Differential motion and the two-link planar arm
#
# **What you will learn**
#
# * that the Jacobian is the matrix of partial derivatives of the forward kinematics, $J = \partial f / \partial q$;
# * how it maps joint rates to the velocity of the hand, $\dot x = J(q)\,\dot q$, and why that map changes with
#   the configuration;
# * how to picture the map: the unit circle of joint rates becomes an ellipse of hand velocities, which collapses
#   to a line when the arm is stretched out.
#
# Every matrix below is printed in the shorthand used on the blackboard: $s_1 = \sin\theta_1$,
# $c_{12} = \cos(\theta_1 + \theta_2)$.

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symjac import forward_kinematics, jacobian, jacobian_of, latex, load_robot, numeric_jacobian
from symjac.teaching.exercises import check, check_set

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The arm and its forward kinematics
#
# Two revolute joints with parallel axes, links of length $L_1$ and $L_2$. The built-in robot `planar2r` describes
# it by a Denavit-Hartenberg table; the position of the hand (the origin of frame {2}) is the last column of
# ${}^0_2T$.

# %%
robot = load_robot("planar2r")
T = forward_kinematics(robot)
display(Math(r"{}^0_2T = " + latex(T)))

# %% [markdown]
# Keep only the two coordinates the arm controls, $x$ and $y$. They are a vector function $f(q)$ of the joint
# angles $q = (\theta_1, \theta_2)$.

# %%
theta1, theta2 = robot.q
f = sp.Matrix(T[:2, 3])
display(Math(r"f(q) = " + latex(f)))

# %% [markdown]
# ## The Jacobian is a matrix of partial derivatives
#
# Differentiate each coordinate with respect to each joint angle. Column $i$ says how fast the hand moves when only
# joint $i$ turns at unit rate.

# %%
J_f = jacobian_of(f, robot.q)
display(Math(r"J = \frac{\partial f}{\partial q} = " + latex(J_f)))

# %% [markdown]
# symjac derives the same matrix as the top two rows of the *basic* Jacobian, whose six rows are the linear and
# angular velocity $[v; \omega]$ of the hand. The third angular row shows that both joints turn the hand about
# $z$ at the sum of their rates.

# %%
J = jacobian(robot)
display(Math(r"{}^0J = " + latex(J)))
check(J[:2, :], J_f, robot)

# %% [markdown]
# ## The velocity map depends on the configuration
#
# Pick two configurations and the same joint rates. The hand moves differently: the Jacobian is a *local* linear
# map, evaluated where the arm is.

# %%
qdot = np.array([1.0, -0.5])
for q in ([0.3, 1.2], [0.3, 0.05]):
    J_num = numeric_jacobian(robot, q)[:2, :]
    print(f"q = {q}: hand velocity = {np.round(J_num @ qdot, 4)} m/s")

# %% [markdown]
# ## Picturing the map: velocity ellipses
#
# Joint rates on the unit circle, $\|\dot q\| = 1$, are mapped by $J$ to an ellipse of hand velocities. Its axes
# are the singular values of $J$. Far from a singularity the ellipse is round-ish; as $\theta_2 \to 0$ (the arm
# stretched out) it flattens into a segment: the hand cannot move along the arm.

# %%
angles = np.linspace(0, 2 * np.pi, 200)
circle = np.vstack([np.cos(angles), np.sin(angles)])
fig, ax = plt.subplots(figsize=(6, 6))
L1, L2 = (float(robot.defaults[s]) for s in sp.symbols("L1 L2", real=True))
for q2 in (2.0, 1.2, 0.6, 0.15):
    q = np.array([0.4, q2])
    elbow = np.array([L1 * np.cos(q[0]), L1 * np.sin(q[0])])
    hand = elbow + L2 * np.array([np.cos(q.sum()), np.sin(q.sum())])
    ax.plot([0, elbow[0], hand[0]], [0, elbow[1], hand[1]], "k-o", lw=1)
    ellipse = numeric_jacobian(robot, q)[:2, :] @ circle
    ax.plot(hand[0] + 0.2 * ellipse[0], hand[1] + 0.2 * ellipse[1], label=f"theta2 = {q2}")
ax.set_aspect("equal")
ax.set_title("Hand velocities for unit joint rates (scaled by 0.2)")
ax.legend()
fig.savefig(OUTPUT / "01_velocity_ellipses.png", dpi=100)

# %% [markdown]
# The ellipse's area is proportional to $|\det J|$. For this arm the determinant does not depend on $\theta_1$ at
# all: turning the whole arm about the base changes nothing about how well it can move.

# %%
det = sp.factor(sp.simplify(J_f.det()))
display(Math(r"\det J = " + latex(det)))

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. Write down $\partial x / \partial \theta_2$ for this arm.
# 2. At $\theta_1 = 0$, $\theta_2 = \pi/2$, which hand velocity $(v_x, v_y)$ do the joint rates $(1, 0)$ produce
#    (in terms of $L_1$, $L_2$)?
# 3. For which values of $\theta_2$ does the velocity ellipse degenerate into a segment?

# %%
L1_s, L2_s = sp.symbols("L1 L2", real=True)
answer_1 = ...  # your answer here
check(answer_1, J_f[0, 1], robot)

# %%
answer_2 = ...  # your answer here
check(answer_2, (J_f * sp.Matrix([1, 0])).subs({theta1: 0, theta2: sp.pi / 2}), robot)

# %%
answer_3 = ...  # your answer here
check_set(answer_3, sp.solveset(sp.sin(theta2), theta2, sp.Interval.Ropen(0, 2 * sp.pi)))
print("all answers correct")
