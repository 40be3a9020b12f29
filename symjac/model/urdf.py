r"""Reading URDF files: the serial chain between two links as a general-convention :class:`~symjac.model.robot.Robot`.

What is read
    ``<robot name>``, every ``<link name>``, and every ``<joint name type>`` with its ``<parent link>``,
    ``<child link>``, ``<origin xyz rpy>``, ``<axis xyz>``, ``<limit lower upper>`` and ``<mimic>``. Visual,
    collision, inertial, transmission and gazebo elements are ignored. Limits with ``lower = upper = 0`` (URDF's
    default) mean "no limits"; any other pair must have ``lower < upper``.

The chain
    From ``base_link`` (default: the root link) to ``tip_link`` (default: the only leaf; with several leaves the
    error lists them). Revolute, continuous and prismatic joints become joints of the robot, in order; fixed joints are
    folded into the origin of the next moving joint, and those after the last moving joint into the tool transform.
    Floating and planar joints are refused when they lie on the chain and ignored on other branches (a gripper beside
    the arm does not stop the arm from loading). Frame {0} is ``base_link``; frame {i} is
    the child link of moving joint *i* turned so that its z-axis is the joint axis (see :mod:`symjac.model.robot`); the
    ``"tool"`` frame is ``tip_link``.

Mimic joints
    ``<mimic joint="J" multiplier="m" offset="o"/>`` on a moving joint of the chain couples it to joint ``J`` (a
    moving joint of the chain): its position is :math:`m\,x_J + o` (defaults 1 and 0). symjac's variable of a general
    joint is its URDF position (the alignment turns :math:`z` onto the axis as written, never onto its opposite), so
    :math:`\vartheta_i = m\,\vartheta_J + o` exactly; the coordinates are the variables of the moving joints that
    mimic nothing, in chain order. A mimic of a mimic is followed to the joint that mimics nothing
    (:math:`\vartheta_i = m_1 (m_2 \vartheta_K + o_2) + o_1`); a cycle is refused. Mimic joints on other branches, and
    ``<mimic>`` on fixed joints, are ignored.

Numbers
    Every number becomes an exact rational (``0.333 -> 333/1000``), so derivations stay exact and fast. An angle (an
    ``rpy`` entry or a revolute limit) within :data:`symjac.model.expressions.ANGLE_SNAP_TOLERANCE` (1e-9) of a multiple
    of :math:`\pi/12` becomes that exact multiple of :math:`\pi` (``1.5707963267949 -> pi/2``), so symbolic results read
    :math:`\cos(\pi/2) = 0`, not a decimal. Axes are made unit exactly: ``0 1 1`` is :math:`(0, \sqrt2/2, \sqrt2/2)`.

Safety
    The file is parsed with the standard library's expat parser, after refusing any document type declaration
    (``<!DOCTYPE``/``<!ENTITY``): no entity is ever expanded and no other file or URL is ever read (no external
    entities, no ``package://`` lookups). A xacro file (``<xacro:...>`` elements, ``${...}`` substitutions) is
    refused with the command that expands it. Files up to :data:`MAX_URDF_BYTES` in UTF-8, or in US-ASCII or
    ISO-8859-1 when the XML declaration says so, are read.
    Every problem raises :class:`~symjac.errors.RobotFileError` naming the file and the element.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import sympy as sp

from symjac.errors import ExpressionError, RobotFileError
from symjac.model.conventions.general import GeneralPlacement
from symjac.model.coordinates import Coupling
from symjac.model.expressions import exact_number, is_valid_name, snap_angle
from symjac.model.robot import Convention, FixedTransform, Joint, JointType, Robot, fixed_transform_from_matrix
from symjac.symbolic.transforms import alignment, compose, homogeneous, inverse_motions

__all__ = ["MAX_URDF_BYTES", "robot_from_urdf"]

MAX_URDF_BYTES = 5_000_000
"""Largest URDF file read, in bytes (a real arm's file is tens of kilobytes; larger is refused in one line)."""
MAX_URDF_ANGLE = 10**9  # radians; a float angle this large has lost every digit below 1e-7 rad anyway
_MOVING = {"revolute": JointType.REVOLUTE, "continuous": JointType.REVOLUTE, "prismatic": JointType.PRISMATIC}
_KNOWN_TYPES = {*_MOVING, "fixed", "floating", "planar"}
_DECLARATION = re.compile(rb"<!\s*(DOCTYPE|ENTITY|ELEMENT|ATTLIST)", re.IGNORECASE)
_ENCODING = re.compile(rb"""^(?:\xef\xbb\xbf)?\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")
_ENCODINGS = {"utf-8": "utf-8", "utf8": "utf-8", "us-ascii": "ascii", "ascii": "ascii", "iso-8859-1": "latin-1",
              "iso8859-1": "latin-1", "latin-1": "latin-1", "latin1": "latin-1", "l1": "latin-1"}
# an xacro element or a ${...} / $(...) substitution in an attribute value; not the xmlns:xacro declaration alone,
# which xacro itself leaves on the <robot> of the URDF files it writes
_XACRO = re.compile(r"""<\s*xacro:|=\s*(?:"[^"]*|'[^']*)\$[{(]""")
_NAME_CHARS = re.compile(r"[^A-Za-z0-9_]")


@dataclass(frozen=True)
class _UrdfJoint:
    name: str
    type: str
    parent: str
    child: str
    origin: FixedTransform
    axis: tuple[sp.Expr, sp.Expr, sp.Expr]
    limits: tuple[sp.Expr, sp.Expr] | None
    mimic: _Mimic | None


@dataclass(frozen=True)
class _Mimic:
    """``<mimic joint multiplier offset>``: this joint's position is ``multiplier * position(joint) + offset``."""

    joint: str
    multiplier: sp.Expr
    offset: sp.Expr


def robot_from_urdf(
    content: str | bytes,
    source: str = "<urdf>",
    base_link: str | None = None,
    tip_link: str | None = None,
    name: str | None = None,
) -> Robot:
    """Build the general-convention robot of the chain ``base_link`` .. ``tip_link`` of a URDF document.

    Parameters
    ----------
    content : str or bytes
        The URDF text (UTF-8).
    source : str
        The file name, used in error messages.
    base_link, tip_link : str, optional
        The chain's first and last link (defaults: the root, and the only leaf).
    name : str, optional
        The robot's name (default: the ``<robot name>``, made an identifier).

    Raises
    ------
    RobotFileError
        For hostile or malformed input (document type declarations, bad XML, missing or duplicate links, loops,
        unknown joint types, non-finite numbers) and for chains symjac cannot model (floating or planar joints on
        the chain, a mimic joint on the chain whose leader is not a moving joint of the chain, a cycle of mimic
        joints, no moving joint). The message names the file and the element.

    Examples
    --------
    >>> urdf = '''<robot name="arm"><link name="a"/><link name="b"/>
    ...   <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.5"/>
    ...     <axis xyz="0 1 0"/><limit lower="-1.5707963267949" upper="1.5707963267949"/></joint></robot>'''
    >>> robot = robot_from_urdf(urdf)
    >>> robot.joints[0].limits, robot.joints[0].placement.axis
    ((-pi/2, pi/2), (0, 1, 0))
    """
    root = _parse(content, source)
    links, joints = _read(root, source)
    chain = _chain(links, joints, source, base_link, tip_link)
    robot_name = name if name is not None else _identifier(root.get("name") or "urdf_robot")
    if not is_valid_name(robot_name):
        raise _fail(source, f"robot name {robot_name!r} is not an identifier (letters, digits, underscore)")
    return _robot(robot_name, chain, source, joints)


def _fail(source: str, message: str, element: str | None = None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def _parse(content: str | bytes, source: str) -> ET.Element:
    if isinstance(content, str):
        try:
            data = content.encode("utf-8")
        except UnicodeEncodeError as error:  # lone surrogates
            raise _fail(source, f"not UTF-8 text: {error}") from None
    else:
        data = bytes(content)
    if len(data) > MAX_URDF_BYTES:
        raise _fail(source, f"file larger than {MAX_URDF_BYTES} bytes")
    if b"\x00" in data:
        raise _fail(source, "not a UTF-8 text file (NUL bytes)")
    declared = _ENCODING.match(data)
    encoding = "utf-8"
    if declared:
        encoding = _ENCODINGS.get(declared.group(1).decode("ascii").lower().replace("_", "-"), "")
        if not encoding:
            raise _fail(source, f"only UTF-8, ASCII and ISO-8859-1 files are read, this one declares "
                                f"{declared.group(1).decode('ascii')!r}")
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as error:
        raise _fail(source, f"not {'UTF-8' if encoding == 'utf-8' else encoding.upper()} text: {error}") from None
    # A document type declaration is where entities (billion laughs, external files) live: refuse it outright,
    # before the parser sees anything, rather than trusting the parser's limits.
    if _DECLARATION.search(data):
        raise _fail(source, "document type and entity declarations (<!DOCTYPE, <!ENTITY) are not allowed in URDF")
    if _XACRO.search(text):
        name = Path(source).name if source != "<urdf>" else "FILE"
        output = name.removesuffix(".xacro").removesuffix(".urdf") + ".urdf"
        raise _fail(source, f"this is a xacro file (macros and ${{...}} substitutions are not URDF): run "
                            f"`xacro {name} > {output}` first and load {output}")
    try:
        # expat reads the declared encoding itself (UTF-8, US-ASCII and ISO-8859-1 are built in)
        root = ET.fromstring(data)
    except ET.ParseError as error:
        raise _fail(source, f"invalid XML: {error}") from None
    except RecursionError:  # pragma: no cover - expat is iterative; kept for tree builders that are not
        raise _fail(source, "invalid XML: elements nested too deeply") from None
    if root.tag != "robot":
        raise _fail(source, f"the root element must be <robot>, got <{root.tag}>")
    return root


def _number(text: str, source: str, element: str) -> sp.Rational:
    token = text.strip()
    if len(token) > 40:
        raise _fail(source, f"number too long: {token[:40]!r}...", element)
    try:
        value = float(token)
        return exact_number(value)
    except (ValueError, ExpressionError):
        raise _fail(source, f"expected a finite number, got {token!r}", element) from None


def _vector(text: str | None, source: str, element: str, default: Sequence[int] = (0, 0, 0)) -> list[sp.Rational]:
    if text is None:
        return [sp.Integer(v) for v in default]
    parts = text.split()
    if len(parts) != 3:
        raise _fail(source, f"expected 3 numbers, got {text!r}", element)
    return [_number(part, source, element) for part in parts]


def _read(root: ET.Element, source: str) -> tuple[set[str], dict[str, _UrdfJoint]]:
    links: set[str] = set()
    for link in root.findall("link"):
        link_name = link.get("name")
        if not link_name:
            raise _fail(source, "a <link> has no name", "link")
        if link_name in links:
            raise _fail(source, f"link {link_name!r} is defined twice", f"link {link_name}")
        links.add(link_name)
    joints: dict[str, _UrdfJoint] = {}
    for joint in root.findall("joint"):
        joint_name = joint.get("name")
        if not joint_name:
            raise _fail(source, "a <joint> has no name", "joint")
        where = f"joint {joint_name}"
        if joint_name in joints:
            raise _fail(source, f"joint {joint_name!r} is defined twice", where)
        kind = joint.get("type")
        if kind not in _KNOWN_TYPES:
            raise _fail(source, f"unknown joint type {kind!r}; URDF types are {', '.join(sorted(_KNOWN_TYPES))}",
                        where)
        ends = []
        for tag in ("parent", "child"):
            element = joint.find(tag)
            link_name = element.get("link") if element is not None else None
            if not link_name:
                raise _fail(source, f"missing <{tag} link=...>", where)
            if link_name not in links:
                raise _fail(source, f"{tag} link {link_name!r} is not defined", where)
            ends.append(link_name)
        origin_element = joint.find("origin")
        xyz = _vector(origin_element.get("xyz") if origin_element is not None else None, source, f"{where} origin")
        rpy = [snap_angle(v) for v in _vector(origin_element.get("rpy") if origin_element is not None else None,
                                              source, f"{where} origin")]
        if any(abs(v) > MAX_URDF_ANGLE for v in rpy):  # SymPy cannot reduce sin(1e308) when fixed joints merge
            raise _fail(source, f"an rpy angle is larger than {MAX_URDF_ANGLE:.0e} rad in size", f"{where} origin")
        axis_element = joint.find("axis")
        axis = _vector(axis_element.get("xyz") if axis_element is not None else None, source, f"{where} axis",
                       (1, 0, 0))
        if kind in _MOVING and all(v == 0 for v in axis):
            raise _fail(source, "the axis must not be the zero vector", f"{where} axis")
        limits = None
        limit_element = joint.find("limit")
        if kind in ("revolute", "prismatic") and limit_element is not None:
            bounds = [_number(limit_element.get(key, "0"), source, f"{where} limit") for key in ("lower", "upper")]
            if kind == "revolute":
                bounds = [snap_angle(b) for b in bounds]
            if bounds[0] != 0 or bounds[1] != 0:  # lower = upper = 0 is the common "no limits given"
                if not float(bounds[0]) < float(bounds[1]):  # the TOML reader's wording
                    raise _fail(source, f"'limits' must be finite with lower < upper, got "
                                        f"[{float(bounds[0])}, {float(bounds[1])}]", f"{where} limit")
                limits = (bounds[0], bounds[1])
        joints[joint_name] = _UrdfJoint(joint_name, kind, ends[0], ends[1],
                                        FixedTransform(xyz=tuple(xyz), rpy=tuple(rpy)),  # type: ignore[arg-type]
                                        tuple(axis), limits, _mimic(joint, kind, source, where))  # type: ignore[arg-type]
    return links, joints


def _mimic(joint: ET.Element, kind: str, source: str, where: str) -> _Mimic | None:
    """The ``<mimic>`` of a moving joint, its numbers checked finite (None without one, and on fixed joints)."""
    element = joint.find("mimic")
    if element is None or kind not in _MOVING:
        return None
    leader = element.get("joint")
    if not leader:
        raise _fail(source, "<mimic> must name the joint it follows (joint=...)", f"{where} mimic")
    multiplier = _number(element.get("multiplier", "1"), source, f"{where} mimic")
    offset = _number(element.get("offset", "0"), source, f"{where} mimic")
    if abs(multiplier) > MAX_URDF_ANGLE or abs(offset) > MAX_URDF_ANGLE:
        raise _fail(source, f"mimic multiplier and offset must be at most {MAX_URDF_ANGLE:.0e} in size",
                    f"{where} mimic")
    return _Mimic(leader, multiplier, snap_angle(offset) if _MOVING[kind] is JointType.REVOLUTE else offset)


def _chain(links: set[str], joints: dict[str, _UrdfJoint], source: str, base_link: str | None,
           tip_link: str | None) -> list[_UrdfJoint]:
    """The joints from ``base_link`` to ``tip_link``, base first, after checking that the links form a tree."""
    if not links:
        raise _fail(source, "the robot has no links")
    parent_joint: dict[str, _UrdfJoint] = {}
    for joint in joints.values():
        if joint.child in parent_joint:
            raise _fail(source, f"link {joint.child!r} is the child of two joints "
                                f"({parent_joint[joint.child].name!r} and {joint.name!r})", f"joint {joint.name}")
        parent_joint[joint.child] = joint
    roots = sorted(links - set(parent_joint))
    if not roots:
        raise _fail(source, "the joints form a loop: every link has a parent")
    # every link must reach a root; a loop elsewhere would otherwise go unnoticed
    for link in sorted(links):
        seen = {link}
        while link in parent_joint:
            link = parent_joint[link].parent
            if link in seen:
                raise _fail(source, f"the joints form a loop through link {link!r}", f"link {link}")
            seen.add(link)
    if base_link is None:
        if len(roots) > 1:
            raise _fail(source, f"several root links ({', '.join(roots)}); choose one with base_link")
        base_link = roots[0]
    if base_link not in links:
        raise _fail(source, f"base_link {base_link!r} is not a link of this robot (links: {', '.join(sorted(links))})")
    if tip_link is None:
        parents = {joint.parent for joint in joints.values()}
        below = [link for link in sorted(links - parents) if _reaches(link, base_link, parent_joint)]
        if len(below) != 1:
            raise _fail(source, f"choose tip_link: the links without children below {base_link!r} are "
                                f"{', '.join(below) or 'none'}")
        tip_link = below[0]
    if tip_link not in links:
        raise _fail(source, f"tip_link {tip_link!r} is not a link of this robot (links: {', '.join(sorted(links))})")
    if not _reaches(tip_link, base_link, parent_joint):
        raise _fail(source, f"tip_link {tip_link!r} is not below base_link {base_link!r}")
    path: list[_UrdfJoint] = []
    link = tip_link
    while link != base_link:
        path.append(parent_joint[link])
        link = parent_joint[link].parent
    path.reverse()
    for joint in path:
        if joint.type in ("floating", "planar"):
            raise _fail(source, f"{joint.type} joints are not supported on the chain", f"joint {joint.name}")
    if not any(joint.type in _MOVING for joint in path):
        raise _fail(source, f"no revolute, continuous or prismatic joint between {base_link!r} and {tip_link!r}")
    return path


def _reaches(link: str, ancestor: str, parent_joint: dict[str, _UrdfJoint]) -> bool:
    while link != ancestor:
        if link not in parent_joint:
            return False
        link = parent_joint[link].parent
    return True


def _leader(joint: _UrdfJoint, joints: dict[str, _UrdfJoint], chain: set[str],
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
        if mimic.joint not in chain:
            raise _fail(source, f"joint {current.name!r} mimics joint {mimic.joint!r}, which is not on the chain "
                                f"(choose base_link and tip_link so that the chain holds both)", where)
        if mimic.joint in followed:
            raise _fail(source, f"mimic joints form a cycle: {' -> '.join([*followed, mimic.joint])}", where)
        leader = joints[mimic.joint]
        if leader.type not in _MOVING:
            raise _fail(source, f"joint {current.name!r} mimics joint {mimic.joint!r}, a {leader.type} joint", where)
        offset, multiplier = offset + multiplier * mimic.offset, multiplier * mimic.multiplier
        followed.append(leader.name)
        current = leader
    return current.name, multiplier, offset


def _coupled(robot: Robot, path: list[_UrdfJoint], joints: dict[str, _UrdfJoint], source: str) -> Robot:
    """``robot`` with the coupling of the mimic joints of its chain (``robot`` itself when there are none)."""
    moving = [joint for joint in path if joint.type in _MOVING]
    if all(joint.mimic is None for joint in moving):
        return robot
    variable = {joint.name: symbol for joint, symbol in zip(moving, robot.joint_variables, strict=True)}
    values = []
    for joint in moving:
        leader, multiplier, offset = _leader(joint, joints, {j.name for j in path}, source)
        values.append(multiplier * variable[leader] + offset)
    coordinates = tuple(variable[joint.name] for joint in moving if joint.mimic is None)
    return replace(robot, coupling=Coupling(coordinates, tuple(values)))


def _robot(robot_name: str, path: list[_UrdfJoint], source: str, all_joints: dict[str, _UrdfJoint]) -> Robot:
    pending: list[FixedTransform] = []
    joints: list[Joint] = []
    for urdf_joint in path:
        if urdf_joint.type not in _MOVING:
            pending.append(urdf_joint.origin)
            continue
        origin = _combine([*pending, urdf_joint.origin], [])
        pending = []
        axis = urdf_joint.axis
        placement = GeneralPlacement(None if origin == FixedTransform() else origin,
                                     None if tuple(axis) == (0, 0, 1) else axis)
        joints.append(Joint(index=len(joints) + 1, type=_MOVING[urdf_joint.type], placement=placement,
                            limits=urdf_joint.limits, name=urdf_joint.name))
    last_alignment = alignment(placement.unit_axis)
    tool = _combine(pending, list(inverse_motions(last_alignment)))
    # every number was checked finite when read, limits ordered, names made identifiers: the robot is valid
    robot = Robot(name=robot_name, convention=Convention.GENERAL, joints=tuple(joints),
                  description=f"from {Path(source).name}", tool=None if tool == FixedTransform() else tool,
                  source=source)
    return _coupled(robot, path, all_joints, source)


def _combine(transforms: list[FixedTransform], prefix: list) -> FixedTransform:
    """The product ``prefix @ transforms[0] @ ...`` as one fixed transform, in xyz/rpy form whenever exact."""
    nontrivial = [t for t in transforms if t != FixedTransform()]
    if not prefix and len(nontrivial) <= 1:
        return nontrivial[0] if nontrivial else FixedTransform()
    rotation_matrix, position = compose([*prefix, *(sp.Matrix(t.matrix) for t in nontrivial)])
    return fixed_transform_from_matrix(homogeneous(rotation_matrix, position))


def _identifier(text: str) -> str:
    name = _NAME_CHARS.sub("_", text)
    return name if name[:1].isalpha() else f"r_{name}"
