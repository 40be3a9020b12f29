r"""Acceleration-level kinematics in closed form: the kinematic Hessian, the Jacobian's time derivative and the bias.

With the columns :math:`J_j = [v_j; \omega_j]` of the basic Jacobian at a point P fixed to the last link
(:math:`\omega_j = \bar\epsilon_j z_j`, zero for a prismatic joint), every second derivative of the forward
kinematics is a cross product of two columns. Joint m moves axis j (and P) rigidly when it comes before it, and it
moves P but not axis j otherwise, so in a fixed frame

.. math::
    H_{jm} = \frac{\partial J_j}{\partial q_m} =
    \begin{cases}
        [\,\omega_m \times v_j;\ \omega_m \times \omega_j\,] & m < j \\
        [\,\omega_j \times v_m;\ 0\,] & m \ge j
    \end{cases}

(the linear part is symmetric in j and m: it is :math:`\partial^2 p_P / \partial q_j \partial q_m`). The time
derivative follows by the chain rule, :math:`\dot J = \sum_m H_{\cdot m}\,\dot q_m`, and the *bias acceleration*
is :math:`\dot J \dot q`: the acceleration :math:`[\dot v; \dot\omega]` of P when :math:`\ddot q = 0`, so that
:math:`[\dot v; \dot\omega] = J \ddot q + \dot J \dot q`.

**Frames.** In a fixed frame ({0}, "world") this is all. A Jacobian expressed in a *moving* frame {k},
:math:`{}^kJ = \mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J`, has a derivative of its own because :math:`{}^k_0R` turns
with the joints that carry {k} (:math:`\dot{{}^k_0R} = -{}^k_0R\,[\omega_k]_\times`):

.. math::
    \frac{d}{dt}{}^kJ = {}^k\dot J_0 - \mathrm{diag}([{}^k\omega_k]_\times, [{}^k\omega_k]_\times)\,{}^kJ,

where :math:`{}^k\dot J_0` is the fixed-frame derivative re-expressed in {k}. Per joint m that carries {k} the
Hessian loses the same term; the two coincide for m < j, which therefore vanish. Both are computed from the
columns of :math:`{}^kJ` alone (cross products do not care which frame they are written in).

**Points of earlier links.** For a point fixed in link l (``link=l``) the columns of joints m > l are zero, and the
same formula gives every fixed-frame slice. Only the moving-frame term needs joint m's own angular velocity
:math:`a_m` (:math:`z_m` for a revolute joint, zero for a prismatic one) where the Jacobian's column is zero: a
joint after l that carries {k} still turns the frame the Jacobian is written in,

.. math::
    \frac{\partial\,{}^kJ_j}{\partial q_m} = -\begin{bmatrix} a_m \times v_j \\ a_m \times \omega_j \end{bmatrix}
    \qquad (m > l,\ m \text{ carries } \{k\}).

How this maps onto other tools: pinocchio's ``getFrameJacobianTimeVariation`` in ``LOCAL_WORLD_ALIGNED`` is the
fixed-frame derivative (``frame=0`` with the frame's origin as the point, rotated to the world frame); in
``LOCAL`` it is the derivative of the Jacobian expressed in the moving frame itself (``frame="tool"`` with
``point="tool"``, or ``frame=n`` at the wrist), whose product with :math:`\dot q` is pinocchio's spatial
(not classical) acceleration :math:`[{}^ka - {}^k\omega \times {}^kv;\ {}^k\dot\omega]`. The Robotics Toolbox's
``jacob0_dot`` and ``hessian0`` are the fixed-frame quantities in the base frame (``frame=0``); its Hessian stacks
the slices :math:`\partial J/\partial q_m` first, where symjac's array puts the joint index last.
"""

from __future__ import annotations

from typing import Literal, get_args

import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.memo import frame_of, memoized, one_of
from symjac.kinematics.points import Point, link_of, link_point
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import Robot
from symjac.symbolic.nested import presented, presented_matrix
from symjac.symbolic.simplify import simplify_matrix

DerivativeMethod = Literal["hessian", "differentiation"]
DERIVATIVE_METHODS: tuple[str, ...] = get_args(DerivativeMethod)
"""How dJ/dt is derived: from the Hessian's column cross products, or by SymPy's chain rule."""

__all__ = [
    "DERIVATIVE_METHODS",
    "DerivativeMethod",
    "bias_acceleration",
    "carried_joints",
    "hessian",
    "hessian_slice",
    "jacobian_derivative",
]


def carried_joints(robot: Robot | Chain, frame: Frame) -> tuple[int, ...]:
    """The joints (1-based) whose motion turns ``frame``: none for {0} and "world", 1..k for {k}, all for "tool"."""
    chain = as_chain(robot)
    return tuple(range(1, min(max(chain.position(frame), 0), chain.n_joints) + 1))


@memoized(frame=frame_of, point=link_point, link=link_of, coupling="congruent", layout="frame", fresh=presented)
def hessian(
    chain: Chain, frame: Frame = 0, point: Point | None = None, *, simplify: bool = True, link: int | None = None
) -> sp.ImmutableDenseNDimArray:
    r"""The kinematic Hessian :math:`H_{ijm} = \partial J_{ij} / \partial q_m` of the basic Jacobian :math:`{}^kJ`.

    Parameters
    ----------
    robot : Robot or Chain
    frame, point, link
        As for :func:`symjac.kinematics.jacobian`: the Hessian is that of exactly the Jacobian ``jacobian(robot, frame,
        point, link=link)``, moving frame included (see the module docstring).
    simplify : bool
        Compact textbook form (default), or the cross products of the (compact) Jacobian's columns as they come,
        unexpanded.

    Returns
    -------
    H : sympy.ImmutableDenseNDimArray, shape (6, n, n), n = n_coordinates
        ``H[i, j, m]`` is the derivative of row i (:data:`~symjac.kinematics.jacobian.ROW_NAMES`), column j of the
        Jacobian with respect to coordinate m (all 0-based; coordinates are the joint variables unless the robot
        couples joints, :mod:`symjac.kinematics.coupling`). ``H[:, :, m]`` is the 6 x n slice
        :math:`\partial J / \partial q_m` (:func:`hessian_slice`). In a fixed frame the linear rows are symmetric,
        ``H[i, j, m] == H[i, m, j]`` for i < 3.

    Examples
    --------
    >>> from symjac import load_robot
    >>> H = hessian(load_robot("planar2r"))
    >>> H.shape
    (6, 2, 2)
    >>> hessian_slice(H, 1)[:2, :]  # d J / d theta2: the second link's lever arm turns
    Matrix([
    [-L2*cos(theta1 + theta2), -L2*cos(theta1 + theta2)],
    [-L2*sin(theta1 + theta2), -L2*sin(theta1 + theta2)]])
    """
    return _hessian(chain, frame, point, simplify, link)  # type: ignore[arg-type]  # normalised by @memoized


def hessian_slice(H: sp.NDimArray, m: int) -> sp.Matrix:
    r"""The 6 x n matrix :math:`\partial J / \partial q_m` (0-based m) of a Hessian from :func:`hessian`."""
    rows, cols, coordinates = H.shape
    if not 0 <= m < coordinates:
        raise ArgumentError(f"coordinate index {m} is outside 0..{coordinates - 1}")
    return sp.Matrix(rows, cols, lambda i, j: H[i, j, m])


def _columns(J: sp.MatrixBase) -> list[tuple[sp.Matrix, sp.Matrix]]:
    return [(sp.Matrix(J[:3, j]), sp.Matrix(J[3:, j])) for j in range(J.cols)]


def _hessian_pair(columns: list[tuple[sp.Matrix, sp.Matrix]], j: int, m: int,
                  carried: dict[int, sp.Matrix]) -> tuple[sp.Matrix, sp.Matrix]:
    r""":math:`\partial J_j / \partial q_m` (0-based j, m) from the columns of :math:`{}^kJ`: (linear, angular).

    ``carried`` maps each joint that turns {k} to its angular velocity :math:`a_m` (its column's, but also for a
    joint past the point's link, whose column is zero).
    """
    v_j, w_j = columns[j]
    v_m, w_m = columns[m]
    zero = sp.zeros(3, 1)
    if m < j:
        return (zero, zero) if m in carried else (w_m.cross(v_j), w_m.cross(w_j))
    if m in carried:
        a_m = carried[m]
        return w_j.cross(v_m) - a_m.cross(v_j), -a_m.cross(w_j)
    return w_j.cross(v_m), zero


def _hessian(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], simplify: bool,
             link: int) -> sp.ImmutableDenseNDimArray:
    n = chain.n_joints
    if simplify:
        raw = hessian(chain, frame, list(point), simplify=False, link=link)
        flat = simplify_matrix(sp.Matrix(raw.reshape(6, n * n).tolist()), chain.angle_bases(frame))
        return sp.ImmutableDenseNDimArray(list(flat), (6, n, n))
    columns = _columns(jacobian(chain, frame, list(point), link=link))
    carried = {m - 1: columns[m - 1][1] if m <= link else _spin(chain, frame, m)
               for m in carried_joints(chain, frame)}
    H = sp.MutableDenseNDimArray.zeros(6, n, n)
    for j in range(n):
        for m in range(n):
            linear, angular = _hessian_pair(columns, j, m, carried)
            for i, value in enumerate((*linear, *angular)):
                H[i, j, m] = value
    return sp.ImmutableDenseNDimArray(H)


def _spin(chain: Chain, frame: Frame, joint: int) -> sp.Matrix:
    r"""Joint ``joint``'s (1-based) angular velocity per unit rate in ``frame``, compact: :math:`z_a` or zero."""
    if not chain.robot.joints[joint - 1].is_revolute:
        return sp.zeros(3, 1)
    return sp.Matrix(chain.simplified_transform(frame, chain.axis_frame(joint))[:3, 2])


@memoized(frame=frame_of, point=link_point, link=link_of, method=one_of(DERIVATIVE_METHODS), fresh=presented_matrix,
          coupling="columns", layout="frame")
def jacobian_derivative(
    chain: Chain,
    frame: Frame = 0,
    point: Point | None = None,
    method: DerivativeMethod = "hessian",
    *,
    simplify: bool = True,
    link: int | None = None,
) -> sp.Matrix:
    r"""The time derivative :math:`\frac{d}{dt}{}^kJ` of the basic Jacobian, in the joint variables and rates.

    .. math:: \dot J = \sum_m \frac{\partial J}{\partial q_m}\,\dot q_m

    Parameters
    ----------
    robot : Robot or Chain
    frame, point, link
        As for :func:`symjac.kinematics.jacobian`. For a fixed frame ({0}, "world") this is what
        :math:`[\dot v; \dot\omega] = J\ddot q + \dot J\dot q` needs; for a moving frame it is the derivative of the
        Jacobian *expressed in that moving frame*, which differs (module docstring).
    method : "hessian" or "differentiation"
        Sum of the Hessian's slices written as cross products of columns (default), or SymPy's derivative of
        :math:`J` by the chain rule; both give the same matrix.
    simplify : bool
        Compact textbook form (default), or the raw expressions.

    Returns
    -------
    Jdot : sympy.Matrix, shape (6, n_coordinates)
        In the coordinates and the rate symbols of :func:`symjac.joint_rate_symbols` (``thetadot1``, ``ddot3``,
        ...; the coordinates' rates when the robot couples joints).

    Examples
    --------
    >>> from symjac import load_robot
    >>> jacobian_derivative(load_robot("planar2r"))[0, 1]
    -L2*(thetadot1 + thetadot2)*cos(theta1 + theta2)
    """
    # coupled: Jdot_q = Jdot(theta(q), C qdot) C = sum_m H_q[:, :, m] qdot_m, the columns law
    return _jacobian_derivative(chain, frame, point, method, simplify, link)  # type: ignore[arg-type]  # normalised


def _jacobian_derivative(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], method: DerivativeMethod,
                         simplify: bool, link: int) -> sp.ImmutableMatrix:
    if simplify:
        raw = jacobian_derivative(chain, frame, list(point), method, simplify=False, link=link)
        return sp.ImmutableMatrix(_collect_rates(simplify_matrix(raw, chain.angle_bases(frame)), chain))
    rates = joint_rate_symbols(chain)
    if method == "differentiation":
        J = jacobian(chain, frame, list(point), simplify=False, link=link)
        q = chain.robot.joint_variables
        return sp.ImmutableMatrix(J.rows, J.cols, lambda i, j: sum(J[i, j].diff(q_m) * rate
                                                                    for q_m, rate in zip(q, rates, strict=True)))
    H = hessian(chain, frame, list(point), simplify=False, link=link)
    n = chain.n_joints
    return sp.ImmutableMatrix(6, n, lambda i, j: sum(H[i, j, m] * rates[m] for m in range(n)))


@memoized(frame=frame_of, point=link_point, link=link_of, method=one_of(DERIVATIVE_METHODS), fresh=presented_matrix,
          coupling="rates", layout="frame")
def bias_acceleration(
    chain: Chain,
    frame: Frame = 0,
    point: Point | None = None,
    method: DerivativeMethod = "hessian",
    *,
    simplify: bool = True,
    link: int | None = None,
) -> sp.Matrix:
    r"""The bias acceleration :math:`\dot J\dot q` (6 x 1), the term a resolved-acceleration controller subtracts.

    It is the acceleration :math:`[\dot v; \dot\omega]` of the point at zero joint acceleration.

    Arguments as for :func:`jacobian_derivative`; in a moving frame it is :math:`(\tfrac{d}{dt}{}^kJ)\,\dot q`.

    Examples
    --------
    >>> from symjac import load_robot
    >>> bias_acceleration(load_robot("planar2r"))[0]
    -L1*thetadot1**2*cos(theta1) - L2*(thetadot1 + thetadot2)**2*cos(theta1 + theta2)
    """
    # coupled: Jdot_q qdot = Jdot thetadot with thetadot = C qdot, the rates law
    raw = jacobian_derivative(chain, frame, point, method, simplify=False, link=link) * sp.Matrix(
        joint_rate_symbols(chain))
    if not simplify:
        return sp.ImmutableMatrix(raw)
    return sp.ImmutableMatrix(_collect_rates(simplify_matrix(raw, chain.angle_bases(frame)), chain))


def _collect_rates(matrix: sp.MatrixBase, chain: Chain) -> sp.Matrix:
    r"""Factor the sums of rates left by the layout where that is shorter.

    ``thetadot1*(thetadot1 + 2*thetadot2) + thetadot2**2`` reads :math:`(\dot\theta_1 + \dot\theta_2)^2`.
    """
    rates = frozenset(joint_rate_symbols(chain))

    def is_rate_sum(expr: sp.Expr) -> bool:
        return expr.is_Add and bool(expr.free_symbols) and expr.free_symbols <= rates

    def shorter(expr: sp.Expr) -> sp.Expr:
        factored = sp.factor(expr)
        return factored if sp.count_ops(factored) < sp.count_ops(expr) else expr

    return matrix.applyfunc(lambda entry: entry.replace(is_rate_sum, shorter))
