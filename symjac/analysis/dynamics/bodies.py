r"""What the dynamics reads from a chain: each link's body and each joint's axis, in the link's own frame {k}.

Link k is the body moved by joint k, with its frame {k} (:attr:`Robot.inertials <symjac.model.robot.Robot>`:
mass, centre of mass :math:`{}^kc_k` and tensor :math:`{}^kI_k` about the centre, axes of {k}). Joint k turns about,
or slides along, the axis :math:`z_a` through the origin of frame {a}: {k-1} in the standard DH convention, {k} in the
modified and general ones (:meth:`Chain.axis_frame <symjac.kinematics.chain.Chain.axis_frame>`). Written in {k}, the
axis is :math:`{}^kz_a` and the origin of {k} lies :math:`r = {}^kp_{ak}` from the axis point (zero unless the
axis frame is {k-1}).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeVar

import sympy as sp

from symjac.errors import ImpossibleInertiaError, NoInertialDataError, ResultTooLargeError
from symjac.kinematics.chain import Chain
from symjac.kinematics.coupling import coordinate_bases
from symjac.model.inertia import Inertial, inertial_problem
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import has_intermediates, named, presented
from symjac.symbolic.simplify import printed_ops, simplify_matrix
from symjac.symbolic.size import limit_lowered

T = TypeVar("T")

__all__ = ["JointAxis", "exact_or_nested", "joint_axis", "laid_out", "laid_out_from_first_basis", "link_bodies",
           "result_bases", "tidy"]


def link_bodies(chain: Chain) -> tuple[Inertial, ...]:
    """The inertial data of links 1..n; an error names every link that has none.

    Examples
    --------
    >>> from symjac import robot_from_mapping
    >>> from symjac.kinematics.chain import chain_of
    >>> arm = robot_from_mapping({"name": "arm", "convention": "standard",
    ...                           "joints": [{"type": "revolute", "a": 1}, {"type": "revolute", "a": 1}]})
    >>> link_bodies(chain_of(arm))
    Traceback (most recent call last):
    ...
    symjac.errors.NoInertialDataError: arm: links 1, 2 have no inertial data (mass, centre of mass, inertia); ...
    """
    robot = chain.robot
    inertials = robot.inertials  # one entry per link (None where unknown)
    # a file's own names where it has them (URDF, MJCF): link k is the one its joint k moves
    missing = [f"{k} (moved by joint {joint.name})" if joint.name else str(k)
               for k, (joint, inertial) in enumerate(zip(robot.joints, inertials, strict=True), start=1)
               if inertial is None]
    if missing:
        which = f"link {missing[0]} has" if len(missing) == 1 else f"links {', '.join(missing)} have"
        raise NoInertialDataError(
            f"{robot.name}: {which} no inertial data (mass, centre of mass, inertia); give them in the robot file's "
            f"[joints.inertial] tables or the URDF <inertial> elements, or use symbolic ones "
            f"(symjac.model.inertial_parameters.with_symbolic_inertials)")
    for k, (joint, inertial) in enumerate(zip(robot.joints, inertials, strict=True), start=1):
        problem = None if inertial is None or inertial.keep_impossible else inertial_problem(inertial, robot.defaults)
        if problem is not None:
            which = f"link {k} (moved by joint {joint.name})" if joint.name else f"link {k}"
            raise ImpossibleInertiaError(
                f"{robot.name}: {which}: {problem}, which no rigid body has; correct the data, or keep them "
                f"knowingly with keep_impossible = true in the link's inertial table (Inertial.keep_impossible)")
    return tuple(inertial for inertial in inertials if inertial is not None)


@dataclass(frozen=True)
class JointAxis:
    r"""Joint k's axis in frame {k}: direction :math:`{}^kz_a` and the origin of {k} seen from the axis, :math:`r`."""

    z: sp.ImmutableMatrix
    r: sp.ImmutableMatrix
    revolute: bool


def joint_axis(chain: Chain, k: int) -> JointAxis:
    """The axis of joint ``k`` (1-based) written in frame {k} (module docstring)."""
    a = chain.axis_frame(k)
    z = sp.ImmutableMatrix(chain.rotation(k, a)[:, 2])
    r = sp.ImmutableMatrix.zeros(3, 1) if a == k else sp.ImmutableMatrix(-chain.transform(k, a)[:3, 3])
    return JointAxis(z, r, chain.robot.joints[k - 1].is_revolute)


def tidy(chain: Chain, vector: sp.MatrixBase, frame: int, simplify: bool) -> sp.ImmutableMatrix:
    """A small per-link quantity in compact form (trig normal form in ``frame``'s angle basis), or as it is.

    Each step of a recursion is simplified as it is formed, so that vanishing terms are gone before the next link
    multiplies them out. One basis per frame: the alternatives only shorten a few entries, and each costs a whole
    layout (with them the PUMA 560's torques took 67 s instead of 29 s, for the same final size). A nested chain
    (generic geometry, :mod:`symjac.kinematics.generic`) has no textbook form: each entry is named instead
    (:func:`~symjac.symbolic.nested.named`), so the next link multiplies names and nothing grows.
    """
    if chain.nested:
        return sp.ImmutableMatrix(sp.Matrix(vector).applyfunc(named))
    if not simplify or all(entry.is_number for entry in vector):
        return sp.ImmutableMatrix(vector)
    return sp.ImmutableMatrix(simplify_matrix(vector, chain.angle_basis(frame)))


def result_bases(chain: Chain) -> tuple[AngleBasis, ...]:
    r"""The angle bases of results that belong to no frame (torques, M, C, g, energies): those of {0} and alternatives.

    These are the bases of frame {0} (:meth:`Chain.angle_bases <symjac.kinematics.chain.Chain.angle_bases>`), which
    measure each group of parallel joints from either end and from the frames next to {0}: :math:`c_2` and
    :math:`c_{12}` of a planar arm, :math:`c_{23}` of the PUMA. Every frame's bases (``all_angle_bases``) add, on arms
    without parallel joints, only sign-flipped copies of the same angles, and each costs a whole layout (16 bases
    took most of the PUMA's Newton-Euler torques).
    """
    if chain.robot.coupling is not None:
        # in the coordinates: a basis of the joints' own angles would bring a coupled joint's variable back
        # (theta2 for theta1 + theta2 when theta2 = 2 theta1)
        return tuple(coordinate_bases(chain, 0))
    return chain.angle_bases(0)


def laid_out(chain: Chain, matrix: sp.MatrixBase, simplify: bool) -> sp.ImmutableMatrix:
    """A whole result as people get it: compact in :func:`result_bases`, or, for a nested chain, presented.

    A nested result is written out when that stays small, else kept with its intermediates
    (:func:`~symjac.symbolic.nested.presented`).
    """
    if chain.nested or has_intermediates(matrix):
        return presented(sp.ImmutableMatrix(sp.Matrix(matrix).applyfunc(named)))  # type: ignore[no-any-return]
    return sp.ImmutableMatrix(simplify_matrix(matrix, result_bases(chain)) if simplify else matrix)


def laid_out_from_first_basis(chain: Chain, entries: list[sp.Expr]) -> sp.ImmutableMatrix:
    """:func:`laid_out` of a column whose entries are already laid out in the first of :func:`result_bases`.

    Each entry is written in every other basis too and the shortest form kept (the first basis wins ties), as
    :func:`~symjac.symbolic.simplify.simplify_matrix` does with several bases; the first basis is not done again.
    """
    best = list(entries)
    ops = [printed_ops(entry) for entry in best]
    for basis in result_bases(chain)[1:]:
        for index, candidate in enumerate(simplify_matrix(sp.Matrix(entries), basis)):
            cost = printed_ops(candidate)
            if cost < ops[index]:
                best[index], ops[index] = candidate, cost
    return sp.ImmutableMatrix(best)


def exact_or_nested(chain: Chain, derive: Callable[[Chain], T]) -> T:
    """``derive(chain)``, or, when its compact form would be too large to write out, ``derive`` on the nested twin.

    As forward kinematics does (:attr:`Chain.nested_twin <symjac.kinematics.chain.Chain.nested_twin>`): the result
    then comes with named intermediates instead of being refused.
    """
    try:
        return derive(chain)
    except ResultTooLargeError:
        if chain.nested or limit_lowered():
            raise
        return derive(chain.nested_twin)
