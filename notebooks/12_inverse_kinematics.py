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
# # 12. Inverse kinematics: every configuration that reaches a pose
#
# **What you will learn**
#
# * why the planar 2R arm reaches most points in two ways, elbow up and elbow down, and where the two meet;
# * how `symjac.inverse_kinematics` finds every solution: in closed form where the geometry of the arm allows it
#   (and it says which fact of the geometry that is), else with a numeric solver started from several seeds;
# * the PUMA 560's eight postures for one pose of its hand: shoulder left or right, elbow up or down, wrist flipped
#   or not;
# * which parts of a pose an arm with fewer than six joints does not control.
#
# A pose is the 4 x 4 transform of the end of the chain in frame {0}, as `numeric_model(robot).fk(q)` returns it.
# Build one from a position and URDF's roll, pitch, yaw ($R = R_z(\text{yaw}) R_y(\text{pitch}) R_x(\text{roll})$)
# with `pose_from_rpy`, or from a unit quaternion (w first) with `pose_from_quaternion`.

# %%
import os
from pathlib import Path

import numpy as np
from IPython.display import display

from symjac import inverse_kinematics, load_robot, numeric_model, pose_from_rpy
from symjac.drawing.solutions import draw_solutions
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The 2R arm: elbow up and elbow down
#
# The tip of the planar 2R arm is at $x = L_1 c_1 + L_2 c_{12}$, $y = L_1 s_1 + L_2 s_{12}$. The law of cosines
# gives the elbow, $c_2 = (x^2 + y^2 - L_1^2 - L_2^2) / (2 L_1 L_2)$, and two angles have that cosine,
# $\theta_2 = \pm \arccos c_2$: the two branches (the solver calls $+\arccos c_2$ elbow down, as the textbook does,
# and $-\arccos c_2$ elbow up). Each fixes the shoulder,
# $\theta_1 = \operatorname{atan2}(y, x) - \operatorname{atan2}(L_2 s_2, L_1 + L_2 c_2)$. When $|c_2| > 1$ the point is
# out of reach; at $c_2 = \pm 1$ (arm stretched or folded) the two branches meet: a singular configuration.

# %%
planar = load_robot("planar2r")
L1, L2 = 0.5, 0.4  # the catalog's defaults
x, y = 0.6, 0.3
c2 = (x**2 + y**2 - L1**2 - L2**2) / (2 * L1 * L2)
by_hand = []
for theta2 in (np.arccos(c2), -np.arccos(c2)):
    theta1 = np.arctan2(y, x) - np.arctan2(L2 * np.sin(theta2), L1 + L2 * np.cos(theta2))
    by_hand.append([theta1, theta2])
print("by hand:", np.round(by_hand, 6).tolist())

result = inverse_kinematics(planar, pose_from_rpy([x, y, 0.0], [0.0, 0.0, 0.0]))
print(result.why)
print("the arm sets", result.controlled.sets, "; not", result.controlled.not_set)
for solution in result.solutions:
    print(np.round(solution.q, 6).tolist(), solution.branch, f"misses by {solution.position_error:.1e} m")

# %%
figure = draw_solutions(planar, result, view=(-90.0, 90.0))
figure.savefig(OUTPUT / "planar2r_elbows.png", dpi=90)
display(figure)

# %% [markdown]
# ## The PUMA 560's eight postures
#
# The PUMA's last three axes meet at the wrist centre, so its position depends on the first three joints only:
# those are solved first (two shoulders times two elbows), then the wrist's orientation (two ways to flip it).
# Outside the joint limits some of the eight are not available to the real arm: `within_limits=False` keeps them,
# each flagged.

# %%
puma = load_robot("puma560")
q_made = np.array([0.4, -0.6, 0.3, 0.5, 0.7, -0.2])
pose = numeric_model(puma).fk(q_made)
postures = inverse_kinematics(puma, pose, within_limits=False)
print(postures.method, "-", postures.why)
for solution in postures.solutions:
    flag = "" if solution.within_limits else "  (outside the limits)"
    print(np.round(solution.q, 3).tolist(), ", ".join(solution.branch) + flag)

# %%
figure = draw_solutions(puma, postures)
figure.savefig(OUTPUT / "puma560_postures.png", dpi=60)
display(figure)

# %% [markdown]
# ## Arms without a closed form: the numeric solver
#
# The Panda's seven axes meet nowhere useful, so there is no closed form: `inverse_kinematics` says why and runs
# Levenberg-Marquardt on the compiled forward kinematics and Jacobian from several random seeds (deterministic for a
# given `rng`). A redundant arm reaches a pose in infinitely many ways; each start finds one of them.

# %%
panda = load_robot("panda")
q_panda = np.array([0.1, 0.2, 0.3, -1.5, 0.2, 1.0, 0.3])
found = inverse_kinematics(panda, numeric_model(panda).fk(q_panda))
print(found.method, "-", found.why)
for solution in found.solutions:
    print(np.round(solution.q, 3).tolist(), f"misses by {solution.position_error:.1e} m")

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer and run the cell; `check` compares numbers to $10^{-6}$. Worked answers:
# `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. The 2R arm's tip at $(x, y) = (0.3, 0.6)$: what is $\theta_2$ of the elbow-down branch (the solver's name for
#    $\theta_2 = +\arccos c_2$, the textbook's)?
# 2. How far beyond the 2R arm's reach is the point $(1.2, 0)$, in metres?
# 3. How many configurations (within the limits or not) does the PUMA 560 have for the pose `pose` above?

# %%
answer_1 = ...  # your answer here
check(answer_1, np.arccos((0.3**2 + 0.6**2 - L1**2 - L2**2) / (2 * L1 * L2)), tolerance=1e-6)

# %%
answer_2 = ...  # your answer here
check(answer_2, 1.2 - (L1 + L2), tolerance=1e-6)

# %%
answer_3 = ...  # your answer here
check(answer_3, len(postures.solutions))
print("all answers correct")
