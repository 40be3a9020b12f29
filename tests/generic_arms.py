r"""Random generic arms as robot files, each with its own forward kinematics in plain NumPy (issue 41's checks).

An arm is drawn as numbers (geometry from a seeded generator: calibrated-looking floats, never textbook values at the
joint the draw marks generic), written out as TOML text with 17 significant digits and read by
:func:`symjac.robot_from_toml`. Its reference kinematics is written here from the textbook formulas, from the same
numbers and nothing of symjac's:

* standard DH: :math:`{}^{i-1}_iT = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)`;
* modified DH: :math:`{}^{i-1}_iT = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)`;
* general joints: the child link frame :math:`C_i = C_{i-1}\,T_{\text{origin},i}\,\mathrm{Rot}(u_i, \theta_i)`
  (or :math:`\mathrm{Trans}(u_i d_i)`), origins :math:`T(x, y, z)\,R_z(\text{yaw})\,R_y(\text{pitch})\,
  R_x(\text{roll})`, rotations by Rodrigues' formula;
* product of exponentials: :math:`T = e^{[S_1]q_1} \cdots e^{[S_n]q_n} M` (space form) or
  :math:`M\,e^{[B_1]q_1} \cdots e^{[B_n]q_n}` (body form), each exponential by Rodrigues' formula.

Where symjac's result depends on a documented *choice* of frame (frame {i} of a general joint is its child link frame
turned so that z is the joint axis; frame {i} of a PoE joint sits at the point of its axis nearest the origin, a
prismatic joint keeping the point before it), that choice is written here from its documentation
(:mod:`symjac.model.conventions.general`, :mod:`symjac.model.conventions.poe`,
:func:`symjac.symbolic.transforms.alignment`). The tool transform is relative to frame {n}, as in every robot file.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from hypothesis import strategies as st

# --- elementary motions ----------------------------------------------------------------------------------------


def rot_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rot_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1.0]])


def rot_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def trans(x: float, y: float, z: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def vee(W: np.ndarray) -> np.ndarray:
    """The vector of the skew-symmetric part of a 3 x 3 matrix."""
    S = (W - W.T) / 2
    return np.array([S[2, 1], S[0, 2], S[1, 0]])


def origin(xyz: list[float], rpy: list[float]) -> np.ndarray:
    """URDF origin: T(x, y, z) Rz(yaw) Ry(pitch) Rx(roll)."""
    return trans(*xyz) @ rot_z(rpy[2]) @ rot_y(rpy[1]) @ rot_x(rpy[0])


def rodrigues(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about the unit ``axis`` through the origin, 4 x 4."""
    K = hat(axis)
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    return T


def screw_exponential(screw: np.ndarray, angle: float) -> np.ndarray:
    r""":math:`e^{[S]\theta}` of a screw :math:`S = (\omega, v)`: Rodrigues for :math:`|\omega| = 1`, a translation
    for :math:`\omega = 0` (the file's 13-digit unit vector is normalised first, as the book's MatrixExp6 does)."""
    w, v = screw[:3], screw[3:]
    size = np.linalg.norm(w)
    T = np.eye(4)
    if size < 1e-12:
        T[:3, 3] = v * angle
        return T
    w, v, angle = w / size, v / size, angle * size
    K = hat(w)
    T[:3, :3] = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    T[:3, 3] = (np.eye(3) * angle + (1 - np.cos(angle)) * K + (angle - np.sin(angle)) * K @ K) @ v
    return T


def adjoint(T: np.ndarray) -> np.ndarray:
    """[Ad_T], 6 x 6, for twists written angular part first."""
    R, p = T[:3, :3], T[:3, 3]
    A = np.zeros((6, 6))
    A[:3, :3] = R
    A[3:, 3:] = R
    A[3:, :3] = hat(p) @ R
    return A


def alignment(axis: np.ndarray, exact_axis: tuple[int, int, int] | None) -> np.ndarray:
    """symjac's documented rotation A with A e_z = u: an elementary rotation for a coordinate axis given exactly
    (I, Rx(pi), Ry(+-pi/2), Rx(-+pi/2) for +-z, +-x, +-y), else the columns (e1, u x e1, u), e1 = e_z x u / |.|."""
    if exact_axis is not None:
        x, y, z = exact_axis
        return (np.eye(4) if z == 1 else rot_x(np.pi) if z == -1 else rot_y(x * np.pi / 2) if x else
                rot_x(-y * np.pi / 2))
    u = axis / np.linalg.norm(axis)
    e1 = np.array([-u[1], u[0], 0.0])
    e1 /= np.linalg.norm(e1)
    A = np.eye(4)
    A[:3, :3] = np.column_stack([e1, np.cross(u, e1), u])
    return A


def unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return Q if np.linalg.det(Q) > 0 else -Q


# --- TOML text ----------------------------------------------------------------------------------------------------


def number(value: Any) -> str:
    """A float as TOML with 17 significant digits (round-trips the double); strings (``"pi/2"``) quoted."""
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, int):
        return str(value)
    return repr(float(value))


def vector(values: Any) -> str:
    return "[" + ", ".join(number(v) for v in values) + "]"


def fixed_table(name: str, transform: tuple[list[float], list[float]] | None) -> list[str]:
    if transform is None:
        return []
    xyz, rpy = transform
    return [f"[{name}]", f"xyz = {vector(xyz)}", f"rpy = {vector(rpy)}"]


SPECIAL = {"0": 0.0, "pi/2": np.pi / 2, "-pi/2": -np.pi / 2}


def value_of(entry: Any) -> float:
    return SPECIAL[entry] if isinstance(entry, str) else float(entry)


# --- arms -------------------------------------------------------------------------------------------------------


@dataclass
class Arm:
    """A generic arm: its robot file text and its independent forward kinematics.

    ``links(q)`` returns the poses of frames {0}..{n} relative to frame {0} (so the first is the identity); the tool
    transform (relative to {n}) and the base (world to {0}) are constant.
    """

    kind: str
    text: str
    n: int
    links: Callable[[np.ndarray], list[np.ndarray]]
    tool: np.ndarray | None = None
    base: np.ndarray | None = None
    screws: np.ndarray | None = None  # PoE: space screws as columns (6 x n), as written or as Ad_M B
    body_screws: np.ndarray | None = None  # PoE body form: the file's screws
    home: np.ndarray | None = None
    prismatic: tuple[bool, ...] = field(default=())

    def pose(self, q: np.ndarray, frame: Any) -> np.ndarray:
        """Pose of ``frame`` (0..n, "tool", "world") relative to frame {0} at ``q``."""
        if frame == "world":
            return np.linalg.inv(self.base if self.base is not None else np.eye(4))
        poses = self.links(q)
        if frame == "tool":
            return self.tool_pose(q, poses)
        return poses[int(frame)]

    def tool_pose(self, q: np.ndarray, poses: list[np.ndarray] | None = None) -> np.ndarray:
        if self.kind == "poe body":  # M e^[B1]q1 ... e^[Bn]qn: the book's body form, independent of the frames
            T = self.home.copy()
            for i in range(self.n):
                T = T @ screw_exponential(self.body_screws[:, i], q[i])
            return T
        if self.kind == "poe":
            T = np.eye(4)
            for i in range(self.n):
                T = T @ screw_exponential(self.screws[:, i], q[i])
            return T @ self.home
        poses = self.links(q) if poses is None else poses
        return poses[-1] @ (self.tool if self.tool is not None else np.eye(4))


def _dh_arm(rng: np.random.Generator, kind: str, rows: list[tuple[bool, Any]], tool: bool, base: bool) -> Arm:
    """DH rows (prismatic, twist: a float or a special name); lengths, offsets and tool from ``rng``."""
    params = []
    lines = ['name = "generic_dh"', f'convention = "{kind}"']
    for prismatic, twist in rows:
        a, d, theta = (float(x) for x in rng.uniform(-0.6, 0.6, 3))
        params.append((prismatic, value_of(twist), a, d, theta))
        lines += ["[[joints]]", f'type = "{"prismatic" if prismatic else "revolute"}"', f"alpha = {number(twist)}",
                  f"a = {number(a)}", f"d = {number(d)}", f"theta = {number(theta)}"]
    tool_xyz_rpy = ([*rng.uniform(-0.3, 0.3, 3)], [*rng.uniform(-2, 2, 3)]) if tool else None
    base_xyz_rpy = ([*rng.uniform(-0.3, 0.3, 3)], [*rng.uniform(-2, 2, 3)]) if base else None
    lines += fixed_table("tool", tool_xyz_rpy) + fixed_table("base", base_xyz_rpy)

    def links(q: np.ndarray) -> list[np.ndarray]:
        poses = [np.eye(4)]
        for (prismatic, alpha, a, d, theta), value in zip(params, q, strict=True):
            if prismatic:
                d += value
            else:
                theta += value
            if kind == "standard":
                link = rot_z(theta) @ trans(0, 0, d) @ trans(a, 0, 0) @ rot_x(alpha)
            else:
                link = rot_x(alpha) @ trans(a, 0, 0) @ rot_z(theta) @ trans(0, 0, d)
            poses.append(poses[-1] @ link)
        return poses

    return Arm(kind, "\n".join(lines) + "\n", len(rows), links,
               tool=origin(*tool_xyz_rpy) if tool_xyz_rpy else None,
               base=origin(*base_xyz_rpy) if base_xyz_rpy else None,
               prismatic=tuple(p for p, _ in rows))


COORDINATE_AXES = [(0, 0, 1), (0, 0, -1), (1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0)]


def _general_arm(rng: np.random.Generator, rows: list[tuple[bool, Any]], tool: bool, base: bool) -> Arm:
    """General joints: per row (prismatic, axis: an index into COORDINATE_AXES or "generic"); generic rpy where
    the row says "generic", else multiples of pi/2 in the file as numbers 0."""
    params = []
    lines = ['name = "generic_general"', 'convention = "general"']
    for prismatic, axis_kind in rows:
        xyz = [float(x) for x in rng.uniform(-0.5, 0.5, 3)]
        if axis_kind == "generic":
            rpy = [float(x) for x in rng.uniform(-3, 3, 3)]
            axis, exact = [float(x) for x in rng.normal(size=3)], None
        else:
            rpy = [0.0, 0.0, 0.0]
            exact = COORDINATE_AXES[axis_kind]
            axis = list(exact)
        params.append((prismatic, origin(xyz, rpy), unit(np.array(axis, dtype=float)), exact))
        lines += ["[[joints]]", f'type = "{"prismatic" if prismatic else "revolute"}"', f"xyz = {vector(xyz)}",
                  f"rpy = {vector(rpy)}", f"axis = {vector(axis)}"]
    tool_xyz_rpy = ([*rng.uniform(-0.3, 0.3, 3)], [*rng.uniform(-2, 2, 3)]) if tool else None
    base_xyz_rpy = ([*rng.uniform(-0.3, 0.3, 3)], [*rng.uniform(-2, 2, 3)]) if base else None
    lines += fixed_table("tool", tool_xyz_rpy) + fixed_table("base", base_xyz_rpy)

    def links(q: np.ndarray) -> list[np.ndarray]:
        child, poses = np.eye(4), [np.eye(4)]
        for (prismatic, placement, axis, exact), value in zip(params, q, strict=True):
            motion = trans(*(axis * value)) if prismatic else rodrigues(axis, value)
            child = child @ placement @ motion
            poses.append(child @ alignment(axis, exact))  # frame {i}: the child link frame turned z onto the axis
        return poses

    return Arm("general", "\n".join(lines) + "\n", len(rows), links,
               tool=origin(*tool_xyz_rpy) if tool_xyz_rpy else None,
               base=origin(*base_xyz_rpy) if base_xyz_rpy else None,
               prismatic=tuple(p for p, _ in rows))


def poe_screws(rng: np.random.Generator, rows: list[tuple[bool, str]], digits: int = 13) -> np.ndarray:
    """Screws (w, -w x p) or (0, v) as columns, rounded to ``digits`` decimals as a calibration file would give
    them; an axis "z" is the exact +z axis, "generic" a random unit vector."""
    columns = []
    for prismatic, axis_kind in rows:
        direction = np.array([0.0, 0.0, 1.0]) if axis_kind == "z" else unit(rng.normal(size=3))
        if prismatic:
            screw = np.concatenate([np.zeros(3), direction])
        else:
            screw = np.concatenate([direction, -np.cross(direction, rng.normal(size=3) * 0.6)])
        columns.append(np.round(screw, digits))
    return np.array(columns).T


def poe_home(rng: np.random.Generator) -> np.ndarray:
    M = np.eye(4)
    M[:3, :3] = random_rotation(rng)
    M[:3, 3] = rng.uniform(-0.8, 0.8, 3)
    return M


def poe_text(screws: np.ndarray, home: np.ndarray, body: bool, prismatic: tuple[bool, ...]) -> str:
    lines = ['name = "generic_poe"', 'convention = "poe"']
    if body:
        lines.append("body = true")
    lines += ["[home]", "matrix = [" + ", ".join(vector(row) for row in home) + "]"]
    for i, p in enumerate(prismatic):
        lines += ["[[joints]]", f'type = "{"prismatic" if p else "revolute"}"', f"screw = {vector(screws[:, i])}"]
    return "\n".join(lines) + "\n"


def _poe_arm(rng: np.random.Generator, rows: list[tuple[bool, str]], body: bool) -> Arm:
    prismatic = tuple(p for p, _ in rows)
    given = poe_screws(rng, rows)
    home = poe_home(rng)
    space = adjoint(home) @ given if body else given
    # frame {i} at home: G_i = Trans(p_i) A_i, p_i = w x v (the axis point nearest the origin) for a revolute
    # joint, the point before for a prismatic one; A_i turns z onto w (or v); the exact +z axis gives A_i = I
    placements, point = [], np.zeros(3)
    for i, (p, axis_kind) in enumerate(rows):
        w, v = space[:3, i], space[3:, i]
        if not p:
            w = unit(w)
            point = np.cross(w, v)
        direction = unit(v) if p else w
        exact = (0, 0, 1) if axis_kind == "z" and not body else None
        placements.append(trans(*point) @ alignment(direction, exact))

    def links(q: np.ndarray) -> list[np.ndarray]:
        product, poses = np.eye(4), [np.eye(4)]
        for i in range(len(rows)):
            product = product @ screw_exponential(space[:, i], q[i])
            poses.append(product @ placements[i])
        return poses

    return Arm("poe body" if body else "poe", poe_text(given, home, body, prismatic), len(rows), links,
               screws=space, body_screws=given if body else None, home=home, prismatic=prismatic)


KINDS = ("standard", "modified", "general", "poe", "poe body")


@st.composite
def generic_arms(draw: st.DrawFn, min_joints: int = 3, max_joints: int = 8,
                 kinds: tuple[str, ...] = KINDS) -> Arm:
    """A random generic arm of one of ``kinds``: joint types, which constants are generic and the optional tool
    and base drawn by hypothesis, the numbers from a seeded generator; one joint is always generic."""
    kind = draw(st.sampled_from(kinds), label="kind")
    n = draw(st.integers(min_joints, max_joints), label="joints")
    prismatic = draw(st.lists(st.sampled_from([False, False, True]), min_size=n, max_size=n), label="prismatic")
    generic_joint = draw(st.integers(0, n - 1), label="generic joint")
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1), label="seed"))
    tool = draw(st.booleans(), label="tool")
    base = draw(st.booleans(), label="base") if not kind.startswith("poe") else False
    if kind in ("standard", "modified"):
        special = draw(st.lists(st.sampled_from([None, "0", "pi/2", "-pi/2"]), min_size=n, max_size=n))
        rows = [(p, float(rng.uniform(-3, 3)) if s is None or i == generic_joint else s)
                for i, (p, s) in enumerate(zip(prismatic, special, strict=True))]
        return _dh_arm(rng, kind, rows, tool, base)
    if kind == "general":
        axes = draw(st.lists(st.sampled_from(["generic", 0, 2, 5]), min_size=n, max_size=n))
        return _general_arm(rng, [(p, "generic" if i == generic_joint else a)
                                  for i, (p, a) in enumerate(zip(prismatic, axes, strict=True))], tool, base)
    axes = draw(st.lists(st.sampled_from(["generic", "generic", "z"]), min_size=n, max_size=n))
    return _poe_arm(rng, [(p, "generic" if i == generic_joint else a)
                          for i, (p, a) in enumerate(zip(prismatic, axes, strict=True))], kind == "poe body")


# --- finite differences -----------------------------------------------------------------------------------------

STEP = 1e-3
"""Step of the fourth-order central stencil: truncation about h^4/30 and rounding about eps/h, both near 1e-13 here
(a second-order stencil at h = 1e-6 rounds to about 1e-10 times the arm's size, too close to the 1e-9 checked)."""


def derivative(function: Callable[[np.ndarray], np.ndarray], x: np.ndarray, direction: np.ndarray,
               h: float = STEP) -> np.ndarray:
    """d/dt function(x + t direction) at t = 0, by the central stencil (8 (f1 - f-1) - (f2 - f-2)) / 12h."""
    f = [function(x + k * h * direction) for k in (-2, -1, 1, 2)]
    return (8 * (f[2] - f[1]) - (f[3] - f[0])) / (12 * h)


def point_jacobian(arm: Arm, q: np.ndarray, frame: Any, link: Any, point: np.ndarray) -> np.ndarray:
    """6 x n [v; omega] of ``point`` (coordinates in the frame of ``link``: 0..n or "tool") expressed in ``frame``,
    from central differences of the pose: omega^ = dR/dq R^T (vee of its skew part)."""
    homogeneous_point = np.append(point, 1.0)

    def flat(qq: np.ndarray) -> np.ndarray:
        T = arm.pose(qq, link)
        return np.concatenate([(T @ homogeneous_point)[:3], T[:3, :3].ravel()])

    R = arm.pose(q, link)[:3, :3]
    J = np.zeros((6, arm.n))
    for i in range(arm.n):
        d = derivative(flat, q, np.eye(arm.n)[i])
        J[:3, i] = d[:3]
        J[3:, i] = vee(d[3:].reshape(3, 3) @ R.T)
    R_0_f = arm.pose(q, frame)[:3, :3]
    return np.kron(np.eye(2), R_0_f.T) @ J


def screw_jacobians(arm: Arm, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """J_s and J_b (rows omega then v) from [V_s] = dT T^-1 and [V_b] = T^-1 dT of the tool pose."""
    T = arm.tool_pose(q)
    T_inv = np.linalg.inv(T)
    J_s, J_b = np.zeros((6, arm.n)), np.zeros((6, arm.n))
    for i in range(arm.n):
        dT = derivative(lambda qq: arm.tool_pose(qq), q, np.eye(arm.n)[i])
        for J, V in ((J_s, dT @ T_inv), (J_b, T_inv @ dT)):
            J[:3, i] = vee(V[:3, :3])
            J[3:, i] = V[:3, 3]
    return J_s, J_b
