r"""The arm as numbers to draw: frame poses, joint axes and ellipsoids at one configuration, in world coordinates.

Pure NumPy on top of the chain (no matplotlib): :func:`arm_pose` evaluates every frame of the chain,
:math:`{}^{W}T_k = {}^{W}T_0 \, {}^{0}T_1 \cdots {}^{k-1}T_k` for the frame positions world, {0}, ..., {n}, tool,
by multiplying the link transforms of the chain compiled once per robot (:func:`sympy.lambdify` of each link's
4 x 4 transform, parameters at their defaults). Joint :math:`i` turns or slides along the z-axis of its axis frame
(:meth:`~symjac.kinematics.chain.Chain.axis_frame`: {i-1} in standard DH, {i} otherwise), through that frame's
origin.

The ellipsoids at the tool point use the geometric Jacobian built from the same frames (the :math:`z_i \times
p_{i,t}` form, in world coordinates): the velocity ellipsoid :math:`\{J_v \dot q : \|\dot q\| \le 1\}` has semi-axes
:math:`\sigma_k u_k` (singular values and left singular vectors of :math:`J_v`), the force ellipsoid :math:`\{F :
\|J_v^T F\| \le 1\}` has semi-axes :math:`u_k / \sigma_k`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, as_chain
from symjac.kinematics.memo import memoized
from symjac.model.robot import JointType, Robot

__all__ = ["ArmPose", "Ellipsoid", "arm_pose", "configuration", "ellipsoid", "home_configuration"]

EllipsoidKind = Literal["velocity", "force"]
"""Which ellipsoid: of the tool velocities that unit joint rates give, or of the wrenches unit torques resist."""

FORCE_AXIS_RATIO = 100.0
"""The force ellipsoid's semi-axes are clipped at this many times its shortest one, 1 / sigma_max: they grow
without bound as a singular value goes to zero (the arm then holds that force with no torque at all)."""


@dataclass(frozen=True)
class Ellipsoid:
    r"""An ellipsoid at ``centre`` with semi-axes ``axes[k]`` (rows: unit direction times length, world coordinates).

    ``clipped[k]`` says the k-th length was cut at :data:`FORCE_AXIS_RATIO` times the shortest (it is larger, or
    infinite at a singular configuration); velocity ellipsoids are never cut.
    """

    kind: EllipsoidKind
    centre: np.ndarray
    axes: np.ndarray
    clipped: tuple[bool, bool, bool]


@dataclass(frozen=True)
class ArmPose:
    r"""The arm at configuration ``q``, everything in world coordinates (metres).

    ``frames[k]`` is the 4 x 4 pose of frame position ``k - 1`` (world, {0}, ..., {n}, tool) and ``labels[k]`` its
    name as drawn; ``joint_origins[i]`` and ``joint_axes[i]`` are the point and unit direction of joint i + 1;
    ``limit_margins[i]`` is how far joint i + 1 is from its nearer limit, as a fraction of half its range (1 in the
    middle, 0 at a limit, negative beyond it; NaN without limits). ``reach`` is the summed length of the segments
    between frame origins: the drawing's unit of size.
    """

    q: np.ndarray
    frames: tuple[np.ndarray, ...]
    labels: tuple[str, ...]
    joint_origins: np.ndarray
    joint_axes: np.ndarray
    joint_types: tuple[JointType, ...]
    limit_margins: np.ndarray
    reach: float
    jacobian: np.ndarray

    @property
    def origins(self) -> np.ndarray:
        """The origins of all frames, world to tool, as rows."""
        return np.array([frame[:3, 3] for frame in self.frames])

    @property
    def tool(self) -> np.ndarray:
        """The pose of the last frame (the tool frame, or {n} without a tool)."""
        return self.frames[-1]


def home_configuration(robot: Robot | Chain) -> np.ndarray:
    """Zero, or the middle of a joint's limits where zero lies outside them (a coupled robot: zero).

    Examples
    --------
    >>> from symjac import load_robot
    >>> np.round(home_configuration(load_robot("panda")), 4).tolist()  # joint 4 cannot reach 0
    [0.0, 0.0, 0.0, -1.5708, 0.0, 0.0, 0.0]
    """
    model = as_chain(robot).robot
    home = np.zeros(model.n_coordinates)
    if model.coupling is None:
        for k, joint in enumerate(model.joints):
            if joint.limits is not None:
                low, high = (float(sp.sympify(bound).xreplace(model.defaults)) for bound in joint.limits)
                home[k] = 0.0 if low <= 0.0 <= high else (low + high) / 2
    return home


def configuration(robot: Robot | Chain, q: Sequence[float] | np.ndarray | None) -> np.ndarray:
    """``q`` as a float array of the robot's coordinates; a clear error for anything else.

    ``None`` stands for :func:`home_configuration`.
    """
    model = as_chain(robot).robot
    if q is None:
        return home_configuration(model)
    if isinstance(q, str | bytes):
        raise ArgumentError(f"q must be {model.n_coordinates} numbers, got the text {q!r}")
    try:
        values = np.asarray(q, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError(f"q must be {model.n_coordinates} numbers, got {q!r}") from None
    if values.shape != (model.n_coordinates,):
        raise ArgumentError(f"q must have {model.n_coordinates} entries for {model.name}, got shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise ArgumentError(f"q must be finite, got {values.tolist()}")
    return values


@dataclass(frozen=True)
class _Compiled:
    """The chain's link transforms and coupling as NumPy functions (parameters at their defaults)."""

    steps: Callable[..., Any]  # joint values -> list of 4 x 4 step transforms, base first, tool last
    joint_values: Callable[..., Any]  # coordinates -> joint values
    coupling_jacobian: Callable[..., Any]  # coordinates -> d(joint values)/d(coordinates)
    limits: np.ndarray  # (n, 2), NaN where a joint has no limits


@memoized()
def _compiled(chain: Chain) -> _Compiled:
    robot = chain.robot
    defaults = robot.defaults
    positions = range(chain.n_joints + 2)
    steps = [sp.Matrix(chain.transform(chain.frame_name(k - 1), chain.frame_name(k))).xreplace(defaults)
             for k in positions]
    variables = list(robot.joint_variables)
    coordinates = list(robot.q)
    values = sp.Matrix(robot.joint_values).xreplace(defaults)
    limits = np.full((chain.n_joints, 2), np.nan)
    for i, joint in enumerate(robot.joints):
        if joint.limits is not None:
            limits[i] = [float(sp.sympify(bound).xreplace(defaults)) for bound in joint.limits]
    return _Compiled(
        steps=sp.lambdify([variables], steps, modules="numpy", cse=True),
        joint_values=sp.lambdify([coordinates], list(values), modules="numpy"),
        coupling_jacobian=sp.lambdify([coordinates], values.jacobian(coordinates), modules="numpy"),
        limits=limits,
    )


def _label(chain: Chain, position: int) -> str:
    name = chain.frame_name(position)
    return "{W}" if name == "world" else "{T}" if name == "tool" else f"{{{name}}}"


def arm_pose(robot: Robot | Chain, q: Sequence[float] | np.ndarray | None = None) -> ArmPose:
    r"""Every frame, joint axis and the tool-point Jacobian of ``robot`` at ``q``, numerically, in world coordinates.

    .. math::

        {}^{W}T_k = \prod_{j \le k} T_j, \qquad
        J = \begin{bmatrix} z_i \times (p_t - o_i) \\ z_i \end{bmatrix} \text{(revolute)}, \quad
        \begin{bmatrix} z_i \\ 0 \end{bmatrix} \text{(prismatic)},

    with :math:`o_i, z_i` the origin and z-axis of joint i's axis frame and :math:`p_t` the tool point (origin of the
    tool frame, or of {n}); a coupled robot's columns are combined by the coupling's Jacobian, one per coordinate.

    Examples
    --------
    >>> from symjac import load_robot
    >>> pose = arm_pose(load_robot("planar2r"), [0.0, np.pi / 2])
    >>> np.round(pose.tool[:3, 3], 12).tolist()  # (L1, L2, 0) with the defaults L1 = 0.5, L2 = 0.4
    [0.5, 0.4, 0.0]
    >>> pose.labels
    ('{W}', '{0}', '{1}', '{2}', '{T}')
    """
    chain = as_chain(robot)
    model = chain.robot
    coordinates = configuration(chain, q)
    compiled = _compiled(chain)
    joints = np.array(compiled.joint_values(coordinates), dtype=float)
    poses = _chained(compiled, joints)
    axis_frames = [chain.axis_frame(i) + 1 for i in range(1, chain.n_joints + 1)]  # +1: position -1 is index 0
    origins = np.array([poses[k][:3, 3] for k in axis_frames]).reshape(-1, 3)
    axes = np.array([poses[k][:3, 2] for k in axis_frames]).reshape(-1, 3)
    types = tuple(joint.type for joint in model.joints)
    point = poses[-1][:3, 3]
    columns = [np.concatenate([np.cross(z, point - o), z]) if kind is JointType.REVOLUTE
               else np.concatenate([z, np.zeros(3)]) for o, z, kind in zip(origins, axes, types, strict=True)]
    J = np.array(columns).T.reshape(6, chain.n_joints)
    if model.coupling is not None:
        J = J @ np.asarray(compiled.coupling_jacobian(coordinates), dtype=float).reshape(chain.n_joints, -1)
    low, high = compiled.limits[:, 0], compiled.limits[:, 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        margins = np.minimum(joints - low, high - joints) / ((high - low) / 2)
    origins_all = np.array([pose[:3, 3] for pose in poses])
    reach = float(np.sum(np.linalg.norm(np.diff(origins_all, axis=0), axis=1)))
    return ArmPose(coordinates, tuple(poses), tuple(_label(chain, k) for k in range(-1, chain.n_joints + 2)),
                   origins, axes, types, margins, reach if reach > 1e-9 else 1.0, J)


def _chained(compiled: _Compiled, joints: np.ndarray) -> list[np.ndarray]:
    """World poses of positions -1..n+1 from the step transforms (the base step leads from the world to {0})."""
    poses = [np.eye(4)]
    for step in compiled.steps(joints):
        poses.append(poses[-1] @ np.asarray(step, dtype=float))
    return poses


def ellipsoid(pose: ArmPose, kind: EllipsoidKind = "velocity") -> Ellipsoid:
    r"""The velocity or force ellipsoid of the linear rows at the tool point, semi-axes as rows.

    .. math:: J_v = U \Sigma V^T: \quad a_k = \sigma_k u_k \text{ (velocity)}, \qquad a_k = u_k / \sigma_k
       \text{ (force)},

    a force semi-axis longer than :data:`FORCE_AXIS_RATIO` times the shortest being cut to that length.

    Examples
    --------
    >>> from symjac import load_robot
    >>> e = ellipsoid(arm_pose(load_robot("planar2r"), [0.0, np.pi / 2]))
    >>> np.round(np.linalg.norm(e.axes, axis=1), 6).tolist()  # the singular values of J_v; planar: one is 0
    [0.698598, 0.286288, 0.0]
    """
    if kind not in ("velocity", "force"):
        raise ArgumentError(f"unknown ellipsoid {kind!r}; choose velocity or force")
    U, sigma, _ = np.linalg.svd(pose.jacobian[:3, :])
    sigma = np.concatenate([sigma, np.zeros(3 - len(sigma))])
    if kind == "velocity":
        lengths = sigma
    else:
        with np.errstate(divide="ignore"):
            lengths = np.where(sigma > 0, 1.0 / np.where(sigma > 0, sigma, 1.0), np.inf)
    strongest = float(sigma.max())
    longest = np.inf if kind == "velocity" else FORCE_AXIS_RATIO / strongest if strongest > 0 else pose.reach
    first, second, third = (bool(length > longest) for length in lengths)
    return Ellipsoid(kind, pose.tool[:3, 3].copy(), U.T * np.minimum(lengths, longest)[:, None],
                     (first, second, third))
