r"""The arm as matplotlib artists: :func:`draw` makes a figure, :class:`ArmDrawing` updates one in place.

Each part is one mplot3d artist with a ``gid`` naming it, so that a test (or a user) can find it and read back the
numbers it holds:

* ``links``: one polyline through the frame origins, world to tool;
* ``joint-i`` (1-based): a cylinder along joint i's axis for a revolute joint, a box for a prismatic one, centred on
  the origin of its axis frame, and the axis itself as the dashed line ``joint-i-axis`` (from the origin, 1.6 half
  lengths of the body each way); with ``limits=True`` the body goes from red (at a limit) through yellow to green
  (mid-range);
* ``frame-k-x``, ``-y``, ``-z``: the unit axes of frame {k} scaled to the triad length (x red, y green, z blue), and
  the text ``{k}`` (``label-k``) beside its origin; ``W`` and ``T`` name the world and tool frames. The first frame
  (world, or {0}) and the last (tool, or {n}) are always drawn, the others when ``frames`` is true (the default up to
  8 joints);
* ``velocity-ellipsoid`` / ``force-ellipsoid``: a translucent mesh at the tool point, and its three semi-axes as the
  lines ``velocity-ellipsoid-axis-k`` (:func:`~symjac.drawing.geometry.ellipsoid`, times the drawing's scale),
  dotted where a force semi-axis was clipped (near a singularity it is far longer, or infinite);
* ``arrow``: a direction drawn at the tool point (the report's lost direction).

The ids are valid SVG and HTML ids: matplotlib writes them into an SVG file as the ``id`` of each artist's group.

Sizes (joint bodies, triads) are fractions of the arm's reach at the first configuration drawn, so that they stay put
while the arm moves. The axes are equal in scale: a cube around everything drawn.
"""

from __future__ import annotations

import functools
import io
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from symjac.drawing.geometry import ArmPose, EllipsoidKind, arm_pose, configuration, ellipsoid
from symjac.errors import ArgumentError, SymjacError
from symjac.kinematics.chain import Chain, as_chain
from symjac.model.robot import JointType, Robot

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["ArmDrawing", "draw", "equal_axes", "matplotlib_figure", "view_angles"]

AXIS_COLOURS = ("#d62728", "#2ca02c", "#1f77b4")
"""x, y, z of every frame triad."""

JOINT_COLOUR = "#7f9fbf"
LINK_COLOUR = "#404040"
ELLIPSOID_COLOURS = {"velocity": "#9467bd", "force": "#ff7f0e"}
ARROW_COLOUR = "#e41a1c"
DEFAULT_VIEW = (-60.0, 25.0)
"""Azimuth and elevation in degrees (matplotlib's ``view_init``)."""

MOST_JOINTS_WITH_FRAMES = 8
"""Intermediate frame triads are drawn by default up to this many joints (beyond it they hide the arm)."""

_SIDES = 16  # facets of a joint cylinder and meridians of an ellipsoid


def matplotlib_figure(**options: Any) -> Figure:
    """A matplotlib Figure not tied to pyplot (no window, no global state); a clear error without matplotlib.

    Jupyter shows it as a PNG whatever matplotlib's backend (it has a ``_repr_png_``), so ``draw(...)`` as the last
    line of a cell shows the arm even where pyplot was never imported.
    """
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise SymjacError("drawing the arm needs matplotlib: pip install 'symjac[draw]'") from None
    return _shown_in_notebooks(Figure)(**options)  # type: ignore[no-any-return]


@functools.cache
def _shown_in_notebooks(base: type) -> type:
    class ArmFigure(base):  # type: ignore[valid-type, misc]
        """A matplotlib Figure with a PNG representation for IPython."""

        def _repr_png_(self) -> bytes:
            buffer = io.BytesIO()
            self.savefig(buffer, format="png", dpi=90, metadata={"Software": None})
            return buffer.getvalue()

    return ArmFigure


def _perpendicular(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors completing ``axis`` to a right-handed orthonormal basis."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    first = np.cross(axis, helper)
    first /= np.linalg.norm(first)
    return first, np.cross(axis, first)


def _prism(origin: np.ndarray, axis: np.ndarray, radius: float, half: float, sides: int) -> list[np.ndarray]:
    """The faces of a prism with ``sides`` sides along ``axis`` (a cylinder for many sides, a box for four)."""
    e1, e2 = _perpendicular(axis)
    angles = np.linspace(0.0, 2 * np.pi, sides, endpoint=False) + (np.pi / 4 if sides == 4 else 0.0)
    ring = radius * (np.outer(np.cos(angles), e1) + np.outer(np.sin(angles), e2))
    bottom, top = origin - half * axis + ring, origin + half * axis + ring
    faces = [np.array([bottom[k], bottom[(k + 1) % sides], top[(k + 1) % sides], top[k]]) for k in range(sides)]
    return [*faces, bottom, top]


def _ellipsoid_mesh(centre: np.ndarray, axes: np.ndarray) -> list[np.ndarray]:
    """Quadrilaterals covering the ellipsoid x = centre + sum_k a_k n_k, n on the unit sphere."""
    u = np.linspace(0.0, 2 * np.pi, _SIDES + 1)
    v = np.linspace(0.0, np.pi, _SIDES // 2 + 1)
    sphere = np.stack([np.outer(np.cos(u), np.sin(v)), np.outer(np.sin(u), np.sin(v)),
                       np.outer(np.ones_like(u), np.cos(v))], axis=-1)
    points = centre + sphere @ axes
    return [np.array([points[i, j], points[i + 1, j], points[i + 1, j + 1], points[i, j + 1]])
            for i in range(len(u) - 1) for j in range(len(v) - 1)]


def _limit_colour(margin: float) -> str | tuple[float, float, float, float]:
    if not np.isfinite(margin):
        return JOINT_COLOUR
    from matplotlib import colormaps

    return colormaps["RdYlGn"](float(np.clip(margin, 0.0, 1.0)))  # type: ignore[no-any-return]


class ArmDrawing:
    """The arm's artists on one 3-D axes, created once and moved by :meth:`update` (sliders, animations).

    Parameters
    ----------
    axes : mpl_toolkits.mplot3d.axes3d.Axes3D
        Where to draw.
    robot : Robot or Chain
    frames : bool, optional
        Draw the triads of the frames between the first and the last drawn (default: up to 8 joints). The first is
        the world frame with a base transform, else {0}; the last the tool frame with a tool, else {n}.
    ellipsoids : sequence of "velocity" and "force"
        Ellipsoids at the tool point.
    limits : bool
        Colour each joint by its distance to its limits (joints without limits stay grey-blue).
    reach : float, optional
        The unit of size of joints and triads (default: the reach at the first configuration).
    ellipsoid_scale : float, optional
        Metres drawn per unit of the ellipsoids' semi-axes (m/s per rad/s, or N per N m). Default: the largest
        semi-axis at the first configuration is drawn half the reach long (velocity and force ellipsoids apart).
    prefix : str
        Put before every ``gid`` (so that several drawings in one HTML page keep their SVG ids apart).
    """

    def __init__(self, axes: Any, robot: Robot | Chain, *, frames: bool | None = None,
                 ellipsoids: Sequence[EllipsoidKind] | EllipsoidKind = (), limits: bool = False,
                 reach: float | None = None,
                 ellipsoid_scale: float | None = None, prefix: str = ""):
        self.axes = axes
        axes.set_autoscale_on(False)  # the limits are set once, from everything drawn (a flat arm broke autoscaling)
        self.chain = as_chain(robot)
        n = self.chain.n_joints
        self.frames = n <= MOST_JOINTS_WITH_FRAMES if frames is None else bool(frames)
        kinds = (ellipsoids,) if isinstance(ellipsoids, str) else tuple(ellipsoids)
        for kind in kinds:
            if kind not in ELLIPSOID_COLOURS:
                raise ArgumentError(f"unknown ellipsoid {kind!r}; choose velocity or force")
        self.ellipsoids: tuple[EllipsoidKind, ...] = tuple(dict.fromkeys(kinds))
        self.limits = limits
        self.reach = reach
        self.prefix = prefix
        if ellipsoid_scale is not None and not (np.isfinite(ellipsoid_scale) and ellipsoid_scale > 0):
            raise ArgumentError(f"ellipsoid_scale must be a positive number, got {ellipsoid_scale!r}")
        self.scales: dict[str, float] = {kind: ellipsoid_scale for kind in self.ellipsoids} if ellipsoid_scale else {}
        self.links = axes.plot([], [], [], color=LINK_COLOUR, linewidth=2.5, marker="o", markersize=3,
                               solid_capstyle="round", gid=f"{self.prefix}links")[0]
        self.joints: list[Any] = []
        self.triads: dict[int, tuple[list[Any], Any]] = {}
        self.meshes: dict[str, tuple[Any, list[Any]]] = {}
        self.arrow: Any = None
        self.pose: ArmPose | None = None

    def _shown_frames(self, pose: ArmPose) -> list[int]:
        last = len(pose.frames) - 1
        # world and {0} coincide without a base, {n} and tool without a tool: draw each place once
        first = 0 if self.chain.robot.base is not None else 1
        final = last if self.chain.robot.tool is not None else last - 1
        middle = range(first + 1, final) if self.frames else range(0)
        return [first, *middle, final]

    def update(self, q: Sequence[float] | np.ndarray | None = None) -> ArmPose:
        """Move every artist to configuration ``q`` (the home configuration when ``None``); the numbers drawn."""
        pose = arm_pose(self.chain, q)
        if self.reach is None:
            self.reach = pose.reach
        origins = pose.origins
        self.links.set_data_3d(origins[:, 0], origins[:, 1], origins[:, 2])
        self._move_joints(pose, self.reach)
        self._move_frames(pose, 0.12 * self.reach)
        self._move_ellipsoids(pose, self.reach)
        self.pose = pose
        return pose

    def _move_joints(self, pose: ArmPose, size: float) -> None:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        for i, (origin, axis, kind) in enumerate(zip(pose.joint_origins, pose.joint_axes, pose.joint_types,
                                                     strict=True)):
            sides = _SIDES if kind is JointType.REVOLUTE else 4
            half = 0.06 * size if kind is JointType.REVOLUTE else 0.09 * size
            faces = _prism(origin, axis, 0.04 * size, half, sides)
            colour = _limit_colour(pose.limit_margins[i]) if self.limits else JOINT_COLOUR
            axis_line = np.array([origin - 1.6 * half * axis, origin + 1.6 * half * axis]).T
            if len(self.joints) <= i:
                body = Poly3DCollection(faces, facecolors=colour, edgecolors="none", alpha=0.95,
                                        gid=f"{self.prefix}joint-{i + 1}")
                self.axes.add_collection3d(body)
                line = self.axes.plot(*axis_line, color="black", linewidth=0.8, linestyle="dashed",
                                      gid=f"{self.prefix}joint-{i + 1}-axis")[0]
                self.joints.append((body, line))
            else:
                body, line = self.joints[i]
                body.set_verts(faces)
                body.set_facecolor(colour)
                line.set_data_3d(*axis_line)

    def _move_frames(self, pose: ArmPose, length: float) -> None:
        for k in self._shown_frames(pose):
            frame = pose.frames[k]
            origin = frame[:3, 3]
            label_at = origin + 0.35 * length * (frame[:3, 0] + frame[:3, 1]) - 0.15 * length * frame[:3, 2]
            name = pose.labels[k][1:-1]
            if k not in self.triads:
                lines = [self.axes.plot(*np.array([origin, origin + length * frame[:3, c]]).T, color=AXIS_COLOURS[c],
                                        linewidth=1.6, gid=f"{self.prefix}frame-{name}-{'xyz'[c]}")[0]
                         for c in range(3)]
                text = self.axes.text(*label_at, pose.labels[k], fontsize=8, gid=f"{self.prefix}label-{name}")
                self.triads[k] = (lines, text)
            else:
                lines, text = self.triads[k]
                for c, line in enumerate(lines):
                    line.set_data_3d(*np.array([origin, origin + length * frame[:3, c]]).T)
                text.set_position_3d(label_at)

    def _move_ellipsoids(self, pose: ArmPose, size: float) -> None:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        for shown in self.ellipsoids:
            shape = ellipsoid(pose, shown)
            if shown not in self.scales:
                longest = float(np.max(np.linalg.norm(shape.axes, axis=1)))
                self.scales[shown] = 0.5 * size / longest if longest > 0 else 1.0
            drawn = self.scales[shown] * shape.axes
            mesh = _ellipsoid_mesh(shape.centre, drawn)
            segments = [np.array([shape.centre - a, shape.centre + a]) for a in drawn]
            if shown not in self.meshes:
                colour = ELLIPSOID_COLOURS[shown]
                surface = Poly3DCollection(mesh, facecolors=colour, edgecolors="none", alpha=0.18,
                                           gid=f"{self.prefix}{shown}-ellipsoid")
                self.axes.add_collection3d(surface)
                lines = [self.axes.plot(*segment.T, color=colour, linewidth=1.2,
                                        gid=f"{self.prefix}{shown}-ellipsoid-axis-{k}")[0]
                         for k, segment in enumerate(segments)]
                self.meshes[shown] = (surface, lines)
            else:
                surface, lines = self.meshes[shown]
                surface.set_verts(mesh)
                for line, segment in zip(lines, segments, strict=True):
                    line.set_data_3d(*segment.T)
            for line, cut in zip(lines, shape.clipped, strict=True):
                line.set_linestyle("dotted" if cut else "solid")  # a clipped semi-axis is longer than drawn

    def draw_arrow(self, direction: Sequence[float], length: float | None = None) -> None:
        """An arrow at the tool point along ``direction`` (world coordinates), ``length`` default 0.4 x reach."""
        if self.pose is None:
            raise ArgumentError("draw the arm (update) before an arrow at its tool")
        vector = np.asarray(direction, dtype=float)
        norm = np.linalg.norm(vector)
        if vector.shape != (3,) or not np.isfinite(norm) or norm == 0:
            raise ArgumentError(f"an arrow needs a finite nonzero 3-vector, got {list(direction)}")
        tip = self.pose.tool[:3, 3]
        span = (0.4 * (self.reach or 1.0) if length is None else length) * vector / norm
        self.arrow = self.axes.quiver(*tip, *span, color=ARROW_COLOUR, linewidth=2.2, arrow_length_ratio=0.25,
                                      gid=f"{self.prefix}arrow")

    def points(self) -> np.ndarray:
        """Every point drawn (for the axes' limits)."""
        chunks = [np.array(self.links.get_data_3d()).T]
        for lines, _ in self.triads.values():
            chunks += [np.array(line.get_data_3d()).T for line in lines]
        for _, lines in self.meshes.values():
            chunks += [np.array(line.get_data_3d()).T for line in lines]
        return np.concatenate(chunks)


def equal_axes(axes: Any, points: np.ndarray, margin: float) -> None:
    """Equal scale on x, y and z: the smallest cube holding ``points``, widened by ``margin``."""
    low, high = points.min(axis=0), points.max(axis=0)
    centre, half = (low + high) / 2, float(np.max(high - low)) / 2 + margin
    axes.set_xlim(centre[0] - half, centre[0] + half)
    axes.set_ylim(centre[1] - half, centre[1] + half)
    axes.set_zlim(centre[2] - half, centre[2] + half)
    axes.set_box_aspect((1.0, 1.0, 1.0), zoom=0.9)  # a little room for the z label
    axes.tick_params(labelsize=7, pad=1)


def _configurations(robot: Robot | Chain, q: Any) -> list[np.ndarray]:
    """One configuration or several (rows), each validated."""
    if q is None:
        return [configuration(robot, None)]
    try:
        values = np.asarray(q, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError(f"q must be numbers, got {q!r}") from None
    rows = values.reshape(1, -1) if values.ndim == 1 else values
    if rows.ndim != 2 or len(rows) == 0:
        raise ArgumentError(f"q must be one configuration or a list of them, got shape {values.shape}")
    return [configuration(robot, row) for row in rows]


def _format_q(values: np.ndarray) -> str:
    return "q = (" + ", ".join(f"{v:.2f}" for v in values) + ")"


def draw(robot: Robot | Chain, q: Any = None, *, frames: bool | None = None,
         ellipsoids: Sequence[EllipsoidKind] | EllipsoidKind = (), limits: bool = False,
         ellipsoid_scale: float | None = None, view: tuple[float, float] = DEFAULT_VIEW,
         arrow: Sequence[float] | None = None, title: str | None = None,
         size: tuple[float, float] | None = None, prefix: str = "") -> Figure:
    r"""A 3-D drawing of ``robot`` at ``q``: links, joints, frames, and optionally ellipsoids, as a matplotlib figure.

    Parameters
    ----------
    robot : Robot or Chain
    q : sequence of floats, shape (n,) or (k, n), optional
        The configuration (radians and metres), or k of them drawn side by side. Default: zero, or mid-range for a
        joint whose limits exclude zero (:func:`~symjac.drawing.geometry.home_configuration`).
    frames : bool, optional
        Draw every frame's triad labelled {i} (default: up to 8 joints); the base and tool frames are always drawn.
    ellipsoids : "velocity", "force" or both
        The velocity ellipsoid (semi-axes :math:`\sigma_k u_k` of :math:`J_v`) and the force ellipsoid
        (:math:`u_k / \sigma_k`) at the tool point, world coordinates.
    ellipsoid_scale : float, optional
        Metres drawn per unit of the semi-axes (default: the largest is half the reach, at the first configuration).
    limits : bool
        Colour each joint by its distance to its limits.
    view : (azimuth, elevation)
        In degrees.
    arrow : 3-vector, optional
        A direction drawn as an arrow at the tool point of every panel.
    title : str, optional
        The figure's title (default: the robot's name, ``""`` for none); several panels are also titled by their
        configurations.
    size : (width, height) in inches, optional
    prefix : str
        Put before the ids (``gid``) of the artists; with several panels, panel k's ids start ``{prefix}panelk-``.

    Returns
    -------
    matplotlib.figure.Figure
        Not tied to pyplot: save it with ``figure.savefig(path)``; notebooks display it.

    Examples
    --------
    >>> from symjac import load_robot
    >>> figure = draw(load_robot("planar2r"), [0.3, 0.6])
    >>> [artist.get_gid() for artist in figure.axes[0].lines][:4]
    ['links', 'joint-1-axis', 'joint-2-axis', 'frame-0-x']
    """
    configurations = _configurations(robot, q)
    kinds = (ellipsoids,) if isinstance(ellipsoids, str) else tuple(ellipsoids)
    azimuth, elevation = view_angles(view)
    count = len(configurations)
    figure = matplotlib_figure(figsize=size or (4.8 * count, 4.8), layout="constrained")
    drawings: list[ArmDrawing] = []
    reach = None
    for index, values in enumerate(configurations):
        axes = figure.add_subplot(1, count, index + 1, projection="3d")
        drawing = ArmDrawing(axes, robot, frames=frames, ellipsoids=kinds, limits=limits, reach=reach,
                             ellipsoid_scale=ellipsoid_scale if not drawings else None,
                             prefix=prefix if count == 1 else f"{prefix}panel{index + 1}-")
        if drawings:
            drawing.scales = dict(drawings[0].scales)  # panels side by side share one scale
        drawing.update(values)
        reach = drawing.reach
        if arrow is not None:
            drawing.draw_arrow(arrow)
        axes.view_init(elev=elevation, azim=azimuth)
        axes.set_xlabel("x (m)")
        axes.set_ylabel("y (m)")
        axes.set_zlabel("z (m)")
        if count > 1:
            axes.set_title(_format_q(values), fontsize=9)
        drawings.append(drawing)
    everything = np.concatenate([d.points() for d in drawings])
    if arrow is not None:
        everything = np.concatenate([everything, *[d.pose.tool[:3, 3][None] + 0.4 * (reach or 1.0)
                                                    * np.asarray(arrow, float)[None] / np.linalg.norm(arrow)
                                                    for d in drawings if d.pose is not None]])
    for drawing in drawings:
        equal_axes(drawing.axes, everything, 0.1 * (reach or 1.0))
    if title != "":
        figure.suptitle(title if title is not None else as_chain(robot).robot.name)
    return figure


def view_angles(view: Sequence[float]) -> tuple[float, float]:
    """``(azimuth, elevation)`` in degrees as two finite floats, or a clear error."""
    try:
        azimuth, elevation = (float(v) for v in view)
    except (TypeError, ValueError):
        raise ArgumentError(f"view must be (azimuth, elevation) in degrees, got {view!r}") from None
    if not (np.isfinite(azimuth) and np.isfinite(elevation)):
        raise ArgumentError(f"view must be finite, got {view!r}")
    return azimuth, elevation
