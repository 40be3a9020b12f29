"""Identification: the dynamics linear in the inertial parameters, and their estimation from measured data.

The workflow (:mod:`.workflow`) stacks a regressor over samples and solves by (weighted) least squares; the
exciting trajectories (:mod:`.excitation`) are finite Fourier series judged by the stacked regressor's condition
number. Pure NumPy (SciPy only for :func:`~.excitation.optimise_excitation`).
"""

from symjac.analysis.identification.excitation import (
    Excitation,
    excitation_condition,
    fourier_basis,
    fourier_trajectory,
    optimise_excitation,
)
from symjac.analysis.identification.workflow import Identification, identify, joint_weights, stack

__all__ = [
    "Excitation",
    "Identification",
    "excitation_condition",
    "fourier_basis",
    "fourier_trajectory",
    "identify",
    "joint_weights",
    "optimise_excitation",
    "stack",
]
