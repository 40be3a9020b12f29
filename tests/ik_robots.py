"""Small robot files the inverse-kinematics tests share (arms the catalog does not have)."""

CYLINDRICAL = """
name = "cylindrical"
description = "Cylindrical arm: a waist, a vertical slide, a radial slide offset c from the waist axis"
convention = "modified"

[parameters]
d1 = 0.3
c = 0.1

[[joints]]
type = "revolute"
alpha = 0
a = 0
d = "d1"
theta = 0

[[joints]]
type = "prismatic"
alpha = 0
a = 0
d = 0
theta = 0
limits = [0.0, 0.8]

[[joints]]
type = "prismatic"
alpha = "-pi/2"
a = "c"
d = 0
theta = 0
limits = [0.2, 0.9]
"""
