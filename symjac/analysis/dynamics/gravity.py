r"""Gravity as a setting of the dynamics: a direction in the base frame {0} and a magnitude.

By default gravity pulls along :math:`-z_0` with the magnitude :math:`g`, a symbol (``g``, positive), so that
symbolic results read :math:`m_2 g\,l_{c2} c_{12}`; its value, :math:`9.81\ \mathrm{m/s^2}`, is kept next to it
(:attr:`Gravity.defaults`) for numeric substitution, as a robot's parameters keep theirs
(:func:`dynamics_defaults`). The gravity acceleration vector in {0} is :math:`g_0 = g\,u` (u the unit direction);
the potential energy of a body of mass m with centre :math:`p_c` (in {0}) is :math:`V = -m\,g_0^T p_c`.

A numeric magnitude (``Gravity(magnitude=9.81)``) writes the number into the results; :data:`NO_GRAVITY` leaves gravity
out (the mass matrix route of :func:`~symjac.analysis.dynamics.newton_euler.newton_euler` uses it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import sympy as sp

from symjac.errors import ArgumentError
from symjac.model.robot import Robot

__all__ = ["EARTH", "GRAVITY_SYMBOL", "NO_GRAVITY", "STANDARD_GRAVITY", "Gravity", "check_gravity", "dynamics_defaults"]

GRAVITY_SYMBOL = sp.Symbol("g", positive=True)
"""The magnitude of gravity in symbolic results: ``g``."""

STANDARD_GRAVITY = sp.Rational(981, 100)
"""The default value of :data:`GRAVITY_SYMBOL`, in m/s^2 (exact, as the robots' parameter defaults are)."""


@dataclass(frozen=True)
class Gravity:
    r"""Gravity acting on the arm: ``magnitude`` times the unit ``direction`` (given in the base frame {0}).

    ``value`` is the number :data:`GRAVITY_SYMBOL` stands for when ``magnitude`` is that symbol (or any symbol):
    what :attr:`defaults` gives for numeric work. The direction is normalised; it must not be zero.

    Examples
    --------
    >>> Gravity().vector.T
    Matrix([[0, 0, -g]])
    >>> Gravity(direction=(0, -1, 0), magnitude=sp.Rational(981, 100)).vector.T
    Matrix([[0, -981/100, 0]])
    """

    direction: Sequence[object] = (0, 0, -1)
    magnitude: sp.Expr = GRAVITY_SYMBOL
    value: sp.Expr = field(default=STANDARD_GRAVITY)

    def __post_init__(self) -> None:
        """Normalise the direction and check the numbers."""
        direction = [sp.nsimplify(v, rational=True) if isinstance(v, float) else sp.sympify(v)
                     for v in self.direction]
        if len(direction) != 3:
            raise ArgumentError(f"gravity's direction has 3 components in {{0}}, got {len(direction)}")
        if not all(v.is_number and v.is_real for v in direction):
            raise ArgumentError(f"gravity's direction must be 3 real numbers, got {tuple(direction)}")
        norm = sp.sqrt(sum(v**2 for v in direction))
        if norm == 0:
            raise ArgumentError("gravity's direction must not be the zero vector")
        unit = tuple(sp.nsimplify(sp.simplify(v / norm)) if v != 0 else sp.S.Zero for v in direction)
        object.__setattr__(self, "direction", unit)
        # a float such as 9.81 becomes the exact 981/100: floats make SymPy slow and leave 1e-17 residues
        magnitude = sp.nsimplify(self.magnitude, rational=True) if isinstance(self.magnitude, float) else \
            sp.sympify(self.magnitude)
        object.__setattr__(self, "magnitude", magnitude)
        value = sp.nsimplify(self.value, rational=True) if isinstance(self.value, float) else sp.sympify(self.value)
        if not value.is_number:
            raise ArgumentError(f"gravity's value must be a number, got {value}")
        object.__setattr__(self, "value", value)

    @property
    def vector(self) -> sp.ImmutableMatrix:
        r"""The gravity acceleration :math:`g_0` in {0}, 3 x 1 (``[0, 0, -g]`` by default)."""
        return sp.ImmutableMatrix([self.magnitude * v for v in self.direction])  # type: ignore[attr-defined]

    @property
    def defaults(self) -> dict[sp.Symbol, sp.Expr]:
        """``{g: 981/100}`` when the magnitude is a symbol, else nothing: for ``expr.subs(...)``."""
        return {self.magnitude: self.value} if isinstance(self.magnitude, sp.Symbol) else {}

    @property
    def is_zero(self) -> bool:
        """Whether this is no gravity at all (magnitude 0)."""
        return self.magnitude == 0


EARTH = Gravity()
"""The default: :math:`g` along :math:`-z_0`, :math:`g = 9.81` for numbers."""

NO_GRAVITY = Gravity(magnitude=sp.S.Zero)
"""No gravity: results hold the inertial and velocity terms only."""


def dynamics_defaults(robot: Robot, gravity: Gravity = EARTH) -> dict[sp.Symbol, sp.Expr]:
    """Every number a symbolic dynamics result of ``robot`` needs: the robot's parameter defaults and gravity's.

    Examples
    --------
    >>> from symjac import load_robot
    >>> defaults = {str(symbol): value for symbol, value in dynamics_defaults(load_robot("planar2r")).items()}
    >>> defaults["L1"], defaults["m2"], defaults["g"], len(defaults)  # lengths, 10 inertial parameters a link, g
    (1/2, 1, 981/100, 23)
    """
    check_gravity(robot, gravity)
    return {**robot.defaults, **gravity.defaults}


def check_gravity(robot: Robot, gravity: Gravity) -> None:
    """Refuse a gravity whose symbol a parameter of the robot also uses (the two could not be told apart)."""
    if not isinstance(gravity, Gravity):
        raise ArgumentError(f"gravity must be a symjac Gravity, got {type(gravity).__name__}")
    names = {symbol.name for symbol in gravity.magnitude.free_symbols}  # type: ignore[attr-defined]
    clash = sorted(names & {parameter.name for parameter in robot.parameters})
    if clash:
        raise ArgumentError(f"{robot.name}: the parameter {clash[0]!r} has the name of gravity's magnitude; "
                            f"rename it or give Gravity(magnitude=...) another symbol")
