r"""Geometry at a configuration, as data: which axes and points line up, to classify a singularity.

Facts are checked numerically (to 1e-7) at a sample of the singular set and compared with a generic configuration:
only what becomes true there explains the singularity. Two wrist axes aligned is a *wrist* singularity; the point
on the first axis, or in the plane through it parallel to the second, a *shoulder* singularity; three parallel lines
(two of them joint axes) in one plane, the arm stretched out or folded back, an *elbow* singularity.

Nothing here is worded: a :class:`Finding` names its relation, joints and landmark, and
:mod:`symjac.printing.prose` says it in a sentence.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum, StrEnum
from itertools import combinations
from typing import Literal

import numpy as np
import sympy as sp

from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.numeric import numeric_at
from symjac.model.robot import Robot

__all__ = [
    "Cause",
    "Finding",
    "FrameAxis",
    "Geometry",
    "Landmark",
    "Relation",
    "SingularityKind",
    "classify",
    "concurrent_groups",
    "findings",
    "frame_axes",
    "geometry_at",
    "named_axis",
    "parallel",
]


class SingularityKind(StrEnum):
    """What a singular factor is: a textbook kind, a design flaw (a parameter), or none of these."""

    WRIST = "wrist"
    SHOULDER = "shoulder"
    ELBOW = "elbow"
    ALIGNMENT = "alignment"  # a redundant arm's axes line up, set by joints of neither group alone
    PARAMETER = "parameter"  # vanishes only for a special design, never by moving the arm
    OTHER = "other"


class Relation(Enum):
    """A geometric fact between joint axes and points."""

    PARALLEL_AXES = "parallel axes"  # two joint axes parallel (or collinear)
    ON_FIRST_AXIS = "on the first axis"  # a landmark on the axis of joint 1
    IN_SHOULDER_PLANE = "in the shoulder plane"  # ... in the plane through axis 1 parallel to axis 2
    IN_PLANE_OF_AXES = "in the plane of two parallel axes"  # a third line in the plane of two parallel axes


@dataclass(frozen=True)
class Landmark:
    """A point or line a finding is about: the reference point, the origin of a frame, or a joint's axis."""

    kind: Literal["reference point", "frame origin", "joint axis"]
    index: int | None = None  # the frame (origin) or the 0-based joint (axis)


@dataclass(frozen=True)
class Finding:
    """One geometric fact at a configuration.

    ``joints`` are 0-based; ``kind`` is the singularity the fact indicates, ``None`` for two axes parallel outside
    the wrist (which explains nothing by itself); ``collinear`` tells parallel axes that share a line.
    """

    relation: Relation
    joints: tuple[int, ...]
    kind: SingularityKind | None
    landmark: Landmark | None = None
    collinear: bool = False

    @property
    def key(self) -> tuple[Relation, tuple[int, ...], Landmark | None]:
        """What makes two findings the same fact (parallel axes that become collinear are not a new fact)."""
        return self.relation, self.joints, self.landmark


@dataclass(frozen=True)
class Cause:
    """Why a factor is singular: its kind and the evidence (new findings, or the wrist joints it depends on)."""

    kind: SingularityKind
    findings: tuple[Finding, ...] = ()
    wrist_joints: tuple[int, ...] = ()


@dataclass(frozen=True)
class FrameAxis:
    """Axis ``axis`` (0, 1, 2 for x, y, z) of frame ``frame``."""

    frame: Frame
    axis: int


@dataclass(frozen=True)
class Geometry:
    """Joint axes (point, unit direction) and reference points in frame {0}, numerically at one configuration.

    ``points`` holds the reference point first, then the origins of the later joints' axis frames (a wrist centre).
    """

    axes: tuple[tuple[np.ndarray, np.ndarray], ...]
    points: tuple[tuple[Landmark, np.ndarray], ...]


def geometry_at(robot: Robot | Chain, q: Sequence[float], point: tuple[sp.Expr, ...]) -> Geometry:
    r"""Joint axes :math:`(o_i, z_i)` and reference points in frame {0} at ``q`` (parameters at their defaults).

    The reference point is :math:`{}^0p = {}^0_nR\,{}^np + {}^0p_n`.
    """
    chain = as_chain(robot)
    model = chain.robot
    axes = []
    for joint in model.joints:
        T = numeric_at(chain, chain.transform(0, chain.axis_frame(joint.index)), q)
        axes.append((T[:3, 3], T[:3, 2]))
    T_n = numeric_at(chain, chain.transform(0, chain.n_joints), q)
    P = T_n[:3, :3] @ np.array([float(sp.sympify(c).xreplace(model.defaults)) for c in point]) + T_n[:3, 3]
    points: list[tuple[Landmark, np.ndarray]] = [(Landmark("reference point"), P)]
    for joint in model.joints[2:]:
        origin = axes[joint.index - 1][0]
        if all(np.linalg.norm(origin - p) > 1e-9 for _, p in points):
            points.append((Landmark("frame origin", chain.axis_frame(joint.index)), origin))
    return Geometry(tuple(axes), tuple(points))


def parallel(u: np.ndarray, v: np.ndarray, tol: float = 1e-7) -> bool:
    r"""Whether two unit vectors are parallel or anti-parallel: :math:`\lVert u \times v \rVert < \mathrm{tol}`."""
    return bool(np.linalg.norm(np.cross(u, v)) < tol)


def _distance_to_line(p: np.ndarray, origin: np.ndarray, direction: np.ndarray) -> float:
    return float(np.linalg.norm(np.cross(p - origin, direction)))


def _coplanar(first: np.ndarray, second: np.ndarray, third: np.ndarray, direction: np.ndarray) -> bool:
    """Whether three lines with a common ``direction`` through the given points lie in one plane."""
    normal = np.cross(direction, second - first)
    return abs(float(np.dot(third - first, normal))) < 1e-7 * max(1.0, float(np.linalg.norm(normal)))


def _wrist(robot: Robot) -> set[int]:
    return set(range(robot.n_joints - 3, robot.n_joints)) if robot.n_joints >= 5 else set()


def findings(robot: Robot | Chain, geometry: Geometry) -> tuple[Finding, ...]:
    """Geometric facts at one configuration, in a fixed order (parallel axes, shoulder, elbow).

    Kinds: ``wrist`` (two of the last three axes parallel), ``shoulder`` (a point on the first axis, or in the plane
    through it parallel to the second), ``elbow`` (three parallel lines, two of them joint axes, in one plane: the
    arm stretched out or folded back), ``None`` (any other two axes parallel).
    """
    model = as_chain(robot).robot
    facts: dict[tuple[object, ...], Finding] = {}
    revolute = [i for i, joint in enumerate(model.joints) if joint.is_revolute]
    wrist = _wrist(model)
    axes = geometry.axes
    for i, j in combinations(revolute, 2):
        (oi, zi), (oj, zj) = axes[i], axes[j]
        if parallel(zi, zj):
            finding = Finding(Relation.PARALLEL_AXES, (i, j), SingularityKind.WRIST if {i, j} <= wrist else None,
                              collinear=_distance_to_line(oj, oi, zi) < 1e-7)
            facts[finding.key] = finding
    if revolute and revolute[0] == 0:
        o1, z1 = axes[0]
        normal = np.cross(z1, axes[1][1]) if model.n_joints > 1 else np.zeros(3)
        for landmark, p in geometry.points:
            if _distance_to_line(p, o1, z1) < 1e-7:
                finding = Finding(Relation.ON_FIRST_AXIS, (0,), SingularityKind.SHOULDER, landmark)
            elif np.linalg.norm(normal) > 1e-7 and abs(float(np.dot(p - o1, normal))) < 1e-7 * np.linalg.norm(normal):
                finding = Finding(Relation.IN_SHOULDER_PLANE, (0, 1), SingularityKind.SHOULDER, landmark)
            else:
                continue
            facts[finding.key] = finding
    for i, j in combinations(revolute, 2):
        (oi, zi), (oj, zj) = axes[i], axes[j]
        if not parallel(zi, zj) or _distance_to_line(oj, oi, zi) < 1e-7:
            continue
        thirds = [(Landmark("joint axis", k), axes[k][0]) for k in revolute
                  if k > j and parallel(axes[k][1], zi)] + list(geometry.points)
        for landmark, p in thirds:
            if min(_distance_to_line(p, oi, zi), _distance_to_line(p, oj, zi)) < 1e-7:
                continue
            if _coplanar(oi, oj, p, zi):
                finding = Finding(Relation.IN_PLANE_OF_AXES, (i, j), SingularityKind.ELBOW, landmark)
                facts[finding.key] = finding
                break
    return tuple(facts.values())


def concurrent_groups(geometry: Geometry, joints: Sequence[int]) -> tuple[tuple[int, ...], ...]:
    """Groups of three or more of ``joints`` (0-based) whose axes pass through one point, such as a spherical wrist.

    Two axes meet where the distance between their lines vanishes (and they are not parallel); the axes through
    that point form a group. Groups are listed once, in joint order.
    """
    groups: dict[tuple[int, ...], None] = {}
    for i, j in combinations(joints, 2):
        (oi, zi), (oj, zj) = geometry.axes[i], geometry.axes[j]
        normal = np.cross(zi, zj)
        if np.linalg.norm(normal) < 1e-7 or abs(float(np.dot(oj - oi, normal))) > 1e-7 * np.linalg.norm(normal):
            continue
        # the meeting point: oi + t zi closest to the line of j
        t = float(np.dot(np.cross(oj - oi, zj), normal) / np.dot(normal, normal))
        point = oi + t * zi
        group = tuple(k for k in joints if _distance_to_line(point, *geometry.axes[k]) < 1e-7)
        if len(group) >= 3:
            groups[group] = None
    return tuple(g for g in groups if not any(set(g) < set(other) for other in groups))


def classify(new: Sequence[Finding], factor_joints: set[int], robot: Robot | Chain) -> Cause:
    """Kind and evidence from the findings that hold on the singular set but not at a generic configuration.

    The first wrist, shoulder or elbow finding decides; failing one, a factor in the wrist joints alone is a wrist
    singularity; anything else is ``other``, with whatever new findings there are.
    """
    for kind in (SingularityKind.WRIST, SingularityKind.SHOULDER, SingularityKind.ELBOW):
        evidence = [finding for finding in new if finding.kind == kind]
        if evidence:
            return Cause(kind, (evidence[0],))
    wrist = _wrist(as_chain(robot).robot)
    if wrist and factor_joints and factor_joints <= wrist:
        return Cause(SingularityKind.WRIST, wrist_joints=tuple(sorted(factor_joints)))
    return Cause(SingularityKind.OTHER, tuple(new))


def frame_axes(robot: Robot | Chain, q: Sequence[float], frame: Frame) -> dict[FrameAxis, np.ndarray]:
    """Unit axes of every frame, expressed in ``frame`` (columns of :math:`{}^{frame}_kR`), analysis frame first."""
    chain = as_chain(robot)
    model = chain.robot
    position = chain.position(frame)
    order = [position] + [k for k in range(-1, chain.n_joints + 2) if k != position]
    named: dict[FrameAxis, np.ndarray] = {}
    for k in order:
        name = chain.frame_name(k)
        if (name == "world" and model.base is None) or (name == "tool" and model.tool is None):
            continue
        R = numeric_at(chain, chain.rotation(frame, name), q)
        for axis in range(3):
            named[FrameAxis(name, axis)] = R[:, axis]
    return named


def named_axis(unit: np.ndarray, axes: dict[FrameAxis, np.ndarray]) -> FrameAxis | None:
    r"""The first frame axis ``unit`` lies along (either sense, :math:`|u \cdot a| = 1`), ``None`` if there is none."""
    return next((name for name, a in axes.items() if abs(abs(float(np.dot(unit, a))) - 1) < 1e-7), None)
