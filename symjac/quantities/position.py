r"""The position :math:`{}^{k}p` of a point fixed in the last link, expressed in frame {k} (``symjac position``).

.. math::
    \begin{bmatrix} {}^{k}p \\ 1 \end{bmatrix} = {}^{k}_{n}T \begin{bmatrix} {}^{n}p \\ 1 \end{bmatrix}

with :math:`{}^{n}p` the point's coordinates in frame {n} (``wrist`` the origin of {n}, ``tool`` the tool point,
or three coordinates). Written in a coupled robot's coordinates by substitution, as the pose it comes from.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from symjac.quantities.options import frame_and_point_options
from symjac.quantities.spec import Quantity, Request

if TYPE_CHECKING:
    import sympy as sp

    from symjac.kinematics.chain import Chain, Frame
    from symjac.kinematics.jacobian import Point
    from symjac.model.robot import Robot
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "point_position", "position_document"]


def point_position(robot: Robot | Chain, point: Point = "wrist", frame: Frame = 0) -> sp.Matrix:
    r"""The position of ``point`` (fixed in link n) in ``frame``: the top of :math:`{}^{k}_{n}T\,[{}^{n}p; 1]`.

    Parameters
    ----------
    robot : Robot or Chain
    point : "wrist", "tool" or sequence of 3
        The point, as for :func:`symjac.kinematics.jacobian.jacobian` (coordinates in frame {n}).
    frame : int, "world" or "tool"
        The frame {k} its coordinates are written in.

    Returns
    -------
    sympy.Matrix, shape (3, 1)
        :math:`{}^{k}p`, in the coordinates.

    Examples
    --------
    >>> from symjac import load_robot
    >>> point_position(load_robot("planar2r")).T
    Matrix([[L1*cos(theta1) + L2*cos(theta1 + theta2), L1*sin(theta1) + L2*sin(theta1 + theta2), 0]])
    """
    import sympy as sp

    from symjac.kinematics.chain import as_chain, forward_kinematics
    from symjac.kinematics.jacobian import point_vector

    chain = as_chain(robot)
    T = forward_kinematics(chain, frame, chain.n_joints)
    p = sp.Matrix([*point_vector(chain.robot, point), 1])
    return (T * p)[:3, :]


def position_document(robot: Robot, p: sp.MatrixBase, frame: Frame, point: str,
                      digits: int | None = None) -> Document:
    r""":math:`{}^{k}p`, the position of ``point`` in ``frame`` (JSON: ``position`` and ``latex``)."""
    from symjac.printing.document import Block, Document, Equation, JsonKey
    from symjac.printing.results import frame_tex, shown

    equation = Equation(f"{{}}^{{{frame_tex(frame)}}}p", f"p in frame {frame}", shown(robot, p, digits),
                        key=JsonKey("position", latex="latex", flat=True))
    return Document(f"{robot.name}: position of the {point} point in frame {frame}", robot.name,
                    (Block((), (equation,)),), facts={"frame": frame, "point": point}, model=robot)


def command(request: Request) -> Document:
    """``symjac position``: the point's position in the frame."""
    robot = request.robot
    frame, point = request.frame(), request.point()
    p = request.progress(f"position of the {request.args.point} point of {robot.name}",
                         lambda: point_position(robot, point, frame))
    return position_document(robot, p, frame, request.args.point, request.digits)


QUANTITY = Quantity(
    name="position",
    summary="print the position of a point fixed in the last link, in a frame",
    derivation="symjac.quantities.position:point_position",
    coupling="substituted",
    document="symjac.quantities.position:position_document",
    kind="position",
    command="position",
    options=frame_and_point_options,
    handler=command,
)
