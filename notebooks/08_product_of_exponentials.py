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
# # 8. The product of exponentials: the UR5 by screw axes
#
# **What you will learn**
#
# * how a robot is described without Denavit-Hartenberg frames: the pose $M$ of the tool at the home
#   configuration and one screw axis $\mathcal{S}_i = (\omega_i, v_i)$ per joint, as in Lynch and Park's
#   *Modern Robotics*;
# * that the forward kinematics is then $T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_6]\theta_6}
#   M$, each factor a rotation about (or a slide along) a fixed line in space;
# * what the space Jacobian $J_s$ and the body Jacobian $J_b$ are, and that they are the Jacobian you already know
#   seen from another frame and another point.
#
# Screws and twists are written angular part first, $(\omega, v)$, as in the book; symjac's basic Jacobian puts
# $v$ first.

# %%
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symjac import (
    body_jacobian,
    exponential_product,
    forward_kinematics,
    jacobian,
    latex,
    load_robot,
    numeric_jacobian,
    space_jacobian,
)
from symjac.model.conventions.poe import home_pose
from symjac.teaching.exercises import check

# %% [markdown]
# ## The robot file
#
# The catalog robot `ur5_poe` holds the UR5 with the book's dimensions ($W_1 = 0.109$, $W_2 = 0.082$,
# $L_1 = 0.425$, $L_2 = 0.392$, $H_1 = 0.089$, $H_2 = 0.095$, in metres). At home the arm lies stretched along the
# x-axis of the space frame {s}. Each row of the table is one joint: its axis direction $\omega_i$, its $v_i$, and a
# point $q_i$ of the axis ($v_i = -\omega_i \times q_i$).

# %%
robot = load_robot("ur5_poe")
for joint in robot.joints:
    omega, v = joint.placement.omega, joint.placement.v
    print(joint.index, "omega =", list(omega), " v =", list(v))
M = home_pose(robot)
display(Math("M = " + latex(M)))

# %% [markdown]
# ## Forward kinematics as a product of exponentials
#
# Each exponential is Rodrigues' formula in closed form. Multiplied out, they give the same pose as symjac's chain
# of link transforms, entry by entry.

# %%
T_product = exponential_product(robot)
T_chain = forward_kinematics(robot, 0, "tool")
assert sp.simplify(T_product - T_chain) == sp.zeros(4, 4)
display(Math(r"T(\theta) = " + latex(T_chain)))

# %% [markdown]
# ## The space Jacobian
#
# Column $i$ of $J_s(\theta)$ is joint $i$'s screw axis at the current configuration, in {s}: the axis has been
# carried along by the joints before it. At $\theta = 0$ the columns are the screws of the table.

# %%
J_s = space_jacobian(robot)
display(Math("J_s = " + latex(J_s)))
assert J_s.xreplace(dict.fromkeys(robot.q, 0)) == sp.Matrix([j.placement.screw for j in robot.joints]).T

# %% [markdown]
# ## The body Jacobian
#
# $J_b = [\mathrm{Ad}_{T^{-1}}] J_s$ gives the twist in the tool frame. It is the basic Jacobian at the tool point,
# expressed in the tool frame, with its two halves swapped.

# %%
J_b = body_jacobian(robot)
display(Math("J_b = " + latex(J_b)))
J_tool = jacobian(robot, frame="tool", point="tool")
assert J_b == sp.Matrix.vstack(J_tool[3:, :], J_tool[:3, :])

# %% [markdown]
# ## The same arm from its DH table
#
# The catalog's `ur5` is the same arm described by the manufacturer's DH table. With the book's dimensions its
# frame {0} is the space frame turned by $\pi$ about z (its arm points along $-x$ at home), and its frame {6} is the
# tool frame: after that change of frame, its basic Jacobian at the wrist and the PoE robot's at the tool are equal.

# %%
dh = load_robot("ur5")
book = {"d1": 0.089, "a2": -0.425, "a3": -0.392, "d4": 0.109, "d5": 0.095, "d6": 0.082}
q = np.array([0.3, -1.1, 0.8, 0.4, -0.6, 1.2])
turn = np.kron(np.eye(2), np.diag([-1.0, -1.0, 1.0]))
J_dh = np.array(jacobian(dh).subs({sp.Symbol(k, real=True): v for k, v in book.items()})
                .subs(dict(zip(dh.q, q, strict=True))), dtype=float)
J_poe = numeric_jacobian(robot, q, frame=0, point="tool")
print("largest difference:", np.abs(turn @ J_dh - J_poe).max())
assert np.allclose(turn @ J_dh, J_poe, atol=1e-12)

# %% [markdown]
# For the exercises, the shorthand of the first joints:

# %%
theta1, theta2 = robot.q[0], robot.q[1]
H1, L1 = sp.symbols("H1 L1")

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly with
# what symjac derives (plain `sp.symbols("H1 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. Column 2 of $J_s$ is joint 2's screw axis after joint 1 has turned by $\theta_1$. Write it as a 6-vector
#    $(\omega_2, v_2)$.
# 2. Joint 1's axis passes through the origin of {s}. What is column 1 of $J_s$, whatever $\theta$?
# 3. Which column of $J_b$ never changes with $\theta$ (give its index, 1 to 6)?

# %%
answer_1 = ...  # your answer here
check(answer_1, J_s[:, 1], robot)

# %%
answer_2 = ...  # your answer here
check(answer_2, J_s[:, 0], robot)

# %%
answer_3 = ...  # your answer here
check(answer_3, 6, robot)
print("all answers correct")
