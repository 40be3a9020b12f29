r"""The one place a coupling is applied: results derived in the joint variables, written in the coordinates.

Every derivation runs on the joints alone (:attr:`Chain.joint_chain <symjac.kinematics.chain.Chain.joint_chain>`,
each joint its own coordinate). For a robot with a :class:`~symjac.model.coordinates.Coupling`
:math:`\vartheta(q) = C\,q + \vartheta_0` (C constant, see :mod:`symjac.model.coordinates`), the result is then
moved to the coordinates here:

.. math::
    J_q = J(\vartheta(q))\,C, \qquad
    H_q[:, j, m] = \sum_a \sum_b H[:, a, b]\,C_{aj}\,C_{bm}, \qquad
    \dot J_q = \dot J\big|_{\dot\vartheta = C\dot q}\,C = \sum_m H_q[:, :, m]\,\dot q_m,

the bias :math:`\dot J_q\dot q = \dot J\dot\vartheta` with :math:`\dot\vartheta = C\dot q`, and torques
:math:`\tau_q = C^T\tau` (the generalised forces that do the same work, :math:`\tau_q^T\dot q = \tau^T\dot\vartheta`).
Transforms and anything else written in the joint variables, their rates and accelerations take
:math:`\vartheta = \vartheta(q)`, :math:`\dot\vartheta = C\dot q`, :math:`\ddot\vartheta = C\ddot q`
(:func:`in_coordinates`). Without a coupling every function here returns its argument unchanged.

**The laws, by name.** Each derived quantity states once which of four laws moves it to the coordinates
(:data:`COUPLING_LAWS`); :func:`symjac.kinematics.memo.memoized` (its ``coupling=`` argument) is the one place that
asks whether a robot is coupled, derives the quantity on the joint chain and applies the law:

==============  ==============================================  ======================================
law             equation                                        quantities
==============  ==============================================  ======================================
``columns``     :math:`J_q = J(\vartheta(q))\,C`                Jacobians, J-dot, velocity propagation
``transposed``  :math:`\tau_q = C^T\tau`                        torque maps (force propagation)
``congruent``   :math:`H_q[i] = C^T H[i]\,C`                    the kinematic Hessian; M, C (dynamics)
``rates``       :math:`\vartheta(q),\ \dot\vartheta = C\dot q`  poses, bias, acceleration propagation
==============  ==============================================  ======================================

A structured result (a propagation with its steps) is moved field by field by its own ``in_coordinates(chain,
law)`` method, which applies the named laws to its matrices.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, TypeVar, get_args

import sympy as sp

from symjac.errors import ArgumentError
from symjac.model.robot import JointType, Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import simplify_matrix

if TYPE_CHECKING:  # the chain module applies the coupling to forward kinematics, so it imports this one
    from symjac.kinematics.chain import Chain, Frame

M = TypeVar("M", sp.MatrixBase, sp.NDimArray)

LawName = Literal["columns", "transposed", "congruent", "rates"]
"""The name of a coupling law (:data:`COUPLING_LAWS`)."""

LAW_NAMES: tuple[str, ...] = get_args(LawName)
"""The four coupling laws by name, as a quantity states its own (``coupling="columns"``)."""

__all__ = [
    "COUPLING_LAWS",
    "LAW_NAMES",
    "CouplingLaw",
    "LawName",
    "congruent_in_coordinates",
    "coordinate_bases",
    "coordinate_substitution",
    "coupling_law",
    "coupling_matrix",
    "hessian_in_coordinates",
    "in_coordinates",
    "jacobian_in_coordinates",
    "torques_in_coordinates",
]


def coupling_matrix(robot: Robot | Chain) -> sp.Matrix:
    r""":math:`C = \partial\vartheta/\partial q`, shape (n_joints, n_coordinates); the identity without a coupling."""
    model = _model(robot)
    return sp.eye(model.n_joints) if model.coupling is None else sp.Matrix(model.coupling.matrix)


def coordinate_substitution(robot: Robot | Chain) -> dict[sp.Symbol, sp.Expr]:
    r"""The substitution that writes joint-space results in the coordinates (empty without a coupling).

    :math:`\vartheta_i \to \vartheta_i(q)`, :math:`\dot\vartheta_i \to (C\dot q)_i`,
    :math:`\ddot\vartheta_i \to (C\ddot q)_i`, all at once (a coordinate that is a joint's own variable keeps it).

    Examples
    --------
    >>> from symjac import load_robot
    >>> coordinate_substitution(load_robot("planar2r"))
    {}
    """
    if _model(robot).coupling is None:
        return {}
    from symjac.kinematics.chain import MemoKey, as_chain  # the chain imports this module

    chain = as_chain(robot)  # kept with everything else derived from the robot (asked for by every result)
    return dict(chain.memo(MemoKey(_substitution, ()), lambda: _substitution(chain.robot)))


def _substitution(model: Robot) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """:func:`coordinate_substitution` of a coupled robot."""
    assert model.coupling is not None
    C = model.coupling.matrix
    qdot, qddot = model.coordinate_rates, model.coordinate_accelerations
    values: list[tuple[sp.Symbol, sp.Expr]] = []
    for i, (joint, value) in enumerate(zip(model.joints, model.coupling.values, strict=True)):
        values.append((joint.variable, value))
        values.append((joint.rate, sp.Add(*[C[i, j] * qdot[j] for j in range(C.cols) if C[i, j] != 0])))
        values.append((joint.acceleration, sp.Add(*[C[i, j] * qddot[j] for j in range(C.cols) if C[i, j] != 0])))
    return tuple(values)


def in_coordinates(robot: Robot | Chain, result: M, layout: Frame | None = None) -> M:
    """A result written in the joint variables (and their rates and accelerations), written in the coordinates.

    With ``layout`` (a frame; ``robot`` must then be a chain) it is laid out again in compact form, in the angles
    that frame's results read best in (:func:`coordinate_bases`).
    """
    values = coordinate_substitution(robot)
    if not values:
        return result
    if isinstance(result, sp.NDimArray):
        size = math.prod(result.shape)
        flat = result.reshape(size)
        entries = sp.Matrix(1, size, [flat[i].xreplace(values) for i in range(size)])
        if layout is not None:
            entries = simplify_matrix(entries, coordinate_bases(robot, layout))  # type: ignore[arg-type]
        return type(result)(list(entries), result.shape)  # type: ignore[return-value]
    substituted = result.xreplace(values)
    if layout is not None:
        substituted = simplify_matrix(substituted, coordinate_bases(robot, layout))  # type: ignore[arg-type]
    return type(result)(substituted)  # type: ignore[return-value]


def jacobian_in_coordinates(robot: Robot | Chain, J: sp.MatrixBase, layout: Frame | None = None
                            ) -> sp.ImmutableMatrix:
    r""":math:`J_q = J(\vartheta(q))\,C` for a matrix J whose columns belong to the joints (``layout``: as above)."""
    if _model(robot).coupling is None:
        return sp.ImmutableMatrix(J)
    J_q = _product(in_coordinates(robot, sp.Matrix(J)), coupling_matrix(robot))
    if layout is not None:
        J_q = _laid_out_again(robot, J_q, J, layout)
    return sp.ImmutableMatrix(J_q)


def _laid_out_again(robot: Robot | Chain, J_q: sp.Matrix, J: sp.MatrixBase, layout: Frame) -> sp.Matrix:
    """Simplify again (in ``layout``'s coordinate bases) only the entries of J_q that the coupling changed.

    An entry of a coordinate that is a joint's own variable, equal to that joint's entry of J (it never involved a
    coupled joint), is already laid out: simplifying it again costs as much as the whole joint-space layout did.
    """
    model = _model(robot)
    column_of = {variable: k for k, variable in enumerate(model.joint_variables)}
    changed = [(r, c) for c, coordinate in enumerate(model.coordinates) for r in range(J_q.rows)
               if coordinate not in column_of or J_q[r, c] != J[r, column_of[coordinate]]]
    if changed:
        entries = simplify_matrix(sp.Matrix(1, len(changed), [J_q[r, c] for r, c in changed]),
                                  coordinate_bases(robot, layout))  # type: ignore[arg-type]  # a chain, documented
        for (r, c), entry in zip(changed, entries, strict=True):
            J_q[r, c] = entry
    return J_q


def coordinate_bases(chain: Chain, frame: Frame) -> list[AngleBasis]:
    r"""The angle bases of ``frame`` (:meth:`Chain.angle_bases`) written in the revolute coordinates.

    Each basis angle of the joint chain takes :math:`\vartheta(q)`; angles that become constant or repeat are
    dropped, single coordinates fill the gaps, and a set that is no longer a unimodular basis is left out. A
    parallelogram's :math:`\theta_2 + \theta_3 + \theta_4` vanishes; :math:`\theta_2 + \theta_3` stays.
    """
    model = chain.robot
    values = dict(zip(model.joint_variables, model.joint_values, strict=True))
    variables = tuple(c for c, kind in zip(model.q, model.coordinate_types, strict=True) if kind is JointType.REVOLUTE)
    bases: list[AngleBasis] = []
    for basis in chain.joint_chain.angle_bases(frame):
        angles: list[sp.Expr] = []
        for angle in (sp.expand(a.xreplace(values)) for a in basis.angles):
            if angle.free_symbols & set(variables) and angle not in angles:
                angles.append(angle)
        angles += [v for v in variables if v not in angles]
        try:
            candidate = AngleBasis(variables, tuple(angles[:len(variables)]))
        except ValueError:  # substituted angles that are not a unimodular basis of the coordinates
            continue
        if candidate not in bases:
            bases.append(candidate)
    return bases or [AngleBasis(variables, variables)]


def torques_in_coordinates(robot: Robot | Chain, M_tau: sp.MatrixBase) -> sp.ImmutableMatrix:
    r""":math:`C^T M` for a matrix whose rows belong to the joints (a torque map :math:`\tau = M F`)."""
    if _model(robot).coupling is None:
        return sp.ImmutableMatrix(M_tau)
    return sp.ImmutableMatrix(_product(coupling_matrix(robot).T, in_coordinates(robot, sp.Matrix(M_tau))))


def hessian_in_coordinates(robot: Robot | Chain, H: sp.NDimArray, layout: Frame | None = None
                           ) -> sp.ImmutableDenseNDimArray:
    r""":math:`H_q[i, j, m] = \sum_a \sum_b H[i, a, b]\,C_{aj}\,C_{bm}` for a Hessian in the joint variables."""
    if _model(robot).coupling is None:
        return sp.ImmutableDenseNDimArray(H)
    C = coupling_matrix(robot)
    H = in_coordinates(robot, H)
    rows, joints, _ = H.shape
    slices = [_product(_product(C.T, sp.Matrix(joints, joints, lambda a, b, i=i: H[i, a, b])), C)
              for i in range(rows)]  # slice i is C^T H[i] C
    n = C.cols
    flat = sp.Matrix(1, rows * n * n, [slices[i][j, m] for i in range(rows) for j in range(n) for m in range(n)])
    if layout is not None:
        flat = simplify_matrix(flat, coordinate_bases(robot, layout))  # type: ignore[arg-type]
    return sp.ImmutableDenseNDimArray(list(flat), (rows, n, n))


def congruent_in_coordinates(robot: Robot | Chain, value: sp.MatrixBase | sp.NDimArray, layout: Frame | None = None
                             ) -> sp.ImmutableMatrix | sp.ImmutableDenseNDimArray:
    r"""The ``congruent`` law: :math:`C^T M\,C` for a matrix, a Hessian slice by slice.

    A matrix's rows and columns belong to the joints (the mass and Coriolis matrices; :math:`\vartheta =
    \vartheta(q)`, :math:`\dot\vartheta = C\dot q` substituted); an array is a Hessian (:func:`hessian_in_coordinates`).
    """
    if isinstance(value, sp.NDimArray):
        return hessian_in_coordinates(robot, value, layout)
    if _model(robot).coupling is None:
        return sp.ImmutableMatrix(value)
    C = coupling_matrix(robot)
    return sp.ImmutableMatrix(_product(_product(C.T, in_coordinates(robot, sp.Matrix(value))), C))


def _product(left: sp.MatrixBase, right: sp.MatrixBase) -> sp.Matrix:
    """``left * right`` with zero terms left out, so an uncoupled column keeps its joint-space entries as they are."""
    return sp.Matrix(left.rows, right.cols, lambda r, c: sp.Add(*[left[r, k] * right[k, c] for k in range(left.cols)
                                                                 if left[r, k] != 0 and right[k, c] != 0]))


def _model(robot: Robot | Chain) -> Robot:
    return robot if isinstance(robot, Robot) else robot.robot


@dataclass(frozen=True)
class CouplingLaw:
    r"""How a quantity derived in the joint variables is written in the coordinates (module docstring).

    ``name`` is one of :data:`LAW_NAMES`, ``equation`` the law in LaTeX, and ``move(chain, value, layout)`` applies
    it to a matrix or array in the joint variables (``layout``: a frame to lay the result out again in, or None).
    """

    name: str
    equation: str
    move: Callable[[Any, Any, Any], Any]

    def __call__(self, chain: Chain, value: Any, layout: Frame | None = None) -> Any:
        """``value`` (a matrix, an array, or a result with an ``in_coordinates(chain, law)`` method) moved."""
        if isinstance(value, sp.MatrixBase | sp.NDimArray):
            return self.move(chain, value, layout)
        return value.in_coordinates(chain, self)


COUPLING_LAWS: dict[str, CouplingLaw] = {law.name: law for law in (
    CouplingLaw("columns", r"J_q = J(\vartheta(q))\,C", jacobian_in_coordinates),
    CouplingLaw("transposed", r"\tau_q = C^T \tau", lambda chain, M, layout: torques_in_coordinates(chain, M)),
    CouplingLaw("congruent", r"H_q[i] = C^T H[i]\,C", congruent_in_coordinates),
    CouplingLaw("rates", r"\vartheta = \vartheta(q),\ \dot\vartheta = C\dot q,\ \ddot\vartheta = C\ddot q",
                lambda chain, value, layout: in_coordinates(chain, value, layout)),
)}
"""The coupling laws by name (:data:`LAW_NAMES`)."""


def coupling_law(name: str) -> CouplingLaw:
    r"""The law called ``name``; an :class:`~symjac.errors.ArgumentError` names the known ones.

    Examples
    --------
    >>> coupling_law("columns").equation
    'J_q = J(\\vartheta(q))\\,C'
    """
    if name not in COUPLING_LAWS:
        raise ArgumentError(f"unknown coupling law {name!r}; choose one of {', '.join(LAW_NAMES)}")
    return COUPLING_LAWS[name]
