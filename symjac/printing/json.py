"""JSON-ready data for every result: plain dicts and lists, expressions as SymPy strings (``sp.sstr``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import sympy as sp

from symjac._version import __version__
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import Equation, equation_latex
from symjac.printing.tables import dh_rows

if TYPE_CHECKING:  # the analyses' types only: printing a Jacobian's JSON does not load them
    from symjac.analysis.singularity.determinant import Determinant
    from symjac.analysis.singularity.redundant import SingularSet
    from symjac.analysis.singularity.singularities import SingularityReport
    from symjac.kinematics.chain import Frame

__all__ = [
    "determinant_data",
    "forward_kinematics_data",
    "hessian_data",
    "jacobian_data",
    "jacobian_derivative_data",
    "matrix_strings",
    "metadata",
    "representation_data",
    "screw_jacobian_data",
    "set_data",
    "show_data",
    "singularity_data",
    "step_data",
    "torques_data",
]


def metadata(robot: Robot) -> dict[str, Any]:
    """What every JSON output starts with: symjac's version, the robot, its variables and parameters.

    ``joint_variables`` are the independent coordinates results are written in; a coupled robot adds ``coupling``,
    each coupled joint's variable and the expression of the coordinates it equals (``{"theta4": "-theta2 - theta3"}``).
    """
    data = {"symjac": __version__, "robot": robot.name, "convention": robot.convention.value,
            "joint_variables": [str(q) for q in robot.q],
            "parameters": {p.name: float(p.default) for p in robot.parameters}}
    if robot.coupling is not None:
        data["coupling"] = {str(variable): sp.sstr(value) for variable, value
                            in zip(robot.joint_variables, robot.joint_values, strict=True) if value != variable}
    return data


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
        "zero_minors": [{"columns": [c + 1 for c in z.columns], "rank": z.rank,
                         "concurrent": [[j + 1 for j in group] for group in z.concurrent],
                         "reason": prose.zero_minor_words(z)} for z in report.zero_minors],
        "sets": [set_data(s) for s in report.sets],
        "factors": [{
            "expression": sp.sstr(f.expression), "multiplicity": f.multiplicity, "kind": str(f.kind),
            "reason": prose.reason(f), "solutions": [sp.sstr(s.equation) for s in f.solutions],
            "existence": None if f.existence is None else sp.sstr(f.existence),
            "exists_for_defaults": f.exists_for_defaults, "sample": f.sample,
            "lost_direction": None if f.lost_direction is None else f.lost_direction.vector,
            "lost": prose.lost_words(f),
            "self_motion": None if f.self_motion is None else f.self_motion.rates,
            "self_motion_words": prose.self_motion_words(f),
            "solution_limits": [str(status) for status in f.limits], "reachable_within_limits": f.reachable,
            "limits_words": prose.limit_text(f),
        } for f in report.factors],
    }


def set_data(singular_set: SingularSet) -> dict[str, Any]:
    """One singular set of a redundant arm: ``EXPR = 0`` conditions, solutions per condition, kind, explanation."""
    return {
        "conditions": [f"{sp.sstr(c.expression)} = 0" for c in singular_set.conditions],
        "solutions": [[f"{sp.sstr(s.lhs)} = {sp.sstr(s.rhs)}" for s in c.solutions] for c in singular_set.conditions],
        "kind": str(singular_set.kind), "explanation": prose.set_reason(singular_set),
        "existence": None if singular_set.existence is None else sp.sstr(singular_set.existence),
        "exists_for_defaults": singular_set.exists_for_defaults, "sample": singular_set.sample,
        "lost_direction": None if singular_set.lost_direction is None else singular_set.lost_direction.vector,
        "lost": prose.lost_words(singular_set),
        "self_motion": None if singular_set.self_motion is None else singular_set.self_motion.rates,
        "null_space": [m.rates for m in singular_set.null_space],
        "regular_null_space": [m.rates for m in singular_set.regular_null_space],
        "solution_limits": [str(status) for status in singular_set.limits],
        "reachable_within_limits": singular_set.reachable, "limits_words": prose.limit_text(singular_set),
    }


def show_data(robot: Robot, transforms: dict[str, sp.MatrixBase]) -> dict[str, Any]:
    """``symjac show``: the DH table as rows of strings and each named transform as a matrix of strings."""
    return {**metadata(robot), "dh_table": dh_rows(robot),
            "transforms": {name: matrix_strings(m) for name, m in transforms.items()}}


def forward_kinematics_data(robot: Robot, equation: Equation, source: Frame, target: Frame) -> dict[str, Any]:
    r"""``symjac fk``: the pose (``equation.rhs``) between two frames, as strings and as LaTeX (``{}^{0}_{6}T =``)."""
    return {**metadata(robot), "source": source, "target": target, "entries": matrix_strings(equation.rhs),
            "latex": equation_latex(equation)}


def step_data(step: Equation) -> dict[str, Any]:
    """One propagation step: its name in words, its LaTeX equation and its entries as SymPy strings."""
    return {"name": step.text, "latex": equation_latex(step), "entries": [sp.sstr(e) for e in step.rhs]}


def jacobian_data(robot: Robot, equation: Equation, frame: Frame, point: str, method: str,
                  steps: list[Equation] | None = None) -> dict[str, Any]:
    """``symjac jacobian``: the basic Jacobian (``equation.rhs``, in ``frame``), with the propagation steps if any."""
    J = equation.rhs
    return {**metadata(robot), "frame": frame, "point": point, "method": method,
            "shape": list(J.shape), "rows": list(ROW_NAMES), "columns": [str(q) for q in robot.q],
            "entries": matrix_strings(J), "latex": equation_latex(equation),
            **({"steps": [step_data(step) for step in steps]} if steps is not None else {})}


def screw_jacobian_data(robot: Robot, equation: Equation, kind: str) -> dict[str, Any]:
    """``symjac jacobian --kind space|body``: J_s or J_b, rows angular part first, one column (screw) per joint."""
    from symjac.kinematics.screws import SCREW_ROWS

    J = equation.rhs
    return {**metadata(robot), "kind": kind, "shape": list(J.shape), "rows": list(SCREW_ROWS),
            "columns": [str(q) for q in robot.q], "entries": matrix_strings(J), "latex": equation_latex(equation)}


def jacobian_derivative_data(robot: Robot, Jdot: Equation, bias: Equation, frame: Frame, point: str,
                             rates: list[str], steps: list[Equation] | None = None) -> dict[str, Any]:
    """``symjac jacobian --derivative``: dJ/dt and the bias acceleration Jdot qdot, in the joint rates ``rates``.

    ``Jdot`` and ``bias`` are the equations printed; with ``steps`` (the acceleration propagation), each step as
    :func:`step_data`.
    """
    return {**metadata(robot), "frame": frame, "point": point, "rates": rates, "shape": list(Jdot.rhs.shape),
            "rows": list(ROW_NAMES), "columns": [str(q) for q in robot.q], "entries": matrix_strings(Jdot.rhs),
            "bias_acceleration": [sp.sstr(b) for b in bias.rhs], "latex": equation_latex(Jdot),
            "bias_latex": equation_latex(bias),
            **({"steps": [step_data(step) for step in steps]} if steps is not None else {})}


def hessian_data(robot: Robot, equations: list[Equation], frame: Frame, point: str) -> dict[str, Any]:
    """``symjac hessian``: ``entries[i][j][k]`` = dJ[i, j]/dq_k (layout (6, n, n)), each slice dJ/dq_k and its LaTeX."""
    n = robot.n_coordinates
    slices = [equation.rhs for equation in equations]
    entries = [[[sp.sstr(slices[k][i, j]) for k in range(n)] for j in range(n)] for i in range(6)]
    return {**metadata(robot), "frame": frame, "point": point, "shape": [6, n, n],
            "layout": "entries[i][j][k] = d J[i][j] / d q[k]", "rows": list(ROW_NAMES),
            "columns": [str(q) for q in robot.q], "entries": entries,
            "slices": {str(q): matrix_strings(slices[k]) for k, q in enumerate(robot.q)},
            "slices_latex": {str(q): equation_latex(equations[k]) for k, q in enumerate(robot.q)}}


def representation_data(robot: Robot, result: Any, J_0: sp.MatrixBase, J_x: sp.MatrixBase, point: str,
                        orientation: str, position: str) -> dict[str, Any]:
    """``symjac jacobian --representation``: coordinates, the rate matrix E, the basic Jacobian and its singularities.

    ``result`` is a :class:`symjac.analysis.representations.RepresentationJacobian` (fields ``coordinates``, ``E``,
    ``frame``, ``singularities``); ``J_x`` is E(x) J_0 multiplied out.
    """
    return {**metadata(robot), "frame": result.frame, "point": point, "orientation": orientation,
            "position": position, "coordinates": [str(c) for c in result.coordinates], "E": matrix_strings(result.E),
            "J_0": matrix_strings(J_0), "J_x": matrix_strings(J_x),
            "representation_singularities": [_representation_singularity(s) for s in result.singularities],
            "latex": equation_latex(Equation(r"J_x = E(x)\,J_0", "J_x", J_x))}


def _representation_singularity(singularity: Any) -> str:
    """``factor = 0 (variable = values): what goes wrong there`` (:func:`.prose.representation_words`)."""
    values = " or ".join(str(value) for value in singularity.solutions)
    return f"{singularity.factor} = 0 ({singularity.variable} = {values}): {prose.representation_words(singularity)}"


def torques_data(robot: Robot, equation: Equation, frame: Frame, point: str, wrench: str | None,
                 q: str | None, wrench_names: list[str]) -> dict[str, Any]:
    """``symjac torques``: the joint torques (``equation.rhs``) for the wrench given (or the symbolic one)."""
    return {**metadata(robot), "frame": frame, "point": point, "wrench": wrench or wrench_names, "q": q,
            "torques": [sp.sstr(t) for t in equation.rhs], "latex": equation_latex(equation)}
