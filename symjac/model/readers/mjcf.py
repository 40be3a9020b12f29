r"""The MJCF reader: a MuJoCo model as a :class:`~symjac.model.readers.tree.KinematicTree`, then a serial chain.

What is read
    ``<mujoco model>``; ``<compiler angle eulerseq autolimits>`` (MJCF angles are in **degrees** unless
    ``angle="radian"``); ``<default>`` classes (nested, ``class`` and ``childclass``) for joints, sites and
    equalities; ``<include file>`` (:mod:`symjac.model.readers.mjcf_xml`); the ``<worldbody>`` tree: each ``<body>``
    is a link (``worldbody`` is the link ``world``) placed by ``pos`` and one orientation attribute
    (:mod:`symjac.model.readers.mjcf_frames`), also inside ``<frame>`` elements; its ``<joint>`` elements (``hinge``
    and ``slide``, with ``pos``, ``axis``, ``range``, ``limited``, ``ref``, and ``armature``, ``damping`` and
    ``frictionloss`` as the joint's :class:`~symjac.model.drive.Drive`); its ``<inertial pos (orientation) mass
    diaginertia | fullinertia>``; its ``<site>`` elements; and ``<equality><joint joint1 joint2 polycoef>``.
    Geoms, meshes, actuators, sensors, tendons and contacts are not read: a body without ``<inertial>`` has no
    inertial data here, although MuJoCo would compute one from its geoms; with ``<compiler inertiafromgeom="true">``
    (MuJoCo then ignores ``<inertial>``) no body has any.

Joints
    A body without joints is fixed to its parent. A hinge at ``pos`` :math:`p` (body frame) turns the body about the
    axis through :math:`p`: the tree gets a joint at ``body pose * T(p)``, a link at the turned anchor and a fixed
    joint :math:`T(-p)` to the body, which the chain folds away. Several joints in one body act one after the other
    (MuJoCo's order), each on an intermediate link named ``body[joint]``. The joint variable is MuJoCo's ``qpos``:
    a joint with ``ref`` :math:`r` places the body as written at ``qpos = r``, so its origin is turned (or moved) by
    :math:`-r` about (along) its axis. Limits: ``range`` when ``limited="true"``, or ``limited="auto"`` (the default)
    with ``autolimits``; hinge ranges and ``ref`` are angles in the compiler's unit. ``ball`` and ``free`` joints
    (and ``<freejoint>``) are refused on the chain with the reason, and held still beside it (a free object in the
    scene does not stop the arm from loading). ``<equality><joint>`` with ``polycoef="c0 c1 0 0 0"`` (MuJoCo's
    :math:`q_1 - r_1 = c_0 + c_1 (q_2 - r_2)`) is a mimic rule of ``joint1`` (a coupling); higher coefficients, a
    ``joint1`` without ``joint2`` (a locked joint) and two equalities on one joint are refused; inactive ones
    (``active="false"``) are ignored; equalities of other types (connect, weld, tendon) are not read.

Sites
    A ``tip_link`` that names a site (and no body), or ``tip_site``, ends the chain at that site: the tool frame is
    the site's frame.

Numbers and safety as in :mod:`symjac.model.readers.mjcf_frames` and :mod:`symjac.model.readers.mjcf_xml`; every
problem raises :class:`~symjac.errors.RobotFileError` naming the file and the element.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field, replace
from pathlib import Path

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.drive import Drive, drive_problem
from symjac.model.exact_transforms import fixed_transform_from_matrix
from symjac.model.readers import too_many_links
from symjac.model.readers.mjcf_frames import Compiler, angle, frame, numbers, rotation_about
from symjac.model.readers.mjcf_xml import MAX_MJCF_BYTES, Defaults, compiler_of, defaults_of, model_root
from symjac.model.readers.tree import (
    ChainChoiceError,
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
from symjac.symbolic.transforms import homogeneous

__all__ = ["MAX_MJCF_BYTES", "MjcfModel", "mjcf_model", "robot_from_mjcf"]

WORLD = "world"
_KINDS = ("hinge", "slide", "ball", "free")
_REFUSED = {"ball": "a ball joint turns about three axes at once (one quaternion): symjac's joints have one "
                    "variable each; write it as three hinges",
            "free": "a free joint lets the body float: choose a base_link at or below this body"}


@dataclass
class MjcfModel:
    """What an MJCF file holds for symjac: its kinematic tree, its sites and the joints symjac cannot model.

    ``sites[name] = (link, T)``: the site's pose ``T`` (4 x 4) in the frame of ``link``; ``refused[joint]``: why a
    tree joint of type floating (a ball or free joint) cannot be on a chain.
    """

    tree: KinematicTree
    sites: dict[str, tuple[str, sp.Matrix]] = field(default_factory=dict)
    refused: dict[str, str] = field(default_factory=dict)


def robot_from_mjcf(content: str | bytes, source: str = "<mjcf>", base_link: str | None = None,
                    tip_link: str | None = None, name: str | None = None, *, tip_site: str | None = None,
                    folder: str | Path | None = None, max_bytes: int = MAX_MJCF_BYTES) -> Robot:
    """Build the general-convention robot of the chain ``base_link`` .. ``tip_link`` (or ``tip_site``) of an MJCF model.

    Parameters
    ----------
    content : str or bytes
        The MJCF text (UTF-8).
    source : str
        The file name, used in error messages; its folder is where ``<include>`` files are looked for.
    base_link, tip_link : str, optional
        Body names: the chain's first and last link (defaults: ``world``, and the only leaf body). ``tip_link`` may
        name a site instead.
    name : str, optional
        The robot's name (default: the ``<mujoco model>``, made an identifier).
    tip_site : str, optional
        A site that ends the chain (its frame is the tool frame); not with ``tip_link``.
    folder : str or Path, optional
        The folder ``<include file>`` is relative to (default: the folder of ``source`` when it is a file).
    max_bytes : int
        The most bytes the model and its included files may hold together (default :data:`MAX_MJCF_BYTES`).

    Raises
    ------
    RobotFileError
        For hostile or malformed input and chains symjac cannot model (see the module text), naming file and element.

    Examples
    --------
    >>> mjcf = '''<mujoco model="arm"><worldbody><body name="l1" pos="0 0 0.5">
    ...   <joint name="j1" axis="0 1 0" range="-90 90"/><site name="tip" pos="0.4 0 0"/></body></worldbody></mujoco>'''
    >>> robot = robot_from_mjcf(mjcf, tip_site="tip")
    >>> robot.joints[0].limits, robot.joints[0].placement.axis, robot.tool.xyz
    ((-pi/2, pi/2), (0, 1, 0), (2/5, 0, 0))
    """
    data = content.encode("utf-8", "surrogatepass") if isinstance(content, str) else bytes(content)
    if folder is None and source != "<mjcf>" and Path(source).is_file():
        folder = Path(source).parent
    model = mjcf_model(data, source, Path(folder) if folder is not None else None, max_bytes=max_bytes)
    if tip_site is not None and tip_link is not None:
        raise ChainChoiceError("give {tip_link} or {tip_site}, not both", source=source)
    links = {link.name for link in model.tree.links}
    site = tip_site if tip_site is not None else tip_link if tip_link is not None and tip_link not in links else None
    tree = model.tree
    if site is not None:
        if site not in model.sites:
            sites = ", ".join(sorted(model.sites)) or "none"
            if tip_site is None:  # a name given as the tip link that is neither a body nor a site
                words = f"{site!r} is neither a body nor a site of this model (bodies: {', '.join(sorted(links))}; " \
                        f"sites: {sites})"
                raise ChainChoiceError("{tip_link} " + words.replace("{", "{{").replace("}", "}}"), source=source)
            raise RobotFileError(f"site {site!r} is not a site of this model (sites: {sites})", source=source)
        body, T = model.sites[site]
        tip_link = site if site not in links else f"{site} (site)"
        tree = KinematicTree(tree.name, (*tree.links, TreeLink(tip_link)),
                             (*tree.joints, TreeJoint(f"{tip_link} (fixed)", TreeJointType.FIXED, body, tip_link,
                                                      fixed_transform_from_matrix(T))))
    try:
        return replace(robot_from_tree(tree, source, base_link=base_link, tip_link=tip_link, name=name),
                       source_format="MJCF")
    except RobotFileError as error:
        joint = (error.field or "").removeprefix("joint ")
        if joint in model.refused:  # a ball or free joint on the chain: say why, in MJCF's words
            raise RobotFileError(model.refused[joint], source=source, field=f"joint {joint}") from None
        if isinstance(error, ChainChoiceError) and error.template.startswith("choose {tip_link}") and model.sites:
            sites = ", ".join(sorted(model.sites)[:20]).replace("{", "{{").replace("}", "}}")
            raise ChainChoiceError(f"{error.template}; or end it at a site with {{tip_site}} ({sites})",
                                   source=source) from None
        raise


def mjcf_model(data: bytes | str, source: str = "<mjcf>", folder: Path | None = None, *,
               max_bytes: int = MAX_MJCF_BYTES) -> MjcfModel:
    """The kinematic tree, sites and refused joints of an MJCF document (see the module text)."""
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogatepass")
    root = model_root(data, source, folder, max_bytes)
    too_many_links(sum(1 for _ in root.iter("body")), source)
    reader = _Reader(source, compiler_of(root, source), defaults_of(root, source))
    worldbodies = root.findall("worldbody")
    reader.links.append(TreeLink(WORLD))
    for worldbody in worldbodies:
        reader.walk(worldbody)
    mimics = _mimics(root, reader)
    joints = tuple(TreeJoint(j.name, j.type, j.parent, j.child, j.origin, j.axis, j.limits, mimics.get(j.name),
                             j.drive) for j in reader.joints)
    tree = KinematicTree(root.get("model") or "mjcf_robot", tuple(reader.links), joints)
    return MjcfModel(tree, reader.sites, reader.refused)


def _fail(source: str, message: str, element: str | None = None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def _transform(T: sp.Matrix) -> FixedTransform:
    return FixedTransform() if sp.eye(4) == T else fixed_transform_from_matrix(T)


def _translation(vector: list[sp.Expr]) -> sp.Matrix:
    return homogeneous(sp.eye(3), sp.Matrix(vector))


class _Reader:
    """The walk over ``<worldbody>``: links, joints, sites and refused joints, in MuJoCo's (depth-first) order."""

    def __init__(self, source: str, compiler: Compiler, defaults: Defaults):
        self.source, self.compiler, self.defaults = source, compiler, defaults
        self.links: list[TreeLink] = []
        self.joints: list[TreeJoint] = []
        self.sites: dict[str, tuple[str, sp.Matrix]] = {}
        self.refused: dict[str, str] = {}
        self.kinds: dict[str, TreeJointType] = {}
        self.references: dict[str, sp.Expr] = {}
        self.bodies = 0
        self.joint_count = 0

    def walk(self, worldbody: ET.Element) -> None:
        for child in worldbody:
            if child.tag in ("joint", "freejoint"):
                raise _fail(self.source, "joints belong in bodies, not in <worldbody>", "worldbody")
        # (element, link of the enclosing body, pose of the element's frame in that link, childclass)
        stack: list[tuple[ET.Element, str, sp.Matrix, str]] = [(worldbody, WORLD, sp.eye(4), "main")]
        while stack:
            element, link, pose, childclass = stack.pop()
            children: list[tuple[ET.Element, str, sp.Matrix, str]] = []
            for child in element:
                where = f"{child.tag} {child.get('name') or '(unnamed)'} in body {link}"
                if child.tag in ("body", "frame"):
                    own_class = child.get("childclass", childclass)
                    self.defaults.check(own_class, self.source, where)
                    attributes = self.defaults.attributes(child, childclass, self.source, where) \
                        if child.tag == "frame" else child.attrib
                    T = pose * frame(attributes, self.compiler, self.source, where)
                    if child.tag == "frame":
                        if child.find("joint") is not None or child.find("freejoint") is not None:
                            raise _fail(self.source, "joints inside <frame> are not read", where)
                        children.append((child, link, T, own_class))
                    else:
                        children.append((child, self.body(child, link, T, childclass), sp.eye(4), own_class))
                elif child.tag == "site":
                    self.site(child, link, pose, childclass, where)
            stack.extend(reversed(children))

    def body(self, element: ET.Element, parent: str, T: sp.Matrix, childclass: str) -> str:
        """Add the body's link and the joints from ``parent`` to it; return the link's name."""
        self.bodies += 1
        name = element.get("name") or f"body{self.bodies}"
        own_class = element.get("childclass", childclass)
        inertial = None if self.compiler.inertia_from_geoms else element.find("inertial")
        kinds = []
        for joint in element:
            if joint.tag not in ("joint", "freejoint"):
                continue
            self.joint_count += 1
            attributes = {**joint.attrib, "type": "free"} if joint.tag == "freejoint" else \
                self.defaults.attributes(joint, own_class, self.source, f"joint in body {name}")
            joint_name = attributes.get("name") or f"joint{self.joint_count - 1}"
            kind = attributes.get("type", "hinge")
            if kind not in _KINDS:
                raise _fail(self.source, f"unknown joint type {kind!r}; MJCF types are {', '.join(_KINDS)}",
                            f"joint {joint_name}")
            kinds.append((joint_name, kind, attributes))
        refused = [(joint_name, kind) for joint_name, kind, _ in kinds if kind in _REFUSED]
        link = TreeLink(name, self._inertial(inertial, name) if inertial is not None else None)
        if refused:  # held still beside the chain, refused on it
            joint_name, kind = refused[0]
            self.refused[joint_name] = f"{kind} joint {joint_name!r} (body {name}): {_REFUSED[kind]}"
            self.links.append(link)
            self.joints.append(TreeJoint(joint_name, TreeJointType.FLOATING, parent, name, _transform(T)))
            return name
        pending = T
        previous = parent
        for index, (joint_name, kind, attributes) in enumerate(kinds):
            where = f"joint {joint_name}"
            axis = numbers(attributes.get("axis", "0 0 1"), 3, self.source, f"{where} axis")
            if all(v == 0 for v in axis):
                raise _fail(self.source, "the axis must not be the zero vector", f"{where} axis")
            hinge = kind == "hinge"
            reference = self._angle_or_length(attributes.get("ref", "0"), hinge, f"{where} ref")
            if hinge:
                p = numbers(attributes.get("pos", "0 0 0"), 3, self.source, f"{where} pos")
                origin = pending * _translation(p)
                if reference != 0:
                    origin = origin * homogeneous(rotation_about(axis, -reference), sp.zeros(3, 1))
                after = _translation([-v for v in p])
            else:
                norm = sp.sqrt(sum(v**2 for v in axis))
                origin = pending * _translation([sp.radsimp(-reference * v / norm) for v in axis])
                after = sp.eye(4)
            last = index == len(kinds) - 1
            child = name if last and after == sp.eye(4) else f"{name}[{joint_name}]"
            if child != name:
                self.links.append(TreeLink(child))
            self.kinds[joint_name] = TreeJointType.REVOLUTE if hinge else TreeJointType.PRISMATIC
            self.references[joint_name] = reference
            limits = self._limits(attributes, hinge, where)
            self.joints.append(TreeJoint(joint_name, self.kinds[joint_name] if limits is not None or not hinge
                                         else TreeJointType.CONTINUOUS, previous, child, _transform(origin),
                                         tuple(axis), limits, drive=self._drive(attributes, where)))  # type: ignore
            previous, pending = child, after
        if previous != name or not kinds:
            self.joints.append(TreeJoint(f"{name} (fixed)", TreeJointType.FIXED, previous, name, _transform(pending)))
        self.links.append(link)
        return name

    def site(self, element: ET.Element, link: str, pose: sp.Matrix, childclass: str, where: str) -> None:
        attributes = self.defaults.attributes(element, childclass, self.source, where)
        name = attributes.get("name")
        if name is None:
            return  # an unnamed site cannot be asked for
        if name in self.sites:
            raise _fail(self.source, f"site {name!r} is defined twice", f"site {name}")
        self.sites[name] = (link, pose * frame(attributes, self.compiler, self.source, where))

    def _angle_or_length(self, text: str, hinge: bool, where: str) -> sp.Expr:
        value = numbers(text, 1, self.source, where, length=not hinge)[0]
        return angle(value, self.compiler, self.source, where) if hinge else value

    def _drive(self, attributes: dict[str, str], where: str) -> Drive | None:
        """``armature``, ``damping`` and ``frictionloss`` (MuJoCo's defaults 0, classes applied) as a drive."""
        values = [numbers(attributes.get(key, "0"), 1, self.source, f"{where} {key}", length=False)[0]
                  for key in ("armature", "damping", "frictionloss")]
        drive = Drive(*values)
        problem = drive_problem(drive)
        if problem is not None:
            raise _fail(self.source, problem, where)
        return None if drive.is_zero else drive

    def _limits(self, attributes: dict[str, str], hinge: bool, where: str) -> JointLimits | None:
        limited = attributes.get("limited", "auto")
        if limited not in ("true", "false", "auto"):
            raise _fail(self.source, f"limited must be 'true', 'false' or 'auto', got {limited!r}", where)
        if limited == "auto":
            if "range" in attributes and not self.compiler.autolimits:
                raise _fail(self.source, "a range without limited=... needs <compiler autolimits=\"true\">", where)
            limited = "true" if "range" in attributes else "false"
        if limited == "false":
            return None
        where = f"{where} range"
        bounds = [self._angle_or_length(text, hinge, where) for text in attributes.get("range", "0 0").split()] \
            if len(attributes.get("range", "0 0").split()) == 2 else None
        if bounds is None:
            raise _fail(self.source, f"expected 2 numbers, got {attributes['range'][:60]!r}", where)
        return JointLimits(bounds[0], bounds[1])

    def _inertial(self, element: ET.Element, body: str) -> LinkInertial:
        where = f"body {body} inertial"
        if "mass" not in element.attrib:
            raise _fail(self.source, "<inertial> needs mass=...", where)
        mass = numbers(element.get("mass", ""), 1, self.source, where, length=False)[0]
        pose = frame(element.attrib, self.compiler, self.source, where)
        if "fullinertia" in element.attrib:
            if pose[:3, :3] != sp.eye(3):  # MuJoCo's rule: the tensor's axes are the body's
                raise _fail(self.source, "fullinertia takes no orientation (quat, euler, ...)", where)
            xx, yy, zz, xy, xz, yz = numbers(element.get("fullinertia", ""), 6, self.source, where, length=False)
            tensor = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        elif "diaginertia" in element.attrib:
            tensor = sp.diag(*numbers(element.get("diaginertia", ""), 3, self.source, where, length=False))
        else:
            raise _fail(self.source, "<inertial> needs diaginertia=... or fullinertia=...", where)
        R = pose[:3, :3]
        tensor = (R * tensor * R.T).applyfunc(lambda e: sp.radsimp(sp.expand(e)))
        return LinkInertial(mass, tuple(pose[:3, 3]), (sp.S.Zero,) * 3,  # type: ignore[arg-type]
                            tensor[0, 0], tensor[0, 1], tensor[0, 2], tensor[1, 1], tensor[1, 2], tensor[2, 2])


def _mimics(root: ET.Element, reader: _Reader) -> dict[str, Mimic]:
    """The joint equalities as mimic rules: ``q1 = r1 + c0 + c1 (q2 - r2)`` is ``q1 = c1 q2 + (r1 + c0 - c1 r2)``."""
    source = reader.source
    mimics: dict[str, Mimic] = {}
    for equality in root.findall("equality"):
        for element in equality.findall("joint"):
            attributes = reader.defaults.attributes(element, "main", source, "equality joint")
            first, second = attributes.get("joint1"), attributes.get("joint2")
            where = f"equality joint {attributes.get('name') or first}"
            if attributes.get("active", "true") == "false":
                continue
            if not first:
                raise _fail(source, "<joint> equality needs joint1=...", where)
            for joint in (first, second):
                if joint is not None and joint not in reader.kinds:
                    raise _fail(source, f"{joint!r} is not a hinge or slide joint of this model", where)
            if second is None:
                raise _fail(source, f"joint {first!r} is locked (no joint2): make it part of the body instead", where)
            coefficients = numbers(attributes.get("polycoef", "0 1 0 0 0"), 5, source, f"{where} polycoef",
                                   length=False)
            if any(c != 0 for c in coefficients[2:]):
                raise _fail(source, "polycoef is not linear (c2, c3 or c4 is not zero): symjac couples joints "
                                    "linearly only", where)
            if first in mimics:
                raise _fail(source, f"joint {first!r} is coupled by two equalities", where)
            c0, c1 = coefficients[:2]
            offset = reader.references[first] + c0 - c1 * reader.references[second]
            mimics[first] = Mimic(second, c1, sp.nsimplify(offset) if offset.is_Float else offset)
    return mimics
