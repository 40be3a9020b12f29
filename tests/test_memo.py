"""The one memo: derived quantities are kept in their chain under typed keys, once per normalised request."""

from __future__ import annotations

import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.manipulability import log_det_gradient
from symjac.analysis.singularity.determinant import determinant
from symjac.errors import ArgumentError, FrameError
from symjac.kinematics.acceleration import bias_acceleration, hessian
from symjac.kinematics.chain import Chain, MemoKey
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.memo import frame_of, memoized, one_of
from symjac.kinematics.numeric import numeric_jacobian


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
