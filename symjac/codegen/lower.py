r"""Lowering: from a robot's symbolic quantities to target-independent straight-line code (CSE), and its names.

1. **Candidates.** For a Jacobian: the raw chain products differentiated, the raw cross-product form, the compact
   textbook form, and the latter two in a neighbouring frame rotated back. Simplified entries are not always faster
   (raw chain products won on Panda with an earlier simplifier), so nothing is assumed: every candidate is lowered
   and the one with the fewest operations after CSE is kept (ties: the first).
2. **Angles.** Every sine/cosine of a joint-angle combination is expanded by the angle-addition formulas into the
   sines and cosines of the joint angles themselves (:class:`~symjac.symbolic.angles.AngleExpansion`): a module
   evaluates exactly one ``sin`` and one ``cos`` per revolute joint.
3. **CSE.** Flatten, check that every free symbol is an argument (the error names the others),
   ``sympy.cse(order="canonical")`` (:mod:`symjac.codegen.cse`: on a long chain, shared subexpressions named first).
4. **Nested results** (generic geometry, :mod:`symjac.codegen.nested`): the definitions of their intermediates,
   angle-expanded once each, become the first temporaries and go through one CSE with the outputs, instead of a
   written-out graph CSE'd again; numbers SymPy distributed over the sums of a rotation are grouped again. A nested
   chain gets only the cross-product candidates: its compact forms are its raw products (no textbook form to find),
   and the differentiated products were about three times larger (a calibrated 6R arm: 958 against 348 operations).
5. **Compact candidates within a budget.** The "fastest" strategy derives a compact candidate only up to
   :data:`COMPACT_TERMS` terms; on a long 3-D chain it is skipped and the raw products compete alone.

Everything derived here is kept in the robot's :class:`~symjac.kinematics.chain.Chain` by
:func:`~symjac.kinematics.memo.memoized` (keyed by the lowering function and its normalised arguments), so generating
several targets for one robot derives and lowers each function once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TypeVar

import sympy as sp

from symjac.codegen.cse import eliminate_common
from symjac.codegen.nested import expanded_nested, grouped, has_nested, placeheld
from symjac.codegen.printers import check_expression
from symjac.codegen.request import frame_text, rows_of, strategy_of
from symjac.errors import CodegenError, ResultTooLargeError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import jacobian, point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.model.robot import WRENCH_NAMES, Robot
from symjac.symbolic.angles import AngleExpansion
from symjac.symbolic.dag import free_symbols
from symjac.symbolic.size import term_limit
from symjac.symbolic.transforms import block_rotation

__all__ = [
    "LoweredFunction",
    "SymbolNames",
    "angle_expansion",
    "lower",
    "lower_function",
    "lowered_forward_kinematics",
    "lowered_jacobian",
    "lowered_kinematics",
    "lowered_torques",
    "symbol_names",
]

Inputs = tuple[tuple[str, tuple[sp.Symbol, ...]], ...]
T = TypeVar("T")


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

    Intermediates of nested results (:mod:`symjac.symbolic.nested`) are no arguments: their definitions become
    temporaries (:func:`symjac.codegen.nested.placeheld`), and the arguments are checked in those definitions.

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
    flat = [sp.sympify(e) for e in outputs]
    given, flat = placeheld(flat) if has_nested(flat) else ([], flat)
    values = [d for _, d in given] + flat
    allowed = set(arguments) | {h for h, _ in given}
    unknown = free_symbols(values) - allowed
    if unknown:
        names = ", ".join(sorted(map(str, unknown)))
        known = ", ".join(sorted(map(str, set(arguments)))) or "none"
        raise CodegenError(f"expressions depend on {names}, which is not an argument (arguments: {known})")
    check_expression(*values)
    temporaries, reduced = eliminate_common(flat, given)
    if given:  # a nested result: numbers distributed over the sums of its rotations, grouped again
        temporaries, reduced = grouped(temporaries, reduced)
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
    flat = [sp.sympify(e) for e in exprs]
    if not expanded:
        flat = angles.expand_all(flat)
    if has_nested(flat):  # generic geometry: the intermediates' definitions expanded too, once each
        flat = expanded_nested(angles, flat)
    arguments = {s for _, symbols in inputs for s in symbols} | set(parameters) | set(angles.sines)
    arguments |= set(angles.cosines)
    temporaries, outputs = lower(flat, arguments)
    used = set().union(*(e.free_symbols for _, e in temporaries), *(e.free_symbols for e in outputs))
    angle_list = tuple((s, c, a) for s, c, a in zip(angles.sines, angles.cosines, angles.angles, strict=True)
                       if s in used or c in used)
    op_count = sum(int(sp.count_ops(e)) for _, e in temporaries) + sum(int(sp.count_ops(e)) for e in outputs)
    return LoweredFunction(inputs, angle_list, temporaries, outputs, tuple(flat), shape, op_count, origin)


@memoized()
def angle_expansion(chain: Chain) -> AngleExpansion:
    """The expansion of sines and cosines into those of the single revolute joint angles of ``chain``."""
    revolute = [joint for joint in chain.robot.joints if joint.is_revolute]
    return AngleExpansion(tuple(j.variable for j in revolute), tuple(j.angle for j in revolute),
                          tuple(j.index for j in revolute))


COMPACT_TERMS = 20_000
"""The most terms a compact candidate of the "fastest" strategy may have (:func:`symjac.symbolic.size.term_limit`).

Deriving a normal form costs time in proportion to its terms, and past a few ten thousand terms (a 3-D chain of 14
or more joints, whose expanded normal form grows about 1.8x per joint) the raw products, whose subexpressions CSE
shares, are as small after CSE: the compact candidate is then skipped rather than derived for seconds or minutes.
"""


COMPACT_TURNS = 14
"""The most turns of the joint axis (changes between parallel groups) a chain may have for compact candidates.

A normal form grows about 1.8x with every turn of the chain; a 14-joint 3-D snake (13 turns) is already past
:data:`COMPACT_TERMS`. Past this many turns the compact candidates are not derived at all: trying them only spent
seconds converting raw trees until the term limit stopped them (a 20-joint snake: about a third of its code
generation time). The result is the same ``None`` a failed attempt gives.
"""


DIFFERENTIATED_UP_TO = 6
"""The most joints for which the "fastest" strategy also lowers the differentiated raw products.

Differentiation wins on short planar arms (a planar 2R in frame {0}: 18 operations), but its raw form grows faster
with the chain than the cross-product form, which won on every longer chain measured (frame {0}: Panda 173 against
255 operations, a 7-joint generic chain 869 against 1376, planar 10R 108 against 387, 20-joint snake 3174 against
4932); lowering the losing candidate cost the 20-joint snake about 3 s of its code generation.
"""


def _too_many_turns(chain: Chain) -> bool:
    """Whether ``chain`` turns its joint axis more than :data:`COMPACT_TURNS` times.

    Such a chain gets no compact candidate, and its raw cross-product form rotated from frame {0} or {1} was larger
    than the one in the frame itself (20-joint snake, frame {0}: 3331 against 3174 operations), while deriving it
    cost a second set of chain products: the raw cross-product form in the frame itself is its only candidate.
    """
    return len(chain.parallel_groups) - 1 > COMPACT_TURNS


def _within_budget(chain: Chain, compute: Callable[[], T]) -> T | None:
    """``compute()`` within :data:`COMPACT_TERMS`, or ``None`` past it.

    A chain with more than :data:`COMPACT_TURNS` turns gets ``None`` without an attempt. The callers are memoized,
    so a failed attempt is remembered and not tried again.
    """
    if _too_many_turns(chain):
        return None
    try:
        with term_limit(COMPACT_TERMS):
            return compute()
    except ResultTooLargeError:
        return None


@memoized(frame=frame_of, point=point_vector)
def _compact_jacobian(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...]) -> sp.Matrix | None:
    """The compact (simplified) Jacobian in ``frame`` at ``point``, or ``None`` past :data:`COMPACT_TERMS`."""
    return _within_budget(chain, lambda: jacobian(chain, frame, point))


@memoized()
def _compact_tool_transform(chain: Chain) -> sp.ImmutableMatrix | None:
    """The compact (simplified) transform ^0_tT, or ``None`` past :data:`COMPACT_TERMS`."""
    return _within_budget(chain, lambda: chain.simplified_transform(0, "tool"))


def _jacobian_candidates(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], strategy: str
) -> Iterator[tuple[str, sp.Matrix]]:
    where = frame_text(frame)
    differentiated = chain.n_joints <= DIFFERENTIATED_UP_TO and not chain.nested
    if strategy == "raw" or (strategy == "fastest" and differentiated):
        yield "raw chain products, differentiated", jacobian(chain, frame, point, "differentiation", simplify=False)
    if strategy == "raw":
        return
    if strategy == "simplified":
        yield "compact (simplified) Jacobian", jacobian(chain, frame, point, simplify=True)
        return
    compact = None if chain.nested else _compact_jacobian(chain, frame, point)
    if compact is not None:
        yield "compact (simplified) Jacobian", compact
    yield "raw chain products, cross-product form", jacobian(chain, frame, point, "cross_product", simplify=False)
    if _too_many_turns(chain):  # no compact form to rotate, and the raw form via another frame is no smaller
        return
    for via in (0, 1):
        if via > chain.n_joints or chain.position(frame) == via:
            continue
        rotation = block_rotation(chain.rotation(frame, via))
        compact = None if chain.nested else _compact_jacobian(chain, via, point)
        if compact is not None:
            yield f"compact Jacobian in frame {{{via}}}, rotated into {where}", rotation * compact
        yield (f"raw cross-product form in frame {{{via}}}, rotated into {where}",
               rotation * jacobian(chain, via, point, "cross_product", simplify=False))


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def lowered_jacobian(
    chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...], strategy: str
) -> LoweredFunction:
    """The Jacobian rows ``rows`` in ``frame`` at ``point``: the candidate of ``strategy`` that costs least."""
    robot = chain.robot
    angles = angle_expansion(chain)
    best: LoweredFunction | None = None
    for origin, J in _jacobian_candidates(chain, frame, point, strategy):
        selected = [J[r, c] for r in rows for c in range(robot.n_coordinates)]
        candidate = lower_function(angles, selected, (len(rows), robot.n_coordinates), (("q", robot.q),),
                                   robot.parameter_symbols, origin)
        if best is None or candidate.cost < best.cost:
            best = candidate
    assert best is not None  # every strategy yields at least one candidate
    return best


@memoized(strategy=strategy_of)
def lowered_forward_kinematics(chain: Chain, strategy: str) -> LoweredFunction:
    """The pose of the tool frame in frame {0}: the raw or the compact product, whichever costs less."""
    robot = chain.robot
    candidates = []
    if strategy in ("fastest", "raw"):
        candidates.append(("raw chain product", chain.transform(0, "tool")))
    if strategy == "simplified":
        candidates.append(("compact (simplified) transform", chain.simplified_transform(0, "tool")))
    elif strategy == "fastest" and not chain.nested:  # a nested chain's compact product is its raw one
        compact = _compact_tool_transform(chain)
        if compact is not None:
            candidates.append(("compact (simplified) transform", compact))
    lowered = [lower_function(angle_expansion(chain), list(T), (4, 4), (("q", robot.q),),
                              robot.parameter_symbols, origin) for origin, T in candidates]
    return min(lowered, key=lambda candidate: candidate.cost)


@memoized(frame=frame_of, point=point_vector)
def lowered_kinematics(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...]) -> LoweredFunction:
    """Point position in {0}, ^0_nR and ^0_kR (21 values): what the self-test differentiates numerically."""
    T_0_n = chain.transform(0, chain.n_joints)
    x_P = T_0_n[:3, :3] * sp.Matrix(point) + T_0_n[:3, 3]
    values = [*x_P, *T_0_n[:3, :3], *chain.rotation(0, frame)]
    return lower_function(angle_expansion(chain), values, (21,), (("q", chain.robot.q),),
                          chain.robot.parameter_symbols, "raw chain products")


def lowered_torques(chain: Chain, J: LoweredFunction, rows: tuple[int, ...]) -> LoweredFunction:
    """Joint torques tau = J^T F from the (angle-expanded) Jacobian ``J``; ``F`` holds the wrench rows ``rows``."""
    wrench = tuple(sp.Symbol(f"_F{r}", real=True) for r in rows)
    n = chain.robot.n_coordinates
    tau = [sum((J.expanded[k * n + i] * wrench[k] for k in range(len(rows))), sp.S.Zero) for i in range(n)]
    return lower_function(angle_expansion(chain), tau, (n,), (("q", chain.robot.q), ("wrench", wrench)),
                          chain.robot.parameter_symbols, f"J^T F from the Jacobian ({J.origin})", expanded=True)


class SymbolNames:
    """Printed names for a function's symbols: validated robot names, fresh names for everything generated.

    ``symbols`` keep their own names (the coordinates and parameters of a module description, already validated);
    a :class:`~symjac.model.robot.Robot` stands for its coordinates and parameters.
    """

    def __init__(self, symbols: Robot | Iterable[sp.Symbol], taken: Iterable[str]):
        self.taken = set(taken)
        self.mapping: dict[sp.Symbol, str] = {}
        own = (*symbols.q, *symbols.parameter_symbols) if isinstance(symbols, Robot) else tuple(symbols)
        for symbol in own:
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


def symbol_names(symbols: Robot | Iterable[sp.Symbol], lowered: LoweredFunction, taken: Iterable[str]
                 ) -> SymbolNames:
    """Names for ``lowered``: ``s3``/``c3`` for joint 3's sine and cosine, ``f_x``.. for the wrench, ``x0``..

    ``symbols`` keep their names (:attr:`ModuleDescription.symbols <symjac.codegen.description.ModuleDescription>`).
    """
    names = SymbolNames(symbols, taken)
    for sine, cosine, _ in lowered.angles:  # _s3, _c3: joint 3's (its angle may be written in the coordinates)
        names.fresh(sine, sine.name.removeprefix("_"))
        names.fresh(cosine, cosine.name.removeprefix("_"))
    for argument, symbols in lowered.inputs:
        if argument == "wrench":
            for symbol in symbols:  # _F0 .. _F5: the row each multiplies
                names.fresh(symbol, WRENCH_NAMES[int(symbol.name.removeprefix("_F"))])
        elif argument in ("qdot", "qddot", "tau"):
            for symbol in symbols:  # thetadot1, ddot3, thetaddot1, ...
                names.fresh(symbol, symbol.name)
    named = [symbol for symbol, _ in lowered.temporaries if not symbol.name.startswith("_")]
    for symbol in named:  # a coupled robot's joint variables and rates (d3 = d30 + k*theta4), under their names
        names.fresh(symbol, symbol.name)
    for k, symbol in enumerate(s for s, _ in lowered.temporaries if s not in named):
        names.fresh(symbol, f"x{k}")
    return names
