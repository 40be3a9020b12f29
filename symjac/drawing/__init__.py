"""Pictures of the arm: the links, joints and frames at a configuration, drawn by matplotlib.

:mod:`~symjac.drawing.geometry` turns a configuration into numbers (frame poses, joint axes, ellipsoids) and imports
no matplotlib; :mod:`~symjac.drawing.figure` lays those numbers out as mplot3d artists that can be updated in place
(sliders, animations); :mod:`~symjac.drawing.animation` writes a joint path as GIF or MP4.
"""

from symjac.drawing.animation import animate, joint_path
from symjac.drawing.figure import ArmDrawing, draw
from symjac.drawing.geometry import ArmPose, Ellipsoid, arm_pose, ellipsoid

__all__ = ["ArmDrawing", "ArmPose", "Ellipsoid", "animate", "arm_pose", "draw", "ellipsoid", "joint_path"]
