"""Solvers over the compiled robot: inverse kinematics (closed form where the geometry has one, else numeric)."""

from symjac.solvers.controlled import COMPONENTS, Controlled, controlled_components
from symjac.solvers.inverse_kinematics import (
    METHODS,
    InverseKinematicsResult,
    InverseKinematicsSolution,
    Method,
    inverse_kinematics,
)

__all__ = [
    "COMPONENTS",
    "METHODS",
    "Controlled",
    "InverseKinematicsResult",
    "InverseKinematicsSolution",
    "Method",
    "controlled_components",
    "inverse_kinematics",
]
