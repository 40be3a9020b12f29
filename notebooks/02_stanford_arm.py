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
# # 2. The Stanford arm: from a DH table to its Jacobian, two ways
#
# **What you will learn**
#
# * how a Denavit-Hartenberg table (modified, Craig's convention) becomes link transforms ${}^{i-1}_iT$ and the
#   forward kinematics ${}^0_6T$;
# * two derivations of the same Jacobian: differentiating the position of the wrist, and the column formula
#   $J_i = [z_i \times p_{i6};\ z_i]$ (for a prismatic joint $[z_i;\ 0]$);
# * how a Jacobian is re-expressed in another frame, ${}^kJ = \mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J$, and why a
#   middle frame gives much shorter entries;
# * how to find the misprints in a printed matrix by comparing it entry by entry with a derivation.
#
# The Stanford (Scheinman) arm has two revolute joints, a prismatic joint $d_3$ and a spherical wrist.

# %%
import sympy as sp
from IPython.display import Markdown, Math, display

from symjac import chain_of, change_frame, forward_kinematics, is_identity, jacobian, latex, load_robot
from symjac.symbolic.angles import AngleBasis
from symjac.teaching.exercises import check

robot = load_robot("stanford")
chain = chain_of(robot)
basis = AngleBasis.of(j.variable for j in robot.joints if j.is_revolute)

# %% [markdown]
# ## The DH table
#
# In the modified convention row $i$ holds $\alpha_{i-1}, a_{i-1}$ (twist and length of the link *before* joint
# $i$), then $d_i$ and $\theta_i$. The joint variable is added to $\theta_i$ (revolute) or $d_i$ (prismatic).

# %%
rows = ["| $i$ | type | $\\alpha_{i-1}$ | $a_{i-1}$ | $d_i$ | $\\theta_i$ |", "|---|---|---|---|---|---|"]
for joint in robot.joints:
    cells = [latex(value) for value in (joint.placement.alpha, joint.placement.a, joint.d, joint.theta)]
    rows.append(f"| {joint.index} | {joint.type.value} | " + " | ".join(f"${c}$" for c in cells) + " |")
display(Markdown("\n".join(rows)))

# %% [markdown]
# ## Link transforms and forward kinematics
#
# Each row gives ${}^{i-1}_iT = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)$. Multiplying them gives
# the pose of the wrist frame {6} in the base frame {0}.

# %%
for i in range(1, robot.n_joints + 1):
    display(Math(f"{{}}^{{{i - 1}}}_{{{i}}}T = " + latex(chain.simplified_transform(i - 1, i))))

# %%
T_0_6 = forward_kinematics(robot)
display(Math(r"{}^0_6T = " + latex(T_0_6)))

# %% [markdown]
# ## The Jacobian by differentiation
#
# The linear rows are the derivatives of the wrist position ${}^0p_6$; the angular rows are the joint axes $z_i$
# expressed in {0} (zero for the prismatic joint, which does not rotate anything).

# %%
J_diff = jacobian(robot, method="differentiation")
display(Math(r"{}^0J = " + latex(J_diff)))

# %% [markdown]
# ## The Jacobian column by column: $z_i \times p_{i6}$
#
# Column $i$ of a revolute joint is the velocity that a unit rotation about axis $z_i$ gives to the wrist point,
# $z_i \times p_{i6}$, where $p_{i6}$ is the vector from the origin of frame $\{i\}$ to the wrist. symjac computes
# the cross product in frame $\{i\}$, where $z_i = [0, 0, 1]^T$, and rotates it into {0}. The two derivations agree
# exactly:

# %%
J_cross = jacobian(robot, method="cross_product")
check(J_cross, J_diff, robot)

# %% [markdown]
# ## Changing the frame
#
# The same motion can be described in any frame. The entries are shortest in a frame in the middle of the arm:
# here frame {3}.

# %%
R_3_0 = chain.rotation(3, 0)
J_3 = jacobian(robot, frame=3)
display(Math(r"{}^3J = " + latex(J_3)))
check(change_frame(J_diff, R_3_0), J_3, robot)
print("operations in frame 0:", sp.count_ops(J_diff), " in frame 3:", sp.count_ops(J_3))

# %% [markdown]
# ## Where the printed notes disagree with the derivation
#
# Lecture notes are typed by hand. symjac keeps every printed formula of its course notes as data
# (`symjac/errata/formulas.toml`: where it is, and its entries as printed) and compares each one exactly with the
# derivation; `symjac errata` prints the whole errata sheet. Two of the Stanford arm's matrices have misprints:

# %%
from symjac.teaching.errata import compare, formula  # noqa: E402

for identifier in ("000-eq4.87", "000-s4.11.1-J"):
    result = compare(formula(identifier))
    print(f"{result.formula.where}: {result.formula.what}")
    for r, c in result.differing:
        display(Math(f"({r},{c}):\\ \\text{{printed}}\\ {latex(result.formula.printed[r - 1, c - 1])},"
                     f"\\quad \\text{{derived}}\\ {latex(result.derived[r - 1, c - 1])}"))
    print("why:", result.formula.why)

# %% [markdown]
# Reading the differences:
#
# * ${}^1_2T_{32}$: $R_x(-\pi/2)\,R_z(\theta_2)$ has $-c_2$ in row 3, column 2; the print lost the sign.
# * ${}^0J_{45}$: the print repeats the entry below it; the axis $z_5 = {}^0_4R\,[0, 1, 0]^T$ gives
#   $-c_1 c_2 s_4 - s_1 c_4$.
# * ${}^0J_{46}$, ${}^0J_{56}$: the last term should carry $c_5$, not $s_5$ (the third column of ${}^0_6R$).
#
# The same comparison, entry by entry with `is_identity`, is all there is to it: the printed matrix as data, the
# derived one from symjac, and an exact test per entry.

# %%
assert compare(formula("000-s4.11.1-J")).differing == ((4, 5), (4, 6), (5, 6))
assert compare(formula("000-eq4.87")).differing == ((3, 2),)
printed_J = formula("000-s4.11.1-J").printed
assert [(r + 1, c + 1) for r in range(6) for c in range(6)
        if not is_identity(J_diff[r, c], printed_J[r, c], basis)] == [(4, 5), (4, 6), (5, 6)]

# %% [markdown]
# For the exercises, the textbook shorthand as SymPy expressions:

# %%
s1, c1 = sp.sin(robot.q[0]), sp.cos(robot.q[0])
s2, c2 = sp.sin(robot.q[1]), sp.cos(robot.q[1])

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. Column 3 belongs to the prismatic joint $d_3$. Write it down (linear and angular part) in frame {0}.
# 2. Write the linear part of column 1, $z_1 \times p_{16}$, in frame {0}.
# 3. Which entry of ${}^3J$ is the rate at which $d_3$ moves the wrist along $z_3$?

# %%
answer_1 = ...  # your answer here
check(answer_1, J_diff[:, 2], robot)

# %%
p = T_0_6[:3, 3]
answer_2 = ...  # your answer here
check(answer_2, J_diff[:3, 0], robot)

# %%
answer_3 = ...  # your answer here
check(answer_3, 1, robot)
print("all answers correct")
