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
# # 9. Looking at the arm: frames, ellipsoids and sliders
#
# **What you will learn**
#
# * how the frames of a Denavit-Hartenberg table sit on the real arm: each joint turns about (or slides along) the
#   z-axis of one frame;
# * what the velocity ellipsoid $\{J_v \dot q : \|\dot q\| \le 1\}$ and the force ellipsoid
#   $\{F : \|J_v^T F\| \le 1\}$ look like, and why one flattens while the other stretches near a singularity;
# * how to move the arm joint by joint with sliders and watch the Jacobian change.
#
# Everything here is drawn by `symjac.draw`, which returns an ordinary matplotlib figure.

# %%
import os
from pathlib import Path

import ipywidgets as widgets
import numpy as np
from IPython.display import display

from symjac import ArmDrawing, arm_pose, draw, ellipsoid, load_robot, numeric_jacobian
from symjac.drawing.figure import matplotlib_figure
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The frames of the PUMA 560
#
# The catalog's PUMA 560 uses the modified (Craig) convention, so joint $i$ turns about $z_i$. Frames {4}, {5}
# and {6} share one origin, the wrist centre: that is what makes the wrist spherical.

# %%
puma = load_robot("puma560")
q_puma = np.radians([20.0, -30.0, 45.0, 10.0, 40.0, 0.0])
figure = draw(puma, q_puma)
figure.savefig(OUTPUT / "puma560.png", dpi=90)
display(figure)
pose = arm_pose(puma, q_puma)
print("wrist centre, from frames {4}, {5}, {6}:", np.round(pose.origins[5:8], 4).tolist())

# %% [markdown]
# ## Ellipsoids on the planar 2R arm
#
# For the 2R arm the ellipsoids are ellipses in the plane of the arm (the third semi-axis, along z, is zero for
# velocity: no joint moves the tool out of the plane). With the elbow at $90°$ the arm is as dexterous as it gets;
# as the elbow straightens, the velocity ellipse flattens along the arm and the force ellipse grows along it: a
# stretched arm holds a force along itself with almost no torque.

# %%
planar = load_robot("planar2r")
elbows = np.radians([[20.0, 90.0], [20.0, 45.0], [20.0, 10.0]])
figure = draw(planar, elbows, ellipsoids=("velocity", "force"), view=(-90.0, 90.0))
figure.savefig(OUTPUT / "planar2r_ellipsoids.png", dpi=90)
display(figure)
for q in elbows:
    lengths = np.linalg.norm(ellipsoid(arm_pose(planar, q), "velocity").axes, axis=1)
    print(f"theta2 = {np.degrees(q[1]):4.0f} deg: velocity semi-axes {np.round(lengths[:2], 4)}")

# %% [markdown]
# ## Sliders
#
# One slider per joint of the Panda. The drawing is made once; moving a slider moves its artists
# (`ArmDrawing.update`), then prints the numeric Jacobian's manipulability $\sqrt{\det J J^T}$ and its smallest
# singular value. Run this notebook in Jupyter to use the sliders; run headless (as the tests do), it shows the arm
# once, at the sliders' starting values.

# %%
panda = load_robot("panda")
start = np.array([0.0, -0.4, 0.0, -2.0, 0.0, 1.6, 0.8])
canvas = matplotlib_figure(figsize=(5.2, 5.2), layout="constrained")
drawing = ArmDrawing(canvas.add_subplot(projection="3d"), panda, ellipsoids=("velocity",), limits=True)
drawing.update(start)
drawing.axes.set_xlim(-0.6, 0.6)
drawing.axes.set_ylim(-0.6, 0.6)
drawing.axes.set_zlim(0.0, 1.2)
drawing.axes.set_box_aspect((1.0, 1.0, 1.0))
shown = widgets.Output()


def move(**angles: float) -> None:
    """Redraw the Panda at the sliders' angles and print its Jacobian's conditioning."""
    q = np.array([angles[str(name)] for name in panda.q])
    drawing.update(q)
    J = numeric_jacobian(panda, q, frame=0, point="tool")
    sigma = np.linalg.svd(J, compute_uv=False)
    with shown:
        shown.clear_output(wait=True)
        display(canvas)
        print(f"w = sqrt(det J J^T) = {np.prod(sigma):.5f},  smallest singular value = {sigma[-1]:.5f}")


sliders = {str(name): widgets.FloatSlider(value=value, min=-2.9, max=2.9, step=0.05, description=str(name))
           for name, value in zip(panda.q, start, strict=True)}
display(widgets.VBox([widgets.interactive(move, **sliders), shown]))
move(**{name: slider.value for name, slider in sliders.items()})
canvas.savefig(OUTPUT / "panda_sliders.png", dpi=90)

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer and run the cell; `check` compares numbers to $10^{-6}$. Worked answers:
# `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. The planar 2R arm (defaults $L_1 = 0.5$, $L_2 = 0.4$) at $\theta_2 = 0$: how long is the shortest in-plane
#    semi-axis of its velocity ellipse?
# 2. At $\theta = (0, \pi/2)$: how long is the longest semi-axis of its velocity ellipse (in m/s for a joint-rate
#    vector of length 1 rad/s)? Hint: it is a singular value of $J_v$.
# 3. The PUMA 560's frames {4}, {5} and {6} share their origin. How many distinct joint origins does the drawing of
#    the PUMA show (count points that coincide once)?

# %%
answer_1 = ...  # your answer here
check(answer_1, sorted(np.linalg.norm(ellipsoid(arm_pose(planar, [0.3, 0.0])).axes, axis=1))[1])

# %%
answer_2 = ...  # your answer here
check(answer_2, np.linalg.norm(ellipsoid(arm_pose(planar, [0.0, np.pi / 2])).axes, axis=1).max(), tolerance=1e-6)

# %%
answer_3 = ...  # your answer here
check(answer_3, len(np.unique(np.round(pose.joint_origins, 9), axis=0)))
print("all answers correct")
