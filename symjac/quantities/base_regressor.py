r"""The base parameters and the base regressor :math:`Y_b` of :math:`\tau = Y_b\pi_b` (``--base-parameters``).

The base parameters :math:`\pi_b` are the identifiable combinations of the standard ones, each an exact linear
combination (:func:`~symjac.analysis.identification.base.base_parameters`); :math:`Y_b` keeps the regressor's
independent columns. ``symjac dynamics ROBOT --base-parameters`` prints them as a table (base parameter =
expression); generated modules (``identification=True``) compute ``base_regressor(q, qdot, qddot)`` and export the
names as ``BASE_PARAMETERS``. Coupling: as the regressor's (``transposed``).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from symjac.quantities.regressor import command
from symjac.quantities.spec import Generated, Quantity

if TYPE_CHECKING:
    import sympy as sp

__all__ = ["QUANTITY", "base_regressor_matrix", "options"]


def base_regressor_matrix(robot: Any, *args: Any, **kwargs: Any) -> sp.ImmutableMatrix:
    r"""The base regressor :math:`Y_b` of the robot's regressor (the arguments of ``regressor``)."""
    from symjac.analysis.identification.base import base_parameters
    from symjac.analysis.identification.regressor import regressor

    return base_parameters(regressor(robot, *args, **kwargs)).matrix


def options(sub: argparse.ArgumentParser) -> None:
    """``--base-parameters``."""
    sub.add_argument("--base-parameters", action="store_true",
                     help="print the base parameters: the identifiable combinations of the standard parameters, "
                          "each base parameter = its expression, and those that do not act on tau")


QUANTITY = Quantity(
    name="base_regressor",
    summary="print the base parameters (identifiable combinations) and the base regressor",
    derivation="symjac.quantities.base_regressor:base_regressor_matrix",
    coupling="transposed",
    document="symjac.printing.identification:identification_document",
    codegen=Generated("base_regressor",
                      "Y_b, shape {shape}: tau = Y_b pi_b, the columns in the order of BASE_PARAMETERS.",
                      "The base regressor Y_b(q, qdot, qddot) of tau = Y_b pi_b (the base parameters).",
                      output="Y_b", scope="module", identification=True, inputs=("qdot", "qddot"),
                      summary="Base regressor Y_b(q, qdot, qddot) of tau = Y_b pi_b (base parameters, BASE_PARAMETERS)",
                      lowering="symjac.codegen.dynamics:lowered_base_regressor"),
    command="dynamics",
    flag="base_parameters",
    options=options,
    handler=command,
)
