r"""Hayati's parameters for nearly parallel axes: :math:`R_z(\theta_i) T_z(d_i) T_x(a_i) R_x(\alpha_i) R_y(\beta_i)`.

The standard DH row plus a turn :math:`\beta_i` about the new y-axis, so that a small misalignment of two parallel
axes is a small change of parameters (a worked example of a convention plug-in).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.model.conventions.base import Cell, Column, JointForm, JointReader, joint_form
from symjac.model.expressions import expression_text
from symjac.model.robot import Convention, Joint, Placement, Robot
from symjac.symbolic.transforms import Motion

__all__ = ["PLUGIN", "Hayati", "HayatiPlacement"]


@dataclass(frozen=True)
class HayatiPlacement(Placement):
    r"""The common normal :math:`T_x(a) R_x(\alpha)` and the tilt :math:`R_y(\beta)` after the joint motion."""

    alpha: sp.Expr = sp.S.Zero
    a: sp.Expr = sp.S.Zero
    beta: sp.Expr = sp.S.Zero


class Hayati:
    """The plug-in of Hayati's convention."""

    convention = Convention.register("hayati")
    table_name = "Hayati table"
    keys: tuple[str, ...] = ("alpha", "a", "beta")
    columns: tuple[Column, ...] = (Column("alpha", "i"), Column("a", "i"), Column("beta", "i"), Column("d", "i"),
                                   Column("theta", "i"))

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[HayatiPlacement, str]:
        """``alpha``, ``a`` and ``beta``."""
        return HayatiPlacement(reader.number("alpha", angle=True), reader.number("a"),
                               reader.number("beta", angle=True)), ""

    def write(self, joint: Joint) -> dict[str, Any]:
        """Every field, zeros included."""
        p = joint.placement
        assert isinstance(p, HayatiPlacement)
        return {key: expression_text(value) for key, value in
                (("alpha", p.alpha), ("a", p.a), ("beta", p.beta), ("d", joint.d), ("theta", joint.theta))}

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        r""":math:`R_z T_z` followed by :math:`T_x(a) R_x(\alpha) R_y(\beta)`."""
        forms = []
        for joint in robot.joints:
            p = joint.placement
            assert isinstance(p, HayatiPlacement)
            after = (Motion("T", "x", p.a), Motion("R", "x", p.alpha), Motion("R", "y", p.beta))
            forms.append(joint_form(joint, after=after))
        return tuple(forms)

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        r""":math:`\alpha_i, a_i, \beta_i, d_i, \theta_i`."""
        p = joint.placement
        assert isinstance(p, HayatiPlacement)
        return p.alpha, p.a, p.beta, joint.offset, joint.angle

    def to_modified(self, robot: Robot) -> None:
        """None: the DH table is measured from the joint axes."""
        return None

    def from_modified(self, robot: Robot) -> None:
        """None: no conversion target."""
        return None


PLUGIN = Hayati()
