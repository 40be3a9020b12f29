r"""The dynamics in regressor form: :math:`\tau = Y(q, \dot q, \ddot q)\,\pi`, linear in the standard parameters.

Newton-Euler written about each link's origin is linear in the parameters of :mod:`.parameters` (:math:`m`,
:math:`h = m c`, :math:`I_o` about the origin of {k}). With the kinematic quantities of
:mod:`~symjac.analysis.dynamics.newton_euler` (:math:`\omega_k, \alpha_k` and :math:`a_k`, the acceleration of the
origin of {k} minus gravity, all in {k}):

.. math::
    F_k = m_k a_k + \alpha_k \times h_k + \omega_k \times (\omega_k \times h_k), \qquad
    N_k = I_{o,k}\,\alpha_k + \omega_k \times I_{o,k}\,\omega_k + h_k \times a_k

(force, and moment about the origin of {k}), then inward :math:`f_k = R' f_{k+1} + F_k`,
:math:`n_k = N_k + R' n_{k+1} + p' \times R' f_{k+1}` and :math:`\tau_k = z_a^T(n_k + r \times f_k)` (revolute) or
:math:`z_a^T f_k` (prismatic). Each parameter's column is this recursion with that parameter 1 and the others 0: the
outward pass runs once, and each link's ten unit contributions are carried inward separately, so column j of Y is
exactly the coefficient of :math:`\pi_j`. On an exact chain everything is a normal form in one polynomial ring
(:mod:`~symjac.analysis.dynamics.polynomial`), laid out at the end as the torques are; on a nested chain (generic
geometry) each entry is named as it is formed.

The drive adds to joint j's torque :math:`I_{a,j}\ddot\vartheta_j + F_{v,j}\dot\vartheta_j + F_{c,j}\,\mathrm{sign}(
\dot\vartheta_j) + F_{o,j}`; with ``smooth=eps`` the Coulomb term is :math:`F_{c,j}\tanh(\dot\vartheta_j/\varepsilon)`
(differentiable, for optimisation). A coupled robot's regressor is :math:`C^T Y` in the coordinates, as its torques.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.analysis.dynamics.bodies import exact_or_nested, joint_axis, laid_out, laid_out_from_first_basis
from symjac.analysis.dynamics.gravity import EARTH, Gravity, check_gravity
from symjac.analysis.identification.parameters import standard_parameters
from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, MemoKey, as_chain
from symjac.kinematics.coupling import coupling_matrix, in_coordinates
from symjac.model.robot import Robot
from symjac.progress import report
from symjac.symbolic.layout import nested_expr
from symjac.symbolic.nested import named
from symjac.symbolic.trigpoly import image_of, reduce_image

__all__ = ["Regressor", "regressor"]

Vector = tuple[Any, Any, Any]


@dataclass(frozen=True)
class Regressor:
    r"""The regressor :math:`Y` of a robot: :math:`\tau = Y\pi` exactly (module docstring).

    ``matrix`` is n_coordinates x len(parameters), in the coordinates, rates and accelerations of the robot and its
    geometric parameters (and gravity's magnitude); ``parameters`` are the columns' symbols
    (:func:`~symjac.analysis.identification.parameters.standard_parameters`), ``names`` their names.
    """

    matrix: sp.ImmutableMatrix
    parameters: tuple[sp.Symbol, ...]
    names: tuple[str, ...]
    robot: Robot
    gravity: Gravity


class _Vectors:
    """3-vectors over a ring with + and * (normal forms, or SymPy expressions), each entry reduced by ``tidy``."""

    def __init__(self, zero: Any, one: Any, tidy: Callable[[Any], Any]):
        self.zero, self.one, self.tidy = zero, one, tidy
        self.zeros: Vector = (zero, zero, zero)

    def reduce(self, value: Any) -> Any:
        return self.tidy(value) if value else self.zero

    def unit(self, axis: int) -> Vector:
        return (self.one if axis == 0 else self.zero, self.one if axis == 1 else self.zero,
                self.one if axis == 2 else self.zero)

    def cross(self, u: Vector, v: Vector) -> Vector:
        if not any(u) or not any(v):
            return self.zeros
        return (self.reduce(u[1] * v[2] - u[2] * v[1]), self.reduce(u[2] * v[0] - u[0] * v[2]),
                self.reduce(u[0] * v[1] - u[1] * v[0]))

    def times(self, R: Sequence[Sequence[Any]], v: Vector) -> Vector:
        if not any(v):
            return self.zeros
        rows = [sum((a * b for a, b in zip(row, v, strict=True) if a and b), self.zero) for row in R]
        return (self.reduce(rows[0]), self.reduce(rows[1]), self.reduce(rows[2]))

    def scaled(self, s: Any, v: Vector) -> Vector:
        if not s or not any(v):
            return self.zeros
        return (self.reduce(s * v[0]), self.reduce(s * v[1]), self.reduce(s * v[2]))

    def add(self, *vectors: Vector) -> Vector:
        return (self.reduce(sum((v[0] for v in vectors), self.zero)),
                self.reduce(sum((v[1] for v in vectors), self.zero)),
                self.reduce(sum((v[2] for v in vectors), self.zero)))

    def dot(self, u: Vector, v: Vector) -> Any:
        return self.reduce(sum((a * b for a, b in zip(u, v, strict=True) if a and b), self.zero))


_INERTIA_ENTRIES = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))  # XX XY XZ YY YZ ZZ


def _contributions(vectors: _Vectors, omega: Vector, alpha: Vector, a: Vector) -> list[tuple[Vector, Vector]]:
    """Link k's (F_k, N_k) for each of its ten parameters set to 1 and the others to 0 (module docstring)."""
    zero = vectors.zero

    def tensor(i: int, j: int, v: Vector) -> Vector:  # the unit tensor of entry (i, j), symmetric, times v
        out = [zero, zero, zero]
        out[i] = v[j]
        if i != j:
            out[j] = v[i]
        return (out[0], out[1], out[2])

    found = []
    for i, j in _INERTIA_ENTRIES:
        found.append((vectors.zeros, vectors.add(tensor(i, j, alpha), vectors.cross(omega, tensor(i, j, omega)))))
    for axis in range(3):
        e = vectors.unit(axis)
        F = vectors.add(vectors.cross(alpha, e), vectors.cross(omega, vectors.cross(omega, e)))
        found.append((F, vectors.cross(e, a)))
    found.append((a, vectors.zeros))
    return found


def _inputs(chain: Chain, gravity: Gravity) -> list[sp.Expr]:
    """What the recursion reads, flat: 2, -g_0, the rates and accelerations, then per link R, p, z_a, r (18)."""
    joints = chain.robot.joints
    inputs: list[sp.Expr] = [sp.Integer(2), *(-e for e in gravity.vector), *(j.rate for j in joints),
                             *(j.acceleration for j in joints)]
    for k in range(1, chain.n_joints + 1):
        axis = joint_axis(chain, k)
        inputs += [*chain.rotation(k, k - 1), *chain.transform(k - 1, k)[:3, 3], *axis.z, *axis.r]
    return [sp.sympify(e) for e in inputs]


def _columns(vectors: _Vectors, values: Sequence[Any], kinds: Sequence[bool]) -> list[list[Any]]:
    """Y of a chain of joints (no coupling), ``[joint][column]``, ten columns per link, from :func:`_inputs`' values."""
    n = len(kinds)
    two, a, qd, qdd = values[0], tuple(values[1:4]), values[4:4 + n], values[4 + n:4 + 2 * n]
    links = []
    for k in range(n):
        c = values[4 + 2 * n + 18 * k:4 + 2 * n + 18 * (k + 1)]
        links.append(([c[0:3], c[3:6], c[6:9]], tuple(c[9:12]), tuple(c[12:15]), tuple(c[15:18]), kinds[k]))
    omega, alpha = vectors.zeros, vectors.zeros
    parts = []
    for k, (R, p, z, r, revolute) in enumerate(links):
        report(f"Regressor, outward: link {k + 1} of {n}")
        turn = vectors.scaled(qd[k], z) if revolute else vectors.zeros
        turning = vectors.scaled(qdd[k], z) if revolute else vectors.zeros
        slide = vectors.zeros if revolute else vectors.scaled(qd[k], z)
        sliding = vectors.zeros if revolute else vectors.scaled(qdd[k], z)
        omega_rotated = vectors.times(R, omega)
        a = vectors.times(R, vectors.add(a, vectors.cross(alpha, p), vectors.cross(omega, vectors.cross(omega, p))))
        u = vectors.add(vectors.cross(turn, r), slide)
        a = vectors.add(a, vectors.cross(turning, r), vectors.cross(turn, vectors.cross(turn, r)), sliding,
                        vectors.scaled(two, vectors.cross(omega_rotated, u)))
        alpha = vectors.add(vectors.times(R, alpha), vectors.cross(omega_rotated, turn), turning)
        omega = vectors.add(omega_rotated, turn)
        parts.append(_contributions(vectors, omega, alpha, a))
    Y = [[vectors.zero] * (10 * n) for _ in range(n)]
    carried: dict[int, tuple[Vector, Vector]] = {}  # column -> (f, n) at the current link
    for k in range(n - 1, -1, -1):
        report(f"Regressor, inward: link {k + 1} of {n}")
        R, p, z, r, revolute = links[k]
        if k < n - 1:
            R_next, p_next = links[k + 1][0], links[k + 1][1]
            R_back = [[R_next[j][i] for j in range(3)] for i in range(3)]  # (^{k+1}_kR)^T = ^k_{k+1}R
            for column, (f, m) in carried.items():
                f_rotated = vectors.times(R_back, f)
                carried[column] = (f_rotated, vectors.add(vectors.times(R_back, m), vectors.cross(p_next, f_rotated)))
        for index, (F, N) in enumerate(parts[k]):
            carried[10 * k + index] = (F, N)
        for column, (f, m) in carried.items():
            Y[k][column] = vectors.dot(z, vectors.add(m, vectors.cross(r, f)) if revolute else f)
    return Y


def _link_columns(chain: Chain, gravity: Gravity) -> sp.Matrix:
    """The link parameters' columns of Y for a chain of joints, laid out as the torques are."""
    n = chain.n_joints
    revolute = [joint.is_revolute for joint in chain.robot.joints]
    inputs = _inputs(chain, gravity)
    if chain.nested:
        Y = _columns(_Vectors(sp.S.Zero, sp.S.One, named), inputs, revolute)
        return sp.Matrix(laid_out(chain, sp.Matrix(Y), True))
    image, polys = image_of(inputs, chain.angle_basis(0))
    ring = image.ring_and_gens[0]
    Y = _columns(_Vectors(ring.zero, ring.one, lambda poly: reduce_image(poly, image)), polys, revolute)
    report("Regressor: layout")
    entries = [nested_expr(poly, image) if poly else sp.S.Zero for row in Y for poly in row]
    return sp.Matrix(n, 10 * n, list(laid_out_from_first_basis(chain, entries)))


def _drive_columns(chain: Chain, asked: Sequence[bool], smooth: sp.Expr | None) -> list[sp.Matrix]:
    """Per joint j, the columns of its drive parameters asked for (Ia, Fv, Fc, Fo): nonzero in row j only."""
    joints = chain.robot.joints
    columns = []
    for j, joint in enumerate(joints):
        coulomb = sp.sign(joint.rate) if smooth is None else sp.tanh(joint.rate / smooth)
        for wanted, entry in zip(asked, (joint.acceleration, joint.rate, coulomb, sp.S.One), strict=True):
            if wanted:
                column = sp.zeros(len(joints), 1)
                column[j] = entry
                columns.append(column)
    return columns


def regressor(robot: Robot | Chain, gravity: Gravity = EARTH, *, armature: bool = False, viscous: bool = False,
              coulomb: bool = False, offset: bool = False, smooth: object = None) -> Regressor:
    r"""The regressor :math:`Y(q, \dot q, \ddot q)` with :math:`\tau = Y\pi` exactly (module docstring).

    Parameters
    ----------
    robot : Robot or Chain
        Any arm: no inertial data are needed (the parameters are the unknowns).
    gravity : Gravity
        Default :data:`~symjac.analysis.dynamics.gravity.EARTH`: :math:`g` along :math:`-z_0`.
    armature, viscous, coulomb, offset : bool
        Add each joint's ``Ia{j}`` (:math:`\ddot\vartheta_j`), ``Fv{j}`` (:math:`\dot\vartheta_j`), ``Fc{j}``
        (:math:`\mathrm{sign}\,\dot\vartheta_j`) and ``Fo{j}`` (1) columns after its link's ten.
    smooth : number or symbol, optional
        :math:`\varepsilon > 0`: the Coulomb column is :math:`\tanh(\dot\vartheta_j/\varepsilon)` instead of the sign.

    Returns
    -------
    Regressor
        ``matrix`` n_coordinates x len(parameters), columns in the order of
        :func:`~symjac.analysis.identification.parameters.standard_parameters`.

    Examples
    --------
    >>> from symjac import load_robot
    >>> Y = regressor(load_robot("planar2r"))
    >>> Y.names[:10]
    ('XX1', 'XY1', 'XZ1', 'YY1', 'YZ1', 'ZZ1', 'MX1', 'MY1', 'MZ1', 'M1')
    >>> Y.matrix[1, Y.names.index("ZZ2")]  # joint 2's torque per unit ZZ2 (inertia about the origin of {2})
    thetaddot1 + thetaddot2
    >>> Y.matrix[1, Y.names.index("MX2")]  # frame {2} sits at the tip (standard DH): its origin moves
    L1*(thetaddot1*cos(theta2) + thetadot1**2*sin(theta2)) + L2*(2*thetaddot1 + 2*thetaddot2)
    """
    chain = as_chain(robot)
    check_gravity(chain.robot, gravity)
    asked = (armature, viscous, coulomb, offset)
    epsilon: sp.Expr | None = None
    if smooth is not None:  # a float such as 0.01 becomes the exact 1/100, as gravity's magnitude does
        epsilon = sp.nsimplify(smooth, rational=True) if isinstance(smooth, float) else sp.sympify(smooth)
    if epsilon is not None and (not coulomb or epsilon.is_positive is False):  # a plain symbol may be positive
        raise ArgumentError(f"smooth is the epsilon > 0 of the smooth Coulomb friction tanh(qdot/epsilon), given with "
                            f"coulomb=True; got smooth={smooth!r} with coulomb={coulomb}")
    parameters = standard_parameters(chain, armature=armature, viscous=viscous, coulomb=coulomb, offset=offset)

    def compute(chain: Chain) -> Regressor:
        joints = chain.joint_chain
        links = _link_columns(joints, gravity)
        drives = _drive_columns(joints, asked, epsilon)
        per_joint = len(drives) // joints.n_joints
        columns = []
        for j in range(joints.n_joints):
            columns += [links[:, 10 * j + i] for i in range(10)] + drives[per_joint * j:per_joint * (j + 1)]
        Y = sp.Matrix.hstack(*columns)
        if chain.robot.coupling is not None:
            Y = laid_out(chain, coupling_matrix(chain).T * in_coordinates(chain, Y), True)
        return Regressor(sp.ImmutableMatrix(Y), parameters, tuple(p.name for p in parameters), chain.robot, gravity)

    key = MemoKey(regressor, (gravity, *asked, epsilon))
    return chain.memo(key, lambda: exact_or_nested(chain, compute))
