r"""The robot model: a validated serial chain as immutable data, in the words of its convention.

Notation (Craig), used throughout symjac: ``T_0_3`` is the pose of frame {3} relative to frame {0}, so
``T_0_3 = T_0_1 @ T_1_2 @ T_2_3`` (inner indices cancel); likewise ``R_0_3``, ``p_0_3`` and ``z_0_i`` (the z-axis of
frame {i} expressed in {0}).

Every robot file states its convention (there is no default); each is a plug-in of :mod:`symjac.model.conventions`:

* ``standard`` DH: :math:`{}^{i-1}_{i}T = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)`; joint *i* moves about or
  along :math:`z_{i-1}`;
* ``modified`` DH (Craig): :math:`{}^{i-1}_{i}T = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)`; joint *i*
  moves about or along :math:`z_i`;
* ``general`` (as URDF writes a chain): a fixed origin transform, then a motion about or along a constant unit axis;
  frame {i} is turned so that its z-axis is the joint axis.

A :class:`Joint` holds what every convention shares, the kind of joint and the offsets of its own motion
:math:`R_z(\theta_i + \theta)\,T_z(d)` (revolute; :math:`R_z(\theta)\,T_z(d_i + d)` prismatic), and its convention's
:class:`Placement` record (``DHPlacement(alpha, a)``, ``GeneralPlacement(origin, axis)``) for the constant motions
around it. Revolute joint *i* has the variable ``theta{i}``; prismatic joint *i* has ``d{i}``. Constant parameters keep
the names the file gives them (``a2``, ``d4``, ``L1``) as real SymPy symbols, with exact numeric defaults that are
used only where numbers are asked for.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum
from typing import ClassVar, Literal

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.coordinates import Coupling, acceleration_symbol, coupling_problem, rate_symbol
from symjac.model.drive import Drive, checked_drives
from symjac.model.hashing import cached_hash
from symjac.model.inertia import Inertial, inertial_problem
from symjac.symbolic.transforms import homogeneous, rotation_rpy

__all__ = ["VELOCITY_NAMES", "WRENCH_NAMES", "Convention", "FixedTransform", "Joint", "JointType", "Parameter",
           "Placement", "Robot", "reserved_names", "unit_vector"]

WRENCH_NAMES: tuple[str, ...] = ("f_x", "f_y", "f_z", "n_x", "n_y", "n_z")
"""The components of a symbolic wrench (:func:`symjac.wrench_symbols`): force first, then moment."""

VELOCITY_NAMES: tuple[str, ...] = ("v_x", "v_y", "v_z", "omega_x", "omega_y", "omega_z")
"""The six rows of a basic Jacobian, linear velocity first (:data:`symjac.kinematics.jacobian.ROW_NAMES`), and the
symbols of commanded velocity components (:data:`symjac.analysis.inverse_rates.RATE_SYMBOLS`)."""


class Convention(str):
    """The name of a registered convention: how a robot description writes its links.

    The built-in values are ``Convention.STANDARD``, ``Convention.MODIFIED`` and ``Convention.GENERAL``; a convention
    plug-in (:mod:`symjac.model.conventions`) registers its own with :meth:`register`. Values are interned, so
    ``Convention("modified") is Convention.MODIFIED``, and compare equal to their text.

    Examples
    --------
    >>> Convention("modified") is Convention.MODIFIED, Convention.MODIFIED == "modified"
    (True, True)
    """

    __slots__ = ()
    _registered: ClassVar[dict[str, Convention]] = {}
    STANDARD: ClassVar[Convention]
    MODIFIED: ClassVar[Convention]
    GENERAL: ClassVar[Convention]

    def __new__(cls, value: str) -> Convention:
        """The registered convention named ``value`` (``ValueError`` if there is none)."""
        if value in cls._registered:
            return cls._registered[value]
        raise ValueError(f"{value!r} is not a convention; registered: {', '.join(cls._registered)}")

    @classmethod
    def register(cls, name: str) -> Convention:
        """Register ``name`` (once) and return its value."""
        if name not in cls._registered:
            cls._registered[name] = str.__new__(cls, name)
        return cls._registered[name]

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """Every registered name, in the order of registration."""
        return tuple(cls._registered)

    @property
    def value(self) -> str:
        """The name as plain text (as an enum value would give it)."""
        return str.__str__(self)

    def __repr__(self) -> str:
        """``Convention('standard')``."""
        return f"Convention({self.value!r})"


Convention.STANDARD = Convention.register("standard")
Convention.MODIFIED = Convention.register("modified")
Convention.GENERAL = Convention.register("general")


class JointType(StrEnum):
    """Kind of a joint: rotation about, or translation along, its z-axis."""

    REVOLUTE = "revolute"
    PRISMATIC = "prismatic"


@dataclass(frozen=True)
class Parameter:
    """A named constant of the robot with its exact numeric default.

    ``inertial`` marks the symbolic inertial ones (``m2``, ``Ixx2``, ...), which only the dynamics read.
    """

    name: str
    default: sp.Rational
    inertial: bool = False

    @property
    def symbol(self) -> sp.Symbol:
        """The real SymPy symbol that stands for this parameter in derivations."""
        return sp.Symbol(self.name, real=True)


@dataclass(frozen=True)
class Placement:
    """Where a joint sits relative to the one before it, in the words of its convention (a plug-in's record).

    Each convention of :mod:`symjac.model.conventions` subclasses it: ``DHPlacement(alpha, a)`` for both DH
    conventions, ``GeneralPlacement(origin, axis)`` for URDF-style joints. The plug-in turns it into the constant
    motions of the one internal joint form (:class:`symjac.model.conventions.JointForm`).
    """


@dataclass(frozen=True)
class Joint:
    r"""One joint: its kind, its convention's :class:`Placement`, and the offsets of its own motion.

    Every convention moves joint *i* by :math:`R_z(\theta_i + \theta)\,T_z(d)` (revolute) or
    :math:`R_z(\theta)\,T_z(d_i + d)` (prismatic) about its own axis: ``theta`` and ``d`` are those constant
    offsets; the constant motions around it come from ``placement``. ``name`` is the joint's name as the robot file
    or URDF writes it (empty when it gives none), ``continuous`` whether the file says the joint turns without end
    (URDF's ``continuous`` type: a revolute joint without ``limits``); like ``name`` it takes no part in equality.
    """

    index: int
    type: JointType
    placement: Placement
    d: sp.Expr = sp.S.Zero
    theta: sp.Expr = sp.S.Zero
    limits: tuple[sp.Expr, sp.Expr] | None = None
    name: str = field(default="", compare=False)
    continuous: bool = field(default=False, compare=False)  # a URDF "continuous" joint: revolute, never limited

    @property
    def is_revolute(self) -> bool:
        """Whether the joint rotates (its variable is an angle)."""
        return self.type is JointType.REVOLUTE

    @property
    def variable(self) -> sp.Symbol:
        """The joint variable: ``theta{i}`` for a revolute joint, ``d{i}`` for a prismatic one."""
        return sp.Symbol(f"{self._prefix}{self.index}", real=True)

    @property
    def rate(self) -> sp.Symbol:
        r"""The joint rate :math:`\dot\theta_i` (``thetadot{i}``) or :math:`\dot d_i` (``ddot{i}``)."""
        return sp.Symbol(f"{self._prefix}dot{self.index}", real=True)

    @property
    def acceleration(self) -> sp.Symbol:
        r"""The joint acceleration :math:`\ddot\theta_i` (``thetaddot{i}``) or :math:`\ddot d_i` (``dddot{i}``)."""
        return sp.Symbol(f"{self._prefix}ddot{self.index}", real=True)

    @property
    def _prefix(self) -> str:
        return "theta" if self.is_revolute else "d"

    @property
    def angle(self) -> sp.Expr:
        """The rotation about z of this link: variable plus offset (revolute) or the constant (prismatic)."""
        return self.variable + self.theta if self.is_revolute else self.theta

    @property
    def offset(self) -> sp.Expr:
        """The translation along z of this link: variable plus offset (prismatic) or the constant (revolute)."""
        return self.d if self.is_revolute else self.variable + self.d


def unit_vector(vector: Sequence[sp.Expr]) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """``vector / |vector|`` exactly (``(0, 707107/10**6, 707107/10**6)`` gives ``(0, sqrt(2)/2, sqrt(2)/2)``)."""
    x, y, z = (sp.nsimplify(v) if isinstance(v, sp.Float) else sp.sympify(v) for v in vector)
    norm = sp.sqrt(x**2 + y**2 + z**2)
    return sp.radsimp(x / norm), sp.radsimp(y / norm), sp.radsimp(z / norm)


@dataclass(frozen=True)
class FixedTransform:
    r"""A constant rigid transform (base or tool), kept in the form it was given so it can be written back.

    Either ``xyz`` and ``rpy`` (roll about x, then pitch about y, then yaw about z, all about fixed axes:
    :math:`R = R_z(\text{yaw}) R_y(\text{pitch}) R_x(\text{roll})`), or a full 4 x 4 ``given_matrix``.
    """

    xyz: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    rpy: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    given_matrix: sp.ImmutableMatrix | None = None

    @property
    def matrix(self) -> sp.ImmutableMatrix:
        """The 4 x 4 homogeneous transform."""
        if self.given_matrix is not None:
            return self.given_matrix
        return sp.ImmutableMatrix(homogeneous(rotation_rpy(*self.rpy), sp.Matrix(self.xyz)))


@dataclass(frozen=True)
class Robot:
    """A serial robot: DH table, parameters with defaults, optional base and tool transforms and joint coupling.

    Build one with :func:`symjac.model.robot_file.robot_from_mapping` or :func:`symjac.load_robot`; every instance is
    validated.

    Joints and coordinates: the chain has :attr:`n_joints` joints with the :attr:`joint_variables` ``theta{i}`` /
    ``d{i}``; a user gives values for the :attr:`n_coordinates` independent :attr:`coordinates` (``q``). Without a
    ``coupling`` (the default) every joint variable is its own coordinate and the two coincide; with one
    (:class:`~symjac.model.coordinates.Coupling`), each joint variable is an affine expression of the coordinates,
    and every result symjac returns (transforms, Jacobians, Hessians, rates, torques) is in the coordinates.

    Inertial data: ``inertials[k - 1]`` is link *k*'s :class:`~symjac.model.inertia.Inertial` (mass, centre of mass
    and tensor about it, in frame {k}; the body ``link=k`` of a Jacobian names, ``link=0`` being the base, which has
    none), or None where it is unknown, as for every link without it (the default ``()``). Each must be well formed
    with the parameters' defaults (a mass that is not negative, finite values, a symmetric tensor:
    :func:`~symjac.model.inertia.inertial_problem` with ``physical=False``); robot files, URDF and MJCF keep a
    tensor no rigid body can have with an :class:`~symjac.errors.InertialWarning`. ``drives[i - 1]`` is joint *i*'s
    :class:`~symjac.model.drive.Drive` (armature, viscous and Coulomb friction, in joint space) or None, likewise.

    ``angle_unit`` is the unit the robot file wrote its angles in (``"deg"`` or ``"rad"``, the default): the model
    itself is always in radians; the command line reads a plain ``--q`` number in this unit. Like ``source`` it is
    where the robot came from, not what it is, so it takes no part in equality. So are ``tip_frame``, the frame the
    chain ends at as the source names it (a URDF's tip link), and ``source_format``, the reader's name (``"URDF"``,
    ``"MJCF"``, ``"TOML robot file"``); both are empty when there is none.
    """

    name: str
    convention: Convention
    joints: tuple[Joint, ...]
    parameters: tuple[Parameter, ...] = ()
    description: str = ""
    base: FixedTransform | None = None
    tool: FixedTransform | None = None
    source: str = field(default="<mapping>", compare=False)
    coupling: Coupling | None = None
    inertials: tuple[Inertial | None, ...] = ()
    drives: tuple[Drive | None, ...] = ()
    angle_unit: Literal["rad", "deg"] = field(default="rad", compare=False)
    tip_frame: str = field(default="", compare=False)
    source_format: str = field(default="", compare=False)
    __hash__ = cached_hash  # computed once: every cached derivation looks its chain up by it

    def __post_init__(self) -> None:
        """Refuse bad parameter names, couplings and inertial data.

        A parameter may not be named like a symbol symjac generates; a coupling must be affine and complete; inertial
        data must be one per link and physically possible (one line naming the link).
        """
        reserved = reserved_names([joint.type for joint in self.joints])
        if self.coupling is not None and self.coupling.values == self.joint_variables == self.coupling.coordinates:
            object.__setattr__(self, "coupling", None)  # the identity: one robot, one chain, today's results
        if self.coupling is not None:
            problem = coupling_problem(self.coupling, self.joint_variables, self.parameter_symbols)
            if problem is not None:
                raise RobotFileError(problem, source=self.source, field="coupling")
            for c in self.coupling.coordinates:
                for symbol in (c, rate_symbol(c), acceleration_symbol(c)):
                    reserved.setdefault(symbol.name, f"taken by the coordinate {c} or its derivatives")
        for parameter in self.parameters:
            if parameter.name in reserved:
                raise RobotFileError(f"{parameter.name!r} is reserved: {reserved[parameter.name]}",
                                     source=self.source, field=f"parameters.{parameter.name}")
        self._check_inertials()
        drives = checked_drives(self.drives, self.joints, self.defaults,
                                lambda message, _: RobotFileError(message, source=self.source, field="drive"))
        object.__setattr__(self, "drives", drives)

    def _check_inertials(self) -> None:
        inertials = tuple(self.inertials)
        if all(inertial is None for inertial in inertials):  # none known: one None per link, whatever the count
            inertials = (None,) * len(self.joints)
        object.__setattr__(self, "inertials", inertials)
        if len(inertials) != len(self.joints):
            raise RobotFileError(f"{len(inertials)} inertial entries for {len(self.joints)} links: give one per link "
                                 f"(None where unknown)", source=self.source, field="inertial")
        defaults = self.defaults
        for link, inertial in enumerate(inertials, start=1):
            if inertial is None:
                continue
            if not isinstance(inertial, Inertial):
                raise RobotFileError(f"link {link}: expected Inertial or None, got {type(inertial).__name__}",
                                     source=self.source, joint=link, field="inertial")
            problem = inertial_problem(inertial, defaults, physical=False)
            if problem is not None:
                raise RobotFileError(f"link {link}: {problem}", source=self.source, joint=link, field="inertial")

    @property
    def n_joints(self) -> int:
        """Number of joints; links, frames {1}..{n} and propagation steps are counted in joints."""
        return len(self.joints)

    @property
    def n_coordinates(self) -> int:
        """Number of independent coordinates: Jacobian columns, rates and configurations are counted in these."""
        return len(self.coordinates)

    @property
    def joint_variables(self) -> tuple[sp.Symbol, ...]:
        """Joint variables (theta_i or d_i), in chain order: what the chain's transforms are written in."""
        return tuple(joint.variable for joint in self.joints)

    @property
    def uncoupled(self) -> Robot:
        """The same robot with every joint its own coordinate (itself if it has no coupling)."""
        return self if self.coupling is None else replace(self, coupling=None)

    @property
    def joint_values(self) -> tuple[sp.Expr, ...]:
        """Each joint variable as an expression of the coordinates (the joint variables themselves without coupling)."""
        return self.joint_variables if self.coupling is None else self.coupling.values

    @property
    def coordinates(self) -> tuple[sp.Symbol, ...]:
        """The independent coordinates: the joint variables unless a coupling names others."""
        return self.joint_variables if self.coupling is None else self.coupling.coordinates

    @property
    def q(self) -> tuple[sp.Symbol, ...]:
        """The independent coordinates (:attr:`coordinates`), what a configuration gives values for, in order.

        Without a coupling these are the joint variables (theta_i or d_i) in chain order.
        """
        return self.coordinates

    @property
    def coordinate_rates(self) -> tuple[sp.Symbol, ...]:
        r"""The rates :math:`\dot q` of the coordinates (the joint rates without a coupling)."""
        if self.coupling is None:
            return tuple(joint.rate for joint in self.joints)
        return tuple(rate_symbol(c) for c in self.coupling.coordinates)

    @property
    def coordinate_accelerations(self) -> tuple[sp.Symbol, ...]:
        r"""The accelerations :math:`\ddot q` of the coordinates (the joint accelerations without a coupling)."""
        if self.coupling is None:
            return tuple(joint.acceleration for joint in self.joints)
        return tuple(acceleration_symbol(c) for c in self.coupling.coordinates)

    @property
    def coordinate_types(self) -> tuple[JointType, ...]:
        """Per coordinate, whether it is an angle (it moves a revolute joint) or a length (prismatic joints only)."""
        if self.coupling is None:
            return tuple(joint.type for joint in self.joints)
        C = self.coupling.matrix
        turns = [any(C[i, j] != 0 for i, joint in enumerate(self.joints) if joint.is_revolute) for j in range(C.cols)]
        return tuple(JointType.REVOLUTE if turn else JointType.PRISMATIC for turn in turns)

    @property
    def parameter_symbols(self) -> tuple[sp.Symbol, ...]:
        """Parameter symbols in file order."""
        return tuple(parameter.symbol for parameter in self.parameters)

    @property
    def geometric_parameters(self) -> tuple[Parameter, ...]:
        """The parameters kinematics may read: all but the symbolic inertial ones (:attr:`Parameter.inertial`)."""
        return tuple(parameter for parameter in self.parameters if not parameter.inertial)

    @property
    def defaults(self) -> dict[sp.Symbol, sp.Rational]:
        """Exact numeric default of every parameter, keyed by symbol (for ``expr.subs(robot.defaults)``)."""
        return {parameter.symbol: parameter.default for parameter in self.parameters}


def reserved_names(joint_types: Sequence[JointType]) -> dict[str, str]:
    """The names a robot with these joints cannot give a parameter, each with the reason, in plain words.

    They are the names of the symbols symjac generates for it: joint variables (``theta{i}`` for every joint, as it
    prints as joint *i*'s angle, and ``d{i}`` for prismatic joints; ``d{i}`` of a revolute joint stays free for the
    DH offset), joint rates and accelerations of either kind, wrench components and velocity components.

    Examples
    --------
    >>> reserved_names([JointType.REVOLUTE])["f_x"]
    'symjac names the wrench components f_x .. n_z'
    >>> sorted(name for name in reserved_names([JointType.PRISMATIC]) if name.endswith("1"))
    ['d1', 'dddot1', 'ddot1', 'theta1', 'thetaddot1', 'thetadot1']
    """
    reserved = dict.fromkeys(WRENCH_NAMES, "symjac names the wrench components f_x .. n_z")
    reserved |= dict.fromkeys(VELOCITY_NAMES, "symjac names the velocity components v_x .. omega_z")
    for index, kind in enumerate(joint_types, start=1):
        for probe_kind in JointType:
            probe = Joint(index=index, type=probe_kind, placement=Placement())
            reserved[probe.rate.name] = "symjac names the joint rates thetadot<i> and ddot<i>"
            reserved[probe.acceleration.name] = "symjac names the joint accelerations thetaddot<i> and dddot<i>"
            if probe_kind is kind or probe_kind is JointType.REVOLUTE:
                reserved[probe.variable.name] = ("taken by a joint variable (symjac names the variable of revolute "
                                                 "joint i theta<i>, of prismatic joint i d<i>)")
    return reserved
