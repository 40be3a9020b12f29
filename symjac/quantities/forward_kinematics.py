r"""Forward kinematics: the pose of the end of the chain (``symjac fk``).

The pose runs from the world frame when the robot has a base transform (else frame {0}) to the tool frame when it
has a tool (else the last joint frame {n}): the whole arm (:mod:`symjac.model.ends`). Generated code computes it from
frame {0}, to the same end; the origin of that end is the default point of the Jacobian, in Python, on the command
line and in generated code.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from symjac.quantities.spec import Generated, Quantity, Request

if TYPE_CHECKING:
    from symjac.kinematics.chain import Frame
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command"]


def command(request: Request) -> Document:
    """``symjac fk``: the pose of the end of the chain relative to its start."""
    from symjac.kinematics.chain import forward_kinematics
    from symjac.model.ends import first_frame, last_frame
    from symjac.printing.results import forward_kinematics_document

    robot = request.robot
    source: Frame = first_frame(robot)
    target: Frame = last_frame(robot)
    T = request.progress(f"forward kinematics of {robot.name}", lambda: forward_kinematics(robot, source, target))
    return forward_kinematics_document(robot, source, target, T, request.digits)


QUANTITY = Quantity(
    name="forward_kinematics",
    summary="print the forward kinematics",
    derivation="symjac.kinematics.chain:forward_kinematics",
    coupling="rates",
    document="symjac.printing.results:forward_kinematics_document",
    codegen=Generated(
        "forward_kinematics", "The homogeneous transform [[R, p], [0, 0, 0, 1]], row by row.",
        listing="The 4 x 4 pose of {end} in frame {{0}}, the end of the chain.",
        summary="The pose of {end} in frame {{0}}, the end of the chain",
        output="T", scope="module", lowering="symjac.codegen.coupled:coordinate_forward_kinematics"),
    command="fk",
    options=lambda sub: None,  # the common options only
    handler=command,
)
