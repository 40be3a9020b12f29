r"""Identification of the dynamic parameters: the dynamics linear in its parameters, and their estimation from data.

:mod:`.parameters` names the standard parameters (ten per link, about the link origin; drive parameters per joint)
and gives a robot's own values of them; :mod:`.regressor` derives :math:`Y` with :math:`\tau = Y\pi`; :mod:`.base`
finds the base parameters in closed form (:mod:`.dependence`: the columns' exact linear dependence); SymPy in, SymPy
out. The workflow (:mod:`.workflow`) stacks a regressor over samples and solves by (weighted) least squares; the
exciting trajectories (:mod:`.excitation`) are finite Fourier series judged by the stacked regressor's condition
number (NumPy; SciPy only for :func:`~.excitation.optimise_excitation`).
"""

from symjac.analysis.identification.base import BaseParameters, base_parameters
from symjac.analysis.identification.excitation import (
    Excitation,
    excitation_condition,
    fourier_basis,
    fourier_trajectory,
    optimise_excitation,
)
from symjac.analysis.identification.parameters import DRIVE_NAMES, LINK_NAMES, standard_parameters, standard_values
from symjac.analysis.identification.regressor import Regressor, regressor
from symjac.analysis.identification.workflow import Identification, identify, joint_weights, stack

__all__ = [
    "DRIVE_NAMES",
    "LINK_NAMES",
    "BaseParameters",
    "Excitation",
    "Identification",
    "Regressor",
    "base_parameters",
    "excitation_condition",
    "fourier_basis",
    "fourier_trajectory",
    "identify",
    "joint_weights",
    "optimise_excitation",
    "regressor",
    "stack",
    "standard_parameters",
    "standard_values",
]
