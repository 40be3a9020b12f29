r"""What the closed-form executor says about a pose, in the arm's words: why it is out of reach, where solutions merge.

- **Unreachable** (:func:`unreachable_note`): the first step no branch gets past says which point of the arm cannot be
  placed and how far out it is, by the kind of step (:attr:`~symjac.analysis.inverse_kinematics.plan.Step.reach`):
  an elbow (a rotation to a distance) places its subject between the folded and the stretched arm, so the subject is
  beyond the stretched arm or closer in than the folded one; an offset keeps the subject away from an axis (the
  PUMA's shoulder offset: the wrist centre at least ``d3`` from axis 1) or from the shoulder (a slide that passes
  by it); any other step has the target out of that joint's range.
- **Merged** (:func:`merged_note`): where a step's two solutions coincide (the stretched or folded elbow, the wrist
  centre on the offset cylinder, the wrist at ``q5 = 0``) the one solution says which names it stands for.
- **Continuum** (:func:`continuum_note`): where a step's joint takes every value, the joints solved after it
  follow it; when they all turn about axes parallel to it at that pose, the orientation about that direction is
  their signed sum, which stays fixed: ``theta2 + theta3 + theta4 + theta6`` on the UR5 with ``theta5 = 0``,
  ``theta4 + theta6`` on the PUMA's wrist (axes 4 and 6 in line).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import sympy

from symjac.analysis.inverse_kinematics.geometry import exponential
from symjac.analysis.inverse_kinematics.plan import Step

__all__ = ["continuum_note", "merged_note", "motion", "unreachable_note"]


def _arrays(arguments: dict[str, Any]) -> dict[str, Any]:
    return {name: np.array(value, dtype=float) if isinstance(value, tuple) else value
            for name, value in arguments.items()}


def _point(a: dict[str, Any], name: str) -> np.ndarray:
    value = a.get(name)
    return np.zeros(3) if value is None else np.asarray(value, dtype=float)


def _across(k: np.ndarray, x: np.ndarray) -> np.ndarray:
    return x - k * float(k @ x)


def _joints(step: Step) -> str:
    return "joint " + " and ".join(str(j + 1) for j in step.joints) if len(step.joints) == 1 else \
        "joints " + " and ".join(str(j + 1) for j in step.joints)


def _stretch(a: dict[str, Any]) -> tuple[float, float, float]:
    """For a rotation to a distance: (beyond the stretched arm, closer in than the folded arm, the cosine c)."""
    k, r = a["k"], _point(a, "point_on_axis")
    u, v = a["p"] - r, a["q"] - r
    along = float(k @ (u - v))
    ru, rv = (float(np.linalg.norm(_across(k, x))) for x in (u, v))
    squared = a["delta"] ** 2 - along**2
    if squared < 0:
        return 0.0, abs(along) - a["delta"], 2.0
    across = math.sqrt(squared)
    cosine = (ru**2 + rv**2 - squared) / max(2.0 * ru * rv, 1e-300)
    return max(across - (ru + rv), 0.0), max(abs(ru - rv) - across, 0.0), cosine


def _offset(subproblem: str, a: dict[str, Any]) -> tuple[float, float]:
    """For a step whose offset keeps the subject off a cylinder about its axis: (how far inside, the radius).

    A rotation to a plane ``(rot(k, t) h_b).(w - p_a) = d`` and the rotation to a distance that stands for it
    (:func:`~symjac.analysis.inverse_kinematics.planar.plane_step`: ``p = r + l u``, ``q`` the subject,
    ``delta^2 = l^2 + |q - r|^2 - 2 l d``) both ask ``(rot(k, t) u).x = d`` of the subject ``x`` seen from the axis;
    that needs ``|x'| |u'| >= |d - (k.u)(k.x)|``, a distance ``|d - (k.u)(k.x)| / |u'|`` from the axis at least.
    """
    k, r = a["k"], _point(a, "point_on_axis")
    if subproblem == "rotation_to_plane":
        u, x = a["p"] - r, a["h"]
        d = a["d"] - float(a["h"] @ r)
    else:
        scaled, x = a["p"] - r, a["q"] - r
        length = float(np.linalg.norm(scaled))
        u = scaled / length
        d = (length**2 + float(x @ x) - a["delta"] ** 2) / (2.0 * length)
    size = max(float(np.linalg.norm(_across(k, u))), 1e-300)
    radius = abs(d - float(k @ u) * float(k @ x)) / size
    return max(radius - float(np.linalg.norm(_across(k, x))), 0.0), radius


def _elsewhere(subproblem: str, a: dict[str, Any]) -> float:
    """How far any other failed step's target is from what it reaches (a length)."""
    if subproblem.startswith("slide"):
        u = a["p"] - a["q"]
        across = float(np.linalg.norm(_across(a["k"], u)))
        return across if subproblem == "slide_to_point" else max(across - a["delta"], 0.0)
    if subproblem == "rotation_to_plane":
        return _offset(subproblem, a)[0]
    if subproblem == "rotation_to_distance":
        return max(_stretch(a)[:2])
    r = _point(a, "intersection" if subproblem == "two_rotations_to_point" else "point_on_axis")
    u, v = a["p"] - r, a["q"] - r
    if subproblem == "two_rotations_to_point":  # different radii, or the two circles of reach miss each other
        k1, k2 = a["k1"], a["k2"]
        w = float(k1 @ k2)
        alpha = (k1 @ v - w * (k2 @ u)) / (1.0 - w * w)
        beta = (k2 @ u - w * (k1 @ v)) / (1.0 - w * w)
        middle = float(np.sqrt(max(alpha**2 + beta**2 + 2.0 * alpha * beta * w, 0.0)))
        return max(abs(float(np.linalg.norm(u) - np.linalg.norm(v))), middle - float(np.linalg.norm(u)), 0.0)
    k = a["k"]
    along = float(k @ (u - v))
    ru, rv = (float(np.linalg.norm(_across(k, x))) for x in (u, v))
    return math.hypot(along, ru - rv)


def unreachable_note(step: Step, arguments: dict[str, Any]) -> tuple[float, str]:
    """How far out the target is when ``step`` has no solution, and a sentence saying so in the arm's words.

    ``arguments`` are the step's numeric subproblem arguments at the failing branch. The sentence names the subject
    and the distance once: ``"the wrist centre is 0.1234 beyond the reach of the arm stretched at joint 3"``.
    """
    a = _arrays(arguments)
    subject = step.subject or "the target"
    if step.reach == "elbow" and step.subproblem == "rotation_to_distance":
        far, near, _ = _stretch(a)
        if far >= near:
            return far, f"{subject} is {far:.4g} beyond the reach of the arm stretched at {_joints(step)}"
        return near, f"{subject} is {near:.4g} closer in than the arm folded at {_joints(step)} reaches"
    if step.reach == "offset" and step.subproblem in ("rotation_to_plane", "rotation_to_distance"):
        short, radius = _offset(step.subproblem, a)
        axis = step.joints[0] + 1
        return short, (f"{subject} is {short:.4g} too close to axis {axis}: the arm's offset keeps it at least "
                       f"{radius:.4g} from that axis")
    if step.reach == "offset" and step.subproblem == "slide_to_distance":
        line = float(np.linalg.norm(_across(a["k"], a["p"] - a["q"])))
        short = max(line - a["delta"], 0.0)
        return short, (f"{subject} is {short:.4g} too close to the shoulder: the line of the slide ({_joints(step)}) "
                       f"passes {line:.4g} from it")
    distance = _elsewhere(step.subproblem, a)
    return distance, f"{subject} is {distance:.4g} out of the range of {_joints(step)}"


def merged_note(step: Step, arguments: dict[str, Any]) -> str:
    """The note of a solution where ``step``'s two solutions coincide: which names the one solution stands for."""
    first, second = step.branches
    both = f"{first} and {second} coincide"
    if step.reach == "elbow" and step.subproblem == "rotation_to_distance":
        return f"elbow {'stretched' if _stretch(_arrays(arguments))[2] < 0 else 'folded'}: {both}"
    if step.reach == "offset" and step.subproblem == "slide_to_distance":
        return f"{step.subject or 'the target'} where the slide passes closest to the shoulder: {both}"
    if step.reach == "offset" and step.subproblem in ("rotation_to_plane", "rotation_to_distance"):
        radius = _offset(step.subproblem, _arrays(arguments))[1]
        where = "on" if radius <= 1e-9 else f"{radius:.4g} from"
        return f"{step.subject or 'the target'} {where} axis {step.joints[0] + 1}, as close as it comes: {both}"
    return both


def continuum_note(variables: Sequence[str], lines: Sequence[tuple[np.ndarray, np.ndarray]], revolute: Sequence[bool],
                   q: np.ndarray, joint: int, later: Sequence[int]) -> str:
    """What stays fixed when ``joint`` takes every value at ``q`` and the joints ``later`` (solved after it) follow.

    ``lines`` are every joint's axis at ``q`` (direction, point). With twists at ``q``, ``T(q + dq) T(q)^-1`` is the
    product of ``exp(xi_j dq_j)`` over the joints that move: a joint on the free joint's line undoes it exactly (their
    signed sum is fixed); else when each later joint is revolute about an axis parallel to the free one, the
    rotation about that direction is their signed sum, which the target fixes (the earlier joints do not move).
    """
    h, p = lines[joint]
    for other, (g, r) in enumerate(lines):  # a joint on the same line undoes it exactly
        if other != joint and revolute[other] and np.linalg.norm(np.cross(h, g)) < 1e-6 \
                and np.linalg.norm(np.cross(r - p, h)) < 1e-6:
            sign = 1.0 if h @ g > 0 else -1.0
            fixed = math.remainder(q[joint] + sign * q[other], 2 * math.pi)
            return (f"{variables[joint]} {'+' if sign > 0 else '-'} {variables[other]} = {fixed:.6g} is fixed; "
                    f"{variables[joint]} shown at 0")
    follow = [j for j in later if j != joint]
    if follow and all(revolute[j] and np.linalg.norm(np.cross(h, lines[j][0])) < 1e-6 for j in follow):
        terms = sorted([joint, *follow])
        signs = {j: 1.0 if h @ lines[j][0] > 0 else -1.0 for j in terms}
        lead = signs[terms[0]]
        fixed = math.remainder(sum(lead * signs[j] * q[j] for j in terms), 2 * math.pi)
        text = variables[terms[0]] + "".join(f" {'+' if lead * signs[j] > 0 else '-'} {variables[j]}"
                                             for j in terms[1:])
        moved = "" if len(follow) < 2 else (f" ({', '.join(variables[j] for j in sorted(follow))} change with "
                                             f"{variables[joint]})")
        return f"{text} = {fixed:.6g} is fixed; {variables[joint]} shown at 0{moved}"
    if follow:
        return (f"{variables[joint]} takes every value; shown at 0 (the joints solved after it, "
                f"{', '.join(variables[j] for j in follow)}, follow it)")
    return f"{variables[joint]} takes every value; shown at 0"


@functools.lru_cache(maxsize=256)
def _motion_symbolic(kind: str) -> Callable[..., Any]:
    h, p = sympy.Matrix(sympy.symbols("h1:4")), sympy.Matrix(sympy.symbols("p1:4"))
    value = sympy.Symbol("value")
    return sympy.lambdify([*h, *p, value], exponential(h, p, kind, value), modules="numpy")


def motion(h: np.ndarray, p: np.ndarray, kind: str, value: float) -> np.ndarray:
    """The 4 x 4 motion of a joint of ``kind`` about (along) the unit axis ``h`` through ``p`` by ``value``."""
    return np.asarray(_motion_symbolic(kind)(*h, *p, value), dtype=float)
