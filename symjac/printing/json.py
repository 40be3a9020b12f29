"""JSON-ready data: plain dicts and lists, expressions as SymPy strings (``sp.sstr``).

Every result's JSON is built by one function from its document (:func:`document_data`): what the LaTeX and pretty
forms print, with the keys the document's equations name. Only a singularity report, whose data is no equation,
has its own (:func:`singularity_data`).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from math import isnan
from typing import TYPE_CHECKING, Any

import sympy as sp

from symjac._version import __version__
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import Block, Document, Equation, JsonKey, ParameterTable, equation_latex
from symjac.printing.tables import parameter_rows

if TYPE_CHECKING:  # the analyses' types only: printing a Jacobian's JSON does not load them
    from symjac.analysis.singularity.determinant import Determinant
    from symjac.analysis.singularity.evidence import Evidence
    from symjac.analysis.singularity.redundant import SingularSet
    from symjac.analysis.singularity.singularities import SingularityReport

__all__ = [
    "determinant_data",
    "document_data",
    "evidence_data",
    "matrix_strings",
    "metadata",
    "sample_data",
    "set_data",
    "show_data",
    "singularity_data",
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
    """A factored determinant: the product, its coefficient, ``[factor, multiplicity]`` pairs, 1-based columns, rows."""
    return {"expression": sp.sstr(det.expression), "coefficient": sp.sstr(det.coefficient),
            "factors": [[sp.sstr(f), m] for f, m in det.factors], "columns": [c + 1 for c in det.columns],
            "rows": list(det.row_names), "frame": det.frame}


def singularity_data(report: SingularityReport) -> dict[str, Any]:
    """A singularity report: rows, frame, point, determinant (or minors), and each factor with its explanation."""
    det = report.determinant
    return {
        "rows": list(det.row_names), "frame": det.frame, "point": [sp.sstr(c) for c in det.point],
        "redundant": report.redundant and not report.over_rows, "row_minors": report.over_rows,
        "row_choice": None if report.choice is None else {
            "criterion": report.choice.criterion, "exact": report.choice.exact, "frame": report.choice.frame,
            "rows": [ROW_NAMES[r] for r in report.choice.rows],
            "dropped": {ROW_NAMES[r]: None if a is None else ROW_NAMES[a] for r, a in report.choice.dropped}},
        "determinant": determinant_data(det),
        "minors": [determinant_data(m) for m in report.minors],
        "zero_minors": [{"columns": [c + 1 for c in z.columns], "rank": z.rank,
                         "concurrent": [[j + 1 for j in group] for group in z.concurrent],
                         "reason": prose.zero_minor_words(z)} for z in report.zero_minors],
        "sets": [set_data(s) for s in report.sets],
        "factors": [{
            "expression": sp.sstr(f.expression), "multiplicity": f.multiplicity, "kind": str(f.kind),
            "reason": prose.reason(f), "solutions": [sp.sstr(s.equation) for s in f.solutions],
            "existence": None if f.existence is None else sp.sstr(f.existence),
            "exists_for_defaults": f.exists_for_defaults, "sample": sample_data(f.sample, report.variables),
            "evidence": evidence_data(f.evidence, prose.evidence_clauses(f.evidence, f.cause)),
            "lost_direction": None if f.lost_direction is None else f.lost_direction.vector,
            "lost": prose.lost_words(f),
            "self_motion": None if f.self_motion is None else f.self_motion.rates,
            "self_motion_words": prose.self_motion_words(f),
            "solution_limits": [str(status) for status in f.limits], "reachable_within_limits": f.reachable,
            "limits_words": prose.limit_text(f),
        } for f in report.factors],
    }


def sample_data(sample: Sequence[float] | None, variables: Sequence[sp.Symbol]) -> dict[str, float] | None:
    """The configuration an explanation's numbers were read at: ``{"theta1": 1.419, ...}`` (``None`` if none).

    Values are in radians and metres, as all JSON data, whatever the robot file's ``angle_unit``.
    """
    if sample is None:
        return None
    return {str(v): float(x) for v, x in zip(variables, sample, strict=True)}


def evidence_data(facts: Evidence | None, clauses: Sequence[str] = ()) -> dict[str, Any] | None:
    r"""The facts checked at the sample (joints 1-based): what the words ``clauses`` state, and the numbers behind them.

    ``speeds`` maps each column's coordinate to the speed of the reference point per unit rate; ``stopped`` the
    joints that no longer move it (``stopped_on_set``: proven on the whole set), ``parallel`` the pairs whose columns
    became parallel, ``dependent`` the support of the null motion; ``points`` the speeds of each landmark point
    (``null`` for a prismatic joint); ``lost_residual`` and ``motion_residual`` are
    :math:`\lVert u^T J\rVert / \sigma_1` and :math:`\lVert J \dot q\rVert / \sigma_1`.
    """
    if facts is None:
        return None
    return {
        "rows": [ROW_NAMES[r] for r in facts.rows], "frame": facts.frame, "columns": [c + 1 for c in facts.columns],
        "rank": facts.rank, "scale": facts.scale, "tolerance": facts.tolerance,
        "speeds": {facts.names[c]: speed for c, speed in zip(facts.columns, facts.speeds, strict=True)},
        "stopped": [c + 1 for c in facts.stopped], "stopped_on_set": [c + 1 for c in facts.stopped_on_set],
        "moving": [c + 1 for c in facts.moving],
        "parallel": [[i + 1, j + 1] for i, j in facts.parallel], "dependent": [c + 1 for c in facts.dependent],
        "points": [{"point": prose.landmark_name(p.landmark),
                    "speeds": {facts.names[k]: None if isnan(v) else v for k, v in enumerate(p.speeds)},
                    "stopped": [k + 1 for k in p.stopped], "moving": [k + 1 for k in p.moving]} for p in facts.points],
        "lost_residual": facts.lost_residual, "motion_residual": facts.motion_residual, "clauses": list(clauses),
    }


def set_data(singular_set: SingularSet) -> dict[str, Any]:
    """One singular set of a redundant arm: ``EXPR = 0`` conditions, solutions per condition, kind, explanation."""
    return {
        "conditions": [f"{sp.sstr(c.expression)} = 0" for c in singular_set.conditions],
        "solutions": [[f"{sp.sstr(s.lhs)} = {sp.sstr(s.rhs)}" for s in c.solutions] for c in singular_set.conditions],
        "kind": str(singular_set.kind), "explanation": prose.set_reason(singular_set),
        "existence": None if singular_set.existence is None else sp.sstr(singular_set.existence),
        "exists_for_defaults": singular_set.exists_for_defaults,
        "sample": sample_data(singular_set.sample, singular_set.variables),
        "evidence": evidence_data(singular_set.evidence, prose.evidence_clauses(singular_set.evidence)),
        "lost_direction": None if singular_set.lost_direction is None else singular_set.lost_direction.vector,
        "lost": prose.lost_words(singular_set),
        "self_motion": None if singular_set.self_motion is None else singular_set.self_motion.rates,
        "null_space": [m.rates for m in singular_set.null_space],
        "regular_null_space": [m.rates for m in singular_set.regular_null_space],
        "solution_limits": [str(status) for status in singular_set.limits],
        "reachable_within_limits": singular_set.reachable, "limits_words": prose.limit_text(singular_set),
    }


def document_data(document: Document) -> dict[str, Any]:
    """The JSON form of any document: metadata, facts, then every keyed equation (:class:`.document.JsonKey`).

    ``document.model``'s :func:`metadata` first (when it has a robot), then ``document.facts`` as they are, then
    the math of each block and of ``document.extra`` in order: a :class:`~.document.ParameterTable` as
    ``parameter_table`` (rows of strings; also under its old key ``dh_table``, deprecated), an equation with a key
    as its right side's SymPy strings (and its LaTeX line where the key asks).
    This is the only JSON builder of a result: what LaTeX and pretty text print is what JSON holds.

    A nested result (generic geometry) is written in its intermediates' names (:func:`.nested.named_document`):
    its entries hold ``w_1, w_2, ...`` and a last key ``definitions`` lists ``[name, expression]`` pairs in
    evaluation order, each expression in terms of the joint variables, parameters and earlier names only, with
    its numbers at full precision (substituting the definitions in order, then the entries, gives the result).
    A result without intermediates has no ``definitions`` key.
    """
    from symjac.printing.nested import all_definitions, named_document

    document = named_document(document)
    data: dict[str, Any] = {} if document.model is None else metadata(document.model)
    data.update(document.facts)
    stacks: dict[str, list[sp.MatrixBase]] = {}
    for math in (*(m for block in document.blocks for m in block.math), *document.extra):
        if isinstance(math, ParameterTable):
            data["parameter_table"] = data["dh_table"] = parameter_rows(math.robot)
        elif math.key is not None:
            _place(data, math, math.key, stacks)
    for name, matrices in stacks.items():  # entries[i][j][k]: item k's [i, j]
        rows, cols = matrices[0].shape
        data[name] = [[[sp.sstr(m[i, j]) for m in matrices] for j in range(cols)] for i in range(rows)]
    where = all_definitions(document)
    if where:
        data["definitions"] = [[str(symbol), sp.sstr(value)] for symbol, value in where]
    return data


def _place(data: dict[str, Any], equation: Equation, key: JsonKey, stacks: dict[str, list[sp.MatrixBase]]) -> None:
    """Write one keyed equation into ``data`` (see :class:`.document.JsonKey`)."""
    if not isinstance(equation.rhs, sp.MatrixBase | sp.NDimArray):  # a scalar: its string (one entry of a record)
        entries: Any = [sp.sstr(equation.rhs)] if key.record else sp.sstr(equation.rhs)
    else:
        entries = [sp.sstr(e) for e in equation.rhs] if key.flat or key.record else matrix_strings(equation.rhs)
    if key.record:
        data.setdefault(key.name, []).append(
            {"name": equation.text, "latex": equation_latex(equation), "entries": entries})
    elif key.item is not None:
        if key.stacked is not None:
            data.setdefault(key.stacked, None)  # its place among the keys; filled once every item is in
            stacks.setdefault(key.stacked, []).append(equation.rhs)
        data.setdefault(key.name, {})[key.item] = entries
        if key.latex is not None:
            data.setdefault(key.latex, {})[key.item] = equation_latex(equation)
    else:
        data[key.name] = entries
        if key.latex is not None:
            data[key.latex] = equation_latex(equation)


def show_data(robot: Robot, transforms: dict[str, sp.MatrixBase]) -> dict[str, Any]:
    """``symjac show``'s JSON: the DH table and each named transform (deprecated: :func:`document_data`)."""
    warnings.warn("show_data is deprecated: a document's JSON is document_data(document), built from the document "
                  "itself (symjac.printing.results.transforms_document)", DeprecationWarning, stacklevel=2)
    equations = tuple(Equation(name, name, m, key=JsonKey("transforms", item=name)) for name, m in transforms.items())
    document = Document("", robot.name, (Block((), (ParameterTable(robot),)), Block((), equations)),
                        facts={"transforms": {}}, model=robot)
    return document_data(document)
