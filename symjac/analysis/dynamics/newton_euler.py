r"""Inverse dynamics by the recursive Newton-Euler algorithm, in the link frames, every step kept.

**Outward** (base to tip), for link k in its frame {k}, with :math:`R = {}^k_{k-1}R`, :math:`p = {}^{k-1}p_k`, the
joint axis :math:`z_a` and offset :math:`r` of :mod:`~symjac.analysis.dynamics.bodies`, :math:`\omega' =
R\,\omega_{k-1}`, and :math:`\dot\theta_k, \ddot\theta_k` zero for a prismatic joint, :math:`\dot d_k, \ddot d_k`
zero for a revolute one:

.. math::
    \omega_k &= \omega' + \dot\theta_k z_a, \qquad
    \alpha_k = R\,\alpha_{k-1} + \omega' \times \dot\theta_k z_a + \ddot\theta_k z_a \\
    a_k &= R\,(a_{k-1} + \alpha_{k-1} \times p + \omega_{k-1} \times (\omega_{k-1} \times p))
        + \ddot\theta_k z_a \times r + \dot\theta_k z_a \times (\dot\theta_k z_a \times r) + \ddot d_k z_a
        + 2\,\omega' \times (\dot\theta_k z_a \times r + \dot d_k z_a) \\
    a_{ck} &= a_k + \alpha_k \times c_k + \omega_k \times (\omega_k \times c_k), \qquad
    F_k = m_k a_{ck}, \qquad N_k = I_k \alpha_k + \omega_k \times I_k \omega_k

starting from :math:`\omega_0 = \alpha_0 = 0` and :math:`a_0 = -g_0` (the base accelerating upwards stands for
gravity, :mod:`~symjac.analysis.dynamics.gravity`; so every :math:`a_k` and :math:`a_{ck}` is the acceleration minus
gravity, what an accelerometer fixed there would read). :math:`a_k` is the acceleration of the origin of {k} and
:math:`a_{ck}` that of the centre of mass :math:`c_k` (given in {k}); :math:`I_k` is the tensor about the centre.

**Inward** (tip to base), with :math:`R' = {}^k_{k+1}R` and :math:`p' = {}^kp_{k+1}`, the force :math:`f_k` and
moment :math:`n_k` (about the origin of {k}) that link k-1 exerts on link k:

.. math::
    f_k = R' f_{k+1} + F_k, \qquad n_k = N_k + R' n_{k+1} + c_k \times F_k + p' \times R' f_{k+1}, \qquad
    \tau_k = z_a^T (n_k + r \times f_k)\ \text{(revolute)}, \quad \tau_k = z_a^T f_k\ \text{(prismatic)}.

With :math:`r = 0` (modified DH, general joints) these are Craig's (6.45)-(6.53). Every quantity is laid out in
compact form as it is formed (:func:`~symjac.analysis.dynamics.bodies.tidy`), so terms that vanish never reach the
next link; the torques come out in textbook form.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import sympy as sp

from symjac.analysis.dynamics.bodies import (
    exact_or_nested,
    joint_axis,
    laid_out,
    laid_out_from_first_basis,
    link_bodies,
    tidy,
)
from symjac.analysis.dynamics.drives import FrictionLaw, armature_matrix, drive_torques, has_drives
from symjac.analysis.dynamics.gravity import EARTH, NO_GRAVITY, Gravity, check_gravity
from symjac.analysis.dynamics.polynomial import PolynomialSteps, polynomial_recursion
from symjac.kinematics.chain import Chain, MemoKey, as_chain
from symjac.kinematics.coupling import coupling_matrix, in_coordinates
from symjac.model.robot import Robot
from symjac.progress import report

__all__ = ["STEP_NAMES", "LinkStep", "NewtonEuler", "newton_euler", "newton_euler_mass_matrix", "recursion"]

STEP_NAMES: tuple[str, ...] = ("omega", "alpha", "a", "a_c", "F", "N", "f", "n")
"""The quantities of one link's step, in the order they are formed (names as :meth:`LinkStep.named` gives them)."""


@dataclass(frozen=True)
class LinkStep:
    r"""One link's quantities, each 3 x 1 in the link's frame {k} (module docstring), and its joint's torque."""

    link: int
    omega: sp.ImmutableMatrix
    alpha: sp.ImmutableMatrix
    a: sp.ImmutableMatrix
    a_c: sp.ImmutableMatrix
    F: sp.ImmutableMatrix
    N: sp.ImmutableMatrix
    f: sp.ImmutableMatrix
    n: sp.ImmutableMatrix
    tau: sp.Expr

    def moved(self, move: Callable[[sp.ImmutableMatrix], sp.ImmutableMatrix]) -> LinkStep:
        """The same step with ``move`` applied to every quantity (to write it in a coupled robot's coordinates)."""
        values = {name: move(getattr(self, name)) for name in STEP_NAMES}
        return dataclasses.replace(self, tau=move(sp.ImmutableMatrix([self.tau]))[0], **values)

    def named(self) -> dict[str, sp.ImmutableMatrix | sp.Expr]:
        """The quantities by name with the link number: ``omega_2``, ``alpha_2``, ..., ``n_2``, ``tau_2``."""
        values = {f"{name}_{self.link}": getattr(self, name) for name in STEP_NAMES}
        values[f"tau_{self.link}"] = self.tau
        return values


@dataclass(frozen=True)
class NewtonEuler:
    r"""The whole recursion: one :class:`LinkStep` per link (base to tip) and the torques :math:`\tau` (n x 1).

    For a robot with coupled joints the steps are written in the coordinates (:math:`\vartheta = \vartheta(q)`,
    :math:`\dot\vartheta = C\dot q`, ...) and ``torques`` are the generalised forces :math:`C^T\tau` (one per
    coordinate); ``joint_torques`` are always those of the joints. The steps are laid out when first asked for
    (``layout``): the torques alone do not need them.
    """

    joint_torques: sp.ImmutableMatrix
    torques: sp.ImmutableMatrix
    gravity: Gravity
    layout: Callable[[], tuple[LinkStep, ...]] = field(repr=False, compare=False)

    @cached_property
    def steps(self) -> tuple[LinkStep, ...]:
        """One :class:`LinkStep` per link, base to tip."""
        return self.layout()

    def named(self) -> list[dict[str, sp.ImmutableMatrix | sp.Expr]]:
        """Per link, base to tip, its named quantities (:meth:`LinkStep.named`): what ``--steps`` prints."""
        return [step.named() for step in self.steps]


def _cross(u: sp.MatrixBase, v: sp.MatrixBase) -> sp.Matrix:
    """``u x v``, with nothing built when either is zero (most are, in the first links)."""
    if u.is_zero_matrix or v.is_zero_matrix:
        return sp.zeros(3, 1)
    return sp.Matrix(u).cross(sp.Matrix(v))


def recursion(chain: Chain, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr],
              gravity: Gravity = EARTH, *, simplify: bool = True) -> tuple[LinkStep, ...]:
    r"""Run the recursion on a chain of joints (no coupling) for the given joint rates and accelerations.

    ``rates`` and ``accelerations`` are one expression per joint (symbols for inverse dynamics; zeros and unit
    values for the mass matrix's columns). Returns the steps, base to tip, with each joint's torque. Laid out
    (``simplify``), the recursion runs on normal forms (:mod:`~symjac.analysis.dynamics.polynomial`) and each step is
    laid out in its frame's angle basis at the end, as :func:`~symjac.analysis.dynamics.bodies.tidy` lays it out.
    """
    if simplify and not chain.nested:
        return _laid_out_steps(chain, polynomial_recursion(chain, rates, accelerations, gravity.vector))
    n = chain.n_joints
    bodies = link_bodies(chain)
    omega, alpha = sp.zeros(3, 1), sp.zeros(3, 1)
    a = -sp.Matrix(gravity.vector)
    outward = []
    for k in range(1, n + 1):
        report(f"Newton-Euler, outward: link {k} of {n}")
        axis = joint_axis(chain, k)
        R, p = chain.rotation(k, k - 1), chain.transform(k - 1, k)[:3, 3]
        turn = axis.z * rates[k - 1] if axis.revolute else sp.zeros(3, 1)
        turning = axis.z * accelerations[k - 1] if axis.revolute else sp.zeros(3, 1)
        slide = sp.zeros(3, 1) if axis.revolute else axis.z * rates[k - 1]
        sliding = sp.zeros(3, 1) if axis.revolute else axis.z * accelerations[k - 1]
        omega_rotated = R * omega
        a = R * (a + _cross(alpha, p) + _cross(omega, _cross(omega, p)))
        u = _cross(turn, axis.r) + slide
        a = a + _cross(turning, axis.r) + _cross(turn, _cross(turn, axis.r)) + sliding + 2 * _cross(omega_rotated, u)
        a = tidy(chain, a, k, simplify)
        alpha = tidy(chain, R * alpha + _cross(omega_rotated, turn) + turning, k, simplify)
        omega = tidy(chain, omega_rotated + turn, k, simplify)
        body = bodies[k - 1]
        c, inertia = sp.Matrix(body.com), sp.Matrix(body.inertia)
        a_c = tidy(chain, a + _cross(alpha, c) + _cross(omega, _cross(omega, c)), k, simplify)
        F = tidy(chain, body.mass * a_c, k, simplify)
        N = tidy(chain, inertia * alpha + _cross(omega, inertia * omega), k, simplify)
        outward.append((k, axis, omega, alpha, a, a_c, F, N, c))
    steps: list[LinkStep] = []
    f, m = sp.zeros(3, 1), sp.zeros(3, 1)
    for k, axis, omega, alpha, a, a_c, F, N, c in reversed(outward):
        report(f"Newton-Euler, inward: link {k} of {n}")
        if k < n:
            R_next, p_next = chain.rotation(k, k + 1), chain.transform(k, k + 1)[:3, 3]
            f_rotated = R_next * f
            m = N + R_next * m + _cross(c, F) + _cross(p_next, f_rotated)
            f = f_rotated + F
        else:
            f, m = sp.Matrix(F), N + _cross(c, F)
        f, m = tidy(chain, f, k, simplify), tidy(chain, m, k, simplify)
        about_axis = m + _cross(axis.r, f) if axis.revolute else f
        tau = (axis.z.T * about_axis)[0]  # laid out with the others at the end
        steps.append(LinkStep(k, sp.ImmutableMatrix(omega), sp.ImmutableMatrix(alpha), sp.ImmutableMatrix(a),
                              sp.ImmutableMatrix(a_c), sp.ImmutableMatrix(F), sp.ImmutableMatrix(N),
                              sp.ImmutableMatrix(f), sp.ImmutableMatrix(m), tau))
    return tuple(reversed(steps))


def _laid_out_steps(chain: Chain, found: PolynomialSteps) -> tuple[LinkStep, ...]:
    """The steps of a recursion on normal forms, each quantity laid out in its own frame's angle basis."""
    steps = []
    for k in range(1, chain.n_joints + 1):
        values = {name: tidy(chain, found.vector(k, name), k, True) for name in STEP_NAMES}
        steps.append(LinkStep(k, tau=found.expression(found.torques[k - 1]), **values))
    return tuple(steps)


def _torques(chain: Chain, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr], gravity: Gravity,
             simplify: bool, final: bool = True) -> tuple[sp.ImmutableMatrix, Callable[[], tuple[LinkStep, ...]]]:
    """The joint torques of the recursion laid out as results (:func:`laid_out`), and the way to its steps.

    On normal forms the first layout is already in frame {0}'s angle basis, the first of the result bases
    (:func:`~symjac.analysis.dynamics.bodies.laid_out_from_first_basis`). Not ``final``: as the recursion leaves
    them (a caller lays out a larger result made of them).
    """
    if simplify and not chain.nested:
        found = polynomial_recursion(chain, rates, accelerations, gravity.vector)
        entries = [found.expression(p) for p in found.torques]
        tau = laid_out_from_first_basis(chain, entries) if final else sp.ImmutableMatrix(entries)
        return tau, lambda: _laid_out_steps(chain, found)
    steps = recursion(chain, rates, accelerations, gravity, simplify=simplify)
    raw = sp.Matrix([step.tau for step in steps])
    return laid_out(chain, raw, simplify) if final else sp.ImmutableMatrix(raw), lambda: steps


def newton_euler(robot: Robot | Chain, gravity: Gravity = EARTH, *, simplify: bool = True,
                 friction: FrictionLaw = "sign", eps: sp.Expr | float | None = None) -> NewtonEuler:
    r"""Inverse dynamics :math:`\tau(q, \dot q, \ddot q)` by recursive Newton-Euler (module docstring).

    Where the robot has drive data (:attr:`Robot.drives <symjac.model.robot.Robot>`) the torques include the motors'
    armature and the joints' friction (:mod:`~symjac.analysis.dynamics.drives`): ``friction`` ``"sign"`` (default)
    or ``"smooth"`` (:math:`F_c\tanh(\dot q/\varepsilon)`, with ``eps``). Each step's ``tau`` is then its joint's
    whole torque, the drive's share included.

    Parameters
    ----------
    robot : Robot or Chain
        With inertial data on every link (:attr:`Robot.inertials <symjac.model.robot.Robot>`; symbolic ones from
        :func:`~symjac.model.inertial_parameters.with_symbolic_inertials`).
    gravity : Gravity
        Default :data:`~symjac.analysis.dynamics.gravity.EARTH`: :math:`g` along :math:`-z_0`.
    simplify : bool
        Lay every step out in compact form as it is formed (default); ``False`` keeps the raw products.

    Returns
    -------
    NewtonEuler
        ``torques`` (n_coordinates x 1) in the joint rates ``thetadot{i}``/``ddot{i}`` and accelerations
        ``thetaddot{i}``/``dddot{i}`` (those of the coordinates for a coupled robot), and the steps.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.model.inertia import Inertial
    >>> import dataclasses
    >>> from symjac.analysis.dynamics.gravity import GRAVITY_SYMBOL, Gravity
    >>> m = sp.Symbol("m", positive=True)
    >>> arm = dataclasses.replace(load_robot("planar2r"), inertials=(Inertial(m), Inertial(m)))  # masses at the ends
    >>> tau = newton_euler(arm, Gravity(direction=(0, -1, 0))).torques  # gravity along -y, in the arm's plane
    >>> tau[1].subs(GRAVITY_SYMBOL, 0)
    L2*m*(L1*(thetaddot1*cos(theta2) + thetadot1**2*sin(theta2)) + L2*(thetaddot1 + thetaddot2))
    >>> sp.expand(tau[1]).coeff(GRAVITY_SYMBOL)
    L2*m*cos(theta1 + theta2)
    """
    chain = as_chain(robot)
    check_gravity(chain.robot, gravity)

    def compute(chain: Chain) -> NewtonEuler:
        joints = chain.joint_chain
        model = joints.robot
        # each torque in the shortest of frame {0}'s angles (c_12 rather than c_1 c_2 - s_1 s_2), in its step too
        tau, layout = _torques(joints, [j.rate for j in model.joints], [j.acceleration for j in model.joints],
                               gravity, simplify)
        if has_drives(model):  # joint space: the coupling below moves them with the rest
            tau = sp.ImmutableMatrix(tau + drive_torques(model, friction, eps))

        def steps() -> tuple[LinkStep, ...]:
            return tuple(dataclasses.replace(step, tau=tau[k]) for k, step in enumerate(layout()))

        if chain.robot.coupling is None:
            return NewtonEuler(tau, tau, gravity, steps)

        def moved() -> tuple[LinkStep, ...]:
            return tuple(s.moved(lambda value: in_coordinates(chain, value)) for s in steps())

        tau_joints = in_coordinates(chain, sp.Matrix(tau))
        tau_q = laid_out(chain, coupling_matrix(chain).T * tau_joints, simplify)
        return NewtonEuler(sp.ImmutableMatrix(tau_joints), tau_q, gravity, moved)

    key = MemoKey(newton_euler, (gravity, simplify) if friction == "sign" else (gravity, simplify, friction, eps))
    return chain.memo(key, lambda: exact_or_nested(chain, compute))


def newton_euler_mass_matrix(robot: Robot | Chain, *, simplify: bool = True) -> sp.ImmutableMatrix:
    r"""The mass matrix by Newton-Euler: column j is :math:`\tau` at :math:`\dot q = 0,\ \ddot q = e_j`, no gravity.

    An independent route to :func:`~symjac.analysis.dynamics.lagrange.mass_matrix` (the two agree exactly); for a
    coupled robot :math:`C^T M C`, in the coordinates. The drives' armature is on the joints' diagonal.
    """
    chain = as_chain(robot)

    def compute(chain: Chain) -> sp.ImmutableMatrix:
        joints = chain.joint_chain
        n = joints.n_joints
        columns = []
        for j in range(n):
            unit = [sp.S.One if i == j else sp.S.Zero for i in range(n)]
            columns.append(list(_torques(joints, [sp.S.Zero] * n, unit, NO_GRAVITY, simplify, final=False)[0]))
        M = sp.Matrix(columns).T + armature_matrix(joints)
        if chain.robot.coupling is not None:
            C = coupling_matrix(chain)
            M = C.T * in_coordinates(chain, M) * C
        return laid_out(chain, M, simplify)

    key = MemoKey(newton_euler_mass_matrix, (simplify,))
    return chain.memo(key, lambda: exact_or_nested(chain, compute))
