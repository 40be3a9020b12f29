r"""General joints, as URDF writes them: a fixed origin transform, then a motion about or along a constant unit axis.

Joint *i* is a fixed origin transform (``xyz`` and ``rpy``, or a 4 x 4 ``matrix``) followed by a rotation about, or
a translation along, a constant unit ``axis`` (default :math:`+z`, any direction and sign allowed). An exact constant
*alignment* rotation :math:`A_i` takes :math:`z` onto the axis (:func:`symjac.symbolic.transforms.alignment`), so
the joint has the internal form

.. math:: {}^{i-1}_{i}T = A_{i-1}^{-1}\,T_{\text{origin},i}\,A_i\,R_z(\theta_i)\,T_z(d_i), \qquad A_0 = I,

and frame {i} is the joint's child link frame turned by :math:`A_i`; its z-axis is the joint axis (as in the modified
convention, joint *i* moves about or along :math:`z_i`). The tool transform of a general robot is given relative to
frame {n} like every other tool.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.model.conventions.base import (
    Cell,
    Column,
    JointForm,
    JointReader,
    NoRobotFields,
    joint_form,
    transform_fields,
)
from symjac.model.expressions import expression_text
from symjac.model.robot import Convention, FixedTransform, Joint, Placement, Robot, unit_vector
from symjac.symbolic.transforms import Motion, alignment, compose, homogeneous, inverse_motions

__all__ = ["GENERAL", "PLUGIN", "General", "GeneralPlacement", "general_placement", "origin_motions"]

_ZERO = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
_ORIGIN_KEYS = ("xyz", "rpy", "matrix")


@dataclass(frozen=True)
class GeneralPlacement(Placement):
    """The ``origin`` of a general joint (``None`` is the identity) and its ``axis`` as given (``None`` is +z)."""

    origin: FixedTransform | None = None
    axis: tuple[sp.Expr, sp.Expr, sp.Expr] | None = None

    @property
    def unit_axis(self) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
        """The joint axis as an exact unit vector (``(0, 0, 1)`` unless another axis is given)."""
        return (sp.S.Zero, sp.S.Zero, sp.S.One) if self.axis is None else unit_vector(self.axis)


def general_placement(joint: Joint) -> GeneralPlacement:
    """The placement of a general ``joint`` (a ``TypeError`` naming the joint if it has another convention's)."""
    if not isinstance(joint.placement, GeneralPlacement):
        raise TypeError(f"joint {joint.index} is not a general joint (it has {type(joint.placement).__name__})")
    return joint.placement


def origin_motions(origin: FixedTransform | None) -> tuple[Motion | sp.Matrix, ...]:
    r"""The origin of a general joint as motions.

    .. math:: T(x, y, z)\,R_z(\text{yaw})\,R_y(\text{pitch})\,R_x(\text{roll})
    """
    if origin is None:
        return ()
    if origin.given_matrix is not None:
        return (sp.Matrix(origin.given_matrix),)
    (x, y, z), (roll, pitch, yaw) = origin.xyz, origin.rpy
    return (Motion("T", "x", x), Motion("T", "y", y), Motion("T", "z", z),
            Motion("R", "z", yaw), Motion("R", "y", pitch), Motion("R", "x", roll))


class General(NoRobotFields):
    """The plug-in of general (URDF-style) joints (see :class:`~symjac.model.conventions.base.ConventionPlugin`)."""

    convention = Convention.GENERAL
    table_name = "general chain (URDF-style origin and axis)"
    keys: tuple[str, ...] = ("xyz", "rpy", "matrix", "axis", "name")
    columns: tuple[Column, ...] = (Column("xyz"), Column("rpy"), Column("axis"), Column("d", "i"),
                                   Column("theta", "i"))

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[GeneralPlacement, str]:
        """Origin (``xyz``/``rpy`` or ``matrix``), ``axis`` (3 finite numbers, not zero) and ``name``."""
        origin = reader.transform([key for key in _ORIGIN_KEYS if key in table], "origin")
        axis = None
        if "axis" in table:
            entries = table["axis"]
            if not isinstance(entries, Sequence) or isinstance(entries, str) or len(entries) != 3:
                raise reader.fail("'axis' must be a list of 3 numbers", "axis")
            given = tuple(reader.value(entry, "axis") for entry in entries)
            numbers = [entry.subs(reader.defaults) for entry in given]
            if not all(entry.is_number and reader.is_finite(entry) for entry in numbers):
                raise reader.fail(f"'axis' must be 3 finite numbers, got {list(given)}", "axis")
            if max(abs(float(entry)) for entry in numbers) < 1e-9:  # no squares: [1e308, 0, 1] must not overflow
                raise reader.fail("'axis' must not be the zero vector", "axis")
            axis = None if given == (0, 0, 1) else given
        name = table.get("name", "")
        if not isinstance(name, str):
            raise reader.fail("'name' must be a string", "name")
        return GeneralPlacement(None if origin == FixedTransform() else origin, axis), name  # type: ignore[arg-type]

    def write(self, joint: Joint) -> dict[str, Any]:
        """``name``, the origin and ``axis`` when given, ``d`` and ``theta`` when not zero."""
        placement = general_placement(joint)
        row: dict[str, Any] = {"name": joint.name} if joint.name else {}
        if placement.origin is not None:
            row.update(transform_fields(placement.origin))
        if placement.axis is not None:
            row["axis"] = [expression_text(e) for e in placement.axis]
        row.update({key: expression_text(value) for key, value in (("d", joint.d), ("theta", joint.theta))
                    if value != 0})
        return row

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        r"""Each joint as :math:`A_{i-1}^{-1}\,T_{\text{origin},i}\,A_i` followed by :math:`R_z T_z`."""
        forms: list[JointForm] = []
        previous: tuple[Motion | sp.Matrix, ...] = ()
        for joint in robot.joints:
            placement = general_placement(joint)
            current = alignment(placement.unit_axis)
            before = (*inverse_motions(previous), *origin_motions(placement.origin), *current)
            forms.append(joint_form(joint, before=before))
            previous = current
        return tuple(forms)

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        """Origin ``xyz`` and ``rpy``, ``axis`` (vectors), the translation and the rotation about the axis."""
        placement = general_placement(joint)
        origin = placement.origin
        return (origin.xyz if origin else _ZERO, origin.rpy if origin else _ZERO, placement.axis or (0, 0, 1),
                joint.offset, joint.angle)

    def inertial_frames(self, robot: Robot) -> tuple[sp.Matrix | None, ...]:
        r"""The joint's child link frame, as URDF gives inertial data: :math:`A_i^{-1}` in frame {i}."""
        frames: list[sp.Matrix | None] = []
        for joint in robot.joints:
            placement = general_placement(joint)
            if placement.axis is None:
                frames.append(None)
                continue
            R, _ = compose(alignment(placement.unit_axis))
            frames.append(homogeneous(R.T, sp.zeros(3, 1)))
        return tuple(frames)

    def to_modified(self, robot: Robot) -> None:
        """None: a DH table is found from the joint axes (:func:`symjac.kinematics.convert.dh_from_general`)."""
        return None

    def from_modified(self, robot: Robot) -> None:
        """None: general is no conversion target."""
        return None


GENERAL = PLUGIN = General()
