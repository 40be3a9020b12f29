r"""The joint torques :math:`\tau = J^T F` that hold a wrench :math:`F` at a point (``symjac torques``)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from symjac.quantities.options import frame_and_point_options
from symjac.quantities.spec import Generated, Quantity, Request

if TYPE_CHECKING:
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "options"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--frame``, ``--point``, the wrench and a configuration to evaluate at."""
    frame_and_point_options(sub)
    sub.add_argument("--wrench", help="fx,fy,fz,nx,ny,nz applied at the point, in the frame (default symbolic)")
    sub.add_argument("--q", help="a configuration q1,...,qn: 30deg, 0.5rad, expressions with pi, or numbers in the "
                                 "robot file's angle unit (radians unless it says angle_unit = \"deg\")")


def command(request: Request) -> Document:
    """``symjac torques``: tau for the wrench given (or the symbolic one), at ``--q`` as numbers."""
    from symjac.kinematics.propagation import wrench_symbols
    from symjac.kinematics.statics import joint_torques
    from symjac.printing.latex import DIGITS
    from symjac.printing.results import torques_document

    args, robot = request.args, request.robot
    frame, point, link = request.frame(), request.point(), request.link()
    wrench = None if args.wrench is None else request.values(args.wrench, 6, "--wrench")
    q = None if args.q is None else request.configuration(args.q)
    tau = request.progress(f"joint torques of {robot.name}",
                           lambda: joint_torques(robot, wrench=wrench, frame=frame, point=point, q=q, link=link))
    evaluated = None if q is None else args.digits or DIGITS  # at a configuration: numbers, shown as decimals
    return torques_document(robot, tau, frame, request.point_name(), args.wrench, args.q, wrench_symbols(),
                            request.digits, evaluated, link=link)


QUANTITY = Quantity(
    name="joint_torques",
    summary="print the joint torques tau = J^T F that hold a wrench",
    derivation="symjac.kinematics.statics:joint_torques",
    coupling="transposed",
    document="symjac.printing.results:torques_document",
    codegen=Generated(
        "joint_torques", "One torque (force, for a prismatic joint) per joint.",
        listing="Joint torques tau = J^T F of that Jacobian, F = ({wrench}).",
        summary="Joint torques tau = J^T F holding a wrench F at {at}, F in frame {frame}",
        summary_coupled="Joint torques tau = C^T J^T F holding a wrench F at {at}, F in frame {frame}",
        returns_coupled="One generalised force per coordinate, C^T J^T F.", output="tau", inputs=("wrench",),
        lowering="symjac.codegen.coupled:coordinate_torques"),
    command="torques",
    options=options,
    handler=command,
)
