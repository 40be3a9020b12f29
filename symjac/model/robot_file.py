r"""Robot descriptions as mappings (the parsed TOML file) to :class:`~symjac.model.robot.Robot` and back, validated.

Every field is checked before a robot is built, and an error names the file, the joint and the field. Expressions
in fields (``"-pi/2"``, ``"L1 + L2"``) go through the whitelist parser of :mod:`symjac.model.expressions`, never through
``eval`` or ``sympify``. The file format is described in the README ("Robot files").

Coupled joints: a joint table may say ``coupled = "-(theta2 + theta3)"``: that joint's variable is not free but equals
the expression, which must be affine (a constant plus constant multiples) in the variables of the joints that are
*not* coupled, with parameters and ``pi`` allowed in the coefficients (``coupled = "0.02 * theta4 / (2*pi) + d30"``).
Those uncoupled joints' variables, in chain order, are the robot's independent coordinates
(:mod:`symjac.model.coordinates`). A coupled expression may not name a coupled joint's variable (its own or
another's), so there are no cycles to resolve; it is written in radians and lengths whatever ``angle_unit`` says.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import sympy as sp

from symjac.errors import ExpressionError, InertialWarning, RobotFileError, warn
from symjac.model.bounds import file_limits, size_problem
from symjac.model.conventions import PLUGINS, convention_named, file_inertials, plugin, with_file_inertials
from symjac.model.conventions.base import transform_fields
from symjac.model.coordinates import Coupling
from symjac.model.expressions import exact_number, expression_text, name_problem, parse_expression
from symjac.model.inertia import Inertial, inertial_from_table, inertial_problem, inertial_table
from symjac.model.inertial_parameters import placeholder_defaults, symbolic_links, symbolic_where_missing
from symjac.model.robot import FixedTransform, Joint, JointType, Parameter, Robot, reserved_names

__all__ = ["robot_from_mapping", "robot_to_mapping"]

_ROTATION_ROUNDING = 2e-5  # how far from a rotation a file's matrix may be (6 decimals: about 5e-6); kept as given


_TOP_KEYS = {"name", "description", "convention", "angle_unit", "parameters", "joints", "base", "tool", "inertials"}
_TRANSFORM_KEYS = {"xyz", "rpy", "matrix"}


def robot_from_mapping(data: Mapping[str, Any], source: str = "<mapping>") -> Robot:
    """Validate a robot description given as a mapping (the parsed TOML file) and build the :class:`Robot`.

    Parameters
    ----------
    data : mapping
        Keys ``name``, ``convention`` and ``joints`` (required), ``description``, ``angle_unit`` (``"rad"``, the
        default, or ``"deg"`` for alpha, revolute theta, rpy and revolute limits), ``parameters``, ``base``,
        ``tool``, ``inertials`` (``"symbolic"``: links without inertial data get symbolic inertial parameters,
        :func:`~symjac.model.inertial_parameters.symbolic_where_missing`). See the README for the full format.
    source : str
        Where the data came from, used in error messages.

    Returns
    -------
    Robot

    Raises
    ------
    RobotFileError
        Naming the source, the joint and the field of the first problem found.

    Examples
    --------
    >>> robot = robot_from_mapping({
    ...     "name": "planar2r", "convention": "standard", "parameters": {"L1": 1, "L2": 0.5},
    ...     "joints": [{"type": "revolute", "a": "L1"}, {"type": "revolute", "a": "L2"}]})
    >>> robot.q
    (theta1, theta2)
    """

    def fail(message: str, joint: int | None = None, field: str | None = None) -> RobotFileError:
        return RobotFileError(message, source=source, joint=joint, field=field)

    if not isinstance(data, Mapping):
        raise fail(f"expected a table of robot fields, got {type(data).__name__}")
    declared = data.get("convention")
    own = PLUGINS.get(declared) if isinstance(declared, str) else None  # type: ignore[call-overload]
    top_keys = _TOP_KEYS if own is None else (_TOP_KEYS | set(own.robot_keys)) - ({"tool"} if own.owns_tool else set())
    unknown = sorted(set(data) - top_keys)
    if "tool" in unknown and own is not None:
        raise fail(f"'tool' is not used by the {declared} convention: {own.tool_note}", field="tool")
    if unknown:
        raise fail(f"unknown key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(sorted(top_keys))}")

    if not data:
        raise fail("the robot description is empty: a robot file needs 'name', 'convention' and [[joints]]")
    if "name" not in data:
        raise fail("'name' is required: give the robot a name (an identifier: letters, digits, underscore)",
                   field="name")
    name = data["name"]
    problem = name_problem(name)
    if problem is not None:
        raise fail(f"'name' must be an identifier (letters, digits, underscore), got {name!r}: {problem}",
                   field="name")
    description = data.get("description", "")
    if not isinstance(description, str):
        raise fail("'description' must be a string", field="description")
    convention = convention_named(data, source)
    spec = plugin(convention)
    unit = data.get("angle_unit", "rad")
    if unit not in ("rad", "deg"):
        raise fail(f"'angle_unit' must be 'rad' or 'deg', got {unit!r}", field="angle_unit")
    angle_scale = sp.pi / 180 if unit == "deg" else sp.S.One

    if "joints" not in data:
        raise fail("'joints' is required: a robot file needs a non-empty list of joint tables ([[joints]])",
                   field="joints")
    joints_data = data["joints"]
    if not isinstance(joints_data, Sequence) or isinstance(joints_data, str) or not joints_data:
        raise fail("'joints' must be a non-empty list of joint tables", field="joints")
    joint_types: list[JointType] = []
    for number, joint_data in enumerate(joints_data, start=1):
        if not isinstance(joint_data, Mapping):
            raise fail(f"expected a table, got {type(joint_data).__name__}", joint=number)
        if "type" not in joint_data:
            raise fail("'type' is required: say 'revolute' or 'prismatic'", joint=number, field="type")
        kind = joint_data["type"]
        if not isinstance(kind, str) or kind not in {t.value for t in JointType}:
            raise fail(f"'type' must be 'revolute' or 'prismatic', got {kind!r}", joint=number, field="type")
        joint_types.append(JointType(kind))
    parameters = _parameters(data.get("parameters", {}), reserved_names(joint_types), fail)
    names = {parameter.name: parameter.symbol for parameter in parameters}
    defaults = {parameter.symbol: parameter.default for parameter in parameters}

    def value(raw: Any, field: str, joint: int | None = None, scale: sp.Expr = sp.S.One) -> sp.Expr:
        try:
            expr = parse_expression(raw, names) if isinstance(raw, str) else exact_number(raw)
        except ExpressionError as error:
            raise fail(str(error), joint=joint, field=field) from None
        return expr * scale

    settings = spec.read_settings(
        data, lambda key: _fixed_transform(data[key], key, value, defaults, fail, angle_scale),
        lambda message, field: fail(message, field=field))

    allowed = {"type", "d", "theta", "limits", "coupled", "inertial", *spec.keys}
    joints, inertials = [], []
    for number, (joint_data, kind) in enumerate(zip(joints_data, joint_types, strict=True), start=1):
        unknown = sorted(set(joint_data) - allowed)
        if unknown:
            listed = [*sorted(allowed - {"inertial"}), "inertial"]  # the link's data after the joint's own fields
            raise fail(f"unknown key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(listed)}",
                       joint=number)
        reader = _JointReader(joint_data, number, value, defaults, fail, angle_scale, settings)
        placement, joint_name = spec.read(joint_data, reader)
        d, theta = reader.number("d"), reader.number("theta", angle=True)
        limits = None
        if "limits" in joint_data:
            scale = angle_scale if kind is JointType.REVOLUTE else sp.S.One
            limits = file_limits(joint_data["limits"], lambda raw, s=scale, j=number: value(raw, "limits", j, s),
                                 defaults, lambda message, j=number: fail(message, joint=j, field="limits"),
                                 turn=kind is JointType.REVOLUTE and unit == "rad")
        joints.append(Joint(index=number, type=kind, placement=placement, d=d, theta=theta, limits=limits,
                            name=joint_name))
        inertials.append(_inertial(joint_data, number, value, defaults, fail))

    coupling = _coupling(joints_data, joints, names, defaults, fail)
    transforms: dict[str, FixedTransform | None] = {}
    for key in ("base", "tool"):
        if key in data:
            transforms[key] = _fixed_transform(data[key], key, value, defaults, fail, angle_scale)
    if spec.owns_tool:
        transforms["tool"] = spec.tool(joints, settings)

    robot = Robot(name=name, convention=convention, joints=tuple(joints), parameters=parameters,
                  description=description, base=transforms.get("base"), tool=transforms.get("tool"), source=source,
                  coupling=coupling, angle_unit=unit)
    robot = robot if all(i is None for i in inertials) else with_file_inertials(robot, inertials)
    if data.get("inertials", "symbolic") != "symbolic":
        raise fail(f"'inertials' can only be \"symbolic\", got {data['inertials']!r}", field="inertials")
    return symbolic_where_missing(robot) if "inertials" in data else robot


def _inertial(table: Mapping[str, Any], number: int, value: Any, defaults: Mapping[sp.Symbol, sp.Rational],
              fail: Any) -> Inertial | None:
    """Joint ``number``'s ``inertial`` table (link *number*'s data, in its convention's frame), checked, or None."""
    if "inertial" not in table:
        return None

    def problem(message: str, field: str) -> RobotFileError:
        return fail(f"link {number}: {message}", joint=number, field=field)

    def entry(raw: Any, field: str) -> sp.Expr:
        try:
            return value(raw, field, number)
        except RobotFileError as error:  # say the link, as every inertial error does
            raise problem(error.message, field) from None

    inertial = inertial_from_table(table["inertial"], entry, problem)
    for entry in (inertial.mass, *inertial.com, *inertial.inertia):
        _require_finite(entry, defaults, lambda message: problem(message, "inertial"))
    reason = inertial_problem(inertial, defaults, physical=False)
    if reason is not None:
        raise problem(reason, "inertial")
    reason = None if inertial.keep_impossible else inertial_problem(inertial, defaults)
    if reason is not None:  # kept, as URDF's are: a converted CAD export must read back (kinematics does not need it)
        warn(InertialWarning(f"{problem(reason, 'inertial').args[0]} (kept as given; the dynamics refuse it unless "
                             f"the table says keep_impossible = true)"))
    return inertial


def _coupling(tables: Sequence[Mapping[str, Any]], joints: Sequence[Joint], names: Mapping[str, sp.Symbol],
              defaults: Mapping[sp.Symbol, sp.Rational], fail: Any) -> Coupling | None:
    """The coupling the joints' ``coupled`` fields give, or None if no joint has one (the identity)."""
    coupled = {joint.variable for joint, table in zip(joints, tables, strict=True) if "coupled" in table}
    if not coupled:
        return None
    coordinates = tuple(joint.variable for joint in joints if joint.variable not in coupled)
    if not coordinates:
        raise fail("every joint is coupled: at least one joint must be free (its variable a coordinate)",
                   joint=len(joints), field="coupled")
    listed = ", ".join(map(str, coordinates))
    known = {**names, **{str(joint.variable): joint.variable for joint in joints}}
    values: list[sp.Expr] = []
    for joint, table in zip(joints, tables, strict=True):
        if joint.variable not in coupled:
            values.append(joint.variable)
            continue

        def problem(message: str, index: int = joint.index) -> RobotFileError:
            return fail(message, joint=index, field="coupled")

        raw = table["coupled"]
        if isinstance(raw, bool) or not isinstance(raw, str | int | float):
            raise problem(f"'coupled' must be an expression of the coordinates ({listed}), got {raw!r}")
        try:
            value = parse_expression(raw, known) if isinstance(raw, str) else exact_number(raw)
        except ExpressionError as error:
            raise problem(str(error)) from None
        used = value.free_symbols & coupled
        if joint.variable in used:
            raise problem(f"{joint.variable} refers to itself in {raw!r}: use the coordinates ({listed})")
        if used:
            other = sorted(map(str, used))[0]
            raise problem(f"{other} in {raw!r} is itself coupled: refer only to the variables of uncoupled joints "
                          f"({listed})")
        for c in coordinates:
            coefficient = sp.diff(value, c)
            if coefficient.free_symbols & set(coordinates):
                raise problem(f"{raw!r} is not affine in the coordinates ({listed}): give a constant plus "
                              f"constant multiples of them")
            _require_finite(coefficient, defaults, problem)
        _require_finite(value.xreplace(dict.fromkeys(coordinates, sp.S.Zero)), defaults, problem)
        values.append(value)
    return Coupling(coordinates, tuple(values))


class _JointReader:
    """Reads one joint table for a convention plug-in (:class:`~symjac.model.conventions.base.JointReader`)."""

    def __init__(self, table: Mapping[str, Any], number: int, value: Any, defaults: Mapping[sp.Symbol, sp.Rational],
                 fail: Any, angle_scale: sp.Expr, settings: Mapping[str, Any]):
        self.table, self.joint, self.defaults, self.settings = table, number, defaults, settings
        self._value, self._fail, self._angle_scale = value, fail, angle_scale

    def value(self, raw: Any, field: str, *, angle: bool = False) -> sp.Expr:
        """``raw`` parsed (angles scaled by the file's unit)."""
        return self._value(raw, field, self.joint, self._angle_scale if angle else sp.S.One)

    def number(self, key: str, *, angle: bool = False) -> sp.Expr:
        """The value under ``key`` (0 if absent), checked finite."""
        expr = self.value(self.table.get(key, 0), key, angle=angle)
        _require_finite(expr, self.defaults, lambda message: self.fail(message, key), angle,
                        turn=angle and self._angle_scale == 1)  # a file in radians: one turn at most
        return expr

    def transform(self, keys: Sequence[str], field: str) -> FixedTransform:
        """The fixed transform of the ``xyz``/``rpy`` or ``matrix`` entries among ``keys`` (identity if none)."""
        if not keys:
            return FixedTransform()

        def joint_value(raw: Any, name: str, joint: int | None = None, scale: sp.Expr = sp.S.One) -> sp.Expr:
            return self._value(raw, name, self.joint, scale)

        return _fixed_transform({key: self.table[key] for key in keys}, field, joint_value, self.defaults,
                                lambda message, joint=None, field=None: self.fail(message, field), self._angle_scale)

    def fail(self, message: str, field: str | None = None) -> RobotFileError:
        """The error for this joint."""
        return self._fail(message, joint=self.joint, field=field)

    def is_finite(self, number: sp.Expr) -> bool:
        """Whether ``number`` converts to a finite float."""
        return _is_finite(number)


def _parameters(raw: Any, reserved: Mapping[str, str], fail: Any) -> tuple[Parameter, ...]:
    if not isinstance(raw, Mapping):
        raise fail("'parameters' must be a table of name = number", field="parameters")
    parameters = []
    for name, default in raw.items():
        where = f"parameters.{name}"
        problem = name_problem(name)
        if problem is not None:
            raise fail(f"parameter name {name!r} is not allowed: {problem}", field=where)
        if name in reserved:
            raise fail(f"parameter name {name!r} is reserved: {reserved[name]}", field=where)
        try:
            parameters.append(Parameter(name, exact_number(default)))
        except ExpressionError as error:
            raise fail(f"default must be a finite number: {error}", field=where) from None
    return tuple(parameters)


def _require_finite(expr: sp.Expr, defaults: Mapping[sp.Symbol, sp.Rational], fail: Any,
                    angle: bool | None = None, *, turn: bool = False) -> None:
    """Refuse ``expr`` unless finite with the defaults, and (an angle or a length) no larger than any robot's.

    With ``turn`` (an angle a file gives in radians) more than a turn is refused too: it is surely in degrees.
    """
    number = expr.subs(defaults)
    if not number.is_number or not _is_finite(number):
        raise fail(f"value {expr} is not a finite number once parameters take their defaults")
    problem = None if angle is None else size_problem(float(number), angle=angle, turn=turn)
    if problem is not None:
        raise fail(f"{expression_text(expr)} = {problem}" if expr.free_symbols else problem)


def _is_finite(number: sp.Expr) -> bool:
    try:
        return math.isfinite(float(number))
    except TypeError:  # complex infinity (1/L1 with L1 = 0) has no float
        return False


def _fixed_transform(raw: Any, key: str, value: Any, defaults: Mapping[sp.Symbol, sp.Rational], fail: Any,
                     angle_scale: sp.Expr) -> FixedTransform:
    if not isinstance(raw, Mapping):
        raise fail(f"'{key}' must be a table with 'xyz' and 'rpy', or 'matrix'", field=key)
    unknown = sorted(set(raw) - _TRANSFORM_KEYS)
    if unknown:
        raise fail(f"unknown key(s) {', '.join(map(repr, unknown))}; allowed: xyz, rpy, matrix", field=key)
    if "matrix" in raw:
        if set(raw) != {"matrix"}:
            raise fail("give either 'matrix' or 'xyz'/'rpy', not both", field=key)
        rows = raw["matrix"]
        if not (isinstance(rows, Sequence) and len(rows) == 4
                and all(isinstance(row, Sequence) and not isinstance(row, str) and len(row) == 4 for row in rows)):
            raise fail("'matrix' must be 4 rows of 4 entries", field=f"{key}.matrix")
        matrix = sp.ImmutableMatrix([[value(entry, f"{key}.matrix") for entry in row] for row in rows])
        if list(matrix[3, :]) != [0, 0, 0, 1]:
            raise fail("the last row of 'matrix' must be [0, 0, 0, 1]", field=f"{key}.matrix")
        for index, entry in enumerate(matrix):  # the translation column holds lengths
            _require_finite(entry, defaults, lambda message: fail(message, field=f"{key}.matrix"),
                            False if index % 4 == 3 else None)
        rotation = matrix[:3, :3].subs(defaults).evalf()
        error = max(float((rotation.T * rotation - sp.eye(3)).norm()), abs(float(rotation.det()) - 1))
        if not error < _ROTATION_ROUNDING:  # a calibrated file's 6 decimals are off by about 1e-6
            raise fail(f"the upper-left 3 x 3 block of 'matrix' is not a rotation (|R^T R - I| = {error:.2g}, more "
                       f"than the {_ROTATION_ROUNDING:g} a file's rounding allows)", field=f"{key}.matrix")
        return FixedTransform(given_matrix=matrix)

    def vector(name: str, scale: sp.Expr) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
        entries = raw.get(name, [0, 0, 0])
        if not isinstance(entries, Sequence) or isinstance(entries, str) or len(entries) != 3:
            raise fail(f"'{name}' must be a list of 3 numbers or expressions", field=f"{key}.{name}")
        x, y, z = (value(entry, f"{key}.{name}", None, scale) for entry in entries)
        for entry in (x, y, z):
            _require_finite(entry, defaults, lambda message: fail(message, field=f"{key}.{name}"), name == "rpy",
                            turn=name == "rpy" and angle_scale == 1)
        return x, y, z

    return FixedTransform(xyz=vector("xyz", sp.S.One), rpy=vector("rpy", angle_scale))


def robot_to_mapping(robot: Robot) -> dict[str, Any]:
    """Return the plain-data description of ``robot`` (inverse of :func:`robot_from_mapping`; angles in radians).

    Examples
    --------
    >>> robot = robot_from_mapping({"name": "r", "convention": "modified",
    ...                             "joints": [{"type": "revolute", "alpha": "-pi/2"}]})
    >>> robot_to_mapping(robot)["joints"][0]["alpha"]
    '-pi/2'
    """
    data: dict[str, Any] = {"name": robot.name}
    if robot.description:
        data["description"] = robot.description
    data["convention"] = robot.convention.value
    symbolic = symbolic_links(robot)
    if any(parameter.inertial for parameter in robot.parameters):
        data["inertials"] = "symbolic"
    # a link left to ``"symbolic"`` needs only the defaults that are not the placeholder's
    placeholders = placeholder_defaults(symbolic)
    given = [p for p in robot.parameters if placeholders.get(p.name, p.default + 1) != p.default]
    if given:
        data["parameters"] = {parameter.name: expression_text(parameter.default) for parameter in given}
    spec = plugin(robot.convention)
    data.update(spec.write_settings(robot))
    joints = []
    written = zip(robot.joints, _written_values(robot), file_inertials(robot), strict=True)
    for link, (joint, value, inertial) in enumerate(written, start=1):
        row: dict[str, Any] = {"type": joint.type.value, **spec.write(joint)}
        if value != joint.variable:
            row["coupled"] = expression_text(value)
        if joint.limits is not None:
            row["limits"] = [expression_text(limit) for limit in joint.limits]
        if inertial is not None and link not in symbolic:
            row["inertial"] = inertial_table(inertial)
        joints.append(row)
    data["joints"] = joints
    for key in ("base",) if spec.owns_tool else ("base", "tool"):
        transform: FixedTransform | None = getattr(robot, key)
        if transform is not None:
            data[key] = transform_fields(transform)
    return data


def _written_values(robot: Robot) -> tuple[sp.Expr, ...]:
    """Each joint's variable as a robot file can say it: the coordinates must be joint variables."""
    foreign = [str(c) for c in robot.coordinates if c not in set(robot.joint_variables)]
    if foreign:
        raise RobotFileError(f"the coordinate {foreign[0]} is not a joint variable: a robot file couples joints "
                             f"only to the variables of uncoupled joints", source=robot.source, field="coupled")
    return robot.joint_values
