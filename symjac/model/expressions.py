r"""Robot-file field expressions: a whitelist parser and its inverse.

A field of a robot file is a number or a small expression such as ``"-pi/2"`` or ``"L1 + L2"``. The text is parsed
with :func:`ast.parse` and the tree is walked node by node; only these nodes are accepted:

* numbers (``int`` or decimal ``float`` literals, turned into exact SymPy rationals: ``0.4318 -> 2159/5000``),
* names: the constant ``pi`` and the parameter names the file declares,
* binary ``+ - * /`` and ``**`` with a small integer exponent, unary ``+`` and ``-``, parentheses,
* calls of the functions in :data:`FUNCTIONS`: ``sin(x)``, ``cos(x)``, ``sqrt(x)``, ``atan(x)`` and ``atan2(y, x)``
  (an offset such as ``atan2(0.128, 0.024)`` stays exact: SymPy writes it ``atan(16/3)``).

Anything else (other calls, attributes, subscripts, strings, lambdas, ...) is rejected *before* any of it could run:
the SymPy expression is built here, never by ``eval``, ``sympify`` or ``parse_expr`` on file text.
"""

from __future__ import annotations

import ast
import keyword
import math
import re
import warnings
from collections.abc import Mapping
from fractions import Fraction

import sympy as sp

from symjac.errors import ExpressionError

__all__ = [
    "ANGLE_SNAP_TOLERANCE",
    "exact_number",
    "expression_text",
    "is_valid_name",
    "name_problem",
    "parse_expression",
    "snap_angle",
]

MAX_EXPRESSION_LENGTH = 200
MAX_EXPONENT = 8
MAX_POWER_BITS = 4096  # largest numerator/denominator a power may produce: "((9**8)**8)**8..." must not hang
_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


def is_valid_name(name: str) -> bool:
    """Return whether ``name`` may name a parameter: an ASCII identifier, not a Python keyword, not ``pi``."""
    return name_problem(name) is None


def name_problem(name: object) -> str | None:
    """Why ``name`` cannot name a parameter or a robot, in plain words, or ``None`` when it can.

    Examples
    --------
    >>> name_problem("__import__")
    'names must start with a letter (names starting with an underscore are not allowed)'
    >>> name_problem("L1") is None
    True
    """
    if not isinstance(name, str):
        return f"names must be strings, got {type(name).__name__}"
    if not name:
        return "the name is empty"
    if name.startswith("_"):
        return "names must start with a letter (names starting with an underscore are not allowed)"
    if not _IDENTIFIER.match(name):
        if not name[0].isascii() or not name[0].isalpha():
            return "names must start with a letter (A-Z, a-z)"
        return "names may contain only ASCII letters, digits and underscores"
    if keyword.iskeyword(name):
        return f"{name!r} is a Python keyword"
    if name == "pi":
        return "'pi' is the constant pi"
    if name in FUNCTIONS:
        return f"{name!r} is a function expressions may call"
    return None


def exact_number(value: int | float) -> sp.Rational:
    """Return the exact rational a decimal literal denotes (``0.4318 -> 2159/5000``, not the binary float).

    Python's ``repr`` of a float is the shortest decimal that round-trips, i.e. the text the user wrote.
    """
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ExpressionError(f"expected a number, got {type(value).__name__} {value!r}")
    if isinstance(value, float) and not (value == value and abs(value) != float("inf")):
        raise ExpressionError(f"expected a finite number, got {value!r}")
    if isinstance(value, int):
        return sp.Integer(value)
    fraction = Fraction(repr(float(value)))  # float(): a numpy float64 repr is "np.float64(...)"
    return sp.Rational(fraction.numerator, fraction.denominator)


def parse_expression(text: str, names: Mapping[str, sp.Symbol]) -> sp.Expr:
    """Parse a field expression over ``names`` and ``pi`` into an exact SymPy expression.

    Parameters
    ----------
    text : str
        The field text, for example ``"-pi/2"`` or ``"a3 + 0.02"``.
    names : mapping of str to sympy.Symbol
        The parameter names the expression may use.

    Returns
    -------
    sympy.Expr
        The expression, with exact rationals for decimal literals.

    Raises
    ------
    ExpressionError
        If the text is not in the grammar; nothing in it is executed.

    Examples
    --------
    >>> import sympy as sp
    >>> parse_expression("-pi/2", {})
    -pi/2
    >>> L1, L2 = sp.symbols("L1 L2")
    >>> parse_expression("L1 + 0.5*L2", {"L1": L1, "L2": L2})
    L1 + L2/2
    """
    expr = _parse(text, names)
    written = expression_text(expr)
    if isinstance(written, str) and len(written) > MAX_EXPRESSION_LENGTH:
        # what is read must be writable back (robot_to_toml) and readable again: refuse it here, not on the way back
        raise ExpressionError(f"{text!r} is {len(written)} characters long written exactly ({written[:30]}...), "
                              f"more than {MAX_EXPRESSION_LENGTH}: use numbers with fewer digits")
    return expr


def _parse(text: str, names: Mapping[str, sp.Symbol]) -> sp.Expr:
    if not isinstance(text, str):
        raise ExpressionError(f"expected a string expression, got {type(text).__name__}")
    if len(text) > MAX_EXPRESSION_LENGTH:
        raise ExpressionError(f"expression longer than {MAX_EXPRESSION_LENGTH} characters")
    if not text.strip():
        raise ExpressionError("empty expression")
    try:
        with warnings.catch_warnings():  # "invalid escape sequence", "is with a literal": the tree says it plainer
            warnings.simplefilter("ignore", SyntaxWarning)
            tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise ExpressionError(f"cannot parse {text!r}: not a valid expression") from None
    return _build(tree.body, names, text)


FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "sqrt": sp.sqrt, "atan": sp.atan, "atan2": sp.atan2}
"""The functions a field may call: exact unit axes (``sqrt(2)/2``), the axes a DH table with a generic twist gives
(``cos(3/10)``), angles given by two lengths (``atan2(y, x)``, the angle of the point (x, y), and ``atan(t)``)."""

_ARGUMENTS = {"atan2": ("y", "x")}
"""The argument names of the functions that take more than one (every other function takes one)."""

_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
}


def _build(node: ast.AST, names: Mapping[str, sp.Symbol], text: str) -> sp.Expr:
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float) and not isinstance(node.value, bool):
        return exact_number(node.value)
    if isinstance(node, ast.Name):
        if node.id == "pi":
            return sp.pi
        if node.id in names:
            return names[node.id]
        known = ", ".join(sorted(names)) or "none declared"
        raise ExpressionError(f"unknown name {node.id!r} in {text!r} (parameters: {known})")
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        operand = _build(node.operand, names, text)
        return -operand if isinstance(node.op, ast.USub) else operand
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        left, right = _build(node.left, names, text), _build(node.right, names, text)
        if isinstance(node.op, ast.Div) and right == 0:
            raise ExpressionError(f"division by zero in {text!r}")
        return _small_powers(_BINARY[type(node.op)](left, right), text)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
        exponent = node.right
        if isinstance(exponent, ast.UnaryOp) and isinstance(exponent.op, ast.USub):
            exponent = exponent.operand
        if not (
            isinstance(exponent, ast.Constant)
            and type(exponent.value) is int
            and exponent.value <= MAX_EXPONENT
        ):
            raise ExpressionError(f"only small integer powers (up to {MAX_EXPONENT}) are allowed in {text!r}")
        base, power = _build(node.left, names, text), _build(node.right, names, text)
        if base == 0 and power < 0:
            raise ExpressionError(f"division by zero in {text!r}")
        bits = max((max(abs(r.p).bit_length(), r.q.bit_length()) for r in base.atoms(sp.Rational)), default=0)
        if bits * abs(int(power)) > MAX_POWER_BITS:
            raise ExpressionError(f"number too large in {text!r}")
        return _small_powers(base**power, text)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS:
        return _call(node, node.func.id, names, text)
    raise ExpressionError(f"{_what(node)} not allowed in {text!r}: use numbers, names, + - * / **, pi and "
                          f"{_signatures()}")


def _signatures() -> str:
    """The callable functions as they are written: ``sin(x), cos(x), sqrt(x), atan(x), atan2(y, x)``."""
    return ", ".join(f"{name}({', '.join(_ARGUMENTS.get(name, ('x',)))})" for name in FUNCTIONS)


def _call(node: ast.Call, name: str, names: Mapping[str, sp.Symbol], text: str) -> sp.Expr:
    r"""One call of a whitelisted function, with the number of arguments it takes and their domain checked.

    :math:`\sqrt{x}` needs :math:`x \ge 0`; :math:`\operatorname{atan2}(y, x)`, the angle of the point
    :math:`(x, y)`, needs :math:`(x, y) \ne (0, 0)`.
    """
    expected = _ARGUMENTS.get(name, ("x",))
    if node.keywords or len(node.args) != len(expected) or any(isinstance(a, ast.Starred) for a in node.args):
        given, count = len(node.args) + len(node.keywords), f"{len(expected)} argument{'s' * (len(expected) > 1)}"
        raise ExpressionError(f"function calls are not allowed in {text!r} with {given} argument{'s' * (given != 1)}: "
                              f"write {name}({', '.join(expected)}) ({name} takes {count}, by position)")
    arguments = [_build(argument, names, text) for argument in node.args]
    if name == "sqrt" and (arguments[0].is_extended_negative or arguments[0].has(sp.zoo, sp.nan, sp.oo)):
        raise ExpressionError(f"square root of a negative number in {text!r}")
    if name == "atan2" and all(argument.is_zero for argument in arguments):
        raise ExpressionError(f"atan2(0, 0) has no value in {text!r}: the point (x, y) must not be the origin")
    result = FUNCTIONS[name](*arguments)
    if result.has(sp.nan, sp.zoo):
        raise ExpressionError(f"{name} has no value in {text!r}")
    return result


_OPERATORS = {
    ast.FloorDiv: "//", ast.Mod: "%", ast.MatMult: "@", ast.LShift: "<<", ast.RShift: ">>", ast.BitOr: "|",
    ast.BitXor: "^", ast.BitAnd: "&", ast.Not: "not", ast.Invert: "~",
}
_KINDS: dict[type, str] = {
    ast.Call: "function calls are", ast.IfExp: "conditional expressions (x if c else y) are",
    ast.JoinedStr: "string formatting (f-strings) is", ast.FormattedValue: "string formatting (f-strings) is",
    ast.Attribute: "attributes (x.y) are", ast.Subscript: "indexing (x[i]) is", ast.Lambda: "lambda functions are",
    ast.Compare: "comparisons are", ast.BoolOp: "'and' and 'or' are", ast.NamedExpr: "assignments (:=) are",
    ast.List: "lists are", ast.Tuple: "tuples (commas) are", ast.Set: "sets are", ast.Dict: "dictionaries are",
    ast.ListComp: "comprehensions are", ast.SetComp: "comprehensions are", ast.DictComp: "comprehensions are",
    ast.GeneratorExp: "comprehensions are", ast.Starred: "starred expressions (*x) are",
    ast.Await: "'await' is", ast.Yield: "'yield' is", ast.YieldFrom: "'yield' is", ast.Slice: "slices are",
}


def _what(node: ast.AST) -> str:
    """The construct ``node`` is, in plain words, with its verb: ``"function calls are"``."""
    if isinstance(node, ast.BinOp | ast.UnaryOp):
        return f"the operator {_OPERATORS.get(type(node.op), type(node.op).__name__)} is"
    if isinstance(node, ast.Constant):
        value = node.value
        if isinstance(value, str | bytes):
            return "strings are"
        if isinstance(value, complex):
            return "complex numbers are"
        if value is Ellipsis:
            return "'...' is"
        return f"{value!r} is"  # True, False, None
    return _KINDS.get(type(node), "this kind of expression is")


def _small_powers(expr: sp.Expr, text: str) -> sp.Expr:
    """Reject a result SymPy merged into a power beyond the grammar (``L1**8*L1 -> L1**9``): unwritable."""
    if any(p.exp.is_Integer and abs(p.exp) > MAX_EXPONENT for p in expr.atoms(sp.Pow)):
        raise ExpressionError(f"only small integer powers (up to {MAX_EXPONENT}) are allowed in {text!r}")
    return expr


def expression_text(expr: sp.Expr) -> int | float | str:
    """Write an exact expression back in the robot-file grammar (inverse of :func:`parse_expression`).

    Integers stay integers, terminating decimals become floats (``2159/5000 -> 0.4318``), everything else a
    string that :func:`parse_expression` reads back to the same expression.
    """
    expr = sp.sympify(expr)
    if expr.is_Integer:
        return int(expr)
    if expr.is_Rational:
        as_float = float(expr)
        if exact_number(as_float) == expr:
            return as_float
    text = sp.sstr(expr)
    try:  # sstr can regroup: 1/(2*(L1 + L2)) reads back as 1/(2*L1 + 2*L2), a different tree
        if _parse(text, {symbol.name: symbol for symbol in expr.free_symbols}) == expr:
            return text
    except ExpressionError:
        pass
    return _tree_text(expr)


def _tree_text(expr: sp.Expr) -> str:
    """Write ``expr`` node by node, fully parenthesised, so that parsing rebuilds the very same tree."""
    if expr.is_Integer:
        return str(expr) if expr >= 0 else f"({expr})"
    if expr.is_Rational:
        return f"({expr.p}/{expr.q})"
    if expr.is_Add:
        return "(" + " + ".join(_tree_text(term) for term in expr.args) + ")"
    if expr.is_Mul:
        coefficient, rest = expr.as_coeff_Mul()
        factors = [_tree_text(factor) for factor in sp.Mul.make_args(rest)]
        product = "*".join(factors) if len(factors) == 1 else "(" + "*".join(factors) + ")"
        return product if coefficient == 1 else f"({_tree_text(coefficient)}*{product})"
    if expr.is_Pow and abs(expr.exp) == sp.S.Half:
        root = f"sqrt({_tree_text(expr.base)})"
        return root if expr.exp > 0 else f"(1/{root})"
    if expr.is_Pow:
        return f"{_tree_text(expr.base)}**({expr.exp})"
    if isinstance(expr, sp.sin | sp.cos | sp.atan | sp.atan2):
        return f"{type(expr).__name__}({', '.join(_tree_text(argument) for argument in expr.args)})"
    return sp.sstr(expr)  # pi and parameter symbols


ANGLE_SNAP_TOLERANCE = 1e-9
"""How close (radians) a number must be to a multiple of pi/12 for :func:`snap_angle` to make it exact."""


def snap_angle(value: sp.Rational) -> sp.Expr:
    r"""An exact angle: ``k*pi/12`` when ``value`` is within 1e-9 of it, else ``value`` unchanged.

    Examples
    --------
    >>> snap_angle(sp.Rational(15707963267949, 10**13))
    pi/2
    >>> snap_angle(sp.Rational(3, 10))
    3/10
    """
    turns = float(value) / (math.pi / 12)
    if not math.isfinite(turns):  # beyond float range: no multiple of pi/12 to snap to
        return value
    k = round(turns)
    if abs(float(value) - k * math.pi / 12) < ANGLE_SNAP_TOLERANCE:
        return sp.pi * sp.Rational(k, 12)
    return value
