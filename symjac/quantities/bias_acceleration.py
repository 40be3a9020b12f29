r"""The time derivative :math:`\dot J` of the Jacobian and the bias acceleration :math:`\dot J \dot q`.

Printed by ``symjac jacobian --derivative`` (with ``--steps``: the acceleration propagation first); generated
modules compute the bias acceleration (``codegen --acceleration``).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from symjac.errors import ArgumentError
from symjac.quantities.spec import Generated, Quantity, Request

if TYPE_CHECKING:
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "options"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--derivative``, the flag that asks the ``jacobian`` command for this quantity."""
    sub.add_argument("--derivative", action="store_true",
                     help="print the time derivative dJ/dt and the bias acceleration Jdot qdot instead")


def command(request: Request) -> Document:
    """``symjac jacobian --derivative``: dJ/dt and Jdot qdot in the frame, at the point."""
    from symjac.kinematics.acceleration import bias_acceleration, carried_joints, jacobian_derivative
    from symjac.kinematics.acceleration_propagation import acceleration_propagation
    from symjac.kinematics.propagation import joint_rate_symbols
    from symjac.printing.results import derivative_document
    from symjac.quantities.jacobian import propagation_tip

    args, robot = request.args, request.robot
    frame, point, link = request.frame(), request.point(), request.link()
    if args.kind != "geometric":  # the screw Jacobians refuse --derivative, naming it
        from symjac.quantities.jacobian import screw_jacobian

        return screw_jacobian(request)
    if args.representation is not None:
        raise ArgumentError("--derivative does not apply with --representation (the derivative is of the basic "
                            "Jacobian)")
    propagation = None
    if args.steps:
        tip = propagation_tip(robot, point, link)
        propagation = request.progress(f"acceleration propagation of {robot.name}",
                                       lambda: acceleration_propagation(robot, tip, link=link))
    Jdot = request.progress(f"Jacobian derivative of {robot.name} in frame {frame}",
                            lambda: jacobian_derivative(robot, frame=frame, point=point, link=link))
    bias = bias_acceleration(robot, frame=frame, point=point, link=link)
    return derivative_document(robot, Jdot, bias, frame, request.point_name(), bool(carried_joints(robot, frame)),
                               joint_rate_symbols(robot), propagation, request.digits, link=link)


QUANTITY = Quantity(
    name="bias_acceleration",
    summary="print the time derivative dJ/dt and the bias acceleration Jdot qdot",
    derivation="symjac.kinematics.acceleration:bias_acceleration",
    coupling="rates",
    document="symjac.printing.results:derivative_document",
    codegen=Generated(
        "bias_acceleration", "The rows of Jdot qdot: the acceleration [dv/dt; domega/dt] at zero {unit} acceleration.",
        listing="Its bias acceleration Jdot qdot, from q and the {unit} rates qdot.",
        summary="The bias acceleration Jdot qdot of ``{jacobian}`` (the acceleration at zero qddot)", output="out",
        acceleration=True, inputs=("qdot",), lowering="symjac.codegen.coupled:coordinate_bias_acceleration"),
    command="jacobian",
    flag="derivative",
    options=options,
    handler=command,
)
