r"""Statics: the joint torques that hold a wrench, :math:`\tau = J^T F`, and wrenches moved between frames.

:math:`F = [f; n]` is the force and moment the arm applies to its environment at a point P, expressed in a frame {k};
by virtual work (:math:`\tau^T \delta q = F^T \delta x` with :math:`\delta x = J\,\delta q`) the torques that hold it
are :math:`\tau = ({}^kJ_P)^T\,{}^kF`, with :math:`{}^kJ_P` the basic Jacobian at P expressed in {k}. Moving a
wrench between frames and points (a force/torque sensor to the tool tip, say) is :func:`symjac.symbolic.transforms.
wrench_transform`; :func:`wrench_between` applies it to two frames of a robot.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.numeric import as_vector, evaluate_at
from symjac.kinematics.points import Point
from symjac.kinematics.propagation import linear_combination, wrench_symbols
from symjac.model.robot import Robot
from symjac.symbolic.nested import presented
from symjac.symbolic.transforms import wrench_transform

__all__ = ["joint_torques", "wrench_between"]


def joint_torques(
    robot: Robot | Chain,
    wrench: Sequence[sp.Expr | float] | None = None,
    frame: Frame = 0,
    point: Point | None = None,
    q: Sequence[float | sp.Expr] | None = None,
    *,
    link: int | None = None,
) -> sp.Matrix:
    r"""The joint torques (forces, for prismatic joints) :math:`\tau = ({}^kJ_P)^T\,{}^kF` that hold a wrench.

    Parameters
    ----------
    robot : Robot
    wrench : sequence of 6, optional
        :math:`[f_x, f_y, f_z, n_x, n_y, n_z]` applied by the arm at ``point``, expressed in ``frame``. Default: the
        symbols ``f_x .. n_z``.
    frame, point, link
        As for :func:`symjac.kinematics.jacobian`: the wrench acts at a point fixed in link ``link`` (default the
        last; joints after it bear none of it).
    q : sequence of n_coordinates, optional
        A configuration. With it, joint variables and parameters take numbers (the parameters' defaults) and the
        result is numeric.

    Returns
    -------
    tau : sympy.Matrix, shape (n_coordinates, 1)
        One generalised force per coordinate: :math:`C^T J^T F` for a robot that couples joints
        (:mod:`symjac.kinematics.coupling`).

    Examples
    --------
    >>> from symjac import load_robot
    >>> joint_torques(load_robot("planar2r"), frame=1)[:, 0].T
    Matrix([[-L2*f_x*sin(theta2) + f_y*(L1 + L2*cos(theta2)) + n_z, -L2*f_x*sin(theta2) + L2*f_y*cos(theta2) + n_z]])
    """
    F = sp.Matrix(wrench_symbols()) if wrench is None else as_vector(wrench, 6, "wrench")
    tau = linear_combination(jacobian(robot, frame=frame, point=point, link=link).T, F)
    if q is None:
        return presented(tau)  # type: ignore[no-any-return]
    return evaluate_at(robot, tau, q)


def wrench_between(robot: Robot | Chain, source: Frame, target: Frame) -> sp.Matrix:
    r"""The 6 x 6 map of a wrench from frame ``source`` (about its origin) to frame ``target`` (about its origin).

    .. math:: {}^{t}F = \begin{bmatrix} R & 0 \\ \hat{p} R & R \end{bmatrix} {}^{s}F, \quad
              {}^t_sT = \begin{bmatrix} R & p \\ 0 & 1 \end{bmatrix}

    Examples
    --------
    >>> from symjac import load_robot
    >>> robot = load_robot("planar3r")
    >>> wrench_between(robot, "tool", 3)[5, :]  # a force along y at the tool point: moment L3 f_y about {3}
    Matrix([[0, L3, 0, 0, 0, 1]])
    """
    return wrench_transform(as_chain(robot).transform(target, source))
