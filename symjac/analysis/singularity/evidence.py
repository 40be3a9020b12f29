r"""What the numbers say at a sample of a singular set: the facts an explanation may state, each one checked.

At a configuration :math:`q_s` on the set the analysed Jacobian :math:`J` (the chosen rows, frame, point and columns)
is evaluated and compared with the same Jacobian at a generic configuration :math:`q_g`. The facts:

* the speed of the reference point per unit rate of joint :math:`k`, :math:`\lVert J_{v,k} \rVert` (the linear part
  of column :math:`k` on all three linear rows; metres per radian for a revolute joint);
* the joints that *no longer move the point*: :math:`\lVert J_{v,k}(q_s) \rVert \le \epsilon` while
  :math:`\lVert J_{v,k}(q_g) \rVert > \epsilon`;
* the same two facts for every landmark point of the geometry
  (:func:`~symjac.analysis.singularity.geometry.geometry_at`: the reference point, a wrist centre): a revolute joint
  :math:`k` moves a point :math:`p` beyond it in the chain at :math:`\lVert z_k \times (p - o_k)\rVert`
  (:class:`PointSpeeds`);
* of those, the ones that stop on the whole set: the linear column, with the solution :math:`q_i = f(\ldots)` the
  sample was drawn from substituted, simplifies to zero symbolically (parameters kept symbolic);
* the joints whose analysed columns became *parallel*: :math:`\sigma_2([J_i\ J_j]) \le \epsilon` at :math:`q_s`, not
  at :math:`q_g` (two joints that now do the same thing);
* the joints whose columns became *dependent*: the support of the null space of :math:`J(q_s)` (a column lies in
  the span of the others exactly when some :math:`\dot q` with :math:`J \dot q = 0` uses it);
* the lost direction :math:`u` (a left singular vector of :math:`J(q_s)` for a zero singular value) and a null
  motion :math:`\dot q` (a right one), with their residuals :math:`\lVert u^T J \rVert` and
  :math:`\lVert J \dot q \rVert`.

The tolerance is relative to the size of the Jacobian: :math:`\epsilon = 10^{-6}\,\sigma_1(J(q_s))`. A speed counts as
*moving* only above :math:`10^{-3}\,\sigma_1`; between the two nothing is claimed. Everything is data; words are
:mod:`symjac.printing.prose`'s, and they state only what this holds.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass, replace
from itertools import combinations

import numpy as np
import sympy as sp

from symjac.analysis.singularity.geometry import Geometry, Landmark, geometry_at
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.numeric import numeric_jacobian

__all__ = ["MOVING", "ZERO", "Evidence", "PointSpeeds", "evidence_at"]

ZERO = 1e-6
"""Relative to the largest singular value of the analysed Jacobian: below this a column (or residual) is zero."""

MOVING = 1e-3
"""Relative to the same: above this a joint still moves the point."""


@dataclass(frozen=True)
class PointSpeeds:
    r"""How fast each revolute joint moves one landmark point at the sample, per radian.

    ``speeds[k]`` is :math:`\lVert z_k \times (p - o_k)\rVert` for joint ``k`` (0-based) when the joint lies before
    the point in the chain, ``0.0`` for a joint after it, ``nan`` for a prismatic joint. ``stopped`` are the revolute
    joints that move the point generically but not at the sample, ``moving`` those that move it faster than
    :data:`MOVING` times the Jacobian's size.
    """

    landmark: Landmark
    speeds: tuple[float, ...]
    stopped: tuple[int, ...]
    moving: tuple[int, ...]


@dataclass(frozen=True)
class Evidence:
    r"""The checked facts at ``sample`` (coordinates, parameters at their defaults) for the analysed Jacobian.

    ``rows`` (0..5 for :math:`v_x .. \omega_z`), ``frame`` and ``columns`` (0-based coordinates) say which Jacobian;
    ``names`` what each coordinate of the robot is called (``theta1``), in the order of ``sample``; ``revolute``
    whether each coordinate is an angle; ``coupled`` whether the coordinates differ from the joints (a coupling).
    ``jacobian`` is :math:`J(q_s)` on ``rows`` x ``columns`` and ``scale`` its
    largest singular value. ``speeds[k]`` is the speed of the point per unit rate of coordinate ``columns[k]``.
    Joint lists (``stopped``, ``parallel``, ``dependent``, ``moving``) hold 0-based coordinates; ``stopped_on_set``
    the stopped ones proven symbolically to stop everywhere on the set. ``lost`` is the
    lost direction :math:`u` on ``rows`` and ``null_motion`` a motion :math:`\dot q` on ``columns`` (empty when the
    Jacobian has full rank there); ``points`` the speeds of every landmark point (none for a coupled robot, whose
    columns are not joints); ``lost_residual`` and ``motion_residual`` are :math:`\lVert u^T J\rVert` and
    :math:`\lVert J\dot q\rVert` divided by ``scale``.
    """

    sample: tuple[float, ...]
    names: tuple[str, ...]
    revolute: tuple[bool, ...]
    coupled: bool
    rows: tuple[int, ...]
    frame: Frame
    columns: tuple[int, ...]
    jacobian: tuple[tuple[float, ...], ...]
    scale: float
    rank: int
    speeds: tuple[float, ...]
    stopped: tuple[int, ...]
    moving: tuple[int, ...]
    parallel: tuple[tuple[int, int], ...]
    dependent: tuple[int, ...]
    stopped_on_set: tuple[int, ...] = ()
    points: tuple[PointSpeeds, ...] = ()
    lost: tuple[float, ...] = ()
    lost_residual: float = 0.0
    null_motion: tuple[float, ...] = ()
    motion_residual: float = 0.0

    @property
    def tolerance(self) -> float:
        r"""The absolute tolerance :math:`\epsilon` below which a column or residual counts as zero."""
        return ZERO * self.scale

    @property
    def lost_checked(self) -> bool:
        r"""Whether the stated lost direction is one: :math:`\lVert u^T J\rVert \le \epsilon` (a unit :math:`u`)."""
        return len(self.lost) > 0 and self.lost_residual <= ZERO

    @property
    def motion_checked(self) -> bool:
        r"""Whether the stated null motion moves nothing: :math:`\lVert J \dot q\rVert \le \epsilon` (a unit one)."""
        return len(self.null_motion) > 0 and self.motion_residual <= ZERO

    def point(self, landmark: Landmark) -> PointSpeeds | None:
        """The speeds of ``landmark`` (``None`` when it was not examined)."""
        return next((p for p in self.points if p.landmark == landmark), None)

    def speed(self, coordinate: int) -> float:
        """The speed of the point per unit rate of ``coordinate`` (0-based, one of ``columns``)."""
        return self.speeds[self.columns.index(coordinate)]


def _linear_norms(full: np.ndarray, columns: Sequence[int]) -> np.ndarray:
    return np.linalg.norm(full[:3, list(columns)], axis=0)


def _moved_by(landmark: Landmark, joint: int) -> bool:
    """Whether 0-based ``joint`` lies before ``landmark`` in the chain (frame {f}'s origin moves with joints 1..f)."""
    return landmark.kind != "frame origin" or not isinstance(landmark.index, int) or joint < landmark.index


def _point_speeds(chain: Chain, here: Geometry, generic: Geometry, scale: float) -> tuple[PointSpeeds, ...]:
    revolute = [joint.is_revolute for joint in chain.robot.joints]
    before = dict(generic.points)

    def speeds(landmark: Landmark, p: np.ndarray, geometry: Geometry) -> list[float]:
        return [float("nan") if not revolute[k] else float(np.linalg.norm(np.cross(z, p - o)))
                if _moved_by(landmark, k) else 0.0 for k, (o, z) in enumerate(geometry.axes)]

    found = []
    for landmark, p in here.points:
        now = speeds(landmark, p, here)
        then = speeds(landmark, before[landmark], generic) if landmark in before else [0.0] * len(now)
        stopped = tuple(k for k, (s, g) in enumerate(zip(now, then, strict=True)) if s <= ZERO * scale < g)
        moving = tuple(k for k, s in enumerate(now) if s > MOVING * scale)
        found.append(PointSpeeds(landmark, tuple(now), stopped, moving))
    return tuple(found)


_SYMBOLIC_OPS = 600
"""Operations beyond which a substituted column is not simplified (the claim then stays numeric, at the sample)."""


def _stopped_on_set(chain: Chain, frame: Frame, point: tuple[sp.Expr, sp.Expr, sp.Expr], stopped: Sequence[int],
                    solution: tuple[sp.Expr, sp.Expr] | None) -> tuple[int, ...]:
    r"""The ``stopped`` columns whose linear part :math:`J_{v,k}` is zero with ``lhs = rhs`` substituted."""
    if solution is None or not stopped:
        return ()
    J = jacobian(chain, frame=frame, point=point)
    draw = random.Random(len(stopped))
    proven = []
    for c in stopped:
        entries = [entry.subs(*solution) for entry in J[:3, c]]
        symbols = sorted(set().union(*(e.free_symbols for e in entries)), key=str)
        trial = {symbol: draw.uniform(0.2, 1.3) for symbol in symbols}  # a quick refutation before simplifying
        if any(abs(complex(e.evalf(subs=trial))) > 1e-9 for e in entries):
            continue
        if all(sp.count_ops(e) <= _SYMBOLIC_OPS and sp.simplify(e) == 0 for e in entries):
            proven.append(c)
    return tuple(proven)


def _parallel_pairs(J: np.ndarray, columns: Sequence[int], tolerance: float) -> set[tuple[int, int]]:
    pairs = set()
    norms = np.linalg.norm(J, axis=0)
    for a, b in combinations(range(len(columns)), 2):
        if norms[a] <= tolerance or norms[b] <= tolerance:
            continue
        if np.linalg.svd(J[:, [a, b]], compute_uv=False)[-1] <= tolerance:
            pairs.add((columns[a], columns[b]))
    return pairs


def evidence_at(chain: Chain, rows: Sequence[int], frame: Frame, point: tuple[sp.Expr, sp.Expr, sp.Expr],
                columns: Sequence[int],
                sample: Sequence[float], lost: Sequence[float] | None = None, motion: Sequence[float] | None = None,
                solution: tuple[sp.Expr, sp.Expr] | None = None, seed: int = 1729) -> Evidence:
    r"""The facts at ``sample`` for the Jacobian on ``rows`` x ``columns`` in ``frame`` at ``point`` (see the module).

    ``lost`` (on ``rows``) and ``motion`` (on ``columns``) are the lost direction and null motion an explanation
    states; their residuals are checked here (without them, singular vectors of :math:`J(q_s)` are used).
    ``solution`` (``lhs``, ``rhs``) is the family of the set the sample lies on, for the symbolic check. The generic
    configuration :math:`q_g` is drawn uniformly from :math:`[-2.5, 2.5]` per coordinate with ``seed``.
    """
    model = chain.robot
    rows, columns = tuple(rows), tuple(columns)
    full = numeric_jacobian(chain, list(sample), frame, point)
    draw = random.Random(seed)
    anywhere = [draw.uniform(-2.5, 2.5) for _ in model.q]
    generic_full = numeric_jacobian(chain, anywhere, frame, point)
    J, generic = full[list(rows), :][:, list(columns)], generic_full[list(rows), :][:, list(columns)]
    U, sigma, Vt = np.linalg.svd(J)
    scale = float(sigma[0]) if sigma.size and sigma[0] > 0 else 1.0
    tolerance = ZERO * scale
    rank = int(np.sum(sigma > tolerance))
    speeds, generic_speeds = _linear_norms(full, columns), _linear_norms(generic_full, columns)
    stopped = tuple(c for c, s, g in zip(columns, speeds, generic_speeds, strict=True) if s <= tolerance < g)
    moving = tuple(c for c, s in zip(columns, speeds, strict=True) if s > MOVING * scale)
    parallel = tuple(sorted(_parallel_pairs(J, columns, tolerance)
                            - _parallel_pairs(generic, columns, ZERO * max(float(np.linalg.norm(generic, 2)), 1e-300))))
    null = Vt[rank:].T  # columns: a basis of the null space
    dependent = tuple(c for k, c in enumerate(columns) if null.size and np.abs(null[k]).max() > 1e-6)
    names = tuple(str(v) for v in model.q)
    points = () if model.coupling is not None else _point_speeds(chain, geometry_at(chain, sample, point),
                                                                 geometry_at(chain, anywhere, point), scale)
    revolute = tuple(kind == "revolute" for kind in model.coordinate_types)
    facts = Evidence(tuple(float(x) for x in sample), names, revolute, model.coupling is not None, rows, frame, columns,
                     tuple(tuple(float(x) for x in row) for row in J), scale, rank,
                     tuple(float(s) for s in speeds), stopped, moving, parallel, dependent,
                     _stopped_on_set(chain, frame, point, stopped, solution), points)
    if lost is None and motion is None and rank == min(J.shape):
        return facts
    u = np.asarray(lost, dtype=float) if lost is not None else U[:, rank] if rank < J.shape[0] else np.zeros(0)
    qdot = np.asarray(motion, dtype=float) if motion is not None else null[:, 0] if null.size else np.zeros(0)
    return replace(facts, lost=tuple(float(x) for x in u),
                   lost_residual=float(np.linalg.norm(u @ J)) / scale if u.size else 0.0,
                   null_motion=tuple(float(x) for x in qdot),
                   motion_residual=float(np.linalg.norm(J @ qdot)) / scale if qdot.size else 0.0)

