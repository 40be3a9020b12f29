"""The robot-file expression grammar: exact numbers, whitelisted syntax, nothing executed, and its inverse."""

from __future__ import annotations

import math
import re
import subprocess
import sys

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symjac.errors import ExpressionError, SymjacError
from symjac.model.expressions import (
    MAX_EXPONENT,
    MAX_EXPRESSION_LENGTH,
    exact_number,
    expression_text,
    is_valid_name,
    name_problem,
    parse_expression,
)

L1, L2, a3 = sp.symbols("L1 L2 a3", real=True)
NAMES = {"L1": L1, "L2": L2, "a3": a3}


def parse(text):
    return parse_expression(text, NAMES)


def reparse(written):
    """Read back what expression_text wrote: a number stays a number, a string is parsed."""
    return parse(written) if isinstance(written, str) else exact_number(written)


# --------------------------------------------------------------------------------------------- numbers


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0", sp.Integer(0)),
        ("7", sp.Integer(7)),
        ("-3", sp.Integer(-3)),
        ("0.4318", sp.Rational(2159, 5000)),
        ("0.1", sp.Rational(1, 10)),
        ("-0.5", sp.Rational(-1, 2)),
        ("1e-3", sp.Rational(1, 1000)),
        ("2.5e2", sp.Integer(250)),
        ("0.089159", sp.Rational(89159, 1000000)),
        ("1_000", sp.Integer(1000)),
    ],
)
def test_numbers_become_exact_rationals(text, expected):
    value = parse(text)
    assert value == expected
    assert isinstance(value, sp.Rational)
    assert not value.atoms(sp.Float)


def test_decimal_literal_is_the_decimal_not_the_binary_float():
    assert parse("0.4318") == sp.Rational(2159, 5000)
    assert exact_number(0.4318) == sp.Rational(2159, 5000)
    assert exact_number(0.4318) != sp.Rational(0.4318)  # the binary float is a different rational


def test_parsed_numbers_are_exact_in_arithmetic():
    assert parse("0.1 + 0.2") == sp.Rational(3, 10)
    assert parse("1/3") == sp.Rational(1, 3)
    assert parse("1/3 + 1/6") == sp.Rational(1, 2)


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (0, sp.Integer(0)),
        (42, sp.Integer(42)),
        (-7, sp.Integer(-7)),
        (10**30, sp.Integer(10**30)),
        (0.4318, sp.Rational(2159, 5000)),
        (-0.39225, sp.Rational(-1569, 4000)),
        (2.0, sp.Integer(2)),
        (-0.0, sp.Integer(0)),
        (1e-7, sp.Rational(1, 10**7)),
        (1e22, sp.Integer(10**22)),
    ],
)
def test_exact_number(value, expected):
    result = exact_number(value)
    assert result == expected
    assert isinstance(result, sp.Rational)


def test_exact_number_of_an_int_is_an_integer():
    assert isinstance(exact_number(3), sp.Integer)


def test_exact_number_accepts_a_numpy_float():
    np = pytest.importorskip("numpy")
    assert exact_number(np.float64(0.4318)) == sp.Rational(2159, 5000)


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, float("nan")])
def test_exact_number_rejects_non_finite(value):
    with pytest.raises(ExpressionError, match="finite"):
        exact_number(value)


@pytest.mark.parametrize("value", [True, False, "0.5", None, [1], 1j, sp.Rational(1, 2)])
def test_exact_number_rejects_non_numbers(value):
    with pytest.raises(ExpressionError, match="expected a number"):
        exact_number(value)


# --------------------------------------------------------------------------------------------- grammar


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("pi", sp.pi),
        ("-pi/2", -sp.pi / 2),
        ("pi/2", sp.pi / 2),
        ("+pi", sp.pi),
        ("- pi / 2", -sp.pi / 2),
        ("160*pi/180", 8 * sp.pi / 9),
        ("L1", L1),
        ("-a3", -a3),
        ("L1 + L2", L1 + L2),
        ("L1 - L2", L1 - L2),
        ("L1*L2", L1 * L2),
        ("L1/L2", L1 / L2),
        ("a3 + 0.02", a3 + sp.Rational(1, 50)),
        ("L1 + 0.5*L2", L1 + L2 / 2),
        ("(L1 + L2)*2", 2 * L1 + 2 * L2),
        ("2*(L1 - (L2 - 1))", 2 * L1 - 2 * L2 + 2),
        ("((L1))", L1),
        ("  L1 + L2  ", L1 + L2),
        ("L1**2", L1**2),
        ("L1**2 + L2**2", L1**2 + L2**2),
        ("(L1 + L2)**2", (L1 + L2) ** 2),
        ("2**8", sp.Integer(256)),
        ("2**-1", sp.Rational(1, 2)),
        ("L1**-2", L1**-2),
        ("L1**0", sp.Integer(1)),
        ("pi**2/4", sp.pi**2 / 4),
        ("0**0", sp.Integer(1)),
        ("-2**2", sp.Integer(-4)),
    ],
)
def test_grammar_accepts(text, expected):
    assert parse(text) == expected


def test_parameter_symbols_are_the_ones_given():
    symbol = sp.Symbol("L1", real=True)
    assert parse_expression("L1", {"L1": symbol}) is symbol
    assert parse_expression("2*L1", {"L1": symbol}).free_symbols == {symbol}


def test_pi_needs_no_declaration():
    assert parse_expression("pi", {}) is sp.pi


@pytest.mark.parametrize("text", [f"L1**{MAX_EXPONENT}", f"L1**-{MAX_EXPONENT}", "2**8", "(L1 + 1)**8"])
def test_small_integer_powers_allowed(text):
    parse(text)


@pytest.mark.parametrize(
    "text",
    [
        f"L1**{MAX_EXPONENT + 1}",
        f"L1**-{MAX_EXPONENT + 1}",
        "2**100",
        "10**1000000000",
        "9**99999999999999",
        "L1**0.5",
        "2**0.5",
        "L1**2.0",
        "L1**L2",
        "L1**pi",
        "2**(1 + 1)",
        "2**(-(-2))",
        "2**True",
        "2**2**2",
    ],
)
def test_large_float_or_non_constant_exponents_rejected(text):
    with pytest.raises(ExpressionError, match="small integer powers"):
        parse(text)


@pytest.mark.parametrize("text", ["(L1**2)**8", "(L1**8)*L1", "L1*L1*L1*L1*L1*L1*L1*L1*L1", "(pi**4)**4", "1/L1**8/L1"])
def test_powers_merged_beyond_the_limit_rejected(text):
    # SymPy would merge these into L1**16, L1**9, ... which expression_text could not write back
    with pytest.raises(ExpressionError, match="small integer powers"):
        parse(text)


@pytest.mark.parametrize("base", ["9", "(9*L1)", "(2 + L1/7)"])
def test_nested_powers_cannot_blow_up(base):
    # each level multiplies the exponent by 8: forty levels would be a number with ~10**36 digits
    # (run in a child process: without the guard this does not fail, it hangs and eats memory)
    text = base
    while len(text) + 5 <= MAX_EXPRESSION_LENGTH:
        text = f"({text}**8)"
    script = (
        "import sympy as sp\n"
        "from symjac.errors import ExpressionError\n"
        "from symjac.model.expressions import parse_expression\n"
        "try:\n"
        f"    parse_expression({text!r}, {{'L1': sp.Symbol('L1', real=True)}})\n"
        "except ExpressionError as error:\n"
        "    print('rejected:', error)\n"
    )
    try:
        result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        pytest.fail(f"parsing {text!r} did not finish")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("rejected:")


def test_moderate_nested_power_is_still_exact():
    assert parse("(2**8)**8") == sp.Integer(2) ** 64


def test_unknown_name_rejected_naming_it():
    with pytest.raises(ExpressionError, match=r"unknown name 'L3'") as info:
        parse("L1 + L3")
    assert "L1" in str(info.value)  # the message lists the declared parameters
    assert "L2" in str(info.value)


def test_unknown_name_without_parameters():
    with pytest.raises(ExpressionError, match=r"unknown name 'x'.*none declared"):
        parse_expression("x", {})


@pytest.mark.parametrize("name", ["e", "E", "I", "oo", "sin", "theta1", "Pi", "PI", "sqrt"])
def test_sympy_names_are_not_implicitly_known(name):
    with pytest.raises(ExpressionError, match=f"unknown name '{name}'"):
        parse_expression(name, {})


@pytest.mark.parametrize("text", ["1/0", "L1/0", "1/(L1 - L1)", "1/(pi - pi)", "L1/0.0", "0**-1", "(L1 - L1)**-2"])
def test_division_by_zero_rejected(text):
    with pytest.raises(ExpressionError, match="division by zero"):
        parse(text)


@pytest.mark.parametrize("text", ["", " ", "\t\n"])
def test_empty_expression_rejected(text):
    with pytest.raises(ExpressionError, match="empty"):
        parse(text)


def test_over_long_expression_rejected():
    longest = "1" * MAX_EXPRESSION_LENGTH
    assert parse(longest) == sp.Integer(longest)
    with pytest.raises(ExpressionError, match="longer than"):
        parse("1" * (MAX_EXPRESSION_LENGTH + 1))
    with pytest.raises(ExpressionError, match="longer than"):
        parse("+".join(["L1"] * 100))


@pytest.mark.parametrize("text", ["1 +", "L1 L2", "(L1", "L1)", "1..2", "=", "L1 = 2", "import os", "2 ** ** 2"])
def test_syntax_errors_rejected(text):
    with pytest.raises(ExpressionError, match="cannot parse"):
        parse(text)


@pytest.mark.parametrize("value", [1, 0.5, None, b"L1", ["L1"]])
def test_non_string_rejected(value):
    with pytest.raises(ExpressionError, match="expected a string"):
        parse_expression(value, NAMES)


@pytest.mark.parametrize(
    ("text", "node"),
    [
        ("lambda: 0", "lambda functions are"),
        ("lambda x: x", "lambda functions are"),
        ("L1.real", "attributes (x.y) are"),
        ("pi.evalf", "attributes (x.y) are"),
        ("().__class__", "attributes (x.y) are"),
        ("L1[0]", "indexing (x[i]) is"),
        ("(1, 2)[0]", "indexing (x[i]) is"),
        ("exp(L1)", "function calls are"),
        ("log(2)", "function calls are"),
        ("sin(L1, 2)", "function calls are"),
        ("L1()", "function calls are"),
        ("'L1'", "strings are"),
        ("'1'", "strings are"),
        ("b'1'", "strings are"),
        ("True", "True is"),
        ("False", "False is"),
        ("None", "None is"),
        ("...", "'...' is"),
        ("1j", "complex numbers are"),
        ("L1 + True", "True is"),
        ("[1]", "lists are"),
        ("(1, 2)", "tuples (commas) are"),
        ("{1: 2}", "dictionaries are"),
        ("{1}", "sets are"),
        ("L1 < L2", "comparisons are"),
        ("L1 and L2", "'and' and 'or' are"),
        ("not L1", "the operator not is"),
        ("~1", "the operator ~ is"),
        ("1 // 2", "the operator // is"),
        ("5 % 3", "the operator % is"),
        ("1 << 2", "the operator << is"),
        ("L1 @ L2", "the operator @ is"),
        ("1 if L1 else 2", "conditional expressions (x if c else y) are"),
        ("(x := 1)", "assignments (:=) are"),
        ("[x for x in ()]", "comprehensions are"),
        ("f'{L1}'", "string formatting (f-strings) is"),
        ("*L1", None),
    ],
)
def test_disallowed_syntax_rejected(text, node):
    with pytest.raises(ExpressionError) as info:
        parse(text)
    if node is not None:
        assert str(info.value).startswith(f"{node} not allowed in ")  # plain words, not the ast node's name
        assert not re.search(r"\b(Call|IfExp|JoinedStr|BinOp|UnaryOp|Constant|Attribute)\b", str(info.value))


HOSTILE = [
    "__import__('os').system('touch {path}')",
    "__import__('os').system('touch {path}') or 1",
    "1 + __import__('pathlib').Path('{path}').touch()",
    "open('{path}', 'w').write('x')",
    "[c for c in ().__class__.__base__.__subclasses__()][0]",
    "(lambda: __import__('os').system('touch {path}'))()",
    "L1.__class__.__init__.__globals__['os'].system('touch {path}')",
    "exec(\"open('{path}', 'w')\")",
    "eval(\"open('{path}', 'w')\")",
]


@pytest.mark.parametrize("template", HOSTILE)
def test_hostile_text_rejected_without_running(template, tmp_path):
    target = tmp_path / "pwned_symjac"
    text = template.format(path=target)
    with pytest.raises(ExpressionError):
        parse(text)
    assert not target.exists()


def test_hostile_text_rejected_without_running_with_the_brief_example(tmp_path):
    target = tmp_path / "pwned_symjac"
    with pytest.raises(ExpressionError, match="not allowed"):
        parse_expression(f"__import__('os').system('touch {target}')", {})
    assert not target.exists()
    with pytest.raises(ExpressionError, match="not allowed"):
        parse_expression("().__class__", {})


def test_expression_error_is_a_symjac_value_error():
    with pytest.raises(SymjacError):
        parse("nope")
    with pytest.raises(ValueError):
        parse("nope")


# --------------------------------------------------------------------------------------------- names


@pytest.mark.parametrize("name", ["L1", "a", "a2", "d_4", "theta_offset", "Lx_", "dF", "x" * 50, "tan", "e"])
def test_valid_names(name):
    assert is_valid_name(name)


@pytest.mark.parametrize(
    "name",
    ["", "2x", "a-b", "a b", "a.b", "_x", "__class__", "class", "lambda", "None", "True", "pi", "é", "Lé", "a\n", "1"],
)
def test_invalid_names(name):
    assert not is_valid_name(name)


# --------------------------------------------------------------------------------------------- expression_text


@pytest.mark.parametrize(
    ("expr", "written"),
    [
        (sp.Integer(0), 0),
        (sp.Integer(3), 3),
        (sp.Integer(-12), -12),
        (sp.Rational(2159, 5000), 0.4318),
        (sp.Rational(-1, 2), -0.5),
        (-sp.pi / 2, "-pi/2"),
        (L1 + L2, "L1 + L2"),
        (sp.Rational(1, 3), "1/3"),
    ],
)
def test_expression_text(expr, written):
    result = expression_text(expr)
    assert result == written
    assert type(result) is type(written)


def test_expression_text_accepts_plain_python_numbers():
    assert expression_text(5) == 5
    assert expression_text(sp.Rational(1, 4)) == 0.25


@pytest.mark.parametrize(
    "expr",
    [
        sp.Integer(0),
        sp.Integer(7),
        sp.Integer(-7),
        sp.Integer(10**25),
        sp.Rational(2159, 5000),
        sp.Rational(-1569, 4000),
        sp.Rational(1, 3),
        sp.Rational(-22, 7),
        sp.Rational(1, 2**60),
        sp.Rational(1, 10**30),
        sp.pi,
        -sp.pi / 2,
        8 * sp.pi / 9,
        sp.pi**2 / 4,
        1 / sp.pi,
        L1 + L2,
        L1 - L2,
        -a3,
        L1 * L2 / 3,
        L1 / L2,
        1 / (L1 + L2),
        L1**-2,
        L1**8 + L2**-8,
        (L1 + L2) ** 2,
        a3 + sp.Rational(1, 50),
        sp.Rational(2159, 5000) * L1 - sp.pi / 3,
    ],
)
def test_expression_text_round_trip(expr):
    assert reparse(expression_text(expr)) == expr


@pytest.mark.parametrize("text", ["0.4318", "-pi/2", "L1 + L2", "1/3", "(L1 + L2)**2/7", "-(a3 - 0.02)*pi/180"])
def test_parse_then_write_then_parse(text):
    expr = parse(text)
    assert reparse(expression_text(expr)) == expr


@pytest.mark.parametrize(
    "expr",
    [
        sp.Rational(1, 2) / (L1 + L2),  # sstr: 1/(2*(L1 + L2)), which parses to 1/(2*L1 + 2*L2)
        sp.Rational(1, 1000) / (1 + sp.pi),
        -1 / (L1 - L2),
        sp.Mul(2, L1, L1 + L2),
        sp.Rational(-3, 7) * L1 * (L1 + L2) ** -2,
    ],
)
def test_expression_text_round_trip_where_sympy_would_regroup(expr):
    written = expression_text(expr)
    assert isinstance(written, str)
    assert reparse(written) == expr


def test_expression_text_keeps_the_readable_form_when_it_round_trips():
    assert expression_text(8 * sp.pi / 9) == "8*pi/9"
    assert expression_text(L1 / L2) == "L1/L2"
    assert expression_text(L1**-2) == "L1**(-2)"


# --------------------------------------------------------------------------------------------- property

_ATOMS = st.one_of(
    st.integers(min_value=-50, max_value=50).map(str),
    st.decimals(min_value=-10, max_value=10, places=3, allow_nan=False, allow_infinity=False).map(str),
    st.sampled_from(["pi", "L1", "L2", "a3"]),
)


def _combine(children):
    binary = st.tuples(children, st.sampled_from(["+", "-", "*", "/"]), children).map(
        lambda t: f"({t[0]} {t[1]} {t[2]})"
    )
    power = st.tuples(children, st.integers(min_value=-3, max_value=3)).map(lambda t: f"({t[0]})**{t[1]}")
    negation = children.map(lambda c: f"-{c}")
    return st.one_of(binary, power, negation)


EXPRESSION_TEXTS = st.recursive(_ATOMS, _combine, max_leaves=6)


@settings(deadline=None, max_examples=50)
@given(EXPRESSION_TEXTS)
def test_round_trip_property(text):
    try:
        expr = parse(text)
    except ExpressionError:
        return  # division by zero, a merged power beyond the limit, ...: rejected texts have nothing to round-trip
    written = expression_text(expr)
    assert isinstance(written, int | float | str)
    assert reparse(written) == expr


@settings(deadline=None, max_examples=50)
@given(st.fractions(max_denominator=10**6))
def test_round_trip_property_of_rationals(fraction):
    expr = sp.Rational(fraction.numerator, fraction.denominator)
    assert reparse(expression_text(expr)) == expr


@settings(deadline=None, max_examples=50)
@given(st.floats(allow_nan=False, allow_infinity=False))
def test_exact_number_matches_the_shortest_decimal(value):
    assert exact_number(value) == sp.Rational(repr(value))
    assert float(exact_number(value)) == value


@pytest.mark.parametrize(("text", "expected"), [
    ("sqrt(2)/2", sp.sqrt(2) / 2), ("cos(3/10)", sp.cos(sp.Rational(3, 10))), ("-sin(pi/6)", -sp.S.Half),
    ("sin(0.25)**2", sp.sin(sp.Rational(1, 4))**2), ("1/sqrt(3)", sp.sqrt(3) / 3)])
def test_the_four_functions_are_read_exactly_and_written_back(text, expected):
    value = parse_expression(text, {})
    assert value == expected
    assert parse_expression(str(expression_text(value)), {}) == value


def test_a_square_root_of_a_negative_number_is_refused():
    with pytest.raises(ExpressionError, match="square root of a negative number"):
        parse_expression("sqrt(-2)", {})


@pytest.mark.parametrize("text", ["sqrt(cos(1)**2 + sin(1)**2 - 2)", "sqrt(-2)", "tan(1)", "sqrt(1/0)"])
def test_a_function_outside_the_grammar_or_a_root_of_a_negative_is_refused_in_words(text):
    with pytest.raises(ExpressionError):
        parse_expression(text, {})


@pytest.mark.parametrize("name", ["sin", "cos", "sqrt"])
def test_the_function_names_are_not_parameter_names(name):
    assert "function" in name_problem(name)


# ------------------------------------------------------------------------------------ atan and atan2 (issue 42)

h, w = sp.symbols("h w", real=True)


@pytest.mark.parametrize(("text", "expected", "written"), [
    ("atan2(0.128, 0.024)", sp.atan(sp.Rational(16, 3)), "atan(16/3)"),  # SymPy's exact form for x > 0
    ("atan2(0.128, -0.024)", sp.pi - sp.atan(sp.Rational(16, 3)), "pi - atan(16/3)"),
    ("atan2(1, 1)", sp.pi / 4, "pi/4"), ("atan2(sqrt(3), 1)", sp.pi / 3, "pi/3"), ("atan2(-1, 0)", -sp.pi / 2, "-pi/2"),
    ("atan(0.5)", sp.atan(sp.S.Half), "atan(1/2)"), ("atan(1)", sp.pi / 4, "pi/4"),
    ("atan2(h, w)", sp.atan2(h, w), "atan2(h, w)"),
    ("pi/2 - atan2(2*h, w + 0.1)", sp.pi / 2 - sp.atan2(2 * h, w + sp.Rational(1, 10)), None),
])
def test_atan_and_atan2_are_read_exactly_and_written_back(text, expected, written):
    names = {"h": h, "w": w}
    value = parse_expression(text, names)
    assert value == expected
    text_back = expression_text(value)
    if written is not None:
        assert text_back == written
    assert parse_expression(str(text_back), names) == value


def test_an_atan2_of_parameters_is_written_back_through_the_tree_writer_too():
    value = sp.Rational(1, 2) / (sp.atan2(h, w) + sp.atan(h))  # sstr regroups 1/(2*(...)): the tree writer's turn
    written = expression_text(value)
    assert written == "((1/2)*(atan(h) + atan2(h, w))**(-1))"
    assert parse_expression(written, {"h": h, "w": w}) == value


@pytest.mark.parametrize("text", ["atan2(0, 0)", "atan2(0.0, -0)", "atan2(sin(pi), 0)", "atan2(L1 - L1, 0)"])
def test_atan2_of_the_origin_is_refused(text):
    with pytest.raises(ExpressionError, match=r"atan2\(0, 0\) has no value in .*: the point \(x, y\) must not be the"):
        parse(text)


@pytest.mark.parametrize(("text", "message"), [
    ("atan2(1)", r"write atan2\(y, x\) .*atan2 takes 2 arguments"),
    ("atan2(1, 2, 3)", r"write atan2\(y, x\) .*atan2 takes 2 arguments"),
    ("atan2()", r"write atan2\(y, x\)"),
    ("atan(1, 2)", r"with 2 arguments: write atan\(x\) \(atan takes 1 argument, by position\)"),
    ("atan2(y=1, x=2)", r"by position"),
    ("atan2(*L1)", r"write atan2\(y, x\)"),
    ("atan(*L1)", r"write atan\(x\)"),
    ("sin(L1, 2)", "function calls are"),
])
def test_a_wrong_number_of_arguments_is_refused_in_words(text, message):
    with pytest.raises(ExpressionError, match=message):
        parse(text)


@pytest.mark.parametrize(("text", "what"), [
    ("atan2(exp(1), 1)", "function calls are"), ("atan(log(2))", "function calls are"),
    ("atan2(L1, tan(1))", "function calls are"), ("atan2(L1.real, 1)", "attributes"),
    ("atan2(theta9, 1)", "unknown name"),
    ("atan2('1', 1)", "strings are"), ("atan2((1, 2), 1)", "tuples"), ("atan(sqrt(-1))", "square root of a negative"),
    ("atan2(1, 1/0)", "division by zero"), ("math.atan2(1, 1)", "function calls are"),
    ("atan2.__call__(1, 1)", "function calls are"),
])
def test_calls_nested_in_atan2_are_held_to_the_same_whitelist(text, what):
    with pytest.raises(ExpressionError, match=re.escape(what)):
        parse(text)


def test_the_refusal_lists_the_callable_functions_with_their_arguments():
    with pytest.raises(ExpressionError, match=re.escape("sin(x), cos(x), sqrt(x), atan(x), atan2(y, x)")):
        parse("exp(1)")


def test_nested_whitelisted_calls_are_fine():
    assert float(parse("atan2(sin(1), cos(1))")) == pytest.approx(1.0)
    assert parse("atan(atan2(1, 1))") == sp.atan(sp.pi / 4)


@pytest.mark.parametrize("name", ["atan", "atan2"])
def test_atan_names_are_function_names(name):
    assert "function" in name_problem(name)


def test_atan2_prints_readably():
    from symjac.printing.latex import latex
    from symjac.printing.pretty import pretty

    assert latex(sp.atan2(h, w)) == r"\operatorname{atan2}\left(h, w\right)"
    assert "atan" in latex(sp.atan(sp.Rational(16, 3))) and r"\frac{16}{3}" in latex(sp.atan(sp.Rational(16, 3)))
    assert pretty(sp.atan2(h, w)) == "atan2(h, w)"


# --------------------------------------------------------------------------------------------- a robot file

def _arm(offset: str, parameters: str = "") -> str:
    return (f'name = "offset2r"\nconvention = "standard"\n[parameters]\nL1 = 0.5\nL2 = 0.4\n{parameters}\n'
            f'[[joints]]\ntype = "revolute"\nalpha = 0\na = "L1"\nd = 0\ntheta = {offset}\n'
            '[[joints]]\ntype = "revolute"\nalpha = 0\na = "L2"\nd = 0\ntheta = 0\n')


def test_a_dh_offset_written_as_atan2_round_trips_and_gives_the_decimal_arms_jacobian():
    import numpy as np

    from symjac.codegen import generate
    from symjac.kinematics.chain import Chain, forward_kinematics
    from symjac.kinematics.jacobian import jacobian
    from symjac.kinematics.numeric import numeric_jacobian
    from symjac.model.io import robot_from_toml, robot_to_toml

    robot = robot_from_toml(_arm('"atan2(0.128, 0.024)"'))
    assert robot.joints[0].theta == sp.atan(sp.Rational(16, 3))
    written = robot_to_toml(robot)
    assert 'theta = "atan(16/3)"' in written
    assert robot_from_toml(written) == robot  # what the writer writes reads back to the same robot
    decimal = robot_from_toml(_arm(repr(math.atan2(0.128, 0.024))))
    assert not Chain(robot).nested  # a joint's own offset keeps the textbook route (no generic rotation)

    J = jacobian(robot)
    assert J.has(sp.atan) and not J.has(sp.Float)
    for q in ([0.3, -0.7], [1.2, 0.4], [-2.0, 2.5]):
        np.testing.assert_allclose(numeric_jacobian(robot, q), numeric_jacobian(decimal, q), atol=1e-12)
        # against central differences of the tip's position
        point = forward_kinematics(robot)[:2, 3]
        values = {**dict(zip((robot.joints[0].variable, robot.joints[1].variable), q, strict=True)),
                  **{p.symbol: p.default for p in robot.parameters}}
        columns = []
        for i, variable in enumerate((robot.joints[0].variable, robot.joints[1].variable)):
            step = 1e-6
            plus, minus = dict(values), dict(values)
            plus[variable], minus[variable] = q[i] + step, q[i] - step
            columns.append((np.array(point.evalf(subs=plus), float) - np.array(point.evalf(subs=minus), float))
                           .ravel() / (2 * step))
        np.testing.assert_allclose(numeric_jacobian(robot, q)[:2], np.array(columns).T, atol=1e-7)

    namespace: dict = {}
    source = generate(robot)
    assert "atan" not in source and "1.3854483767992019" in source  # a float literal, computed once
    exec(compile(source, "offset2r_generated", "exec"), namespace)
    np.testing.assert_allclose(np.array(namespace["jacobian"]([0.3, -0.7])), numeric_jacobian(decimal, [0.3, -0.7]),
                               atol=1e-12)
    assert "sympy.atan(sympy.Rational(16, 3))" in generate(robot, "lambdify")


def test_an_atan2_of_parameters_at_the_origin_is_refused_naming_the_field():
    from symjac.errors import RobotFileError
    from symjac.model.io import robot_from_toml

    robot = robot_from_toml(_arm('"atan2(h, w)"', "h = 0.128\nw = 0.024"))
    assert robot_from_toml(_arm('"atan2(h, w)"', "h = 0.128\nw = 0.024")) == robot
    with pytest.raises(RobotFileError, match=r"joint 1.*theta.*not a finite number"):
        robot_from_toml(_arm('"atan2(h, w)"', "h = 0\nw = 0"))
    with pytest.raises(RobotFileError, match=r"joint 1.*theta.*atan2\(0, 0\) has no value"):
        robot_from_toml(_arm('"atan2(0, 0)"'))
