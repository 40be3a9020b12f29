r"""Representation Jacobians :math:`J_x = E(x)\,J_0`: end-effector rates in the coordinates a user picks.

The basic Jacobian :math:`J_0` maps joint rates to the twist :math:`[v; \omega]`. No set of orientation coordinates
has :math:`\omega` as its time derivative, but every one has a rate map that depends only on the coordinates
themselves (course chapter "The Jacobian", section 4.3):

.. math::
    \dot x_p = E_p(x_p)\,v, \qquad \dot x_r = E_r(x_r)\,\omega, \qquad
    J_x = \begin{bmatrix} E_p & 0 \\ 0 & E_r \end{bmatrix} J_0 = E(x)\,J_0 .

Conventions (one set, used by every function here):

* :math:`v` and :math:`\omega` are expressed in the base frame {0} (or "world"), as the rows of
  :func:`symjac.kinematics.jacobian` with ``frame=0``; :math:`\omega` is the spatial angular velocity,
  :math:`\dot R = \hat\omega R`.
* **Euler angles**, all 24 conventions, are values :class:`EulerConvention` ``(axes, extrinsic)`` with names:

  - *intrinsic* ``"zyz"``, ``"xyz"``, ... (the twelve :data:`EULER_ORDERS`): rotations about the axes of the *moving*
    frame, so the named axes multiply left to right: ``"zyz"`` is :math:`R = R_z(\alpha) R_y(\beta) R_z(\gamma)`
    (the wrist of the lecture slides), ``"xyz"`` is :math:`R_x(\alpha) R_y(\beta) R_z(\gamma)`;
  - *extrinsic* ``"zyz_extrinsic"``, ``"xzy_extrinsic"``, ...: rotations about the *fixed* axes in the order named,
    :math:`\alpha` first, so they multiply right to left: ``"zyx_extrinsic"`` is
    :math:`R_x(\gamma) R_y(\beta) R_z(\alpha)`, which is intrinsic ``"xyz"`` at :math:`(\gamma, \beta, \alpha)`;
  - **roll-pitch-yaw** ``"rpy"`` is extrinsic x-y-z (also accepted as ``"xyz_extrinsic"``), with roll :math:`\phi`,
    pitch :math:`\theta`, yaw :math:`\psi`: :math:`R = R_z(\psi) R_y(\theta) R_x(\phi)` (Craig's X-Y-Z fixed
    angles, and the ``rpy`` field of robot files, :func:`symjac.symbolic.transforms.rotation_rpy`).

  Proper conventions (first axis = last axis) have the middle angle in :math:`[0, \pi]`, Tait-Bryan ones in
  :math:`[-\pi/2, \pi/2]`; the other angles lie in :math:`(-\pi, \pi]`.
* **Direction cosines**: the nine entries of :math:`R`, row by row :math:`(r_{11}, r_{12}, \ldots, r_{33})`;
  :math:`\dot R = \hat\omega R`.
* **Euler parameters** (unit quaternion) ``"quaternion"``: :math:`(\eta, \epsilon_x, \epsilon_y, \epsilon_z)` with
  :math:`R = I + 2\eta\hat\epsilon + 2\hat\epsilon^2` and :math:`\eta \ge 0` when extracted.
* **Equivalent axis-angle** ``"axis_angle"``: unit axis :math:`k` and angle :math:`\vartheta \in [0, \pi]`,
  :math:`(k_x, k_y, k_z, \vartheta)`, :math:`R = c_\vartheta I + (1 - c_\vartheta) k k^T + s_\vartheta \hat k` (four
  coordinates, as the notes count them).
* **Position**: ``"cartesian"`` :math:`(x, y, z)`; ``"spherical"`` :math:`(r, \theta_s, \phi_s)` with polar angle
  :math:`\theta_s` from the z-axis and azimuth :math:`\phi_s`; ``"cylindrical"`` :math:`(\rho, \phi_c, z)`.

Representation singularities (where :math:`E` does not exist because the coordinates stop describing every nearby
pose, e.g. gimbal lock at :math:`s_\beta = 0` for Z-Y-Z) belong to the representation, not to the arm; they are
reported by :func:`representation_singularities`, apart from the kinematic singularities of :math:`J_0`.

The chapter's printed :math:`E_r` (4.31) is, in this convention, the Z-X-Z matrix (``rate_matrix("zxz")``); the Z-Y-Z
angles of the lecture slides give the matrix below.

Modules: :mod:`.registry` (the representation values, their names and coordinates, the registry),
:mod:`.maps` (symbolic :math:`R`, :math:`p`, :math:`B`, :math:`E` and singularities), :mod:`.extraction` (NumPy),
:mod:`.jacobian` (robots), :mod:`.derivative` (:math:`\dot J_x` and the bias :math:`\dot J_x \dot q` of an
analytic-Jacobian controller). Adding a representation: a value type and its registry entry in ``registry.py``,
its maps in ``maps.py``, its extraction in ``extraction.py``.

Examples
--------
>>> rate_matrix("zyz")
Matrix([
[-cos(alpha)*cos(beta)/sin(beta), -sin(alpha)*cos(beta)/sin(beta), 1],
[                    -sin(alpha),                      cos(alpha), 0],
[           cos(alpha)/sin(beta),            sin(alpha)/sin(beta), 0]])
"""

from symjac.analysis.representations.derivative import (
    NumericRepresentationJacobianDerivative,
    RepresentationJacobianDerivative,
    coordinate_rates,
    representation_jacobian_derivative,
    representation_jacobian_derivative_at,
)
from symjac.analysis.representations.extraction import GIMBAL_LOCK_TOLERANCE, extract, extract_position
from symjac.analysis.representations.jacobian import (
    NumericRepresentationJacobian,
    RepresentationJacobian,
    representation_jacobian,
    representation_jacobian_at,
)
from symjac.analysis.representations.maps import (
    angular_velocity_matrix,
    point_from,
    position_rate_matrix,
    rate_matrix,
    representation_singularities,
    rotation_from,
)
from symjac.analysis.representations.registry import (
    EULER_CONVENTIONS,
    EULER_ORDERS,
    POSITIONS,
    REPRESENTATIONS,
    AxisAngle,
    Cartesian,
    Cylindrical,
    DirectionCosines,
    EulerConvention,
    Orientation,
    Position,
    Quaternion,
    Representation,
    RepresentationSingularity,
    Spherical,
    coordinates,
    representation,
)
from symjac.errors import RepresentationError

__all__ = [
    "EULER_CONVENTIONS",
    "EULER_ORDERS",
    "GIMBAL_LOCK_TOLERANCE",
    "POSITIONS",
    "REPRESENTATIONS",
    "AxisAngle",
    "Cartesian",
    "Cylindrical",
    "DirectionCosines",
    "EulerConvention",
    "NumericRepresentationJacobian",
    "NumericRepresentationJacobianDerivative",
    "Orientation",
    "Position",
    "Quaternion",
    "Representation",
    "RepresentationError",
    "RepresentationJacobian",
    "RepresentationJacobianDerivative",
    "RepresentationSingularity",
    "Spherical",
    "angular_velocity_matrix",
    "coordinate_rates",
    "coordinates",
    "extract",
    "extract_position",
    "point_from",
    "position_rate_matrix",
    "rate_matrix",
    "representation",
    "representation_jacobian",
    "representation_jacobian_at",
    "representation_jacobian_derivative",
    "representation_jacobian_derivative_at",
    "representation_singularities",
    "rotation_from",
]
