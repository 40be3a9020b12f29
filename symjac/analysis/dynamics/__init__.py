"""The dynamics of an arm: gravity (:mod:`.gravity`), inverse dynamics by recursive Newton-Euler with every step
kept (:mod:`.newton_euler`), and the Lagrangian route: mass matrix, Coriolis matrix, gravity torques, energies and the
Euler-Lagrange equations (:mod:`.lagrange`). Pure mathematics: SymPy results in, SymPy results out.
"""

from symjac.analysis.dynamics.gravity import EARTH, GRAVITY_SYMBOL, NO_GRAVITY, Gravity, dynamics_defaults
from symjac.analysis.dynamics.lagrange import (
    coriolis_matrix,
    euler_lagrange,
    gravity_torques,
    kinetic_energy,
    mass_matrix,
    potential_energy,
)
from symjac.analysis.dynamics.newton_euler import LinkStep, NewtonEuler, newton_euler, newton_euler_mass_matrix

__all__ = [
    "EARTH",
    "GRAVITY_SYMBOL",
    "NO_GRAVITY",
    "Gravity",
    "LinkStep",
    "NewtonEuler",
    "coriolis_matrix",
    "dynamics_defaults",
    "euler_lagrange",
    "gravity_torques",
    "kinetic_energy",
    "mass_matrix",
    "newton_euler",
    "newton_euler_mass_matrix",
    "potential_energy",
]
