r"""What drives a joint: the reflected inertia of its motor and the friction it meets, in joint space.

Carried by :attr:`symjac.model.robot.Robot.drives` (one per joint, or None) and read from robot files
(``[joints.drive]``), URDF (``<dynamics damping friction>``) and MJCF (a joint's ``armature``, ``damping``,
``frictionloss``). The dynamics add them to the rigid bodies' (:mod:`symjac.analysis.dynamics`):

.. math::
    M(q) \mathrel{+}= \operatorname{diag}(I_a), \qquad
    \tau \mathrel{+}= I_a \ddot q + F_v \dot q + F_c \operatorname{sign}(\dot q)

per joint (for coupled joints :math:`C^T \operatorname{diag}(I_a) C` and :math:`C^T(\dots)`). The armature
:math:`I_a = J_m G^2` is the rotor's inertia :math:`J_m` seen through a gear ratio :math:`G` (the gyroscopic effect
of the spinning rotor is left out, as the Robotics Toolbox and pinocchio leave it out). All three are joint-side
values: kg m^2 (kg for a prismatic joint), N m s/rad (N s/m) and N m (N). Entries are SymPy expressions: numbers, or
expressions of the robot's parameters; each must be finite and not negative once parameters take their defaults.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import sympy as sp

from symjac.model.expressions import exact_number, expression_text

__all__ = ["DRIVE_KEYS", "Drive", "checked_drives", "drive_from_table", "drive_problem", "drive_table"]

DRIVE_KEYS: tuple[str, ...] = ("armature", "motor_inertia", "gear_ratio", "viscous", "coulomb")
"""The keys of a robot file's ``[joints.drive]`` table, in the order they are written."""


def _expr(value: object) -> sp.Expr:
    if isinstance(value, int | float) and not isinstance(value, bool):
        return exact_number(value)
    return sp.sympify(value)


@dataclass(frozen=True)
class Drive:
    r"""A joint's drive: armature :math:`I_a`, viscous friction :math:`F_v`, Coulomb friction :math:`F_c`.

    Parameters
    ----------
    armature : sympy.Expr
        The reflected rotor inertia :math:`I_a = J_m G^2` (kg m^2), added to the mass matrix's diagonal.
    viscous : sympy.Expr
        :math:`F_v` (N m s/rad): the torque :math:`F_v \dot q` opposes the motion.
    coulomb : sympy.Expr
        :math:`F_c` (N m): the torque :math:`F_c \operatorname{sign}(\dot q)` (or the smooth
        :math:`F_c \tanh(\dot q/\varepsilon)`) opposes the motion; none at rest (no stiction).
    motor : (J_m, G) or None
        The rotor inertia and gear ratio the armature was given as (ignored by ``==``; kept to write it back so).

    Examples
    --------
    >>> Drive.from_motor(0.0002, -62.6111).armature
    392014984321/500000000000
    """

    armature: sp.Expr = sp.S.Zero
    viscous: sp.Expr = sp.S.Zero
    coulomb: sp.Expr = sp.S.Zero
    motor: tuple[sp.Expr, sp.Expr] | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        """Turn the entries into SymPy expressions (Python numbers exactly)."""
        for name in ("armature", "viscous", "coulomb"):
            object.__setattr__(self, name, _expr(getattr(self, name)))
        if self.motor is not None:
            object.__setattr__(self, "motor", tuple(_expr(v) for v in self.motor))

    @classmethod
    def from_motor(cls, motor_inertia: object, gear_ratio: object, viscous: object = 0, coulomb: object = 0) -> Drive:
        """The drive of a rotor of inertia ``motor_inertia`` behind a gear of ratio ``gear_ratio``: Jm G^2."""
        Jm, G = _expr(motor_inertia), _expr(gear_ratio)
        return cls(Jm * G**2, viscous, coulomb, motor=(Jm, G))  # type: ignore[arg-type]

    @property
    def is_zero(self) -> bool:
        """Whether the drive adds nothing (every entry exactly zero)."""
        return self.armature == 0 and self.viscous == 0 and self.coulomb == 0


def drive_problem(drive: Drive, defaults: Mapping[sp.Symbol, sp.Expr] | None = None) -> str | None:
    """What is wrong with ``drive`` once parameters take ``defaults`` (not finite, negative), or None.

    Entries that stay symbolic pass (as :func:`~symjac.model.inertia.inertial_problem` lets them).

    Examples
    --------
    >>> drive_problem(Drive(viscous=-1))
    'the viscous friction -1 is negative'
    """
    subs = dict(defaults or {})
    words = {"armature": "armature", "viscous": "viscous friction", "coulomb": "Coulomb friction"}
    for name, what in words.items():
        expr: sp.Expr = getattr(drive, name)
        value = expr.xreplace(subs) if subs else expr
        if value.free_symbols:  # symbolic (an identification's Ia1, Fv1): nothing to check
            continue
        try:
            number = float(value)
        except TypeError:  # complex or zoo
            number = math.nan
        if not math.isfinite(number):
            return f"the {what} {expr} is not a finite number"
        if number < 0:
            return f"the {what} {expr} is negative"
    return None


def checked_drives(drives: Sequence[object], joints: Sequence[object], defaults: Mapping[sp.Symbol, sp.Expr],
                   fail: Callable[[str, int | None], Exception]) -> tuple[Drive | None, ...]:
    """One :class:`Drive` or None per joint, checked (:attr:`Robot.drives <symjac.model.robot.Robot>`).

    None everywhere when none is given; a drive that adds nothing is None too (so a robot with zero drives is the
    robot without). ``fail(message, joint)`` is the error to raise; its message names the joint.
    """
    given = tuple(drives)
    if all(drive is None for drive in given):
        return (None,) * len(joints)
    if len(given) != len(joints):
        raise fail(f"{len(given)} drive entries for {len(joints)} joints: give one per joint (None where none)",
                   None)
    for number, (drive, joint) in enumerate(zip(given, joints, strict=True), start=1):
        name = getattr(joint, "name", "")
        where = f"joint {number}" + (f" ({name})" if name else "")
        if drive is not None and not isinstance(drive, Drive):
            raise fail(f"{where}: expected Drive or None, got {type(drive).__name__}", number)
        problem = None if drive is None else drive_problem(drive, defaults)
        if problem is not None:
            raise fail(f"{where}: {problem}", number)
    kept = tuple(drive if isinstance(drive, Drive) and not drive.is_zero else None for drive in given)
    return (None,) * len(joints) if all(drive is None for drive in kept) else kept


def drive_from_table(table: object, value: Callable[[object, str], sp.Expr],
                     fail: Callable[[str, str], Exception]) -> Drive:
    """The :class:`Drive` a robot file's ``drive`` table gives.

    ``armature`` (joint-side, kg m^2) or ``motor_inertia`` with ``gear_ratio`` (the armature is then
    ``motor_inertia * gear_ratio**2``), ``viscous`` and ``coulomb`` (joint-side); every key is optional, missing
    ones are zero. ``value(raw, field)`` parses one entry; ``fail(message, field)`` is the error to raise.
    """
    if not isinstance(table, Mapping):
        raise fail("'drive' must be a table with 'armature' (or 'motor_inertia' and 'gear_ratio'), 'viscous' and "
                   "'coulomb'", "drive")
    unknown = sorted(set(table) - set(DRIVE_KEYS))
    if unknown:
        raise fail(f"unknown key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(DRIVE_KEYS)}", "drive")
    entries = {key: value(table[key], f"drive.{key}") for key in DRIVE_KEYS if key in table}
    motor = [key for key in ("motor_inertia", "gear_ratio") if key in table]
    if motor and "armature" in table:
        raise fail("give either 'armature' or 'motor_inertia' and 'gear_ratio', not both", "drive.armature")
    if len(motor) == 1:
        other = "gear_ratio" if motor[0] == "motor_inertia" else "motor_inertia"
        raise fail(f"'{motor[0]}' needs '{other}' (the armature is motor_inertia * gear_ratio**2)", f"drive.{other}")
    zero = sp.S.Zero
    if motor:
        return Drive.from_motor(entries["motor_inertia"], entries["gear_ratio"], entries.get("viscous", zero),
                                entries.get("coulomb", zero))
    return Drive(entries.get("armature", zero), entries.get("viscous", zero), entries.get("coulomb", zero))


def drive_table(drive: Drive) -> dict[str, object]:
    """The ``drive`` table of a robot file for ``drive`` (the armature as it was given: as a motor, or not)."""
    table: dict[str, object] = {}
    if drive.motor is not None and sp.expand(drive.motor[0] * drive.motor[1] ** 2 - drive.armature) == 0:
        table.update(motor_inertia=expression_text(drive.motor[0]), gear_ratio=expression_text(drive.motor[1]))
    elif drive.armature != 0:
        table["armature"] = expression_text(drive.armature)
    for name in ("viscous", "coulomb"):
        if getattr(drive, name) != 0:
            table[name] = expression_text(getattr(drive, name))
    return table
