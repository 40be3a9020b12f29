r"""Closed-form plan for 6-joint arms whose joints 2, 3 and 4 have parallel axes (the Universal Robots family).

With the target pose ``(R, p)``, the home pose ``(R_M, p_M)`` and the joint axes ``h_i`` through ``p_i`` at home
(:class:`~symjac.analysis.inverse_kinematics.geometry.ArmGeometry`), the forward kinematics is the product of
exponentials ``T(q) = e1 e2 ... e6 M``. Rotations about the parallel axes 2, 3, 4 keep every component along their
direction ``h2``; that one fact gives the whole decomposition:

1. **Wrist point.** Axes 5 and 6 meet at ``c``; joints 5 and 6 do not move it, so the target puts it at
   ``w = R R_M^T (c - p_M) + p``.
2. **theta1** (shoulder): ``w`` seen from link 1 keeps its component along ``h2``:
   ``(rot(h1, theta1) h2).(w - p1) = h2.(c - p1) = d``, solved as a rotation to a distance (the point
   ``p1 + 2 d h2`` turned about axis 1 lies at ``|w - p1|`` from ``w``); two solutions, shoulder right and left.
3. **theta5** (wrist): ``R1^T R R_M^T = R234 R5 R6`` and ``R234 h2 = h2`` give
   ``|rot(h5, theta5) h6 - h2| = |R1^T R R_M^T h6 - h2|``, a rotation to a distance; two solutions, wrist down and up.
4. **theta6**: ``rot(h6, theta6) (R_M R^T R1 h2) = rot(h5, -theta5) h2``, a rotation to a point.
5. **theta3** (elbow): axes 4 and 5 meet at ``b``; the target puts it at ``b_w = w + R R_M^T rot(h6, -theta6)
   (b - c)``, and seen from link 1, ``b1 = rot(h1, -theta1)(b_w - p1) + p1``; ``theta3`` turns ``b`` about axis 3 to the
   distance ``|b1 - p2|`` from axis 2, a rotation to a distance; two solutions, elbow down and up with shoulder right,
   up and down with shoulder left (the step's ``swapped_by``): turning the shoulder over turns the arm over, and "elbow
   up" is the elbow above the line from shoulder to wrist (checked by height in tests/test_ik_branch_names.py).
6. **theta2**: turns ``rot(h3, theta3) b`` onto ``b1`` about axis 2, a rotation to a point.
7. **theta4**: ``rot(h4, theta4) h5 = R3^T R2^T R1^T R R_M^T rot(h6, -theta6) h5``, a rotation to a point.

Eight solutions in general. At the wrist singularity (``h6`` turned along ``h2``, theta5 = 0 on the UR5) step 4 has
every angle (theta6 shown at 0 and theta2 + theta3 + theta4 takes the rest); at the shoulder singularity (``w`` at
distance ``|d|`` from the plane through axis 1 and along ``h2``, on the UR5 ``w`` above the base at the offset) the two
theta1 merge.
"""

from __future__ import annotations

import sympy

from symjac.analysis.inverse_kinematics.geometry import ArmGeometry
from symjac.analysis.inverse_kinematics.plan import Plan, Step, pose_matrix
from symjac.analysis.inverse_kinematics.planar import (
    DISTANCE_RULE,
    ELBOW,
    SHOULDER,
    length,
    plane_step,
    rotation,
    turned,
)

__all__ = ["WRIST", "three_parallel_axes_plan"]

WRIST = ("wrist down", "wrist up")
_WRIST_POINT = sympy.symbols("w_x w_y w_z", real=True)
_ORIGIN = sympy.zeros(3, 1)


def _expand(m: sympy.Matrix) -> sympy.Matrix:
    return m.applyfunc(sympy.expand)


def _conditions(geometry: ArmGeometry) -> tuple[sympy.Matrix, sympy.Matrix] | None:
    """The points ``c`` (axes 5, 6 meet) and ``b`` (axes 4, 5 meet) when the arm is of the family, else None."""
    if geometry.free_joint is not None or len(geometry.kinds) != 6 or any(k != "revolute" for k in geometry.kinds):
        return None
    if geometry.robot.coupling is not None:
        return None
    if not (geometry.parallel(1, 2) and geometry.parallel(2, 3)) or geometry.parallel(0, 1):
        return None
    if geometry.parallel(3, 4) or geometry.parallel(4, 5):
        return None
    c, b = geometry.intersection(4, 5), geometry.intersection(3, 4)
    if c is None or b is None:
        return None
    if all(sympy.simplify(e) == 0 for e in (b - geometry.points[2]).cross(geometry.axes[2])):
        return None  # the wrist point on the elbow axis: the distance step has nothing to measure
    return c, b


def three_parallel_axes_plan(geometry: ArmGeometry) -> Plan | None:
    """The plan of a 6R arm with joints 2, 3, 4 parallel and axes 4-5 and 5-6 meeting, or None for other arms.

    Parameters
    ----------
    geometry : ArmGeometry
        The arm's axes at home (exact).

    Returns
    -------
    Plan or None
        Family ``"three parallel axes"``, six steps (the module docstring), 8 solutions at most.
    """
    found = _conditions(geometry)
    if found is None:
        return None
    c, b = found
    h, points, robot = geometry.axes, geometry.points, geometry.robot
    t1, t2, t3, t4, t5, t6 = robot.joint_variables
    pose = pose_matrix()
    r, p = pose[:3, :3], pose[:3, 3]
    r_m, p_m = geometry.home[:3, :3], geometry.home[:3, 3]
    w = sympy.Matrix(_WRIST_POINT)
    definitions = tuple(zip(_WRIST_POINT, _expand(r * r_m.T * (c - p_m) + p), strict=True))
    offset = sympy.simplify(h[1].dot(c - points[0]))
    shoulder = plane_step(0, geometry, h[1], w, offset, "the direction of the parallel axes about axis 1",
                          "the wrist point (where axes 5 and 6 meet)")
    r1 = rotation(h[0], t1)
    seen = r1.T * r * r_m.T  # R234 R5 R6
    wrist = Step(
        (4,),
        "rotation_to_distance",
        {"k": h[4], "p": h[5], "q": h[1], "delta": length(_expand(seen * h[5] - h[1])), "point_on_axis": _ORIGIN},
        f"{t5} tilts the direction of axis 6 to the distance from the parallel axes' direction that the target "
        f"rotation seen from link 1 gives it, a rotation to a distance ({DISTANCE_RULE}: {WRIST[0]}, then "
        f"{WRIST[1]})",
        WRIST,
        subject="the direction of axis 6",
    )
    roll = Step(
        (5,),
        "rotation_to_point",
        {"k": h[5], "p": _expand(seen.T * h[1]), "q": _expand(rotation(h[4], -t5) * h[1]), "point_on_axis": _ORIGIN},
        f"{t6} turns the parallel axes' direction, seen from the tool, onto where joint 5 leaves it, a rotation to a "
        "point",
        subject="the tool's orientation",
    )
    r6_back = rotation(h[5], -t6)
    b_w = w + r * r_m.T * r6_back * (b - c)
    b1 = _expand(turned(h[0], points[0], -t1, b_w))
    elbow = Step(
        (2,),
        "rotation_to_distance",
        {"k": h[2], "p": b, "q": points[1], "delta": length(b1 - points[1]), "point_on_axis": points[2]},
        f"{t3} bends the elbow until the point where axes 4 and 5 meet is as far from axis 2 as the target puts it, "
        f"a rotation to a distance ({DISTANCE_RULE}: {ELBOW[0]}, then {ELBOW[1]}; swapped with {SHOULDER[1]})",
        ELBOW,
        swapped_by=0,
        subject="the point where axes 4 and 5 meet",
        reach="elbow",
    )
    lift = Step(
        (1,),
        "rotation_to_point",
        {"k": h[1], "p": _expand(turned(h[2], points[2], t3, b)), "q": b1, "point_on_axis": points[1]},
        f"{t2} swings that point onto its target about axis 2, a rotation to a point",
        subject="the point where axes 4 and 5 meet",
    )
    r23 = rotation(h[2], -t3) * rotation(h[1], -t2)
    last = Step(
        (3,),
        "rotation_to_point",
        {"k": h[3], "p": h[4], "q": _expand(r23 * seen * r6_back * h[4]), "point_on_axis": _ORIGIN},
        f"{t4} turns the direction of axis 5 to where the rest of the target rotation puts it, a rotation to a point",
        subject="the tool's orientation",
    )
    reasons = (
        "the axes of joints 2, 3 and 4 are parallel",
        "the axes of joints 5 and 6 meet, and so do the axes of joints 4 and 5",
    )
    return Plan(
        robot,
        "three parallel axes",
        reasons,
        definitions,
        (shoulder, wrist, roll, elbow, lift, last),
        "the whole pose",
    )
