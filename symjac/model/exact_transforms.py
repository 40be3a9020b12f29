"""Exact rigid transforms written back in a robot file's words: ``xyz``/``rpy`` where the angles are exact."""

from __future__ import annotations

import sympy as sp

from symjac.model.expressions import snap_angle
from symjac.model.robot import FixedTransform
from symjac.symbolic.transforms import homogeneous, rotation_rpy

__all__ = ["fixed_transform_from_matrix"]


def fixed_transform_from_matrix(T: sp.MatrixBase) -> FixedTransform:
    r"""Write an exact rigid transform as ``xyz``/``rpy`` when its roll, pitch and yaw are exact, else as a matrix.

    Examples
    --------
    >>> from symjac.symbolic.transforms import rotation
    >>> fixed_transform_from_matrix(homogeneous(rotation("x", sp.pi / 2), sp.Matrix([1, 0, 0]))).rpy
    (pi/2, 0, 0)
    """
    R = sp.Matrix(T[:3, :3]).applyfunc(lambda e: sp.radsimp(sp.nsimplify(e) if e.is_Float else e))
    position = tuple(sp.radsimp(sp.expand(e)) for e in T[:3, 3])
    if all(e.is_number for e in R):
        sin_pitch = -R[2, 0]
        if sin_pitch == 1 or sin_pitch == -1:
            angles = (sp.atan2(-R[1, 2], R[1, 1]), sp.pi / 2 * sin_pitch, sp.S.Zero)
        else:
            angles = (sp.atan2(R[2, 1], R[2, 2]), sp.asin(sin_pitch), sp.atan2(R[1, 0], R[0, 0]))
        snapped = tuple(snap_angle(sp.Rational(float(a))) if a.has(sp.atan2, sp.asin, sp.atan) else a
                        for a in angles)
        if all(not a.has(sp.atan2, sp.asin, sp.atan) for a in snapped):
            difference = rotation_rpy(*snapped) - R
            if all(sp.radsimp(sp.expand(e)) == 0 for e in difference):
                return FixedTransform(xyz=position, rpy=snapped)  # type: ignore[arg-type]
    return FixedTransform(given_matrix=sp.ImmutableMatrix(homogeneous(R, sp.Matrix(position))))
