r"""Standard Denavit-Hartenberg: :math:`{}^{i-1}_{i}T = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)`.

Joint *i* moves about or along :math:`z_{i-1}`; the row of joint *i* holds :math:`\alpha_i, a_i, d_i, \theta_i`.

Both DH conventions multiply the same elementary factors; only the grouping into links differs. With
:math:`Z_i = R_z(\theta_i) T_z(d_i)` and :math:`X_i = T_x(a_i) R_x(\alpha_i)` (which commute, so
:math:`R_x(\alpha) T_x(a) = T_x(a) R_x(\alpha)`):

.. math::
    \text{standard: } B\,(Z_1 X_1)(Z_2 X_2)\cdots(Z_n X_n)\,T
    \;=\; B\,(X_0 Z_1)(X_1 Z_2)\cdots(X_{n-1} Z_n)\,(X_n T) \text{ with } X_0 = I,

which is a modified table with rows :math:`(\alpha_{i-1}, a_{i-1}, d_i, \theta_i)` and the tool :math:`X_n T`.
The way back moves :math:`X_0` of a modified table into the base transform and leaves :math:`X_n = I`. Joint
variables, offsets and parameters are unchanged, so forward kinematics from the world frame to the tool frame and
every Jacobian expressed in the world frame at the tool point are *identical* expressions. The intermediate
frames differ: standard frame {i} is modified frame {i+1} before joint i+1 moves.

A tool transform that is exactly :math:`X_n` (``xyz = [a, 0, 0]``, ``rpy = [alpha, 0, 0]``) is folded back into the
last row, so standard -> modified -> standard returns the very same table.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import sympy as sp

from symjac.errors import ConversionError
from symjac.model.conventions.base import Cell, Column, JointForm, JointReader, NoRobotFields, moved_inertial
from symjac.model.conventions.dh import DHPlacement, dh_cells, dh_columns, dh_forms, dh_placement, read_dh, write_dh
from symjac.model.exact_transforms import fixed_transform_from_matrix
from symjac.model.robot import Convention, FixedTransform, Joint, Robot
from symjac.symbolic.transforms import homogeneous, inverse_transform, rotation

__all__ = ["PLUGIN", "STANDARD", "StandardDH", "modified_from_standard", "standard_from_modified"]


class StandardDH(NoRobotFields):
    """The plug-in of the standard DH convention (see :class:`~symjac.model.conventions.base.ConventionPlugin`)."""

    convention = Convention.STANDARD
    table_name = "standard Denavit-Hartenberg table"
    keys: tuple[str, ...] = ("alpha", "a", "name")
    columns: tuple[Column, ...] = dh_columns("i")

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[DHPlacement, str]:
        """``alpha`` and ``a`` of a robot-file joint table."""
        return read_dh(table, reader)

    def write(self, joint: Joint) -> dict[str, Any]:
        """``alpha``, ``a``, ``d`` and ``theta``."""
        return write_dh(joint)

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        r"""Each row as :math:`R_z T_z` followed by :math:`T_x(a_i) R_x(\alpha_i)`."""
        return dh_forms(robot, normal_first=False)

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        r""":math:`\alpha_i, a_i, d_i, \theta_i`."""
        return dh_cells(joint)

    def to_modified(self, robot: Robot) -> Robot:
        """:func:`modified_from_standard`."""
        return modified_from_standard(robot)

    def from_modified(self, robot: Robot) -> Robot:
        """:func:`standard_from_modified`."""
        return standard_from_modified(robot)


STANDARD = PLUGIN = StandardDH()


def modified_from_standard(robot: Robot) -> Robot:
    """The modified-DH robot with the same world-to-tool kinematics as a standard-DH ``robot`` (module docstring).

    Examples
    --------
    >>> from symjac import load_robot
    >>> ur5 = load_robot("ur5")
    >>> modified = modified_from_standard(ur5)
    >>> [str(j.placement.alpha) for j in modified.joints], modified.tool
    (['0', 'pi/2', '0', '0', 'pi/2', '-pi/2'], None)
    >>> standard_from_modified(modified) == ur5
    True
    """
    if robot.convention is not Convention.STANDARD:
        raise ConversionError(f"{robot.name} is not in the standard convention (it is {robot.convention.value})")
    joints = []
    previous = DHPlacement()
    for joint in robot.joints:
        joints.append(replace(joint, placement=previous))
        previous = dh_placement(joint)
    tool = _prepend_x(previous.a, previous.alpha, robot.tool)
    # standard frame {i} is modified frame {i} followed by X_i = Tx(a_i) Rx(alpha_i): each body moves with it
    inertials = tuple(moved_inertial(inertial, _x_matrix(dh_placement(joint).a, dh_placement(joint).alpha))
                      for inertial, joint in zip(robot.inertials, robot.joints, strict=True))
    return replace(robot, convention=Convention.MODIFIED, joints=tuple(joints), tool=tool, inertials=inertials)


def standard_from_modified(robot: Robot) -> Robot:
    """The standard-DH robot with the same world-to-tool kinematics as a modified-DH ``robot`` (module docstring)."""
    if robot.convention is not Convention.MODIFIED:
        raise ConversionError(f"{robot.name} is not in the modified convention (it is {robot.convention.value})")
    rows = [dh_placement(joint) for joint in robot.joints]
    base = _append_x(robot.base, rows[0].a, rows[0].alpha)
    joints = [replace(joint, placement=rows[i + 1] if i + 1 < len(rows) else DHPlacement())
              for i, joint in enumerate(robot.joints)]
    tool = robot.tool
    if tool is not None and tool.given_matrix is None and tool.xyz[1:] == (0, 0) and tool.rpy[1:] == (0, 0):
        # a tool that is exactly X_n = Tx(a) Rx(alpha) belongs in the last row
        joints[-1] = replace(joints[-1], placement=DHPlacement(alpha=tool.rpy[0], a=tool.xyz[0]))
        tool = None
    inertials = tuple(moved_inertial(inertial, inverse_transform(_x_matrix(row.a, row.alpha)))
                      for inertial, row in zip(robot.inertials, map(dh_placement, joints), strict=True))
    return replace(robot, convention=Convention.STANDARD, joints=tuple(joints), base=base, tool=tool,
                   inertials=inertials)


def _x_matrix(a: sp.Expr, alpha: sp.Expr) -> sp.Matrix:
    return homogeneous(rotation("x", alpha), sp.Matrix([a, 0, 0]))


def _prepend_x(a: sp.Expr, alpha: sp.Expr, tool: FixedTransform | None) -> FixedTransform | None:
    r""":math:`T_x(a) R_x(\alpha)` followed by ``tool``, as one fixed transform (xyz/rpy whenever possible)."""
    if tool is None:
        return None if a == 0 and alpha == 0 else FixedTransform(xyz=(a, sp.S.Zero, sp.S.Zero),
                                                                 rpy=(alpha, sp.S.Zero, sp.S.Zero))
    if a == 0 and alpha == 0:
        return tool
    if tool.given_matrix is None and tool.rpy[1:] == (0, 0):
        # Rx(alpha) Rx(roll) = Rx(alpha + roll); the position turns with Rx(alpha)
        x, y, z = (sp.Matrix([a, 0, 0]) + rotation("x", alpha) * sp.Matrix(tool.xyz)).applyfunc(sp.expand)
        return FixedTransform(xyz=(x, y, z), rpy=(alpha + tool.rpy[0], sp.S.Zero, sp.S.Zero))
    return fixed_transform_from_matrix(_x_matrix(a, alpha) * sp.Matrix(tool.matrix))


def _append_x(base: FixedTransform | None, a: sp.Expr, alpha: sp.Expr) -> FixedTransform | None:
    r"""``base`` followed by :math:`T_x(a) R_x(\alpha)`."""
    if a == 0 and alpha == 0:
        return base
    if base is None:
        return FixedTransform(xyz=(a, sp.S.Zero, sp.S.Zero), rpy=(alpha, sp.S.Zero, sp.S.Zero))
    return fixed_transform_from_matrix(sp.Matrix(base.matrix) * _x_matrix(a, alpha))
