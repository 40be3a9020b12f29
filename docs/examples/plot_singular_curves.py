"""
Distance from singularity of the planar 3R arm
==============================================

For a planar arm the task is the tool point's x and y, and the 2 x 3 Jacobian loses rank only where every 2 x 2
minor vanishes: all three links in one line, theta2 and theta3 each 0 or pi. Those are four isolated points of the
(theta2, theta3) plane, and the smallest singular value of the numeric Jacobian, drawn here, shows how the arm
approaches them: the dark spots. (The 2R arm's singular set, by contrast, is the lines theta2 = 0 and theta2 = pi.)
"""

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import symjac

robot = symjac.load_robot("planar3r")
J = symjac.jacobian(robot, frame=0, point="tool")[:2, :]  # rows v_x, v_y
q = robot.joint_variables
numeric = sp.lambdify(q, J.subs(robot.defaults), "numpy")

grid = np.linspace(-np.pi, np.pi, 181)
sigma = np.empty((grid.size, grid.size))
for i, t3 in enumerate(grid):
    for j, t2 in enumerate(grid):
        sigma[i, j] = np.linalg.svd(np.asarray(numeric(0.0, t2, t3), dtype=float), compute_uv=False)[-1]

figure, axes = plt.subplots(figsize=(6.4, 5.0), layout="constrained")
image = axes.imshow(sigma, origin="lower", extent=(-np.pi, np.pi, -np.pi, np.pi), cmap="magma", aspect="auto")
figure.colorbar(image, ax=axes, label="smallest singular value of J (m/rad)")
axes.plot([0, 0, np.pi, np.pi, -np.pi, -np.pi], [0, np.pi, 0, np.pi, 0, np.pi], "x", color="white", markersize=8)
axes.set(xlabel="theta2 (rad)", ylabel="theta3 (rad)", title="planar3r: distance from singularity (x: singular)")
plt.show()
