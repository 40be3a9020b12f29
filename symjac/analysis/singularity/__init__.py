"""Singular configurations, from the determinant to what the arm loses.

The determinant of the square task Jacobian in factored form (:mod:`.determinant`), each
factor solved (:mod:`.solve`), explained geometrically (:mod:`.geometry`), checked against the joint limits
(:mod:`.joint_limits`), and the whole analysis of one arm (:mod:`.singularities`).
"""

from symjac.analysis.singularity.determinant import Determinant, determinant
from symjac.analysis.singularity.singularities import LimitStatus, SingularFactor, SingularityReport, singularities

__all__ = ["Determinant", "LimitStatus", "SingularFactor", "SingularityReport", "determinant", "singularities"]
