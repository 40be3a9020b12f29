r"""What an arm loses at a singular configuration, as data: a direction it cannot move in, motions that move nothing.

At a singular configuration the Jacobian's left null space holds the Cartesian directions :math:`u` with
:math:`u^T J = 0` (a velocity the arm cannot produce, and by :math:`\tau = J^T F` a wrench it holds with zero joint
torque), and its null space the joint rates :math:`\dot q` with :math:`J \dot q = 0` (a self-motion).
:func:`lost_direction` names each half of :math:`u` by the frame axis it lies along.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from symjac.analysis.singularity.geometry import FrameAxis, Geometry, frame_axes, named_axis, parallel
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.numeric import numeric_at

__all__ = ["DirectionPart", "LostDirection", "SelfMotion", "canonical", "lost_direction"]


@dataclass(frozen=True)
class DirectionPart:
    """The linear or angular half of a lost direction: a unit 3-vector, and the frame axis it lies along if any."""

    unit: tuple[float, float, float]
    axis: FrameAxis | None


@dataclass(frozen=True)
class LostDirection:
    r"""A Cartesian direction :math:`u` the arm cannot move in, with :math:`u^T J = 0` for the analysed rows.

    ``vector`` holds the components on ``rows`` (``v_x .. omega_z``), expressed in ``frame``; ``linear`` and
    ``angular`` are its halves (``None`` when zero); ``radial`` tells a pure translation along the line from the
    origin of frame {0} to the reference point. The same vector is a wrench held with zero joint torque.
    """

    vector: tuple[float, ...]
    rows: tuple[int, ...]
    frame: Frame
    linear: DirectionPart | None
    angular: DirectionPart | None
    radial: bool = False

    @property
    def full(self) -> np.ndarray:
        """The 6-vector ``[v; omega]`` with zeros on the rows not analysed."""
        full = np.zeros(6)
        full[list(self.rows)] = self.vector
        return full


@dataclass(frozen=True)
class SelfMotion:
    r"""Joint rates :math:`\dot q` with :math:`J \dot q = 0`: ``rates[i]`` on joint ``columns[i]`` (0-based).

    A coupled robot's columns are its coordinates, not its joints: ``names`` then gives each column's coordinate
    (``theta5``) so that words do not call coordinate 4 "joint 4"; empty without a coupling.
    """

    rates: tuple[float, ...]
    columns: tuple[int, ...]
    names: tuple[str, ...] = ()


def lost_direction(chain: Chain, rows: tuple[int, ...], frame: Frame, sample: Sequence[float], geometry: Geometry,
                   vector: np.ndarray) -> LostDirection:
    """The lost direction with each half named by the frame axis it lies along, and whether it is radial."""
    axes = frame_axes(chain, sample, frame)
    full = np.zeros(6)
    full[list(rows)] = vector
    halves: list[DirectionPart | None] = []
    for part in (full[:3], full[3:]):
        norm = np.linalg.norm(part)
        if norm < 1e-9:
            halves.append(None)
            continue
        unit = part / norm
        halves.append(DirectionPart((float(unit[0]), float(unit[1]), float(unit[2])), named_axis(unit, axes)))
    # radial: the reach vector from the base to the reference point, expressed in the analysis frame
    reach = numeric_at(chain, chain.rotation(frame, 0), sample) @ geometry.points[0][1]
    radial = bool(np.linalg.norm(full[3:]) < 1e-9 and np.linalg.norm(reach) > 1e-9
                  and parallel(full[:3], reach, 1e-7))
    return LostDirection(tuple(float(x) for x in vector), rows, frame, halves[0], halves[1], radial)


def canonical(vector: np.ndarray) -> np.ndarray:
    """A unit vector with its largest component positive and round-off zeroed."""
    vector = np.where(np.abs(vector) < 1e-12, 0.0, vector)
    return vector if vector[np.argmax(np.abs(vector))] > 0 else -vector
