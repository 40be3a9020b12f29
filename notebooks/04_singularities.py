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
# # 4. Singularities: where the Jacobian loses rank, and what the arm loses there
#
# **What you will learn**
#
# * that an arm is singular where $\det J = 0$ (for the rows of $J$ it controls), and how to read the factored
#   determinant: each factor is one kind of singularity;
# * the elbow singularity of the planar 2R arm (stretched out or folded back, on the edge of the workspace);
# * the shoulder singularity of a spatial 3R arm, which only exists if the links are long enough;
# * the wrist, elbow and shoulder singularities of the PUMA 560;
# * why a palletizer with coupled joints has a square Jacobian, and where it is singular;
# * what happens at a singularity: a direction the hand cannot move in, a force it holds with no torque, a joint
#   motion that moves nothing, and joint rates that blow up nearby.

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Markdown, Math, display

from symjac import jacobian, latex, load_robot, numeric_jacobian, rates_along_path, singularities
from symjac.analysis.spaces import jacobian_spaces, symbolic_spaces
from symjac.printing import singularity_summary
from symjac.teaching.exercises import check, check_set

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)


def show(report):
    """Show a singularity report: each caption as text with its math typeset, each equation as LaTeX."""
    for caption, equation in singularity_summary(report):
        display(Markdown(caption))
        if equation:
            display(Math(equation))


# %% [markdown]
# ## The planar 2R arm: the elbow
#
# A planar arm controls only $x$ and $y$, so the determinant is taken of those two rows. symjac chooses them, and
# the frame in which the Jacobian is shortest (the determinant is the same in every frame).

# %%
planar = load_robot("planar2r")
report_2r = singularities(planar)
show(report_2r)

# %% [markdown]
# At $\theta_2 = 0$ the arm is stretched out: the hand can move sideways, but not along the arm (radially). The
# force along the arm is held by the structure alone: $J^T F = 0$.

# %% [markdown]
# ## A spatial 3R arm: elbow and shoulder
#
# This arm has a vertical first axis, a shoulder offset $L_1$ and two parallel joints; the point of interest is
# frame {4} at the end of the last link. The position rows give

# %%
arm = load_robot("articulated3r")
report_3r = singularities(arm)
show(report_3r)

# %% [markdown]
# Two conditions. $s_3 = 0$ is an elbow singularity again. The second factor vanishes when the point lies on the
# first joint's axis (a shoulder singularity, *inside* the workspace); the arm can only get there if
# $L_2 + L_3 \ge L_1$. Exactly, at $\theta_3 = 0$ in frame {4}:

# %%
spaces = symbolic_spaces(arm, {arm.q[2]: 0}, frame="tool")
display(Math(r"{}^4J\big|_{\theta_3=0} = " + latex(spaces.jacobian)))
display(Math(r"\text{lost direction (left null space)} = " + latex(spaces.left_null_space)))
display(Math(r"\text{self-motion (null space)} = " + latex(spaces.null_space)))

# %% [markdown]
# ### Manipulability over the joint space
#
# $w = \sqrt{\det(J J^T)}$ measures how well the arm can move in all directions at once. Over a grid of
# $(\theta_2, \theta_3)$ it drops to zero exactly along the singular curves found above (drawn in white).

# %%
t2 = np.linspace(-np.pi, np.pi, 121)
t3 = np.linspace(-np.pi, np.pi, 121)
w = np.array([[jacobian_spaces(numeric_jacobian(arm, [0.0, a, b], point="tool")[:3, :]).manipulability
               for a in t2] for b in t3])
L1, L2, L3 = (float(arm.defaults[sp.Symbol(n, real=True)]) for n in ("L1", "L2", "L3"))
A2, A3 = np.meshgrid(t2, t3)
fig, ax = plt.subplots(figsize=(6, 5))
image = ax.pcolormesh(A2, A3, w, shading="auto")
ax.contour(A2, A3, np.sin(A3), levels=[0], colors="white", linestyles="--")
ax.contour(A2, A3, L1 + L2 * np.cos(A2) + L3 * np.cos(A2 + A3), levels=[0], colors="white")
ax.set_xlabel("theta2")
ax.set_ylabel("theta3")
ax.set_title("Manipulability of the 3R arm; singular curves in white")
fig.colorbar(image)
fig.savefig(OUTPUT / "04_manipulability.png", dpi=100)

# %% [markdown]
# ### Joint rates near the shoulder singularity
#
# Command a constant velocity along $z$ of the tool frame, $\dot z = 0.1$ m/s, and walk $\theta_2$ towards the
# shoulder curve. The closed form $\dot\theta_1 = \dot z / (-L_1 - L_2 c_2 - L_3 c_{23})$ blows up; damped least
# squares keeps the rates bounded at the price of not quite producing the commanded velocity.

# %%
theta3 = 1.0
crossing = float(sp.nsolve(L1 + L2 * sp.cos(sp.Symbol("x")) + L3 * sp.cos(sp.Symbol("x") + theta3), 2.0))
path = np.array([[0.0, crossing - d, theta3] for d in np.geomspace(0.5, 1e-4, 60)])
rates = rates_along_path(arm, path, xdot=[0.0, 0.0, 0.1], frame="tool")
distance = crossing - path[:, 1]
fig, ax = plt.subplots(figsize=(7, 4))
ax.loglog(distance, np.abs(rates.exact[:, 0]), label="exact inverse, |theta1 rate|")
ax.loglog(distance, np.abs(rates.damped[:, 0]), label="damped least squares")
ax.invert_xaxis()
ax.set_xlabel("distance of theta2 from the singular curve (rad)")
ax.set_ylabel("rad/s")
ax.legend()
fig.savefig(OUTPUT / "04_rates_near_singularity.png", dpi=100)

# %% [markdown]
# ## The PUMA 560: wrist, elbow, shoulder
#
# Six rows, six joints. The determinant factors into the three classic conditions: $s_5 = 0$ (the wrist axes 4
# and 6 line up), the elbow condition in $\theta_3$ and the shoulder condition (the wrist centre above the first
# axis, offset by $d_3$).

# %%
show(singularities(load_robot("puma560")))

# %% [markdown]
# ## A palletizer: five joints, four coordinates, a square Jacobian
#
# A palletizer stacks boxes: it only needs the box's position and its heading about the vertical, four numbers.
# The catalog `palletizer` has five revolute joints, but a parallelogram linkage ties the fourth to the second and
# third, $\theta_4 = -(\theta_2 + \theta_3)$, so the flange stays level whatever the shoulder and elbow do. Its robot
# file says so with `coupled = "-theta2 - theta3"` on joint 4, and symjac works in the four independent coordinates
# $(\theta_1, \theta_2, \theta_3, \theta_5)$: the Jacobian has four columns, $J_q = J(\theta(q))\,C$ with the
# constant $C = \partial\theta/\partial q$.

# %%
palletizer = load_robot("palletizer")
print("coordinates:", palletizer.q, " joint variables:", palletizer.joint_values)
J_pal = jacobian(palletizer)
display(Math(r"J_q = " + latex(J_pal)))

# %% [markdown]
# The rows $\omega_x$ and $\omega_y$ are zero everywhere: the linkage removes the two tilts, so the flange cannot
# roll or pitch. The four rows $v_x, v_y, v_z, \omega_z$ that are left against four columns make a square matrix,
# and its determinant says where the palletizer is singular: the elbow stretched out or folded back
# ($\sin\theta_3 = 0$), and the flange point above the base axis (the radius $L_1 + L_2 c_2 + L_3 c_{23} + L_4$
# is zero), where turning the base no longer moves it sideways.

# %%
assert J_pal[3:5, :] == sp.zeros(2, 4)
show(singularities(palletizer))

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. What is $\det J$ of the planar 2R arm? Give it as an expression in $L_1, L_2, \theta_2$.
# 2. For which $\theta_5$ is the PUMA 560 in its wrist singularity (give the set in $[0, 2\pi)$)?
# 3. Make the 3R arm's first link long, $L_1 = 1$, with $L_2 = 0.25$, $L_3 = 0.5$. Can it reach its shoulder
#    singularity? (symjac evaluates the existence condition for the robot's parameters.)

# %%
L1_s, L2_s = sp.symbols("L1 L2", real=True)
answer_1 = ...  # your answer here
check(answer_1, report_2r.determinant.expression, planar)

# %%
puma_report = singularities(load_robot("puma560"))
(wrist,) = [f for f in puma_report.factors if f.kind == "wrist"]
answer_2 = ...  # your answer here
check_set(answer_2, {s.rhs for s in wrist.solutions})

# %%
from symjac import robot_from_mapping, robot_to_mapping  # noqa: E402

data = robot_to_mapping(arm)
data["parameters"] = {"L1": 1, "L2": 0.25, "L3": 0.5}
short = singularities(robot_from_mapping(data))
shoulder = next(f for f in short.factors if f.expression.has(arm.q[1]))
answer_3 = ...  # your answer here
check(answer_3, shoulder.exists_for_defaults)
print(shoulder.existence, "->", shoulder.exists_for_defaults)
print("all answers correct")
