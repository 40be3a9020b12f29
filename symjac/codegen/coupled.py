r"""Lowering for a coupled robot: every function derived in the joint variables, evaluated in the coordinates.

A robot with a :class:`~symjac.model.coordinates.Coupling` :math:`\vartheta(q) = C\,q + \vartheta_0` (C constant)
is lowered on the chain of its joints alone (:attr:`Chain.joint_chain
<symjac.kinematics.chain.Chain.joint_chain>`), with the raw chain products and angle expansions of
:mod:`symjac.codegen.lower` and :mod:`symjac.codegen.acceleration`, and then written in the coordinates here:

.. math::
    J_q = J(\vartheta(q))\,C, \qquad \tau_q = C^T J^T F, \qquad
    H_q[i, j, m] = \sum_a \sum_b H[i, a, b]\,C_{aj}\,C_{bm}, \qquad
    \dot J_q\,\dot q = \dot J\,\dot\vartheta\ \text{with}\ \dot\vartheta = C\,\dot q.

The products with C skip its zero entries and go through CSE together, so a column of J that two coordinates share
is computed once. A joint angle is given to ``sin``/``cos`` as its expression in the coordinates
(``s4 = sin(-theta2 - theta3)``); a prismatic joint variable or a joint rate that is not a coordinate (rate) becomes
the first assignments of the function (``d3 = d30 + k*theta4``, ``thetadot4 = -thetadot2 - thetadot3``). Without a
coupling every function here returns exactly what the joint-space lowering returns.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import sympy as sp

from symjac.codegen.acceleration import lowered_bias_acceleration, lowered_hessian
from symjac.codegen.lower import (
    LoweredFunction,
    angle_expansion,
    lower_function,
    lowered_forward_kinematics,
    lowered_jacobian,
    lowered_kinematics,
    lowered_torques,
)
from symjac.codegen.request import rows_of, strategy_of
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.jacobian import point_vector
from symjac.kinematics.memo import frame_of, memoized
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import Robot
from symjac.quantities.spec import LawName, entry_point

__all__ = [
    "coordinate_angles",
    "coordinate_bias_acceleration",
    "coordinate_derivation",
    "coordinate_forward_kinematics",
    "coordinate_hessian",
    "coordinate_jacobian",
    "coordinate_kinematics",
    "coordinate_torques",
    "coordinates_of_joints",
    "coupling_lines",
]

Combine = Callable[[Sequence[sp.Expr]], list[sp.Expr]]


def coupling_lines(chain: Chain) -> tuple[str, ...]:
    """Each joint variable that is not a coordinate as an equation in the coordinates: ``theta4 = -theta2 - theta3``."""
    model = chain.robot
    if model.coupling is None:
        return ()
    return tuple(f"{variable} = {value}" for variable, value in zip(model.joint_variables, model.joint_values,
                                                                      strict=True) if variable != value)


def coordinates_of_joints(robot: Robot) -> tuple[sp.Expr, ...]:
    r"""Each coordinate as an expression of the joint variables: how a joint-space solution (IK) becomes ``q``.

    The joint variables themselves without a coupling. With one, :math:`\vartheta = C\,q + \vartheta_0` is solved
    on the first rows of C that are independent (a coordinate that is a joint's own variable is that joint's value):
    :math:`q = C_S^{-1}(\vartheta_S - \vartheta_{0,S})`, the joints that are coordinates tried first. A coupling
    whose C has dependent columns is refused.

    Examples
    --------
    >>> from symjac import load_robot
    >>> coordinates_of_joints(load_robot("palletizer"))
    (theta1, theta2, theta3, theta5)
    """
    coupling = robot.coupling
    if coupling is None:
        return tuple(robot.joint_variables)
    C, offsets, own = sp.Matrix(coupling.matrix), coupling.offsets, set(coupling.coordinates)
    rows: list[int] = []
    for i in sorted(range(C.rows), key=lambda i: coupling.values[i] not in own):  # a coordinate's own joint first
        if C.extract([*rows, i], list(range(C.cols))).rank() > len(rows):
            rows.append(i)
    if len(rows) < C.cols:
        raise CodegenError(f"{robot.name}: the joint values do not determine its coordinates (the coupling matrix "
                           f"has rank {len(rows)}, fewer than its {C.cols} columns)")
    rows.sort()
    joints = sp.Matrix([robot.joint_variables[i] - offsets[i] for i in rows])
    return tuple(sp.expand(value) for value in C.extract(rows, list(range(C.cols))).inv() * joints)


def _values(chain: Chain) -> dict[sp.Symbol, sp.Expr]:
    r"""Joint variables and joint rates that are not coordinates (rates): :math:`\vartheta(q)`, :math:`C\dot q`."""
    model = chain.robot
    C = coupling_matrix(chain)
    qdot = sp.Matrix(model.coordinate_rates)
    values: dict[sp.Symbol, sp.Expr] = {}
    for i, (joint, value) in enumerate(zip(model.joints, model.joint_values, strict=True)):
        rate = (C[i, :] * qdot)[0]
        if value != joint.variable:
            values[joint.variable] = value
        if rate != joint.rate:
            values[joint.rate] = rate
    return values


def coordinate_angles(chain: Chain) -> tuple[sp.Expr, ...]:
    """The revolute joint angles (with offsets) as expressions of the coordinates, in the lowering's order."""
    angles = angle_expansion(chain.joint_chain).angles
    if chain.robot.coupling is None:
        return angles
    values = _values(chain)
    return tuple(sp.expand(angle.xreplace(values)) for angle in angles)


def _in_coordinates(chain: Chain, lowered: LoweredFunction, shape: tuple[int, ...], combine: Combine | None,
                    note: str) -> LoweredFunction:
    """``lowered`` (joint space) with its outputs combined by C, evaluated in the coordinates and their rates."""
    model = chain.robot
    values = _values(chain)
    temporaries = list(lowered.temporaries)
    outputs = list(lowered.outputs)
    expanded = list(lowered.expanded)
    if combine is not None:
        extra, reduced = sp.cse(combine(outputs), symbols=sp.numbered_symbols("_cq", real=True), order="canonical")
        temporaries += extra
        outputs = list(reduced)
        expanded = combine(expanded)
    needed = set().union(*(e.free_symbols for e in outputs)) if outputs else set()
    kept: list[tuple[sp.Symbol, sp.Expr]] = []
    for symbol, expr in reversed(temporaries):
        if symbol in needed:
            kept.append((symbol, expr))
            needed |= expr.free_symbols
    kept.reverse()
    # joint variables and rates read outside the sines and cosines: computed first, under their own names
    first = [(symbol, value) for symbol, value in values.items() if symbol in needed]
    angles = tuple((s, c, sp.expand(a.xreplace(values))) for s, c, a in lowered.angles if s in needed or c in needed)
    coordinates = {"q": tuple(model.q), "qdot": joint_rate_symbols(chain)}
    inputs = tuple((name, coordinates.get(name, symbols)) for name, symbols in lowered.inputs)
    body = [*first, *kept]
    op_count = sum(int(sp.count_ops(e)) for _, e in body) + sum(int(sp.count_ops(e)) for e in outputs)
    return LoweredFunction(inputs, angles, tuple(body), tuple(outputs),
                           tuple(sp.Basic.xreplace(sp.sympify(e), values) for e in expanded), shape, op_count,
                           f"{lowered.origin}{note}")


def _columns(C: sp.Matrix, rows: int) -> Combine:
    """Row-major ``rows`` x n_joints entries times C: ``M C`` (zero entries of C skipped)."""
    def combine(entries: Sequence[sp.Expr]) -> list[sp.Expr]:
        n = C.rows
        return [sp.Add(*[entries[r * n + a] * C[a, j] for a in range(n) if C[a, j] != 0])
                for r in range(rows) for j in range(C.cols)]
    return combine


def _transposed(C: sp.Matrix) -> Combine:
    """n_joints entries (a vector) times C^T: ``C^T v``."""
    def combine(entries: Sequence[sp.Expr]) -> list[sp.Expr]:
        return [sp.Add(*[C[a, j] * entries[a] for a in range(C.rows) if C[a, j] != 0]) for j in range(C.cols)]
    return combine


def _congruent(C: sp.Matrix, rows: int) -> Combine:
    """Row-major ``rows`` x n_joints x n_joints entries, each slice H_i written C^T H_i C."""
    def combine(entries: Sequence[sp.Expr]) -> list[sp.Expr]:
        n, m = C.rows, C.cols
        result: list[sp.Expr] = []
        for i in range(rows):
            right = [[sp.Add(*[entries[(i * n + a) * n + b] * C[b, k] for b in range(n) if C[b, k] != 0])
                      for k in range(m)] for a in range(n)]  # H_i C
            result += [sp.Add(*[C[a, j] * right[a][k] for a in range(n) if C[a, j] != 0])
                       for j in range(m) for k in range(m)]
        return result
    return combine


@memoized(strategy=strategy_of)
def coordinate_forward_kinematics(chain: Chain, strategy: str) -> LoweredFunction:
    """:func:`~symjac.codegen.lower.lowered_forward_kinematics`, in the coordinates."""
    if chain.robot.coupling is None:
        return lowered_forward_kinematics(chain, strategy)
    return _in_coordinates(chain, lowered_forward_kinematics(chain.joint_chain, strategy), (4, 4), None, "")


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def coordinate_jacobian(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
                        strategy: str) -> LoweredFunction:
    r""":math:`J_q = J(\vartheta(q))\,C` (rows ``rows``): :func:`~symjac.codegen.lower.lowered_jacobian` times C."""
    J = lowered_jacobian(chain.joint_chain, frame, point, rows, strategy)
    if chain.robot.coupling is None:
        return J
    C = coupling_matrix(chain)
    return _in_coordinates(chain, J, (len(rows), C.cols), _columns(C, len(rows)), ", times C")


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def coordinate_torques(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
                       strategy: str) -> LoweredFunction:
    r""":math:`\tau_q = C^T J^T F` from the joint-space torques of the Jacobian :func:`coordinate_jacobian` uses."""
    joints = chain.joint_chain
    tau = lowered_torques(joints, lowered_jacobian(joints, frame, point, rows, strategy), rows)
    if chain.robot.coupling is None:
        return tau
    C = coupling_matrix(chain)
    return _in_coordinates(chain, tau, (C.cols,), _transposed(C), ", times C^T")


@memoized(frame=frame_of, point=point_vector)
def coordinate_kinematics(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...]) -> LoweredFunction:
    """:func:`~symjac.codegen.lower.lowered_kinematics` (what the self-test differentiates), in the coordinates."""
    if chain.robot.coupling is None:
        return lowered_kinematics(chain, frame, point)
    return _in_coordinates(chain, lowered_kinematics(chain.joint_chain, frame, point), (21,), None, "")


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def coordinate_hessian(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
                       strategy: str) -> LoweredFunction:
    r""":math:`H_q[i] = C^T H[i]\,C`: :func:`~symjac.codegen.acceleration.lowered_hessian` in the coordinates."""
    H = lowered_hessian(chain.joint_chain, frame, point, rows, strategy)
    if chain.robot.coupling is None:
        return H
    C = coupling_matrix(chain)
    return _in_coordinates(chain, H, (len(rows), C.cols, C.cols), _congruent(C, len(rows)),
                           ", C^T H C")


@memoized(frame=frame_of, point=point_vector, rows=rows_of, strategy=strategy_of)
def coordinate_bias_acceleration(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: tuple[int, ...],
                                 strategy: str) -> LoweredFunction:
    r""":math:`\dot J\dot\vartheta` with :math:`\dot\vartheta = C\dot q` (equal to :math:`\dot J_q\dot q`)."""
    bias = lowered_bias_acceleration(chain.joint_chain, frame, point, rows, strategy)
    if chain.robot.coupling is None:
        return bias
    return _in_coordinates(chain, bias, (len(rows),), None, ", qdot via C")


@memoized()
def coordinate_derivation(chain: Chain, derivation: str, law: LawName, where: tuple[object, ...] = (),
                          rows: tuple[int, ...] = ()) -> LoweredFunction:
    r"""A quantity's own derivation, lowered: the generic lowering of a quantity that names none (a plug-in).

    ``derivation`` (``"module:function"``) is called with the chain of the joints, and with ``where`` = (frame,
    point) as ``frame=``, ``point=`` for a per-request quantity; it returns a matrix or a scalar in the joint
    variables. ``rows`` (if any) selects its rows. A one-column matrix becomes a vector. For a coupled robot the
    result moves to the coordinates by ``law``: ``rates`` (:math:`\vartheta(q)` substituted), ``columns`` (times C)
    or ``transposed`` (:math:`C^T v`).
    """
    joints = chain.joint_chain
    derive = entry_point(derivation)
    value = derive(joints) if not where else derive(joints, frame=where[0], point=where[1])
    if isinstance(value, sp.MatrixBase):
        matrix = sp.Matrix(value)
        if rows:
            matrix = matrix.extract(list(rows), list(range(matrix.cols)))
        shape: tuple[int, ...] = (matrix.rows,) if matrix.cols == 1 else (matrix.rows, matrix.cols)
        entries = list(matrix)
    elif isinstance(value, sp.Expr | int | float):
        shape, entries = (), [sp.sympify(value)]
    else:
        raise CodegenError(f"{derivation} returned a {type(value).__name__}; code generation takes a matrix or a "
                           "scalar (or give the quantity a lowering of its own)")
    model = joints.robot
    lowered = lower_function(angle_expansion(joints), entries, shape, (("q", model.q),), model.parameter_symbols,
                             f"the quantity's derivation {derivation}")
    if chain.robot.coupling is None or law == "rates":
        return lowered if chain.robot.coupling is None else _in_coordinates(chain, lowered, shape, None, "")
    C = coupling_matrix(chain)
    if law == "columns" and len(shape) == 2:
        return _in_coordinates(chain, lowered, (shape[0], C.cols), _columns(C, shape[0]), ", times C")
    if law == "transposed" and len(shape) == 1:
        return _in_coordinates(chain, lowered, (C.cols,), _transposed(C), ", times C^T")
    raise CodegenError(f"{derivation}: the {law} coupling law does not apply to a result of shape {shape}; give the "
                       "quantity a lowering of its own")
