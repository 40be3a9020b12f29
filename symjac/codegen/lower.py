r"""Lowering: from a robot's symbolic quantities to target-independent straight-line code (CSE), and its names.

1. **Candidates.** For a Jacobian: the raw chain products differentiated, the raw cross-product form, the compact
   textbook form, and the latter two in a neighbouring frame rotated back. Simplified entries are not always faster
   (raw chain products won on Panda with an earlier simplifier), so nothing is assumed: every candidate is lowered
   and the one with the fewest operations after CSE is kept (ties: the first).
2. **Angles.** Every sine/cosine of a joint-angle combination is expanded by the angle-addition formulas into the
   sines and cosines of the joint angles themselves (:class:`~symjac.angles.AngleExpansion`): a module evaluates
   exactly one ``sin`` and one ``cos`` per revolute joint.
3. **CSE.** Flatten, check that every free symbol is an argument (the error names the others),
   ``sympy.cse(order="canonical")``.

Everything derived here is kept in the robot's :class:`~symjac.chain.Chain` (:meth:`~symjac.chain.Chain.memo`, keys
starting with ``"codegen"``), so generating several targets for one robot derives and lowers each function once.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property

import sympy as sp

from symjac.acceleration import carried_joints
from symjac.angles import AngleExpansion
from symjac.chain import Chain, Frame
from symjac.codegen.printers import check_expression
from symjac.codegen.request import WRENCH_NAMES, frame_text
from symjac.errors import CodegenError
from symjac.jacobian import jacobian
from symjac.model import Robot
from symjac.propagation import joint_rates
from symjac.transforms import block_rotation

__all__ = [
    "LoweredFunction",
    "SymbolNames",
    "angle_expansion",
    "lower",
    "lower_function",
    "lowered_bias_acceleration",
    "lowered_forward_kinematics",
    "lowered_hessian",
    "lowered_jacobian",
    "lowered_kinematics",
    "lowered_torques",
    "symbol_names",
]

Inputs = tuple[tuple[str, tuple[sp.Symbol, ...]], ...]


@dataclass(frozen=True)
class LoweredFunction:
    """One function as SymPy data after CSE (target-independent).

    ``inputs`` are the array arguments and their entry symbols, ``angles`` the (sine, cosine, angle) triples the
    expressions use, ``outputs`` the flattened results in row-major order of ``shape``, ``expanded`` the same before
    CSE, ``op_count`` the arithmetic operations after CSE (``sympy.count_ops``) and ``origin`` the candidate's name.
    """

    inputs: Inputs
    angles: tuple[tuple[sp.Symbol, sp.Symbol, sp.Expr], ...]
    temporaries: tuple[tuple[sp.Symbol, sp.Expr], ...]
    outputs: tuple[sp.Expr, ...]
    expanded: tuple[sp.Expr, ...]
    shape: tuple[int, ...]
    op_count: int
    origin: str

    @cached_property
    def used_symbols(self) -> set[sp.Symbol]:
        """Every symbol the evaluation reads: arguments, sines and cosines, and the variables in the angles."""
        exprs = [e for _, e in self.temporaries] + list(self.outputs) + [a for _, _, a in self.angles]
        return set().union(*(e.free_symbols for e in exprs))

    @property
    def trig_count(self) -> int:
        """Sines and cosines evaluated per configuration."""
        used = self.used_symbols
        return sum((s in used) + (c in used) for s, c, _ in self.angles)

    @property
    def cost(self) -> int:
        """What candidate selection minimises: operations plus one per sine and cosine."""
        return self.op_count + self.trig_count


def lower(
    outputs: Sequence[sp.Expr] | sp.MatrixBase,
    arguments: Iterable[sp.Symbol],
) -> tuple[tuple[tuple[sp.Symbol, sp.Expr], ...], tuple[sp.Expr, ...]]:
    """Flatten ``outputs``, check every free symbol is one of ``arguments``, and apply canonical CSE.

    Returns
    -------
    temporaries : tuple of (Symbol, Expr)
        In evaluation order; the symbols are ``_x0, _x1, ...``.
    outputs : tuple of Expr
        The flattened outputs in terms of arguments and temporaries.

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> lower([sp.sin(x) * y, sp.sin(x) * y + 1], [x, y])
    (((_x0, y*sin(x)),), (_x0, _x0 + 1))
    >>> lower([x + y], [x])
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: expressions depend on y, which is not an argument (arguments: x)
    """
    flat = list(outputs)
    allowed = set(arguments)
    unknown = set().union(*(sp.sympify(e).free_symbols for e in flat)) - allowed if flat else set()
    if unknown:
        names = ", ".join(sorted(map(str, unknown)))
        known = ", ".join(sorted(map(str, allowed))) or "none"
        raise CodegenError(f"expressions depend on {names}, which is not an argument (arguments: {known})")
    for expr in flat:
        check_expression(sp.sympify(expr))
    temporaries, reduced = sp.cse(flat, symbols=sp.numbered_symbols("_x", real=True), order="canonical")
    return tuple(temporaries), tuple(reduced)


def lower_function(
    angles: AngleExpansion,
    exprs: Sequence[sp.Expr],
    shape: tuple[int, ...],
    inputs: Inputs,
    parameters: tuple[sp.Symbol, ...],
    origin: str,
    expanded: bool = False,
) -> LoweredFunction:
    """Expand the angles of ``exprs`` (unless ``expanded``), lower them and count operations and sines/cosines."""
    flat = [sp.sympify(e) for e in exprs] if expanded else [angles.expand(sp.sympify(e)) for e in exprs]
    arguments = {s for _, symbols in inputs for s in symbols} | set(parameters) | set(angles.sines)
    arguments |= set(angles.cosines)
    temporaries, outputs = lower(flat, arguments)
    used = set().union(*(e.free_symbols for _, e in temporaries), *(e.free_symbols for e in outputs))
    angle_list = tuple((s, c, a) for s, c, a in zip(angles.sines, angles.cosines, angles.angles, strict=True)
                       if s in used or c in used)
    op_count = sum(int(sp.count_ops(e)) for _, e in temporaries) + sum(int(sp.count_ops(e)) for e in outputs)
    return LoweredFunction(inputs, angle_list, temporaries, outputs, tuple(flat), shape, op_count, origin)


def angle_expansion(chain: Chain) -> AngleExpansion:
    """The expansion of sines and cosines into those of the single revolute joint angles of ``chain``."""
    def compute() -> AngleExpansion:
        revolute = [joint for joint in chain.robot.joints if joint.is_revolute]
        return AngleExpansion(tuple(j.variable for j in revolute), tuple(j.angle for j in revolute),
                              tuple(j.index for j in revolute))

    return chain.memo(("codegen", "angles"), compute)


def _jacobian_candidates(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], strategy: str
) -> Iterator[tuple[str, sp.Matrix]]:
    where = frame_text(frame)
    if strategy in ("fastest", "raw"):
        yield "raw chain products, differentiated", jacobian(chain, frame, point, "differentiation", simplify=False)
    if strategy == "raw":
        return
    yield "compact (simplified) Jacobian", jacobian(chain, frame, point, simplify=True)
    if strategy == "simplified":
        return
    yield "raw chain products, cross-product form", jacobian(chain, frame, point, "cross_product", simplify=False)
    for via in (0, 1):
        if via > chain.n or chain.position(frame) == via:
            continue
        rotation = block_rotation(chain.rotation(frame, via))
        yield (f"compact Jacobian in frame {{{via}}}, rotated into {where}",
               rotation * jacobian(chain, via, point, simplify=True))
        yield (f"raw cross-product form in frame {{{via}}}, rotated into {where}",
               rotation * jacobian(chain, via, point, "cross_product", simplify=False))


def lowered_jacobian(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> LoweredFunction:
    """The Jacobian rows ``rows`` in ``frame`` at ``point``: the candidate of ``strategy`` that costs least."""
    def compute() -> LoweredFunction:
        robot = chain.robot
        angles = angle_expansion(chain)
        best: LoweredFunction | None = None
        for origin, J in _jacobian_candidates(chain, frame, point, strategy):
            selected = [J[r, c] for r in rows for c in range(robot.dof)]
            candidate = lower_function(angles, selected, (len(rows), robot.dof), (("q", robot.q),),
                                       robot.parameter_symbols, origin)
            if best is None or candidate.cost < best.cost:
                best = candidate
        assert best is not None  # every strategy yields at least one candidate
        return best

    return chain.memo(("codegen", "jacobian", frame, point, rows, strategy), compute)


def lowered_forward_kinematics(chain: Chain, strategy: str) -> LoweredFunction:
    """The pose of the tool frame in frame {0}: the raw or the compact product, whichever costs less."""
    def compute() -> LoweredFunction:
        robot = chain.robot
        candidates = []
        if strategy in ("fastest", "raw"):
            candidates.append(("raw chain product", chain.transform(0, "tool")))
        if strategy in ("fastest", "simplified"):
            candidates.append(("compact (simplified) transform", chain.simplified_transform(0, "tool")))
        lowered = [lower_function(angle_expansion(chain), list(T), (4, 4), (("q", robot.q),),
                                  robot.parameter_symbols, origin) for origin, T in candidates]
        return min(lowered, key=lambda candidate: candidate.cost)

    return chain.memo(("codegen", "forward_kinematics", strategy), compute)


def lowered_kinematics(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...]) -> LoweredFunction:
    """Point position in {0}, ^0_nR and ^0_kR (21 values): what the self-test differentiates numerically."""
    def compute() -> LoweredFunction:
        T_0_n = chain.transform(0, chain.n)
        x_P = T_0_n[:3, :3] * sp.Matrix(point) + T_0_n[:3, 3]
        values = [*x_P, *T_0_n[:3, :3], *chain.rotation(0, frame)]
        return lower_function(angle_expansion(chain), values, (21,), (("q", chain.robot.q),),
                              chain.robot.parameter_symbols, "raw chain products")

    return chain.memo(("codegen", "kinematics", frame, point), compute)


def lowered_torques(chain: Chain, J: LoweredFunction, rows: tuple[int, ...]) -> LoweredFunction:
    """Joint torques tau = J^T F from the (angle-expanded) Jacobian ``J``; ``F`` holds the wrench rows ``rows``."""
    wrench = tuple(sp.Symbol(f"_F{r}", real=True) for r in rows)
    n = chain.n
    tau = [sum((J.expanded[k * n + i] * wrench[k] for k in range(len(rows))), sp.S.Zero) for i in range(n)]
    return lower_function(angle_expansion(chain), tau, (n,), (("q", chain.robot.q), ("wrench", wrench)),
                          chain.robot.parameter_symbols, f"J^T F from the Jacobian ({J.origin})", expanded=True)


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
        self.entries = tuple(self.value(e) for e in J.outputs)

    def value(self, expr: sp.Expr) -> sp.Expr:
        """``expr`` itself if it is a number, a symbol or a negated symbol; else a new temporary holding it."""
        if expr.is_Atom or (expr.is_Mul and len(expr.args) == 2 and expr.args[0] == -1 and expr.args[1].is_Symbol):
            return expr
        symbol = next(self._fresh)
        self.temporaries.append((symbol, expr))
        return symbol

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


def lowered_hessian(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> LoweredFunction:
    r"""The kinematic Hessian ``H[i, j, m] = dJ[i, j] / dq_m`` (rows ``rows``), from the columns of the Jacobian.

    .. math::
        \frac{\partial J_j}{\partial q_m} = [\omega_m \times v_j;\ \omega_m \times \omega_j]\ (m < j),\quad
        [\omega_j \times v_m;\ 0]\ (m \ge j)

    in a fixed frame; a joint m that turns the frame {k} the Jacobian is expressed in also contributes
    :math:`-[\omega_m \times v_j;\ \omega_m \times \omega_j]` (:mod:`symjac.acceleration`). Each entry is one
    component of a cross product of two Jacobian columns, and CSE shares the products the linear rows repeat (they
    are symmetric in j and m in a fixed frame).
    """
    def compute() -> LoweredFunction:
        n = chain.n
        program = _Program(chain, lowered_jacobian(chain, frame, point, tuple(range(6)), strategy))
        columns = program.columns()
        carried = len(carried_joints(chain, frame))
        H: dict[tuple[int, int], Vector] = {}
        zero: Vector = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
        for j in range(n):
            v_j, w_j = columns[j]
            for m in range(n):
                v_m, w_m = columns[m]
                linear, angular = (_cross(w_m, v_j), _cross(w_m, w_j)) if m < j else (_cross(w_j, v_m), zero)
                if m < carried:  # joint m turns frame {k}: d(^k_0R)/dq_m adds -[w_m x v_j; w_m x w_j]
                    linear = tuple(a - b for a, b in zip(linear, _cross(w_m, v_j), strict=True))
                    angular = tuple(a - b for a, b in zip(angular, _cross(w_m, w_j), strict=True))
                H[j, m] = (*linear, *angular)
        outputs = [H[j, m][r] for r in rows for j in range(n) for m in range(n)]
        return program.lowered(outputs, (len(rows), n, n), (("q", chain.robot.q),),
                               "cross products of the Jacobian's columns", common=True)

    return chain.memo(("codegen", "hessian", frame, point, rows, strategy), compute)


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
    def compute() -> LoweredFunction:
        candidates = [_bias_in(chain, frame, via, point, rows, strategy) for via in (frame, 0, 1)
                      if via == frame or (via <= chain.n and chain.position(frame) != via)]
        return min(candidates, key=lambda candidate: candidate.cost)

    return chain.memo(("codegen", "bias_acceleration", frame, point, rows, strategy), compute)


def _bias_in(chain: Chain, frame: Frame, via: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
             strategy: str) -> LoweredFunction:
    """The bias acceleration in ``frame``, computed from the columns of the Jacobian in ``via`` and rotated.

    Cross products commute with rotations, so the whole sum can be formed from the columns written in any frame;
    a frame near the base often has cheaper columns (the PUMA's frame {1} Jacobian does not depend on theta1).
    """
    robot = chain.robot
    n = chain.n
    rates = joint_rates(chain)
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
        R = chain.rotation(frame, via).applyfunc(program.expansion.expand)
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


class SymbolNames:
    """Printed names for a function's symbols: validated robot names, fresh names for everything generated."""

    def __init__(self, robot: Robot, taken: Iterable[str]):
        self.taken = set(taken)
        self.mapping: dict[sp.Symbol, str] = {}
        for symbol in (*robot.q, *robot.parameter_symbols):
            self.mapping[symbol] = symbol.name
            self.taken.add(symbol.name)

    def fresh(self, symbol: sp.Symbol, base: str) -> str:
        """The name of ``symbol``: its existing one, else ``base`` with underscores appended until it is free."""
        if symbol in self.mapping:
            return self.mapping[symbol]
        name = base
        while name in self.taken:
            name = f"{name}_"
        self.taken.add(name)
        self.mapping[symbol] = name
        return name


def symbol_names(robot: Robot, lowered: LoweredFunction, taken: Iterable[str]) -> SymbolNames:
    """Names for ``lowered``: ``s3``/``c3`` for joint 3's sine and cosine, ``f_x``.. for the wrench, ``x0``.."""
    names = SymbolNames(robot, taken)
    joint_index = {j.variable: j.index for j in robot.joints}
    for sine, cosine, angle in lowered.angles:
        index = next(joint_index[v] for v in angle.free_symbols if v in joint_index)
        names.fresh(sine, f"s{index}")
        names.fresh(cosine, f"c{index}")
    for argument, symbols in lowered.inputs:
        if argument == "wrench":
            for symbol in symbols:  # _F0 .. _F5: the row each multiplies
                names.fresh(symbol, WRENCH_NAMES[int(symbol.name.removeprefix("_F"))])
        elif argument == "qdot":
            for symbol in symbols:  # thetadot1, ddot3, ...
                names.fresh(symbol, symbol.name)
    for k, (symbol, _) in enumerate(lowered.temporaries):
        names.fresh(symbol, f"x{k}")
    return names
