r"""The URDF reader: a URDF document as a :class:`~symjac.model.readers.tree.KinematicTree`, then a serial chain.

What is read
    ``<robot name>``; every ``<link name>`` with its ``<inertial>`` (``<origin xyz rpy>``, ``<mass value>``,
    ``<inertia ixx ixy ixz iyy iyz izz>``); and every ``<joint name type>`` with its ``<parent link>``,
    ``<child link>``, ``<origin xyz rpy>``, ``<axis xyz>``, ``<limit lower upper velocity effort>``, ``<mimic>`` and
    ``<dynamics damping friction>`` (viscous and Coulomb friction, :class:`~symjac.model.drive.Drive`).
    Visual, collision, transmission and gazebo elements are ignored. Position limits with ``lower = upper = 0``
    (URDF's default) mean "no limits", and so do two bounds of at least :data:`MAX_URDF_ANGLE` in size (``+-1e16``,
    which files written for Gazebo give spinning rotors); any other pair must have ``lower < upper``. URDF angles
    are radians: an ``rpy`` entry of more than a turn, or a revolute limit of more than two turns, is refused as degrees
    (:func:`symjac.model.bounds.urdf_turn_problem`). The chain between two links, fixed joints, mimic joints and
    frames are the tree's (:mod:`symjac.model.readers.tree`).

Mimic joints
    ``<mimic joint="J" multiplier="m" offset="o"/>`` on a moving joint (defaults 1 and 0): its position is
    :math:`m\,x_J + o`. ``<mimic>`` on fixed joints is ignored.

Numbers
    Every number becomes an exact rational (``0.333 -> 333/1000``), so derivations stay exact and fast. An angle (an
    ``rpy`` entry or a revolute limit) within :data:`symjac.model.expressions.ANGLE_SNAP_TOLERANCE` (1e-9) of a multiple
    of :math:`\pi/12` becomes that exact multiple of :math:`\pi` (``1.5707963267949 -> pi/2``), so symbolic results read
    :math:`\cos(\pi/2) = 0`, not a decimal. Axes are made unit exactly: ``0 1 1`` is :math:`(0, \sqrt2/2, \sqrt2/2)`.

Safety
    The file is parsed with the standard library's expat parser, after refusing any document type declaration
    (``<!DOCTYPE``/``<!ENTITY``): no entity is ever expanded and no other file or URL is ever read (no external
    entities, no ``package://`` lookups). A xacro file (elements or attributes in the xacro namespace, ``${...}``
    or ``$(...)`` in attribute values; never what comments or text hold) is refused with the command that expands
    it into a new file. Files up to :data:`MAX_URDF_BYTES` (5 MB) in UTF-8, or in US-ASCII or ISO-8859-1 when the XML
    declaration says so, are read: the whole file is parsed in memory, and a real arm's file is tens of kilobytes
    (the largest of a public collection of 69 robots, a dual-arm mobile manipulator, is 211 kB), so the limit keeps
    runaway and hostile files out; ``max_bytes`` raises it.
    Every problem raises :class:`~symjac.errors.RobotFileError` naming the file and the element.
"""

from __future__ import annotations

import re
import shlex
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import sympy as sp

from symjac.errors import ExpressionError, RobotFileError
from symjac.model.bounds import size_problem, urdf_turn_problem
from symjac.model.drive import Drive, drive_problem
from symjac.model.expressions import exact_number, snap_angle
from symjac.model.readers import too_large, too_many_links
from symjac.model.readers.tree import (
    JointLimits,
    KinematicTree,
    LinkInertial,
    Mimic,
    TreeJoint,
    TreeJointType,
    TreeLink,
    robot_from_tree,
)
from symjac.model.robot import FixedTransform, Robot

__all__ = ["MAX_URDF_ANGLE", "MAX_URDF_BYTES", "robot_from_urdf", "tree_from_urdf"]

MAX_URDF_BYTES = 5_000_000
"""Largest URDF file read by default, in bytes (a real arm's file is tens of kilobytes; larger is refused in one
line, and ``max_bytes`` raises the limit)."""
MAX_URDF_ANGLE = 10**9
"""Radians: the largest angle read (a float this large has lost every digit below 1e-7 rad); position bounds this
large in size mean "no bound"."""
_TYPES = {kind.value: kind for kind in TreeJointType}
_MOVING = {TreeJointType.REVOLUTE, TreeJointType.CONTINUOUS, TreeJointType.PRISMATIC}
_BOUNDED = {TreeJointType.REVOLUTE, TreeJointType.PRISMATIC}  # a continuous joint's lower and upper are ignored
_DECLARATION = re.compile(rb"<!\s*(DOCTYPE|ENTITY|ELEMENT|ATTLIST)", re.IGNORECASE)
_ENCODING = re.compile(rb"""^(?:\xef\xbb\xbf)?\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")
_ENCODINGS = {"utf-8": "utf-8", "utf8": "utf-8", "us-ascii": "ascii", "ascii": "ascii", "iso-8859-1": "latin-1",
              "iso8859-1": "latin-1", "latin-1": "latin-1", "latin1": "latin-1", "l1": "latin-1"}
_SUBSTITUTION = re.compile(r"\$[{(]")  # xacro's ${expression} and $(find package) in an attribute value
_INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def robot_from_urdf(
    content: str | bytes,
    source: str = "<urdf>",
    base_link: str | None = None,
    tip_link: str | None = None,
    name: str | None = None,
    max_bytes: int = MAX_URDF_BYTES,
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
    max_bytes : int
        The largest document read, in bytes (default :data:`MAX_URDF_BYTES`).

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
    robot = robot_from_tree(tree_from_urdf(content, source, max_bytes=max_bytes), source, base_link=base_link,
                            tip_link=tip_link, name=name)
    return replace(robot, source_format="URDF")


def tree_from_urdf(content: str | bytes, source: str = "<urdf>", *, max_bytes: int = MAX_URDF_BYTES) -> KinematicTree:
    """The links and joints of a URDF document, checked element by element (see the module text)."""
    root = _parse(content, source, max_bytes)
    too_many_links(len(root.findall("link")), source)
    links = []
    seen: set[str] = set()
    for link in root.findall("link"):
        link_name = link.get("name")
        if not link_name:
            raise _fail(source, "a <link> has no name", "link")
        if link_name in seen:
            raise _fail(source, f"link {link_name!r} is defined twice", f"link {link_name}")
        seen.add(link_name)
        links.append(TreeLink(link_name, _inertial(link.find("inertial"), source, f"link {link_name} inertial")))
    joints = [_joint(joint, source) for joint in root.findall("joint")]
    return KinematicTree(root.get("name") or "urdf_robot", tuple(links), tuple(joints))


def _fail(source: str, message: str, element: str | None = None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def _parse(content: str | bytes, source: str, max_bytes: int) -> ET.Element:
    if isinstance(content, str):
        try:
            data = content.encode("utf-8")
        except UnicodeEncodeError as error:  # lone surrogates
            raise _fail(source, f"not UTF-8 text: {error}") from None
    else:
        data = bytes(content)
    if len(data) > max_bytes:
        raise _fail(source, too_large(max_bytes))
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
    try:
        # expat reads the declared encoding itself (UTF-8, US-ASCII and ISO-8859-1 are built in)
        root = ET.fromstring(data)
    except ET.ParseError as error:
        if "unbound prefix" in str(error) and _tag_at(text, error.position).startswith("xacro:"):
            raise _xacro(source) from None  # <xacro:macro> without the xmlns:xacro declaration
        raise _fail(source, f"invalid XML: {error}") from None
    except RecursionError:  # pragma: no cover - expat is iterative; kept for tree builders that are not
        raise _fail(source, "invalid XML: elements nested too deeply") from None
    if root.tag != "robot":
        raise _fail(source, f"the root element must be <robot>, got <{root.tag}>")
    if _is_xacro(root):
        raise _xacro(source)
    return root


def _is_xacro(root: ET.Element) -> bool:
    """Whether the parsed document still needs xacro (xacro elements or attributes, substitutions in attributes).

    Signs: an element or attribute in the xacro namespace, or ``${...}`` or ``$(...)`` in an attribute value.

    Comments and text are not looked at: files written by xacro keep commented-out macros and ``${...}`` in comments,
    and the ``xmlns:xacro`` declaration alone, which xacro leaves on the ``<robot>`` it writes, is no sign either.
    """
    for element in root.iter():
        if _in_xacro_namespace(element.tag):
            return True
        for key, value in element.attrib.items():
            if _in_xacro_namespace(key) or _SUBSTITUTION.search(value):
                return True
    return False


def _in_xacro_namespace(name: str) -> bool:
    return name.startswith("{") and name[1:name.find("}")].rstrip("/#").endswith("xacro")


def _tag_at(text: str, position: tuple[int, int]) -> str:
    """The element name starting at expat's (line, column) ``position`` of ``text`` ("" if none)."""
    line, column = position
    lines = text.splitlines()
    start = lines[line - 1][column:] if 0 < line <= len(lines) else ""
    match = re.match(r"<\s*([\w.:-]+)", start)
    return match.group(1) if match else ""


def _xacro(source: str) -> RobotFileError:
    """The refusal of a xacro file, with a command that expands it into a new file beside it.

    The output never is the input nor a file that exists (``-o``, not a shell redirection, which would empty the
    input before xacro reads it), and both paths are quoted for a POSIX shell.
    """
    path = Path(source) if source != "<urdf>" else Path("FILE.urdf.xacro")
    stem = path.name.removesuffix(".xacro").removesuffix(".urdf")
    candidates = [f"{stem}.urdf", f"{stem}_expanded.urdf", *(f"{stem}_expanded_{k}.urdf" for k in range(2, 100))]
    output = next(path.with_name(name) for name in candidates
                  if path.with_name(name) != path and not path.with_name(name).exists())
    return _fail(source, f"this is a xacro file (xacro macros or ${{...}} substitutions are not URDF): run "
                         f"`xacro {shlex.quote(str(path))} -o {shlex.quote(str(output))}` first and load {output}")


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


def _origin(element: ET.Element | None, source: str, where: str) -> FixedTransform:
    """``<origin xyz rpy>`` (the identity without one), its angles snapped and bounded."""
    xyz = _vector(element.get("xyz") if element is not None else None, source, where)
    rpy = [snap_angle(v) for v in _vector(element.get("rpy") if element is not None else None, source, where)]
    for values, angle, name in ((xyz, False, "xyz"), (rpy, True, "rpy")):  # and sin(1e308) would not reduce
        problems = (size_problem(float(v), angle=angle) or (urdf_turn_problem(float(v)) if angle else None)
                    for v in values)  # an angle of more than a turn is degrees written in a radian format
        problem = next((p for p in problems if p is not None), None)
        if problem is not None:
            raise _fail(source, f"{name}: {problem}", where)
    return FixedTransform(xyz=tuple(xyz), rpy=tuple(rpy))  # type: ignore[arg-type]


def _joint(joint: ET.Element, source: str) -> TreeJoint:
    joint_name = joint.get("name")
    if not joint_name:
        raise _fail(source, "a <joint> has no name", "joint")
    where = f"joint {joint_name}"
    kind = _TYPES.get(joint.get("type") or "")
    if kind is None:
        raise _fail(source, f"unknown joint type {joint.get('type')!r}; URDF types are {', '.join(sorted(_TYPES))}",
                    where)
    ends = []
    for tag in ("parent", "child"):
        element = joint.find(tag)
        link_name = element.get("link") if element is not None else None
        if not link_name:
            raise _fail(source, f"missing <{tag} link=...>", where)
        ends.append(link_name)
    origin = _origin(joint.find("origin"), source, f"{where} origin")
    axis_element = joint.find("axis")
    axis = _vector(axis_element.get("xyz") if axis_element is not None else None, source, f"{where} axis", (1, 0, 0))
    return TreeJoint(joint_name, kind, ends[0], ends[1], origin, tuple(axis),  # type: ignore[arg-type]
                     _limits(joint.find("limit"), kind, source, f"{where} limit"), _mimic(joint, kind, source, where),
                     _dynamics(joint.find("dynamics"), kind, source, f"{where} dynamics"))


def _dynamics(element: ET.Element | None, kind: TreeJointType, source: str, where: str) -> Drive | None:
    """``<dynamics damping friction>``: viscous and Coulomb friction of a moving joint (missing ones 0)."""
    if element is None or kind not in _MOVING:
        return None
    drive = Drive(viscous=_number(element.get("damping", "0"), source, where),
                  coulomb=_number(element.get("friction", "0"), source, where))
    problem = drive_problem(drive)
    if problem is not None:
        raise _fail(source, problem, where)
    return drive


def _limits(element: ET.Element | None, kind: TreeJointType, source: str, where: str) -> JointLimits | None:
    """``<limit>``: position bounds of revolute and prismatic joints (0, 0 is none), speed and effort if given."""
    if element is None or kind not in _MOVING:
        return None
    lower = upper = None
    if kind in _BOUNDED:
        bounds = [_number(element.get(key, "0"), source, where) for key in ("lower", "upper")]
        # +-1e16, as files written for Gazebo give spinning rotors, is no bound at all (nor is it degrees)
        unbounded = all(abs(b) >= MAX_URDF_ANGLE for b in bounds)
        if kind is TreeJointType.REVOLUTE and not unbounded:
            bounds = [snap_angle(b) for b in bounds]
            problem = next((p for p in (urdf_turn_problem(float(b), limit=True) for b in bounds) if p), None)
            if problem is not None:  # multi-turn wrists pass (bounds.MAX_URDF_LIMIT), limits in degrees do not
                raise _fail(source, problem, where)
        if not unbounded and (bounds[0] != 0 or bounds[1] != 0):  # lower = upper = 0 is "no limits given" too
            lower, upper = bounds
    rates = [_number(element.get(key), source, where) if element.get(key) is not None else None  # type: ignore
             for key in ("velocity", "effort")]
    return JointLimits(lower, upper, *rates)


def _mimic(joint: ET.Element, kind: TreeJointType, source: str, where: str) -> Mimic | None:
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
    return Mimic(leader, multiplier, offset if kind is TreeJointType.PRISMATIC else snap_angle(offset))


def _inertial(element: ET.Element | None, source: str, where: str) -> LinkInertial | None:
    """``<inertial>``: the mass, the inertial frame's ``<origin>`` and the tensor's six entries (missing ones 0)."""
    if element is None:
        return None
    mass_element = element.find("mass")
    if mass_element is None or mass_element.get("value") is None:
        raise _fail(source, "<inertial> needs <mass value=...>", where)
    mass = _number(mass_element.get("value"), source, where)  # type: ignore[arg-type]
    origin = _origin(element.find("origin"), source, f"{where} origin")
    inertia = element.find("inertia")
    entries = [_number(inertia.get(key, "0") if inertia is not None else "0", source, f"{where} inertia")
               for key in _INERTIA_KEYS]
    return LinkInertial(mass, origin.xyz, origin.rpy, *entries)
