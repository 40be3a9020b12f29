r"""The joint axes of an arm at home, exact, and the facts closed-form inverse kinematics is decided on.

At zero joint values joint ``i`` turns (or slides) about the unit axis ``h_i`` through the point ``p_i``, and the tool
frame sits at ``M``; both are taken from the axis frames in frame {0} (:func:`~symjac.kinematics.convert.axes_at_home`),
so they are exact SymPy expressions in the robot's parameters. Forward kinematics is then the product of exponentials

.. math:: T(q) = e^{[\xi_1] q_1} \cdots e^{[\xi_n] q_n} M,

with ``e^{[xi_i] q}`` the rotation by ``q`` about the line ``(h_i, p_i)``, or the translation by ``q h_i``. The pose is
in frame {0}: the frame ``numeric_model(robot).fk(q)`` returns, before the robot's base transform and after its tool.

The predicates are identities in every parameter, never tests within a tolerance:

- axes ``i`` and ``j`` are parallel when ``h_i x h_j`` simplifies to zero;
- two axes that are not parallel meet when ``(p_j - p_i).(h_i x h_j)`` simplifies to zero, at
  ``p_i + s h_i`` with ``s = ((p_j - p_i) x h_j).(h_i x h_j) / |h_i x h_j|^2``;
- several axes meet at one point when every one of them passes through the point two of them meet at
  (``(c - p_k) x h_k`` simplifies to zero).

Where they miss, :meth:`ArmGeometry.why_not_meet` says by how much at the parameters' defaults.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from itertools import combinations

import sympy

from symjac.errors import ArgumentError
from symjac.kinematics.convert import axes_at_home
from symjac.model.robot import JointType, Robot
from symjac.symbolic.transforms import homogeneous

__all__ = ["ArmGeometry", "arm_geometry", "exponential", "reduced_geometry"]


def _zero(expr: sympy.Expr) -> bool:
    expr = sympy.expand(expr)
    return expr == 0 or sympy.simplify(expr) == 0


def _simplified(matrix: sympy.Matrix) -> sympy.Matrix:
    return matrix.applyfunc(lambda e: sympy.simplify(sympy.expand(e)))


def exponential(axis: sympy.Matrix, point: sympy.Matrix, kind: str, value: sympy.Expr) -> sympy.Matrix:
    r"""The 4 x 4 motion of one joint by ``value`` about (along) the line through ``point`` along the unit ``axis``.

    A rotation is ``R = I + sin(q) [h] + (1 - cos(q)) [h]^2`` with translation ``(I - R) p``; a slide translates by
    ``value axis``.
    """
    if kind == "prismatic":
        return homogeneous(sympy.eye(3), axis * value)
    skew = sympy.Matrix([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    rotation = sympy.eye(3) + sympy.sin(value) * skew + (1 - sympy.cos(value)) * skew * skew
    return homogeneous(rotation, (sympy.eye(3) - rotation) * point)


@dataclass(frozen=True)
class ArmGeometry:
    """The joint axes of ``robot`` at home (q = 0) in frame {0}, exact.

    ``axes[i]`` is the unit axis ``h_i`` (3 x 1) and ``points[i]`` a point on it, ``kinds[i]`` ``"revolute"`` or
    ``"prismatic"``, ``home`` the 4 x 4 tool pose ``M``. ``joints[i]`` is the robot joint (0-based) that entry ``i``
    belongs to: all of them, or all but ``free_index`` for the arm that remains when that joint's value is given
    (:func:`reduced_geometry`; its variable then appears in the axes that follow it and in ``home``). Methods take
    these 0-based indices, like the tuples; :attr:`free_joint` is the given joint's number (1-based), as everywhere
    a user names a joint.
    """

    robot: Robot
    axes: tuple[sympy.Matrix, ...]
    points: tuple[sympy.Matrix, ...]
    kinds: tuple[str, ...]
    home: sympy.Matrix
    joints: tuple[int, ...] = ()
    free_index: int | None = None

    def __hash__(self) -> int:
        return hash((self.robot, self.joints, self.free_index))

    @property
    def free_joint(self) -> int | None:
        """The number (1-based) of the joint whose value is given, or None for the whole arm."""
        return None if self.free_index is None else self.free_index + 1

    def _index(self, joint: int) -> int:
        if joint not in self.joints:
            raise ArgumentError(f"arm geometry of {self.robot.name}: joint {joint} (0-based) is not one of "
                                f"{list(self.joints)}")
        return self.joints.index(joint)

    def axis(self, joint: int) -> sympy.Matrix:
        """The unit axis of robot joint ``joint`` (0-based) at home."""
        return self.axes[self._index(joint)]

    def point(self, joint: int) -> sympy.Matrix:
        """A point on the axis of robot joint ``joint`` (0-based) at home."""
        return self.points[self._index(joint)]

    def kind(self, joint: int) -> str:
        """``"revolute"`` or ``"prismatic"`` for robot joint ``joint`` (0-based)."""
        return self.kinds[self._index(joint)]

    def motion(self, joint: int) -> sympy.Matrix:
        """The 4 x 4 motion of robot joint ``joint`` (0-based) by its variable, about its axis in this arm.

        For a reduced arm, a joint after the given one moves as ``E_k e^{[xi_j] q_j} E_k^{-1}`` with its axis at the
        robot's home (products of plain sines and cosines, where the turned axis would give ``1 - cos`` terms).
        """
        variable = self.robot.joint_variables[joint]
        if self.free_index is None or joint < self.free_index:
            return exponential(self.axis(joint), self.point(joint), self.kind(joint), variable)
        whole = arm_geometry(self.robot)
        k = self.free_index
        given = exponential(whole.axes[k], whole.points[k], whole.kinds[k], self.robot.joint_variables[k])
        inverse = exponential(whole.axes[k], whole.points[k], whole.kinds[k], -self.robot.joint_variables[k])
        own = exponential(whole.axes[joint], whole.points[joint], whole.kinds[joint], variable)
        return (given * own * inverse).applyfunc(sympy.expand)

    def parallel(self, i: int, j: int) -> bool:
        """Whether the axes of robot joints ``i`` and ``j`` (0-based) are parallel, as an identity."""
        return all(_zero(e) for e in self.axis(i).cross(self.axis(j)))

    def intersection(self, *joints: int) -> sympy.Matrix | None:
        """The point where the axes of these robot joints (0-based) all meet, exact, or None when they do not.

        Parallel axes have no common point (coincident lines neither: they meet everywhere).
        """
        if len(joints) < 2:
            raise ArgumentError(f"arm geometry of {self.robot.name}: an intersection needs two axes or more, got "
                                f"{list(joints)}")
        pair = next(((i, j) for i, j in combinations(joints, 2) if not self.parallel(i, j)), None)
        if pair is None:
            return None
        i, j = pair
        h_i, h_j, p_i, p_j = self.axis(i), self.axis(j), self.point(i), self.point(j)
        normal = h_i.cross(h_j)
        if not _zero((p_j - p_i).dot(normal)):
            return None
        s = (p_j - p_i).cross(h_j).dot(normal) / normal.dot(normal)
        common = _simplified(p_i + s * h_i)
        if all(all(_zero(e) for e in (common - self.point(k)).cross(self.axis(k))) for k in joints):
            return common
        return None

    def why_not_meet(self, *joints: int) -> str:
        """A sentence saying how the axes of these robot joints (0-based) miss one another, at the defaults."""
        numbers = dict(self.robot.defaults)
        at = "at the defaults"
        if self.free_index is not None:  # the given joint's variable is in the axes after it: take it at 0
            numbers[self.robot.joint_variables[self.free_index]] = sympy.S.Zero
            at = f"at the defaults, joint {self.free_joint} at 0"
        names = ", ".join(str(j + 1) for j in joints[:-1]) + f" and {joints[-1] + 1}"
        if self.intersection(*joints) is not None:
            return f"the axes of joints {names} meet in one point"
        for i, j in combinations(joints, 2):
            h_i, h_j = self.axis(i).subs(numbers), self.axis(j).subs(numbers)
            between = (self.point(j) - self.point(i)).subs(numbers)
            normal = h_i.cross(h_j)
            size = float(sympy.sqrt(normal.dot(normal)))
            if self.parallel(i, j) or size < 1e-12:
                across = between - h_i * h_i.dot(between)
                how = "parallel" if self.parallel(i, j) else "parallel there"
                return (f"the axes of joints {i + 1} and {j + 1} are {how}, "
                        f"{float(sympy.sqrt(across.dot(across))):.6g} apart ({at})")
            if not _zero((self.point(j) - self.point(i)).dot(self.axis(i).cross(self.axis(j)))):
                gap = abs(float(between.dot(normal))) / size
                detail = f"{gap:.6g} apart along their common normal" if gap else "they meet for some values only"
                return f"the axes of joints {i + 1} and {j + 1} do not meet: {detail} ({at})"
        return f"the axes of joints {names} meet in pairs but not in one point"


def _axes(robot: Robot) -> tuple[tuple[sympy.Matrix, ...], tuple[sympy.Matrix, ...], sympy.Matrix]:
    frames, home = axes_at_home(robot)
    axes = tuple(_simplified(sympy.Matrix(frame[:3, 2])) for frame in frames)
    points = tuple(_simplified(sympy.Matrix(frame[:3, 3])) for frame in frames)
    return axes, points, _simplified(sympy.Matrix(home))


@functools.lru_cache(maxsize=32)
def arm_geometry(robot: Robot) -> ArmGeometry:
    """The joint axes, points on them, joint kinds and home tool pose of ``robot`` at q = 0, exact (memoized).

    Coupled joints are taken as the uncoupled chain (each joint its own variable).

    Examples
    --------
    >>> from symjac import load_robot
    >>> geometry = arm_geometry(load_robot("puma560"))
    >>> geometry.intersection(3, 4, 5).T
    Matrix([[a2 + a3, d3, -d4]])
    >>> geometry.parallel(1, 2)
    True
    """
    axes, points, home = _axes(robot.uncoupled)
    kinds = tuple("prismatic" if joint.type is JointType.PRISMATIC else "revolute" for joint in robot.joints)
    return ArmGeometry(robot, axes, points, kinds, home, tuple(range(robot.n_joints)))


@functools.lru_cache(maxsize=32)
def reduced_geometry(robot: Robot, free_joint: int) -> ArmGeometry:
    r"""The arm that remains when joint number ``free_joint`` (1-based) is held at its variable's value.

    ``e^{[xi_k] q_k}`` moves to the right past the later joints: each later axis ``(h_j, p_j)`` becomes its image under
    that motion, and so does ``M``; the variable ``q_k`` stays a symbol (the redundancy parameter).
    """
    geometry = arm_geometry(robot)
    if isinstance(free_joint, bool) or not isinstance(free_joint, int) or not 1 <= free_joint <= robot.n_joints:
        raise ArgumentError(f"{robot.name}: free_joint must be a joint number from 1 to {robot.n_joints}, "
                            f"got {free_joint!r}")
    k = free_joint - 1
    motion = exponential(geometry.axes[k], geometry.points[k], geometry.kinds[k], robot.joint_variables[k])
    rotation, shift = motion[:3, :3], motion[:3, 3]
    axes = [*geometry.axes[:k], *(_simplified(rotation * h) for h in geometry.axes[k + 1:])]
    points = [*geometry.points[:k], *(_simplified(rotation * p + shift) for p in geometry.points[k + 1:])]
    kinds = (*geometry.kinds[:k], *geometry.kinds[k + 1:])
    joints = tuple(j for j in range(robot.n_joints) if j != k)
    return ArmGeometry(robot, tuple(axes), tuple(points), kinds, _simplified(motion * geometry.home), joints, k)
