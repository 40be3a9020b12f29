r"""LaTeX in textbook shorthand: :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`.

The shorthand lives only in the printers (a subclass of SymPy's LaTeX printer here, :mod:`.pretty` for Unicode):
the math keeps ordinary ``sin``/``cos`` of joint variables.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable, Iterator
from contextvars import ContextVar
from typing import Any

import sympy as sp
from sympy.core.exprtools import decompose_power
from sympy.printing.latex import LatexPrinter

from symjac.errors import SymjacError
from symjac.printing.shorthand import (
    GREEK,
    file_decimal,
    readable_float,
    shorthand_indices,
    textbook_factors,
    textbook_form,
)

__all__ = ["DIGITS", "LatexTooLargeError", "SortKeys", "TextbookLatexPrinter", "escape_text", "latex",
           "latex_size_limit", "ordered_terms", "rounded"]

DIGITS = 4
"""Significant digits of the numbers in ``--numeric`` results unless ``--digits`` says otherwise."""

_TEXT_ESCAPES = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "_": r"\_", "#": r"\#", "%": r"\%", "&": r"\&",
                 "$": r"\$", "^": r"\^{}", "~": r"\~{}", "<": r"\textless{}", ">": r"\textgreater{}"}


_SIZE_LIMIT: ContextVar[int | None] = ContextVar("symjac_latex_size_limit", default=None)


class LatexTooLargeError(SymjacError):
    """A LaTeX result longer than the limit in force (:func:`latex_size_limit`); it is written only to a file."""


@contextlib.contextmanager
def latex_size_limit(limit: int) -> Iterator[None]:
    """Within the block, a matrix whose entries print to more than ``limit`` characters raises at once.

    The entries are printed one by one and the printing stops as soon as they pass the limit, so refusing an
    800 KB Jacobian costs a quarter of printing it.
    """
    token = _SIZE_LIMIT.set(limit)
    try:
        yield
    finally:
        _SIZE_LIMIT.reset(token)


class _DecimalLatexPrinter(LatexPrinter):
    """SymPy's LaTeX with numbers from files as the decimals they were written as (:func:`.file_decimal`).

    Each distinct subexpression is printed once per printer: the entries of a Jacobian share most of their terms
    (a 7-joint chain with generic twists has about 100,000 nodes in its Jacobian but 5,500 distinct ones), and
    SymPy orders the terms of every sum again each time it meets it.
    """

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__(settings)
        self._memo: dict[sp.Basic, str] = {}
        self._has_mod = True
        self._sort_keys = SortKeys()

    def doprint(self, expr: Any) -> str:
        # SymPy asks of every term of every sum whether it contains a Mod (which would need brackets), a walk of the
        # whole term each time: a third of the time to print a long Jacobian. One walk of the whole answers for all.
        self._has_mod = not isinstance(expr, sp.Basic | sp.MatrixBase) or expr.has(sp.Mod)
        return super().doprint(expr)

    def _print_matrix_contents(self, expr: sp.MatrixBase) -> str:
        limit = _SIZE_LIMIT.get()
        if limit is not None:
            printed = 0
            for entry in expr:  # remembered by _print, so the full layout below prints nothing twice
                printed += len(self._print(entry))
                if printed > limit:
                    raise LatexTooLargeError(f"the LaTeX of a matrix passes {limit:,} characters")
        return str(super()._print_matrix_contents(expr))

    def _needs_add_brackets(self, expr: sp.Expr) -> bool:
        if self._has_mod:
            return bool(super()._needs_add_brackets(expr))
        return bool(expr.is_Relational or expr.is_Add)

    def _print(self, expr: Any, **kwargs: Any) -> str:
        # Only whole expressions printed without options are remembered: ``exp=`` (a power of a function) and the
        # like change the text. Equal SymPy objects print alike (Floats of different precision are not equal).
        if kwargs or not isinstance(expr, sp.Basic):
            return super()._print(expr, **kwargs)
        text = self._memo.get(expr)
        if text is None:
            text = self._memo[expr] = super()._print(expr)
        return text

    def _print_Rational(self, expr: sp.Rational) -> str:
        return file_decimal(expr) or super()._print_Rational(expr)

    def _print_Float(self, expr: sp.Float) -> str:
        return str(super()._print_Float(readable_float(expr)))

    def _as_ordered_terms(self, expr: sp.Expr, order: str | None = None) -> list[sp.Expr]:
        if (order or self.order) in (None, "lex") and expr.is_Add:
            return ordered_terms(expr, self._sort_keys)
        return super()._as_ordered_terms(expr, order)

    def _print_Mul(self, expr: sp.Mul) -> str:
        coefficient, rest = expr.as_coeff_Mul()
        decimal = file_decimal(abs(coefficient))
        if decimal is None:
            return super()._print_Mul(expr)
        body = self._print(rest)  # 0.089159 s_{1}, as the robot file wrote it
        body = rf"\left({body}\right)" if rest.is_Add else body
        return ("- " if coefficient < 0 else "") + f"{decimal} {body}"


class TextbookLatexPrinter(_DecimalLatexPrinter):
    """LaTeX with :math:`s_{ij}, c_{ij}, c_{2-4}` shorthand and ``bmatrix`` matrices.

    What it prints is first put in :func:`.textbook_form` (offsets expanded, fractions taken out of sums), so every
    sine and cosine of joint variables is shorthand.
    """

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"mat_str": "bmatrix", "mat_delim": "", **(settings or {})})
        self._plain: _DecimalLatexPrinter | None = None
        self._forms: dict[sp.Basic, sp.Basic] = {}

    def doprint(self, expr: Any) -> str:
        """The text of ``expr`` in :func:`.textbook_form`."""
        return super().doprint(textbook_form(expr, self._forms))

    def _shorthand(self, letter: str, expr: sp.Function, exp: str | None) -> str | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            argument = expr.args[0]
            if not (isinstance(argument, sp.Symbol) and argument.name in GREEK):
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
        if self._plain is None:
            self._plain = _DecimalLatexPrinter({"mat_str": "bmatrix", "mat_delim": ""})
        return LatexPrinter._print_Function(self._plain, expr, exp)

    def _print_atan2(self, expr: sp.Function, exp: str | None = None) -> str:
        text = r"\operatorname{atan2}\left(" + ", ".join(self._print(a) for a in expr.args) + r"\right)"
        return f"{text}^{{{exp}}}" if exp else text

    def _print_Mul(self, expr: sp.Mul) -> str:
        if file_decimal(abs(expr.as_coeff_Mul()[0])) is not None:
            return super()._print_Mul(expr)
        ordered = textbook_factors(expr, self._sort_keys)
        number = expr.as_coeff_Mul()[0]
        if ordered is None and isinstance(number, sp.Rational) and not number.is_Integer \
                and textbook_factors(expr * number.q, self._sort_keys) is not None:
            numerator = self._print((-expr if number < 0 else expr) * number.q)  # c_2 (c_3 - 1) / 2
            return ("- " if number < 0 else "") + rf"\frac{{{numerator}}}{{{number.q}}}"
        if ordered is None:
            return super()._print_Mul(expr)
        coefficient, factors = ordered
        parts = [r"\left(" + self._print(f) + r"\right)" if f.is_Add else self._print(f) for f in factors]
        if abs(coefficient) != 1:
            parts.insert(0, str(abs(coefficient)))
        return ("- " if coefficient < 0 else "") + " ".join(parts)


def _complex(number: sp.Expr) -> complex:
    """``complex(number)``; rationals and floats are converted directly instead of through SymPy's ``evalf``."""
    if isinstance(number, sp.Rational):
        with contextlib.suppress(OverflowError):
            return complex(number.p / number.q)
    if isinstance(number, sp.Float):
        return complex(float(number))
    return complex(number)


class SortKeys:
    """SymPy's ``default_sort_key`` of expressions, remembered, with sums ordered by :func:`ordered_terms`.

    The key of a sum holds the keys of its terms in printing order, so SymPy computes that order again for every
    nested sum it meets, the slow way. This computes the same key (``Expr.sort_key`` for products, powers, sums and
    functions; the class's own key for atoms and anything that defines its own) once per distinct subexpression.
    """

    def __init__(self) -> None:
        self._keys: dict[sp.Basic, Any] = {}

    def __call__(self, expr: sp.Basic) -> Any:
        """The sort key of ``expr``, equal to ``sympy.default_sort_key(expr)``."""
        key = self._keys.get(expr)
        if key is None:
            key = self._keys[expr] = self._key(expr)
        return key

    def _key(self, expr: sp.Basic) -> Any:
        if type(expr).sort_key is not sp.Expr.sort_key:
            return expr.sort_key()
        coefficient, rest = expr.as_coeff_Mul()
        exponent = sp.S.One
        if rest.is_Pow:
            rest, exponent = rest.as_base_exp()
            if rest is sp.S.Exp1:
                return expr.sort_key()  # SymPy keys E**x as the function exp(x): its own rule
        if rest.is_Dummy or rest.is_Atom:
            return expr.sort_key()
        if rest.is_Add:
            args = ordered_terms(rest, self)
        elif rest.is_Mul:
            commutative, noncommutative = rest.args_cnc()
            args = sorted(commutative, key=self) + noncommutative
        else:
            args = list(rest.args)
        keys = tuple(self(arg) for arg in args)
        return rest.class_key(), (len(keys), keys), exponent.sort_key(), coefficient


def ordered_terms(expr: sp.Add, sort_key: Callable[[sp.Basic], Any] = sp.default_sort_key) -> list[sp.Expr]:
    """The terms of a sum in the order SymPy prints them (``expr.as_ordered_terms()``, lexicographic), faster.

    Each term is split into a numeric coefficient and powers of its other factors (the generators); terms are
    sorted by their exponent vectors over the sorted generators, highest first, then by coefficient. A sum of a
    positive number and a negative multiple (``1 - x``) keeps the number first. Half the time of printing a long
    Jacobian went into SymPy turning each rational coefficient into a complex number through ``evalf``.

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> ordered_terms(x**2 + 3*x*y + 1) == (x**2 + 3*x*y + 1).as_ordered_terms()
    True
    """
    args = expr.args
    if any(term.is_Order for term in args):
        return expr.as_ordered_terms()
    numbers = sorted(args, key=lambda a: not isinstance(a, sp.Number | sp.NumberSymbol))
    if len(numbers) == 2 and isinstance(numbers[0], sp.Number | sp.NumberSymbol) and numbers[1].is_Mul:
        factors = sorted(numbers[1].args, key=lambda a: not isinstance(a, sp.Number))
        if (len(factors) == 2 and isinstance(factors[0], sp.Number) and numbers[0].is_positive
                and factors[0].is_negative):
            return numbers
    split = [_split_term(term) for term in args]
    generators = sorted({base for _, powers, _ in split for base in powers}, key=sort_key)
    position = {base: i for i, base in enumerate(generators)}

    def key(item: tuple[sp.Expr, dict[sp.Expr, sp.Expr], tuple[sp.Expr, ...], complex]) -> tuple[Any, ...]:
        _, powers, noncommutative, coefficient = item
        monomial = [0] * len(generators)
        for base, exponent in powers.items():
            monomial[position[base]] = exponent
        return (tuple(-e for e in monomial), tuple(e.sort_key() for e in noncommutative),
                ((bool(coefficient.imag), coefficient.imag), (coefficient.real, coefficient.imag)))

    items = [(term, powers, noncommutative, coefficient)
             for term, (coefficient, powers, noncommutative) in zip(args, split, strict=True)]
    return [item[0] for item in sorted(items, key=key)]


@functools.lru_cache(maxsize=65536)
def _is_number(factor: sp.Expr) -> bool:
    """``factor.is_number``, remembered: SymPy walks the whole factor each time, and long sums repeat their factors."""
    return bool(factor.is_number)


def _split_term(term: sp.Expr) -> tuple[complex, dict[sp.Expr, sp.Expr], tuple[sp.Expr, ...]]:
    """(numeric coefficient, {generator: exponent}, non-commutative factors) of one term of a sum."""
    number, rest = term.as_coeff_Mul()
    coefficient = _complex(number)
    powers: dict[sp.Expr, sp.Expr] = {}
    noncommutative: list[sp.Expr] = []
    for factor in () if rest is sp.S.One else sp.Mul.make_args(rest):
        if _is_number(factor):
            try:
                coefficient *= _complex(factor)
                continue
            except (TypeError, ValueError):
                pass
        if factor.is_commutative:
            base, exponent = decompose_power(factor)
            powers[base] = exponent
        else:
            noncommutative.append(factor)
    return coefficient, powers, tuple(noncommutative)


def latex(expr: Any, **settings: Any) -> str:
    r"""LaTeX of an expression or matrix in textbook shorthand.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> latex(sp.Matrix([[sp.cos(t1) * sp.sin(t1 + t2)]]))
    '\\begin{bmatrix}c_{1} s_{12}\\end{bmatrix}'
    """
    return TextbookLatexPrinter(settings).doprint(expr)


def escape_text(text: str) -> str:
    r"""Words for LaTeX text mode: ``_ # % & $ { } ^ ~ \ < >`` made printable.

    Examples
    --------
    >>> escape_text("my_arm: 50% of {3}")
    'my\\_arm: 50\\% of \\{3\\}'
    """
    return "".join(_TEXT_ESCAPES.get(character, character) for character in text)


def rounded(expr: Any, digits: int = DIGITS) -> Any:
    """``expr`` (or a matrix) with every number a decimal of ``digits`` significant digits; integers stay integers.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> rounded(sp.Rational(2159, 5000) * x + sp.Rational(1, 3) + 2 * sp.sin(x), 3)
    0.432*x + 2*sin(x) + 0.333
    """
    value = sp.sympify(expr).evalf(digits)
    return value.xreplace({f: sp.Integer(int(f)) for f in value.atoms(sp.Float) if float(f).is_integer()})
