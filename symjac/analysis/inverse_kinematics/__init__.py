"""Inverse kinematics: the geometric subproblems closed-form solutions are built from."""

from symjac.analysis.inverse_kinematics.subproblems import (
    AngleSolutions,
    Subproblem,
    rotation_to_distance,
    rotation_to_distance_symbolic,
    rotation_to_point,
    rotation_to_point_symbolic,
    two_rotations_to_point,
    two_rotations_to_point_symbolic,
)

__all__ = [
    "AngleSolutions",
    "Subproblem",
    "rotation_to_distance",
    "rotation_to_distance_symbolic",
    "rotation_to_point",
    "rotation_to_point_symbolic",
    "two_rotations_to_point",
    "two_rotations_to_point_symbolic",
]
