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
# # 10. Dynamics: Lagrange and Newton-Euler side by side
#
# **What you will learn**
#
# * how the equations of motion $\tau = M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q)$ come out of the energies:
#   the kinetic energy $T = \tfrac12 \dot q^T M(q)\,\dot q$, the potential energy $V(q)$, and the Euler-Lagrange
#   equations $\tau_i = \frac{d}{dt}\frac{\partial L}{\partial \dot q_i} - \frac{\partial L}{\partial q_i}$ of
#   $L = T - V$;
# * how the recursive Newton-Euler algorithm gets the same torques link by link: velocities and accelerations
#   outward from the base (gravity enters as an upward acceleration of the base), then forces and moments inward
#   from the tip, the torque of each joint the component of the moment along its axis;
# * why $\dot M - 2C$ is skew-symmetric when $C$ comes from the Christoffel symbols;
# * what the PUMA 560 needs from its motors just to hold still: its gravity torques $g(q)$.

# %%
import dataclasses
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symjac import (
    Gravity,
    coriolis_matrix,
    euler_lagrange,
    gravity_torques,
    latex,
    load_robot,
    mass_matrix,
    newton_euler,
)
from symjac.analysis.dynamics import kinetic_energy, potential_energy
from symjac.model.inertia import Inertial
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.printing import propagation_steps
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The planar 2R arm with its masses on the links
#
# Link $i$ has mass $m_i$, its centre of mass on the link line at $l_{ci}$ from joint $i$, and the moment of
# inertia $I_i$ about the centre of mass (axis normal to the plane). In the standard DH frames of `planar2r`,
# frame $\{i\}$ sits at the *far* end of link $i$, so the centre of mass is at $x = l_{ci} - L_i$ in $\{i\}$.
# Gravity pulls along $-y_0$, in the arm's plane.

# %%
m1, m2, lc1, lc2, I1, I2 = sp.symbols("m1 m2 lc1 lc2 I1 I2", positive=True)
planar = load_robot("planar2r")  # its file gives each link ten symbols, m1, cx1, .., Izz2: here, our own
L1, L2 = (parameter.symbol for parameter in planar.geometric_parameters)
arm = dataclasses.replace(planar, parameters=planar.geometric_parameters, inertials=(
    Inertial(m1, com=(lc1 - L1, 0, 0), inertia=sp.diag(0, 0, I1)),
    Inertial(m2, com=(lc2 - L2, 0, 0), inertia=sp.diag(0, 0, I2))))
down_y = Gravity(direction=(0, -1, 0))
theta1, theta2 = arm.q
qd, qdd = sp.Matrix(arm.coordinate_rates), sp.Matrix(arm.coordinate_accelerations)

# %% [markdown]
# ## Lagrange: the energies first
#
# symjac sums each link's translational and rotational kinetic energy, from the Jacobian of its centre of mass, and
# each link's potential energy $-m_i\,g_0^T p_{ci}$:

# %%
T = kinetic_energy(arm)
V = potential_energy(arm, down_y)
display(Math("T = " + latex(T)))
display(Math("V = " + latex(V)))

# %% [markdown]
# $T$ is a quadratic form in the joint rates; its matrix is the mass matrix. The Coriolis matrix comes from the
# Christoffel symbols of $M$, $C_{kj} = \sum_i \tfrac12\left(\frac{\partial M_{kj}}{\partial q_i} +
# \frac{\partial M_{ki}}{\partial q_j} - \frac{\partial M_{ij}}{\partial q_k}\right)\dot q_i$, and the gravity
# torques are $g = \partial V/\partial q$. The textbook's mass matrix, symbol for symbol:

# %%
M = mass_matrix(arm)
C = coriolis_matrix(arm)
g = gravity_torques(arm, down_y)
for name, value in (("M", M), ("C", C), ("g", g)):
    display(Math(f"{name} = " + latex(value)))
textbook = sp.Matrix([
    [m1 * lc1**2 + m2 * (L1**2 + lc2**2 + 2 * L1 * lc2 * sp.cos(theta2)) + I1 + I2,
     m2 * (lc2**2 + L1 * lc2 * sp.cos(theta2)) + I2],
    [m2 * (lc2**2 + L1 * lc2 * sp.cos(theta2)) + I2, m2 * lc2**2 + I2]])
check(M, textbook, arm)
check(sp.expand(qd.T * M * qd / 2)[0], T, arm)  # T = 1/2 qdot^T M qdot

# %% [markdown]
# The Euler-Lagrange equations give the torques directly:

# %%
tau_lagrange = euler_lagrange(arm, down_y)
display(Math(r"\tau = " + latex(tau_lagrange)))

# %% [markdown]
# ## Newton-Euler: link by link
#
# Outward, each link's angular velocity $\omega_i$, angular acceleration $\alpha_i$, the acceleration $a_i$ of its
# frame's origin and $a_{c_i}$ of its centre of mass, then the force $F_i = m_i a_{c_i}$ and moment
# $N_i = I_i \alpha_i + \omega_i \times I_i \omega_i$ that move it; inward from the tip, the force $f_i$ and moment
# $n_i$ the previous link exerts on it, and $\tau_i$. Every vector is written in the link's own frame. The base
# accelerates *upwards* at $g$: that is how gravity enters (look at $a_1$).

# %%
recursion = newton_euler(arm, down_y)
for line in propagation_steps(recursion):
    display(Math(line))

# %% [markdown]
# ## Side by side: the same torques
#
# Two derivations that share nothing but the model give the same $\tau$, and it splits into
# $M\ddot q + C\dot q + g$:

# %%
tau_newton_euler = recursion.torques
display(Math(r"\tau_{\text{Lagrange}} = " + latex(tau_lagrange)))
display(Math(r"\tau_{\text{Newton-Euler}} = " + latex(tau_newton_euler)))
check(tau_newton_euler, tau_lagrange, arm)
check(tau_newton_euler, M * qdd + C * qd + g, arm)

# %% [markdown]
# ## $\dot M - 2C$ is skew-symmetric
#
# With $C$ from the Christoffel symbols, $\dot q^T(\dot M - 2C)\,\dot q = 0$ for every motion: the Coriolis and
# centrifugal forces do no work. Here is the matrix itself:

# %%
M_dot = sp.Matrix(2, 2, lambda i, j: sum(M[i, j].diff(q) * rate for q, rate in zip(arm.q, qd, strict=True)))
skew = sp.simplify(M_dot - 2 * C)
display(Math(r"\dot M - 2C = " + latex(skew)))
check(skew + skew.T, sp.zeros(2, 2), arm)

# %% [markdown]
# ## Where the torque goes along a motion
#
# The arm swings both joints as $\theta_i(t) = \tfrac{\pi}{3}\sin t$ (link lengths and masses of a small arm:
# $L_1 = 0.5$ m, $L_2 = 0.4$ m, 2 kg and 1.5 kg, centres at mid-link, slender rods). The shoulder's torque is the
# sum of three parts; gravity is the largest at this speed.

# %%
numbers = {L1: 0.5, L2: 0.4, m1: 2.0, m2: 1.5, lc1: 0.25, lc2: 0.2, I1: 2.0 * 0.5**2 / 12, I2: 1.5 * 0.4**2 / 12,
           sp.Symbol("g", positive=True): 9.81}
variables = [*arm.q, *qd, *qdd]
parts = {"M qdd": M * qdd, "C qd": C * qd, "g": g}
shoulder = {name: sp.lambdify(variables, value[0].xreplace(numbers), "numpy") for name, value in parts.items()}
t = np.linspace(0, 2 * np.pi, 200)
angle, rate, acceleration = np.pi / 3 * np.sin(t), np.pi / 3 * np.cos(t), -np.pi / 3 * np.sin(t)
values = [angle, angle, rate, rate, acceleration, acceleration]
fig, ax = plt.subplots(figsize=(7, 4))
for name, function in shoulder.items():
    ax.plot(t, np.broadcast_to(function(*values), t.shape), label=name)
ax.plot(t, sum(np.broadcast_to(f(*values), t.shape) for f in shoulder.values()), "k--", label="tau1")
ax.set_xlabel("t (s)")
ax.set_ylabel("N m")
ax.set_title("The shoulder's torque and its three parts")
ax.legend()
fig.savefig(OUTPUT / "10_torque_parts.png", dpi=100)

# %% [markdown]
# ## The 3R arm, with every inertial parameter a symbol
#
# The catalog's planar 3R arm, like every catalog arm without published data, gives each link the ten parameters
# $m_i$, $c_{xi}, c_{yi}, c_{zi}$ (centre of mass in $\{i\}$) and $I_{xx\,i}, \dots, I_{zz\,i}$ (inertia about the
# centre of mass, axes of $\{i\}$); `with_symbolic_inertials` does the same for any robot. The two methods still
# agree exactly; only the $z$-axis moments and the in-plane centre coordinates survive in a planar arm.

# %%
arm3 = load_robot("planar3r")
tau3_newton_euler = newton_euler(arm3, down_y).torques
tau3_lagrange = euler_lagrange(arm3, down_y)
check(tau3_newton_euler, tau3_lagrange, arm3)
display(Math(r"\tau_3 = " + latex(tau3_newton_euler[2])))
print("symbols in tau:", sorted(str(s) for s in tau3_newton_euler.free_symbols if str(s)[0] in "mcI"))

# %% [markdown]
# ## The PUMA 560 holding still
#
# Standing still, $\dot q = \ddot q = 0$, the motors supply only $g(q)$. For the PUMA with symbolic inertial
# parameters (gravity along $-z_0$, the base's vertical axis):

# %%
puma = with_symbolic_inertials(load_robot("puma560"))
g_puma = gravity_torques(puma)
for i in range(6):
    display(Math(f"g_{i + 1} = " + latex(g_puma[i])))

# %% [markdown]
# Joint 1 turns about the vertical: gravity never loads it. Joints 2 and 3 carry the arm; the wrist joints only
# their own small links. The same torques are what `symjac dynamics puma560 --symbolic-inertials
# --gravity-torques` prints, and what a controller's gravity compensation adds to its command.

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("m2 lc2 theta1")` are fine). Worked answers:
# `notebooks/solutions.py`. A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add
# `reveal=True` to the cell's `check(...)`.
#
# 1. For the 2R arm above, what is $M_{22}$, the inertia the elbow's motor sees?
# 2. With gravity along $-y_0$, what is the elbow's gravity torque $g_2$? (Hint: only link 2's weight, acting at
#    its centre of mass, matters.)
# 3. What is the PUMA's gravity torque $g_1$?

# %%
answer_1 = ...  # your answer here
check(answer_1, M[1, 1], arm)

# %%
g_symbol = sp.Symbol("g", positive=True)
answer_2 = ...  # your answer here
check(answer_2, g[1], arm)

# %%
answer_3 = ...  # your answer here
check(answer_3, g_puma[0], puma)
print("all answers correct")
