"""Inverse kinematics, in progress: the geometric subproblems closed forms are built from, and a numeric solver."""

from symjac.analysis.inverse_kinematics.closed_form import (
    FAMILIES,
    ClosedFormResult,
    Solution,
    closed_form_plan,
    solve_plan,
)
from symjac.analysis.inverse_kinematics.geometry import ArmGeometry, arm_geometry, reduced_geometry
from symjac.analysis.inverse_kinematics.numeric import KinematicModel, NumericSolution, seed_bounds, solve_numeric
from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS, Plan, Step, pose_matrix
from symjac.analysis.inverse_kinematics.subproblems import (
    AngleSolutions,
    Subproblem,
    rotation_to_distance,
    rotation_to_distance_symbolic,
    rotation_to_plane,
    rotation_to_plane_symbolic,
    rotation_to_point,
    rotation_to_point_symbolic,
    slide_to_distance,
    slide_to_distance_symbolic,
    slide_to_point,
    slide_to_point_symbolic,
    two_rotations_to_point,
    two_rotations_to_point_symbolic,
)

__all__ = [
    "FAMILIES",
    "POSE_SYMBOLS",
    "AngleSolutions",
    "ArmGeometry",
    "ClosedFormResult",
    "KinematicModel",
    "NumericSolution",
    "Plan",
    "Solution",
    "Step",
    "Subproblem",
    "arm_geometry",
    "closed_form_plan",
    "pose_matrix",
    "reduced_geometry",
    "rotation_to_distance",
    "rotation_to_distance_symbolic",
    "rotation_to_plane",
    "rotation_to_plane_symbolic",
    "rotation_to_point",
    "rotation_to_point_symbolic",
    "seed_bounds",
    "slide_to_distance",
    "slide_to_distance_symbolic",
    "slide_to_point",
    "slide_to_point_symbolic",
    "solve_numeric",
    "solve_plan",
    "two_rotations_to_point",
    "two_rotations_to_point_symbolic",
]
