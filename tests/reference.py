"""An independent numeric reference: forward kinematics in plain NumPy and finite-difference Jacobians.

Nothing here uses symjac's transforms, chain or simplification: only the robot's data (DH rows, base, tool), turned
into floats, once per robot object. The Jacobian comes from central differences of this forward kinematics; the
angular part from :math:`\\hat\\omega \\approx (R(q + h e_i) - R(q - h e_i)) R(q)^T / 2h`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from generic_arms import rot_x, rot_z, trans
from sympy.printing.numpy import NumPyPrinter

from symjac import Robot
from symjac.model.robot import JointType
from symjac.symbolic.nested import definitions


def _float(expr: sp.Expr, robot: Robot) -> float:
    return float(sp.sympify(expr).subs(robot.defaults))


def _matrix(transform, robot: Robot) -> np.ndarray:
    """A fixed transform's 4 x 4 matrix as floats (the identity for none)."""
    return np.eye(4) if transform is None else np.array(transform.matrix.subs(robot.defaults), dtype=float)


def _rot_axis(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: rotation by ``angle`` about the unit ``axis``."""
    k = axis / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    return T


def _alignment(axis: np.ndarray) -> np.ndarray:
    """symjac's documented choice of frame {i} for a general joint: a rotation A with A e_z = u (see
    symjac.model.robot)."""
    u = axis / np.linalg.norm(axis)
    A = np.eye(4)
    if abs(abs(u[2]) - 1) < 1e-15:
        A[:3, :3] = np.diag([1.0, -1.0, -1.0]) if u[2] < 0 else np.eye(3)
    elif min(abs(abs(u[0]) - 1), abs(abs(u[1]) - 1)) < 1e-15:
        # R_y(+-pi/2) for +-x, R_x(-+pi/2) for +-y
        if abs(u[0]) > 0.5:
            A[:3, :3] = [[0, 0, u[0]], [0, 1, 0], [-u[0], 0, 0]]
        else:
            A[:3, :3] = [[1, 0, 0], [0, 0, u[1]], [0, -u[1], 0]]
    else:
        e1 = np.array([-u[1], u[0], 0.0])
        e1 /= np.linalg.norm(e1)
        A[:3, :3] = np.column_stack([e1, np.cross(u, e1), u])
    return A


def _general_numbers(robot: Robot) -> list[tuple[np.ndarray, np.ndarray, float, float, bool, np.ndarray]]:
    """Per joint of a general-convention robot, as floats: origin, unit axis, theta and d offsets, whether revolute,
    and the alignment of the joint before it (the identity for the first)."""
    rows, before = [], np.eye(4)
    for joint in robot.joints:
        given = joint.placement.origin
        origin = np.eye(4) if given is None else np.array(given.matrix.subs(robot.defaults), dtype=float)
        axis = np.array([_float(c, robot) for c in (joint.placement.axis or (0, 0, 1))])
        rows.append((origin, axis, _float(joint.theta, robot), _float(joint.d, robot), joint.is_revolute, before))
        before = _alignment(axis)
    return rows


def _general_link(row: tuple, value: float) -> np.ndarray:
    """Pose of frame {i} in frame {i-1} for a general joint, from origin, axis and Rodrigues (no alignment tricks)."""
    origin, axis, theta, d, revolute, before = row
    if revolute:
        theta += value
    else:
        d += value
    motion = _rot_axis(axis, theta) @ trans(*(d * axis / np.linalg.norm(axis)))
    return np.linalg.inv(before) @ origin @ motion @ _alignment(axis)


def _screw_matrix(screw: np.ndarray) -> np.ndarray:
    """The 4 x 4 matrix [S] of a screw (w, v) in se(3)."""
    w, v = screw[:3], screw[3:]
    return np.array([[0, -w[2], w[1], v[0]], [w[2], 0, -w[0], v[1]], [-w[1], w[0], 0, v[2]], [0, 0, 0, 0.0]])


def _screw_points(robot: Robot) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Per joint of a PoE robot: its space screw, and where symjac documents its frame at home: point and axis (a
    revolute axis' given point, else w x v, the point nearest the origin; a prismatic joint keeps the point before)."""
    rows, point = [], np.zeros(3)
    for joint in robot.joints:
        placement = joint.placement
        screw = np.array([_float(e, robot) for e in (*placement.omega, *placement.v)])
        if joint.is_revolute:
            point = (np.array([_float(e, robot) for e in placement.point]) if placement.point is not None
                     else np.cross(screw[:3], screw[3:]))
        rows.append((screw, point, screw[:3] if joint.is_revolute else screw[3:]))
    return rows


def _screw_frames(rows: list[tuple[np.ndarray, np.ndarray, np.ndarray]], q: np.ndarray) -> list[np.ndarray]:
    """Frames {0}..{n} of a PoE robot: e^[S1]q1 ... e^[Si]qi G_i, the exponentials by SciPy's expm."""
    from scipy.linalg import expm

    poses, product = [np.eye(4)], np.eye(4)
    for (screw, point, axis), value in zip(rows, q, strict=True):
        product = product @ expm(_screw_matrix(screw) * value)
        poses.append(product @ trans(*point) @ _alignment(axis))
    return poses


@dataclass(frozen=True)
class _Numbers:
    """A robot's data as floats, read once: base and tool, the links by convention, the coupling as a function."""

    base: np.ndarray
    tool: np.ndarray
    links: list
    joint_values: Callable[..., list] | None


_NUMBERS: dict[int, tuple[Robot, _Numbers]] = {}
"""By ``id(robot)``, the robot held with its numbers so that its id cannot be reused while the entry lives."""


def _numbers(robot: Robot) -> _Numbers:
    """The robot's data as floats, substituted once per robot object: the finite differences call :func:`frames`
    2n + 2 times per Jacobian, and SymPy substitution there cost seconds per robot."""
    entry = _NUMBERS.get(id(robot))
    if entry is not None and entry[0] is robot:
        return entry[1]
    if robot.convention == "poe":
        links = _screw_points(robot)
    elif robot.convention == "general":
        links = _general_numbers(robot)
    else:
        links = [(_float(joint.placement.alpha, robot), _float(joint.placement.a, robot), _float(joint.theta, robot),
                  _float(joint.d, robot), joint.is_revolute) for joint in robot.joints]
    coupling = None
    if robot.coupling is not None:
        # the coupling's law theta(q) from the robot's data, parameters at their defaults, compiled to NumPy once
        laws = [sp.sympify(v).xreplace(robot.defaults) for v in robot.joint_values]
        coupling = sp.lambdify(robot.coordinates, laws, modules="numpy")
    numbers = _Numbers(_matrix(robot.base, robot), _matrix(robot.tool, robot), links, coupling)
    if len(_NUMBERS) > 512:  # hypothesis draws many robots; keep the cache small
        _NUMBERS.clear()
    _NUMBERS[id(robot)] = (robot, numbers)
    return numbers


def joint_values(robot: Robot, q: np.ndarray) -> np.ndarray:
    """The joint variables theta(q) at the coordinates ``q`` (``q`` itself without a coupling or if joint values)."""
    if robot.coupling is None or len(q) == robot.n_joints:
        return np.asarray(q, dtype=float)
    return np.array(_numbers(robot).joint_values(*(float(v) for v in q)), dtype=float)


def frames(robot: Robot, q: np.ndarray) -> list[np.ndarray]:
    """World poses of frame positions world, 0, 1, ..., n, tool (n + 3 matrices) at the coordinates ``q``."""
    q = joint_values(robot, q)
    numbers = _numbers(robot)
    base, tool = numbers.base, numbers.tool
    poses = [np.eye(4), base.copy()]  # a copy: a caller may change what it gets, never the cached numbers
    if robot.convention == "poe":
        # frames {0}..{n}, then the tool: e^[S1]q1 ... e^[Sn]qn M with M = G_n times the tool transform
        screw_frames = [base @ pose for pose in _screw_frames(numbers.links, q)]
        return [np.eye(4), *screw_frames, screw_frames[-1] @ tool]
    for row, value in zip(numbers.links, q, strict=True):
        if robot.convention == "general":
            poses.append(poses[-1] @ _general_link(row, value))
            continue
        alpha, a, theta, d, revolute = row
        if revolute:
            theta += value
        else:
            d += value
        if robot.convention == "standard":
            link = rot_z(theta) @ trans(0, 0, d) @ trans(a, 0, 0) @ rot_x(alpha)
        else:
            link = rot_x(alpha) @ trans(a, 0, 0) @ rot_z(theta) @ trans(0, 0, d)
        poses.append(poses[-1] @ link)
    poses.append(poses[-1] @ tool)
    return poses


def frame_index(robot: Robot, frame: int | str) -> int:
    """Index into :func:`frames` of a symjac frame name."""
    return 0 if frame == "world" else robot.n_joints + 2 if frame == "tool" else int(frame) + 1


def end_of_chain(robot: Robot) -> np.ndarray | None:
    """The default point's coordinates in frame {n}: the tool transform's translation, or None (the origin of {n})."""
    return None if robot.tool is None else _matrix(robot.tool, robot)[:3, 3]


def finite_difference_jacobian(
    robot: Robot, q: np.ndarray, frame: int | str = 0, point: np.ndarray | None = None, h: float = 1e-6
) -> np.ndarray:
    """6 x len(q) Jacobian [v; omega] at the point (coordinates in frame {n}) expressed in ``frame``, in ``q``."""
    point_h = np.append(np.zeros(3) if point is None else np.asarray(point, dtype=float), 1.0)
    n = robot.n_joints

    def pose(qq: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        T_world_n = frames(robot, qq)[n + 1]
        return (T_world_n @ point_h)[:3], T_world_n[:3, :3]

    _, R_mid = pose(q)
    J_world = np.zeros((6, len(q)))
    for i in range(len(q)):
        step = np.zeros(len(q))
        step[i] = h
        (x_plus, R_plus), (x_minus, R_minus) = pose(q + step), pose(q - step)
        J_world[:3, i] = (x_plus - x_minus) / (2 * h)
        omega_hat = (R_plus - R_minus) / (2 * h) @ R_mid.T
        J_world[3:, i] = (omega_hat[2, 1], omega_hat[0, 2], omega_hat[1, 0])
    R_world_k = frames(robot, q)[frame_index(robot, frame)][:3, :3]
    rotate = np.kron(np.eye(2), R_world_k.T)
    return rotate @ J_world


def evaluate(matrix: sp.MatrixBase, robot: Robot, q: np.ndarray, extra: dict | None = None) -> np.ndarray:
    """Numeric value of a symbolic matrix at joint values ``q`` and the parameters' defaults."""
    values = {**{s: float(v) for s, v in robot.defaults.items()}, **dict(zip(robot.q, map(float, q), strict=True))}
    values.update(extra or {})
    symbols = tuple(sorted(values, key=str))
    return np.array(_compiled(matrix, symbols)(*[values[s] for s in symbols]), dtype=float)


_COMPILED: dict[tuple, Callable[..., Any]] = {}
"""Lambdified matrices by (matrix, arguments): a test evaluates one matrix at several configurations."""


def _nested_only(expr: Any) -> tuple[list[tuple[sp.Symbol, sp.Expr]], Any]:
    """Intermediates of a nested result as assignments; nothing else is CSE'd (as before nested results)."""
    return list(definitions(expr)), expr


def _compiled(matrix: sp.MatrixBase, symbols: tuple[sp.Symbol, ...]) -> Callable[..., Any]:
    """``sympy.lambdify(symbols, matrix)``, compiled once per matrix and argument list."""
    key = (sp.ImmutableMatrix(matrix) if isinstance(matrix, sp.MatrixBase) else sp.sympify(matrix), symbols)
    function = _COMPILED.get(key)
    if function is None:
        if len(_COMPILED) > 256:
            _COMPILED.clear()
        # terms printed in the order SymPy holds them: sorting every sum for print took half of lambdify's time
        printer = NumPyPrinter({"fully_qualified_modules": False, "inline": True, "allow_unknown_functions": True,
                                "user_functions": {}, "order": "none"})
        function = _COMPILED[key] = sp.lambdify(symbols, matrix, modules="numpy", printer=printer,
                                                cse=_nested_only)
    return function


def random_configuration(robot: Robot, rng: np.random.Generator) -> np.ndarray:
    """Coordinate values: angles in (-pi, pi), prismatic extensions in (0.1, 1) (the joint values without coupling)."""
    return np.array([rng.uniform(-np.pi, np.pi) if kind is JointType.REVOLUTE else rng.uniform(0.1, 1.0)
                     for kind in robot.coordinate_types])
