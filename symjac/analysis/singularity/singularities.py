r"""The singularity report: every factor of :math:`\det J` solved, classified, and what the arm loses there.

:func:`singularities` puts the pieces together: :func:`symjac.analysis.singularity.determinant.determinant` factors the
determinant,
:func:`symjac.analysis.singularity.solve.solve_factor` solves each factor, and at a sample of each singular set the arm
is examined numerically: :mod:`symjac.analysis.singularity.geometry` classifies it, and the null spaces of the Jacobian
there (:func:`symjac.analysis.spaces.jacobian_spaces`) give the lost direction :math:`u` (:math:`u^T J = 0`: a velocity
the arm cannot produce, and a wrench it holds with zero joint torque) and the self-motion :math:`\dot q` (:math:`J \dot
q = 0`). Everything is data; :mod:`symjac.printing` words and formats it.
"""

from __future__ import annotations

import random
from collections.abc import Container, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import Determinant, determinant
from symjac.analysis.singularity.geometry import (
    Cause,
    FrameAxis,
    Geometry,
    SingularityKind,
    classify,
    findings,
    frame_axes,
    geometry_at,
    named_axis,
    parallel,
)
from symjac.analysis.singularity.joint_limits import LimitStatus, limit_status
from symjac.analysis.singularity.solve import Solution, solution_sample, solve_factor
from symjac.analysis.spaces import jacobian_spaces, task_rows
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import Point, point_vector
from symjac.kinematics.memo import memoized
from symjac.kinematics.numeric import numeric_at, numeric_jacobian

__all__ = [
    "DirectionPart",
    "LimitStatus",
    "LostDirection",
    "SelfMotion",
    "SingularFactor",
    "SingularityKind",
    "SingularityReport",
    "singularities",
]


@dataclass(frozen=True)
class DirectionPart:
    """The linear or angular half of a lost direction: a unit 3-vector, and the frame axis it lies along if any."""

    unit: tuple[float, float, float]
    axis: FrameAxis | None


@dataclass(frozen=True)
class LostDirection:
    r"""A Cartesian direction :math:`u` the arm cannot move in, with :math:`u^T J = 0` for the analysed rows.

    ``vector`` holds the components on ``rows`` (``v_x .. omega_z``), expressed in ``frame``; ``linear`` and
    ``angular`` are its halves (``None`` when zero); ``radial`` tells a pure translation along the line from the
    origin of frame {0} to the reference point. The same vector is a wrench held with zero joint torque.
    """

    vector: tuple[float, ...]
    rows: tuple[int, ...]
    frame: Frame
    linear: DirectionPart | None
    angular: DirectionPart | None
    radial: bool = False

    @property
    def full(self) -> np.ndarray:
        """The 6-vector ``[v; omega]`` with zeros on the rows not analysed."""
        full = np.zeros(6)
        full[list(self.rows)] = self.vector
        return full


@dataclass(frozen=True)
class SelfMotion:
    r"""Joint rates :math:`\dot q` with :math:`J \dot q = 0`: ``rates[i]`` on joint ``columns[i]`` (0-based).

    A coupled robot's columns are its coordinates, not its joints: ``names`` then gives each column's coordinate
    (``theta5``) so that words do not call coordinate 4 "joint 4"; empty without a coupling.
    """

    rates: tuple[float, ...]
    columns: tuple[int, ...]
    names: tuple[str, ...] = ()


@dataclass(frozen=True)
class SingularFactor:
    r"""One factor of :math:`\det J`, solved and explained.

    ``cause`` holds the :class:`~symjac.analysis.singularity.geometry.SingularityKind` and its evidence. ``sample`` is a
    configuration on the singular set (parameters at their defaults); ``lost_direction`` what the arm cannot do
    there, ``self_motion`` a joint motion that moves nothing. ``limits`` says, for each solution, whether it lies
    inside the joint limits (:func:`symjac.analysis.singularity.joint_limits.limit_status`).
    """

    expression: sp.Expr
    multiplicity: int
    solutions: tuple[Solution, ...]
    existence: sp.Expr | None
    exists_for_defaults: bool | None
    cause: Cause
    sample: tuple[float, ...] | None = None
    lost_direction: LostDirection | None = None
    self_motion: SelfMotion | None = None
    limits: tuple[LimitStatus, ...] = ()

    @property
    def reachable(self) -> bool | None:
        """Whether the arm can reach this singular set within its joint limits.

        ``False`` when every solution lies outside the limits, ``True`` when one lies (at least partly) inside or
        involves only joints without limits, ``None`` when that could not be decided or there are no solutions.
        """
        if not self.limits:
            return None
        if all(status is LimitStatus.OUTSIDE for status in self.limits):
            return False
        reached = (LimitStatus.INSIDE, LimitStatus.PARTLY, LimitStatus.UNLIMITED)
        return True if any(status in reached for status in self.limits) else None

    @property
    def kind(self) -> SingularityKind:
        """``wrist``, ``shoulder``, ``elbow``, ``parameter`` (a special design only) or ``other``."""
        return self.cause.kind


@dataclass(frozen=True)
class SingularityReport:
    """Everything :func:`singularities` found: the determinant and each factor explained."""

    robot: str
    determinant: Determinant
    factors: tuple[SingularFactor, ...]
    redundant: bool = False
    minors: tuple[Determinant, ...] = ()

    @property
    def frame(self) -> Frame:
        """The frame the analysis (and every lost direction) is expressed in."""
        return self.determinant.frame


def _point(chain: Chain, point: Point | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    return point_vector(chain, ("tool" if chain.robot.tool is not None else "wrist") if point is None else point)


def _rows(chain: Chain, rows: Sequence[int] | None, point: tuple[sp.Expr, ...]) -> tuple[int, ...]:
    return task_rows(chain, point) if rows is None else tuple(rows)


@memoized(point=_point, rows=_rows)
def singularities(
    chain: Chain,
    rows: Sequence[int] | None = None,
    frame: Frame | None = None,
    point: Point | None = None,
    *,
    numeric: bool = False,
    seed: int = 0,
) -> SingularityReport:
    r"""The singular configurations of ``robot``: :func:`determinant`, every factor solved, classified, explained.

    A redundant arm (more joints than task rows) has no square Jacobian; its report holds the determinants of the
    square minors (one joint locked at a time, :attr:`SingularityReport.minors`), and the arm is singular only where
    all of them vanish together (where the manipulability :math:`\sqrt{\det J J^T}` is zero). Arguments are as
    for :func:`symjac.analysis.singularity.determinant.determinant` (``robot`` a Robot or a Chain); ``seed`` fixes the
    random samples on the singular sets.

    Examples
    --------
    >>> from symjac import load_robot
    >>> report = singularities(load_robot("planar2r"))
    >>> [(f.expression, str(f.kind)) for f in report.factors]
    [(L1, 'parameter'), (L2, 'parameter'), (sin(theta2), 'elbow')]
    """
    return _report(chain, rows, frame, point, numeric, seed)  # type: ignore[arg-type]  # normalised by @memoized


def _report(chain: Chain, rows: tuple[int, ...], frame: Frame | None, point: tuple[sp.Expr, sp.Expr, sp.Expr],
            numeric: bool, seed: int) -> SingularityReport:
    model = chain.robot
    if model.n_coordinates > len(rows):
        minors = tuple(determinant(chain, rows, frame, point, columns=[c for c in range(model.n_coordinates) if c != k],
                                   numeric=numeric) for k in range(model.n_coordinates))
        return SingularityReport(model.name, minors[0], (), redundant=True, minors=minors)
    det = determinant(chain, rows, frame, point, numeric=numeric)
    generator = random.Random(seed)
    generic = findings(chain, geometry_at(chain, [generator.uniform(-2.5, 2.5) for _ in model.q], point))
    known = {finding.key for finding in generic}
    explained = [_explain(chain, det, factor, multiplicity, known, generator) for factor, multiplicity in det.factors]
    return SingularityReport(model.name, det, tuple(explained))


def _explain(chain: Chain, det: Determinant, factor: sp.Expr, multiplicity: int, known: Container[object],
             generator: random.Random) -> SingularFactor:
    model = chain.robot
    solutions, existence = solve_factor(chain, factor)
    holds = None if existence is None else bool(existence.xreplace(model.defaults)) if existence is not sp.true \
        else True
    if not solutions:
        return SingularFactor(factor, multiplicity, (), None, None, Cause(SingularityKind.PARAMETER))
    sample = None
    for solution in solutions:
        sample = solution_sample(chain, solution, generator)
        if sample is not None:
            break
    factor_joints = {i for i, value in enumerate(model.joint_values) if value.free_symbols & factor.free_symbols}
    limits = tuple(limit_status(chain, solution) for solution in solutions)
    if sample is None:
        return SingularFactor(factor, multiplicity, solutions, existence, holds, classify((), factor_joints, chain),
                              limits=limits)
    geometry = geometry_at(chain, sample, det.point)
    new = [finding for finding in findings(chain, geometry) if finding.key not in known]
    cause = classify(new, factor_joints, chain)
    J = numeric_jacobian(chain, sample, det.frame, det.point)[list(det.rows), :][:, list(det.columns)]
    spaces = jacobian_spaces(J, tolerance=1e-8 * max(1.0, float(np.abs(J).max())))
    lost = None
    if spaces.left_null_space.shape[1]:
        lost = _lost_direction(chain, det, sample, geometry, _canonical(spaces.left_null_space[:, 0]))
    motion = None
    if spaces.null_space.shape[1]:
        names = () if chain.robot.coupling is None else tuple(str(chain.robot.q[c]) for c in det.columns)
        motion = SelfMotion(tuple(float(x) for x in _canonical(spaces.null_space[:, 0])), det.columns, names)
    return SingularFactor(factor, multiplicity, solutions, existence, holds, cause, tuple(sample), lost, motion,
                          limits)


def _lost_direction(chain: Chain, det: Determinant, sample: Sequence[float], geometry: Geometry,
                    vector: np.ndarray) -> LostDirection:
    """The lost direction with each half named by the frame axis it lies along, and whether it is radial."""
    axes = frame_axes(chain, sample, det.frame)
    full = np.zeros(6)
    full[list(det.rows)] = vector
    halves: list[DirectionPart | None] = []
    for part in (full[:3], full[3:]):
        norm = np.linalg.norm(part)
        if norm < 1e-9:
            halves.append(None)
            continue
        unit = part / norm
        halves.append(DirectionPart((float(unit[0]), float(unit[1]), float(unit[2])), named_axis(unit, axes)))
    # radial: the reach vector from the base to the reference point, expressed in the analysis frame
    reach = numeric_at(chain, chain.rotation(det.frame, 0), sample) @ geometry.points[0][1]
    radial = bool(np.linalg.norm(full[3:]) < 1e-9 and np.linalg.norm(reach) > 1e-9
                  and parallel(full[:3], reach, 1e-7))
    return LostDirection(tuple(float(x) for x in vector), det.rows, det.frame, halves[0], halves[1], radial)


def _canonical(vector: np.ndarray) -> np.ndarray:
    """A unit vector with its largest component positive and round-off zeroed."""
    vector = np.where(np.abs(vector) < 1e-12, 0.0, vector)
    return vector if vector[np.argmax(np.abs(vector))] > 0 else -vector
