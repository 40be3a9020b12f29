r"""The document of ``symjac dynamics``: the equations of motion, part by part, in textbook shorthand.

:math:`\tau = M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q)`.

:func:`dynamics_document` takes the parts a caller derived and lays out those given in the order a derivation
builds up to the torques: the kinetic and potential energy, :math:`M`, :math:`C`, :math:`g`, then the Newton-Euler
steps and the torques they end with. LaTeX, pretty text and JSON all print it (JSON keys ``kinetic_energy``,
``potential_energy``, ``mass_matrix``, ``coriolis_matrix``, ``gravity_torques``, ``steps``, ``torques``, with
``*_latex`` beside each). The HTML report builds its dynamics section from the same document.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from symjac.analysis.dynamics.gravity import EARTH, Gravity, dynamics_defaults
from symjac.analysis.dynamics.newton_euler import NewtonEuler
from symjac.model.robot import Robot
from symjac.printing.document import Block, Document, Equation, JsonKey
from symjac.printing.latex import rounded

__all__ = ["DynamicsParts", "dynamics_document", "gravity_words"]

_METHODS = {"newton-euler": "recursive Newton-Euler", "lagrange": "the Euler-Lagrange equations of L = T - V"}


@dataclass(frozen=True)
class DynamicsParts:
    r"""The parts of the equations of motion to print; None: not asked for.

    ``torques`` n x 1, ``mass_matrix`` and ``coriolis_matrix`` n x n, ``gravity_torques`` n x 1, ``kinetic_energy``
    and ``potential_energy`` scalars, ``steps`` the Newton-Euler recursion (printed first), all in the robot's
    coordinates.
    """

    torques: sp.MatrixBase | None = None
    mass_matrix: sp.MatrixBase | None = None
    coriolis_matrix: sp.MatrixBase | None = None
    gravity_torques: sp.MatrixBase | None = None
    kinetic_energy: sp.Expr | None = None
    potential_energy: sp.Expr | None = None
    steps: NewtonEuler | None = None


def gravity_words(gravity: Gravity) -> str:
    """Gravity in words: ``g along -z0 (g = 9.81 m/s^2)``, ``9.81 m/s^2 along (0, -1, 0) in {0}``, ``no gravity``.

    Examples
    --------
    >>> gravity_words(EARTH)
    'gravity g along -z0 (g = 9.81 m/s^2)'
    >>> gravity_words(Gravity(direction=(0, -1, 0), magnitude=sp.Rational(162, 100)))
    'gravity 1.62 m/s^2 along -y0'
    """
    if gravity.is_zero:
        return "no gravity"
    axes = {(1, 0, 0): "x0", (0, 1, 0): "y0", (0, 0, 1): "z0"}
    direction = tuple(gravity.direction)  # type: ignore[arg-type]
    named = [f"{'-' if sign < 0 else '+'}{name}" for axis, name in axes.items() for sign in (1, -1)
             if direction == tuple(sign * v for v in axis)]
    along = named[0].lstrip("+") if named else f"({', '.join(str(v) for v in direction)}) in {{0}}"
    magnitude = gravity.magnitude
    if isinstance(magnitude, sp.Symbol):
        return f"gravity {magnitude} along {along} ({magnitude} = {_number(gravity.value)} m/s^2)"
    return f"gravity {_number(magnitude)} m/s^2 along {along}"


def _number(value: sp.Expr) -> str:
    return str(int(value)) if value.is_Integer else f"{float(value):g}"


def dynamics_document(robot: Robot, parts: DynamicsParts, method: str = "newton-euler", gravity: Gravity = EARTH,
                      digits: int | None = None) -> Document:
    r"""``symjac dynamics``: the parts given, captioned, with the method, gravity and coordinates as facts.

    ``digits``: substitute the parameters' defaults and gravity's value, and round to that many significant digits.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.model.inertial_parameters import with_symbolic_inertials
    >>> from symjac.analysis.dynamics import gravity_torques
    >>> arm = with_symbolic_inertials(load_robot("planar2r"))
    >>> g = gravity_torques(arm)
    >>> dynamics_document(arm, DynamicsParts(gravity_torques=g)).blocks[0].caption
    ('Gravity torques g(q) (gravity g along -z0 (g = 9.81 m/s^2))',)
    """
    values = dynamics_defaults(robot, gravity) if digits is not None else {}

    def shown(value: Any) -> Any:
        return value if digits is None else rounded(value.xreplace(values), digits)

    words = gravity_words(gravity)
    entries: list[tuple[str, Any, str, str, str, bool]] = [
        ("Kinetic energy T = 1/2 qdot^T M(q) qdot", parts.kinetic_energy, "T", "T", "kinetic_energy", False),
        (f"Potential energy V(q) ({words})", parts.potential_energy, "V", "V", "potential_energy", False),
        ("Mass matrix M(q) (symmetric, positive definite)", parts.mass_matrix, "M", "M", "mass_matrix", False),
        ("Coriolis matrix C(q, qdot) from the Christoffel symbols (Mdot - 2C skew-symmetric)",
         parts.coriolis_matrix, "C", "C", "coriolis_matrix", False),
        (f"Gravity torques g(q) ({words})", parts.gravity_torques, "g", "g", "gravity_torques", True),
        (f"Joint torques tau = M(q) qddot + C(q, qdot) qdot + g(q), by {_METHODS[method]} ({words})",
         parts.torques, r"\tau", "τ", "torques", True),
    ]
    blocks: list[Block] = []
    for caption, value, tex, text, key, flat in entries:
        if parts.steps is not None and key == "torques":  # the recursion, then the torques it ends with
            from symjac.printing.steps import step_equations

            inward = 6 * len(parts.steps.steps)  # six outward quantities per link, then the inward ones
            captions = {0: ("Newton-Euler, outward from the base: each link's velocities, accelerations and the "
                            "force and moment that move it, in its own frame",),
                        inward: ("Newton-Euler, inward from the tip: the force and moment on each link from the one "
                                 "before, and its joint's torque",)}
            blocks += [Block(captions.get(k, ()), (replace(step, rhs=shown(step.rhs),
                                                           key=JsonKey("steps", record=True)),))
                       for k, step in enumerate(step_equations(parts.steps))]
        if value is not None:
            equation = Equation(tex, text, shown(value), key=JsonKey(key, latex=f"{key}_latex", flat=flat))
            blocks.append(Block((caption,), (equation,)))
    facts = {"method": method, "gravity": {"direction": [str(v) for v in gravity.direction],  # type: ignore[attr-defined]
                                           "magnitude": str(gravity.magnitude), "value": float(gravity.value)},
             "rates": [str(r) for r in robot.coordinate_rates],
             "accelerations": [str(a) for a in robot.coordinate_accelerations],
             "inertial_parameter_order": ["m", "cx", "cy", "cz", "Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz"],
             "units": "SI (kg, m, s; N, N m)"}
    return Document(f"{robot.name}: equations of motion", robot.name, tuple(blocks), facts=facts, model=robot)
