r"""Rigid-body transforms: elementary rotations and motions, skew matrices and 6 x 6 maps.

Everything here is pure SymPy and knows nothing about robot files or conventions. Link transforms are written as
lists of *elementary motions* (rotation or translation about/along an axis) so that :func:`compose` can multiply a
chain while merging consecutive rotations about the same axis: :math:`R_z(\theta_2) T_x(a) \cdots` stays as written, but
:math:`R_z(\theta_2) T_z(d) R_z(\theta_3) = T_z(d) R_z(\theta_2 + \theta_3)`, which is how parallel joints give the
compact :math:`c_{23}` instead of :math:`c_2 c_3 - s_2 s_3`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Literal

import sympy as sp

Axis = Literal["x", "y", "z"]

__all__ = [
    "Axis",
    "Composition",
    "Motion",
    "adjoint",
    "alignment",
    "block_rotation",
    "compose",
    "homogeneous",
    "inverse_motions",
    "inverse_transform",
    "point_shift",
    "rotation",
    "rotation_rpy",
    "skew",
    "twist_transform",
    "vee",
    "wrench_transform",
]
_AXIS_INDEX = {"x": 0, "y": 1, "z": 2}


def rotation(axis: Axis, angle: sp.Expr) -> sp.Matrix:
    r"""Return the 3 x 3 rotation by ``angle`` about the unit ``axis``.

    .. math:: R_z(\theta) = \begin{bmatrix} c & -s & 0 \\ s & c & 0 \\ 0 & 0 & 1 \end{bmatrix}

    Examples
    --------
    >>> rotation("z", sp.pi / 2)
    Matrix([
    [0, -1, 0],
    [1,  0, 0],
    [0,  0, 1]])
    """
    c, s = sp.cos(angle), sp.sin(angle)
    i = _AXIS_INDEX[axis]
    j, k = (i + 1) % 3, (i + 2) % 3
    matrix = sp.eye(3)
    matrix[j, j], matrix[j, k], matrix[k, j], matrix[k, k] = c, -s, s, c
    return matrix


def rotation_rpy(roll: sp.Expr, pitch: sp.Expr, yaw: sp.Expr) -> sp.Matrix:
    r"""Roll-pitch-yaw about fixed axes: :math:`R = R_z(\text{yaw})\,R_y(\text{pitch})\,R_x(\text{roll})`."""
    return rotation("z", yaw) * rotation("y", pitch) * rotation("x", roll)


def homogeneous(rotation_matrix: sp.Matrix, position: sp.Matrix) -> sp.Matrix:
    r"""Stack :math:`R` and :math:`p` into :math:`T = \begin{bmatrix} R & p \\ 0 & 1 \end{bmatrix}`."""
    transform = sp.eye(4)
    transform[:3, :3] = rotation_matrix
    transform[:3, 3] = position
    return transform


def inverse_transform(transform: sp.Matrix) -> sp.Matrix:
    r"""Invert a rigid transform without a general inverse: :math:`T^{-1} = [R^T, -R^T p; 0, 1]`."""
    rotation_t = transform[:3, :3].T
    return homogeneous(rotation_t, -rotation_t * transform[:3, 3])


def skew(vector: Sequence[sp.Expr]) -> sp.Matrix:
    r"""Cross-product matrix: :math:`\hat{p}\,v = p \times v`.

    .. math:: \hat{p} = \begin{bmatrix} 0 & -p_z & p_y \\ p_z & 0 & -p_x \\ -p_y & p_x & 0 \end{bmatrix}
    """
    x, y, z = vector
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def vee(matrix: sp.Matrix) -> sp.Matrix:
    r"""Inverse of :func:`skew`: the vector :math:`w` of a skew-symmetric :math:`\hat{w}`."""
    return sp.Matrix([matrix[2, 1], matrix[0, 2], matrix[1, 0]])


def block_rotation(rotation_matrix: sp.Matrix) -> sp.Matrix:
    r"""The 6 x 6 frame change of a basic Jacobian: :math:`{}^BJ = \mathrm{diag}({}^B_AR, {}^B_AR)\,{}^AJ`."""
    return sp.diag(rotation_matrix, rotation_matrix)


def point_shift(vector: Sequence[sp.Expr]) -> sp.Matrix:
    r"""The 6 x 6 map from the twist at a point W to the twist at E, with :math:`p = p_{WE}`.

    .. math:: \begin{bmatrix} v_E \\ \omega \end{bmatrix} =
              \begin{bmatrix} I & -\hat{p} \\ 0 & I \end{bmatrix} \begin{bmatrix} v_W \\ \omega \end{bmatrix}
    """
    shift = sp.eye(6)
    shift[:3, 3:] = -skew(vector)
    return shift


def twist_transform(transform: sp.MatrixBase) -> sp.Matrix:
    r"""The 6 x 6 map of a rigid body's twist from frame {B} (at its origin) to frame {A} (at its origin).

    With :math:`{}^A_BT = [R, p; 0, 1]`: :math:`{}^A\omega = R\,{}^B\omega` and
    :math:`{}^Av_A = R\,{}^Bv_B - {}^A\omega \times p`, i.e.

    .. math:: \begin{bmatrix} v_A \\ \omega_A \end{bmatrix} =
              \begin{bmatrix} R & \hat{p} R \\ 0 & R \end{bmatrix} \begin{bmatrix} v_B \\ \omega_B \end{bmatrix}

    ``twist_transform(T_6_T)`` gives the wrist twist from the tool-tip twist; ``twist_transform(T_T_6)`` the reverse.

    Examples
    --------
    >>> L = sp.Symbol("L")
    >>> T = homogeneous(sp.eye(3), sp.Matrix([L, 0, 0]))
    >>> (twist_transform(T) * sp.Matrix([0, 0, 0, 0, 0, 1])).T
    Matrix([[0, -L, 0, 0, 0, 1]])
    """
    R, p = sp.Matrix(transform[:3, :3]), sp.Matrix(transform[:3, 3])
    return sp.Matrix(sp.BlockMatrix([[R, skew(p) * R], [sp.zeros(3), R]]))


def adjoint(transform: sp.MatrixBase) -> sp.Matrix:
    r"""The adjoint map of :math:`T = [R, p; 0, 1]` on twists written angular part first, as Lynch and Park do.

    .. math:: [\mathrm{Ad}_T] = \begin{bmatrix} R & 0 \\ \hat{p} R & R \end{bmatrix}, \qquad
              \mathcal{V}_A = [\mathrm{Ad}_{T_{AB}}]\,\mathcal{V}_B

    (:func:`twist_transform` is the same map for twists written linear part first.)

    Examples
    --------
    >>> L = sp.Symbol("L")
    >>> (adjoint(homogeneous(sp.eye(3), sp.Matrix([L, 0, 0]))) * sp.Matrix([0, 0, 1, 0, 0, 0])).T
    Matrix([[0, 0, 1, 0, -L, 0]])
    """
    R, p = sp.Matrix(transform[:3, :3]), sp.Matrix(transform[:3, 3])
    return sp.Matrix(sp.BlockMatrix([[R, sp.zeros(3)], [skew(p) * R, R]]))


def wrench_transform(transform: sp.MatrixBase) -> sp.Matrix:
    r"""The 6 x 6 map of a wrench :math:`[f; n]` from frame {B} (moment about its origin) to frame {A}.

    With :math:`{}^A_BT = [R, p; 0, 1]`: :math:`{}^Af = R\,{}^Bf` and :math:`{}^An = R\,{}^Bn + p \times {}^Af`, i.e.

    .. math:: \begin{bmatrix} f_A \\ n_A \end{bmatrix} =
              \begin{bmatrix} R & 0 \\ \hat{p} R & R \end{bmatrix} \begin{bmatrix} f_B \\ n_B \end{bmatrix}

    It is the transpose of the twist map the other way: ``wrench_transform(T) == twist_transform(T^-1).T``. With
    ``T = T_T_S`` (sensor frame {S} seen from the tool frame {T}) it turns a force/torque sensor reading into the
    wrench at the tool tip.

    Examples
    --------
    >>> L, F = sp.symbols("L F")
    >>> T = homogeneous(sp.eye(3), sp.Matrix([L, 0, 0]))
    >>> (wrench_transform(T) * sp.Matrix([0, F, 0, 0, 0, 0])).T
    Matrix([[0, F, 0, 0, 0, F*L]])
    """
    R, p = sp.Matrix(transform[:3, :3]), sp.Matrix(transform[:3, 3])
    return sp.Matrix(sp.BlockMatrix([[R, sp.zeros(3)], [skew(p) * R, R]]))


# --- elementary motions and their structured product -------------------------------------------------------


@dataclass(frozen=True)
class Motion:
    """An elementary motion: ``kind`` ``"R"`` (rotate by ``value`` about ``axis``) or ``"T"`` (translate along it)."""

    kind: Literal["R", "T"]
    axis: Axis
    value: sp.Expr


def inverse_motions(motions: Sequence[Motion | sp.MatrixBase]) -> tuple[Motion | sp.Matrix, ...]:
    """The motions of the inverse transform: reversed order, negated values, constant transforms inverted."""
    return tuple(inverse_transform(sp.Matrix(m)) if isinstance(m, sp.MatrixBase) else Motion(m.kind, m.axis, -m.value)
                 for m in reversed(motions))


_ALIGNMENTS: dict[tuple[int, int, int], tuple[Motion, ...]] = {
    (0, 0, 1): (),
    (0, 0, -1): (Motion("R", "x", sp.pi),),
    (1, 0, 0): (Motion("R", "y", sp.pi / 2),),
    (-1, 0, 0): (Motion("R", "y", -sp.pi / 2),),
    (0, 1, 0): (Motion("R", "x", -sp.pi / 2),),
    (0, -1, 0): (Motion("R", "x", sp.pi / 2),),
}


def alignment(axis: Sequence[sp.Expr]) -> tuple[Motion | sp.Matrix, ...]:
    r"""A constant rotation :math:`A` whose z-axis is the unit vector ``axis``: :math:`A\,e_z = u`.

    For the coordinate axes it is one elementary rotation (:math:`I`, :math:`R_x(\pi)`, :math:`R_y(\pm\pi/2)`,
    :math:`R_x(\mp\pi/2)` for :math:`\pm z, \pm x, \pm y`); otherwise the 4 x 4 transform with rotation columns
    :math:`(e_1, u \times e_1, u)`, :math:`e_1 = e_z \times u / |e_z \times u|`.

    Examples
    --------
    >>> alignment((0, 1, 0))
    (Motion(kind='R', axis='x', value=-pi/2),)
    """
    u = sp.Matrix([sp.sympify(c) for c in axis])
    key = tuple(int(c) if c.is_Integer else 2 for c in u)
    if key in _ALIGNMENTS:
        return _ALIGNMENTS[key]  # type: ignore[index]
    e1 = sp.Matrix([-u[1], u[0], 0])
    e1 = (e1 / sp.sqrt(e1.dot(e1))).applyfunc(sp.radsimp)
    e2 = u.cross(e1).applyfunc(lambda e: sp.radsimp(sp.expand(e)))
    return (homogeneous(sp.Matrix.hstack(e1, e2, u), sp.zeros(3, 1)),)


def compose(motions: Iterable[Motion | sp.Matrix]) -> tuple[sp.Matrix, sp.Matrix]:
    r"""Multiply elementary motions (and constant 4 x 4 transforms) into :math:`(R, p)`.

    Consecutive rotations about the same axis are merged into one rotation by the summed angle, also across
    translations along that axis (which commute with them). Each translation is added as :math:`p \mathrel{+}= R\,t`
    with the rotation accumulated so far, so a position is a sum of columns of compact rotation matrices.

    Returns
    -------
    R : sympy.Matrix, shape (3, 3)
    p : sympy.Matrix, shape (3, 1)
    """
    return Composition().then(motions).result()


class Composition:
    """A product of motions in progress (see :func:`compose`), which can be continued without starting over.

    :meth:`then` returns a new composition and leaves this one as it was, so the transforms from one frame to every
    later frame are built one link each, sharing their partial products, instead of each from scratch (a 30-joint
    chain asks for hundreds of them).
    """

    __slots__ = ("pending", "position", "rotation")

    def __init__(self, rotation: sp.Matrix | None = None, position: sp.Matrix | None = None,
                 pending: Motion | None = None):
        self.rotation = sp.eye(3) if rotation is None else rotation
        self.position = sp.zeros(3, 1) if position is None else position
        self.pending = pending  # a rotation not yet multiplied into self.rotation, merged with the next if it can be

    def then(self, motions: Iterable[Motion | sp.Matrix]) -> Composition:
        """The product so far followed by ``motions`` (a new composition)."""
        rotation_matrix, position, pending = self.rotation, self.position, self.pending
        for motion in motions:
            if isinstance(motion, sp.MatrixBase):
                rotation_matrix, pending = _flush(rotation_matrix, pending), None
                position = position + rotation_matrix * motion[:3, 3]
                rotation_matrix = rotation_matrix * motion[:3, :3]
            elif motion.kind == "R":
                if pending is not None and pending.axis == motion.axis:
                    pending = Motion("R", motion.axis, pending.value + motion.value)
                else:
                    rotation_matrix, pending = _flush(rotation_matrix, pending), motion
            elif motion.value != 0:
                if pending is not None and pending.axis != motion.axis:
                    rotation_matrix, pending = _flush(rotation_matrix, pending), None
                # a translation along the pending rotation's own axis is not changed by that rotation
                unit = sp.zeros(3, 1)
                unit[_AXIS_INDEX[motion.axis]] = motion.value
                position = position + rotation_matrix * unit
        return Composition(rotation_matrix, position, pending)

    def named(self, name: Callable[[sp.Expr], sp.Expr]) -> Composition:
        """The same product with ``name`` applied to every entry of its rotation and position (nested chains)."""
        return Composition(self.rotation.applyfunc(name), self.position.applyfunc(name), self.pending)

    def result(self) -> tuple[sp.Matrix, sp.Matrix]:
        """:math:`(R, p)` of the product so far."""
        return _flush(self.rotation, self.pending), self.position


def _flush(rotation_matrix: sp.Matrix, pending: Motion | None) -> sp.Matrix:
    """``rotation_matrix`` times the pending rotation about one axis, if there is one (and it is not zero)."""
    if pending is not None and pending.value != 0:
        return rotation_matrix * rotation(pending.axis, pending.value)
    return rotation_matrix
