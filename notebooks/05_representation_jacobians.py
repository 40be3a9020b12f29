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
# # 5. Representation Jacobians and gimbal lock
#
# **What you will learn**
#
# * the difference between the *basic* Jacobian $J_0$, whose rows are the velocity $v$ and the angular velocity
#   $\omega$, and a *representation* Jacobian $J_x = E(x)\,J_0$, whose rows are the rates of whatever coordinates
#   $x$ describe the pose (Euler angles, roll-pitch-yaw, a quaternion, ...);
# * that $E(x)$ can itself be singular (Z-Y-Z Euler angles at $\beta = 0$: *gimbal lock*) even though the arm is
#   perfectly able to move: a singularity of the description, not of the robot;
# * how to tell the two apart, on the PUMA 560.

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp  # noqa: F401  # for your answers to the exercises
from IPython.display import Math, display

from symjac import (
    extract,
    latex,
    load_robot,
    numeric_jacobian,
    rate_matrix,
    representation_jacobian,
    representation_jacobian_at,
    rotation_from,
)
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## Z-Y-Z Euler angles and their rate matrix
#
# With rotations about the moving axes, $R = R_z(\alpha)\,R_y(\beta)\,R_z(\gamma)$. The angular velocity is a
# combination of the three rotation axes weighted by the angle rates; inverting that relation gives
# $\dot x_r = E_r(x)\,\omega$:

# %%
display(Math(r"R_{ZYZ} = " + latex(rotation_from("zyz"))))
E_r = rate_matrix("zyz")
display(Math(r"E_r = " + latex(E_r)))

# %% [markdown]
# $E_r$ divides by $\sin\beta$. At $\beta = 0$ the first and last rotations are about the same axis; only
# $\alpha + \gamma$ is defined, and no finite $(\dot\alpha, \dot\beta, \dot\gamma)$ produces a rotation about the
# missing axis. symjac reports this apart from the arm's own singularities:

# %%
puma = load_robot("puma560")
zyz = representation_jacobian(puma, "zyz")
for singularity in zyz.singularities:
    print(singularity)

# %% [markdown]
# ## Two ways to lose a direction
#
# Walk the PUMA along two paths and watch the smallest singular value of the basic Jacobian $J_0$ (the arm) and
# the condition number of $J_x$ (the arm *plus* its description):
#
# * path A turns joint 5 through $0$: a **kinematic** (wrist) singularity;
# * path B keeps the arm at $\theta_1 = 0.3$, $\theta_2 = -0.6$, $\theta_3 = 1.2$, $\theta_4 = 0$ and turns joint 5
#   through $-0.6 = -(\theta_2 + \theta_3)$, where the tool points straight down: the Z-Y-Z angles reach
#   $\beta = \pi$ (gimbal lock), while the arm itself is nowhere near singular.

# %%
s = np.linspace(-0.4, 0.4, 81)
path_a = np.array([[0.3, -0.6, 1.2, 0.4, v, 0.2] for v in s])
path_b = np.array([[0.3, -0.6, 1.2, 0.0, -0.6 + v, 0.2] for v in s])


def along(path):
    """Smallest singular value of J_0 and condition number of the Z-Y-Z J_x at each configuration."""
    smallest, condition = [], []
    for q in path:
        smallest.append(np.linalg.svd(numeric_jacobian(puma, q), compute_uv=False).min())
        try:
            J_x = representation_jacobian_at(puma, q, "zyz").J_x
            condition.append(np.linalg.cond(J_x))
        except ValueError:  # exactly on the representation singularity
            condition.append(np.nan)
    return np.array(smallest), np.array(condition)


fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=False)
for ax, path, title in ((axes[0], path_a, "A: theta5 through 0 (wrist)"),
                        (axes[1], path_b, "B: tool through straight down (gimbal lock)")):
    smallest, condition = along(path)
    ax.semilogy(s, smallest, label="smallest singular value of J_0")
    ax.semilogy(s, 1 / condition, label="1 / condition number of J_x")
    ax.set_title(title)
    ax.set_xlabel("path parameter")
    ax.legend()
fig.savefig(OUTPUT / "05_gimbal_lock_vs_wrist.png", dpi=100)

# %% [markdown]
# On path A both curves dive: the arm really cannot rotate about one axis there, in any description. On path B
# only $J_x$ degrades; $J_0$ stays well conditioned. Switching to another description (roll-pitch-yaw, or a
# quaternion, which has no singularity at all) makes path B harmless:

# %%
q_b = [0.3, -0.6, 1.2, 0.0, -0.6 + 0.01, 0.2]  # 0.01 rad from the lock
for name in ("zyz", "rpy", "quaternion"):
    J_x = representation_jacobian_at(puma, q_b, name).J_x
    print(f"{name:>10}: condition number of J_x = {np.linalg.cond(J_x):10.1f}")

# %% [markdown]
# ## Extracting Euler angles from a rotation matrix
#
# Away from gimbal lock there are two solutions ($\beta > 0$ and $\beta < 0$); symjac returns the one with
# $\beta \in [0, \pi]$. At $\beta = 0$ only $\alpha + \gamma$ is determined; by convention $\alpha = 0$ and the whole
# rotation goes into $\gamma$.

# %%
R = np.array(rotation_from("zyz", [0.4, 0.0, 0.9]), dtype=float)
print("angles from R at gimbal lock:", extract("zyz", R).round(6))

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. Where is the roll-pitch-yaw description singular? Give the factor that vanishes.
# 2. Compute by hand the Z-Y-Z angles of $R_z(0.3)$ (a pure rotation about $z$), using the convention above.
# 3. Which row of $E_r$ for Z-Y-Z angles never divides by $\sin\beta$? (Give the row as a 1 x 3 matrix.)

# %%
theta_rpy = representation_jacobian(puma, "rpy").coordinates[4]
answer_1 = ...  # your answer here
check(answer_1, representation_jacobian(puma, "rpy").singularities[0].factor)

# %%
answer_2 = ...  # your answer here
check(answer_2, list(extract("zyz", np.array(rotation_from("zyz", [0, 0, 0.3]), dtype=float))))

# %%
alpha = zyz.coordinates[3]
answer_3 = ...  # your answer here
check(answer_3, E_r[1, :])
print("all answers correct")
