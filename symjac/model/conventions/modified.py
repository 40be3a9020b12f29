r"""Modified Denavit-Hartenberg (Craig): :math:`R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)` per link.

Joint *i* moves about or along :math:`z_i`; the row of joint *i* holds :math:`\alpha_{i-1}, a_{i-1}, d_i, \theta_i`.
It is the convention conversions pass through (:mod:`symjac.kinematics.convert`), so both directions are the
identity.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from symjac.model.conventions.base import Cell, Column, JointForm, JointReader, NoRobotFields
from symjac.model.conventions.dh import DHPlacement, dh_cells, dh_columns, dh_forms, read_dh, write_dh
from symjac.model.robot import Convention, Joint, Robot

__all__ = ["MODIFIED", "PLUGIN", "ModifiedDH"]


class ModifiedDH(NoRobotFields):
    """The plug-in of the modified DH convention (see :class:`~symjac.model.conventions.base.ConventionPlugin`)."""

    convention = Convention.MODIFIED
    table_name = "modified Denavit-Hartenberg table"
    keys: tuple[str, ...] = ("alpha", "a", "name")
    columns: tuple[Column, ...] = dh_columns("i-1")

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[DHPlacement, str]:
        r"""``alpha`` (:math:`\alpha_{i-1}`) and ``a`` (:math:`a_{i-1}`) of a robot-file joint table."""
        return read_dh(table, reader)

    def write(self, joint: Joint) -> dict[str, Any]:
        """``alpha``, ``a``, ``d`` and ``theta``."""
        return write_dh(joint)

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        r"""Each row as :math:`R_x(\alpha_{i-1}) T_x(a_{i-1})` followed by :math:`R_z T_z`."""
        return dh_forms(robot, normal_first=True)

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        r""":math:`\alpha_{i-1}, a_{i-1}, d_i, \theta_i`."""
        return dh_cells(joint)

    def to_modified(self, robot: Robot) -> Robot:
        """``robot`` itself."""
        return robot

    def from_modified(self, robot: Robot) -> Robot:
        """``robot`` itself."""
        return robot


MODIFIED = PLUGIN = ModifiedDH()
