r"""The closed-form inverse kinematics of an arm, derived step by step for the classroom.

For a :class:`~symjac.analysis.inverse_kinematics.plan.Plan` this prints the family and the exact facts that decide
it, what the arm controls, the named intermediates (the wrist point), then each step: its sentence, its formulas in
textbook shorthand (:math:`s_1`, :math:`c_{23}`, through :class:`~symjac.printing.latex.TextbookLatexPrinter`) and
its existence condition. With :math:`u = p - r`, :math:`v = q - r` for a rotation about the unit axis :math:`k`
through :math:`r`:

- a rotation to a point: :math:`\theta = \operatorname{atan2}(k \cdot (u \times v),\ u \cdot v - (k \cdot u)(k \cdot
  v))`; it exists whenever the steps before it did, and at :math:`u \times k = 0` every angle works;
- a rotation to a distance :math:`\delta`: :math:`\theta = \phi \mp \psi` with :math:`\phi` the angle above,
  :math:`D = (|u'|^2 + |v'|^2 - \delta^2 + (k \cdot (u - v))^2) / (2 |u'| |v'|)` (the cosine of the turn between the
  folded and the wanted position, :math:`u' = u - k (k \cdot u)`) and :math:`\psi = \operatorname{atan2}(\sqrt{1 -
  D^2}, D)`; it exists when :math:`1 - D^2 \ge 0`;
- a slide along :math:`k`: :math:`d = k \cdot (q - p)`.

Formulas are exact in the parameters, with one exception said here: an angle of parameters alone (the folded angle
:math:`\operatorname{atan2}(0, -L_1 L_2)` of a 2R arm) is printed as the multiple of :math:`\pi/2` it is at the
parameters' defaults, the values the executor and generated code use. The target rotation's orthonormality shortens
the formulas (:math:`r_{31}^2 = 1 - r_{11}^2 - r_{21}^2`). The printed form is tidied exactly, as a textbook would:
the target position is :math:`p_x, p_y, p_z`; an intermediate that comes out a number or a lone symbol (the PUMA's
:math:`\beta_4 = 0`) is written into the later formulas instead of named; a common positive number or named square
root leaves an atan2 (:math:`\gamma_4 = \sqrt{G_4}`: at :math:`\gamma_4 = 0` every angle works) and :math:`x^2 / |x|`
is :math:`|x|`. A common parameter keeps its sign (:math:`\operatorname{atan2}(a_2 d_4, -a_2 a_3)` is exactly
``atan2(sign(a2) d4, -sign(a2) a3)``) and is printed for the sign of its default, said in a sentence
(``symjac.printing.ik_signs``). The sentences' math (:math:`\theta_5 \ge 0`,
:math:`h_1 \times h_2`) is typeset; :math:`h_i` is the unit vector along the axis of joint :math:`i`.

:func:`step_formulas` gives the formulas as SymPy expressions (the ones printed), :func:`ik_derivation_document` the
:class:`~symjac.printing.document.Document` (LaTeX, pretty text and JSON).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from symjac.analysis.inverse_kinematics.plan import POSE_SYMBOLS, Plan, Step, pose_matrix
from symjac.errors import ArgumentError
from symjac.kinematics.chain import chain_of
from symjac.printing.document import Block, Document, Equation, Inline
from symjac.printing.ik_signs import assumed_signs, sign_assumption, tidied, under_signs
from symjac.printing.latex import latex
from symjac.printing.pretty import pretty
from symjac.symbolic.simplify import simplify_matrix

__all__ = ["StepFormulas", "ik_derivation_document", "step_formulas", "substituted"]


@dataclass(frozen=True)
class StepFormulas:
    """One step's formulas: the intermediates in order, the joint value per branch, the existence conditions.

    ``solutions[b]`` is the value of each of ``step.joints`` on branch ``b`` (one tuple per branch, in the order of
    ``step.branches``), in the intermediates, the pose symbols, the plan's definitions and earlier joint variables.
    """

    step: Step
    intermediates: tuple[tuple[sp.Symbol, sp.Expr], ...]
    solutions: tuple[tuple[sp.Expr, ...], ...]
    conditions: tuple[sp.Basic, ...]
    note: str


def _vector(value: Any) -> sp.Matrix:
    return sp.Matrix(value).reshape(3, 1)


def _rotation_identities() -> dict[sp.Expr, sp.Expr]:
    """The target rotation's columns are unit vectors and orthogonal: the third row in terms of the first two."""
    r = pose_matrix()[:3, :3]
    rules: dict[sp.Expr, sp.Expr] = {}
    for j in range(3):
        rules[r[2, j] ** 2] = 1 - r[0, j] ** 2 - r[1, j] ** 2
        for i in range(j + 1, 3):
            rules[r[2, j] * r[2, i]] = -r[0, j] * r[0, i] - r[1, j] * r[1, i]
    return rules


_IDENTITIES = _rotation_identities()


def _simplified(plan: Plan, *exprs: sp.Expr) -> list[sp.Expr]:
    """Each expression in its shortest textbook form over the arm's angle bases (exact; sums of parallel joints).

    The target rotation's orthonormality (:math:`r_{31}^2 = 1 - r_{11}^2 - r_{21}^2`, ...) is used first: the
    formulas hold for every rotation, not for every 3 x 3 matrix.
    """
    exprs = tuple(sp.expand(sp.expand(e).subs(_IDENTITIES)) for e in exprs)
    if not any(e.has(sp.sin, sp.cos) for e in exprs):
        return [sp.factor_terms(e) for e in exprs]
    bases = chain_of(plan.robot.uncoupled).angle_bases(0)
    return list(simplify_matrix(sp.Matrix(exprs), bases))


def _constant_angle(plan: Plan, expr: sp.Expr) -> sp.Expr:
    """A constant atan2 (of parameters only) as the multiple of pi/2 it is at the defaults, when it is one."""
    if expr.free_symbols - set(plan.robot.defaults):
        return expr
    value = float(expr.subs(plan.robot.defaults))
    snapped = sp.Rational(round(2 * value / float(sp.pi)), 2) * sp.pi
    return snapped if abs(float(snapped) - value) < 1e-12 else expr


def _angle_terms(plan: Plan, k: sp.Matrix, u: sp.Matrix, v: sp.Matrix) -> sp.Expr:
    y, x = _simplified(plan, k.dot(u.cross(v)), u.dot(v) - k.dot(u) * k.dot(v))
    return _constant_angle(plan, sp.atan2(y, x))


_EXISTS = "it exists whenever the steps before it did; where the point lies on the axis every angle works"
_TWO = "two solutions where the condition holds strictly, one where they merge, none beyond"


def _origin(args: Mapping[str, Any], name: str) -> sp.Matrix:
    return _vector(args[name]) if args.get(name) is not None else sp.zeros(3, 1)


def _split(index: int, angle: sp.Expr, cosine: sp.Expr, radius: sp.Expr | None = None,
           letter: str = "D") -> tuple[tuple[tuple[sp.Symbol, sp.Expr], ...], sp.Basic]:
    """``phi = angle``, ``D = cosine`` and ``psi = atan2(sqrt(radius^2 - D^2), D)`` (radius 1 unless given)."""
    phi, psi, named = sp.symbols(f"phi{index} psi{index} {letter}{index}", real=True)
    square = sp.Integer(1) if radius is None else radius
    return ((phi, angle), (named, cosine), (psi, sp.atan2(sp.sqrt(square - named**2), named))), sp.Ge(
        square - named**2, 0, evaluate=False)


def _formulas(plan: Plan, step: Step) -> StepFormulas:
    args: Mapping[str, Any] = step.arguments
    index = step.joints[0] + 1
    kind = step.subproblem
    if kind.startswith("slide"):
        k, u = _vector(args["k"]), _vector(args["q"]) - _vector(args["p"])
        (along,) = _simplified(plan, k.dot(u))
        if kind == "slide_to_point":
            return StepFormulas(step, (), ((along,),), (), "it exists whenever the steps before it did")
        (across,) = _simplified(plan, u.dot(u) - k.dot(u) ** 2)
        root, named = sp.symbols(f"sigma{index} E{index}", real=True)
        delta = sp.sympify(args["delta"])
        slide = ((named, delta**2 - across), (root, sp.sqrt(named)))
        return StepFormulas(step, slide, ((along - root,), (along + root,)),
                            (sp.Ge(named, 0, evaluate=False),), _TWO)
    if kind == "two_rotations_to_point":
        return _two_rotations(plan, step)
    if kind not in ("rotation_to_point", "rotation_to_distance", "rotation_to_plane"):
        raise ArgumentError(f"IK derivation: step for joint {index} uses {kind!r}, which it cannot print")
    k, r = _vector(args["k"]), _origin(args, "point_on_axis")
    u = _vector(args["p"]) - r
    if kind == "rotation_to_plane":
        h = _vector(args["h"])
        a, b, c = _simplified(plan, h.dot(u) - k.dot(u) * k.dot(h), h.dot(k.cross(u)),
                              sp.sympify(args["d"]) - h.dot(r) - k.dot(u) * k.dot(h))
        (square,) = _simplified(plan, a**2 + b**2)
        intermediates, condition = _split(index, _constant_angle(plan, sp.atan2(b, a)), c, square, "C")
        phi, _, psi = (s for s, _ in intermediates)
        return StepFormulas(step, intermediates, ((phi - psi,), (phi + psi,)), (condition,), _TWO)
    v = _vector(args["q"]) - r
    angle = _angle_terms(plan, k, u, v)
    if kind == "rotation_to_point":
        return StepFormulas(step, (), ((angle,),), (), _EXISTS)
    delta = sp.sympify(args["delta"])
    across_u, across_v, numerator = _simplified(
        plan, u.dot(u) - k.dot(u) ** 2, v.dot(v) - k.dot(v) ** 2,
        u.dot(u) - k.dot(u) ** 2 + v.dot(v) - k.dot(v) ** 2 - delta**2 + k.dot(u - v) ** 2)
    value = numerator / (2 * sp.sqrt(across_u) * sp.sqrt(across_v))
    intermediates, condition = _split(index, angle, value)
    phi, _, psi = (s for s, _ in intermediates)
    return StepFormulas(step, intermediates, ((phi - psi,), (phi + psi,)), (condition,), _TWO)


def _two_rotations(plan: Plan, step: Step) -> StepFormulas:
    """Two rotations to a point: the middle point ``c = alpha k1 + beta k2 +- gamma (k1 x k2)``, then two angles."""
    args = step.arguments
    k1, k2, r = _vector(args["k1"]), _vector(args["k2"]), _origin(args, "intersection")
    u, v = _vector(args["p"]) - r, _vector(args["q"]) - r
    index = step.joints[0] + 1
    alpha, beta, square, gamma = sp.symbols(f"alpha{index} beta{index} G{index} gamma{index}", real=True)
    w = sp.simplify(k1.dot(k2))
    normal = k1.cross(k2)
    a, b = _simplified(plan, (k1.dot(v) - w * k2.dot(u)) / (1 - w**2), (k2.dot(u) - w * k1.dot(v)) / (1 - w**2))
    (g,) = _simplified(plan, (u.dot(u) - alpha**2 - beta**2 - 2 * alpha * beta * w) / sp.simplify(normal.dot(normal)))
    intermediates = ((alpha, a), (beta, b), (square, g), (gamma, sp.sqrt(square)))
    solutions = []
    for sign in (1, -1):
        middle = alpha * k1 + beta * k2 + sign * gamma * normal
        solutions.append((_angle_terms(plan, k1, middle, v), _angle_terms(plan, k2, u, middle)))
    return StepFormulas(step, intermediates, tuple(solutions), (sp.Ge(square, 0, evaluate=False),), _TWO)


def _inlined(formulas: StepFormulas, parameters: frozenset[sp.Symbol]) -> StepFormulas:
    """Intermediates that are a number or a lone symbol written into the later formulas instead of named.

    The PUMA's wrist step has ``beta_4 = 0``: carrying the name through every formula would hide that the terms in
    it vanish.
    """
    values: dict[sp.Symbol, sp.Expr] = {}
    kept = []
    for symbol, expr in formulas.intermediates:
        expr = tidied(expr.xreplace(values), parameters)
        if expr.is_number or expr.is_Symbol or (-expr).is_Symbol:
            values[symbol] = expr
        else:
            kept.append((symbol, expr))
    roots = frozenset(symbol for symbol, expr in kept if isinstance(expr, sp.Pow) and expr.exp == sp.S.Half)
    solutions = tuple(tuple(tidied(e.xreplace(values), parameters, roots) for e in branch)
                      for branch in formulas.solutions)
    conditions = tuple(type(c)(c.lhs.xreplace(values), c.rhs.xreplace(values), evaluate=False)
                       for c in formulas.conditions)
    return replace(formulas, intermediates=tuple(kept), solutions=solutions, conditions=conditions)


def step_formulas(plan: Plan) -> tuple[StepFormulas, ...]:
    """The printed formulas of every step of ``plan``, as SymPy expressions (see the module docstring)."""
    return tuple(_inlined(_formulas(plan, step), frozenset(plan.robot.defaults)) for step in plan.steps)


def _under(formulas: StepFormulas, signs: Mapping[sp.Symbol, int]) -> StepFormulas:
    """The formulas as printed: for the parameters' signs at their defaults (``under_signs``)."""
    return replace(formulas, intermediates=tuple((s, under_signs(e, signs)) for s, e in formulas.intermediates),
                   solutions=tuple(tuple(under_signs(e, signs) for e in b) for b in formulas.solutions))


def substituted(formulas: StepFormulas) -> tuple[tuple[sp.Expr, ...], ...]:
    """Each branch's joint values with the step's intermediates written out (to evaluate or compare)."""
    values: dict[sp.Symbol, sp.Expr] = {}
    for symbol, expr in formulas.intermediates:
        values[symbol] = expr.xreplace(values)
    return tuple(tuple(e.xreplace(values) for e in branch) for branch in formulas.solutions)


_SHOWN = {symbol: sp.Symbol(f"p_{symbol.name[1]}", real=True) for symbol in POSE_SYMBOLS[9:]}
"""The target position ``px py pz`` as printed: :math:`p_x`, not the product :math:`p x` (``r11`` is already
:math:`r_{11}`, ``w_x`` :math:`w_x`)."""


def _shown(expr: Any) -> Any:
    return expr.xreplace(_SHOWN) if isinstance(expr, sp.Basic | sp.MatrixBase) else expr


_TERM = r"(?:\b[a-z]\d+\.\([^()]*\)|\btheta\d+|\bphi\b|\bpsi\b|\b[a-z]\d+\b)"
_RUN = rf"-?{_TERM}(?:\s*(?:[+-]|>=|<=|=|>|<)\s*-?(?:{_TERM}|\d+(?:\.\d+)?\b))*"
_ITEM = rf"(?:{_RUN}|-?\d+(?:\.\d+)?)"
_PROSE = re.compile(
    rf"\((?P<point>{_ITEM}(?:, {_ITEM}){{2}})(?P<home> at home)?\)"
    r"|\bh(?P<a>\d+) x h(?P<b>\d+)\b"
    rf"|(?P<run>{_RUN})")
_SYMBOLS = ((r"\btheta(\d+)", r"\\theta_{\1}"), (r"\b(phi|psi)\b", r"\\\1"), (r"\b([a-z])(\d+)\b", r"\1_{\2}"),
            (">=", r"\\geq"), ("<=", r"\\leq"), (r"\.\(", r" \\cdot ("))


_AXES = (" (", Inline("h_i", "h_i"), ": the unit vector along the axis of joint ", Inline("i", "i"),
         ", as the joints before it turn it)")


def _axes_defined(blocks: list[Block]) -> list[Block]:
    r"""The first caption that writes :math:`h_a \times h_b` says once what :math:`h_i` is."""
    for number, block in enumerate(blocks):
        if any(isinstance(part, Inline) and r"\times" in part.tex for part in block.caption):
            *caption, last = block.caption  # the statement ends in a full stop
            caption = [*caption, last[:-1], *_AXES, "."] if isinstance(last, str) else [*caption, last, *_AXES]
            return [*blocks[:number], replace(block, caption=tuple(caption)), *blocks[number + 1:]]
    return blocks


def _tex(words: str) -> str:
    for pattern, tex in _SYMBOLS:
        words = re.sub(pattern, tex, words)
    return words


def _prose_math(match: re.Match[str]) -> tuple[str | Inline, ...]:
    if match["point"]:
        return Inline(f"({_tex(match['point'])})", f"({match['point']})"), *((" at home",) if match["home"] else ())
    if match["a"]:
        return (Inline(rf"h_{{{match['a']}}} \times h_{{{match['b']}}}", match[0]),)
    return (Inline(_tex(match[0]), match[0]),)


def _prose(text: str) -> tuple[str | Inline, ...]:
    """Words with the math in them typeset: ``theta5 >= 0``, ``h1 x h2``, ``(a2 + a3, d3, -d4)``, ``phi - psi``.

    The pretty text keeps the words as they were.
    """
    parts: list[str | Inline] = []
    start = 0
    for match in _PROSE.finditer(text):
        parts += [text[start:match.start()], *_prose_math(match)]
        start = match.end()
    parts.append(text[start:])
    return tuple(p for p in parts if p != "")


def _name(plan: Plan, joint: int) -> tuple[str, str]:
    symbol = plan.robot.joint_variables[joint]
    return latex(symbol), pretty(symbol)


def _step_blocks(plan: Plan, number: int, formulas: StepFormulas) -> list[Block]:
    step = formulas.step
    math: list[Equation] = [Equation(latex(s), str(s), _shown(e)) for s, e in formulas.intermediates]
    branches = step.branches or ("",)
    if step.swapped_by is not None and len(branches) == 2:  # names swap with the earlier step's second solution
        b, other = branches, plan.steps[step.swapped_by].branches[1]
        branches = tuple(f"{b[i]}; {b[1 - i]} with {other}" for i in (0, 1))
    for branch, values in zip(branches, formulas.solutions, strict=False):  # one solution: no branch name
        for joint, value in zip(step.joints, values, strict=True):
            tex, text = _name(plan, joint)
            suffix = f" ({branch})" if branch else ""
            math.append(Equation(tex + (rf"\ \text{{({branch})}}" if branch else ""), text + suffix, _shown(value)))
    statement = f"Step {number}: {step.statement.rstrip('.')}."
    blocks = [Block(_prose(statement), tuple(math))]
    condition: tuple[str | sp.Basic | Inline, ...] = (f"Existence: {formulas.note}",)
    if formulas.conditions:
        condition = (*condition, ": ", *(_shown(c) for c in formulas.conditions))
    blocks.append(Block(condition))
    return blocks


def _data(plan: Plan, all_formulas: tuple[StepFormulas, ...], signs: Mapping[sp.Symbol, int]) -> dict[str, Any]:
    return {
        "robot": plan.robot.name,
        "signs": {str(symbol): sign for symbol, sign in signs.items()},  # the formulas are written for these
        "family": plan.family,
        "reasons": list(plan.reasons),
        "controlled": plan.controlled,
        "definitions": {str(s): str(e) for s, e in plan.definitions},
        "steps": [
            {
                "joints": [j + 1 for j in f.step.joints],
                "subproblem": f.step.subproblem,
                "statement": f.step.statement,
                "branches": list(f.step.branches),
                "intermediates": {str(s): str(e) for s, e in f.intermediates},
                "intermediates_latex": {str(s): latex(_shown(e)) for s, e in f.intermediates},
                "solutions": [[str(e) for e in branch] for branch in f.solutions],
                "solutions_latex": [[latex(_shown(e)) for e in branch] for branch in f.solutions],
                "conditions": [str(c) for c in f.conditions],
                "existence": f.note,
            }
            for f in all_formulas
        ],
    }


def ik_derivation_document(plan: Plan) -> Document:
    r"""The derivation of ``plan`` as a :class:`~symjac.printing.document.Document`: family, reasons, steps.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.analysis.inverse_kinematics.geometry import arm_geometry
    >>> from symjac.analysis.inverse_kinematics.planar import planar_plan
    >>> document = ik_derivation_document(planar_plan(arm_geometry(load_robot("planar2r"))))
    >>> document.blocks[0].caption[0]
    'Family: planar 2R, because the axes of joints 1 and 2 are parallel.'
    """
    exact = step_formulas(plan)
    defaults = plan.robot.defaults
    signs = assumed_signs([e for f in exact for e in (*dict(f.intermediates).values(), *sum(f.solutions, ()))],
                          defaults)
    all_formulas = tuple(_under(f, signs) for f in exact)
    blocks = [
        Block(_prose(f"Family: {plan.family}, because {'; '.join(plan.reasons)}.")),
        Block((f"The arm controls {plan.controlled}; the target pose is",),
              (Equation("T", "T", _shown(pose_matrix())),)),
    ]
    if plan.definitions:
        blocks.append(
            Block(
                ("Named from the target:",),
                tuple(Equation(latex(s), str(s), _shown(e)) for s, e in plan.definitions),
            )
        )
    if signs:
        blocks.append(Block(sign_assumption(signs, defaults)))
    for number, formulas in enumerate(all_formulas, start=1):
        blocks += _step_blocks(plan, number, formulas)
    blocks = _axes_defined(blocks)
    counts = " x ".join(str(max(1, len(s.branches))) for s in plan.steps)
    blocks.append(Block((f"At most {counts} = {plan.max_solutions} solutions.",)))
    return Document(
        f"{plan.robot.name}: inverse kinematics in closed form",
        plan.robot.name,
        tuple(blocks),
        data=lambda: _data(plan, all_formulas, signs),
        comments=True,
        model=plan.robot,
    )
