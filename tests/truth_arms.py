"""Arms from published tables that are not in the catalog, as robot files: the truth tests' varied shapes.

Lengths in metres. Each table is written from the maker's or the textbook's published dimensions in standard DH.
"""

from __future__ import annotations

SPHERICAL_RRP = """
name = "spherical_rrp"
description = "spherical RRP arm whose second joint is offset by d2 = 0.1"
convention = "standard"
[parameters]
d1 = 0.4
d2 = 0.1
[[joints]]
type = "revolute"
d = "d1"
alpha = "-pi/2"
[[joints]]
type = "revolute"
d = "d2"
alpha = "pi/2"
[[joints]]
type = "prismatic"
"""

CYLINDRICAL_RPP = """
name = "cylindrical_rpp"
description = "cylindrical RPP arm: a turntable, a vertical slide, a radial slide"
convention = "standard"
[parameters]
d1 = 0.3
[[joints]]
type = "revolute"
d = "d1"
[[joints]]
type = "prismatic"
alpha = "-pi/2"
[[joints]]
type = "prismatic"
"""

OPEN_MANIPULATOR_X = """
name = "open_manipulator_x"
description = "ROBOTIS OpenManipulator-X: a yaw joint, then three pitch joints"
convention = "standard"
[parameters]
d1 = 0.077
a2 = 0.130
a3 = 0.124
a4 = 0.126
[[joints]]
type = "revolute"
d = "d1"
alpha = "pi/2"
[[joints]]
type = "revolute"
a = "a2"
theta = "-atan2(0.128, 0.024)"
[[joints]]
type = "revolute"
a = "a3"
theta = "atan2(0.128, 0.024)"
[[joints]]
type = "revolute"
a = "a4"
"""

FIVE_R = """
name = "five_r"
description = "a 5R arm: yaw, three pitch joints, a roll about the approach axis"
convention = "standard"
[parameters]
d1 = 0.147
a2 = 0.155
a3 = 0.135
d5 = 0.218
[[joints]]
type = "revolute"
d = "d1"
alpha = "pi/2"
[[joints]]
type = "revolute"
a = "a2"
[[joints]]
type = "revolute"
a = "a3"
[[joints]]
type = "revolute"
alpha = "pi/2"
theta = "pi/2"
[[joints]]
type = "revolute"
d = "d5"
"""

TX90 = """
name = "tx90"
description = "Staubli TX90, written in degrees"
convention = "standard"
angle_unit = "deg"
[parameters]
a1 = 0.05
a2 = 0.425
d3 = 0.05
d4 = 0.425
d6 = 0.1
[[joints]]
type = "revolute"
a = "a1"
alpha = -90
[[joints]]
type = "revolute"
a = "a2"
theta = -90
[[joints]]
type = "revolute"
d = "d3"
alpha = 90
theta = 90
[[joints]]
type = "revolute"
d = "d4"
alpha = -90
[[joints]]
type = "revolute"
alpha = 90
[[joints]]
type = "revolute"
d = "d6"
"""

IRB2400 = """
name = "irb2400"
description = "ABB IRB 2400"
convention = "standard"
[parameters]
d1 = 0.615
a1 = 0.1
a2 = 0.705
a3 = 0.135
d4 = 0.755
d6 = 0.085
[[joints]]
type = "revolute"
d = "d1"
a = "a1"
alpha = "-pi/2"
[[joints]]
type = "revolute"
a = "a2"
theta = "-pi/2"
[[joints]]
type = "revolute"
a = "a3"
alpha = "-pi/2"
[[joints]]
type = "revolute"
d = "d4"
alpha = "pi/2"
[[joints]]
type = "revolute"
alpha = "-pi/2"
[[joints]]
type = "revolute"
d = "d6"
"""

YPPR_TOOL = """
name = "yppr_tool"
description = "yaw, pitch, pitch, roll with a tool off the roll axis"
convention = "standard"
[parameters]
d1 = 0.3
a2 = 0.4
a3 = 0.3
[[joints]]
type = "revolute"
d = "d1"
alpha = "pi/2"
[[joints]]
type = "revolute"
a = "a2"
[[joints]]
type = "revolute"
alpha = "pi/2"
theta = "pi/2"
[[joints]]
type = "revolute"
d = "a3"
[tool]
xyz = [0.05, 0, 0.1]
"""

ARMS = {"spherical_rrp": SPHERICAL_RRP, "cylindrical_rpp": CYLINDRICAL_RPP, "open_manipulator_x": OPEN_MANIPULATOR_X,
        "five_r": FIVE_R, "yppr_tool": YPPR_TOOL, "tx90": TX90, "irb2400": IRB2400}
"""Every arm above by name."""
