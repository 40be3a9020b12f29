r"""The ``symjac dynamics`` command's shared part: its options and the handler every dynamics quantity hands to.

The command prints the parts asked for together: the joint torques :math:`\tau(q, \dot q, \ddot q)` by default
(:mod:`.inverse_dynamics`), the mass matrix ``--mass-matrix`` (:mod:`.mass_matrix`), the Coriolis matrix
``--coriolis`` (:mod:`.coriolis_matrix`), the gravity torques ``--gravity-torques`` (:mod:`.gravity_torques`) and the
kinetic and potential energy ``--energy``; any of them may be combined. Each quantity's spec adds its own flag; the
options here (``--method``, ``--gravity``, ``--symbolic-inertials``, ``--steps``) are added once, by the command's own
quantity.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from symjac.errors import ArgumentError

if TYPE_CHECKING:
    from symjac.analysis.dynamics.gravity import Gravity
    from symjac.model.robot import Robot
    from symjac.printing.document import Document
    from symjac.quantities.spec import Request

__all__ = ["DYNAMICS_METHODS", "PARTS", "command", "gravity_setting", "options"]

_AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}

DYNAMICS_METHODS = ("newton-euler", "lagrange")
"""``--method``: recursive Newton-Euler (with its steps) or the Euler-Lagrange equations of T - V."""

PARTS = ("mass_matrix", "coriolis", "gravity_torques", "energy")
"""The flags (``dest``) that ask for a part besides (or instead of) the torques, in the order they print."""


def options(sub: argparse.ArgumentParser) -> None:
    """The options every part of ``symjac dynamics`` shares, and ``--energy``."""
    sub.add_argument("--method", choices=DYNAMICS_METHODS, default="newton-euler",
                     help="derive the torques by recursive Newton-Euler (default) or by Lagrange's equations; "
                          "the two agree exactly")
    sub.add_argument("--gravity", default=None, metavar="[X,Y,Z][:MAGNITUDE]",
                     help="gravity's direction in {0} (3 numbers or an axis: -y, z0) and/or magnitude: --gravity=-y, "
                          "0,-1,0:9.81, :0 (none), :1.62; default g along -z0, the symbol g (9.81 m/s^2 with "
                          "--numeric)")
    sub.add_argument("--symbolic-inertials", action="store_true",
                     help="give every link symbolic inertial parameters m_i, cx_i, ..., Izz_i (for robots without "
                          "inertial data, or to see the structure; a link's own data become their defaults)")
    sub.add_argument("--steps", action="store_true",
                     help="print every Newton-Euler step per link first (omega_i, alpha_i, a_i, a_ci, F_i, N_i, f_i, "
                          "n_i, tau_i)")
    sub.add_argument("--energy", action="store_true", help="print the kinetic energy T and potential energy V")
    sub.add_argument("--torques", action="store_true",
                     help="print the torques too when a part is asked for (they print alone by default)")


def gravity_setting(text: str | None, request: Request | None = None) -> Gravity:
    """``--gravity``: ``[DIRECTION][:MAGNITUDE]``, the direction three numbers in {0} or an axis (``-y``, ``z0``).

    Without a magnitude it stays the symbol g (9.81 m/s^2 for numbers); ``:0`` is no gravity.

    Examples
    --------
    >>> gravity_setting("-y").vector.T
    Matrix([[0, -g, 0]])
    >>> gravity_setting(":1.62").vector.T
    Matrix([[0, 0, -81/50]])
    """
    from symjac.analysis.dynamics.gravity import EARTH, Gravity

    if text is None:
        return EARTH
    direction_text, _, magnitude_text = text.partition(":")
    direction: tuple[object, ...] = EARTH.direction  # type: ignore[assignment]
    axis = direction_text.strip().lower().removesuffix("0")
    if axis.lstrip("+-") in _AXES and len(axis) <= 2:
        sign = -1 if axis.startswith("-") else 1
        direction = tuple(sign * v for v in _AXES[axis.lstrip("+-")])
    elif direction_text.strip():
        parts = direction_text.split(",")
        if len(parts) != 3:
            raise ArgumentError(f"--gravity: the direction is 3 numbers x,y,z in frame {{0}} or an axis (-z, y0), got "
                                f"{direction_text!r}")
        direction = tuple(_number(part, "--gravity's direction") for part in parts)
    if not magnitude_text.strip():
        return Gravity(direction=direction)
    magnitude = _number(magnitude_text, "--gravity's magnitude")
    if magnitude < 0:
        raise ArgumentError(f"--gravity: the magnitude must not be negative, got {magnitude_text.strip()} (turn the "
                            "direction instead)")
    return Gravity(direction=direction, magnitude=magnitude)


def _number(text: str, what: str) -> Any:
    import sympy as sp

    try:
        value = sp.nsimplify(sp.sympify(text.strip(), rational=True), rational=True)
    except (sp.SympifyError, TypeError, SyntaxError):
        value = None
    if value is None or not value.is_number or not value.is_real:
        raise ArgumentError(f"{what} must be a number, got {text.strip()!r}")
    return value


def _robot(request: Request) -> Robot:
    """The robot, with symbolic inertial parameters where ``--symbolic-inertials`` asks for them.

    A link that has inertial data keeps it as the defaults of its symbols (at the parameters' defaults), so
    ``--numeric`` still gives its numbers; a link without gets the placeholder (unit mass at the origin of {i}).
    """
    robot = request.robot
    if not request.args.symbolic_inertials:
        return robot
    from symjac.model.inertial_parameters import with_symbolic_inertials

    return with_symbolic_inertials(robot)


def command(request: Request) -> Document:
    """``symjac dynamics``: the parts asked for (the torques when no part is), one document."""
    from symjac.analysis import dynamics
    from symjac.errors import NoInertialDataError
    from symjac.printing.dynamics import DynamicsParts, dynamics_document

    args = request.args
    if getattr(args, "regressor", False) or getattr(args, "base_parameters", False):
        raise ArgumentError("--regressor and --base-parameters print the parameters' side of the dynamics; ask for "
                            "the other parts (--mass-matrix, --coriolis, --gravity-torques, --energy) separately")
    robot, gravity = _robot(request), gravity_setting(args.gravity)
    asked = {part for part in PARTS if getattr(args, part)}
    if args.steps and args.method != "newton-euler":
        raise ArgumentError("--steps prints the Newton-Euler recursion; it does not apply with --method lagrange")
    torques = args.torques or args.steps or not asked
    what = f"the dynamics of {robot.name}"
    try:
        steps = tau = None
        if torques and args.method == "newton-euler":
            recursion = request.progress(what, lambda: dynamics.newton_euler(robot, gravity))
            tau, steps = recursion.torques, recursion if args.steps else None
        elif torques:
            tau = request.progress(what, lambda: dynamics.euler_lagrange(robot, gravity))
        parts = DynamicsParts(
            torques=tau, steps=steps,
            mass_matrix=request.progress(what, lambda: dynamics.mass_matrix(robot)) if "mass_matrix" in asked
            else None,
            coriolis_matrix=request.progress(what, lambda: dynamics.coriolis_matrix(robot)) if "coriolis" in asked
            else None,
            gravity_torques=request.progress(what, lambda: dynamics.gravity_torques(robot, gravity))
            if "gravity_torques" in asked else None,
            kinetic_energy=dynamics.kinetic_energy(robot) if "energy" in asked else None,
            potential_energy=dynamics.potential_energy(robot, gravity) if "energy" in asked else None)
    except NoInertialDataError as error:  # the API's hint names a function; the command line has an option
        raise NoInertialDataError(f"{str(error).partition(';')[0]}; give them in the robot file or URDF, or add "
                                  "--symbolic-inertials") from None
    return dynamics_document(robot, parts, args.method, gravity, request.digits)
