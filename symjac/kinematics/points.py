r"""Points fixed in a link: which link, where in it, and where it is.

Link k is the body moved by joint k, carrying frame {k}; link 0 is the base (frame {0}). A point fixed in link k is
given by its coordinates :math:`{}^kp` in frame {k}; by default it is the origin of {k}. Link n, the last one, also
carries the tool, so the two named points belong to it: ``"wrist"`` (the origin of {n}) and ``"tool"`` (the origin
of the tool frame). Its position in any frame {f} is

.. math:: {}^fp_P = {}^f_kT \begin{bmatrix} {}^kp \\ 1 \end{bmatrix},

and its velocity depends on joints 1..k only: the Jacobian columns of later joints are zero.
"""

from __future__ import annotations

import operator
from collections.abc import Sequence
from typing import Literal

import sympy as sp

from symjac.errors import ArgumentError, FrameError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.coupling import in_coordinates
from symjac.model.robot import Robot
from symjac.symbolic.nested import presented
from symjac.symbolic.simplify import simplify_matrix

Point = Literal["wrist", "tool"] | Sequence[sp.Expr | float | int]
"""A point: ``"wrist"``, ``"tool"`` or three coordinates (in the frame of the link it is fixed in)."""

__all__ = ["Point", "link_of", "link_point", "point_position", "point_vector"]


def point_vector(robot: Robot | Chain, point: Point) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Coordinates in frame {n} of a point given as ``"wrist"``, ``"tool"`` or three coordinates (validated)."""
    robot = robot.robot if isinstance(robot, Chain) else robot
    if isinstance(point, str):
        if point == "wrist":
            return (sp.S.Zero,) * 3
        if point == "tool":
            if robot.tool is None:
                raise FrameError(f"{robot.name} has no tool transform, so it has no 'tool' point")
            x, y, z = robot.tool.matrix[:3, 3]
            return x, y, z
        raise FrameError(f"unknown point {point!r}: use 'wrist', 'tool' or three coordinates in frame {{n}}")
    values = tuple(point)
    if len(values) != 3:
        raise FrameError(f"a point needs 3 coordinates in frame {{n}}, got {len(values)}")
    coordinates = []
    for value in values:
        expr = sp.sympify(value)
        if not isinstance(expr, sp.Expr) or expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            raise FrameError(f"point coordinate {value!r} is not a finite number or expression")
        coordinates.append(sp.nsimplify(expr, rational=True) if expr.is_Float else expr)
    x, y, z = coordinates
    return x, y, z


def link_of(chain: Chain, link: int | None) -> int:
    """The link number 0..n a point is fixed in (``None``: the last link, n); other values are refused.

    Examples
    --------
    >>> from symjac import load_robot
    >>> link_of(as_chain(load_robot("planar3r")), None)
    3
    """
    n = chain.n_joints
    if link is None:
        return n
    try:
        number = operator.index(link)
    except TypeError:
        number = None
    if number is None or isinstance(link, bool):
        raise ArgumentError(f"link must be a whole number 0..{n}, got {link!r}")
    if not 0 <= number <= n:
        raise ArgumentError(f"link {link!r} does not exist for {chain.robot.name}: use 0..{n} (0 the base, link k "
                            f"moved by joint k, {n} the last link)")
    return number


def link_point(chain: Chain, point: Point | None, link: int) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Coordinates in frame {link} of a point of that link: ``None`` is its origin; the names need link n.

    ``"wrist"`` (the origin of {n}) and ``"tool"`` are fixed in the last link, so with an earlier link they are
    refused with the reason.
    """
    n = chain.n_joints
    if point is None:
        return (sp.S.Zero,) * 3
    if isinstance(point, str) and point not in ("wrist", "tool") and link != n:
        raise FrameError(f"unknown point {point!r}: give its three coordinates in frame {{{link}}}, or none for the "
                         f"origin of {{{link}}}")
    if isinstance(point, str) and point in ("wrist", "tool") and link != n:
        what = "the origin of frame {n}" if point == "wrist" else "the tool frame's origin"
        raise FrameError(f"point {point!r} is {what}, fixed in the last link ({n}), not in link {link}: give the "
                         f"point's coordinates in frame {{{link}}}, or none for the origin of {{{link}}}")
    if not isinstance(point, str) and len(tuple(point)) != 3:
        raise FrameError(f"a point needs 3 coordinates in frame {{{link}}}, got {len(tuple(point))}")
    return point_vector(chain, point)


def point_position(robot: Robot | Chain, point: Point | None = None, link: int | None = None,
                   frame: Frame = 0) -> sp.Matrix:
    r"""The position :math:`{}^fp_P = {}^f_kT\,[{}^kp; 1]` of a point fixed in link k, compact, in the coordinates.

    Parameters
    ----------
    robot : Robot or Chain
    point : "wrist", "tool" or sequence of 3, optional
        Its coordinates in frame {k} (default the origin of {k}); the names belong to the last link.
    link : int, optional
        The link k it is fixed in, 0..n (default n).
    frame : int or "world" or "tool"
        Frame {f} the position is expressed in (default {0}).

    Returns
    -------
    p : sympy.Matrix, shape (3, 1)

    Examples
    --------
    >>> from symjac import load_robot
    >>> point_position(load_robot("planar3r"), [1, 0, 0], link=2).T  # modified DH: {2} sits at the end of link 1
    Matrix([[L1*cos(theta1) + cos(theta1 + theta2), L1*sin(theta1) + sin(theta1 + theta2), 0]])
    """
    chain = as_chain(robot)
    k = link_of(chain, link)
    p = sp.Matrix(link_point(chain, point, k))
    T = chain.simplified_transform(frame, k)
    return presented(in_coordinates(chain, simplify_matrix(T[:3, :3] * p + T[:3, 3], chain.angle_bases(frame))))
