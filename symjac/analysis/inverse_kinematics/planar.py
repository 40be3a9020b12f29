r"""Closed-form plans for arms with fewer than six joints: planar 2R and 3R, SCARA, articulated 3R.

Such an arm controls only part of a pose, and its plan says which part (``Plan.controlled``); the steps read only that
part of the target, so the rest of the pose is ignored. With ``h`` the common direction of parallel axes, the target
point ``p`` is first moved along ``h`` into the plane the arm moves in, ``p~ = p - h (h.(p - t))`` for a point ``t`` of
that plane, and a rotation about ``h`` is read from the part of a turned vector across ``h``.

The steps, all of them geometric subproblems (:mod:`~symjac.analysis.inverse_kinematics.subproblems`):

- **Planar 2R** (two parallel revolute axes, the tool point ``t``): the elbow ``theta2`` turns ``t`` about axis 2 to
  the distance ``|p~ - p1|`` from axis 1 (rotation to a distance; two solutions, elbow down and elbow up), then
  ``theta1`` turns the point there onto ``p~`` (rotation to a point). With the axes along ``z``,
  ``c2 = (x^2 + y^2 - L1^2 - L2^2) / (2 L1 L2)`` and ``theta2 = atan2(+-sqrt(1 - c2^2), c2)``.
- **Planar 3R**: the same for the point ``w`` on axis 3 (the wrist, ``w = p - R R_M^T (t - p3)``), then ``theta3``
  turns a vector ``v`` across ``h`` onto the part across ``h`` of ``R2^T R1^T R R_M^T v``.
- **SCARA** (R R P R, all axes parallel): the planar 2R for the point on axis 4, the slide ``d3 = h3.(w - p4)``,
  then ``theta4`` like the planar 3R's ``theta3``.
- **Articulated 3R** (axis 1 across axes 2 and 3, which are parallel; position only): ``theta1`` puts the target in
  the plane of the arm, ``(rot(h1, theta1) h2).(p - p1) = h2.(t - p1) = d``, as a rotation to a distance: the point
  ``p1 + l h2`` turned about axis 1 lies at ``|p - p1|`` from ``p`` exactly when that holds, for ``l = 2 d``
  (``l = 1`` and the distance ``sqrt(|p - p1|^2 + 1)`` when ``d`` is zero); then ``theta3`` and ``theta2`` as in the
  planar 2R, seen from link 1.

Branches: a rotation to a distance gives ``theta0 - psi`` first and ``theta0 + psi`` second (``theta0`` the folded
angle, ``psi = atan2(sqrt(1 - c^2), c)``); the step's statement names them in that order.
"""

from __future__ import annotations

import sympy

from symjac.analysis.inverse_kinematics.geometry import ArmGeometry
from symjac.analysis.inverse_kinematics.plan import Plan, Step, pose_matrix

__all__ = [
    "across",
    "articulated_plan",
    "cylindrical_plan",
    "length",
    "palletizer_plan",
    "perpendicular",
    "planar_plan",
    "plane_step",
    "rotation",
    "scara_plan",
    "spherical_arm_plan",
    "turned",
]

ELBOW = ("elbow down", "elbow up")
SHOULDER = ("shoulder right", "shoulder left")
HANDED = ("right-handed", "left-handed")
"""A SCARA's elbow, as industrial SCARA controllers name it: right-handed with the elbow angle >= 0 (the forearm
turned counterclockwise from the upper arm about the elbow's axis, seen with that axis pointing at the viewer, so
the elbow lies to the right of the line from shoulder to wrist), left-handed with it negative. The first solution of
the elbow's rotation to a distance, ``phi - psi``, is right-handed: it leaves ``h.((e - s) x (w - e)) = |e - s| |w -
e| sin(psi) > 0`` for shoulder ``s``, elbow ``e`` and wrist ``w``."""
SLIDE = ("slide reversed", "slide out")
"""A slide to a distance: "slide out" puts the point beyond (along the slide's direction) the place where the slide's
line passes closest to the point it keeps its distance from, "slide reversed" before it; one solution, "slide out",
where they coincide. On the Stanford arm and the spherical arm that place is at d3 = 0, so the names are the sign of
d3."""
SLIDE_RULE = "slide reversed: the first solution, before the line's closest point; slide out: the second, beyond it"
DISTANCE_RULE = "the first solution is phi - psi, the second phi + psi"


def rotation(axis: sympy.Matrix, angle: sympy.Expr) -> sympy.Matrix:
    r"""The rotation by ``angle`` about the unit ``axis``: :math:`I + \sin\theta\,K + (1 - \cos\theta) K^2`."""
    k = sympy.Matrix([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return sympy.eye(3) + sympy.sin(angle) * k + (1 - sympy.cos(angle)) * k * k


def turned(axis: sympy.Matrix, point: sympy.Matrix, angle: sympy.Expr, x: sympy.Matrix) -> sympy.Matrix:
    """The point ``x`` turned by ``angle`` about the axis through ``point``."""
    return rotation(axis, angle) * (x - point) + point


def length(v: sympy.Matrix) -> sympy.Expr:
    """``|v|`` as the square root of a sum of squares (never the root of a negative number, even in floats)."""
    return sympy.sqrt(sum((e**2 for e in v), sympy.S.Zero))


def across(axis: sympy.Matrix, v: sympy.Matrix) -> sympy.Matrix:
    """The part of ``v`` across the unit ``axis``: ``v - axis (axis.v)``."""
    return (v - axis * axis.dot(v)).applyfunc(sympy.expand)


def perpendicular(axis: sympy.Matrix) -> sympy.Matrix:
    """An exact unit vector across ``axis``: the coordinate axis farthest from it, made perpendicular."""
    index = min(range(3), key=lambda i: abs(float(axis[i])) if axis[i].is_number else 1.0)
    v = across(axis, sympy.eye(3)[:, index])
    return (v / sympy.sqrt(sympy.simplify(v.dot(v)))).applyfunc(sympy.simplify)


def _zero(expr: sympy.Expr) -> bool:
    return sympy.simplify(expr) == 0


def plane_step(
    joint: int, geometry: ArmGeometry, direction: sympy.Matrix, target: sympy.Matrix, offset: sympy.Expr, what: str,
    subject: str = "the tool point",
) -> Step:
    r"""The rotation of ``joint`` that puts ``target`` at ``offset`` along the turned ``direction``.

    Solves :math:`(\mathrm{rot}(h, \theta) u) \cdot (x - r) = d` (``u = direction``, ``x = target``, ``d = offset``,
    axis ``h`` through ``r``) as a rotation to a distance: :math:`|\ell\, \mathrm{rot}(h, \theta) u - (x - r)|^2
    = \ell^2 + |x - r|^2 - 2 \ell d`, which is :math:`|x - r|^2` for :math:`\ell = 2 d` (and the unit length with
    :math:`\sqrt{|x - r|^2 + 1}` when ``d`` is identically zero).
    """
    axis, point = geometry.axes[joint], geometry.points[joint]
    through_axis = _zero(offset)
    scale = sympy.Integer(1) if through_axis else 2 * offset
    squares = sum(((e**2 for e in target - point)), sympy.S.One if through_axis else sympy.S.Zero)
    distance = sympy.sqrt(squares)
    name = geometry.robot.joint_variables[joint]
    return Step(
        (joint,),
        "rotation_to_distance",
        {"k": axis, "p": point + scale * direction, "q": target, "delta": distance, "point_on_axis": point},
        f"{name} turns {what} so that the target lies at the offset {offset} along it, a rotation to a distance "
        f"({DISTANCE_RULE}: {SHOULDER[0]}, then {SHOULDER[1]})",
        SHOULDER,
        subject=subject,
        reach="offset",
    )


def _pose() -> tuple[sympy.Matrix, sympy.Matrix]:
    pose = pose_matrix()
    return pose[:3, :3], pose[:3, 3]


def _link_point(geometry: ArmGeometry, point: sympy.Matrix) -> sympy.Matrix:
    """Where the target pose puts a point of the last link given at home: ``R R_M^T (x - p_M) + p``."""
    r, p = _pose()
    home = geometry.home
    return (r * home[:3, :3].T * (point - home[:3, 3]) + p).applyfunc(sympy.expand)


def _in_plane(axis: sympy.Matrix, x: sympy.Matrix, plane_point: sympy.Matrix) -> sympy.Matrix:
    """``x`` moved along ``axis`` into the plane through ``plane_point`` across it."""
    return (x - axis * axis.dot(x - plane_point)).applyfunc(sympy.expand)


def _two_link(geometry: ArmGeometry, first: int, second: int, point: sympy.Matrix, target: sympy.Matrix,
              subject: str, branches: tuple[str, str] = ELBOW) -> tuple[Step, Step]:
    """The elbow ``second`` by the distance of ``target`` from axis ``first``, then ``first`` onto ``target``.

    ``point`` is the home position of the point to be placed; ``target`` is already in its plane across the axes.
    """
    h, names = geometry.axes, geometry.robot.joint_variables
    p_first, p_second = geometry.points[first], geometry.points[second]
    elbow = Step(
        (second,),
        "rotation_to_distance",
        {"k": h[second], "p": point, "q": p_first, "delta": length(target - p_first), "point_on_axis": p_second},
        f"{names[second]} bends the elbow until the point is as far from axis {first + 1} as the target, a rotation "
        f"to a distance ({DISTANCE_RULE}: {branches[0]}, then {branches[1]})",
        branches,
        subject=subject,
        reach="elbow",
    )
    moved = turned(h[second], p_second, names[second], point).applyfunc(sympy.expand)
    swing = Step(
        (first,),
        "rotation_to_point",
        {"k": h[first], "p": moved, "q": target, "point_on_axis": p_first},
        f"{names[first]} swings that point onto the target about axis {first + 1}, a rotation to a point",
        subject=subject,
    )
    return elbow, swing


def _orientation_step(geometry: ArmGeometry, joint: int, before: list[int]) -> Step:
    """The last revolute joint of a planar arm from the target's rotation about the common axis direction."""
    r, _ = _pose()
    h = geometry.axes[joint]
    v = perpendicular(h)
    reached = r * geometry.home[:3, :3].T * v
    for j in reversed(before):
        reached = rotation(geometry.axes[j], -geometry.robot.joint_variables[j]) * reached
    target = across(h, reached)
    name = geometry.robot.joint_variables[joint]
    return Step(
        (joint,),
        "rotation_to_point",
        {"k": h, "p": length(target) * v, "q": target, "point_on_axis": sympy.zeros(3, 1)},
        f"{name} turns the tool to the target's rotation about the axes, read from a vector across them "
        f"(the part of the target rotation that tilts out of the plane is not controlled), a rotation to a point",
    )


def _plain(geometry: ArmGeometry) -> bool:
    """A whole arm without coupled joints (every joint its own coordinate)."""
    return geometry.free_joint is None and geometry.robot.coupling is None


def _all_parallel(geometry: ArmGeometry) -> bool:
    return _plain(geometry) and all(geometry.parallel(0, j) for j in range(1, len(geometry.axes)))


def _apart(geometry: ArmGeometry, i: int, x: sympy.Matrix) -> bool:
    """Whether ``x`` lies off axis ``i`` (exactly)."""
    return not all(_zero(e) for e in across(geometry.axes[i], x - geometry.points[i]))


def planar_plan(geometry: ArmGeometry) -> Plan | None:
    """Planar 2R or 3R: two or three revolute joints with parallel axes, the position and rotation in their plane."""
    n = len(geometry.kinds)
    if n not in (2, 3) or any(k != "revolute" for k in geometry.kinds) or not _all_parallel(geometry):
        return None
    h, points, home = geometry.axes[0], geometry.points, geometry.home
    tool = home[:3, 3]
    if not _apart(geometry, 0, points[1]):
        return None
    reasons = (f"the axes of joints {', '.join(str(i + 1) for i in range(n - 1))} and {n} are parallel",)
    if n == 2:
        if not _apart(geometry, 1, tool):
            return None
        _, p = _pose()
        pair = _two_link(geometry, 0, 1, tool, _in_plane(h, p, tool), "the tool point")
        return Plan(geometry.robot, "planar 2R", reasons, (), pair, "the position in the plane across the axes")
    if not _apart(geometry, 1, points[2]):
        return None
    wrist = _in_plane(h, _link_point(geometry, points[2]), points[2])
    pair = _two_link(geometry, 0, 1, points[2], wrist, "the wrist point on axis 3")
    steps = (*pair, _orientation_step(geometry, 2, [0, 1]))
    return Plan(
        geometry.robot,
        "planar 3R",
        reasons,
        (),
        steps,
        "the position in the plane across the axes and the rotation about them",
    )


def scara_plan(geometry: ArmGeometry) -> Plan | None:
    """SCARA: revolute, revolute, prismatic, revolute, every axis parallel; position and rotation about the axes."""
    if geometry.kinds != ("revolute", "revolute", "prismatic", "revolute") or not _all_parallel(geometry):
        return None
    points, names = geometry.points, geometry.robot.joint_variables
    if not _apart(geometry, 0, points[1]) or not _apart(geometry, 1, points[3]):
        return None
    h = geometry.axes[0]
    wrist = _link_point(geometry, points[3])
    planar = _in_plane(h, wrist, points[3])
    elbow, swing = _two_link(geometry, 0, 1, points[3], planar, "the wrist point on axis 4", HANDED)
    along = geometry.axes[2]
    slide = Step(
        (2,),
        "slide_to_point",
        {"k": along, "p": points[3], "q": points[3] + along * along.dot(wrist - points[3])},
        f"{names[2]} slides the wrist along the axes to the target's height, {names[2]} = h3.(w - p4)",
    )
    reasons = ("the axes of joints 1, 2, 3 and 4 are parallel", "joint 3 slides along them")
    return Plan(
        geometry.robot,
        "SCARA",
        reasons,
        (),
        (elbow, swing, slide, _orientation_step(geometry, 3, [0, 1])),
        "the position and the rotation about the parallel axes",
    )


def articulated_plan(geometry: ArmGeometry) -> Plan | None:
    """Articulated 3R: a waist across a shoulder and an elbow with parallel axes; the position of the tool point."""
    if not _plain(geometry) or geometry.kinds != ("revolute",) * 3:
        return None
    if not geometry.parallel(1, 2) or geometry.parallel(0, 1):
        return None
    h, points, robot = geometry.axes, geometry.points, geometry.robot
    tool = geometry.home[:3, 3]
    if not _apart(geometry, 1, points[2]) or not _apart(geometry, 2, tool):
        return None
    _, p = _pose()
    offset = sympy.simplify(h[1].dot(tool - points[0]))
    waist = plane_step(0, geometry, h[1], p, offset, "the direction of axis 2 about axis 1")
    seen = turned(h[0], points[0], -robot.joint_variables[0], p).applyfunc(sympy.expand)
    elbow, swing = _two_link(geometry, 1, 2, tool, seen, "the tool point")
    reasons = ("the axes of joints 2 and 3 are parallel", "the axis of joint 1 is not parallel to them")
    return Plan(robot, "articulated 3R", reasons, (), (waist, elbow, swing), "the position of the tool point")


def spherical_arm_plan(geometry: ArmGeometry) -> Plan | None:
    """Spherical (polar) arm: a waist, a revolute joint across it, a slide across that: the tool point's position.

    ``theta1`` as for the articulated 3R (the slide keeps the component along axis 2 because it is across it), then
    the slide from the distance to the point ``p2`` on axis 2 (two solutions, :data:`SLIDE`), then
    ``theta2`` turns the slid point onto the target.
    """
    if not _plain(geometry) or geometry.kinds != ("revolute", "revolute", "prismatic"):
        return None
    h, points, robot = geometry.axes, geometry.points, geometry.robot
    if geometry.parallel(0, 1) or not _zero(h[1].dot(h[2])):
        return None
    tool = geometry.home[:3, 3]
    if not _apart(geometry, 1, tool) and all(_zero(e) for e in across(h[1], h[2])):
        return None
    _, p = _pose()
    waist = plane_step(0, geometry, h[1], p, sympy.simplify(h[1].dot(tool - points[0])),
                       "the direction of axis 2 about axis 1")
    seen = turned(h[0], points[0], -robot.joint_variables[0], p).applyfunc(sympy.expand)
    name = robot.joint_variables[2]
    slide = Step(
        (2,),
        "slide_to_distance",
        {"k": h[2], "p": tool, "q": points[1], "delta": length(seen - points[1])},
        f"{name} slides the tool point to the target's distance from axis 2, a slide to a distance ({SLIDE_RULE})",
        SLIDE,
        merged=1,
        subject="the tool point",
        reach="offset",
    )
    swing = Step(
        (1,),
        "rotation_to_point",
        {"k": h[1], "p": tool + h[2] * name, "q": seen, "point_on_axis": points[1]},
        f"{robot.joint_variables[1]} swings the slid tool point onto the target about axis 2, a rotation to a point",
    )
    reasons = ("the axis of joint 1 is not parallel to axis 2", "joint 3 slides across axis 2")
    return Plan(robot, "spherical arm", reasons, (), (waist, slide, swing), "the position of the tool point")


def cylindrical_plan(geometry: ArmGeometry) -> Plan | None:
    """Cylindrical arm: a waist, a slide along it, a slide across it; the tool point's position.

    ``theta1`` puts the target in the plane the two slides span (its component along ``n = h1 x h3`` fixed), as for
    the articulated 3R; seen from link 1 the target is ``t + d2 h2 + d3 h3``: the slide across first, from the target
    moved along ``h2`` to the tool's level, then the slide along.
    """
    if not _plain(geometry) or geometry.kinds != ("revolute", "prismatic", "prismatic"):
        return None
    h, points, robot = geometry.axes, geometry.points, geometry.robot
    if not geometry.parallel(0, 1) or not _zero(h[1].dot(h[2])):
        return None
    normal = h[0].cross(h[2]).applyfunc(sympy.simplify)
    tool = geometry.home[:3, 3]
    _, p = _pose()
    waist = plane_step(0, geometry, normal, p, sympy.simplify(normal.dot(tool - points[0])),
                       "the plane of the two slides about axis 1")
    seen = turned(h[0], points[0], -robot.joint_variables[0], p).applyfunc(sympy.expand)
    names = robot.joint_variables
    reach = Step(
        (2,),
        "slide_to_point",
        {"k": h[2], "p": tool, "q": _in_plane(h[1], seen, tool)},
        f"{names[2]} slides the tool point across axis 1 to the target's distance from it, a slide to a point",
    )
    lift = Step(
        (1,),
        "slide_to_point",
        {"k": h[1], "p": tool + h[2] * names[2], "q": seen},
        f"{names[1]} slides the tool point along axis 1 to the target's level, a slide to a point",
    )
    reasons = ("joint 2 slides along the axis of joint 1", "joint 3 slides across it")
    return Plan(robot, "cylindrical", reasons, (), (waist, reach, lift), "the position of the tool point")


def palletizer_plan(geometry: ArmGeometry) -> Plan | None:
    r"""Palletizer: a waist, three parallel joints the last of which is coupled to keep link 4 level, a flange joint.

    The coupling makes :math:`\sum_{j=2}^{4} (h_j \cdot h_2)\, \theta_j = 0`, so the flange point ``f`` (on axis 5)
    sits at the fixed offset ``f - p4`` from the point ``p4`` on axis 4: ``theta1`` as for the articulated 3R, then
    ``theta3`` and ``theta2`` place ``p4`` at ``rot(h1, -theta1)(f_w - p1) + p1 - (f - p4)``, ``theta4`` follows the
    coupling and ``theta5`` turns the flange about its axis.
    """
    robot = geometry.robot
    if geometry.free_joint is not None or robot.coupling is None or geometry.kinds != ("revolute",) * 5:
        return None
    h, points, names = geometry.axes, geometry.points, robot.joint_variables
    if not (geometry.parallel(1, 2) and geometry.parallel(2, 3)) or geometry.parallel(0, 1):
        return None
    coupled = robot.coupling.values
    if coupled[:3] != names[:3] or coupled[4] != names[4] or not _zero(
        sum((h[j].dot(h[1]) * coupled[j] for j in (1, 2, 3)), sympy.S.Zero)
    ):
        return None
    flange = points[4]
    if not _apart(geometry, 1, points[2]) or not _apart(geometry, 2, points[3]):
        return None
    target = _link_point(geometry, flange)
    waist = plane_step(0, geometry, h[1], target, sympy.simplify(h[1].dot(flange - points[0])),
                       "the direction of axes 2 to 4 about axis 1", "the flange point")
    seen = (turned(h[0], points[0], -names[0], target) - (flange - points[3])).applyfunc(sympy.expand)
    elbow, swing = _two_link(geometry, 1, 2, points[3], seen, "the point on axis 4")
    v = perpendicular(h[3])
    follow = Step(
        (3,),
        "rotation_to_point",
        {"k": h[3], "p": v, "q": rotation(h[3], coupled[3]) * v, "point_on_axis": sympy.zeros(3, 1)},
        f"{names[3]} follows the coupling {names[3]} = {coupled[3]}, which keeps link 4 level",
    )
    reasons = ("the axes of joints 2, 3 and 4 are parallel", f"the coupling {names[3]} = {coupled[3]} keeps link 4 "
               "level", "the axis of joint 1 is not parallel to them")
    steps = (waist, elbow, swing, follow, _orientation_step(geometry, 4, [0, 1, 2, 3]))
    return Plan(robot, "palletizer", reasons, (), steps, "the position of the flange point and its rotation about "
                "axis 5")
