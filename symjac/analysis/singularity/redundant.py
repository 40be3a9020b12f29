r"""A redundant arm's singularities explained: the minors that vanish everywhere, and each singular set.

A redundant arm's report (:func:`symjac.analysis.singularity.singularities.singularities`) holds the determinants of
its square minors. This module says why a minor vanishes identically (:class:`ZeroMinor`: its joints' axes meet in
groups, so a wrench loads none of them), and explains every component of the singular set found by
:func:`symjac.analysis.singularity.sets.singular_conditions` (:class:`SingularSet`): its kind, the direction the arm
loses there (:math:`u^T J = 0`, also the wrench held with zero torque), and the self-motion, the null space of
:math:`J` on the set (one dimension more than the :math:`n - m` of a regular configuration) and near it.

Kinds, for an arm of six joints or more, from the joints the conditions involve: the last three joints alone,
``wrist``; the first three alone, ``shoulder``; one joint between them whose two neighbouring axes now lie on one
line, ``elbow`` (the arm stretched out or folded back); joints of both groups with axes that became collinear,
``alignment``; anything else ``other``. A shorter arm (a planar 3R arm on two rows) has no separate groups and is
classified by the square arm's geometric rules
(:func:`symjac.analysis.singularity.geometry.classify`).
"""

from __future__ import annotations

import random
from collections.abc import Container, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from symjac.analysis.singularity.determinant import Determinant
from symjac.analysis.singularity.directions import LostDirection, SelfMotion, canonical, lost_direction
from symjac.analysis.singularity.evidence import Evidence, evidence_at
from symjac.analysis.singularity.geometry import (
    Cause,
    Finding,
    Relation,
    SingularityKind,
    classify,
    concurrent_groups,
    findings,
    geometry_at,
)
from symjac.analysis.singularity.joint_limits import LimitStatus, limit_status, within_limits
from symjac.analysis.singularity.sets import Condition, condition_samples, singular_conditions
from symjac.analysis.singularity.solve import Solution
from symjac.analysis.spaces import JacobianSpaces, jacobian_spaces
from symjac.kinematics.chain import Chain
from symjac.kinematics.numeric import numeric_jacobian

__all__ = ["SingularSet", "ZeroMinor", "explain_sets", "set_joints", "zero_minor"]

_NEAR = 0.25  # rad (or length unit) the condition joints move to leave a singular set for a regular configuration


@dataclass(frozen=True)
class ZeroMinor:
    r"""A square minor that vanishes at every configuration, and why.

    ``rank`` is the minor's rank at a random configuration, ``concurrent`` the groups of its joints (0-based) whose
    axes pass through one point, ``wrench`` a wrench (in the minor's rows and frame) that loads none of its joints.
    Two groups of three meeting at two points leave the force along the line through both points unresisted.
    """

    columns: tuple[int, ...]
    rank: int
    concurrent: tuple[tuple[int, ...], ...]
    wrench: LostDirection | None


@dataclass(frozen=True)
class SingularSet:
    r"""One component of a redundant arm's singular set: ``conditions`` all hold, and the arm loses rank there.

    ``variables`` are the robot's coordinates, which the conditions are written in. ``sample`` is a configuration on
    the set (parameters at their defaults; ``None`` when it exists only for other parameter values). ``null_space``
    is a basis of the self-motions there, ``regular_null_space`` one at a regular configuration near it;
    ``self_motion`` is the self-motion that appears on the set (the part of the null space there orthogonal to the
    one nearby). ``limits`` holds one status per solution, in the order of :attr:`solutions`. ``evidence`` holds the
    facts checked at the sample that the words may state (:func:`symjac.analysis.singularity.evidence.evidence_at`).
    """

    conditions: tuple[Condition, ...]
    variables: tuple[sp.Symbol, ...]
    cause: Cause
    exists_for_defaults: bool
    sample: tuple[float, ...] | None = None
    lost_direction: LostDirection | None = None
    self_motion: SelfMotion | None = None
    null_space: tuple[SelfMotion, ...] = ()
    regular_null_space: tuple[SelfMotion, ...] = ()
    limits: tuple[LimitStatus, ...] = ()
    evidence: Evidence | None = None

    @property
    def kind(self) -> SingularityKind:
        """``wrist``, ``shoulder``, ``elbow``, ``alignment`` or ``other`` (see the module docstring)."""
        return self.cause.kind

    @property
    def solutions(self) -> tuple[Solution, ...]:
        """Every condition's solutions, condition by condition."""
        return tuple(solution for condition in self.conditions for solution in condition.solutions)

    @property
    def existence(self) -> sp.Expr | None:
        """When the set exists, as a condition on the parameters (``True`` always, ``None`` undecided)."""
        parts = [condition.existence for condition in self.conditions]
        if any(part is None for part in parts):
            return None
        return sp.And(*parts)

    @property
    def reachable(self) -> bool | None:
        """Whether each condition has a solution inside the joint limits (``None`` when that is not known)."""
        statuses, start = [], 0
        for condition in self.conditions:
            statuses.append(self.limits[start:start + len(condition.solutions)])
            start += len(condition.solutions)
        if any(all(status is LimitStatus.OUTSIDE for status in group) for group in statuses if group):
            return False
        reached = (LimitStatus.INSIDE, LimitStatus.PARTLY, LimitStatus.UNLIMITED)
        return True if all(any(s in reached for s in group) for group in statuses if group) else None


def zero_minor(chain: Chain, minor: Determinant, q: Sequence[float]) -> ZeroMinor:
    """Why ``minor`` (identically zero) vanishes, examined at the configuration ``q``."""
    geometry = geometry_at(chain, q, minor.point)
    J = numeric_jacobian(chain, q, minor.frame, minor.point)[list(minor.rows), :][:, list(minor.columns)]
    spaces = jacobian_spaces(J, tolerance=1e-8 * max(1.0, float(np.abs(J).max())))
    revolute = [c for c in minor.columns if chain.robot.joints[c].is_revolute] if chain.robot.coupling is None else []
    wrench = None
    if spaces.left_null_space.shape[1]:
        wrench = lost_direction(chain, minor.rows, minor.frame, q, geometry, canonical(spaces.left_null_space[:, 0]))
    return ZeroMinor(minor.columns, spaces.rank, concurrent_groups(geometry, revolute), wrench)


def _joints(conditions: Sequence[Condition], chain: Chain) -> set[int]:
    return _condition_joints(conditions, list(chain.robot.q))


def _condition_joints(conditions: Sequence[Condition], variables: Sequence[sp.Symbol]) -> set[int]:
    return {variables.index(v) for c in conditions for v in c.expression.free_symbols if v in variables}


def set_joints(singular_set: SingularSet) -> tuple[int, ...]:
    """The joints (0-based coordinates) the conditions of ``singular_set`` involve."""
    return tuple(sorted(_condition_joints(singular_set.conditions, singular_set.variables)))


def _cause(chain: Chain, conditions: Sequence[Condition], new: Sequence[Finding]) -> Cause:
    joints, n = _joints(conditions, chain), chain.robot.n_coordinates
    if n < 6:  # no separate shoulder and wrist groups: the square arm's geometric rules
        return classify(new, joints, chain)
    aligned = tuple(f for f in new if f.relation is Relation.PARALLEL_AXES and f.collinear)
    evidence = aligned or tuple(new)
    if joints <= set(range(n - 3, n)):
        return Cause(SingularityKind.WRIST, evidence)
    if joints <= {0, 1, 2}:
        return Cause(SingularityKind.SHOULDER, evidence)
    (joint,) = joints if len(joints) == 1 else (None,)
    if joint is not None and any(f.joints[0] < joint < f.joints[1] for f in aligned):  # its neighbours line up
        return Cause(SingularityKind.ELBOW, evidence)
    return Cause(SingularityKind.ALIGNMENT if aligned else SingularityKind.OTHER, evidence)


def _motions(null_space: np.ndarray, names: tuple[str, ...]) -> tuple[SelfMotion, ...]:
    columns = tuple(range(null_space.shape[0]))
    return tuple(SelfMotion(tuple(float(x) for x in canonical(v)), columns, names) for v in null_space.T)


def _explain(chain: Chain, conditions: tuple[Condition, ...], minor: Determinant, known: Container[object],
             seed: int, rows: Sequence[int]) -> SingularSet:
    limits = tuple(limit_status(chain, s) for c in conditions for s in c.solutions)
    samples = condition_samples(chain, conditions, 8, seed, project=tuple(rows) != minor.rows)
    if not len(samples):
        return SingularSet(conditions, tuple(chain.robot.q), Cause(SingularityKind.OTHER), False, limits=limits)
    rows = list(rows)

    def spaces_at(q: np.ndarray) -> JacobianSpaces:
        J = numeric_jacobian(chain, q.tolist(), minor.frame, minor.point)[rows, :]
        return jacobian_spaces(J, tolerance=1e-8 * max(1.0, float(np.abs(J).max())))

    # the typical point of the set: the highest rank (a sample may also lie on another set, such as the iiwa's
    # elbow folded back with the wrist centre on the shoulder), then within the joint limits
    ranked = sorted(range(len(samples)), key=lambda k: (-spaces_at(samples[k]).rank,
                                                        not within_limits(chain.robot, samples[k].tolist()), k))
    sample = samples[ranked[0]]
    geometry = geometry_at(chain, sample, minor.point)
    new = [finding for finding in findings(chain, geometry) if finding.key not in known]
    singular = spaces_at(sample)
    near = sample.copy()
    near[sorted(_joints(conditions, chain))] += _NEAR
    regular = spaces_at(near)
    names = () if chain.robot.coupling is None else tuple(str(v) for v in chain.robot.q)
    lost = None
    if singular.left_null_space.shape[1]:
        lost = lost_direction(chain, tuple(rows), minor.frame, sample, geometry,
                              canonical(singular.left_null_space[:, 0]))
    extra = singular.null_space - regular.null_space @ (regular.null_space.T @ singular.null_space)
    motion = None
    if extra.size:
        u, sigma, _ = np.linalg.svd(extra, full_matrices=False)
        if sigma[0] > 1e-6:
            motion = _motions(u[:, :1], names)[0]
    facts = evidence_at(chain, tuple(rows), minor.frame, minor.point, range(chain.robot.n_coordinates), sample,
                        None if lost is None else lost.vector, None if motion is None else motion.rates)
    return SingularSet(conditions, tuple(chain.robot.q), _cause(chain, conditions, new), True,
                       tuple(float(x) for x in sample), lost, motion, _motions(singular.null_space, names),
                       _motions(regular.null_space, names), limits, facts)


def explain_sets(chain: Chain, minors: Sequence[Determinant], seed: int = 0,
                 rows: Sequence[int] | None = None) -> tuple[SingularSet, ...]:
    """Every component of the singular set of an arm whose square minors are ``minors``, explained.

    ``rows`` are the Jacobian rows the rank is read from: by default those of the minors (a redundant arm's minors
    share their rows); a short arm's row minors pass all their rows.
    """
    nonzero = [minor for minor in minors if minor.coefficient != 0]
    if not nonzero:
        return ()
    generator = random.Random(seed)
    generic = [generator.uniform(-2.5, 2.5) for _ in chain.robot.q]
    known = {finding.key for finding in findings(chain, geometry_at(chain, generic, nonzero[0].point))}
    chosen = nonzero[0].rows if rows is None else tuple(rows)
    return tuple(_explain(chain, conditions, nonzero[0], known, seed, chosen)
                 for conditions in singular_conditions(chain, nonzero, seed, every_joint=rows is not None))
