r"""Printing in textbook shorthand: :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`.

The shorthand lives only here, in subclasses of SymPy's LaTeX and pretty printers: the math keeps ordinary
``sin``/``cos`` of joint variables. A sine or cosine is abbreviated when its argument is a sum of revolute joint
variables ``theta{i}`` (all with coefficient +1); anything else prints in full.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.pretty.pretty import PrettyPrinter
from sympy.printing.pretty.stringpict import prettyForm

from symjac.propagation import ForcePropagation, VelocityPropagation
from symjac.singularity import ROW_NAMES, SingularityReport

__all__ = ["latex", "pretty", "propagation_steps", "shorthand_indices", "singularity_summary", "textbook_factors"]

_JOINT_ANGLE = re.compile(r"theta(\d+)\Z")
_RATE = re.compile(r"(theta|d)dot\d+\Z")
_GREEK = frozenset({"alpha", "beta", "gamma", "phi", "psi", "vartheta", "eta"})
_SUBSCRIPTS = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉\u201a")  # U+201A, a low comma: c₈‚₉‚₁₀


def shorthand_indices(argument: sp.Expr) -> str | None:
    """The subscript of a trig shorthand: ``theta1 + theta2 -> "12"`` (``"8,9,10"`` past 9); ``None`` if none.

    Examples
    --------
    >>> t2, t3 = sp.symbols("theta2 theta3", real=True)
    >>> shorthand_indices(t2 + t3)
    '23'
    >>> shorthand_indices(t2 - t3) is None
    True
    """
    terms = sp.Add.make_args(argument)
    indices = []
    for term in terms:
        match = _JOINT_ANGLE.match(term.name) if isinstance(term, sp.Symbol) else None
        if match is None:
            return None
        indices.append(int(match.group(1)))
    indices.sort()
    separator = "," if any(i > 9 for i in indices) else ""
    return separator.join(str(i) for i in indices)


def _factor_key(factor: sp.Expr) -> tuple[Any, ...]:
    """Textbook order of a product's factors: parameters, cosines, sines (each by joint index), then sums."""
    base = factor.base if isinstance(factor, sp.Pow) else factor
    if isinstance(base, sp.cos | sp.sin):
        indices = shorthand_indices(base.args[0])
        if indices is not None:
            digits = indices.split(",") if "," in indices else list(indices)
            return (1 if isinstance(base, sp.cos) else 2, [int(i) for i in digits], sp.default_sort_key(factor))
    if isinstance(base, sp.Add):
        return (4, [], sp.default_sort_key(factor))
    if isinstance(base, sp.Symbol) and _RATE.match(base.name):  # rates last, as in L_1 s_2 \dot\theta_1
        return (3, [], sp.default_sort_key(factor))
    if isinstance(base, sp.Function):
        return (3, [], sp.default_sort_key(factor))
    return (0, [], sp.default_sort_key(factor))


def textbook_factors(product: sp.Expr) -> tuple[int, list[sp.Expr]] | None:
    """An integer coefficient and the other factors in textbook order (``c_1 s_{23}``, ``a_2 c_2 (...)``).

    ``None`` for products this ordering does not cover (fractions, negative powers, non-commutative factors),
    which print as SymPy prints them.

    Examples
    --------
    >>> t1, t2, L = sp.symbols("theta1 theta2 L", real=True)
    >>> textbook_factors(-2 * sp.sin(t1 + t2) * sp.cos(t1) * L)
    (-2, [L, cos(theta1), sin(theta1 + theta2)])
    """
    if not isinstance(product, sp.Mul) or not product.is_commutative:
        return None
    coefficient, rest = product.as_coeff_Mul()
    factors = sp.Mul.make_args(rest)
    if not coefficient.is_Integer or any(f.is_Pow and f.exp.is_negative for f in factors):
        return None
    return int(coefficient), sorted(factors, key=_factor_key)


class TextbookLatexPrinter(LatexPrinter):
    """LaTeX with :math:`s_{ij}, c_{ij}` shorthand and ``bmatrix`` matrices."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"mat_str": "bmatrix", "mat_delim": "", **(settings or {})})

    def _shorthand(self, letter: str, expr: sp.Function, exp: str | None) -> str | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            argument = expr.args[0]
            if not (isinstance(argument, sp.Symbol) and argument.name in _GREEK):
                return None
            indices = "\\" + argument.name  # s_{\beta}: representation angles get the shorthand too
        text = f"{letter}_{{{indices}}}"
        return f"{text}^{{{exp}}}" if exp else text

    def _print_sin(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("s", expr, exp) or self._plain_function(expr, exp)

    def _print_cos(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("c", expr, exp) or self._plain_function(expr, exp)

    def _plain_function(self, expr: sp.Function, exp: str | None) -> str:
        r"""``\cos^{2}{\left(\beta \right)}`` as SymPy prints it (its own dispatch would come back here)."""
        plain = LatexPrinter({"mat_str": "bmatrix", "mat_delim": ""})
        return LatexPrinter._print_Function(plain, expr, exp)

    def _print_Mul(self, expr: sp.Mul) -> str:
        ordered = textbook_factors(expr)
        if ordered is None:
            return super()._print_Mul(expr)
        coefficient, factors = ordered
        parts = [r"\left(" + self._print(f) + r"\right)" if f.is_Add else self._print(f) for f in factors]
        if abs(coefficient) != 1:
            parts.insert(0, str(abs(coefficient)))
        return ("- " if coefficient < 0 else "") + " ".join(parts)


class TextbookPrettyPrinter(PrettyPrinter):
    """Unicode pretty printing with ``s₁, c₂₃`` shorthand."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"use_unicode": True, "wrap_line": False, **(settings or {})})

    def _shorthand(self, letter: str, expr: sp.Function) -> prettyForm | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            return None
        return prettyForm(letter + indices.translate(_SUBSCRIPTS))

    def _print_sin(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("s", expr) or self._print_Function(expr)

    def _print_cos(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("c", expr) or self._print_Function(expr)

    def _print_Mul(self, product: sp.Mul) -> prettyForm:
        ordered = textbook_factors(product)
        if ordered is None:
            return super()._print_Mul(product)
        coefficient, factors = ordered
        forms = [self._print(f) for f in factors]
        if coefficient != 1:
            forms.insert(0, self._print(sp.Integer(coefficient)))  # prettyForm.__mul__ turns -1 into a sign
        return prettyForm.__mul__(*forms)


def latex(expr: Any, **settings: Any) -> str:
    r"""LaTeX of an expression or matrix in textbook shorthand.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> latex(sp.Matrix([[sp.cos(t1) * sp.sin(t1 + t2)]]))
    '\\begin{bmatrix}c_{1} s_{12}\\end{bmatrix}'
    """
    return TextbookLatexPrinter(settings).doprint(expr)


def pretty(expr: Any, **settings: Any) -> str:
    """Unicode pretty print of an expression or matrix in textbook shorthand (``c₁₂``)."""
    return TextbookPrettyPrinter(settings).doprint(expr)


def propagation_steps(
    propagation: VelocityPropagation | ForcePropagation, style: str = "latex", values: Mapping[Any, Any] | None = None
) -> list[str]:
    r"""Every step of a velocity or force propagation, one equation per string, ready for lecture notes.

    ``style`` is ``"latex"`` or ``"pretty"`` (Unicode); ``values`` (symbol -> number) are substituted first.

    Examples
    --------
    >>> from symjac import load_robot, velocity_propagation
    >>> propagation_steps(velocity_propagation(load_robot("planar2r")))[3]
    '{}^{1}v_{1} = \\begin{bmatrix}0\\\\L_{1} \\dot{\\theta}_{1}\\\\0\\end{bmatrix}'
    """
    if style not in ("latex", "pretty"):
        raise ValueError(f"style must be 'latex' or 'pretty', got {style!r}")
    if isinstance(propagation, VelocityPropagation):
        rows = propagation.velocities()
        names = ((r"\omega", "ω"), ("v", "v"))
    else:
        rows = propagation.wrenches()
        names = (("f", "f"), ("n", "n"))
    last = max(frame for frame, _, _ in rows if isinstance(frame, int))
    lines = []
    for frame, first, second in rows:
        where, subscript = {"tool": ("T", "T"), "point": (str(last), "P")}.get(str(frame), (str(frame), str(frame)))
        for (tex_name, text_name), vector in zip(names, (first, second), strict=True):
            vector = vector.xreplace(dict(values or {}))
            if style == "latex":
                lines.append(f"{{}}^{{{where}}}{tex_name}_{{{subscript}}} = {latex(vector)}")
            else:
                lines.append(f"{text_name}_{subscript} (in frame {where}) =\n{pretty(vector)}")
    if isinstance(propagation, ForcePropagation):
        tau = propagation.joint_torques().xreplace(dict(values or {}))
        lines.append(rf"\tau = {latex(tau)}" if style == "latex" else f"tau =\n{pretty(tau)}")
    return lines


def singularity_summary(report: SingularityReport, style: str = "latex") -> list[tuple[str, str]]:
    r"""A singularity report as (caption, equation) pairs: the determinant, then each factor with its meaning.

    ``style`` is ``"latex"`` (equations in LaTeX, captions in plain words) or ``"pretty"`` (Unicode).

    Examples
    --------
    >>> from symjac import load_robot, singularities
    >>> summary = singularity_summary(singularities(load_robot("planar2r")))
    >>> summary[0][1]
    '\\det J = L_{1} L_{2} s_{2}'
    """
    if style not in ("latex", "pretty"):
        raise ValueError(f"style must be 'latex' or 'pretty', got {style!r}")
    show = latex if style == "latex" else pretty
    det = report.determinant
    rows = ", ".join(ROW_NAMES[r] for r in det.rows)
    where = f"rows {rows} of the Jacobian in frame {{{det.frame}}}"
    if report.redundant:
        lines = [(f"Redundant arm: {report.robot} has more joints than task rows ({rows}); it is singular only where "
                  "every square minor below vanishes (where sqrt(det(J J^T)) = 0). Minors in frame "
                  f"{{{det.frame}}}.", "")]
        for minor in report.minors:
            locked = next(c for c in range(len(minor.columns) + 1) if c not in minor.columns)
            lines.append((f"Joint {locked + 1} locked:", _equation(style, r"\det J", "det J", minor.expression)))
        return lines
    lines = [(f"Determinant of {where}:", _equation(style, r"\det J", "det J", det.expression))]
    for factor in report.factors:
        head = f"Factor {show(factor.expression)} ({factor.kind}): {factor.reason}."
        if not factor.solutions:
            lines.append((head, ""))
            continue
        solutions = [latex(s.equation) if style == "latex" else pretty(s.equation) for s in factor.solutions]
        joined = r",\quad ".join(solutions) if style == "latex" else "\n".join(solutions)
        if factor.existence is not None and factor.existence is not sp.true:
            verdict = {True: "holds", False: "does not hold", None: "unknown"}[factor.exists_for_defaults]
            head += f" Exists only if {sp.sstr(factor.existence)} (assuming positive lengths; {verdict} for the " \
                    "default parameters)."
        if factor.lost_words:
            head += f" There it {factor.lost_words}; {factor.self_motion_words}."
        lines.append((head, joined))
    return lines


def _equation(style: str, tex_name: str, text_name: str, value: Any) -> str:
    if style == "latex":
        return f"{tex_name} = {latex(value)}"
    return pretty(sp.Eq(sp.Symbol(text_name), value, evaluate=False))
