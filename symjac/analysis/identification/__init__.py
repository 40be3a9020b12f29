r"""Identification of the dynamic parameters: the dynamics linear in its parameters (regressor form).

:mod:`.parameters` names the standard parameters (ten per link, about the link origin; drive parameters per joint)
and gives a robot's own values of them; :mod:`.regressor` derives :math:`Y` with :math:`\tau = Y\pi`; :mod:`.base`
finds the base parameters in closed form (:mod:`.dependence`: the columns' exact linear dependence). Pure
mathematics: SymPy in, SymPy out.
"""

from symjac.analysis.identification.base import BaseParameters, base_parameters
from symjac.analysis.identification.parameters import DRIVE_NAMES, LINK_NAMES, standard_parameters, standard_values
from symjac.analysis.identification.regressor import Regressor, regressor

__all__ = [
    "DRIVE_NAMES",
    "LINK_NAMES",
    "BaseParameters",
    "Regressor",
    "base_parameters",
    "regressor",
    "standard_parameters",
    "standard_values",
]
