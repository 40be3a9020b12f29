r"""The basic Jacobian :math:`{}^{k}J` (rows :math:`[v; \omega]`) at a point, in a frame (``symjac jacobian``).

The command also prints the screw Jacobians :math:`J_s`, :math:`J_b` (``--kind``), the representation Jacobian
:math:`J_x = E(x)\,J_0` (``--representation``) and the steps of a propagation method (``--steps``); its
``--derivative`` is another quantity's (:mod:`.bias_acceleration`).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from symjac.errors import ArgumentError
from symjac.model.ends import end_point
from symjac.quantities.options import LazyChoices, frame_and_point_options
from symjac.quantities.spec import Generated, Quantity, Request

if TYPE_CHECKING:
    from symjac.kinematics.chain import Frame
    from symjac.kinematics.jacobian import Point
    from symjac.printing.document import Document

__all__ = ["QUANTITY", "command", "options", "propagation", "propagation_tip", "representation", "screw_jacobian"]


def options(sub: argparse.ArgumentParser) -> None:
    """``--frame``, ``--point``, the method, the kind, ``--steps``, a representation and its position part."""
    from symjac.kinematics.jacobian import METHODS

    frame_and_point_options(sub)
    representations = "symjac.analysis.representations"  # loaded only when one is asked for (it loads NumPy)
    sub.add_argument("--method", choices=METHODS, default="differentiation", help="derivation method")
    sub.add_argument("--kind", choices=("geometric", "space", "body"), default="geometric",
                     help="geometric: the basic Jacobian [v; omega] (default); space or body: J_s or J_b of "
                          "screw theory, rows (omega; v) as in Lynch and Park (--frame and --point do not apply)")
    sub.add_argument("--steps", action="store_true",
                     help="print the method's steps first: per joint z_i, p_iP and the column z_i x p_iP "
                          "(cross_product), the derivative of the point's position by each joint variable "
                          "(differentiation), or every propagation step (a propagation method, or --derivative)")
    sub.add_argument("--representation", choices=LazyChoices(representations, "REPRESENTATIONS"), default=None,
                     metavar="NAME", help="print the representation Jacobian J_x = E(x) J_0 for these "
                                          "orientation coordinates: %(choices)s")
    sub.add_argument("--position", choices=LazyChoices(representations, "POSITIONS"), default=None,
                     metavar="NAME", help="with --representation: position coordinates, %(choices)s (default "
                                          "cartesian)")


def command(request: Request) -> Document:
    """``symjac jacobian``: the basic Jacobian, or (``--kind``, ``--representation``) one of its relatives."""
    from symjac.kinematics.jacobian import jacobian
    from symjac.printing.results import jacobian_document

    args, robot = request.args, request.robot
    frame, point, link = request.frame(), request.point(), request.link()
    if args.kind != "geometric":
        return screw_jacobian(request)
    if args.representation is not None:
        if link is not None:
            raise ArgumentError("--link does not apply with --representation (the representation is of the end "
                                "frame's orientation)")
        return representation(request, frame, end_point(robot) if point is None else point)
    steps = propagation(request, point) if args.steps else None
    J = request.progress(f"Jacobian of {robot.name} in frame {frame}",
                         lambda: jacobian(robot, frame=frame, point=point, method=args.method, link=link))
    return jacobian_document(robot, J, frame, request.point_name(), args.method, steps, request.digits, link=link)


def screw_jacobian(request: Request) -> Document:
    """``jacobian --kind space|body``: J_s or J_b (the frame and point are the space and tool frames)."""
    from symjac.kinematics.screws import body_jacobian, space_jacobian
    from symjac.printing.results import screw_jacobian_document

    args, robot = request.args, request.robot
    others = [flag for flag, given in (("--frame", args.frame != "0"), ("--point", args.point is not None),
                                       ("--link", request.link() is not None),
                                       ("--representation", args.representation is not None),
                                       ("--derivative", args.derivative), ("--steps", args.steps)) if given]
    if others:
        raise ArgumentError(f"--kind {args.kind} does not take {' or '.join(others)}: it prints J_s (space frame "
                            f"{{0}}) or J_b (tool frame) as they are, at their own points")
    derive = space_jacobian if args.kind == "space" else body_jacobian
    J = request.progress(f"{args.kind} Jacobian of {robot.name}", lambda: derive(robot))
    return screw_jacobian_document(robot, J, args.kind, request.digits)


def representation(request: Request, frame: Frame, point: Point) -> Document:
    """``jacobian --representation``: x, E(x), the basic Jacobian and J_x = E(x) J_0, then E's own singularities."""
    from symjac.analysis.representations import representation_jacobian
    from symjac.printing.results import representation_document

    args, robot = request.args, request.robot
    position = args.position or "cartesian"
    result = request.progress(f"{args.representation} representation Jacobian of {robot.name}",
                              lambda: representation_jacobian(robot, args.representation, position, point, frame))
    return representation_document(robot, result, request.point_name(), args.representation, position,
                                   request.digits)


def propagation(request: Request, point: Point | None) -> Any:
    """The derivation whose steps ``--steps`` prints: a propagation, or the columns of the other two methods."""
    from symjac.kinematics.column_steps import cross_product_steps, differentiation_steps
    from symjac.kinematics.propagation import force_propagation, velocity_propagation

    args, robot, link, frame = request.args, request.robot, request.link(), request.frame()
    tip = propagation_tip(robot, point, link)
    derive: dict[str, Callable[[], Any]] = {
        "velocity_propagation": lambda: velocity_propagation(robot, tip, link=link),
        "force_propagation": lambda: force_propagation(robot, tip, link=link),
        "cross_product": lambda: cross_product_steps(robot, frame, point, link=link),
        "differentiation": lambda: differentiation_steps(robot, frame, point, link=link),
    }
    return request.progress(f"{args.method.replace('_', ' ')} steps of {robot.name}", derive[args.method])


def propagation_tip(robot: Any, point: Point | None, link: int | None = None) -> Any:
    """The point a propagation ends at: None for the tool frame, else coordinates.

    No point: the end of the chain (:func:`~symjac.model.ends.end_point`), or with a ``link`` the origin of its frame.
    """
    from symjac.kinematics.jacobian import point_vector

    if point is None and link is not None:
        return point_vector(robot, "flange")  # (0, 0, 0): the origin of the link's frame
    if (end_point(robot) if point is None else point) == "tool":
        return None
    return point_vector(robot, point)


QUANTITY = Quantity(
    name="jacobian",
    summary="print the basic Jacobian [v; omega]",
    derivation="symjac.kinematics.jacobian:jacobian",
    coupling="columns",
    document="symjac.printing.results:jacobian_document",
    codegen=Generated(
        "jacobian", "Rows as listed in the module docstring; column i belongs to {unit} i.",
        listing="The Jacobian in frame {frame} at {at}, rows {rows}.",
        summary="The basic Jacobian [v; omega] at {at}, in frame {frame}",
        summary_coupled="The Jacobian J_q = J C [v; omega] in the coordinates, at {at}, in frame {frame}",
        output="J", lowering="symjac.codegen.coupled:coordinate_jacobian"),
    command="jacobian",
    options=options,
    handler=command,
)
