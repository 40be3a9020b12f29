"""
The PUMA 560 with its velocity ellipsoid
========================================

:func:`symjac.draw` returns a matplotlib figure of the arm at a configuration: links, joint axes, frames and, here,
the ellipsoid of tool velocities that unit joint rates can produce (its semi-axes are sigma_k u_k from the SVD of
the position rows of the Jacobian).
"""

import symjac

robot = symjac.load_robot("puma560")
figure = symjac.draw(robot, [0.3, -0.6, 0.4, 0.0, 0.8, 0.0], ellipsoids="velocity",
                     title="PUMA 560, velocity ellipsoid at the tool")
# The figure belongs to no pyplot window: figure.savefig("puma560.png") writes it, and a notebook shows it as is.
