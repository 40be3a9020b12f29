r"""Points fixed in a link: which link, where in it, and where it is.

Link k is the body moved by joint k, carrying frame {k}; link 0 is the base (frame {0}). A point fixed in link k is
given by its coordinates :math:`{}^kp` in frame {k}; by default it is the origin of {k}. Link n, the last one, also
carries the tool, so the named points belong to it:

* ``"tool"``: the origin of the tool frame (a robot file's tool transform, a URDF's tip link);
* ``"flange"``: the origin of frame {n} (of a standard-DH arm, :math:`d_n` beyond the wrist centre along
  :math:`z_n`); ``"wrist"`` is the same point, the name it had first;
* ``"wrist_centre"``: where the last three joint axes meet, when they do (:func:`wrist_centre`).

With no point and no link, the point is the end of the chain (:func:`symjac.model.ends.end_point`): the tool point
when the robot has a tool, else the flange, as for forward kinematics and generated code. Its position in any frame
{f} is

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
from symjac.model.ends import end_point
from symjac.model.robot import Robot
from symjac.symbolic.nested import presented
from symjac.symbolic.simplify import simplify_matrix

Point = Literal["tool", "flange", "wrist", "wrist_centre"] | Sequence[sp.Expr | float | int]
"""A point: ``"tool"``, ``"flange"`` (or ``"wrist"``), ``"wrist_centre"`` or three coordinates (in the frame of the
link it is fixed in)."""

POINT_NAMES: tuple[str, ...] = ("tool", "flange", "wrist", "wrist_centre")
"""The named points of the last link: the tool point, the origin of {n} (two names) and the wrist centre."""

__all__ = ["POINT_NAMES", "Point", "link_of", "link_point", "point_position", "point_vector", "wrist_centre"]


def point_vector(robot: Robot | Chain, point: Point | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Coordinates in frame {n} of a point given by name or as three coordinates (validated).

    ``None`` is the end of the chain (:func:`~symjac.model.ends.end_point`): the tool point, else the flange.
    """
    if point is None:
        point = end_point(robot)
    if isinstance(point, str):
        model = robot.robot if isinstance(robot, Chain) else robot
        if point in ("flange", "wrist"):
            return (sp.S.Zero,) * 3
        if point == "tool":
            if model.tool is None:
                raise FrameError(f"{model.name} has no tool transform, so it has no 'tool' point (its end is the "
                                 f"flange, the origin of frame {{{model.n_joints}}})")
            x, y, z = model.tool.matrix[:3, 3]
            return x, y, z
        if point == "wrist_centre":
            return wrist_centre(robot)
        raise FrameError(f"unknown point {point!r}: use {', '.join(map(repr, POINT_NAMES))} or three coordinates "
                         f"in frame {{n}}")
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


def link_point(chain: Chain, point: Point | None, link: int | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Coordinates in frame {link} of a point of that link; the names need link n.

    With no point: the end of the chain (:func:`~symjac.model.ends.end_point`) when no link is given (``link`` is
    None), else the origin of {link}. The named points are fixed in the last link, so with an earlier link they are
    refused with the reason. As a :func:`~symjac.kinematics.memo.memoized` normaliser it comes before ``link``'s,
    so that it sees whether a link was given.
    """
    n = chain.n_joints
    if link is None:
        return point_vector(chain, point)
    link = link_of(chain, link)
    if point is None:
        return (sp.S.Zero,) * 3
    if isinstance(point, str) and point not in POINT_NAMES and link != n:
        raise FrameError(f"unknown point {point!r}: give its three coordinates in frame {{{link}}}, or none for the "
                         f"origin of {{{link}}}")
    if isinstance(point, str) and point in POINT_NAMES and link != n:
        what = {"tool": "the tool frame's origin", "wrist_centre": "the wrist centre"}.get(point,
                                                                                          "the origin of frame {n}")
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
    point : "tool", "flange", "wrist", "wrist_centre" or sequence of 3, optional
        Its coordinates in frame {k} (default the origin of {k}; with no link either, the end of the chain: the tool
        point, else the flange); the names belong to the last link.
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
    p = sp.Matrix(link_point(chain, point, link))
    T = chain.simplified_transform(frame, k)
    return presented(in_coordinates(chain, simplify_matrix(T[:3, :3] * p + T[:3, 3], chain.angle_bases(frame))))


def wrist_centre(robot: Robot | Chain) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    r"""Coordinates in frame {n} of the wrist centre: the point where the last three joint axes meet.

    Each axis j is the line :math:`o_j + s\,z_j` (origin and z-axis of the frame it is the z-axis of). Two
    neighbouring axes meet where

    .. math:: s = \frac{((o_b - o_a) \times z_b) \cdot (z_a \times z_b)}{|z_a \times z_b|^2}, \qquad
              P = o_a + s\,z_a,

    when :math:`z_a \times z_b \ne 0` and :math:`(o_b - o_a) \cdot (z_a \times z_b) = 0`. A point on all three
    axes stays on them whatever the joints do (each turns the links after it about an axis through it), so it is
    fixed in link n and found exactly at :math:`q = 0`: axes n-2 and n-1 must meet at the same point as n-1 and n.

    Raises
    ------
    FrameError
        Naming the robot, when its last three joints are not all revolute or their axes do not meet in one point.

    Examples
    --------
    >>> from symjac import load_robot
    >>> wrist_centre(load_robot("iiwa7"))  # d7 before the origin of {7}, along z7
    (0, 0, -d7)
    >>> wrist_centre(load_robot("puma560"))  # Craig's table puts {4}, {5} and {6} at the wrist centre
    (0, 0, 0)
    """
    model = robot.robot if isinstance(robot, Chain) else robot
    n = model.n_joints
    joints = (model.uncoupled if model.coupling is not None else model).joints
    if n < 3 or not all(joint.is_revolute for joint in joints[-3:]):
        raise FrameError(f"{model.name} has no wrist centre: its last three joints are not all revolute (use "
                         f"'flange', 'tool' or three coordinates in frame {{{n}}})")
    chain = Chain(model.uncoupled if model.coupling is not None else model, nested=False)
    zero = {joint.variable: sp.S.Zero for joint in joints}
    T_0_n = chain.transform(0, n).xreplace(zero)
    R_n_0, p_0_n = T_0_n[:3, :3].T, T_0_n[:3, 3]
    axes = []
    for joint in joints[-3:]:
        T = chain.transform(0, chain.axis_frame(joint.index)).xreplace(zero)
        axes.append((R_n_0 * (T[:3, 3] - p_0_n), R_n_0 * T[:3, 2]))
    first, second = _meeting(*axes[:2]), _meeting(*axes[1:])
    if first is None or second is None or not all(_vanishes(a - b) for a, b in zip(first, second, strict=True)):
        raise FrameError(f"{model.name} has no wrist centre: its last three joint axes do not meet in one point (use "
                         f"'flange', 'tool' or three coordinates in frame {{{n}}})")
    x, y, z = (sp.nsimplify(value, rational=True) if value.is_Float else value for value in first)
    return x, y, z


def _meeting(a: tuple[sp.Matrix, sp.Matrix], b: tuple[sp.Matrix, sp.Matrix]) -> tuple[sp.Expr, ...] | None:
    """Where the lines ``a`` and ``b`` (origin, direction) meet, simplified; None when parallel or skew."""
    (o_a, z_a), (o_b, z_b) = a, b
    normal = z_a.cross(z_b)
    if all(_vanishes(value) for value in normal) or not _vanishes((o_b - o_a).dot(normal)):
        return None
    s = (o_b - o_a).cross(z_b).dot(normal) / normal.dot(normal)
    return tuple(sp.simplify(value) for value in o_a + s * z_a)


def _vanishes(expr: sp.Expr) -> bool:
    """Whether ``expr`` is zero: exactly, or for a number in floats (generic geometry) within 1e-9."""
    value = sp.simplify(expr)
    if value == 0:
        return True
    return bool(value.is_number and abs(complex(value)) < 1e-9)
