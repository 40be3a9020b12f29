r"""The product of exponentials (Lynch and Park, *Modern Robotics*, chapter 4): a home pose and one screw per joint.

A robot is the pose :math:`M` of its tool frame at :math:`\theta = 0` and, per joint, a unit screw axis
:math:`\mathcal{S}_i = (\omega_i, v_i)` in the space frame {s} (angular part first):

.. math:: T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M

A revolute joint has :math:`|\omega_i| = 1` and :math:`v_i = -\omega_i \times q_i` for any point :math:`q_i` of its
axis; a prismatic one has :math:`\omega_i = 0`, :math:`|v_i| = 1`. With ``body = true`` the file gives the screws
:math:`\mathcal{B}_i` in the home tool frame instead, and :math:`\mathcal{S}_i = [\mathrm{Ad}_M]\,\mathcal{B}_i`.

The internal form is the one of general joints (:mod:`symjac.model.conventions.general`): at home, frame {i} sits at
a point :math:`q_i` of joint *i*'s axis with its z-axis along the axis, :math:`G_i = \mathrm{Trans}(q_i) A_i`
(:math:`A_i` the exact alignment of z with the axis; a prismatic joint keeps the point of the joint before it), and
link *i* is :math:`G_{i-1}^{-1} G_i R_z(\theta_i)` (:math:`T_z(d_i)` for a prismatic joint). Because
:math:`G_i R_z(\theta_i) G_i^{-1} = e^{[\mathcal{S}_i]\theta_i}`, the chain's :math:`{}^0T_n` is
:math:`e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} G_n`, and the tool transform, relative to
frame {n} like every tool, is :math:`G_n^{-1} M`. Frame {0} is the space frame {s}; the tool frame is the one
:math:`M` places.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, TypeAlias

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.bounds import size_problem
from symjac.model.conventions.base import Cell, Column, JointForm, JointReader, NoRobotFields, transform_fields
from symjac.model.conventions.general import GENERAL, GeneralPlacement
from symjac.model.conventions.rounding import short, unit, zero_pitch
from symjac.model.exact_transforms import fixed_transform_from_matrix
from symjac.model.expressions import exact_number, expression_text
from symjac.model.robot import (
    Convention,
    FixedTransform,
    Joint,
    JointType,
    Placement,
    Robot,
)
from symjac.symbolic.nested import has_intermediates, inline
from symjac.symbolic.transforms import adjoint, alignment, compose, homogeneous, inverse_transform

__all__ = ["PLUGIN", "POE", "PRODUCT_OF_EXPONENTIALS", "ProductOfExponentials", "ScrewPlacement", "as_general",
           "home_pose", "screw_placement", "space_screws"]

Vector: TypeAlias = tuple[sp.Expr, sp.Expr, sp.Expr]

PRODUCT_OF_EXPONENTIALS = Convention.register("poe")
"""The convention's value, ``Convention("poe")``."""

_ZERO: Vector = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
_LONG_NUMBER = 60
"""Characters beyond which a radical number (sqrt of a 13-digit integer) is written to double precision."""
_TEXTBOOK_CHARS = 12
"""The longest exact form of a measured number (``-sqrt(3)/2``, ``3*pi/4``) taken for it; longer: the decimal."""
_TRANSCENDENTAL_OPS = 6
"""How many operations a number made of sines and cosines of generic angles may keep exactly (``cos(3/10)`` is 1)."""


@dataclass(frozen=True)
class ScrewPlacement(Placement):
    r"""A joint's screw axis in the space frame, exact: :math:`\omega` (unit, or zero for a prismatic joint) and v.

    ``point`` is the point of a revolute axis the file gave (in {s}), ``None`` when it gave the screw itself;
    ``body`` says that the file gave the screw in the home tool frame (``given``, written back that way).
    """

    omega: Vector = _ZERO
    v: Vector = _ZERO
    point: Vector | None = None
    body: bool = False
    given: tuple[Vector, Vector, Vector | None] | None = field(default=None, compare=False)
    r"""For ``body``: :math:`\omega, v` and the point as the file gave them, in the home tool frame."""
    home: FixedTransform | None = field(default=None, compare=False)
    """The home pose M in the form the file gave it (every joint holds it), to write it back that way."""

    @property
    def screw(self) -> tuple[sp.Expr, ...]:
        r""":math:`(\omega_x, \omega_y, \omega_z, v_x, v_y, v_z)`."""
        return (*self.omega, *self.v)


def screw_placement(joint: Joint) -> ScrewPlacement:
    """The screw of ``joint`` (a ``TypeError`` naming the joint if it has another convention's placement)."""
    if not isinstance(joint.placement, ScrewPlacement):
        raise TypeError(f"joint {joint.index} has no screw axis (it has {type(joint.placement).__name__})")
    return joint.placement


def space_screws(robot: Robot) -> tuple[tuple[sp.Expr, ...], ...]:
    r"""Each joint's screw axis :math:`\mathcal{S}_i = (\omega_i, v_i)` in the space frame, of a PoE robot."""
    return tuple(screw_placement(joint).screw for joint in robot.joints)


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Sums of exact numbers and parameters multiplied out.

    Sines and cosines of constants (generic DH twists) are left as they are: expanding products of them only grows
    them.
    """
    if expr.has(sp.sin, sp.cos):
        return expr
    return sp.radsimp(sp.expand(expr))


def _settled(expr: sp.Expr) -> sp.Expr:
    """:func:`_tidy`, and a number that stays a long radical (a calibrated file's) to double precision."""
    expr = _tidy(expr)
    if expr.is_number and not expr.is_Rational and expr.has(sp.Pow) and len(str(expr)) > _LONG_NUMBER:
        return exact_number(float(expr))
    return expr


def _vector(values: Sequence[sp.Expr]) -> Vector:
    x, y, z = (_tidy(sp.sympify(e)) for e in values)
    return x, y, z


def _axis_point(placement: ScrewPlacement) -> Vector:
    r"""A point of a revolute axis: the one given, or the one nearest the origin, :math:`q = \omega \times v`."""
    if placement.point is not None:
        return placement.point
    return _vector(sp.Matrix(placement.omega).cross(sp.Matrix(placement.v)))


def _direction(joint: Joint) -> Vector:
    placement = screw_placement(joint)
    return placement.omega if joint.is_revolute else placement.v


def _home_frames(joints: Sequence[Joint]) -> list[tuple[Vector, Vector]]:
    """Per joint, where its frame sits at home: the point :math:`q_i` and the axis direction."""
    frames, point = [], _ZERO
    for joint in joints:
        if joint.is_revolute:
            point = _axis_point(screw_placement(joint))
        frames.append((point, _direction(joint)))
    return frames


def _frame_matrix(point: Vector, direction: Vector) -> sp.Matrix:
    r""":math:`G = \mathrm{Trans}(q) A`."""
    rotation, _ = compose(alignment(direction))
    return homogeneous(rotation, sp.Matrix(point))


def _tool(joints: Sequence[Joint], home: sp.MatrixBase) -> FixedTransform:
    r"""The tool relative to frame {n}: :math:`G_n^{-1} M`."""
    point, direction = _home_frames(joints)[-1]
    matrix = (inverse_transform(_frame_matrix(point, direction)) * sp.Matrix(home)).applyfunc(_settled)
    return FixedTransform(given_matrix=sp.ImmutableMatrix(matrix))


def home_pose(robot: Robot) -> sp.Matrix:
    r"""The home pose :math:`M` of the tool frame in {s}: :math:`G_n` times the tool transform."""
    point, direction = _home_frames(robot.joints)[-1]
    tool = robot.tool.matrix if robot.tool is not None else sp.eye(4)
    return (_frame_matrix(point, direction) * sp.Matrix(tool)).applyfunc(_settled)


def as_general(robot: Robot) -> Robot:
    r"""A PoE ``robot`` as general joints: the same chain, frame by frame.

    Joint *i* gets the origin :math:`\mathrm{Trans}(q_i - q_{i-1})` and the axis :math:`\omega_i` (or :math:`v_i`);
    the tool transform is the same.
    """
    joints, previous = [], _ZERO
    for joint, (point, direction) in zip(robot.joints, _home_frames(robot.joints), strict=True):
        shift = _vector([a - b for a, b in zip(point, previous, strict=True)])
        origin = None if shift == _ZERO else FixedTransform(xyz=shift)
        axis = None if direction == (0, 0, 1) else direction
        joints.append(replace(joint, placement=GeneralPlacement(origin, axis)))
        previous = point
    return replace(robot, convention=Convention.GENERAL, joints=tuple(joints))


class ProductOfExponentials(NoRobotFields):
    """The plug-in of the product of exponentials (see :class:`~symjac.model.conventions.base.ConventionPlugin`)."""

    convention = PRODUCT_OF_EXPONENTIALS
    table_name = "screw axes in the space frame (product of exponentials)"
    keys: tuple[str, ...] = ("screw", "axis", "point", "name")
    columns: tuple[Column, ...] = (Column("omega", "i"), Column("v", "i"), Column("q", "i"))
    robot_keys: tuple[str, ...] = ("home", "body")
    owns_tool = True
    tool_note = "the [home] table places the tool frame (M, its pose at q = 0)"

    def read_settings(self, data: Mapping[str, Any], transform: Callable[[str], FixedTransform],
                      fail: Callable[[str, str], RobotFileError]) -> Mapping[str, Any]:
        """``home`` (required: the matrix M, or ``xyz`` and ``rpy``; checked to be rigid) and ``body``."""
        if "home" not in data:
            raise fail("'home' is required for the poe convention: the pose M of the tool frame at q = 0, as a "
                       "[home] table with 'matrix', or 'xyz' and 'rpy'", "home")
        body = data.get("body", False)
        if not isinstance(body, bool):
            raise fail(f"'body' must be true (screws in the home tool frame) or false (in the space frame), got "
                       f"{body!r}", "body")
        home = transform("home")
        return {"home": home.matrix, "given_home": home, "body": body}

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[ScrewPlacement, str]:
        """``screw``, or ``axis`` and ``point`` (revolute) or ``axis`` alone (prismatic), and ``name``."""
        for key in ("d", "theta"):
            if key in table:
                raise reader.fail(f"'{key}' has no place in a product of exponentials: the home pose [home] holds "
                                  f"every offset", key)
        revolute = table.get("type") == JointType.REVOLUTE.value
        if "screw" in table and ("axis" in table or "point" in table):
            raise reader.fail("give either 'screw' or 'axis' (and 'point'), not both", "screw")

        def vector(key: str, length: int) -> tuple[sp.Expr, ...]:
            entries = table[key]
            if not isinstance(entries, Sequence) or isinstance(entries, str) or len(entries) != length:
                raise reader.fail(f"'{key}' must be a list of {length} numbers or expressions, got {entries!r}", key)
            values = tuple(reader.value(entry, key) for entry in entries)
            for index, value in enumerate(values):
                number = value.subs(reader.defaults)
                if not reader.is_finite(number):
                    raise reader.fail(f"'{key}' entry {value} is not a finite number once parameters take their "
                                      f"defaults", key)
                lengths = key == "point" or (key == "screw" and index >= 3)  # v = -w x q is a length too
                problem = size_problem(float(number), angle=False) if lengths else None
                if problem is not None:
                    raise reader.fail(f"'{key}' entry {short(value)} = {problem}", key)
            return values

        point: Vector | None = None
        if "screw" in table:
            screw = vector("screw", 6)
            omega, v = _vector(screw[:3]), _vector(screw[3:])
            written: tuple[Vector, Vector, Vector | None] = (omega, v, None)
            if revolute:
                omega = unit(omega, "a revolute screw's w", "screw", reader)
                v = _vector(zero_pitch(omega, v, reader))
            else:
                if omega != _ZERO:
                    raise reader.fail(f"a prismatic joint's screw has w = 0 (it translates along v), got w = "
                                      f"{list(omega)}", "screw")
                v = unit(v, "a prismatic screw's v", "screw", reader)
        elif "axis" in table:
            given_axis = _vector(vector("axis", 3))
            axis = unit(given_axis, "'axis'", "axis", reader)
            if revolute:
                if "point" not in table:
                    raise reader.fail("a revolute 'axis' needs a 'point' on it (or give the 'screw')", "point")
                point = _vector(vector("point", 3))
                omega, v = axis, _vector(sp.Matrix(point).cross(sp.Matrix(axis)))  # v = -w x q
                written = (given_axis, v, point)
            else:
                if "point" in table:
                    raise reader.fail("a prismatic joint has no 'point': its 'axis' is the direction it slides in",
                                      "point")
                omega, v = _ZERO, axis
                written = (_ZERO, given_axis, None)
        else:
            raise reader.fail("give the joint's 'screw' (w then v, 6 entries) or its 'axis' (and a 'point' on it)",
                              "screw")
        name = table.get("name", "")
        if not isinstance(name, str):
            raise reader.fail("'name' must be a string", "name")
        home, given_home = reader.settings["home"], reader.settings["given_home"]
        # written back as the file gave it: a 6-digit axis stays 6 digits, not its normalised double
        given = written if written != (omega, v, point) else None
        if reader.settings["body"]:
            return ScrewPlacement(*self._to_space(omega, v, point, home), True, given or (omega, v, point),
                                  given_home), name
        return ScrewPlacement(omega, v, point, given=given, home=given_home), name

    @staticmethod
    def _to_space(omega: Vector, v: Vector, point: Vector | None, home: sp.MatrixBase
                  ) -> tuple[Vector, Vector, Vector | None]:
        r""":math:`\mathcal{S} = [\mathrm{Ad}_M]\,\mathcal{B}`, and the point :math:`M q`."""
        screw = adjoint(home) * sp.Matrix([*omega, *v])
        moved = None if point is None else _vector(sp.Matrix(home[:3, :3]) * sp.Matrix(point) + home[:3, 3])
        return _vector(screw[:3]), _vector(screw[3:]), moved

    def tool(self, joints: Sequence[Joint], settings: Mapping[str, Any]) -> FixedTransform:
        r"""The tool relative to frame {n}: :math:`G_n^{-1} M`."""
        return _tool(joints, settings["home"])

    def write(self, joint: Joint) -> dict[str, Any]:
        """``name``, then ``axis`` and ``point`` if the file gave them, else ``screw`` (in the frame the file used)."""
        placement = screw_placement(joint)
        omega, v, point = placement.given or (placement.omega, placement.v, placement.point)
        row: dict[str, Any] = {"name": joint.name} if joint.name else {}
        if point is not None:
            row["axis"] = [expression_text(e) for e in omega]
            row["point"] = [expression_text(e) for e in point]
        else:
            row["screw"] = [expression_text(e) for e in (*omega, *v)]
        return row

    def write_settings(self, robot: Robot) -> dict[str, Any]:
        """``body`` when true, and ``home``: M as the file gave it.

        A converted robot's M is written as ``xyz``/``rpy`` when its angles are exact, else as a matrix.
        """
        body = any(screw_placement(joint).body for joint in robot.joints)
        fields: dict[str, Any] = {"body": True} if body else {}
        given = screw_placement(robot.joints[-1]).home
        fields["home"] = transform_fields(given or fixed_transform_from_matrix(home_pose(robot)))
        return fields

    def inertial_frames(self, robot: Robot) -> tuple[sp.Matrix | None, ...]:
        r"""The frame the screws are written in, at home: {s} (:math:`G_i^{-1}` in {i}), or {b} (:math:`G_i^{-1} M`)."""
        body = any(screw_placement(joint).body for joint in robot.joints)
        home = home_pose(robot) if body else sp.eye(4)
        return tuple((inverse_transform(_frame_matrix(point, direction)) * home).applyfunc(_tidy)
                     for point, direction in _home_frames(robot.joints))

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        r"""The forms of :func:`as_general`: :math:`G_{i-1}^{-1} G_i` before :math:`R_z T_z`."""
        return GENERAL.forms(as_general(robot))

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        r""":math:`\omega_i`, :math:`v_i` and, for a revolute joint, a point :math:`q_i` of its axis (space frame)."""
        placement = screw_placement(joint)
        point = _axis_point(placement) if joint.is_revolute else ()
        return placement.omega, placement.v, point  # type: ignore[return-value]

    def to_modified(self, robot: Robot) -> None:
        """None: a DH table is found from the joint axes (:func:`symjac.kinematics.convert.dh_from_general`)."""
        return None

    def from_modified(self, robot: Robot) -> None:
        """None: DH robots become screws from their axes (:meth:`from_axes`), not from their table."""
        return None

    def from_axes(self, robot: Robot, axes: Callable[[], tuple[Sequence[sp.MatrixBase], sp.MatrixBase]]) -> Robot:
        r"""Any ``robot`` as screws: each joint's axis and point, and M, at :math:`\theta = 0`.

        ``axes()`` gives the pose in {0} at home of each joint's axis frame (z along the axis) and of the tool frame
        (frame {n} without a tool). Revolute joints are written by axis and point (that frame's origin), prismatic ones
        by their screw; joint variables, limits, names, parameters and the base are kept.
        """
        frames, pose = axes()
        zero = dict.fromkeys(robot.joint_variables, sp.S.Zero)  # inside the intermediates too
        frames, pose = [_inlined(frame).xreplace(zero) for frame in frames], _inlined(pose).xreplace(zero)
        home = sp.Matrix(pose).applyfunc(_exact)
        simple = all(e.is_Rational or (e.has(sp.pi) and not e.has(sp.sin, sp.cos)) for e in home[:3, :3])
        given = fixed_transform_from_matrix(home) if simple else FixedTransform(given_matrix=sp.ImmutableMatrix(home))
        joints = []
        for joint, frame in zip(robot.joints, frames, strict=True):
            frame = sp.Matrix(frame).applyfunc(_exact)
            axis, origin = _vector(frame[:3, 2]), _vector(frame[:3, 3])
            if joint.is_revolute:
                placement = ScrewPlacement(axis, _vector(sp.Matrix(origin).cross(sp.Matrix(axis))), origin, home=given)
            else:
                placement = ScrewPlacement(_ZERO, axis, home=given)
            joints.append(Joint(index=joint.index, type=joint.type, placement=placement, limits=joint.limits,
                                name=joint.name))
        return replace(robot, convention=self.convention, joints=tuple(joints), tool=_tool(joints, home))

    def rewrite(self, robot: Robot, target: Convention) -> Robot | None:
        """A PoE ``robot`` as general joints (:func:`as_general`); other targets go through a DH table."""
        return as_general(robot) if target is Convention.GENERAL else None


def _textbook(number: sp.Float) -> sp.Expr:
    """A float as the short exact number it rounds (1/2, sqrt(3)/2, pi/4), else its shortest decimal, exactly.

    ``nsimplify`` alone finds an "exact" form for any float (``2**(93/197)*3**(717/985)*...``): only short ones
    are textbook numbers.
    """
    guess = sp.nsimplify(number, [sp.pi], tolerance=1e-12)
    if len(str(guess)) <= _TEXTBOOK_CHARS and not any(p.exp.is_Rational and p.exp.q > 2 for p in guess.atoms(sp.Pow)):
        return guess
    return exact_number(float(number))


def _inlined(matrix: sp.MatrixBase) -> sp.Matrix:
    """A pose at home of a nested chain (generic geometry) written out: numbers, or expressions of parameters."""
    return sp.Matrix(matrix.rows, matrix.cols, inline(list(matrix))) if has_intermediates(matrix) else matrix


def _exact(expr: sp.Expr) -> sp.Expr:
    """An entry of a transform at home, as simple as exact algebra makes it, and short enough for a robot file.

    An entry that stays a long combination of sines and cosines of generic angles (DH twists and offsets like 0.3
    rad) is written with its coefficients to double precision: kept exact, they make every later product grow.
    """
    expr = expr.xreplace({f: _textbook(f) for f in expr.atoms(sp.Float)})
    if not expr.has(sp.sin, sp.cos):
        return _tidy(expr)
    expr = sp.trigsimp(expr) if sp.count_ops(expr) <= 40 else expr
    if sp.count_ops(expr) <= _TRANSCENDENTAL_OPS:
        return expr
    # exact algebra on it would only slow everything after: each coefficient of the parameters to double precision
    symbols = sorted(expr.free_symbols, key=str)
    if not symbols:
        return exact_number(float(expr))
    terms = sp.collect(sp.expand(expr), symbols, evaluate=False)
    return sum(((exact_number(float(c)) if c.is_number else c) * monomial for monomial, c in terms.items()), sp.S.Zero)


POE = PLUGIN = ProductOfExponentials()
