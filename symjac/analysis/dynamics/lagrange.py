r"""The Lagrangian route: the mass matrix from the link Jacobians, energies, Christoffel symbols, Euler-Lagrange.

For link i with mass :math:`m_i`, centre :math:`c_i` and tensor :math:`I_i` about it (frame {i}), and the Jacobian
:math:`{}^iJ_{ci} = [J_{vi}; J_{\omega i}]` of its centre expressed in {i}:

.. math::
    M(q) = \sum_i m_i J_{vi}^T J_{vi} + J_{\omega i}^T I_i J_{\omega i}

(the same as :math:`\sum m_i J_{vi}^T J_{vi} + J_{\omega i}^T R_i I_i R_i^T J_{\omega i}` with both Jacobians in
{0}, since :math:`{}^0J_{\omega i} = R_i\,{}^iJ_{\omega i}`). The Coriolis matrix comes from the Christoffel symbols,

.. math::
    C_{kj} = \sum_i \tfrac12 \left(\frac{\partial M_{kj}}{\partial q_i} + \frac{\partial M_{ki}}{\partial q_j}
        - \frac{\partial M_{ij}}{\partial q_k}\right)\dot q_i,

so that :math:`\dot M - 2C` is skew-symmetric, and :math:`\tau = M\ddot q + C\dot q + g(q)` with
:math:`g = \partial V/\partial q`. The energies are computed from the link velocities (velocity propagation), not
from M: :math:`T = \sum_i \tfrac12 m_i v_{ci}^T v_{ci} + \tfrac12 \omega_i^T I_i \omega_i`,
:math:`V = -\sum_i m_i g_0^T p_{ci}` (:math:`p_{ci}` the centre in {0}); the Euler-Lagrange equations
:math:`\tau_k = \frac{d}{dt}\frac{\partial L}{\partial \dot q_k} - \frac{\partial L}{\partial q_k}`,
:math:`L = T - V`, are then a third route to the torques. Everything is in the robot's coordinates (for coupled
joints :math:`C^T M C`, ...: the Jacobians and energies are written in them). Drive data
(:mod:`~symjac.analysis.dynamics.drives`) add the armature to M and the rotors' energy to T.
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from symjac.analysis.dynamics.bodies import exact_or_nested, laid_out, laid_out_from_first_basis, link_bodies
from symjac.analysis.dynamics.drives import FrictionLaw, armature_matrix, drive_energy, friction_torques, has_drives
from symjac.analysis.dynamics.gravity import EARTH, Gravity, check_gravity
from symjac.analysis.dynamics.polynomial import christoffel_coriolis
from symjac.kinematics.chain import Chain, MemoKey, as_chain
from symjac.kinematics.coupling import in_coordinates
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.propagation import velocity_propagation
from symjac.model.robot import Robot
from symjac.progress import report
from symjac.symbolic.nested import has_intermediates, named

__all__ = [
    "coriolis_matrix",
    "euler_lagrange",
    "gravity_torques",
    "kinetic_energy",
    "mass_matrix",
    "potential_energy",
    "time_derivative",
]


def _memo(chain: Chain, function: Callable[..., object], arguments: tuple,
          compute: Callable[[Chain], sp.Expr]) -> sp.Expr:
    """``compute(chain)`` kept in the chain; from the nested twin when the compact form is too large to write out."""
    return chain.memo(MemoKey(function, arguments), lambda: exact_or_nested(chain, compute))


def mass_matrix(robot: Robot | Chain, *, simplify: bool = True) -> sp.ImmutableMatrix:
    r"""The mass matrix :math:`M(q)` from the Jacobians of the link centres (module docstring).

    Parameters
    ----------
    robot : Robot or Chain
        With inertial data on every link (an error names the links without).
    simplify : bool
        Lay the result out in compact form (default); ``False`` keeps the raw products.

    Returns
    -------
    M : sympy.ImmutableMatrix, shape (n, n)
        Symmetric, in the coordinates ``robot.q`` (:math:`C^T M C` for coupled joints).

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.model.inertia import Inertial
    >>> m = sp.Symbol("m", positive=True)
    >>> import dataclasses
    >>> arm = dataclasses.replace(load_robot("planar2r"), inertials=(Inertial(m), Inertial(m)))  # masses at the ends
    >>> mass_matrix(arm)[0, 0]
    m*(L1*(2*L1 + 2*L2*cos(theta2)) + L2**2)
    """
    chain = as_chain(robot)

    def compute(chain: Chain) -> sp.ImmutableMatrix:
        n = chain.robot.n_coordinates
        M = sp.zeros(n, n)
        for i, body in enumerate(link_bodies(chain), start=1):
            report(f"mass matrix: link {i} of {chain.n_joints}")
            J = jacobian(chain, frame=i, point=body.com, link=i, simplify=simplify)
            J_v, J_w = J[:3, :], J[3:, :]
            M += body.mass * J_v.T * J_v + J_w.T * sp.Matrix(body.inertia) * J_w
            if chain.nested:  # each link's sum named: the next link adds to names
                M = M.applyfunc(named)
        return laid_out(chain, M + armature_matrix(chain), simplify)

    return _memo(chain, mass_matrix, (simplify,), compute)  # type: ignore[return-value]


def coriolis_matrix(robot: Robot | Chain, *, simplify: bool = True) -> sp.ImmutableMatrix:
    r"""The Coriolis matrix :math:`C(q, \dot q)` from the Christoffel symbols of :func:`mass_matrix`.

    Returns
    -------
    C : sympy.ImmutableMatrix, shape (n, n)
        Linear in the rates ``robot.coordinate_rates``; :math:`\dot M - 2C` is skew-symmetric and
        :math:`C\dot q` the Coriolis and centrifugal torques.
    """
    chain = as_chain(robot)

    def compute(chain: Chain) -> sp.ImmutableMatrix:
        M = mass_matrix(chain, simplify=simplify)
        q, qdot = chain.robot.q, chain.robot.coordinate_rates
        n = len(q)
        if simplify and not chain.nested and chain.robot.coupling is None and not has_intermediates(M):
            # on normal forms: no tree is differentiated, and the first result basis is laid out only once
            entries = christoffel_coriolis(chain, M, q, qdot)
            if entries is not None:
                return sp.ImmutableMatrix(n, n, list(laid_out_from_first_basis(chain, entries)))
        dM = [M.diff(variable) for variable in q]  # dM[i][k, j] = dM_kj / dq_i
        C = sp.Matrix(n, n, lambda k, j: sp.Add(*[
            sp.Rational(1, 2) * (dM[i][k, j] + dM[j][k, i] - dM[k][i, j]) * qdot[i] for i in range(n)]))
        return laid_out(chain, C, simplify)

    return _memo(chain, coriolis_matrix, (simplify,), compute)  # type: ignore[return-value]


def potential_energy(robot: Robot | Chain, gravity: Gravity = EARTH, *, simplify: bool = True) -> sp.Expr:
    r"""The potential energy :math:`V(q) = -\sum_i m_i\,g_0^T p_{ci}` (zero at the origin of {0})."""
    chain = as_chain(robot)
    check_gravity(chain.robot, gravity)

    def compute(chain: Chain) -> sp.Expr:
        joints = chain.joint_chain
        V = sp.S.Zero
        for i, body in enumerate(link_bodies(chain), start=1):
            p_c = joints.transform(0, i) * sp.Matrix([*body.com, 1])
            V -= body.mass * (sp.Matrix(gravity.vector).T * p_c[:3, :])[0]
        return laid_out(chain, in_coordinates(chain, sp.Matrix([V])), simplify)[0]

    return _memo(chain, potential_energy, (gravity, simplify), compute)


def gravity_torques(robot: Robot | Chain, gravity: Gravity = EARTH, *, simplify: bool = True) -> sp.ImmutableMatrix:
    r"""The gravity vector :math:`g(q) = \partial V / \partial q`: the torques that hold the arm still.

    Returns
    -------
    g : sympy.ImmutableMatrix, shape (n, 1)
        In ``robot.q`` and gravity's magnitude (the symbol ``g`` unless ``gravity`` gives a number).
    """
    chain = as_chain(robot)

    def compute(chain: Chain) -> sp.ImmutableMatrix:
        V = potential_energy(chain, gravity, simplify=False)
        return laid_out(chain, sp.Matrix([V]).jacobian(sp.Matrix(chain.robot.q)).T, simplify)

    return _memo(chain, gravity_torques, (gravity, simplify), compute)  # type: ignore[return-value]


def kinetic_energy(robot: Robot | Chain, *, simplify: bool = True) -> sp.Expr:
    r"""The kinetic energy :math:`T(q, \dot q)` from the link velocities (velocity propagation, each link's frame)."""
    chain = as_chain(robot)

    def compute(chain: Chain) -> sp.Expr:
        T = sp.S.Zero
        for i, body in enumerate(link_bodies(chain), start=1):
            report(f"kinetic energy: link {i} of {chain.n_joints}")
            *_, (_, omega, v) = velocity_propagation(chain, point=body.com, link=i, simplify=simplify).velocities()
            T += body.mass * (v.T * v)[0] / 2 + (omega.T * sp.Matrix(body.inertia) * omega)[0] / 2
        return laid_out(chain, sp.Matrix([T + drive_energy(chain)]), simplify)[0]

    return _memo(chain, kinetic_energy, (simplify,), compute)


def time_derivative(expr: sp.Expr, robot: Robot | Chain) -> sp.Expr:
    r"""The time derivative of an expression in :math:`q, \dot q` along the motion.

    .. math::
        \frac{d}{dt} = \sum_j \dot q_j \frac{\partial}{\partial q_j} + \ddot q_j \frac{\partial}{\partial \dot q_j}
    """
    model = as_chain(robot).robot
    return sp.Add(*[expr.diff(q) * qd for q, qd in zip(model.q, model.coordinate_rates, strict=True)],
                  *[expr.diff(qd) * qdd for qd, qdd in zip(model.coordinate_rates, model.coordinate_accelerations,
                                                           strict=True)])


def euler_lagrange(robot: Robot | Chain, gravity: Gravity = EARTH, *, simplify: bool = True,
                   friction: FrictionLaw = "sign", eps: sp.Expr | float | None = None) -> sp.ImmutableMatrix:
    r"""The torques by the Euler-Lagrange equations of :math:`L = T - V` (module docstring), n x 1.

    The rotors' energy is in :math:`T` (:func:`~symjac.analysis.dynamics.lagrange.kinetic_energy`); the joints'
    friction, which no potential gives, is added as a generalised force
    (:func:`~symjac.analysis.dynamics.drives.friction_torques` with ``friction`` and ``eps``, as
    :func:`~symjac.analysis.dynamics.newton_euler.newton_euler` takes them).

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.model.inertia import Inertial
    >>> m = sp.Symbol("m", positive=True)
    >>> import dataclasses
    >>> arm = dataclasses.replace(load_robot("planar2r"), inertials=(Inertial(m), Inertial(m)))
    >>> euler_lagrange(arm)[1]
    L2*m*(L1*(thetaddot1*cos(theta2) + thetadot1**2*sin(theta2)) + L2*(thetaddot1 + thetaddot2))
    """
    chain = as_chain(robot)
    check_gravity(chain.robot, gravity)

    def compute(chain: Chain) -> sp.ImmutableMatrix:
        model = chain.robot
        L = kinetic_energy(chain, simplify=simplify) - potential_energy(chain, gravity, simplify=simplify)
        tau = sp.Matrix([time_derivative(L.diff(qd), chain) - L.diff(q)
                         for q, qd in zip(model.q, model.coordinate_rates, strict=True)])
        if has_drives(model):
            tau += friction_torques(model, friction, eps)
        return laid_out(chain, tau, simplify)

    arguments = (gravity, simplify) if friction == "sign" else (gravity, simplify, friction, eps)
    return _memo(chain, euler_lagrange, arguments, compute)  # type: ignore[return-value]
