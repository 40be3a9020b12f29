"""Pictures of the arm: the links, joints and frames at a configuration, drawn by matplotlib.

:mod:`~symjac.drawing.geometry` turns a configuration into numbers (frame poses, joint axes, ellipsoids) and imports
no matplotlib; :mod:`~symjac.drawing.figure` lays those numbers out as mplot3d artists that can be updated in place
(sliders, animations); :mod:`~symjac.drawing.animation` writes a joint path as GIF or MP4.
"""
