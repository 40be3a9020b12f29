"""Checked fields of a robot file's joint tables: the link's ``inertial`` and the joint's ``drive`` sub-tables.

Part of :mod:`symjac.model.robot_file` (every error names the file, the joint and the field), kept apart to keep that
module short; also the finiteness check every numeric field goes through.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import sympy as sp

from symjac.errors import InertialWarning, RobotFileError, warn
from symjac.model.bounds import size_problem
from symjac.model.drive import Drive, drive_from_table, drive_problem
from symjac.model.expressions import expression_text
from symjac.model.inertia import Inertial, inertial_from_table, inertial_problem

__all__ = ["drive_field", "inertial_field", "is_finite", "require_finite"]


def inertial_field(table: Mapping[str, Any], number: int, value: Any, defaults: Mapping[sp.Symbol, sp.Rational],
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
        require_finite(entry, defaults, lambda message: problem(message, "inertial"))
    reason = inertial_problem(inertial, defaults, physical=False)
    if reason is not None:
        raise problem(reason, "inertial")
    reason = None if inertial.keep_impossible else inertial_problem(inertial, defaults)
    if reason is not None:  # kept, as URDF's are: a converted CAD export must read back (kinematics does not need it)
        warn(InertialWarning(f"{problem(reason, 'inertial').args[0]} (kept as given; the dynamics refuse it unless "
                             f"the table says keep_impossible = true)"))
    return inertial


def drive_field(table: Mapping[str, Any], number: int, value: Any, defaults: Mapping[sp.Symbol, sp.Rational],
                fail: Any) -> Drive | None:
    """Joint ``number``'s ``drive`` table (:func:`~symjac.model.drive.drive_from_table`), checked, or None."""
    if "drive" not in table:
        return None

    def problem(message: str, field: str) -> RobotFileError:
        return fail(message, joint=number, field=field)

    drive = drive_from_table(table["drive"], lambda raw, field: value(raw, field, number), problem)
    reason = drive_problem(drive, defaults)
    if reason is not None:
        raise problem(reason, "drive")
    return drive


def require_finite(expr: sp.Expr, defaults: Mapping[sp.Symbol, sp.Rational], fail: Any,
                    angle: bool | None = None, *, turn: bool = False) -> None:
    """Refuse ``expr`` unless finite with the defaults, and (an angle or a length) no larger than any robot's.

    With ``turn`` (an angle a file gives in radians) more than a turn is refused too: it is surely in degrees.
    """
    number = expr.subs(defaults)
    if not number.is_number or not is_finite(number):
        raise fail(f"value {expr} is not a finite number once parameters take their defaults")
    problem = None if angle is None else size_problem(float(number), angle=angle, turn=turn)
    if problem is not None:
        raise fail(f"{expression_text(expr)} = {problem}" if expr.free_symbols else problem)


def is_finite(number: sp.Expr) -> bool:
    """Whether ``number`` converts to a finite float."""
    try:
        return math.isfinite(float(number))
    except TypeError:  # complex infinity (1/L1 with L1 = 0) has no float
        return False
