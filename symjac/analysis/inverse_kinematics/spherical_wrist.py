r"""Arms whose last three axes meet at one point, the wrist centre (Pieper's case): position first, then orientation.

With joints ``a, b, c`` for the position and ``4, 5, 6`` for the wrist (named by the arm's own joint numbers), the
wrist rotations leave the wrist centre ``c0`` (their common point at home) where it is, so

.. math:: e^{[\xi_a] q_a} e^{[\xi_b] q_b} e^{[\xi_c] q_c} c_0 = w = R\, c_t + p,
   \qquad c_t = R_M^T (c_0 - p_M),

the wrist centre of the target pose ``(R, p)`` (``M`` the home tool pose). The position joints then follow by
subproblems, in one of three ways:

- **axes b and c parallel** (PUMA, IRB, KR, Fanuc): rotations about them keep the component along ``h_b``, so
  ``(rot(h_a, q_a) h_b).(w - p_a) = h_b.(c_0 - p_a)`` gives ``q_a`` (rotation to a plane, two solutions); the distance
  from the point ``p_b`` on axis b, ``|e^{[\xi_c] q_c} c_0 - p_b| = |w - e^{[\xi_a] q_a} p_b|``, gives ``q_c``
  (rotation to a distance, two solutions); then ``q_b`` (rotation to a point);
- **axes a and b meet** at ``o``: ``|e^{[\xi_c] q_c} c_0 - o| = |w - o|`` gives ``q_c`` (rotation to a distance, or a
  slide to a distance when joint c is prismatic, as in the Stanford arm), then ``(q_a, q_b)`` by two rotations to a
  point about ``o``.

The wrist turns ``R_w = (R_a R_b R_c)^T R R_M^T = R_4 R_5 R_6``: ``R_4 R_5 h_6 = R_w h_6`` gives ``(q_4, q_5)`` (two
rotations to a point, two solutions) and ``R_6 v = R_5^T R_4^T R_w v`` for a ``v`` across ``h_6`` gives ``q_6``.
Eight solutions in general.

Branch names follow fixed geometric rules, each a choice of sign in a subproblem. Shoulder: with axes b and c
parallel, "shoulder right" is the solution where the wrist centre lies on the positive side of h_a x h_b (h_b turned
by q_a); where axes a and b meet, "shoulder right" is the middle point on the positive side of h_a x h_b. Elbow:
with axes b and c parallel, "elbow up" is the solution with the elbow above the line from shoulder to wrist centre
while the wrist lies on the side of the vertical the shoulder faces (as in Fu, Gonzalez and Lee's ELBOW indicator,
taken relative to the shoulder's): seen along the elbow axis h_c, the wrist centre at a positive angle from the shoulder
point (theta_0 + atan2(sqrt(D), N)) with shoulder right and at a negative one with shoulder left, because turning the
shoulder over turns the whole arm over and the same bend then puts the elbow below the line (the step's
``swapped_by``; tests/test_ik_branch_names.py checks it by the elbow's height on the PUMA 560 and the IRB 140). Where
axes a and b meet, the elbow step comes first and "elbow up" is the negative angle, by the bend alone. A prismatic
joint c has "slide reversed" and "slide out": the wrist centre before or beyond (along the slide's direction) the
point where the slide's line passes closest to the shoulder, which on the Stanford arm is the sign of d_3 (its
line passes closest at d_3 = 0), one solution "slide out" where they coincide. Wrist: "no flip" is the solution
with q_5 >= 0 when axes 4 and 6 are parallel at home (the home posture of these arms), else "wrist flip" is the
middle point on the positive side of h_4 x h_5; where the two coincide (q_5 = 0, or the middle point on the line)
the one solution is "no flip".
"""

from __future__ import annotations

import sympy

from symjac.analysis.inverse_kinematics.geometry import ArmGeometry
from symjac.analysis.inverse_kinematics.plan import Plan, Step, pose_matrix
from symjac.analysis.inverse_kinematics.planar import SLIDE, SLIDE_RULE

__all__ = ["WRIST_CENTRE", "spherical_wrist_plan"]

WRIST_CENTRE: tuple[sympy.Symbol, ...] = sympy.symbols("w_x w_y w_z", real=True)
"""The symbols of the target's wrist centre in a spherical-wrist plan's definitions (none when the tool point is the
wrist centre: the position ``px, py, pz`` is then used as it is)."""


def _s(matrix: sympy.Matrix) -> sympy.Matrix:
    return matrix.applyfunc(lambda e: sympy.simplify(sympy.expand(e)))


def _on_line(point: sympy.Matrix, axis: sympy.Matrix, through: sympy.Matrix) -> bool:
    """Whether ``point`` lies on the line through ``through`` along ``axis``, as an identity."""
    return all(sympy.simplify(sympy.expand(e)) == 0 for e in (point - through).cross(axis))


def _rotation(geometry: ArmGeometry, joint: int) -> sympy.Matrix:
    return geometry.motion(joint)


def spherical_wrist_plan(geometry: ArmGeometry) -> Plan | None:
    """The plan for a 6-joint arm (or the 6 joints left of a 7-joint arm) whose last three axes meet; else None."""
    joints = geometry.joints
    if len(joints) != 6 or any(geometry.kind(j) != "revolute" for j in (*joints[:2], *joints[3:])):
        return None
    a, b, c, j4, j5, j6 = joints
    centre = geometry.intersection(j4, j5, j6)
    if centre is None or geometry.parallel(j4, j5) or geometry.parallel(j5, j6):
        return None
    number = [j + 1 for j in joints]
    reasons = [f"the axes of joints {number[3]}, {number[4]} and {number[5]} meet at the wrist centre "
               f"({', '.join(str(e) for e in centre)} at home)"]
    if geometry.free_joint is not None:
        reasons.append(f"joint {geometry.free_joint} is given: its value is the redundancy parameter")
    home = geometry.home
    pose = pose_matrix()
    rotation, position = pose[:3, :3], pose[:3, 3]
    centre_in_tool = _s(home[:3, :3].T * (centre - home[:3, 3]))
    definitions: tuple[tuple[sympy.Symbol, sympy.Expr], ...] = ()
    if centre_in_tool == sympy.zeros(3, 1):  # the tool point is the wrist centre (the PUMA's flange): w = p
        w = sympy.Matrix(position)
    else:
        w = sympy.Matrix(WRIST_CENTRE)
        definitions = tuple(zip(WRIST_CENTRE, _s(rotation * centre_in_tool + position), strict=True))
    position_steps = _position(geometry, a, b, c, centre, w, reasons)
    if position_steps is None:
        return None
    steps = [*position_steps, *_orientation(geometry, (a, b, c, j4, j5, j6), rotation)]
    return Plan(geometry.robot, "spherical wrist", tuple(reasons), definitions, tuple(steps),
                free_joint=geometry.free_joint)


def _position(geometry: ArmGeometry, a: int, b: int, c: int, centre: sympy.Matrix, w: sympy.Matrix,
              reasons: list[str]) -> list[Step] | None:
    h_a, h_b, h_c = geometry.axis(a), geometry.axis(b), geometry.axis(c)
    p_a, p_b, p_c = geometry.point(a), geometry.point(b), geometry.point(c)
    name = geometry.robot.joint_variables
    shoulder = ("shoulder right", "shoulder left")
    if geometry.kind(c) == "revolute" and _on_line(centre, h_c, p_c):
        return None  # joint c does not move the wrist centre: the position joints cannot reach around it
    if geometry.kind(c) == "revolute" and geometry.parallel(b, c) and not geometry.parallel(a, b) \
            and not _on_line(p_b, h_c, p_c):
        reasons.append(f"the axes of joints {b + 1} and {c + 1} are parallel")
        turn_a = _rotation(geometry, a)
        back = _s(turn_a[:3, :3].T * (w - p_a) + p_a)  # the wrist centre with joint a undone
        elbow_at = _s(turn_a[:3, :3] * (p_b - p_a) + p_a)
        wrist_at = _s(_rotation(geometry, c)[:3, :3] * (centre - p_c) + p_c)
        return [
            Step((a,), "rotation_to_plane", {"k": h_a, "p": h_b, "h": w - p_a, "d": _s(h_b.T * (centre - p_a))[0]},
                 f"{name[a]}: joints {b + 1} and {c + 1} keep the wrist centre's component along their common axis, "
                 f"so turning that axis about axis {a + 1} must give it the target's (rotation to a plane); shoulder "
                 f"right: the wrist centre on the positive side of h{a + 1} x h{b + 1}",
                 shoulder, subject="the wrist centre", reach="offset"),
            Step((c,), "rotation_to_distance", {"k": h_c, "p": centre, "q": p_b, "point_on_axis": p_c,
                                                "delta": sympy.sqrt((w - elbow_at).dot(w - elbow_at))},
                 f"{name[c]}: joint {c + 1} sets the wrist centre's distance from axis {b + 1}'s point, which must "
                 f"equal the target's (rotation to a distance); elbow up: seen along axis {c + 1}, the wrist centre at "
                 f"a negative angle from that point with shoulder left, a positive one with shoulder right",
                 ("elbow down", "elbow up"), swapped_by=0, subject="the wrist centre", reach="elbow"),
            Step((b,), "rotation_to_point", {"k": h_b, "p": wrist_at, "q": back, "point_on_axis": p_b},
                 f"{name[b]}: joint {b + 1} turns the wrist centre onto the target's, joint {a + 1} undone "
                 f"(rotation to a point)", subject="the wrist centre"),
        ]
    meet = geometry.intersection(a, b)
    if meet is None or (geometry.kind(c) == "revolute" and _on_line(meet, h_c, p_c)):
        return None  # axis c through the meeting point: joint c cannot change the wrist centre's distance from it
    reasons.append(f"the axes of joints {a + 1} and {b + 1} meet at ({', '.join(str(e) for e in meet)})")
    delta = sympy.sqrt((w - meet).dot(w - meet))
    if geometry.kind(c) == "prismatic":
        reasons.append(f"joint {c + 1} is prismatic")
        first = Step((c,), "slide_to_distance", {"k": h_c, "p": centre, "q": meet, "delta": delta},
                     f"{name[c]}: the slide sets the wrist centre's distance from the point where axes {a + 1} and "
                     f"{b + 1} meet, which must equal the target's (slide to a distance); {SLIDE_RULE}",
                     SLIDE, merged=1, subject="the wrist centre", reach="offset")
        moved = _s(centre + h_c * name[c])
    else:
        first = Step((c,), "rotation_to_distance", {"k": h_c, "p": centre, "q": meet, "point_on_axis": p_c,
                                                    "delta": delta},
                     f"{name[c]}: joint {c + 1} sets the wrist centre's distance from the point where axes {a + 1} "
                     f"and {b + 1} meet, which must equal the target's (rotation to a distance); elbow up: seen along "
                     f"axis {c + 1}, the wrist centre at a negative angle from that point",
                     ("elbow up", "elbow down"), subject="the wrist centre", reach="elbow")
        moved = _s(_rotation(geometry, c)[:3, :3] * (centre - p_c) + p_c)
    second = Step((a, b), "two_rotations_to_point", {"k1": h_a, "k2": h_b, "p": moved, "q": w, "intersection": meet},
                  f"{name[a]}, {name[b]}: joints {a + 1} and {b + 1} turn the wrist centre onto the target's about "
                  f"the point where their axes meet (two rotations to a point); shoulder right: the middle point on "
                  f"the positive side of h{a + 1} x h{b + 1}", shoulder, subject="the wrist centre")
    return [first, second]


def _orientation(geometry: ArmGeometry, joints: tuple[int, ...], rotation: sympy.Matrix) -> list[Step]:
    a, b, c, j4, j5, j6 = joints
    name = geometry.robot.joint_variables
    arm = sympy.eye(3)
    for joint in (a, b, c):
        arm = arm * _rotation(geometry, joint)[:3, :3]
    wrist = arm.T * rotation * geometry.home[:3, :3].T
    h4, h5, h6 = geometry.axis(j4), geometry.axis(j5), geometry.axis(j6)
    across = _s(h5 - h6 * h6.dot(h5))
    turned = _s(_rotation(geometry, j5)[:3, :3].T * _rotation(geometry, j4)[:3, :3].T)
    alignment = _s(h4.T * h6)[0]
    flip = ("no flip", "wrist flip") if alignment.could_extract_minus_sign() else ("wrist flip", "no flip")
    flip_rule = (f"no flip: {name[j5]} >= 0" if alignment != 0 else
                 f"wrist flip: the middle point on the positive side of h{j4 + 1} x h{j5 + 1}")
    return [
        Step((j4, j5), "two_rotations_to_point", {"k1": h4, "k2": h5, "p": h6, "q": wrist * h6},
             f"{name[j4]}, {name[j5]}: joints {j4 + 1} and {j5 + 1} turn axis {j6 + 1} onto the direction the target "
             f"orientation gives it (two rotations to a point); {flip_rule}", flip, merged=flip.index("no flip"),
             subject=f"the direction of axis {j6 + 1}"),
        Step((j6,), "rotation_to_point", {"k": h6, "p": across, "q": turned * wrist * across},
             f"{name[j6]}: joint {j6 + 1} turns a direction across its axis onto the target's (rotation to a point)",
             subject="the tool's orientation"),
    ]

