r"""Which components of a pose an arm sets, and which it cannot: :func:`controlled_components`.

Read from the Jacobian :math:`J = [J_v; J_\omega]` in frame {0} at the end of the chain, at a few random
configurations (generic ones: a singular configuration has measure zero): a row that is zero at all of them is a
component no joint moves (a planar arm's z and its rotations about x and y), fixed by the geometry; the rank of
:math:`J` is how many components the arm sets independently. When the rank of :math:`J` equals that of :math:`J_v`
(and is below 6), the arm places its end point and the orientation follows from the position (the planar 2R arm,
the articulated 3R arm): the target's orientation is then not asked for.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from symjac.analysis.inverse_kinematics.numeric import seed_bounds
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import ArgumentError
from symjac.model.robot import Robot

__all__ = ["COMPONENTS", "Controlled", "controlled_components", "coordinate_bounds", "coordinate_joints"]

COMPONENTS = ("x", "y", "z", "the rotation about x", "the rotation about y", "the rotation about z")
"""The six pose components, as the Jacobian's rows (frame {0}): position, then rotation."""

SAMPLES = 3
"""Random configurations the Jacobian is read at."""


@dataclass(frozen=True)
class Controlled:
    """What the arm sets of a pose.

    Parameters
    ----------
    rank : int
        How many pose components the arm sets independently (the generic rank of its Jacobian, at most 6).
    fixed : tuple of int
        The components (indices into :data:`COMPONENTS`) no joint moves: fixed by the geometry.
    position_only : bool
        The arm sets its end point only (rank below 6 and equal to the position rows'): the orientation follows.
    """

    rank: int
    fixed: tuple[int, ...]
    position_only: bool

    @property
    def whole_pose(self) -> bool:
        """Whether the arm sets every component (rank 6)."""
        return self.rank == 6

    @property
    def sets(self) -> str:
        """The components it sets, in words: ``"the whole pose"``, ``"x, y and the rotation about z"``."""
        if self.whole_pose:
            return "the whole pose"
        free = [COMPONENTS[k] for k in range(3 if self.position_only else 6) if k not in self.fixed]
        words = _joined(free)
        return words if len(free) == self.rank else f"{self.rank} independent combinations of {words}"

    @property
    def not_set(self) -> str:
        """The components it does not set, in words, with why; empty for the whole pose."""
        if self.whole_pose:
            return ""
        parts = []
        fixed = [COMPONENTS[k] for k in self.fixed]
        if fixed:
            parts.append(f"{_joined(fixed)} (fixed by the arm's geometry)")
        if self.position_only:
            parts.append("the orientation (it follows from the position)")
        return "; ".join(parts) or "the combinations the rank leaves out"


def _joined(words: list[str]) -> str:
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def coordinate_joints(robot: Robot, where: str) -> list[int]:
    """The joint (0-based) each coordinate is, in order: all of them without a coupling.

    A coupled robot whose coordinates are some of its joint variables (the palletizer's theta1, theta2, theta3,
    theta5) gives those joints; one whose coordinates are new symbols is refused in one line naming ``where``.
    """
    variables = list(robot.joint_variables)
    if robot.coupling is None:
        return list(range(len(variables)))
    if not all(symbol in variables for symbol in robot.q):
        raise ArgumentError(f"{where}: {robot.name}'s coordinates are not among its joint variables; inverse "
                            "kinematics of such a coupled arm is not supported")
    return [variables.index(symbol) for symbol in robot.q]


def coordinate_bounds(robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    """Where each coordinate is drawn from: its joint's seed bounds (limits, +-pi or +-1 when free)."""
    lower, upper = seed_bounds(robot)
    joints = coordinate_joints(robot, "coordinate_bounds")
    return lower[joints], upper[joints]


def controlled_components(robot: Robot) -> Controlled:
    """The pose components ``robot`` sets (at its end of the chain, frame {0}), from its Jacobian at random points.

    Examples
    --------
    >>> from symjac import load_robot
    >>> planar = controlled_components(load_robot("planar2r"))
    >>> planar.sets, planar.not_set
    ('x and y', "z (fixed by the arm's geometry); the orientation (it follows from the position)")
    >>> controlled_components(load_robot("puma560")).sets
    'the whole pose'
    """
    model = numeric_model(robot)
    lower, upper = coordinate_bounds(robot)
    generator = np.random.default_rng(46)
    samples = [np.asarray(model.jacobian(generator.uniform(lower, upper)), dtype=float) for _ in range(SAMPLES)]
    scale = max(1.0, max(float(np.abs(J).max()) for J in samples))
    fixed = tuple(k for k in range(6) if all(np.abs(J[k]).max() <= 1e-9 * scale for J in samples))
    rank = max(int(np.linalg.matrix_rank(J, tol=1e-8 * scale)) for J in samples)
    position = max(int(np.linalg.matrix_rank(J[:3], tol=1e-8 * scale)) for J in samples)
    position_only = rank < 6 and rank == position
    if position_only:  # the rotation rows follow: only position rows count as fixed
        fixed = tuple(k for k in fixed if k < 3)
    return Controlled(rank, fixed, position_only)
