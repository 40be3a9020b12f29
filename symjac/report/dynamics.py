r"""The report's dynamics section: :math:`M(q)`, :math:`g(q)` and, for a short arm, :math:`\tau(q, \dot q, \ddot q)`.

A robot with inertial data on every link gets its mass matrix and gravity torques (gravity :math:`g` along
:math:`-z_0`, :data:`~symjac.analysis.dynamics.gravity.EARTH`), and up to :data:`TORQUE_JOINTS` coordinates the
joint torques by recursive Newton-Euler (a six-joint arm's run to hundreds of thousands of characters: the command
line prints them, ``symjac dynamics``); a robot without it gets one sentence naming the links that lack it, and how
to derive with symbolic parameters instead.
"""

from __future__ import annotations

import html

import sympy as sp

from symjac.analysis.dynamics import gravity_torques, mass_matrix, newton_euler
from symjac.analysis.dynamics.gravity import EARTH
from symjac.errors import NoInertialDataError
from symjac.model.robot import Robot
from symjac.printing.dynamics import DynamicsParts, dynamics_document, gravity_words
from symjac.printing.nested import named_document
from symjac.report.content import block_html

__all__ = ["TORQUE_JOINTS", "dynamics_html"]

TORQUE_JOINTS = 3
"""The report shows the joint torques of arms with at most this many coordinates (M and g of every arm)."""

READABLE_CHARACTERS = 20_000
"""A part longer than this (characters of its SymPy text) is named, not printed: the PUMA 560's M has about 5700, the
Panda's, with its identified numbers, about 280 000 (1.3 MB of MathML nobody reads)."""


def _readable(matrix: sp.MatrixBase) -> bool:
    characters = sum(len(str(entry)) for entry in matrix)
    return characters <= READABLE_CHARACTERS


def dynamics_html(robot: Robot) -> str:
    """The section's body: an introduction, then M, g (and tau), or the sentence saying why there is none."""
    try:
        M = mass_matrix(robot)
    except NoInertialDataError as error:
        missing = str(error).partition(";")[0].removeprefix(f"{robot.name}: ")
        return (f'<p class="note">No dynamics: {html.escape(missing)}. Give them in the robot file\'s '
                "<code>[joints.inertial]</code> tables or the URDF's <code>&lt;inertial&gt;</code> elements, or "
                f"derive with symbolic ones: <code>symjac dynamics {html.escape(robot.name)} "
                "--symbolic-inertials</code>.</p>\n")
    short = robot.n_coordinates <= TORQUE_JOINTS
    g = gravity_torques(robot)
    shown_M, shown_g = _readable(M), _readable(g)
    parts = DynamicsParts(mass_matrix=M if shown_M else None, gravity_torques=g if shown_g else None,
                          torques=newton_euler(robot).torques if short else None)
    intro = (f"The equations of motion tau = M(q) qddot + C(q, qdot) qdot + g(q), with {gravity_words(EARTH)}, from "
             "each link's mass, centre of mass and inertia about it (in the link's frame, SI units).")
    if not short:
        intro += (f" The joint torques of an arm of {robot.n_coordinates} coordinates are too long to read here: "
                  f"symjac dynamics {robot.name} prints them, and the Coriolis matrix.")
    unread = [name for name, shown in (("the mass matrix M", shown_M), ("the gravity torques g", shown_g)) if not shown]
    if unread:
        joined = " and ".join(unread)
        intro += (f" {joined[0].upper()}{joined[1:]} of this arm {'runs' if len(unread) == 1 else 'run'} to more "
                  f"than {READABLE_CHARACTERS} "
                  f"characters: symjac dynamics {robot.name} --mass-matrix --gravity-torques prints them, and "
                  f"symjac codegen {robot.name} --dynamics computes them.")
    document = named_document(dynamics_document(robot, parts))
    return f"<p>{html.escape(intro)}</p>\n" + "".join(block_html(block) for block in document.blocks)
