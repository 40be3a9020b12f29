r"""Screw-theory kinematics (Lynch and Park, *Modern Robotics*, chapters 3 to 5), for every robot symjac reads.

A twist and a screw axis are written angular part first, :math:`\mathcal{V} = (\omega, v)`, as in the book (symjac's
basic Jacobian puts :math:`v` first). For a robot with tool frame {b} (the tool, or frame {n} without one) and
space frame {s} = frame {0}:

* the **space Jacobian** :math:`J_s(\theta)`, whose column *i* is joint *i*'s screw axis in {s} at the current
  configuration: :math:`(\omega_i, -\omega_i \times q_i)` for a revolute joint through the point :math:`q_i`,
  :math:`(0, \hat{v}_i)` for a prismatic one; :math:`\mathcal{V}_s = J_s \dot\theta` is the spatial twist
  :math:`(\omega_s, \dot p - \omega_s \times p)`;
* the **body Jacobian** :math:`J_b = [\mathrm{Ad}_{T_{sb}^{-1}}]\,J_s`, which maps :math:`\dot\theta` to the body
  twist :math:`(\omega_b, v_b)`, both in {b}: it is symjac's basic Jacobian at the tool point in the tool frame with
  its two halves swapped;
* the exponential of a screw (:func:`screw_exponential`, Rodrigues' formula in closed form) and the product of
  exponentials of a PoE robot (:func:`exponential_product`).
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from symjac.errors import FrameError
from symjac.kinematics.chain import Chain, as_chain
from symjac.kinematics.coupling import in_coordinates
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.memo import memoized
from symjac.model.conventions.poe import PRODUCT_OF_EXPONENTIALS, home_pose, space_screws
from symjac.model.ends import end_point, last_frame
from symjac.model.robot import Robot
from symjac.symbolic.nested import named, presented, presented_matrix
from symjac.symbolic.simplify import simplify_matrix
from symjac.symbolic.transforms import homogeneous, skew

__all__ = ["SCREW_ROWS", "body_jacobian", "exponential_product", "screw_exponential", "space_jacobian"]

SCREW_ROWS: tuple[str, ...] = ("omega_x", "omega_y", "omega_z", "v_x", "v_y", "v_z")
"""The rows of a space or body Jacobian: angular part first."""

_SWAP = [3, 4, 5, 0, 1, 2]


def screw_exponential(screw: Sequence[sp.Expr], theta: sp.Expr) -> sp.Matrix:
    r"""The rigid motion :math:`e^{[\mathcal{S}]\theta}` of a unit screw axis :math:`\mathcal{S} = (\omega, v)`.

    For :math:`|\omega| = 1` (Rodrigues):

    .. math:: e^{[\mathcal{S}]\theta} = \begin{bmatrix} I + \sin\theta\,[\omega] + (1 - \cos\theta)[\omega]^2 &
              (I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2)\,v \\ 0 & 1 \end{bmatrix}

    and for :math:`\omega = 0`, :math:`|v| = 1`: a translation by :math:`v\theta`.

    Examples
    --------
    >>> t = sp.Symbol("t")
    >>> screw_exponential([0, 0, 1, 0, -1, 0], t)[:2, 3].T  # about the z-axis through (1, 0, 0)
    Matrix([[1 - cos(t), -sin(t)]])
    """
    values = [sp.sympify(e) for e in screw]
    if len(values) != 6:
        raise ValueError(f"a screw axis has 6 entries (w then v), got {len(values)}")
    omega, v = sp.Matrix(values[:3]), sp.Matrix(values[3:])
    if all(e == 0 for e in omega):
        return homogeneous(sp.eye(3), v * theta)
    square = omega.dot(omega)
    if square.is_number and abs(float(square) - 1) > 1e-9:
        raise ValueError(f"Rodrigues' formula needs a unit w, got |w|^2 = {float(square):.6g}")
    W = skew(omega)
    rotation = sp.eye(3) + sp.sin(theta) * W + (1 - sp.cos(theta)) * W * W
    translation = (sp.eye(3) * theta + (1 - sp.cos(theta)) * W + (theta - sp.sin(theta)) * W * W) * v
    return homogeneous(rotation.applyfunc(sp.expand), translation.applyfunc(sp.expand))


def exponential_product(robot: Robot | Chain) -> sp.Matrix:
    r"""The product of exponentials :math:`e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M`.

    Each factor is :func:`screw_exponential` of a PoE robot's screw; the product is multiplied out as it stands (in
    the coordinates).

    It equals ``forward_kinematics(robot, target="tool")`` (the chain's product of link transforms) identically;
    the tests check it.
    """
    chain = as_chain(robot)
    model = chain.robot
    if model.convention is not PRODUCT_OF_EXPONENTIALS:
        raise FrameError(f"{model.name} is not described by a product of exponentials (its convention is "
                         f"{model.convention.value}); convert it first (symjac convert {model.name} --to poe)")
    product = sp.eye(4)
    for screw, variable in zip(space_screws(model), model.joint_variables, strict=True):
        product = product * screw_exponential(screw, variable)
        if chain.nested:  # generic screws: each partial product named, as the chain does (floats, no growth)
            product = product.evalf().applyfunc(named)
    return presented(in_coordinates(chain, product * home_pose(model)))  # type: ignore[no-any-return]


@memoized(fresh=presented_matrix, coupling="columns", layout=0)
def space_jacobian(chain: Chain, *, simplify: bool = True) -> sp.Matrix:
    r"""The space Jacobian :math:`J_s(\theta)`, 6 x n, rows :math:`(\omega, v)` in frame {0} (see the module).

    Column *i* is the screw axis of joint *i* at the current configuration, read from the frame whose z-axis is
    that joint's axis: :math:`(z_i, p_i \times z_i)` (revolute) or :math:`(0, z_i)` (prismatic), :math:`p_i` its
    origin; a coupled robot's columns belong to its coordinates (:math:`J_s C`).

    Examples
    --------
    >>> from symjac import load_robot
    >>> space_jacobian(load_robot("planar2r"))[3:5, :]
    Matrix([
    [0,  L1*sin(theta1)],
    [0, -L1*cos(theta1)]])
    """
    columns = []  # a coupled robot's columns: J_s C (the columns law, applied by @memoized)
    for joint in chain.robot.joints:
        frame = chain.transform(0, chain.axis_frame(joint.index))
        z, p = sp.Matrix(frame[:3, 2]), sp.Matrix(frame[:3, 3])
        columns.append([*z, *p.cross(z)] if joint.is_revolute else [0, 0, 0, *z])
    J = sp.Matrix(columns).T
    return sp.ImmutableMatrix(simplify_matrix(J, chain.angle_bases(0)) if simplify else J)


def body_jacobian(robot: Robot | Chain, *, simplify: bool = True) -> sp.Matrix:
    r"""The body Jacobian :math:`J_b = [\mathrm{Ad}_{T_{sb}^{-1}}]\,J_s`, rows :math:`(\omega, v)` in the tool frame.

    It is the basic Jacobian at the tool point in the tool frame (frame {n} at its origin without a tool) with its
    halves swapped, derived the way :func:`~symjac.kinematics.jacobian.jacobian` derives it.
    """
    chain = as_chain(robot)
    J = jacobian(chain, last_frame(chain), end_point(chain), simplify=simplify)
    return presented(sp.Matrix(J)[_SWAP, :])  # type: ignore[no-any-return]
