r"""The intermediate results of the two column-by-column Jacobian methods, for printing them step by step.

Cross products (:func:`cross_product_steps`): for joint i with axis :math:`z_a` through the origin of frame {a}
(:meth:`~symjac.kinematics.chain.Chain.axis_frame`: {i-1} in standard DH, {i} in modified DH) and the point P,
everything read in frame {k},

.. math::
    {}^kJ_i = \begin{bmatrix} {}^kz_a \times {}^kp_{aP} \\ {}^kz_a \end{bmatrix} \text{ (revolute)}, \qquad
    {}^kJ_i = \begin{bmatrix} {}^kz_a \\ 0 \end{bmatrix} \text{ (prismatic)},
    \qquad {}^kp_{aP} = {}^kp_P - {}^kp_a .

Differentiation (:func:`differentiation_steps`): the position :math:`{}^0p_P = {}^0_lR\,{}^lp + {}^0p_l` of P (fixed in
link l), then per joint :math:`{}^0J_{v,i} = \partial\,{}^0p_P / \partial q_i` and
:math:`{}^0J_{\omega,i} = {}^0z_a` (revolute) or 0 (prismatic), and for a frame {k} other than {0}
:math:`{}^kJ = \mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J`.

Each vector is simplified to the same normal form :func:`symjac.kinematics.jacobian.jacobian` gives, so the columns
assembled are the Jacobian the method prints. A robot with coupled joints is stepped through joint by joint (its
joint chain); its coordinate Jacobian is then :math:`J_q = J\,C`.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.memo import frame_of
from symjac.kinematics.points import Point, link_of, link_point
from symjac.model.robot import Robot
from symjac.symbolic.simplify import simplify_matrix
from symjac.symbolic.transforms import block_rotation

__all__ = ["CrossProductColumn", "CrossProductSteps", "DifferentiationColumn", "DifferentiationSteps",
           "cross_product_steps", "differentiation_steps"]


@dataclass(frozen=True)
class CrossProductColumn:
    r"""Column i of :math:`{}^kJ` by the cross product: the axis :math:`z_a`, the lever :math:`p_{aP}`, the column.

    ``lever`` is None for a prismatic joint (its column is :math:`[z_a; 0]`).
    """

    joint: int
    variable: sp.Symbol
    axis_frame: int
    axis: sp.ImmutableMatrix
    lever: sp.ImmutableMatrix | None
    column: sp.ImmutableMatrix


@dataclass(frozen=True)
class CrossProductSteps:
    """Every column of the cross-product method in frame ``frame``; joints after the point's link have none."""

    frame: Frame
    n_joints: int
    columns: tuple[CrossProductColumn, ...]

    def jacobian(self) -> sp.Matrix:
        """The 6 x n Jacobian the columns assemble to (zero columns for joints that do not move the point)."""
        J = sp.zeros(6, self.n_joints)
        for step in self.columns:
            J[:, step.joint - 1] = step.column
        return J


@dataclass(frozen=True)
class DifferentiationColumn:
    r"""Column i of :math:`{}^0J` by differentiation: :math:`\partial\,{}^0p_P/\partial q_i` and the angular part."""

    joint: int
    variable: sp.Symbol
    axis_frame: int
    revolute: bool
    linear: sp.ImmutableMatrix
    angular: sp.ImmutableMatrix


@dataclass(frozen=True)
class DifferentiationSteps:
    r"""The position :math:`{}^0p_P`, every column of :math:`{}^0J`, and :math:`{}^k_0R` when {k} is not {0}."""

    frame: Frame
    n_joints: int
    position: sp.ImmutableMatrix
    columns: tuple[DifferentiationColumn, ...]
    rotation: sp.ImmutableMatrix | None

    def jacobian(self) -> sp.Matrix:
        r""":math:`{}^kJ = \mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J` from the columns (not simplified again)."""
        J_0 = sp.zeros(6, self.n_joints)
        for step in self.columns:
            J_0[:3, step.joint - 1] = step.linear
            J_0[3:, step.joint - 1] = step.angular
        return J_0 if self.rotation is None else block_rotation(self.rotation) * J_0


def _arguments(robot: Robot | Chain, frame: Frame, point: Point | None,
               link: int | None) -> tuple[Chain, Frame, sp.Matrix, int]:
    chain = as_chain(robot).joint_chain
    frame = frame_of(chain, frame)
    point_l = link_point(chain, point, link)  # before link_of: with no link, no point is the end of the chain
    return chain, frame, sp.Matrix(point_l), link_of(chain, link)


def _simplified(chain: Chain, frame: Frame, vector: sp.MatrixBase, simplify: bool) -> sp.ImmutableMatrix:
    if not simplify or chain.nested:
        return sp.ImmutableMatrix(vector)
    return sp.ImmutableMatrix(simplify_matrix(vector, chain.angle_bases(frame)))


def cross_product_steps(robot: Robot | Chain, frame: Frame = 0, point: Point | None = None, *,
                        link: int | None = None, simplify: bool = True) -> CrossProductSteps:
    r"""Per joint :math:`{}^kz_a`, :math:`{}^kp_{aP}` and the column :math:`{}^kJ_i` (module docstring).

    ``frame``, ``point`` and ``link`` as in :func:`symjac.kinematics.jacobian.jacobian`.

    Examples
    --------
    >>> from symjac import load_robot
    >>> step = cross_product_steps(load_robot("planar2r")).columns[1]
    >>> step.axis_frame, step.lever.T, step.column.T
    (1, Matrix([[L2*cos(theta1 + theta2), L2*sin(theta1 + theta2), 0]]), Matrix([[-L2*sin(theta1 + theta2), L2*cos(theta1 + theta2), 0, 0, 0, 1]]))
    """  # noqa: E501
    chain, frame, point_l, link = _arguments(robot, frame, point, link)
    T_k_l = chain.transform(frame, link)
    p_kP = T_k_l[:3, :3] * point_l + T_k_l[:3, 3]
    columns = []
    for joint in chain.robot.joints[:link]:
        a = chain.axis_frame(joint.index)
        T_k_a = chain.transform(frame, a)
        z = _simplified(chain, frame, T_k_a[:3, 2], simplify)
        if joint.is_revolute:
            lever: sp.ImmutableMatrix | None = _simplified(chain, frame, p_kP - T_k_a[:3, 3], simplify)
            column = sp.Matrix.vstack(sp.Matrix(z).cross(sp.Matrix(lever)), sp.Matrix(z))
        else:
            lever, column = None, sp.Matrix.vstack(sp.Matrix(z), sp.zeros(3, 1))
        columns.append(CrossProductColumn(joint.index, joint.variable, a, z, lever,
                                          _simplified(chain, frame, column, simplify)))
    return CrossProductSteps(frame, chain.n_joints, tuple(columns))


def differentiation_steps(robot: Robot | Chain, frame: Frame = 0, point: Point | None = None, *,
                          link: int | None = None, simplify: bool = True) -> DifferentiationSteps:
    r""":math:`{}^0p_P`, per joint :math:`\partial\,{}^0p_P/\partial q_i` and :math:`{}^0z_a`, then :math:`{}^k_0R`.

    ``frame``, ``point`` and ``link`` as in :func:`symjac.kinematics.jacobian.jacobian`.

    Examples
    --------
    >>> from symjac import load_robot
    >>> steps = differentiation_steps(load_robot("planar2r"))
    >>> steps.position.T
    Matrix([[L1*cos(theta1) + L2*cos(theta1 + theta2), L1*sin(theta1) + L2*sin(theta1 + theta2), 0]])
    >>> steps.columns[1].linear.T
    Matrix([[-L2*sin(theta1 + theta2), L2*cos(theta1 + theta2), 0]])
    """
    chain, frame, point_l, link = _arguments(robot, frame, point, link)
    T_0_l = chain.transform(0, link)
    position = _simplified(chain, 0, T_0_l[:3, :3] * point_l + T_0_l[:3, 3], simplify)
    columns = []
    for joint in chain.robot.joints[:link]:
        a = chain.axis_frame(joint.index)
        linear = _simplified(chain, 0, position.diff(joint.variable), simplify)
        angular = chain.rotation(0, a)[:, 2] if joint.is_revolute else sp.zeros(3, 1)
        columns.append(DifferentiationColumn(joint.index, joint.variable, a, joint.is_revolute, linear,
                                             _simplified(chain, 0, angular, simplify)))
    rotation = None if chain.position(frame) == 0 else _simplified(chain, frame, chain.rotation(frame, 0), simplify)
    return DifferentiationSteps(frame, chain.n_joints, position, tuple(columns), rotation)
