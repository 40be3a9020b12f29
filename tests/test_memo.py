"""The one memo: derived quantities are kept in their chain under typed keys, once per normalised request."""

from __future__ import annotations

import ast
import importlib
import inspect
from pathlib import Path

import pytest
import sympy as sp

import symjac
from symjac import load_robot
from symjac.analysis.manipulability import log_det_gradient
from symjac.analysis.singularity.determinant import determinant
from symjac.codegen import acceleration as codegen_acceleration
from symjac.codegen import generate
from symjac.codegen.lower import lowered_forward_kinematics, lowered_jacobian
from symjac.errors import ArgumentError, FrameError
from symjac.kinematics.acceleration import bias_acceleration, hessian
from symjac.kinematics.chain import Chain, MemoKey
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.memo import frame_of, memoized, one_of
from symjac.kinematics.numeric import numeric_jacobian

lowering = importlib.import_module("symjac.codegen.lower")  # the attribute symjac.codegen.lower is lower()


def test_every_key_in_a_chain_is_a_memo_key_naming_its_function():
    chain = Chain(load_robot("planar2r"))
    jacobian(chain, 1)
    bias_acceleration(chain)
    log_det_gradient(chain)
    numeric_jacobian(chain, [0.1, 0.2])
    keys = list(chain._memo)
    assert keys and all(isinstance(key, MemoKey) and callable(key.function) for key in keys)
    assert all(not isinstance(argument, str) or argument in ("wrist", "differentiation", "hessian")
               for key in keys for argument in key.arguments if not isinstance(argument, tuple))


def test_spellings_of_one_request_share_one_entry():
    chain = Chain(load_robot("puma560"))
    first = jacobian(chain, 3, point=(0, 0.0, 0))
    size = len(chain._memo)
    again = jacobian(chain, 3, "wrist", "differentiation", simplify=True)
    assert again == first and len(chain._memo) == size
    assert again is not jacobian(chain, 3)  # each caller gets its own mutable copy
    again[0, 0] = 1
    assert jacobian(chain, 3) == first


def test_a_robot_and_its_registered_chain_share_values():
    robot = load_robot("planar3r")
    assert determinant(robot) is determinant(robot, None, None, "tool", columns=[0, 1, 2])  # planar3r has a tool


def test_invalid_arguments_fail_before_anything_is_derived():
    chain = Chain(load_robot("planar2r"))
    with pytest.raises(FrameError):
        hessian(chain, 7)
    with pytest.raises(ArgumentError, match="unknown method 'guess'; choose one of hessian, differentiation"):
        bias_acceleration(chain, method="guess")
    assert not chain._memo


def test_the_decorator_normalises_in_order_and_keys_by_function():
    calls: list[tuple[object, ...]] = []

    @memoized(frame=frame_of, kind=one_of(("x", "y"), "kind"), shift=lambda chain, shift, frame: shift + frame)
    def shifted(chain: Chain, frame: int = 0, kind: str = "x", shift: int = 0) -> sp.Expr:
        calls.append((frame, kind, shift))
        return sp.Integer(shift)

    chain = Chain(load_robot("planar2r"))
    assert shifted(chain, 1, shift=1) == 2 and shifted(chain, 1, "x", 1) == 2
    assert calls == [(1, "x", 2)]
    assert MemoKey(shifted.__wrapped__, (1, "x", 2)) in chain._memo
    with pytest.raises(ArgumentError, match="unknown kind 'z'; choose one of x, y"):
        shifted(chain, kind="z")
    with pytest.raises(TypeError, match="no argument 'nothing'"):
        memoized(nothing=frame_of)(lambda chain, frame=0: frame)


@pytest.mark.parametrize("function", [jacobian, determinant, hessian, bias_acceleration, log_det_gradient,
                                      lowered_jacobian, lowered_forward_kinematics])
def test_memoized_functions_show_and_accept_their_first_argument_as_robot(function):
    first = next(iter(inspect.signature(function).parameters.values()))
    assert (first.name, first.kind) == ("robot", inspect.Parameter.POSITIONAL_OR_KEYWORD)
    assert function.__name__ == function.__wrapped__.__name__ and function.__doc__ == function.__wrapped__.__doc__


def test_the_robot_may_be_passed_by_keyword():
    assert jacobian(robot=load_robot("planar2r")) == jacobian(load_robot("planar2r"))
    assert jacobian(robot=load_robot("planar2r"), frame=1) == jacobian(load_robot("planar2r"), 1)
    assert determinant(robot=load_robot("planar3r")) == determinant(load_robot("planar3r"))
    with pytest.raises(TypeError, match="multiple values for argument 'robot'"):
        jacobian(load_robot("planar2r"), robot=load_robot("planar2r"))
    with pytest.raises(TypeError, match="missing a required argument: 'robot'"):
        jacobian(frame=1)


def test_a_memoized_function_may_not_take_a_second_robot():
    with pytest.raises(TypeError, match="may not name a later argument 'robot'"):
        memoized()(lambda chain, robot=None: robot)


def test_code_generation_lowers_each_function_once_per_chain(monkeypatch):
    chain = Chain(load_robot("planar2r"))
    calls: list[str] = []

    def spy(module, name):
        original = getattr(module, name)
        monkeypatch.setattr(module, name, lambda *args, **kwargs: calls.append(name) or original(*args, **kwargs))

    spy(lowering, "jacobian")  # every Jacobian candidate of lowered_jacobian
    spy(lowering, "lower_function")  # every lowering (CSE) of a candidate
    spy(codegen_acceleration, "carried_joints")  # the Hessian and the bias acceleration
    first = generate(chain, "python", frames=(0, 1), acceleration=True)
    derived = len(calls)
    assert set(calls) == {"jacobian", "lower_function", "carried_joints"}
    size = len(chain._memo)
    calls.clear()
    assert generate(chain, "python", frames=(0, 1), acceleration=True) == first
    generate(chain, "numpy", frames=(0, 1), acceleration=True)
    # nothing is derived or lowered again: every lowered function, the torques J^T F included, is kept per chain
    assert calls == [] and derived > 4
    assert len(chain._memo) == size and all(isinstance(key, MemoKey) for key in chain._memo)
    assert {key.function.__name__ for key in chain._memo} >= {
        "angle_expansion", "lowered_jacobian", "lowered_forward_kinematics", "lowered_kinematics",
        "lowered_hessian", "lowered_bias_acceleration", "coordinate_torques"}


def _string_keyed_memo_calls(source: str) -> list[int]:
    """Lines of ``source`` calling ``.memo(key, ...)`` with a string literal anywhere in the key expression."""
    def keys(call: ast.Call) -> list[ast.expr]:
        return call.args[:1] + [keyword.value for keyword in call.keywords if keyword.arg == "key"]

    def has_text(expr: ast.expr) -> bool:
        return any(isinstance(part, ast.JoinedStr) or (isinstance(part, ast.Constant) and isinstance(part.value, str))
                   for part in ast.walk(expr))

    return [node.lineno for node in ast.walk(ast.parse(source))
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "memo"
            and any(has_text(key) for key in keys(node))]


def test_no_module_keeps_a_value_under_a_string_key():
    offending = 'chain.memo(("codegen", "angles"), compute)\nchain.memo(f"{x}", f)\nc.memo(key="k", compute=f)'
    assert _string_keyed_memo_calls(offending) == [1, 2, 3]
    assert _string_keyed_memo_calls("chain.memo(MemoKey(Chain.all_angle_bases, ()), compute)") == []
    package = Path(symjac.__file__).parent
    sources = {path: path.read_text(encoding="utf-8") for path in sorted(package.rglob("*.py"))}
    assert sum(".memo(" in text for text in sources.values()) >= 2  # the check below has something to look at
    offenders = {str(path.relative_to(package)): lines for path, text in sources.items()
                 if (lines := _string_keyed_memo_calls(text))}
    assert not offenders, f"memo keys must be MemoKey values (use @memoized), not strings: {offenders}"
