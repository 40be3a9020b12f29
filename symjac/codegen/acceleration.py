r"""Lowering of the acceleration-level functions: the kinematic Hessian and the bias acceleration Jdot qdot.

Both are built on top of a lowered Jacobian (:func:`~symjac.codegen.lower.lowered_jacobian`, all six rows): every
entry of J gets a name, and the new quantities are written as cross products of those names (the closed forms of
:mod:`symjac.kinematics.acceleration`), instead of differentiating and expanding J's expressions again. J is thus
computed exactly once, as the ``jacobian`` function computes it, and the new code on top is a few dozen operations per
joint.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import sympy as sp

from symjac.codegen.lower import Inputs, LoweredFunction, angle_expansion, lowered_jacobian
from symjac.codegen.nested import expanded_nested, has_nested, placeheld
from symjac.codegen.request import frame_text, rows_of, strategy_of
from symjac.kinematics.acceleration import carried_joints
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.kinematics.propagation import joint_rate_symbols

__all__ = ["lowered_bias_acceleration", "lowered_hessian"]

Vector = tuple[sp.Expr, sp.Expr, sp.Expr]

def _cross(a: Vector, b: Vector) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


class _Program:
    """Straight-line code built on top of a lowered Jacobian: its temporaries, then one per new non-trivial value.

    Every entry of the Jacobian becomes a name (``_J<k>``) unless it is already a number or a single symbol, so the
    acceleration-level quantities below are written as short products of those names: the Jacobian is computed
    once, exactly as the ``jacobian`` function computes it, and nothing is expanded again.
    """

    def __init__(self, chain: Chain, J: LoweredFunction):
        self.J = J
        self.expansion = angle_expansion(chain)
        self.temporaries: list[tuple[sp.Symbol, sp.Expr]] = list(J.temporaries)
        self._fresh = sp.numbered_symbols("_acc_a", real=True)
        self._fresh_nested = sp.numbered_symbols("_acc_w", real=True)
        self.entries = tuple(self.value(e) for e in J.outputs)

    def value(self, expr: sp.Expr) -> sp.Expr:
        """``expr`` itself if it is a number, a symbol or a negated symbol; else a new temporary holding it."""
        if expr.is_Atom or (expr.is_Mul and len(expr.args) == 2 and expr.args[0] == -1 and expr.args[1].is_Symbol):
            return expr
        symbol = next(self._fresh)
        self.temporaries.append((symbol, expr))
        return symbol

    def expanded(self, exprs: Iterable[sp.Expr]) -> list[sp.Expr]:
        """``exprs`` angle-expanded; the intermediates of a nested result become temporaries first (placeholders)."""
        flat = self.expansion.expand_all(list(exprs))
        if not has_nested(flat):
            return flat
        definitions, flat = placeheld(expanded_nested(self.expansion, flat), self._fresh_nested)
        self.temporaries += definitions
        return flat

    def vector(self, exprs: Iterable[sp.Expr]) -> Vector:
        a, b, c = (self.value(e) for e in exprs)
        return (a, b, c)

    def columns(self) -> list[tuple[Vector, Vector]]:
        """The Jacobian's columns (v_j, omega_j) as names; the lowered Jacobian has all six rows."""
        n = self.J.shape[1]
        e = self.entries
        return [((e[j], e[n + j], e[2 * n + j]), (e[3 * n + j], e[4 * n + j], e[5 * n + j])) for j in range(n)]

    def lowered(self, outputs: Sequence[sp.Expr], shape: tuple[int, ...], inputs: Inputs, origin: str,
                common: bool) -> LoweredFunction:
        """The function computing ``outputs``: optional CSE over them, unused temporaries dropped, ops counted."""
        temporaries = list(self.temporaries)
        flat = [sp.sympify(e) for e in outputs]
        if common:
            extra, flat_tuple = sp.cse(flat, symbols=sp.numbered_symbols("_acc_c", real=True), order="canonical")
            temporaries += extra
            flat = list(flat_tuple)
        needed = set().union(*(e.free_symbols for e in flat)) if flat else set()
        kept: list[tuple[sp.Symbol, sp.Expr]] = []
        for symbol, expr in reversed(temporaries):
            if symbol in needed:
                kept.append((symbol, expr))
                needed |= expr.free_symbols
        kept.reverse()
        expansion = self.expansion
        angles = tuple((s, c, a) for s, c, a in zip(expansion.sines, expansion.cosines, expansion.angles, strict=True)
                       if s in needed or c in needed)
        op_count = sum(int(sp.count_ops(e)) for _, e in kept) + sum(int(sp.count_ops(e)) for e in flat)
        return LoweredFunction(inputs, angles, tuple(kept), tuple(flat), tuple(flat), shape, op_count, origin)


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def lowered_hessian(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> LoweredFunction:
    r"""The kinematic Hessian ``H[i, j, m] = dJ[i, j] / dq_m`` (rows ``rows``), from the columns of the Jacobian.

    .. math::
        \frac{\partial J_j}{\partial q_m} = [\omega_m \times v_j;\ \omega_m \times \omega_j]\ (m < j),\quad
        [\omega_j \times v_m;\ 0]\ (m \ge j)

    in a fixed frame; a joint m that turns the frame {k} the Jacobian is expressed in also contributes
    :math:`-[\omega_m \times v_j;\ \omega_m \times \omega_j]` (:mod:`symjac.kinematics.acceleration`). Each entry is one
    component of a cross product of two Jacobian columns, and CSE shares the products the linear rows repeat (they
    are symmetric in j and m in a fixed frame).
    """
    n = chain.robot.n_coordinates
    program = _Program(chain, lowered_jacobian(chain, frame, point, tuple(range(6)), strategy))
    columns = program.columns()
    carried = len(carried_joints(chain, frame))
    H: dict[tuple[int, int], tuple[sp.Expr, ...]] = {}
    zero: Vector = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    for j in range(n):
        v_j, w_j = columns[j]
        for m in range(n):
            v_m, w_m = columns[m]
            linear, angular = (_cross(w_m, v_j), _cross(w_m, w_j)) if m < j else (_cross(w_j, v_m), zero)
            if m < carried:  # joint m turns frame {k}: d(^k_0R)/dq_m adds -[w_m x v_j; w_m x w_j]
                linear = _add(linear, _cross(v_j, w_m))
                angular = _add(angular, _cross(w_j, w_m))
            H[j, m] = (*linear, *angular)
    outputs = [H[j, m][r] for r in rows for j in range(n) for m in range(n)]
    return program.lowered(outputs, (len(rows), n, n), (("q", chain.robot.q),),
                           "cross products of the Jacobian's columns", common=True)


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def lowered_bias_acceleration(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> LoweredFunction:
    r"""The bias acceleration :math:`\dot J\dot q` (rows ``rows``) from the Jacobian's columns and the joint rates.

    With :math:`u_b = \dot q_b\,\omega_b`, :math:`t_b = \dot q_b\,v_b`, the partial sums
    :math:`W_b = \sum_{m<b} u_m` and :math:`K = W_k` (the angular velocity of the frame {k} the Jacobian is
    expressed in: zero for a fixed frame, the sum over the joints that turn {k} otherwise), summing the Hessian's
    cross products over both joint indices telescopes to

    .. math::
        \dot J\dot q = \Big[\sum_b (W_b + W_{b+1}) \times t_b - K \times \sum_b t_b;\
        \sum_b W_b \times u_b - K \times W_n\Big],

    about 36 operations per joint on top of the Jacobian, which it reuses entry by entry.
    """
    vias: list[Frame] = [frame, *(via for via in (0, 1) if via <= chain.n_joints and chain.position(frame) != via)]
    candidates = [_bias_in(chain, frame, via, point, rows, strategy) for via in vias]
    return min(candidates, key=lambda candidate: candidate.cost)


def _bias_in(chain: Chain, frame: Frame, via: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
             strategy: str) -> LoweredFunction:
    """The bias acceleration in ``frame``, computed from the columns of the Jacobian in ``via`` and rotated.

    Cross products commute with rotations, so the whole sum can be formed from the columns written in any frame;
    a frame near the base often has cheaper columns (the PUMA's frame {1} Jacobian does not depend on theta1).
    """
    robot = chain.robot
    n = chain.robot.n_coordinates
    rates = joint_rate_symbols(chain)
    program = _Program(chain, lowered_jacobian(chain, via, point, tuple(range(6)), strategy))
    columns = program.columns()
    zero: Vector = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    W: list[Vector] = [zero]
    u: list[Vector] = []
    t: list[Vector] = []
    for b, (v_b, w_b) in enumerate(columns):
        u.append(program.vector(rates[b] * x for x in w_b))
        t.append(program.vector(rates[b] * x for x in v_b))
        W.append(program.vector(a + c for a, c in zip(W[b], u[b], strict=True)))
    K = W[len(carried_joints(chain, frame))]
    linear: Vector = zero
    angular: Vector = zero
    for b in range(n):
        S = program.vector(a + c for a, c in zip(W[b], W[b + 1], strict=True))
        linear = _add(linear, _cross(S, t[b]))
        angular = _add(angular, _cross(W[b], u[b]))
    if any(x != 0 for x in K):
        velocity = program.vector(sum((t[b][i] for b in range(n)), sp.S.Zero) for i in range(3))
        linear = _add(linear, _cross(velocity, K))
        angular = _add(angular, _cross(W[n], K))
    if via != frame:
        R = sp.Matrix(3, 3, program.expanded(chain.rotation(frame, via)))
        linear, angular = (_rotate(R, program.vector(linear)), _rotate(R, program.vector(angular)))
    values = [*linear, *angular]
    where = "" if via == frame else f" in frame {{{via}}}, rotated into {frame_text(frame)}"
    return program.lowered([values[r] for r in rows], (len(rows),), (("q", robot.q), ("qdot", rates)),
                           f"cross products of the Jacobian's columns{where}", common=True)


def _add(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _rotate(R: sp.MatrixBase, x: Vector) -> Vector:
    a, b, c = (sum((R[i, k] * x[k] for k in range(3)), sp.S.Zero) for i in range(3))
    return (a, b, c)
