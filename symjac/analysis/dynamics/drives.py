r"""The drives' share of the dynamics: motor (armature) inertia and joint friction, in joint space.

Per joint *i* with a :class:`~symjac.model.drive.Drive` (armature :math:`I_{a,i}`, viscous :math:`F_{v,i}`,
Coulomb :math:`F_{c,i}`; zero where a joint has none) and joint rates :math:`\dot\vartheta = C\dot q`:

.. math::
    M_q \mathrel{+}= C^T \operatorname{diag}(I_a)\,C, \qquad
    \tau_q \mathrel{+}= C^T\left(I_a \ddot\vartheta + F_v \dot\vartheta + F_c\,s(\dot\vartheta)\right), \qquad
    T \mathrel{+}= \tfrac12 \dot\vartheta^T \operatorname{diag}(I_a)\,\dot\vartheta

with :math:`s = \operatorname{sign}` (``friction="sign"``, the default: no torque at rest, a jump through zero) or
:math:`s(x) = \tanh(x/\varepsilon)` (``friction="smooth"``, differentiable, for optimisation; ``eps`` sets the width
of the transition in the joint's rate unit). :math:`C` is the coupling matrix (the identity without one). The
gravity torques and the Coriolis matrix do not change: the armature is constant and friction is no Coriolis force.
"""

from __future__ import annotations

from typing import Literal

import sympy as sp

from symjac.kinematics.chain import Chain, as_chain
from symjac.kinematics.coupling import coupling_matrix
from symjac.model.robot import Robot

__all__ = ["FRICTION_LAWS", "FrictionLaw", "armature_matrix", "coulomb_law", "drive_energy", "drive_torques",
           "friction_torques", "has_drives"]

FrictionLaw = Literal["sign", "smooth"]
FRICTION_LAWS: tuple[str, ...] = ("sign", "smooth")
"""How Coulomb friction depends on the rate: ``sign`` (:math:`F_c\\operatorname{sign}(\\dot q)`) or ``smooth``
(:math:`F_c\\tanh(\\dot q/\\varepsilon)`)."""


def has_drives(robot: Robot | Chain) -> bool:
    """Whether any joint of ``robot`` has drive data (its dynamics then differ from the rigid bodies')."""
    return any(drive is not None for drive in as_chain(robot).robot.drives)


def _entries(robot: Robot, name: str) -> list[sp.Expr]:
    return [sp.S.Zero if drive is None else getattr(drive, name) for drive in robot.drives]


def _joint_rates(robot: Robot, accelerations: bool = False) -> sp.Matrix:
    values = robot.coordinate_accelerations if accelerations else robot.coordinate_rates
    return coupling_matrix(robot) * sp.Matrix(values)


def coulomb_law(rate: sp.Expr, friction: FrictionLaw = "sign", eps: sp.Expr | float | None = None) -> sp.Expr:
    r""":math:`\operatorname{sign}(\dot q)` or :math:`\tanh(\dot q/\varepsilon)`; ``eps`` is required for ``smooth``.

    Examples
    --------
    >>> x = sp.Symbol("x", real=True)
    >>> coulomb_law(x), coulomb_law(x, "smooth", sp.Rational(1, 100))
    (sign(x), tanh(100*x))
    """
    if friction == "sign":
        return sp.sign(rate)
    if friction != "smooth":
        raise ValueError(f"friction must be one of {', '.join(FRICTION_LAWS)}, got {friction!r}")
    if eps is None:
        raise ValueError("friction='smooth' needs eps, the rate at which tanh(qdot/eps) reaches 0.76 (e.g. 0.01)")
    width = sp.nsimplify(eps, rational=True) if isinstance(eps, float) else sp.sympify(eps)
    if width.is_number and not width > 0:
        raise ValueError(f"eps must be positive, got {eps}")
    return sp.tanh(rate / width)


def armature_matrix(robot: Robot | Chain) -> sp.ImmutableMatrix:
    r""":math:`C^T \operatorname{diag}(I_a)\,C`, n_coordinates x n_coordinates (zero without drive data)."""
    model = as_chain(robot).robot
    C = coupling_matrix(model)
    return sp.ImmutableMatrix(C.T * sp.diag(*_entries(model, "armature")) * C)


def friction_torques(robot: Robot | Chain, friction: FrictionLaw = "sign",
                     eps: sp.Expr | float | None = None) -> sp.ImmutableMatrix:
    r"""The torques the joints' friction takes: :math:`C^T(F_v\dot\vartheta + F_c\,s(\dot\vartheta))`, n x 1.

    They oppose the motion: a motor must give them on top of the rigid bodies' torques. In the coordinate rates.

    Examples
    --------
    >>> import dataclasses
    >>> from symjac import load_robot
    >>> from symjac.model.drive import Drive
    >>> arm = dataclasses.replace(load_robot("planar2r"), drives=(Drive(viscous=2, coulomb=1), None))
    >>> friction_torques(arm).T
    Matrix([[2*thetadot1 + sign(thetadot1), 0]])
    """
    model = as_chain(robot).robot
    rates = _joint_rates(model)
    joint = [fv * rate + (fc * coulomb_law(rate, friction, eps) if fc != 0 else 0)
             for fv, fc, rate in zip(_entries(model, "viscous"), _entries(model, "coulomb"), rates, strict=True)]
    return sp.ImmutableMatrix(coupling_matrix(model).T * sp.Matrix(joint))


def drive_torques(robot: Robot | Chain, friction: FrictionLaw = "sign",
                  eps: sp.Expr | float | None = None) -> sp.ImmutableMatrix:
    r"""The drives' whole share of the torques: :math:`C^T I_a \ddot\vartheta` plus :func:`friction_torques`."""
    model = as_chain(robot).robot
    inertial = armature_matrix(model) * sp.Matrix(model.coordinate_accelerations)
    return sp.ImmutableMatrix(inertial + friction_torques(model, friction, eps))


def drive_energy(robot: Robot | Chain) -> sp.Expr:
    r"""The rotors' kinetic energy :math:`\tfrac12 \dot q^T C^T \operatorname{diag}(I_a) C \dot q`."""
    model = as_chain(robot).robot
    qdot = sp.Matrix(model.coordinate_rates)
    return sp.expand((qdot.T * armature_matrix(model) * qdot)[0] / 2)
