r"""The position of the tool point in frame {0}, :math:`{}^{0}p_t` (``symjac position``): a throwaway quantity.

The tool point is the origin of the tool frame (of {n} when the robot has no tool transform); its position is the
translation column of :math:`{}^{0}_{t}T`. Generated modules compute it once per module, ``tool_position(q)``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from symjac.quantities.spec import Generated, Quantity, Request, lazily_memoized

if TYPE_CHECKING:
    import sympy as sp

    from symjac.kinematics.chain import Chain
    from symjac.model.robot import Robot
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "document", "tool_position"]


@lazily_memoized(coupling="rates")
def tool_position(chain: Chain) -> sp.Matrix:
    r""":math:`{}^{0}p_t = {}^{0}_{t}T_{1:3,\,4}`: the tool point in frame {0}, a 3 x 1 matrix."""
    import sympy as sp

    return sp.Matrix(chain.transform(0, "tool")[:3, 3])


def document(robot: Robot, p: sp.MatrixBase, digits: int | None = None) -> Document:
    """The position printed: one equation, its entries under ``entries`` in JSON."""
    from symjac.printing.document import Block, Document, Equation, JsonKey
    from symjac.printing.results import shown

    equation = Equation("{}^{0}p_{t}", "p_0_t", shown(robot, p, digits), key=JsonKey("entries", latex="latex",
                                                                                       flat=True))
    return Document(f"{robot.name}: position of the tool point", robot.name,
                    (Block(("Position of the tool point in frame {0}",), (equation,)),),
                    facts={"frame": 0, "shape": [3]}, model=robot)


def command(request: Request) -> Document:
    """``symjac position``: the tool point in frame {0}."""
    robot = request.robot
    p = request.progress(f"tool position of {robot.name}", lambda: tool_position(robot))
    return document(robot, p, request.digits)


QUANTITY = Quantity(
    name="tool_position",
    summary="print the position of the tool point in frame {0}",
    derivation="symjac.quantities.tool_position:tool_position",
    coupling="rates",
    document="symjac.quantities.tool_position:document",
    codegen=Generated(
        "tool_position", "The coordinates x, y, z of the tool point in frame {{0}}.",
        listing="The position of the tool point in frame {{0}}.",
        summary="The position of the tool point in frame {{0}}", output="position", scope="module"),
    command="position",
    options=lambda sub: None,  # the common options only
    handler=command,
)
