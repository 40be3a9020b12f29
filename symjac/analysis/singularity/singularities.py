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

import itertools
import random
from collections.abc import Container, Sequence
from dataclasses import dataclass, replace

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import Determinant, default_rows, determinant
from symjac.analysis.singularity.directions import DirectionPart, LostDirection, SelfMotion, canonical, lost_direction
from symjac.analysis.singularity.evidence import Evidence, evidence_at
from symjac.analysis.singularity.geometry import Cause, SingularityKind, classify, findings, geometry_at
from symjac.analysis.singularity.joint_limits import LimitStatus, limit_status
from symjac.analysis.singularity.redundant import SingularSet, ZeroMinor, explain_sets, zero_minor
from symjac.analysis.singularity.rows import RowChoice, singular_rows
from symjac.analysis.singularity.sets import unsolved_factors
from symjac.analysis.singularity.solve import Solution, solution_sample, solve_factor
from symjac.analysis.spaces import jacobian_spaces
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import Point, point_vector
from symjac.kinematics.memo import memoized
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.ends import end_point
from symjac.model.robot import Robot

__all__ = [
    "DirectionPart",
    "Evidence",
    "LimitStatus",
    "LostDirection",
    "SelfMotion",
    "SingularFactor",
    "SingularSet",
    "SingularityKind",
    "SingularityReport",
    "ZeroMinor",
    "singularities",
]


@dataclass(frozen=True)
class SingularFactor:
    r"""One factor of :math:`\det J`, solved and explained.

    ``cause`` holds the :class:`~symjac.analysis.singularity.geometry.SingularityKind` and its evidence. ``sample`` is a
    configuration on the singular set (parameters at their defaults); ``lost_direction`` what the arm cannot do
    there, ``self_motion`` a joint motion that moves nothing. ``limits`` says, for each solution, whether it lies
    inside the joint limits (:func:`symjac.analysis.singularity.joint_limits.limit_status`). ``evidence`` holds
    the facts checked at the sample that the words may state (:func:`symjac.analysis.singularity.evidence.evidence_at`).
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
    evidence: Evidence | None = None

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
    sets: tuple[SingularSet, ...] = ()
    zero_minors: tuple[ZeroMinor, ...] = ()
    unsolved: tuple[sp.Expr, ...] = ()  # minor factors the set search could not use: the sets may be incomplete
    coordinates: tuple[str, ...] = ()  # a redundant arm's columns: "joint 3", or a coupled robot's "theta5"
    variables: tuple[sp.Symbol, ...] = ()  # the coordinates' symbols, in the order of every sample configuration
    choice: RowChoice | None = None  # how the rows of a short arm were chosen (None: given, or all six)
    point_name: str = "reference"  # "tool", "flange" or the coordinates in frame {n}: which point the rows move
    n_joints: int = 0  # the last frame, n

    @property
    def over_rows(self) -> bool:
        """Whether the minors are those of a short arm's rows (all columns each), not of a redundant arm's columns."""
        return self.choice is not None and not self.choice.exact

    @property
    def frame(self) -> Frame:
        """The frame the analysis (and every lost direction) is expressed in."""
        return self.determinant.frame


def _point(chain: Chain, point: Point | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    return point_vector(chain, end_point(chain) if point is None else point)


def _rows(chain: Chain, rows: Sequence[int] | None) -> tuple[int, ...] | None:
    return None if rows is None else tuple(rows)


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
    square minors (the other joints locked, :attr:`SingularityReport.minors`), and the arm is singular only where
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
    report = _report(chain, rows, frame, point, numeric, seed)  # type: ignore[arg-type]  # normalised by @memoized
    return replace(report, point_name=_point_name(chain, point), n_joints=chain.n_joints)  # type: ignore[arg-type]


def _point_name(chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr]) -> str:
    """``"tool"``, ``"flange"`` (the origin of {n}) or the coordinates of ``point`` in frame {n}."""
    if chain.robot.tool is not None and tuple(point) == tuple(point_vector(chain, "tool")):
        return "tool"
    return "flange" if all(c == 0 for c in point) else ",".join(sp.sstr(c) for c in point)


def _report(chain: Chain, rows: tuple[int, ...], frame: Frame | None, point: tuple[sp.Expr, sp.Expr, sp.Expr],
            numeric: bool, seed: int) -> SingularityReport:
    model = chain.robot
    choice = None
    if rows is None and model.n_coordinates < 6:
        choice = singular_rows(chain, point, None if frame is None else chain.frame_name(chain.position(frame)))
        if not choice.exact:
            return _row_minors(chain, choice, point, numeric, seed)
        rows, frame = default_rows(chain, point, frame)
    elif rows is None:
        rows = tuple(range(6))
    if model.n_coordinates > len(rows):
        n = model.n_coordinates
        kept = sorted(itertools.combinations(range(n), len(rows)),  # by the joints locked: joint 1 locked first
                      key=lambda columns: tuple(c for c in range(n) if c not in columns))
        minors = tuple(determinant(chain, rows, frame, point, columns=columns, numeric=numeric) for columns in kept)
        draw = random.Random(seed)
        anywhere = [draw.uniform(-2.5, 2.5) for _ in model.q]
        zeros = tuple(zero_minor(chain, minor, anywhere) for minor in minors if minor.coefficient == 0)
        sets = explain_sets(chain, minors, seed)
        unsolved = unsolved_factors(chain, [minor for minor in minors if minor.coefficient != 0])
        return SingularityReport(model.name, minors[0], (), redundant=True, minors=minors, sets=sets,
                                 zero_minors=zeros, unsolved=unsolved, coordinates=_column_names(model),
                                 variables=tuple(model.q))
    det = determinant(chain, rows, frame, point, numeric=numeric)
    generator = random.Random(seed)
    generic = findings(chain, geometry_at(chain, [generator.uniform(-2.5, 2.5) for _ in model.q], point))
    known = {finding.key for finding in generic}
    explained = [_explain(chain, det, factor, multiplicity, known, generator) for factor, multiplicity in det.factors]
    return SingularityReport(model.name, det, tuple(explained), variables=tuple(model.q), choice=choice)


def _row_minors(chain: Chain, choice: RowChoice, point: tuple[sp.Expr, sp.Expr, sp.Expr], numeric: bool,
                seed: int) -> SingularityReport:
    r"""A short arm with no exact square rows: every :math:`n \times n` minor of its rows, and where all vanish."""
    model = chain.robot
    subsets = itertools.combinations(choice.rows, model.n_coordinates)
    minors = [determinant(chain, subset, choice.frame, point, numeric=numeric) for subset in subsets]
    nonzero = tuple(minor for minor in minors if minor.coefficient != 0)  # some exist: the rank is n somewhere
    sets = explain_sets(chain, nonzero, seed, rows=choice.rows)
    return SingularityReport(model.name, nonzero[0], (), redundant=True, minors=nonzero, sets=sets,
                             unsolved=unsolved_factors(chain, nonzero), coordinates=_column_names(model),
                             variables=tuple(model.q), choice=choice)


def _column_names(model: Robot) -> tuple[str, ...]:
    """What each Jacobian column drives, in words: ``joint 3``, or a coupled robot's coordinate ``theta5``."""
    return tuple(f"joint {k + 1}" if model.coupling is None else str(v) for k, v in enumerate(model.q))


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
        lost = lost_direction(chain, det.rows, det.frame, sample, geometry, canonical(spaces.left_null_space[:, 0]))
    motion = None
    if spaces.null_space.shape[1]:
        names = () if chain.robot.coupling is None else tuple(str(chain.robot.q[c]) for c in det.columns)
        motion = SelfMotion(tuple(float(x) for x in canonical(spaces.null_space[:, 0])), det.columns, names)
    facts = evidence_at(chain, det.rows, det.frame, det.point, det.columns, sample,
                        None if lost is None else lost.vector, None if motion is None else motion.rates,
                        (solution.lhs, solution.rhs))
    return SingularFactor(factor, multiplicity, solutions, existence, holds, cause, tuple(sample), lost, motion,
                          limits, facts)
