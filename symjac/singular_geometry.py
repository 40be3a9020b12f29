r"""Geometry at a configuration, to classify a singularity and to put what it loses into words.

Facts are checked numerically (to 1e-7) at a sample of the singular set and compared with a generic configuration:
only what becomes true there explains the singularity. Two wrist axes aligned is a *wrist* singularity; the point
on the first axis, or in the plane through it parallel to the second, a *shoulder* singularity; three parallel lines
(two of them joint axes) in one plane, the arm stretched out or folded back, an *elbow* singularity.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from itertools import combinations

import numpy as np
import sympy as sp

from symjac.chain import Frame, chain_of
from symjac.model import Robot

__all__ = ["Geometry", "classify", "describe", "findings", "frame_axes", "geometry_at", "parallel"]

_AXIS_NAMES = ("x", "y", "z")


@dataclass
class Geometry:
    """Joint axes (point, unit direction) and reference points in frame {0}, numerically at one configuration.

    ``points`` holds the reference point first, then the origins of the later joints' axis frames (a wrist centre).
    """

    axes: list[tuple[np.ndarray, np.ndarray]]
    points: list[tuple[str, np.ndarray]]


def geometry_at(robot: Robot, q: Sequence[float], point: tuple[sp.Expr, ...]) -> Geometry:
    """Joint axes and reference points in frame {0} at ``q`` (parameters at their defaults)."""
    chain = chain_of(robot)
    values = {**dict(zip(robot.q, q, strict=True)), **robot.defaults}
    axes = []
    for joint in robot.joints:
        T = np.array(chain.transform(0, chain.axis_frame(joint.index)).xreplace(values).evalf(), dtype=float)
        axes.append((T[:3, 3], T[:3, 2]))
    T_n = np.array(chain.transform(0, chain.n).xreplace(values).evalf(), dtype=float)
    P = T_n[:3, :3] @ np.array([float(sp.sympify(c).xreplace(robot.defaults)) for c in point]) + T_n[:3, 3]
    points = [("the reference point", P)]
    for joint in robot.joints[2:]:
        origin = axes[joint.index - 1][0]
        if all(np.linalg.norm(origin - p) > 1e-9 for _, p in points):
            points.append((f"the origin of frame {{{chain.axis_frame(joint.index)}}}", origin))
    return Geometry(axes, points)


def parallel(u: np.ndarray, v: np.ndarray, tol: float = 1e-7) -> bool:
    """Whether two unit vectors are parallel or anti-parallel."""
    return bool(np.linalg.norm(np.cross(u, v)) < tol)


def _distance_to_line(p: np.ndarray, origin: np.ndarray, direction: np.ndarray) -> float:
    return float(np.linalg.norm(np.cross(p - origin, direction)))


def _coplanar(first: np.ndarray, second: np.ndarray, third: np.ndarray, direction: np.ndarray) -> bool:
    """Whether three lines with a common ``direction`` through the given points lie in one plane."""
    normal = np.cross(direction, second - first)
    return abs(float(np.dot(third - first, normal))) < 1e-7 * max(1.0, float(np.linalg.norm(normal)))


def findings(robot: Robot, geometry: Geometry) -> dict[str, tuple[str, str]]:
    """Geometric facts at one configuration, keyed uniquely, each with a category and a sentence.

    Categories: ``wrist`` (two of the last three axes parallel), ``shoulder`` (a point on the first axis, or in the
    plane through it parallel to the second), ``elbow`` (three parallel lines, two of them joint axes, in one plane:
    the arm stretched out or folded back), ``aligned`` (any other two axes parallel).
    """
    facts: dict[str, tuple[str, str]] = {}
    revolute = [i for i, joint in enumerate(robot.joints) if joint.is_revolute]
    wrist = set(range(robot.dof - 3, robot.dof)) if robot.dof >= 5 else set()
    axes = geometry.axes
    for i, j in combinations(revolute, 2):
        (oi, zi), (oj, zj) = axes[i], axes[j]
        if parallel(zi, zj):
            shape = "collinear" if _distance_to_line(oj, oi, zi) < 1e-7 else "parallel"
            facts[f"parallel {i} {j}"] = ("wrist" if {i, j} <= wrist else "aligned",
                                          f"the axes of joints {i + 1} and {j + 1} are {shape}")
    if revolute and revolute[0] == 0:
        o1, z1 = axes[0]
        normal = np.cross(z1, axes[1][1]) if robot.dof > 1 else np.zeros(3)
        for name, p in geometry.points:
            if _distance_to_line(p, o1, z1) < 1e-7:
                facts[f"on axis 1 {name}"] = ("shoulder", f"{name} lies on the axis of joint 1")
            elif np.linalg.norm(normal) > 1e-7 and abs(float(np.dot(p - o1, normal))) < 1e-7 * np.linalg.norm(normal):
                facts[f"shoulder plane {name}"] = (
                    "shoulder", f"{name} lies in the plane through the axis of joint 1 parallel to the axis of joint 2")
    for i, j in combinations(revolute, 2):
        (oi, zi), (oj, zj) = axes[i], axes[j]
        if not parallel(zi, zj) or _distance_to_line(oj, oi, zi) < 1e-7:
            continue
        thirds = [(f"the axis of joint {k + 1}", axes[k][0]) for k in revolute
                  if k > j and parallel(axes[k][1], zi)] + list(geometry.points)
        for name, p in thirds:
            if min(_distance_to_line(p, oi, zi), _distance_to_line(p, oj, zi)) < 1e-7:
                continue
            if _coplanar(oi, oj, p, zi):
                facts[f"plane {i} {j} {name}"] = (
                    "elbow", f"{name} lies in the plane of the parallel axes of joints {i + 1} and {j + 1}")
                break
    return facts


_KIND_REASONS = {
    "wrist": "two wrist rotations do the same thing, so one orientation direction is lost",
    "shoulder": "rotating joint 1 no longer moves it sideways, so a direction is lost inside the workspace",
    "elbow": "the arm is stretched out or folded back, on the boundary of its reach, and cannot move along that line",
}


def classify(new: Mapping[str, tuple[str, str]], factor_joints: set[int], robot: Robot) -> tuple[str, str]:
    """Kind and reasoning from the facts that hold on the singular set but not at a generic configuration."""
    for kind in ("wrist", "shoulder", "elbow"):
        sentences = [text for category, text in new.values() if category == kind]
        if sentences:
            return kind, f"{sentences[0]}: {_KIND_REASONS[kind]}"
    wrist = set(range(robot.dof - 3, robot.dof)) if robot.dof >= 5 else set()
    if wrist and factor_joints and factor_joints <= wrist:
        return "wrist", f"the factor depends only on the wrist joints {_joint_names(factor_joints)}"
    if new:
        return "other", "; ".join(sorted(text for _, text in new.values()))
    return "other", "no aligned axes found; see the lost direction and the self-motion"


def _joint_names(joints: set[int]) -> str:
    return ", ".join(str(j + 1) for j in sorted(joints))


def frame_axes(robot: Robot, q: Sequence[float], frame: Frame) -> dict[str, np.ndarray]:
    """Unit axes of every frame, expressed in ``frame``, keyed by a readable name (analysis frame first)."""
    chain = chain_of(robot)
    values = {**dict(zip(robot.q, q, strict=True)), **robot.defaults}
    position = chain.position(frame)
    order = [position] + [k for k in range(-1, chain.n + 2) if k != position]
    named: dict[str, np.ndarray] = {}
    for k in order:
        name = chain.frame_name(k)
        if (name == "world" and robot.base is None) or (name == "tool" and robot.tool is None):
            continue
        R = np.array(chain.rotation(frame, name).xreplace(values).evalf(), dtype=float)
        label = f"frame {{{name}}}" if isinstance(name, int) else f"the {name} frame"
        for axis in range(3):
            named[f"{_AXIS_NAMES[axis]} of {label}"] = R[:, axis]
    return named


def describe(vector: np.ndarray, rows: tuple[int, ...], axes: dict[str, np.ndarray],
              words: tuple[str, str, str, str]) -> str:
    """A 6-vector restricted to ``rows`` in words: along/about a named axis when it is one, else its components.

    ``words`` = (linear alone, angular alone, angular after a linear part, joiner), e.g. ``("translate",
    "rotate", "rotating", "while")``.
    """
    full = np.zeros(6)
    full[list(rows)] = vector
    named: list[str | None] = []
    for part in (full[:3], full[3:]):
        norm = np.linalg.norm(part)
        if norm < 1e-9:
            named.append(None)
            continue
        unit = part / norm
        name = next((n for n, a in axes.items() if abs(abs(float(np.dot(unit, a))) - 1) < 1e-7), None)
        named.append(name if name is not None else str(np.round(unit, 3).tolist()))
    linear, angular = named
    if linear and angular:
        return f"{words[0]} along {linear} {words[3]} {words[2]} about {angular}"
    if linear:
        return f"{words[0]} along {linear}"
    return f"{words[1]} about {angular}" if angular else "nothing"
