r"""Coordinates and joints: the independent variables a user gives values for, and the joint variables they drive.

Most arms move each joint by its own motor, so the joint variables *are* the coordinates (the identity coupling,
which every robot has unless it says otherwise). Some mechanisms couple joints: a parallelogram palletizer keeps its
tool flange level with :math:`\theta_4 = -(\theta_2 + \theta_3)`, a URDF mimic joint follows another joint, a
belt-coupled ball screw moves with a wrist angle, :math:`d_3 = k\,\theta_4 + d_{30}`. A :class:`Coupling` names the
independent coordinates :math:`q` and writes every joint variable :math:`\vartheta_i` as an *affine* expression of
them (coefficients and offsets may be symbolic parameters):

.. math:: \vartheta(q) = C\,q + \vartheta_0, \qquad C = \frac{\partial \vartheta}{\partial q}
          \quad (n_\text{joints} \times n_\text{coordinates}, \text{constant}).

Since :math:`C` is constant, every velocity-level quantity maps by one product with it and every second derivative by
two: :math:`J_q = J(\vartheta(q))\,C`, :math:`\dot\vartheta = C\dot q`, :math:`\tau_q = C^T\tau`. Applying it is
:mod:`symjac.kinematics.coupling`'s job; this module only holds and checks the data.

A coordinate that is named like a joint variable (``theta2``) must be that joint's own variable (its value is
``theta2`` itself); other coordinates may take any name (``q1``, ``s``). The rate of a coordinate puts ``dot`` before
its trailing digits (``theta2`` -> ``thetadot2``, ``d3`` -> ``ddot3``, ``q1`` -> ``qdot1``), so with the identity
coupling the coordinate rates are the joint rates.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import sympy as sp

__all__ = ["Coupling", "acceleration_symbol", "coupling_problem", "rate_symbol"]


@dataclass(frozen=True)
class Coupling:
    r"""Independent coordinates and, per joint, its variable as an affine expression of them.

    Parameters
    ----------
    coordinates : tuple of sympy.Symbol
        The independent coordinates :math:`q`, in the order configurations are given; real symbols.
    values : tuple of sympy.Expr
        One per joint, in chain order: :math:`\vartheta_i(q)`, affine in the coordinates.

    Examples
    --------
    >>> t1, t2, t3 = sp.symbols("theta1 theta2 theta3", real=True)
    >>> coupling = Coupling((t1, t2, t3), (t1, t2, t3, -t2 - t3))
    >>> coupling.matrix
    Matrix([
    [1,  0,  0],
    [0,  1,  0],
    [0,  0,  1],
    [0, -1, -1]])
    """

    coordinates: tuple[sp.Symbol, ...]
    values: tuple[sp.Expr, ...]

    def __post_init__(self) -> None:
        """Keep tuples of SymPy objects (a list or plain numbers given by a caller would break hashing)."""
        object.__setattr__(self, "coordinates", tuple(self.coordinates))
        object.__setattr__(self, "values", tuple(sp.sympify(value) for value in self.values))

    @cached_property
    def matrix(self) -> sp.ImmutableMatrix:
        r"""The constant :math:`C = \partial\vartheta / \partial q`, shape (n_joints, n_coordinates)."""
        return sp.ImmutableMatrix(len(self.values), len(self.coordinates),
                                  lambda i, j: sp.expand(sp.diff(self.values[i], self.coordinates[j])))

    @cached_property
    def offsets(self) -> tuple[sp.Expr, ...]:
        r"""The constant part :math:`\vartheta_0 = \vartheta(0)` of every joint variable."""
        zero = dict.fromkeys(self.coordinates, sp.S.Zero)
        return tuple(sp.expand(value.xreplace(zero)) for value in self.values)


def coupling_problem(coupling: Coupling, joint_variables: Sequence[sp.Symbol],
                     parameters: Sequence[sp.Symbol]) -> str | None:
    """What is wrong with ``coupling`` for a robot with these joint variables and parameters, in one line, or None.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> coupling_problem(Coupling((t1,), (t1, t1**2)), (t1, t2), ())
    'joint 2: theta1**2 is not affine in the coordinates (theta1)'
    """
    coordinates, values = coupling.coordinates, coupling.values
    names = ", ".join(str(c) for c in coordinates)
    if len(values) != len(joint_variables):
        return f"{len(values)} joint values for {len(joint_variables)} joints; give one expression per joint"
    if not coordinates:
        return "no coordinates: name at least one"
    for c in coordinates:
        if not isinstance(c, sp.Symbol) or c.is_real is not True:
            return f"coordinate {c!r} must be a real symbol (sympy.Symbol({str(c)!r}, real=True))"
    repeated = next((c for i, c in enumerate(coordinates) if c in coordinates[:i]), None)
    if repeated is not None:
        return f"coordinate {repeated} is named twice"
    clash = next((c for c in coordinates if c in set(parameters)), None)
    if clash is not None:
        return f"coordinate {clash} is also a parameter of the robot"
    by_name = {str(v): i for i, v in enumerate(joint_variables)}
    known = set(coordinates) | set(parameters)
    for i, value in enumerate(values, start=1):
        if not isinstance(value, sp.Expr) or value.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            return f"joint {i}: {value!r} is not a finite expression"
        unknown = sorted(str(s) for s in value.free_symbols - known)
        if unknown:
            return f"joint {i}: unknown symbol {unknown[0]} in {value} (use coordinates ({names}) or parameters)"
        if any(sp.diff(value, c).free_symbols & set(coordinates) for c in coordinates):
            return f"joint {i}: {value} is not affine in the coordinates ({names})"
    for c in coordinates:
        owner = by_name.get(str(c))
        if owner is not None and (c != joint_variables[owner] or values[owner] != c):
            return (f"coordinate {c} is the variable of joint {owner + 1}, so that joint's value must be {c} itself, "
                    f"got {values[owner]}")
    unused = [str(c) for j, c in enumerate(coordinates) if all(e == 0 for e in coupling.matrix[:, j])]
    if unused:
        return f"coordinate {unused[0]} moves no joint"
    return None


def _split(symbol: sp.Symbol) -> tuple[str, str]:
    match = re.fullmatch(r"(.*?)(\d*)", symbol.name)
    assert match is not None  # the pattern matches every string
    return match.group(1), match.group(2)


def rate_symbol(coordinate: sp.Symbol) -> sp.Symbol:
    """The rate of a coordinate: ``dot`` before its trailing digits (``theta2`` -> ``thetadot2``, ``s`` -> ``sdot``).

    Examples
    --------
    >>> rate_symbol(sp.Symbol("d3", real=True)), rate_symbol(sp.Symbol("q12", real=True))
    (ddot3, qdot12)
    """
    prefix, digits = _split(coordinate)
    return sp.Symbol(f"{prefix}dot{digits}", real=True)


def acceleration_symbol(coordinate: sp.Symbol) -> sp.Symbol:
    """The acceleration of a coordinate: ``ddot`` before its trailing digits (``theta2`` -> ``thetaddot2``)."""
    prefix, digits = _split(coordinate)
    return sp.Symbol(f"{prefix}ddot{digits}", real=True)
