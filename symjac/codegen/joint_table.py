"""What a generated module says about its coordinates and its origin: names, types, limits, tip frame, source.

Every target exposes the same facts (``JOINT_NAMES``, ``JOINT_TYPES``, ``LOWER``, ``UPPER``, ``TIP_FRAME`` in Python,
``<robot>_joint_names`` and friends in C, ``joint_names`` in C++), taken from here, so that a ROS ``JointState``
or an optimiser's bounds can be matched by name without a hand-typed table.

Names travel as the robot file or URDF writes them, inside string literals only, and only when they pass
:data:`NAME_PATTERN` (ASCII letters, digits and ``_ . / : -``): nothing is escaped, anything else is refused. Where a
language needs an identifier (the C enum of indices, the C++ index constants) each name has an identifier-safe
variant: the other characters become ``_``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from symjac.codegen.names import IdentifierRule
from symjac.errors import CodegenError
from symjac.model.ends import end_point
from symjac.model.robot import Robot

__all__ = ["NAME_PATTERN", "JointEntry", "convention_words", "joint_entries", "name_identifier", "source_words",
           "tip_frame"]

NAME_PATTERN = re.compile(r"[A-Za-z0-9_./:-]{1,64}\Z")
"""The names a generated module may carry in a string literal: short, ASCII letters, digits, ``_ . / : -``."""

_FORMATS = {"URDF": "URDF file", "MJCF": "MJCF file", "TOML robot file": "robot file (TOML)"}
_CONVENTIONS = {
    "standard": "standard DH",
    "modified": "modified DH (Craig)",
    "general": "general (fixed origins and joint axes, as URDF and MJCF write them)",
    "poe": "product of exponentials (PoE)",
}


@dataclass(frozen=True)
class JointEntry:
    """One entry of ``q`` as a generated module describes it.

    ``name`` is the joint's name as the robot file or URDF writes it (the coordinate's symbol name, ``theta1``,
    when it gives none), ``identifier`` its identifier-safe variant, ``symbol`` the name symjac's formulas use,
    ``type`` ``"revolute"``, ``"prismatic"`` or ``"continuous"`` (revolute without limits), ``lower`` and ``upper``
    the position limits at the parameters' defaults (``-inf`` and ``inf`` when none are given).
    """

    name: str
    identifier: str
    symbol: str
    type: str
    lower: float = -math.inf
    upper: float = math.inf


def name_identifier(name: str) -> str:
    """``name`` made an identifier: characters other than letters, digits and ``_`` become ``_``; ``j_`` before a digit.

    Examples
    --------
    >>> name_identifier("arm/joint-1"), name_identifier("1st")
    ('arm_joint_1', 'j_1st')
    """
    text = "".join(c if c.isascii() and (c.isalnum() or c == "_") else "_" for c in name)
    return text if text[:1].isalpha() or text[:1] == "_" else f"j_{text}"


def joint_entries(robot: Robot, identifiers: IdentifierRule) -> tuple[JointEntry, ...]:
    """The entries of ``q`` of ``robot``: name, identifier, symbol, type and limits of each, in order.

    A coordinate that is a joint's variable takes that joint's name, type and limits (for a coupled robot: the
    joint that mimics nothing); another coordinate (a coupling's own ``s``, a mimic leader beside the chain) its
    symbol's name and the limits its followers imply (:func:`_implied_limits`).
    An identifier the target's language refuses (a keyword) gets a trailing ``_``.

    Raises
    ------
    CodegenError
        For a name outside :data:`NAME_PATTERN`, two coordinates of the same name, or two whose identifiers
        coincide (``a-b`` and ``a_b``).
    """
    by_variable = {joint.variable: joint for joint in robot.joints}
    entries = []
    for symbol, kind in zip(robot.q, robot.coordinate_types, strict=True):
        joint = by_variable.get(symbol)
        name = joint.name if joint is not None and joint.name else symbol.name
        if not NAME_PATTERN.match(name):
            raise CodegenError(f"{robot.source}: joint name {name!r} cannot appear in generated code: use at most 64 "
                               "ASCII letters, digits and the characters _ . / : -")
        lower, upper = -math.inf, math.inf
        if joint is not None and joint.limits is not None:
            lower, upper = (float(limit.subs(robot.defaults)) for limit in joint.limits)
        elif joint is None:
            lower, upper = _implied_limits(robot, symbol)
        continuous = joint is not None and joint.continuous
        entries.append(JointEntry(name, _identifier(name, identifiers), symbol.name,
                                  "continuous" if continuous else kind.value, lower, upper))
    for what, values in (("name", [e.name for e in entries]), ("identifier", [e.identifier for e in entries])):
        for index, value in enumerate(values):
            if value in values[:index]:
                raise CodegenError(f"{robot.source}: two coordinates have the joint {what} {value!r} "
                                   f"({entries[values.index(value)].name!r} and {entries[index].name!r})")
    return tuple(entries)


def _implied_limits(robot: Robot, coordinate: sp.Symbol) -> tuple[float, float]:
    r"""The bounds on a coordinate that no joint owns (a mimic leader beside the chain) its followers' limits imply.

    A joint :math:`\vartheta_i = m\,q + o` with limits :math:`[l_i, u_i]` allows :math:`q` between
    :math:`(l_i - o)/m` and :math:`(u_i - o)/m`; the coordinate's bounds are where every follower's allow it.
    """
    lower, upper = -math.inf, math.inf
    for joint, value in zip(robot.joints, robot.joint_values, strict=True):
        multiplier = sp.diff(value, coordinate)
        if joint.limits is None or multiplier == 0 or (value - multiplier * coordinate).has(*robot.q):
            continue  # no limits, not a follower, or a follower of several coordinates
        m = float(multiplier.subs(robot.defaults))
        o = float((value - multiplier * coordinate).subs(robot.defaults))
        ends = sorted((float(limit.subs(robot.defaults)) - o) / m for limit in joint.limits)
        lower, upper = max(lower, ends[0]), min(upper, ends[1])
    return lower, upper


def _identifier(name: str, identifiers: IdentifierRule) -> str:
    candidate = name_identifier(name)
    for attempt in (candidate, candidate + "_"):
        try:
            return identifiers.check(attempt, "joint name")
        except CodegenError:
            continue
    raise CodegenError(f"joint name {name!r} has no identifier-safe variant in the generated code ({candidate!r} "
                       f"and {candidate + '_'!r} are refused)")


def tip_frame(robot: Robot) -> str:
    """The name of the frame the chain ends at: a URDF's tip link, else ``tool`` or ``flange`` (the origin of {n}).

    Raises
    ------
    CodegenError
        For a name outside :data:`NAME_PATTERN`.
    """
    name = robot.tip_frame or end_point(robot)
    if not NAME_PATTERN.match(name):
        raise CodegenError(f"{robot.source}: tip frame name {name!r} cannot appear in generated code: use at most "
                           "64 ASCII letters, digits and the characters _ . / : -")
    return name


def convention_words(convention: str) -> str:
    """How a header names a convention: ``standard DH``, ``modified DH (Craig)``, ``general (fixed origins ...)``."""
    return _CONVENTIONS.get(convention, convention)


def source_words(robot: Robot, catalog_files: frozenset[str] = frozenset()) -> str:
    """Where the robot came from, for a header: ``URDF file ur5.urdf``, ``robot file (TOML) arm.toml``, ...

    Only the file's name is said (a path would make the header depend on the machine); ``catalog_files`` are the
    file names of symjac's catalog (``planar2r.toml``, ``ur5.urdf``), said as such when the robot is one of them.

    Examples
    --------
    >>> from symjac import load_robot
    >>> source_words(load_robot("ur5.urdf"), frozenset({"ur5.urdf"}))
    "the symjac catalog's URDF file ur5.urdf"
    """
    source = robot.source
    if source.startswith("<") and source.endswith(">"):
        return {"<mapping>": "a mapping", "<string>": "a robot-file string"}.get(
            source, f"a {source.strip('<>').upper()} string")
    path = Path(source)
    # a file name is the user's: only plain characters reach a comment (a newline would end a Python comment, and
    # "*/" a C one), and a header line has room for 60
    name = re.sub(r"[^A-Za-z0-9_.+-]", "_", path.name)
    name = name if len(name) <= 60 else name[:57] + "..."
    kind = _FORMATS.get(robot.source_format) or {".urdf": "URDF file", ".xml": "XML file", ".mjcf": "MJCF file",
                                                 ".toml": "robot file (TOML)"}.get(path.suffix.lower(), "file")
    if source in catalog_files and not path.is_file():
        return f"the symjac catalog's {kind} {name}"
    return f"{kind} {name}"
