"""Inverse kinematics, in progress: the geometric subproblems closed forms are built from, and a numeric solver."""

from symjac.analysis.inverse_kinematics.null_space import NULL_SPACE_TASKS, refine_in_null_space
from symjac.analysis.inverse_kinematics.numeric import KinematicModel, NumericSolution, seed_bounds, solve_numeric
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
    "NULL_SPACE_TASKS",
    "AngleSolutions",
    "KinematicModel",
    "NumericSolution",
    "Subproblem",
    "refine_in_null_space",
    "rotation_to_distance",
    "rotation_to_distance_symbolic",
    "rotation_to_point",
    "rotation_to_point_symbolic",
    "seed_bounds",
    "solve_numeric",
    "two_rotations_to_point",
    "two_rotations_to_point_symbolic",
]
