"""The dynamics of an arm: gravity, inverse dynamics by Newton-Euler, and the Lagrangian route.

Gravity is a setting (:mod:`.gravity`); inverse dynamics comes from the recursive Newton-Euler algorithm with every
step kept (:mod:`.newton_euler`); the Lagrangian route gives the mass matrix, the Coriolis matrix, the gravity
torques, the energies and the Euler-Lagrange equations (:mod:`.lagrange`); motor inertia and friction where the robot
has drive data (:mod:`.drives`). Pure mathematics: SymPy in, SymPy out.
"""

from symjac.analysis.dynamics.drives import armature_matrix, drive_torques, friction_torques
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
    "armature_matrix",
    "coriolis_matrix",
    "drive_torques",
    "dynamics_defaults",
    "euler_lagrange",
    "friction_torques",
    "gravity_torques",
    "kinetic_energy",
    "mass_matrix",
    "newton_euler",
    "newton_euler_mass_matrix",
    "potential_energy",
]
