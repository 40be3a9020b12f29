r"""What a convention plug-in is: the one internal joint form it produces, and what it tells readers and printers.

Every convention writes link *i* as constant motions, the joint's own motion, and constant motions again:

.. math:: {}^{i-1}_{i}T = B_i\,R_z(\theta_i + \theta)\,T_z(d_i + d)\,E_i

(the variable is :math:`\theta_i` for a revolute joint, :math:`d_i` for a prismatic one). Standard DH has
:math:`B_i = I, E_i = T_x(a_i) R_x(\alpha_i)`; modified DH :math:`B_i = R_x(\alpha_{i-1}) T_x(a_{i-1}), E_i = I`;
a general (URDF-style) joint :math:`B_i = A_{i-1}^{-1} T_\text{origin} A_i, E_i = I`. At most one of :math:`B_i`,
:math:`E_i` may hold motions, so the joint axis is the z-axis of frame {i-1} (when :math:`E_i` is not empty) or of
frame {i}: the chain needs nothing else to find its axes and the relation between consecutive ones.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol, TypeAlias

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.expressions import expression_text
from symjac.model.inertia import Inertial
from symjac.model.robot import Convention, FixedTransform, Joint, Placement, Robot
from symjac.symbolic.transforms import Motion

__all__ = ["Cell", "Column", "ConventionPlugin", "JointForm", "JointReader", "NoRobotFields", "joint_form",
           "moved_inertial", "transform_fields"]

Step: TypeAlias = Motion | sp.Matrix
Cell: TypeAlias = sp.Expr | tuple[sp.Expr, ...]
"""One entry of a convention's table: an expression, or a vector (printed in brackets)."""


@dataclass(frozen=True)
class JointForm:
    r"""Link *i* in the one internal form: ``before``, then :math:`R_z(\text{angle})\,T_z(\text{offset})`, ``after``."""

    before: tuple[Step, ...]
    angle: sp.Expr
    offset: sp.Expr
    after: tuple[Step, ...] = ()

    def __post_init__(self) -> None:
        """Refuse constant motions on both sides: then no frame of the chain would carry the joint axis."""
        if self.before and self.after:
            raise ValueError("a joint form has constant motions before or after the joint motion, not both")

    @property
    def motions(self) -> tuple[Step, ...]:
        """The link transform as elementary motions (and constant 4 x 4 transforms), in order."""
        return (*self.before, Motion("R", "z", self.angle), Motion("T", "z", self.offset), *self.after)

    @property
    def axis_at_start(self) -> bool:
        """Whether the joint axis is the z-axis of the frame before the link (else of the frame after it)."""
        return bool(self.after)


def joint_form(joint: Joint, before: Sequence[Step] = (), after: Sequence[Step] = ()) -> JointForm:
    """The internal form of ``joint`` with these constant motions around its own motion."""
    return JointForm(tuple(before), joint.angle, joint.offset, tuple(after))


@dataclass(frozen=True)
class Column:
    r"""A table column heading: a symbol with a subscript (``alpha``, ``i-1``), or a plain word (``xyz``)."""

    symbol: str
    subscript: str = ""


class JointReader(Protocol):
    """What a plug-in gets to read one joint table of a robot file; every error names the file, joint and field."""

    defaults: Mapping[sp.Symbol, sp.Rational]
    """The parameters' numeric defaults (to check that a value is a finite number)."""

    def value(self, raw: Any, field: str, *, angle: bool = False) -> sp.Expr:
        """``raw`` (a number or an expression in the parameters) parsed; angles scaled by the file's angle unit."""

    def number(self, key: str, *, angle: bool = False) -> sp.Expr:
        """The value under ``key`` (0 if absent), checked to be finite once parameters take their defaults."""

    def transform(self, keys: Sequence[str], field: str) -> FixedTransform:
        """A fixed transform from the ``xyz``/``rpy`` or ``matrix`` entries among ``keys`` (identity if none)."""

    @property
    def settings(self) -> Mapping[str, Any]:
        """What the convention read from the file's top level (:meth:`ConventionPlugin.read_settings`)."""

    def fail(self, message: str, field: str | None = None) -> RobotFileError:
        """The error to raise for this joint (and ``field``)."""

    def is_finite(self, number: sp.Expr) -> bool:
        """Whether ``number`` is a finite real number."""


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Multiplied out exactly; sines and cosines of constant angles (rpy = 0.3) squared and summed to one."""
    expr = sp.radsimp(sp.expand(expr))
    return sp.trigsimp(expr) if expr.has(sp.sin, sp.cos) else expr


def moved_inertial(inertial: Inertial | None, T: sp.MatrixBase | None) -> Inertial | None:
    """``inertial`` seen from a frame in which its own frame sits at ``T`` (unchanged when either is None)."""
    if inertial is None or T is None:
        return inertial
    moved = inertial.expressed_in(T)
    return Inertial(moved.mass, tuple(map(_tidy, moved.com)), moved.inertia.applyfunc(_tidy),  # type: ignore[arg-type]
                    moved.given_about, moved.keep_impossible)


def transform_fields(transform: FixedTransform) -> dict[str, Any]:
    """The robot-file fields of a fixed transform: ``matrix``, or ``xyz`` and ``rpy``."""
    if transform.given_matrix is not None:
        return {"matrix": [[expression_text(e) for e in transform.given_matrix.row(r)] for r in range(4)]}
    return {"xyz": [expression_text(e) for e in transform.xyz], "rpy": [expression_text(e) for e in transform.rpy]}


class ConventionPlugin(Protocol):
    """A convention: how its rows become :class:`JointForm` s and what readers, printers and converters need.

    Attributes are data; methods are pure functions of the robot. :mod:`symjac.model.conventions` keeps one per
    :class:`~symjac.model.robot.Convention` value.
    """

    convention: Convention
    table_name: str
    """What its table is called in a caption (``"standard Denavit-Hartenberg table"``)."""
    keys: tuple[str, ...]
    """The keys of a robot-file joint table besides ``type``, ``d``, ``theta`` and ``limits``."""
    columns: tuple[Column, ...]
    """The table columns after the joint number and type."""

    def read(self, table: Mapping[str, Any], reader: JointReader) -> tuple[Placement, str]:
        """The placement (and the joint's name, or ``""``) of one robot-file joint table."""

    def write(self, joint: Joint) -> dict[str, Any]:
        """The robot-file fields of ``joint`` besides ``type`` and ``limits``, in the order they are written."""

    def forms(self, robot: Robot) -> tuple[JointForm, ...]:
        """Each joint of ``robot`` in the internal form."""

    def cells(self, joint: Joint) -> tuple[Cell, ...]:
        """The entries of ``joint``'s table row under :attr:`columns`."""

    def to_modified(self, robot: Robot) -> Robot | None:
        """The same kinematics as an exact modified-DH table rewrite, or ``None`` (then the axes are measured)."""

    def from_modified(self, robot: Robot) -> Robot | None:
        """A modified-DH ``robot`` rewritten in this convention, or ``None`` if it cannot be a conversion target."""

    def from_axes(self, robot: Robot, axes: Callable[[], tuple[Sequence[sp.MatrixBase], sp.MatrixBase]]
                  ) -> Robot | None:
        """Any ``robot`` rewritten in this convention from its joint axes at home, or ``None`` to go through DH.

        ``axes()`` gives the poses in {0} at :math:`q = 0` of each joint's axis frame and of the tool frame.
        """

    def rewrite(self, robot: Robot, target: Convention) -> Robot | None:
        """A ``robot`` of this convention rewritten in ``target`` directly, or ``None`` (then :meth:`from_axes`)."""

    robot_keys: tuple[str, ...]
    """Top-level robot-file keys this convention reads besides the common ones (the product of exponentials: ``home``
    and ``body``)."""
    owns_tool: bool
    """Whether the convention places the tool itself (then a file's ``tool`` is refused and never written)."""
    tool_note: str
    """Where such a convention's files place the tool instead (said when a file gives ``tool``)."""

    def read_settings(self, data: Mapping[str, Any], transform: Callable[[str], FixedTransform],
                      fail: Callable[[str, str], RobotFileError]) -> Mapping[str, Any]:
        """The top-level fields under :attr:`robot_keys`, read before the joints.

        ``transform(key)`` reads a ``xyz``/``rpy`` or ``matrix`` table; ``fail(message, field)`` is the error to raise.
        """

    def tool(self, joints: Sequence[Joint], settings: Mapping[str, Any]) -> FixedTransform | None:
        """The tool transform the convention places (when :attr:`owns_tool`), from the joints read."""

    def write_settings(self, robot: Robot) -> dict[str, Any]:
        """The top-level robot-file fields under :attr:`robot_keys`, as :meth:`read_settings` reads them."""

    def inertial_frames(self, robot: Robot) -> tuple[sp.Matrix | None, ...]:
        """Per link, the pose in frame {i} of the frame its robot-file ``inertial`` table is written in (None: {i})."""


class NoRobotFields:
    """The defaults of a convention that reads joint tables only (both DH conventions, general joints)."""

    robot_keys: tuple[str, ...] = ()
    owns_tool = False
    tool_note = ""

    def read_settings(self, data: Mapping[str, Any], transform: Callable[[str], FixedTransform],
                      fail: Callable[[str, str], RobotFileError]) -> Mapping[str, Any]:
        """Nothing."""
        return {}

    def tool(self, joints: Sequence[Joint], settings: Mapping[str, Any]) -> FixedTransform | None:
        """None: the file's ``tool`` is the tool."""
        return None

    def write_settings(self, robot: Robot) -> dict[str, Any]:
        """Nothing."""
        return {}

    def inertial_frames(self, robot: Robot) -> tuple[sp.Matrix | None, ...]:
        """Frame {i} itself: a DH table's link frames are the ones textbooks give inertial parameters in."""
        return (None,) * robot.n_joints

    def from_axes(self, robot: Robot, axes: Callable[[], tuple[Sequence[sp.MatrixBase], sp.MatrixBase]]
                  ) -> Robot | None:
        """None: conversions go through a modified-DH table."""
        return None

    def rewrite(self, robot: Robot, target: Convention) -> Robot | None:
        """None: conversions go through a modified-DH table."""
        return None
