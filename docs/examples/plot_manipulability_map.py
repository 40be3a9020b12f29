"""
Manipulability map of a positioning arm
=======================================

The articulated 3R arm's determinant, derived and factored by :func:`symjac.determinant`, evaluated over the
(theta2, theta3) plane with the robot's default lengths. Its zero set is drawn on top, one curve per singular factor
from :func:`symjac.singularities`: the elbow (``sin(theta3) = 0``: stretched out or folded back) and the shoulder (the
wrist point on the first axis).
"""

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import symjac

robot = symjac.load_robot("articulated3r")
det = symjac.determinant(robot).expression
print("det J =", det)

_, theta2, theta3 = robot.joint_variables
w = sp.lambdify((theta2, theta3), sp.Abs(det).subs(robot.defaults), "numpy")
grid = np.linspace(-np.pi, np.pi, 301)
T2, T3 = np.meshgrid(grid, grid)

figure, axes = plt.subplots(figsize=(6.4, 5.0), layout="constrained")
image = axes.pcolormesh(T2, T3, w(T2, T3), cmap="viridis", shading="auto")
figure.colorbar(image, ax=axes, label="|det J|")
report = symjac.singularities(robot)
for factor, colour in zip((f for f in report.factors if f.expression.free_symbols & {theta2, theta3}),
                          ("tab:red", "white", "tab:orange"), strict=False):
    values = sp.lambdify((theta2, theta3), factor.expression.subs(robot.defaults), "numpy")(T2, T3)
    axes.contour(T2, T3, np.broadcast_to(values, T2.shape), levels=[0.0], colors=[colour], linewidths=2)
    axes.plot([], [], color=colour, label=f"{factor.kind.value}: {sp.sstr(factor.expression)} = 0")
axes.set(xlabel="theta2 (rad)", ylabel="theta3 (rad)", title="articulated3r: |det J| and its singular curves")
axes.legend(loc="lower left", fontsize="small")
plt.show()
