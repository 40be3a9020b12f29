r"""What each representation *is*: its name, its coordinates, and the one registry that finds it by name.

Every representation is a value (a frozen dataclass); the symbolic maps (:mod:`.maps`) and the numeric extraction
(:mod:`.extraction`) dispatch on its type, so nothing anywhere switches on a name.

Euler and Tait-Bryan angles are one type, :class:`EulerConvention`, covering all 24 conventions:

* **intrinsic** ``EulerConvention("zyz")``, named ``"zyz"``: rotations about the axes of the *moving* frame, so the
  named axes multiply left to right, :math:`R = R_z(\alpha) R_y(\beta) R_z(\gamma)`;
* **extrinsic** ``EulerConvention("zyz", extrinsic=True)``, named ``"zyz_extrinsic"``: rotations about the *fixed*
  axes in the order named, so they multiply right to left, :math:`R = R_z(\gamma) R_y(\beta) R_z(\alpha)`. The
  extrinsic x-y-z convention is roll-pitch-yaw and keeps its name ``"rpy"`` and its coordinates
  :math:`(\phi, \theta, \psi)` (``"xyz_extrinsic"`` is accepted for it too).

Hence extrinsic ``abc`` at :math:`(\alpha, \beta, \gamma)` is intrinsic ``cba`` at :math:`(\gamma, \beta, \alpha)`.

Examples
--------
>>> representation("rpy") == EulerConvention("xyz", extrinsic=True)
True
>>> EulerConvention("zxz", extrinsic=True).name
'zxz_extrinsic'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal, overload

import sympy as sp

from symjac.errors import RepresentationError

__all__ = [
    "AXIS_ORDERS",
    "EULER_CONVENTIONS",
    "EULER_ORDERS",
    "POSITIONS",
    "REGISTRY",
    "REPRESENTATIONS",
    "AxisAngle",
    "Cartesian",
    "Cylindrical",
    "DirectionCosines",
    "EulerConvention",
    "Orientation",
    "OrientationSpec",
    "Position",
    "PositionSpec",
    "Quaternion",
    "Representation",
    "RepresentationSingularity",
    "Spherical",
    "coordinates",
    "representation",
]

AXIS_ORDERS: tuple[str, ...] = (
    "zyz", "zxz", "xyx", "xzx", "yxy", "yzy",  # proper Euler angles: first axis = last axis
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx",  # Tait-Bryan angles: three different axes
)
"""The twelve axis sequences with no axis repeated twice in a row, in the order the names have always been listed."""

EXTRINSIC_SUFFIX = "_extrinsic"


def _real(*names: str, nonnegative: tuple[str, ...] = ()) -> tuple[sp.Symbol, ...]:
    return tuple(sp.Symbol(name, real=True, nonnegative=True) if name in nonnegative else sp.Symbol(name, real=True)
                 for name in names)


@dataclass(frozen=True)
class EulerConvention:
    r"""One of the 24 Euler / Tait-Bryan conventions: three rotations about ``axes``, moving or fixed.

    .. math::
        R_{\text{intrinsic } abc}(\alpha, \beta, \gamma) = R_a(\alpha) R_b(\beta) R_c(\gamma), \qquad
        R_{\text{extrinsic } abc}(\alpha, \beta, \gamma) = R_c(\gamma) R_b(\beta) R_a(\alpha)

    Parameters
    ----------
    axes : str
        Three letters from x, y, z, no letter twice in a row (``"zyz"``, ``"xyz"``, ...), in the order the rotations
        are applied.
    extrinsic : bool
        False: about the moving axes (intrinsic, the default); True: about the fixed axes.

    Examples
    --------
    >>> EulerConvention("zyx").name, EulerConvention("zyx", extrinsic=True).name
    ('zyx', 'zyx_extrinsic')
    >>> EulerConvention("xyz", extrinsic=True).coordinates
    (phi, theta, psi)
    """

    axes: str
    extrinsic: bool = False

    kind: ClassVar[Literal["orientation"]] = "orientation"

    def __post_init__(self) -> None:
        if self.axes not in AXIS_ORDERS:
            raise RepresentationError(f"Euler axes must be one of {', '.join(AXIS_ORDERS)}, got {self.axes!r}")

    @property
    def is_rpy(self) -> bool:
        """Roll-pitch-yaw: the extrinsic x-y-z convention, which keeps its own name and coordinate names."""
        return self.extrinsic and self.axes == "xyz"

    @property
    def name(self) -> str:
        """``"zyz"`` (intrinsic), ``"zyz_extrinsic"`` (extrinsic), ``"rpy"`` (extrinsic x-y-z)."""
        if self.is_rpy:
            return "rpy"
        return self.axes + EXTRINSIC_SUFFIX if self.extrinsic else self.axes

    @property
    def coordinates(self) -> tuple[sp.Symbol, ...]:
        """The angles in the order the rotations are applied: (alpha, beta, gamma), or (phi, theta, psi) for rpy."""
        return _real("phi", "theta", "psi") if self.is_rpy else _real("alpha", "beta", "gamma")

    @property
    def is_proper(self) -> bool:
        r"""Proper Euler angles (first axis = last axis, :math:`\beta \in [0, \pi]`) rather than Tait-Bryan."""
        return self.axes[0] == self.axes[2]

    @property
    def factors(self) -> tuple[tuple[Literal["x", "y", "z"], int], ...]:
        """The rotation factors in matrix-product order: (axis, index of its coordinate)."""
        order = [(axis, index) for index, axis in enumerate(self.axes)]
        return tuple(reversed(order) if self.extrinsic else order)  # type: ignore[arg-type]

    @property
    def leftmost(self) -> int:
        """Index of the coordinate of the leftmost factor: the angle set to 0 at gimbal lock."""
        return self.factors[0][1]


@dataclass(frozen=True)
class DirectionCosines:
    r"""The nine entries of :math:`R`, row by row :math:`(r_{11}, r_{12}, \ldots, r_{33})`."""

    kind: ClassVar[Literal["orientation"]] = "orientation"
    name: ClassVar[str] = "direction_cosines"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real(*(f"r{i}{j}" for i in range(1, 4) for j in range(1, 4)))


@dataclass(frozen=True)
class Quaternion:
    r"""Euler parameters (unit quaternion) :math:`(\eta, \epsilon_x, \epsilon_y, \epsilon_z)`, :math:`\eta \ge 0`."""

    kind: ClassVar[Literal["orientation"]] = "orientation"
    name: ClassVar[str] = "quaternion"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real("eta", "epsilon_x", "epsilon_y", "epsilon_z")


@dataclass(frozen=True)
class AxisAngle:
    r"""Equivalent axis-angle :math:`(k_x, k_y, k_z, \vartheta)`: unit axis, angle in :math:`[0, \pi]`."""

    kind: ClassVar[Literal["orientation"]] = "orientation"
    name: ClassVar[str] = "axis_angle"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real("k_x", "k_y", "k_z", "vartheta")


@dataclass(frozen=True)
class Cartesian:
    """Cartesian position :math:`(x, y, z)`."""

    kind: ClassVar[Literal["position"]] = "position"
    name: ClassVar[str] = "cartesian"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real("x", "y", "z")


@dataclass(frozen=True)
class Spherical:
    r"""Spherical position :math:`(r, \theta_s, \phi_s)`: polar angle from the z-axis, then azimuth."""

    kind: ClassVar[Literal["position"]] = "position"
    name: ClassVar[str] = "spherical"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real("r", "theta_s", "phi_s", nonnegative=("r",))


@dataclass(frozen=True)
class Cylindrical:
    r"""Cylindrical position :math:`(\rho, \phi_c, z)`."""

    kind: ClassVar[Literal["position"]] = "position"
    name: ClassVar[str] = "cylindrical"
    coordinates: ClassVar[tuple[sp.Symbol, ...]] = _real("rho", "phi_c", "z", nonnegative=("rho",))


OrientationSpec = EulerConvention | DirectionCosines | Quaternion | AxisAngle
PositionSpec = Cartesian | Spherical | Cylindrical
Representation = OrientationSpec | PositionSpec
Orientation = str | OrientationSpec
"""An orientation representation: its name (one of :data:`REPRESENTATIONS`) or its value."""
Position = str | PositionSpec
"""A position representation: its name (one of :data:`POSITIONS`) or its value."""

EULER_CONVENTIONS: tuple[EulerConvention, ...] = tuple(
    EulerConvention(axes, extrinsic) for extrinsic in (False, True) for axes in AXIS_ORDERS
)
"""All 24 Euler / Tait-Bryan conventions: the 12 intrinsic ones, then the 12 extrinsic ones."""

_ALL: tuple[Representation, ...] = (
    *EULER_CONVENTIONS, DirectionCosines(), Quaternion(), AxisAngle(), Cartesian(), Spherical(), Cylindrical(),
)
REGISTRY: dict[str, Representation] = {spec.name: spec for spec in _ALL}
"""Every representation by its name: the one place a name is turned into a representation."""

ALIASES: dict[str, str] = {"xyz" + EXTRINSIC_SUFFIX: "rpy"}
"""Other accepted spellings: the systematic name of roll-pitch-yaw."""

REPRESENTATIONS: tuple[str, ...] = tuple(name for name, spec in REGISTRY.items() if spec.kind == "orientation")
"""Names of the orientation representations: the 24 Euler-angle conventions (roll-pitch-yaw among them),
direction cosines, quaternions and axis-angle."""
EULER_ORDERS: tuple[str, ...] = tuple(spec.name for spec in EULER_CONVENTIONS if not spec.extrinsic)
"""Names of the twelve intrinsic Euler-angle orders (``"zyz"``, ``"xyz"``, ...)."""
POSITIONS: tuple[str, ...] = tuple(name for name, spec in REGISTRY.items() if spec.kind == "position")
"""Names of the position representations: Cartesian, spherical, cylindrical."""


@overload
def representation(name: str | Representation, kind: Literal["orientation"]) -> OrientationSpec: ...
@overload
def representation(name: str | Representation, kind: Literal["position"]) -> PositionSpec: ...
@overload
def representation(name: str | Representation, kind: None = None) -> Representation: ...


def representation(
    name: str | Representation, kind: Literal["orientation", "position"] | None = None
) -> Representation:
    """The representation called ``name`` (a value is returned as it is), checked to be of ``kind`` if given.

    Examples
    --------
    >>> representation("zyz_extrinsic")
    EulerConvention(axes='zyz', extrinsic=True)
    >>> representation("polar", "position")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    symjac.errors.RepresentationError: unknown position representation 'polar'; choose one of cartesian, ...
    """
    spec = REGISTRY.get(ALIASES.get(name, name)) if isinstance(name, str) else name
    if spec is None or not isinstance(spec, Representation) or (kind is not None and spec.kind != kind):
        allowed = REPRESENTATIONS if kind == "orientation" else POSITIONS if kind == "position" else tuple(REGISTRY)
        raise RepresentationError(f"unknown {kind or ''}{' ' if kind else ''}representation {name!r}; "
                                  f"choose one of {', '.join(allowed)}")
    return spec


def coordinates(name: str | Representation) -> tuple[sp.Symbol, ...]:
    r"""The coordinate symbols of an orientation or position representation, in the order of :math:`x`.

    Examples
    --------
    >>> coordinates("quaternion")
    (eta, epsilon_x, epsilon_y, epsilon_z)
    >>> coordinates("spherical")
    (r, theta_s, phi_s)
    """
    return representation(name).coordinates


@dataclass(frozen=True)
class RepresentationSingularity:
    r"""Where the rate map :math:`E` of one representation does not exist: ``factor`` :math:`= 0`.

    Parameters
    ----------
    representation : str
        The name of the orientation or position representation it belongs to.
    factor : sympy.Expr
        A factor of :math:`\det(\partial x / \partial\,\text{pose})^{-1}`, in the representation's coordinates.
    variable : sympy.Symbol
        The coordinate the condition restricts.
    solutions : tuple of sympy.Expr
        The values of ``variable`` in its range where ``factor`` vanishes.
    cause : str
        What goes wrong there, as a label: ``"gimbal lock"`` (Euler angles), ``"no rotation axis"`` (axis-angle at
        the identity), ``"origin"``, ``"polar axis"`` (spherical) or ``"z axis"`` (cylindrical);
        :func:`symjac.printing.prose.representation_parts` says it in a sentence.
    """

    representation: str
    factor: sp.Expr
    variable: sp.Symbol
    solutions: tuple[sp.Expr, ...]
    cause: str

    def __str__(self) -> str:
        values = " or ".join(str(value) for value in self.solutions)
        return f"{self.factor} = 0 ({self.variable} = {values}): {self.cause}"
