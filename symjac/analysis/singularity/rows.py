r"""Which rows of the Jacobian an arm with fewer than six joints is singular in, and in which frame.

A configuration is singular when the arm loses a motion it has elsewhere: the Jacobian has lower rank there than
its generic (maximum) rank. Two Jacobians are meant, and neither depends on the frame they are written in:

- an arm that only positions a point (its linear rows alone have rank :math:`n`: the planar 2R's :math:`v_x, v_y`,
  a 3-joint positioning arm) is singular where the three linear rows :math:`J_v` lose rank;
- every other arm is singular where the whole :math:`6 \times n` Jacobian loses rank.

Both are square only by choice of rows. A choice is *exact* when, in some frame {k}, every row left out is zero or
a multiple of a kept row that has a constant entry:

.. math:: J_j(q) = \frac{J_{j c}(q)}{J_{i c}} J_i(q) \quad\text{with } J_{i c} \ne 0 \text{ a number},

so that the kept rows span all rows at every configuration and their determinant vanishes exactly where the
Jacobian loses rank. An arm such as the OpenManipulator-X (a yaw joint, then three pitch joints) has one in frame
{1}: :math:`\omega_y` is :math:`\dot\theta_1` alone and :math:`v_z` a multiple of it, so the rows
:math:`v_x, v_y, \omega_y, \omega_z` are exact, while :math:`v_x, v_y, v_z, \omega_x` in frame {0} add a factor
:math:`s_1` of their own. When no frame gives an exact choice (a 5-joint arm whose approach axis moves), the arm is
analysed through all its :math:`n \times n` row minors, which vanish together exactly where the rank drops (the
Cauchy-Binet formula, :math:`\det J^T J = \sum_S \det(J_S)^2` over the sets :math:`S` of :math:`n` rows).

Zero rows are found exactly; the multiples are checked at random configurations and random parameters near their
defaults (a polynomial identity tested at random points, as in the Schwartz-Zippel lemma).
"""

from __future__ import annotations

import math
import random
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.memo import memoized
from symjac.symbolic.nested import lambdify_cse

__all__ = ["Criterion", "RowChoice", "singular_rows"]

Criterion = Literal["twist", "position", "motion"]
"""``twist``: six rows of an arm with six joints or more; ``position``: the linear rows of an arm that only positions
a point; ``motion``: the whole Jacobian of a shorter arm."""

_SAMPLES = 4  # random configurations (and parameter sets) for the rank and the multiples
_RELATIVE = 1e-9  # a row counts as a multiple when the rest is this small relative to the Jacobian's size


@dataclass(frozen=True)
class RowChoice:
    r"""The rows (of :math:`{}^kJ`, ``frame`` k) whose rank loss makes the arm singular.

    ``frame`` is ``None`` when the rows are closed in every frame (all six, or all three linear rows); ``exact`` is
    whether the rows are square (``len(rows) == n``) and vanish exactly where the Jacobian loses rank; otherwise the
    arm is analysed through the :math:`n \times n` minors of ``rows``. ``dropped`` maps a left-out row to the kept row
    it is a multiple of (``None``: it is zero in that frame).
    """

    rows: tuple[int, ...]
    frame: Frame | None
    criterion: Criterion
    exact: bool
    dropped: tuple[tuple[int, int | None], ...] = ()
    everywhere: bool = True  # every frame was searched (False: only the frame asked for)


@memoized()
def singular_rows(chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr], frame: Frame | None = None) -> RowChoice:
    """The rows the singular sets of ``chain`` are read from, at ``point`` (see the module docstring).

    ``frame`` limits the search for an exact choice to that frame (rows then belong to its Jacobian).

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.kinematics.chain import Chain
    >>> singular_rows(Chain(load_robot("planar2r")), (0, 0, 0))
    RowChoice(rows=(0, 1), frame=2, criterion='position', exact=True, dropped=((2, None),), everywhere=True)
    """
    n = chain.robot.n_coordinates
    if n >= 6:
        return RowChoice(tuple(range(6)), None, "twist", n == 6)
    evaluate = _Evaluator(chain, point)
    full = evaluate.rank(range(6), 0)
    if full < n:
        raise ArgumentError(f"{chain.robot.name}: its {n} coordinates move only {full} independent directions "
                            "anywhere, so its Jacobian has no square form")
    criterion: Criterion = "position" if evaluate.rank(range(3), 0) == n else "motion"
    candidates = (0, 1, 2) if criterion == "position" else tuple(range(6))
    if len(candidates) == n:
        return RowChoice(candidates, None, criterion, True)
    frames: Sequence[Frame] = range(chain.n_joints + 1) if frame is None else (frame,)
    choices = [choice for k in frames if (choice := _exact_in(evaluate, k, candidates, criterion)) is not None]
    if choices:
        return min(choices, key=lambda choice: (evaluate.size(choice.rows, choice.frame), choice.frame))
    k = min(frames, key=lambda k: evaluate.size(evaluate.nonzero(candidates, k), k))
    return RowChoice(evaluate.nonzero(candidates, k), k, criterion, False, everywhere=frame is None)


def _exact_in(evaluate: _Evaluator, frame: Frame, candidates: Sequence[int], criterion: Criterion) -> RowChoice | None:
    """The exact choice in ``frame``: zero rows and multiples of constant rows dropped, if n rows of rank n remain."""
    nonzero = evaluate.nonzero(candidates, frame)
    dropped: dict[int, int | None] = {row: None for row in candidates if row not in nonzero}
    for row in nonzero:
        anchor = next((a for a in nonzero if a != row and a not in dropped and evaluate.multiple(row, a, frame)), None)
        if anchor is not None and not (anchor > row and evaluate.constant_entry(row, frame) is not None):
            dropped[row] = anchor
    kept = tuple(row for row in nonzero if row not in dropped)
    n = evaluate.n
    if len(kept) != n or evaluate.rank(kept, frame) != n:
        return None
    return RowChoice(kept, frame, criterion, True, tuple(sorted(dropped.items())))


class _Evaluator:
    """The simplified Jacobian of ``chain`` at ``point`` per frame, symbolic and at random points."""

    def __init__(self, chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr]) -> None:
        self.chain, self.point, self.n = chain, point, chain.robot.n_coordinates
        robot = chain.robot
        draw = random.Random(20261127)
        self.arguments = [*robot.q, *(p.symbol for p in robot.geometric_parameters)]
        typical = max((abs(float(p.default)) for p in robot.geometric_parameters), default=1.0) or 1.0
        self.points = [[draw.uniform(-math.pi, math.pi) for _ in robot.q]
                       + [float(p.default) * draw.uniform(0.8, 1.2) + draw.uniform(-0.05, 0.05) * typical
                          for p in robot.geometric_parameters] for _ in range(_SAMPLES)]
        self._symbolic: dict[Frame, sp.Matrix] = {}
        self._numeric: dict[Frame, list[np.ndarray]] = {}

    def symbolic(self, frame: Frame) -> sp.Matrix:
        if frame not in self._symbolic:
            self._symbolic[frame] = jacobian(self.chain, frame=frame, point=self.point)
        return self._symbolic[frame]

    def numeric(self, frame: Frame) -> list[np.ndarray]:
        if frame not in self._numeric:
            function = sp.lambdify(self.arguments, self.symbolic(frame), modules="numpy", cse=lambdify_cse)
            self._numeric[frame] = [np.asarray(function(*values), dtype=float) for values in self.points]
        return self._numeric[frame]

    def rank(self, rows: Sequence[int], frame: Frame) -> int:
        rows = list(rows)
        return min(int(np.linalg.matrix_rank(J[rows, :], tol=_RELATIVE * max(1.0, float(np.abs(J).max()))))
                   for J in self.numeric(frame))

    def nonzero(self, rows: Sequence[int], frame: Frame) -> tuple[int, ...]:
        J = self.symbolic(frame)
        return tuple(row for row in rows if any(entry != 0 for entry in J.row(row)))

    def constant_entry(self, row: int, frame: Frame) -> int | None:
        """A column where ``row`` holds a nonzero number (no joint, no parameter), if any."""
        return next((c for c, entry in enumerate(self.symbolic(frame).row(row))
                     if entry.is_number and entry != 0), None)

    def multiple(self, row: int, anchor: int, frame: Frame) -> bool:
        """Whether ``row`` is a multiple of ``anchor``, which has a constant entry, at every random point."""
        column = self.constant_entry(anchor, frame)
        if column is None:
            return False
        for J in self.numeric(frame):
            rest = J[row] - J[row, column] / J[anchor, column] * J[anchor]
            if np.abs(rest).max() > _RELATIVE * max(1.0, float(np.abs(J).max())):
                return False
        return True

    def size(self, rows: Sequence[int], frame: Frame | None) -> int:
        return int(sp.count_ops(self.symbolic(0 if frame is None else frame).extract(list(rows), list(range(self.n)))))
