"""Inverse kinematics (issue 46): numeric solver."""

from symjac.analysis.inverse_kinematics.numeric import KinematicModel, NumericSolution, solve_numeric

__all__ = ["KinematicModel", "NumericSolution", "solve_numeric"]
