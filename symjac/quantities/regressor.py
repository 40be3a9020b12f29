r"""The regressor :math:`Y(q, \dot q, \ddot q)` of :math:`\tau = Y\pi` (``symjac dynamics --regressor``).

Linear in the standard parameters :math:`\pi` (ten per link, about the link origin, in the order of
:func:`~symjac.analysis.identification.parameters.standard_parameters`;
:func:`~symjac.analysis.identification.regressor.regressor`). Coupling: the derivation returns :math:`C^T Y` in the
coordinates, as the torques (the ``transposed`` law on each column). Generated with ``identification=True``; the
modules export the columns' names as ``REGRESSOR_PARAMETERS``.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from symjac.quantities.spec import Generated, Quantity

if TYPE_CHECKING:
    import sympy as sp

    from symjac.printing.document import Document
    from symjac.quantities.spec import Request

__all__ = ["QUANTITY", "command", "options", "regressor_matrix"]


def regressor_matrix(robot: Any, *args: Any, **kwargs: Any) -> sp.ImmutableMatrix:
    r"""The matrix :math:`Y` of :func:`~symjac.analysis.identification.regressor.regressor` (same arguments)."""
    from symjac.analysis.identification.regressor import regressor

    return regressor(robot, *args, **kwargs).matrix


def options(sub: argparse.ArgumentParser) -> None:
    """``--regressor``."""
    sub.add_argument("--regressor", action="store_true",
                     help="print the regressor Y(q, qdot, qddot) of tau = Y pi, linear in the standard parameters "
                          "(XX_i .. ZZ_i about the origin of {i}, MX_i, MY_i, MZ_i, M_i), and their order")


def command(request: Request) -> Document:
    """``symjac dynamics --regressor`` and/or ``--base-parameters``: one document with the parts asked for."""
    from symjac.errors import ArgumentError
    from symjac.printing.identification import identification_document
    from symjac.quantities.dynamics import gravity_setting

    args = request.args
    if args.steps or args.torques or args.symbolic_inertials or args.method != "newton-euler":
        raise ArgumentError("--regressor and --base-parameters need no inertial data and take none of --steps, "
                            "--torques, --symbolic-inertials, --method")
    robot, gravity = request.robot, gravity_setting(args.gravity)

    def derive() -> tuple[Any, Any]:
        from symjac.analysis.identification.regressor import regressor

        Y = regressor(robot, gravity)
        base = None
        if args.base_parameters:
            from symjac.analysis.identification.base import base_parameters

            base = base_parameters(Y)
        return Y, base

    Y, base = request.progress(f"the regressor of {robot.name}", derive)
    return identification_document(robot, Y, base, request.digits, show_regressor=args.regressor)


QUANTITY = Quantity(
    name="regressor",
    summary="print the regressor Y(q, qdot, qddot) of tau = Y pi",
    derivation="symjac.quantities.regressor:regressor_matrix",
    coupling="transposed",
    document="symjac.printing.identification:identification_document",
    codegen=Generated("regressor", "Y, shape {shape}: tau = Y pi, the columns in the order of REGRESSOR_PARAMETERS.",
                      "The regressor Y(q, qdot, qddot) of tau = Y pi, linear in the standard parameters.",
                      output="Y", scope="module", identification=True, inputs=("qdot", "qddot"),
                      summary="Regressor Y(q, qdot, qddot) of tau = Y pi (standard parameters, REGRESSOR_PARAMETERS)",
                      lowering="symjac.codegen.dynamics:lowered_regressor"),
    command="dynamics",
    flag="regressor",
    options=options,
    handler=command,
)
