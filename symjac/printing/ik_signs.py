r"""Robot parameters of unknown sign in the closed-form formulas: exact first, then written as a textbook would.

A robot's parameters are real symbols with no sign (``a2`` is 0.4318 in the PUMA file and may be negative in
another), so a common parameter ``k`` of both arguments of an atan2 cannot simply be cancelled:
``atan2(k y, k x) = atan2(y, x)`` only for ``k > 0``, and ``atan2(y, x) + pi`` (modulo 2 pi) for ``k < 0``. The exact
form keeps the sign: :func:`cancel_parameters` writes ``atan2(sign(k) y, sign(k) x)``, true for every ``k != 0``. A
factor whose sign SymPy decides (a number, a symbol declared ``positive=True``, an even power) is cancelled outright.

A textbook writes the formula for the sign the arm has: :func:`assumed_signs` reads each such parameter's sign from
its default, :func:`under_signs` replaces ``sign(a2)`` by that sign and ``|a2|`` by ``a2`` (or ``-a2``), and
:func:`sign_assumption` is the sentence that says so, with what changes for the other sign.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import sympy as sp

from symjac.printing.document import Inline
from symjac.printing.latex import latex

__all__ = ["assumed_signs", "cancel_parameters", "sign_assumption", "tidied", "under_signs"]


def _common(y: sp.Expr, x: sp.Expr) -> list[sp.Expr]:
    """The factors (with multiplicity) that ``y`` and ``x`` share, from their factored-out forms."""
    ys, xs = list(sp.Mul.make_args(sp.factor_terms(y))), list(sp.Mul.make_args(sp.factor_terms(x)))
    shared = []
    for factor in ys:
        if factor in xs:
            xs.remove(factor)
            shared.append(factor)
    return shared


def cancel_parameters(y: sp.Expr, x: sp.Expr, parameters: Iterable[sp.Symbol]) -> sp.Expr:
    """``atan2(y, x)`` with the common factors made of ``parameters`` taken out exactly.

    A factor ``k`` of known sign is cancelled (``k < 0`` turns both arguments' sign); one of unknown sign leaves
    ``sign(k)`` in both arguments, so that the angle stays exact for either sign.

    >>> a2, d4, a3 = sp.symbols("a2 d4 a3", real=True)
    >>> cancel_parameters(a2 * d4, -a2 * a3, [a2, a3, d4])
    atan2(d4*sign(a2), -a3*sign(a2))
    """
    names = set(parameters)
    sign = sp.S.One
    for factor in _common(y, x):
        if factor.is_number or not factor.free_symbols <= names:
            continue
        y, x = sp.cancel(y / factor), sp.cancel(x / factor)
        if factor.is_negative:
            sign = -sign
        elif not factor.is_positive:
            sign *= sp.sign(factor)
    return sp.atan2(sign * y, sign * x)


def assumed_signs(exprs: Iterable[sp.Expr], defaults: Mapping[sp.Symbol, sp.Expr]) -> dict[sp.Symbol, int]:
    """The parameters in ``sign(.)`` of ``exprs``, each with the sign of its default (+1 or -1)."""
    signs: dict[sp.Symbol, int] = {}
    for expr in exprs:
        for wrapped in sp.sympify(expr).atoms(sp.sign):
            symbol = wrapped.args[0]
            if symbol in defaults and sp.sympify(defaults[symbol]).is_nonzero:
                signs[symbol] = 1 if sp.sympify(defaults[symbol]).is_positive else -1
    return dict(sorted(signs.items(), key=lambda item: sp.default_sort_key(item[0])))


def under_signs(expr: sp.Expr, signs: Mapping[sp.Symbol, int]) -> sp.Expr:
    """``expr`` with ``sign(p)`` as ``signs[p]`` and ``|p|`` as ``signs[p] p``: its form for those signs."""
    rules: dict[sp.Expr, sp.Expr] = {}
    for symbol, value in signs.items():
        rules[sp.sign(symbol)] = sp.Integer(value)
        rules[sp.Abs(symbol)] = value * symbol
    return sp.sympify(expr).xreplace(rules)


def sign_assumption(signs: Mapping[sp.Symbol, int],
                    defaults: Mapping[sp.Symbol, sp.Expr]) -> tuple[str | Inline, ...]:
    """The sentence that says which signs the printed formulas take, and what the other sign changes."""
    def relation(symbol: sp.Symbol, positive: bool) -> Inline:
        relation = sp.StrictGreaterThan(symbol, 0) if positive else sp.StrictLessThan(symbol, 0)
        return Inline(latex(relation), str(relation))

    def listed(items: list[Inline]) -> list[str | Inline]:
        return [part for i, item in enumerate(items) for part in ((", ",) if i else ()) + (item,)]

    values = [Inline(f"{latex(s)} = {float(defaults[s]):g}", f"{s} = {float(defaults[s]):g}") for s in signs]
    p, y, x = sp.symbols("p y x", real=True)
    return ("Written for ", *listed([relation(s, v > 0) for s, v in signs.items()]), ", as in this arm (",
            *listed(values), "): ", Inline(latex(sp.atan2(p * y, p * x)), "atan2(p*y, p*x)"), " is ",
            Inline(latex(sp.atan2(y, x)), "atan2(y, x)"), " only for ", relation(p, True), ". For ",
            *listed([relation(s, v < 0) for s, v in signs.items()]), " each atan2 such a parameter was taken out of "
            "turns by ", Inline(r"\pi", "pi"), " and ",
            *listed([Inline(f"|{latex(s)}| = {latex(-v * s)}", f"|{s}| = {-v * s}") for s, v in signs.items()]), ".")


def _even_powers_of_abs(expr: sp.Expr) -> sp.Expr:
    """``x^2 / |x|`` as ``|x|`` for a real symbol ``x`` (``x^2 = |x|^2``; no sign assumed)."""
    for magnitude in sorted(expr.atoms(sp.Abs), key=sp.default_sort_key):
        inner = magnitude.args[0]
        if not (inner.is_Symbol and inner.is_real):
            continue
        stand_in = sp.Dummy(positive=True)
        expr = expr.xreplace({magnitude: stand_in}).replace(
            lambda e, x=inner: e.is_Pow and e.base == x and e.exp.is_even,
            lambda e, m=stand_in: m**e.exp).xreplace({stand_in: magnitude})
    return expr


def _common_factor(y: sp.Expr, x: sp.Expr, roots: frozenset[sp.Symbol], parameters: frozenset[sp.Symbol]) -> sp.Expr:
    """``atan2(k y, k x)`` as ``atan2(y, x)`` for a positive number ``k`` or a named square root ``k``.

    A square root (``gamma_4 = sqrt(G_4)``) is positive where it is not 0, and at 0 the angle is arbitrary (the
    point lies on the axis), so the shorter form is a solution there too. A common robot parameter of unknown sign
    leaves its sign in both arguments (:func:`cancel_parameters`): ``atan2(a_2 y, a_2 x)``
    is ``atan2(y, x)`` only for ``a_2 > 0``.
    """
    for root in sorted(roots, key=sp.default_sort_key):
        factors_y, factors_x = (list(sp.Mul.make_args(sp.factor_terms(e))) for e in (y, x))
        if root in factors_y and root in factors_x:
            factors_y.remove(root)
            factors_x.remove(root)
            y, x = sp.Mul(*factors_y), sp.Mul(*factors_x)
    if x == 0 and (y in roots or (isinstance(y, sp.Pow) and y.exp == sp.S.Half)):
        return sp.pi / 2  # atan2(sqrt(X), 0); at X = 0 every angle works
    (ky, rest_y), (kx, rest_x) = y.as_content_primitive(), x.as_content_primitive()
    if ky.is_Rational and kx.is_Rational and ky.is_positive and kx.is_positive:
        y, x = ky / sp.gcd(ky, kx) * rest_y, kx / sp.gcd(ky, kx) * rest_x
    return cancel_parameters(y, x, parameters)


def tidied(expr: sp.Expr, parameters: frozenset[sp.Symbol], roots: frozenset[sp.Symbol] = frozenset()) -> sp.Expr:
    """Every atan2 tidied: common positive numbers, named square roots and parameters out (exactly).

    Also ``x^2/|x|`` as ``|x|``.
    """
    expr = _even_powers_of_abs(sp.sympify(expr))
    return expr.replace(lambda e: isinstance(e, sp.atan2),
                        lambda e: _common_factor(e.args[0], e.args[1], roots, parameters))
