r"""What both Denavit-Hartenberg conventions share: the row :math:`(\alpha, a, d, \theta)` and its placement record.

The placement of a DH joint is the common normal to the neighbouring axis, :math:`T_x(a) R_x(\alpha)`: after the
joint's own motion in the standard convention (:math:`\alpha_i, a_i`), before it in the modified one
(:math:`\alpha_{i-1}, a_{i-1}`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.model.conventions.base import Cell, Column, JointForm, JointReader, joint_form
from symjac.model.expressions import expression_text
from symjac.model.robot import Joint, Placement, Robot
from symjac.symbolic.transforms import Motion

__all__ = ["DHPlacement", "dh_cells", "dh_columns", "dh_forms", "dh_placement", "read_dh", "write_dh", "x_motions"]


@dataclass(frozen=True)
class DHPlacement(Placement):
    r"""The twist :math:`\alpha` and length :math:`a` of the common normal a DH row gives a joint."""

    alpha: sp.Expr = sp.S.Zero
    a: sp.Expr = sp.S.Zero


def dh_placement(joint: Joint) -> DHPlacement:
    """The DH placement of ``joint`` (a ``TypeError`` naming the joint if it has another convention's)."""
    if not isinstance(joint.placement, DHPlacement):
        raise TypeError(f"joint {joint.index} has no DH row (it has {type(joint.placement).__name__})")
    return joint.placement


def x_motions(placement: DHPlacement) -> tuple[Motion, Motion]:
    r""":math:`T_x(a)\,R_x(\alpha)` as elementary motions (they commute)."""
    return Motion("T", "x", placement.a), Motion("R", "x", placement.alpha)


def dh_columns(subscript: str) -> tuple[Column, ...]:
    r"""The columns :math:`\alpha, a, d_i, \theta_i`, the first two with ``subscript``."""
    return Column("alpha", subscript), Column("a", subscript), Column("d", "i"), Column("theta", "i")


def dh_cells(joint: Joint) -> tuple[Cell, ...]:
    """A DH row: alpha, a, the translation along z and the rotation about z (variables included)."""
    placement = dh_placement(joint)
    return placement.alpha, placement.a, joint.offset, joint.angle


def read_dh(table: Mapping[str, Any], reader: JointReader) -> tuple[DHPlacement, str]:
    """``alpha`` (an angle) and ``a`` of one robot-file joint table, and its optional ``name``."""
    name = table.get("name", "")
    if not isinstance(name, str):
        raise reader.fail("'name' must be a string", "name")
    return DHPlacement(alpha=reader.number("alpha", angle=True), a=reader.number("a")), name


def write_dh(joint: Joint) -> dict[str, Any]:
    """Every field of a DH row, zeros included, after the joint's ``name`` when it has one."""
    placement = dh_placement(joint)
    row: dict[str, Any] = {"name": joint.name} if joint.name else {}
    return row | {key: expression_text(value) for key, value in
                  (("alpha", placement.alpha), ("a", placement.a), ("d", joint.d), ("theta", joint.theta))}


def dh_forms(robot: Robot, *, normal_first: bool) -> tuple[JointForm, ...]:
    r"""Each DH row as a joint form, with the common normal before the joint motion or after it.

    :math:`R_x(\alpha) T_x(a)` before (``normal_first``, modified DH) or :math:`T_x(a) R_x(\alpha)` after (standard).
    """
    forms = []
    for joint in robot.joints:
        translate, turn = x_motions(dh_placement(joint))
        forms.append(joint_form(joint, before=(turn, translate)) if normal_first
                     else joint_form(joint, after=(translate, turn)))
    return tuple(forms)
