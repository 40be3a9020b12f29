r"""The kinematic Hessian :math:`H[i, j, k] = \partial J_{ij} / \partial q_k` (``symjac hessian``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from symjac.quantities.options import frame_and_point_options
from symjac.quantities.spec import Generated, Quantity, Request

if TYPE_CHECKING:
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command"]


def command(request: Request) -> Document:
    """``symjac hessian``: one 6 x n slice dJ/dq_k per joint."""
    from symjac.kinematics.acceleration import hessian, hessian_slice
    from symjac.printing.results import hessian_document

    robot = request.robot
    frame, point, link = request.frame(), request.point(), request.link()
    H = request.progress(f"Hessian of {robot.name} in frame {frame}",
                         lambda: hessian(robot, frame=frame, point=point, link=link))
    slices = [hessian_slice(H, k) for k in range(len(robot.q))]
    return hessian_document(robot, slices, frame, request.point_name(), request.digits, link=link)


QUANTITY = Quantity(
    name="hessian",
    summary="print the kinematic Hessian: dJ/dq_k for every joint k",
    derivation="symjac.kinematics.acceleration:hessian",
    coupling="congruent",
    document="symjac.printing.results:hessian_document",
    codegen=Generated(
        "hessian", "``H[i, j, m]`` is the derivative of row i, column j of the Jacobian with respect to {unit} m.",
        listing="Its kinematic Hessian: H[i, j, m] = dJ[i, j]/dq_m, shape {shape}.",
        summary="The kinematic Hessian H[i, j, m] = dJ[i, j]/dq_m of ``{jacobian}``", output="H",
        layout="H[(i * {shape[1]} + j) * {shape[2]} + m] = dJ[i][j]/dq_m", acceleration=True,
        lowering="symjac.codegen.coupled:coordinate_hessian"),
    command="hessian",
    options=frame_and_point_options,
    handler=command,
)
