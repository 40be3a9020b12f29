"""JSON-ready data for every result: plain dicts and lists, expressions as SymPy strings (``sp.sstr``)."""

from __future__ import annotations

from typing import Any

import sympy as sp

from symjac._version import __version__
from symjac.model import Robot
from symjac.printing import prose
from symjac.singular_report import SingularityReport
from symjac.singularity import Determinant

__all__ = ["determinant_data", "matrix_strings", "metadata", "singularity_data"]


def metadata(robot: Robot) -> dict[str, Any]:
    """What every JSON output starts with: symjac's version, the robot, its variables and parameters."""
    return {"symjac": __version__, "robot": robot.name, "convention": robot.convention.value,
            "joint_variables": [str(q) for q in robot.q],
            "parameters": {p.name: float(p.default) for p in robot.parameters}}


def matrix_strings(matrix: sp.MatrixBase) -> list[list[str]]:
    """A matrix as rows of SymPy strings."""
    return [[sp.sstr(matrix[r, c]) for c in range(matrix.cols)] for r in range(matrix.rows)]


def determinant_data(det: Determinant) -> dict[str, Any]:
    """A factored determinant: the product, its coefficient, ``[factor, multiplicity]`` pairs, 1-based columns."""
    return {"expression": sp.sstr(det.expression), "coefficient": sp.sstr(det.coefficient),
            "factors": [[sp.sstr(f), m] for f, m in det.factors], "columns": [c + 1 for c in det.columns]}


def singularity_data(report: SingularityReport) -> dict[str, Any]:
    """A singularity report: rows, frame, point, determinant (or minors), and each factor with its explanation."""
    det = report.determinant
    return {
        "rows": list(det.row_names), "frame": det.frame, "point": [sp.sstr(c) for c in det.point],
        "redundant": report.redundant, "determinant": determinant_data(det),
        "minors": [determinant_data(m) for m in report.minors],
        "factors": [{
            "expression": sp.sstr(f.expression), "multiplicity": f.multiplicity, "kind": str(f.kind),
            "reason": prose.reason(f), "solutions": [sp.sstr(s.equation) for s in f.solutions],
            "existence": None if f.existence is None else sp.sstr(f.existence),
            "exists_for_defaults": f.exists_for_defaults, "sample": f.sample,
            "lost_direction": None if f.lost_direction is None else f.lost_direction.vector,
            "lost": prose.lost_words(f),
            "self_motion": None if f.self_motion is None else f.self_motion.rates,
            "self_motion_words": prose.self_motion_words(f),
        } for f in report.factors],
    }
