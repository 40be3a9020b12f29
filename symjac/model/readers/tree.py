r"""The kinematic tree every robot reader produces, and the one way symjac cuts a serial chain out of it.

A reader (URDF, MJCF) turns its file into a :class:`KinematicTree`: named links, each with its inertial
data as the file gives it (:class:`LinkInertial`), and named joints, each with its type, parent and child link, the
fixed ``origin`` transform from the parent link's frame to the child link's frame at zero motion, a constant ``axis``
(in the child link's frame, which the origin places), its limits and a mimic rule. :func:`robot_from_tree` then
builds the general-convention :class:`~symjac.model.robot.Robot` of the chain between two links, the same way for
every format.

The chain
    From ``base_link`` (default: the root link) to ``tip_link`` (default: the only leaf below the base; with several
    the error lists them). Revolute, continuous and prismatic joints become joints of the robot, in order; fixed
    joints are folded into the origin of the next moving joint, and those after the last moving joint into the tool
    transform. Floating and planar joints are refused on the chain; joints on other branches are held at zero
    (a gripper beside the arm does not stop the arm from loading). Frame {0} is ``base_link``; frame {i} is the child
    link of moving joint *i* turned by the constant alignment :math:`A_i` that takes :math:`z` onto the joint axis
    (:mod:`symjac.model.conventions.general`); the ``"tool"`` frame is ``tip_link``.

Mimic joints
    A moving joint of the chain with a :class:`Mimic` rule follows another moving joint *J*:
    :math:`x_i = m\,x_J + o`. The variable of a general joint is its position along the axis as written, so
    :math:`\vartheta_i = m\,\vartheta_J + o` exactly; the robot's coordinates are the variables of the joints that
    mimic nothing, in chain order (a :class:`~symjac.model.coordinates.Coupling`). A mimic of a mimic is followed to
    the joint that mimics nothing (:math:`\vartheta_i = m_1 (m_2 \vartheta_K + o_2) + o_1`); a cycle is refused.
    A leader off the chain (the finger of a gripper that the other finger, on the chain, mimics) is a coordinate of
    its own, named after that joint (``l_gripper_l_finger_joint``; prefixed ``q_`` where the name would read as a
    joint variable), placed where its first follower is. Mimic rules on other branches, and on fixed joints, are
    ignored.

Every problem raises :class:`~symjac.errors.RobotFileError` naming the source and the link or joint.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from enum import StrEnum
from pathlib import Path
from typing import ClassVar

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.conventions.general import GeneralPlacement
from symjac.model.coordinates import Coupling
from symjac.model.drive import Drive
from symjac.model.exact_transforms import fixed_transform_from_matrix
from symjac.model.expressions import is_valid_name
from symjac.model.readers.lumping import link_inertial
from symjac.model.robot import (
    Convention,
    FixedTransform,
    Joint,
    JointType,
    Robot,
    unit_vector,
)
from symjac.symbolic.transforms import alignment, compose, homogeneous, inverse_motions

__all__ = ["ChainChoiceError", "JointLimits", "KinematicTree", "LinkInertial", "Mimic", "TreeJoint", "TreeJointType",
           "TreeLink", "identifier", "robot_from_tree"]


class ChainChoiceError(RobotFileError):
    """The chain cannot be chosen as asked; the message names the arguments that choose it (``base_link``, ...).

    ``template`` is the message with ``{base_link}``, ``{tip_link}`` and ``{tip_site}`` where an argument's name goes
    (``str.format`` fields; the link names in it are escaped), so that a front end can name its own options
    (:meth:`worded`) without ever rewriting a link name: a link may well be called ``base_link``.
    """

    ARGUMENTS: ClassVar[dict[str, str]] = {"base_link": "base_link", "tip_link": "tip_link", "tip_site": "tip_site"}

    def __init__(self, template: str, *, source: str, field: str | None = None):
        self.template = template
        super().__init__(self.worded(), source=source, field=field)

    def worded(self, **names: str) -> str:
        """The message with the arguments called by ``names`` (``base_link="--base-link"``), the others by theirs."""
        return self.template.format(**{**self.ARGUMENTS, **names})


def _braced(text: object) -> str:
    """``text`` (a link name, a list of them) safe inside a :class:`ChainChoiceError` template."""
    return str(text).replace("{", "{{").replace("}", "}}")


class TreeJointType(StrEnum):
    """The kinds of joint a tree holds; only the first three move along a chain symjac models."""

    REVOLUTE = "revolute"
    CONTINUOUS = "continuous"  # a revolute joint without position limits
    PRISMATIC = "prismatic"
    FIXED = "fixed"
    FLOATING = "floating"
    PLANAR = "planar"


_MOVING = {TreeJointType.REVOLUTE: JointType.REVOLUTE, TreeJointType.CONTINUOUS: JointType.REVOLUTE,
           TreeJointType.PRISMATIC: JointType.PRISMATIC}


@dataclass(frozen=True)
class LinkInertial:
    r"""A link's inertial data as its file gives it: raw numbers, not yet in any frame symjac uses.

    ``xyz`` and ``rpy`` place the inertial frame {c} in the link's frame (:math:`R = R_z(y) R_y(p) R_x(r)`); the
    centre of mass is the origin of {c}, and ``ixx .. izz`` are the entries of the tensor about it, along the axes
    of {c}.
    """

    mass: sp.Expr
    xyz: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    rpy: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    ixx: sp.Expr = sp.S.Zero
    ixy: sp.Expr = sp.S.Zero
    ixz: sp.Expr = sp.S.Zero
    iyy: sp.Expr = sp.S.Zero
    iyz: sp.Expr = sp.S.Zero
    izz: sp.Expr = sp.S.Zero

    @property
    def origin(self) -> FixedTransform:
        """The pose of the inertial frame {c} in the link's frame."""
        return FixedTransform(xyz=self.xyz, rpy=self.rpy)

    @property
    def tensor(self) -> sp.ImmutableMatrix:
        """The symmetric 3 x 3 tensor about the centre of mass, axes of the inertial frame {c}."""
        return sp.ImmutableMatrix([[self.ixx, self.ixy, self.ixz], [self.ixy, self.iyy, self.iyz],
                                   [self.ixz, self.iyz, self.izz]])


@dataclass(frozen=True)
class TreeLink:
    """A named rigid body of the tree, with its inertial data when the file gives it."""

    name: str
    inertial: LinkInertial | None = None


@dataclass(frozen=True)
class JointLimits:
    """Position bounds (``lower < upper``; None when the file gives none), and speed and effort limits (or None)."""

    lower: sp.Expr | None = None
    upper: sp.Expr | None = None
    velocity: sp.Expr | None = None
    effort: sp.Expr | None = None

    @property
    def bounds(self) -> tuple[sp.Expr, sp.Expr] | None:
        """``(lower, upper)`` when both are given, else None."""
        return None if self.lower is None or self.upper is None else (self.lower, self.upper)


@dataclass(frozen=True)
class Mimic:
    """A mimic rule: the joint's position is ``multiplier * position(joint) + offset``."""

    joint: str
    multiplier: sp.Expr = sp.S.One
    offset: sp.Expr = sp.S.Zero


@dataclass(frozen=True)
class TreeJoint:
    """A named joint from ``parent`` to ``child``: the fixed ``origin``, then a motion about or along ``axis``."""

    name: str
    type: TreeJointType
    parent: str
    child: str
    origin: FixedTransform = field(default_factory=FixedTransform)
    axis: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.One)
    limits: JointLimits | None = None
    mimic: Mimic | None = None
    drive: Drive | None = None  # armature and friction, joint-side (checked by the reader)


@dataclass(frozen=True)
class KinematicTree:
    """What a reader found: the robot's ``name`` as the file writes it, its links and its joints, in file order."""

    name: str
    links: tuple[TreeLink, ...]
    joints: tuple[TreeJoint, ...]


def robot_from_tree(tree: KinematicTree, source: str, *, base_link: str | None = None,
                    tip_link: str | None = None, name: str | None = None) -> Robot:
    """The general-convention robot of the chain ``base_link`` .. ``tip_link`` of ``tree`` (see the module text).

    Parameters
    ----------
    tree : KinematicTree
        The links and joints a reader found.
    source : str
        The file name, used in error messages and kept as the robot's source.
    base_link, tip_link : str, optional
        The chain's first and last link (defaults: the root, and the only leaf below the base).
    name : str, optional
        The robot's name (default: the tree's, made an identifier).

    Raises
    ------
    RobotFileError
        For trees that are no trees (links defined twice or missing, a link with two parents, loops) and chains
        symjac cannot model (floating or planar joints on it, bad mimic rules, no moving joint, bad limits).
    """
    links, joints = _checked(tree, source)
    path = _chain(links, joints, source, base_link, tip_link)
    robot_name = name if name is not None else identifier(tree.name or "robot")
    if not is_valid_name(robot_name):
        raise _fail(source, f"robot name {robot_name!r} is not an identifier (letters, digits, underscore)")
    return _robot(robot_name, path, source, links, joints)


def identifier(text: str) -> str:
    """``text`` made an identifier: other characters become ``_``; ``r_`` is prefixed unless it starts with a letter."""
    name = "".join(c if c.isascii() and (c.isalnum() or c == "_") else "_" for c in text)
    return name if name[:1].isalpha() else f"r_{name}"


def _fail(source: str, message: str, element: str | None = None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def _checked(tree: KinematicTree, source: str) -> tuple[dict[str, TreeLink], dict[str, TreeJoint]]:
    """The links and joints by name, after checking names, ends, axes and limits."""
    links: dict[str, TreeLink] = {}
    for link in tree.links:
        if link.name in links:
            raise _fail(source, f"link {link.name!r} is defined twice", f"link {link.name}")
        links[link.name] = link
    joints: dict[str, TreeJoint] = {}
    for joint in tree.joints:
        where = f"joint {joint.name}"
        if joint.name in joints:
            raise _fail(source, f"joint {joint.name!r} is defined twice", where)
        for end, link_name in (("parent", joint.parent), ("child", joint.child)):
            if link_name not in links:
                raise _fail(source, f"{end} link {link_name!r} is not defined", where)
        if joint.type in _MOVING and all(v == 0 for v in joint.axis):
            raise _fail(source, "the axis must not be the zero vector", f"{where} axis")
        bounds = joint.limits.bounds if joint.limits is not None else None
        if bounds is not None and not float(bounds[0]) < float(bounds[1]):  # the TOML reader's wording
            raise _fail(source, f"'limits' must be finite with lower < upper, got "
                                f"[{float(bounds[0])}, {float(bounds[1])}]", f"{where} limit")
        joints[joint.name] = joint
    return links, joints


def _chain(links: dict[str, TreeLink], joints: dict[str, TreeJoint], source: str, base_link: str | None,
           tip_link: str | None) -> list[TreeJoint]:
    """The joints from ``base_link`` to ``tip_link``, base first, after checking that the links form a tree."""
    if not links:
        raise _fail(source, "the robot has no links")
    parent_joint: dict[str, TreeJoint] = {}
    for joint in joints.values():
        if joint.child in parent_joint:
            raise _fail(source, f"link {joint.child!r} is the child of two joints "
                                f"({parent_joint[joint.child].name!r} and {joint.name!r})", f"joint {joint.name}")
        parent_joint[joint.child] = joint
    roots = sorted(set(links) - set(parent_joint))
    if not roots:
        raise _fail(source, "the joints form a loop: every link has a parent")
    # every link must reach a root; a loop elsewhere would otherwise go unnoticed. Each link is walked once: a walk
    # stops at a link known to reach a root, so a deep tree costs its size, not its size times its depth
    reaches_root = set(roots)
    for link in sorted(links):
        walked: set[str] = set()
        while link not in reaches_root:
            walked.add(link)
            link = parent_joint[link].parent
            if link in walked:
                raise _fail(source, f"the joints form a loop through link {link!r}", f"link {link}")
        reaches_root |= walked
    if base_link is None:
        if len(roots) > 1:
            raise ChainChoiceError(f"several root links ({_braced(', '.join(roots))}); choose one with {{base_link}}",
                                   source=source)
        base_link = roots[0]
    if base_link not in links:
        raise ChainChoiceError(f"{{base_link}} {_braced(repr(base_link))} is not a link of this robot (links: "
                               f"{_braced(', '.join(sorted(links)))})", source=source)
    if tip_link is None:
        parents = {joint.parent for joint in joints.values()}
        below = [link for link in sorted(set(links) - parents) if _reaches(link, base_link, parent_joint)]
        if len(below) != 1:
            raise ChainChoiceError(f"choose {{tip_link}}: the links without children below {_braced(repr(base_link))} "
                                   f"are {_braced(', '.join(below) or 'none')}", source=source)
        tip_link = below[0]
    if tip_link not in links:
        raise ChainChoiceError(f"{{tip_link}} {_braced(repr(tip_link))} is not a link of this robot (links: "
                               f"{_braced(', '.join(sorted(links)))})", source=source)
    if not _reaches(tip_link, base_link, parent_joint):
        raise ChainChoiceError(f"{{tip_link}} {_braced(repr(tip_link))} is not below {{base_link}} "
                               f"{_braced(repr(base_link))}", source=source)
    path: list[TreeJoint] = []
    link = tip_link
    while link != base_link:
        path.append(parent_joint[link])
        link = parent_joint[link].parent
    path.reverse()
    for joint in path:
        if joint.type in (TreeJointType.FLOATING, TreeJointType.PLANAR):
            raise _fail(source, f"{joint.type} joints are not supported on the chain", f"joint {joint.name}")
    if not any(joint.type in _MOVING for joint in path):
        raise _fail(source, f"no revolute, continuous or prismatic joint between {base_link!r} and {tip_link!r}")
    return path


def _reaches(link: str, ancestor: str, parent_joint: dict[str, TreeJoint]) -> bool:
    while link != ancestor:
        if link not in parent_joint:
            return False
        link = parent_joint[link].parent
    return True


def _leader(joint: TreeJoint, joints: dict[str, TreeJoint], chain: set[str],
            source: str) -> tuple[str, sp.Expr, sp.Expr]:
    """The joint of the chain that mimics nothing which ``joint`` follows, and ``(m, o)``: x = m * x_leader + o."""
    multiplier, offset = sp.S.One, sp.S.Zero
    followed = [joint.name]
    current = joint
    while current.mimic is not None:
        mimic = current.mimic
        where = f"joint {current.name} mimic"
        if mimic.joint not in joints:
            raise _fail(source, f"joint {current.name!r} mimics {mimic.joint!r}, which is not a joint of this robot",
                        where)
        if mimic.joint in followed:
            raise _fail(source, f"mimic joints form a cycle: {' -> '.join([*followed, mimic.joint])}", where)
        leader = joints[mimic.joint]
        if leader.type not in _MOVING:
            raise _fail(source, f"joint {current.name!r} mimics joint {mimic.joint!r}, a {leader.type} joint", where)
        offset, multiplier = offset + multiplier * mimic.offset, multiplier * mimic.multiplier
        followed.append(leader.name)
        current = leader
    return current.name, multiplier, offset


def _coupled(robot: Robot, moving: list[TreeJoint], joints: dict[str, TreeJoint], chain: set[str],
             source: str) -> Robot:
    """``robot`` with the coupling of the mimic joints of its chain (``robot`` itself when there are none)."""
    if all(joint.mimic is None for joint in moving):
        return robot
    variable = {joint.name: symbol for joint, symbol in zip(moving, robot.joint_variables, strict=True)}
    off_chain: dict[str, sp.Symbol] = {}
    taken = {str(symbol) for symbol in robot.joint_variables} | {str(p) for p in robot.parameter_symbols}
    values = []
    for joint in moving:
        leader, multiplier, offset = _leader(joint, joints, chain, source)
        if leader not in variable:  # a leader off the chain (a gripper's other finger) is a coordinate of its own
            off_chain[leader] = off_chain.get(leader) or _off_chain_coordinate(leader, taken)
        values.append(multiplier * (variable[leader] if leader in variable else off_chain[leader]) + offset)
    leaders = set(variable.values()) | set(off_chain.values())
    # each value is m x + o of one leader: the coordinates in the order of their first joint along the chain
    coordinates = tuple(dict.fromkeys(symbol for value in values for symbol in value.free_symbols & leaders))
    return replace(robot, coupling=Coupling(coordinates, tuple(values)))


def _off_chain_coordinate(name: str, taken: set[str]) -> sp.Symbol:
    """The coordinate of a leader joint off the chain: its name made an identifier, never a chain joint's variable."""
    symbol_name = identifier(name)
    if re.fullmatch(r"(theta|d|q)\d*", symbol_name) or symbol_name in taken:
        symbol_name = f"q_{symbol_name}"
    return sp.Symbol(symbol_name, real=True)


def _robot(robot_name: str, path: list[TreeJoint], source: str, links: dict[str, TreeLink],
           all_joints: dict[str, TreeJoint]) -> Robot:
    pending: list[FixedTransform] = []
    joints: list[Joint] = []
    for tree_joint in path:
        if tree_joint.type not in _MOVING:
            pending.append(tree_joint.origin)
            continue
        origin = _combine([*pending, tree_joint.origin], [])
        pending = []
        axis = tree_joint.axis
        placement = GeneralPlacement(None if origin == FixedTransform() else origin,
                                     None if tuple(axis) == (0, 0, 1) else axis)
        bounds = tree_joint.limits.bounds if tree_joint.limits is not None else None
        joints.append(Joint(index=len(joints) + 1, type=_MOVING[tree_joint.type], placement=placement,
                            limits=bounds, name=tree_joint.name,
                            continuous=tree_joint.type is TreeJointType.CONTINUOUS))
    last_alignment = alignment(placement.unit_axis)
    tool = _combine(pending, list(inverse_motions(last_alignment)))
    moving = [joint for joint in path if joint.type in _MOVING]
    fixed_children: dict[str, list[tuple[str, sp.Matrix]]] = {}
    on_chain = {joint.name for joint in path}
    for other in all_joints.values():  # a moving joint off the chain is held at zero: its child rides as if fixed
        if other.type is TreeJointType.FIXED or (other.type in _MOVING and other.name not in on_chain):
            fixed_children.setdefault(other.parent, []).append((other.child, sp.Matrix(other.origin.matrix)))
    bodies = {name: link.inertial for name, link in links.items()}
    inertials = tuple(link_inertial(unit_vector(joint.axis), joint.child, bodies, fixed_children, source)
                      for joint in moving) \
        if any(link.inertial is not None for link in links.values()) else ()
    # every number was checked finite when read, limits ordered, names made identifiers: the robot is valid
    robot = Robot(name=robot_name, convention=Convention.GENERAL, joints=tuple(joints),
                  description=f"from {Path(source).name}", tool=None if tool == FixedTransform() else tool,
                  source=source, inertials=inertials if any(inertials) else (), tip_frame=path[-1].child,
                  drives=tuple(joint.drive for joint in moving))
    return _coupled(robot, moving, all_joints, {joint.name for joint in path}, source)


def _combine(transforms: list[FixedTransform], prefix: list) -> FixedTransform:
    """The product ``prefix @ transforms[0] @ ...`` as one fixed transform, in xyz/rpy form whenever exact."""
    nontrivial = [t for t in transforms if t != FixedTransform()]
    if not prefix and len(nontrivial) <= 1:
        return nontrivial[0] if nontrivial else FixedTransform()
    rotation_matrix, position = compose([*prefix, *(sp.Matrix(t.matrix) for t in nontrivial)])
    return fixed_transform_from_matrix(homogeneous(rotation_matrix, position))
