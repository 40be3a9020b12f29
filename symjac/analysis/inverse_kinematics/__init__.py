"""Inverse kinematics, in progress: the geometric subproblems closed forms are built from, and a numeric solver."""

from symjac.analysis.inverse_kinematics.numeric import KinematicModel, NumericSolution, seed_bounds, solve_numeric
from symjac.analysis.inverse_kinematics.poses import (
    pose_from_matrix,
    pose_from_quaternion,
    pose_from_rpy,
    quaternion_from_pose,
    rpy_from_pose,
)
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
    "KinematicModel",
    "NumericSolution",
    "Subproblem",
    "pose_from_matrix",
    "pose_from_quaternion",
    "pose_from_rpy",
    "quaternion_from_pose",
    "rotation_to_distance",
    "rotation_to_distance_symbolic",
    "rotation_to_point",
    "rotation_to_point_symbolic",
    "rpy_from_pose",
    "seed_bounds",
    "solve_numeric",
    "two_rotations_to_point",
    "two_rotations_to_point_symbolic",
]
