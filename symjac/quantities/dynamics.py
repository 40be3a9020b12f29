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
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from symjac.printing.document import Document
    from symjac.quantities.spec import Request

__all__ = ["DYNAMICS_METHODS", "PARTS", "command", "options"]

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
                     help="gravity's direction in {0} and/or magnitude: 0,-1,0 (along -y0), 0,0,-1:9.81, :0 (none), "
                          ":1.62; default g along -z0, the symbol g (9.81 m/s^2 with --numeric)")
    sub.add_argument("--symbolic-inertials", action="store_true",
                     help="give every link symbolic inertial parameters m_i, cx_i, ..., Izz_i (for robots without "
                          "inertial data, or to see the structure)")
    sub.add_argument("--steps", action="store_true",
                     help="print every Newton-Euler step per link first (omega_i, alpha_i, a_i, a_ci, F_i, N_i, f_i, "
                          "n_i, tau_i)")
    sub.add_argument("--energy", action="store_true", help="print the kinetic energy T and potential energy V")


def command(request: Request) -> Document:
    """``symjac dynamics``: the parts asked for (the torques when no part is), one document."""
    from symjac.quantities.dynamics_document import dynamics_command

    return dynamics_command(request)
