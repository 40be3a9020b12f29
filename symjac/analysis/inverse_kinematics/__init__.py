"""Inverse kinematics, in progress: the geometric subproblems closed forms are built from, and a numeric solver."""

from symjac.analysis.inverse_kinematics.closed_form import (
    FAMILIES,
    BranchProgram,
    ClosedFormResult,
    Solution,
    branch_programs,
    closed_form_plan,
    solve_plan,
)
from symjac.analysis.inverse_kinematics.geometry import ArmGeometry, arm_geometry, reduced_geometry
from symjac.analysis.inverse_kinematics.null_space import NULL_SPACE_TASKS, refine_in_null_space
from symjac.analysis.inverse_kinematics.numeric import KinematicModel, NumericSolution, seed_bounds, solve_numeric
from symjac.analysis.inverse_kinematics.parallel_axes import three_parallel_axes_plan
from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS, Plan, Step, pose_matrix
from symjac.analysis.inverse_kinematics.planar import (
    articulated_plan,
    cylindrical_plan,
    palletizer_plan,
    planar_plan,
    scara_plan,
    spherical_arm_plan,
)
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
    "NULL_SPACE_TASKS",
    "POSE_SYMBOLS",
    "AngleSolutions",
    "ArmGeometry",
    "BranchProgram",
    "ClosedFormResult",
    "KinematicModel",
    "NumericSolution",
    "Plan",
    "Solution",
    "Step",
    "Subproblem",
    "arm_geometry",
    "articulated_plan",
    "branch_programs",
    "closed_form_plan",
    "cylindrical_plan",
    "palletizer_plan",
    "planar_plan",
    "pose_matrix",
    "reduced_geometry",
    "refine_in_null_space",
    "rotation_to_distance",
    "rotation_to_distance_symbolic",
    "rotation_to_plane",
    "rotation_to_plane_symbolic",
    "rotation_to_point",
    "rotation_to_point_symbolic",
    "scara_plan",
    "seed_bounds",
    "slide_to_distance",
    "slide_to_distance_symbolic",
    "slide_to_point",
    "slide_to_point_symbolic",
    "solve_numeric",
    "solve_plan",
    "spherical_arm_plan",
    "three_parallel_axes_plan",
    "two_rotations_to_point",
    "two_rotations_to_point_symbolic",
]
