r"""Forward kinematics of a robot, derived once and cached: :math:`{}^a_bT` between any two frames.

Frames are named by :data:`Frame` values: ``"world"`` (before the base transform), ``0 .. n`` (the DH frames) and
``"tool"`` (after the tool transform). Without a base transform ``"world"`` coincides with {0}; without a tool
transform ``"tool"`` coincides with {n}.

Transforms are built with :func:`symjac.symbolic.transforms.compose` from the elementary motions of the links, so
parallel joints already appear as angle sums. :meth:`Chain.transform` returns these raw structured products (what the
Jacobian methods and code generation start from); :meth:`Chain.simplified_transform` lays them out for people.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from functools import cached_property, lru_cache
from typing import Any, Literal, NamedTuple, TypeVar

import sympy as sp

from symjac.errors import FrameError, ResultTooLargeError
from symjac.kinematics.coupling import COUPLING_LAWS, in_coordinates
from symjac.kinematics.generic import is_generic, numeric_steps
from symjac.model.conventions import joint_forms
from symjac.model.conventions.base import JointForm
from symjac.model.ends import last_frame
from symjac.model.robot import Robot
from symjac.progress import report
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import named, presented
from symjac.symbolic.simplify import simplify_product
from symjac.symbolic.size import limit_lowered
from symjac.symbolic.transforms import Composition, Motion, compose, homogeneous, inverse_motions

Frame = int | Literal["world", "tool"]
"""A frame: ``"world"``, a number from ``0`` to ``n``, or ``"tool"``."""
T = TypeVar("T")

__all__ = ["CHAINS_KEPT", "Chain", "Frame", "MemoKey", "as_chain", "chain_of", "clear_caches", "forward_kinematics"]


class MemoKey(NamedTuple):
    """Where :meth:`Chain.memo` keeps a value: the function that derives it and its normalised arguments.

    Two quantities never collide, because no two functions are the same; see
    :func:`symjac.kinematics.memo.memoized`, which builds these keys.
    """

    function: Callable[..., Any]
    arguments: tuple[Hashable, ...]


class Chain:
    """Symbolic kinematics of one :class:`~symjac.model.robot.Robot`: the one owner of every derived quantity.

    The robot is the immutable model; the chain is its data (the Model/Data split of pinocchio). Transforms, angle
    bases and everything later stages derive from them (Jacobians per frame, point and method, propagations,
    determinants, code generation candidates) are computed once and kept here, through :meth:`memo`; nothing is
    cached anywhere else. Every algorithm takes a chain, or a robot (then :func:`as_chain` finds its chain).

    Examples
    --------
    >>> from symjac import load_robot
    >>> chain = Chain(load_robot("planar2r"))
    >>> chain.simplified_transform(0, 2)[:2, 3]
    Matrix([
    [L1*cos(theta1) + L2*cos(theta1 + theta2)],
    [L1*sin(theta1) + L2*sin(theta1 + theta2)]])
    """

    def __init__(self, robot: Robot, *, nested: bool | None = None):
        self.robot = robot
        self.nested = is_generic(self._forms) if nested is None else nested
        """Whether results are built nested (:mod:`symjac.kinematics.generic`): by default, for generic geometry."""
        self._transforms: dict[tuple[int, int], sp.ImmutableMatrix] = {}
        self._compositions: dict[tuple[int, int], Composition] = {}
        self._simplified: dict[tuple[int, int], sp.ImmutableMatrix] = {}
        self._memo: dict[Hashable, object] = {}
        self._relations: dict[int, tuple[sp.Expr, sp.Expr]] = {}

    def memo(self, key: Hashable, compute: Callable[[], T]) -> T:
        """The value stored under ``key``, computed by ``compute()`` the first time it is asked for.

        Keys are :class:`MemoKey` values (the deriving function and its normalised arguments), built by
        :func:`symjac.kinematics.memo.memoized`. The values are immutable (SymPy immutable matrices, frozen
        dataclasses).
        """
        if key not in self._memo:
            self._memo[key] = compute()
        return self._memo[key]  # type: ignore[return-value]

    # --- frames ------------------------------------------------------------------------------------------

    @property
    def n_joints(self) -> int:
        """Number of joints; the chain's frames are 0..n_joints."""
        return self.robot.n_joints

    @cached_property
    def nested_twin(self) -> Chain:
        """The same robot's chain built nested: public results too large to write out come from it instead."""
        return self if self.nested else Chain(self.robot, nested=True)

    @cached_property
    def joint_chain(self) -> Chain:
        """The chain results are derived on: itself, or for a coupled robot the chain of its joints alone."""
        return self if self.robot.coupling is None else chain_of(self.robot.uncoupled)

    def position(self, frame: Frame) -> int:
        """Index of a frame along the chain: world -1, DH frames 0..n, tool n + 1."""
        if frame == "world":
            return -1
        if frame == "tool":
            return self.n_joints + 1
        if isinstance(frame, int) and not isinstance(frame, bool) and 0 <= frame <= self.n_joints:
            return frame
        raise FrameError(
            f"frame {frame!r} does not exist for {self.robot.name}: use 0..{self.n_joints}, 'world' or 'tool'")

    def frame_name(self, position: int) -> Frame:
        """Inverse of :meth:`position`."""
        return "world" if position == -1 else "tool" if position == self.n_joints + 1 else position

    def axis_frame(self, joint: int) -> int:
        """The frame whose z-axis is the axis of ``joint`` (1-based): {i-1} or {i}.

        It is {i-1} when the link has constant motions after the joint's own (standard DH), else {i} (modified DH,
        general joints): :attr:`~symjac.model.conventions.base.JointForm.axis_at_start`.
        """
        return joint - 1 if self._forms[joint - 1].axis_at_start else joint

    @cached_property
    def _forms(self) -> tuple[JointForm, ...]:
        """Each joint in the internal form (:mod:`symjac.model.conventions`)."""
        return joint_forms(self.robot)

    @cached_property
    def _steps(self) -> list[tuple[Motion | sp.Matrix, ...]]:
        """Motions from frame position k-1 to k, for k = 0 (base), 1..n (links), n+1 (tool)."""
        robot = self.robot
        steps: list[tuple[Motion | sp.Matrix, ...]] = [(robot.base.matrix,) if robot.base else ()]
        steps += [form.motions for form in self._forms]
        steps.append((robot.tool.matrix,) if robot.tool else ())
        return [numeric_steps(step) for step in steps] if self.nested else steps

    # --- transforms ---------------------------------------------------------------------------------------

    def transform(self, source: Frame, target: Frame) -> sp.ImmutableMatrix:
        r"""The raw structured product :math:`{}^{\text{source}}_{\text{target}}T` (pose of target in source)."""
        key = (self.position(source), self.position(target))
        if key not in self._transforms:
            rotation_matrix, position = self._composition(*key).result()
            if self.nested:  # the pending joint rotation, multiplied in just now
                rotation_matrix = rotation_matrix.applyfunc(named)
            self._transforms[key] = sp.ImmutableMatrix(homogeneous(rotation_matrix, position))
        return self._transforms[key]

    def _composition(self, start: int, end: int) -> Composition:
        """The motions from position ``start`` to ``end`` multiplied, continuing the nearest shorter product kept.

        Going out (``end > start``) each step k adds the motions of link k; going in, their inverses in reverse. The
        same product :func:`~symjac.symbolic.transforms.compose` gives for all the motions at once, built one link at a
        time, so that the transforms from one frame to all others cost one link each and share their partial products.
        """
        direction = 1 if end >= start else -1
        reached = end
        while (start, reached) not in self._compositions and reached != start:
            reached -= direction
        composition = self._compositions.get((start, reached), Composition())
        while reached != end:
            reached += direction
            report(f"building frame {{{self.frame_name(reached)}}} of {self.n_joints}")
            step = self._steps[reached] if direction == 1 else inverse_motions(self._steps[reached + 1])
            composition = composition.then(step)
            if self.nested:  # every entry named: the next link multiplies names, so no expression ever grows
                composition = composition.named(named)
            self._compositions[(start, reached)] = composition
        return composition

    def simplified_transform(self, source: Frame, target: Frame) -> sp.ImmutableMatrix:
        """:meth:`transform` in compact textbook form, written in the angle basis of ``source``.

        The link transforms are multiplied on normal forms (:func:`symjac.symbolic.simplify.simplify_product`), so every
        partial product is reduced as it is formed, and a result too large to write out is refused within seconds
        (:class:`~symjac.errors.ResultTooLargeError`) instead of being built.
        """
        key = (self.position(source), self.position(target))
        if self.nested:  # no textbook form: the nested product itself
            return self.transform(source, target)
        if key not in self._simplified:
            start, end = key
            step = 1 if end >= start else -1
            links = [self.transform(self.frame_name(k), self.frame_name(k + step)) for k in range(start, end, step)]
            report(f"simplifying the transform from frame {source} to frame {target}")
            factors = links or [self.transform(source, target)]
            bases = self._one_link_bases(max(key)) if abs(end - start) == 1 else self.angle_bases(source)
            self._simplified[key] = sp.ImmutableMatrix(simplify_product(factors, bases))
        return self._simplified[key]

    def rotation(self, source: Frame, target: Frame) -> sp.ImmutableMatrix:
        r""":math:`{}^{\text{source}}_{\text{target}}R`, raw."""
        return self.transform(source, target)[:3, :3]

    # --- simplification basis -------------------------------------------------------------------------------

    @cached_property
    def parallel_groups(self) -> tuple[tuple[int, ...], ...]:
        """Maximal runs of consecutive joints (1-based) whose axes are parallel or anti-parallel.

        A nested chain is never laid out in angle sums, so each of its joints is a group of its own.
        """
        if self.nested:
            return tuple((i,) for i in range(1, self.n_joints + 1))
        groups: list[list[int]] = [[1]]
        for i in range(1, self.n_joints):
            twist = self._twist_between(i)
            if twist == 0 or abs(twist) == sp.pi:
                groups[-1].append(i + 1)
            else:
                groups.append([i + 1])
        return tuple(tuple(group) for group in groups)

    def _twist_between(self, i: int) -> sp.Expr:
        """The twist between the axes of joints i and i+1: 0 (parallel), pi (anti-parallel) or nan (neither)."""
        return self._relation(i + 1)[0]

    def _z_offset(self, joint: int) -> sp.Expr:
        """The constant turn about z between the axis frames of joint-1 and joint when their axes are parallel.

        DH rows have none (it is in the ``theta`` offset); a general joint's origin and alignments may add one.
        """
        return self._relation(joint)[1]

    def _relation(self, joint: int) -> tuple[sp.Expr, sp.Expr]:
        r"""(twist, z offset) between the axis frames of joints joint-1 and joint.

        With :math:`C` the constant rotation between them (the motions after joint-1's own motion and before
        joint's): parallel axes (:math:`C_{33} = 1`) give :math:`C = R_z(\gamma)`, anti-parallel ones
        :math:`C = R_x(\pi) R_z(\gamma)`; otherwise (also for a symbolic twist) the twist is ``nan`` and no offset
        is used.
        """
        if joint not in self._relations:
            self._relations[joint] = self._new_relation(joint)
        return self._relations[joint]

    def _new_relation(self, joint: int) -> tuple[sp.Expr, sp.Expr]:
        C, _ = compose((*self._forms[joint - 2].after, *self._forms[joint - 1].before))
        c33 = sp.nsimplify(C[2, 2]) if C[2, 2].is_Float else C[2, 2]
        if c33 == 1 or c33 == -1:
            sign = 1 if c33 == 1 else -1
            gamma = sp.atan2(sign * C[1, 0], C[0, 0])
            if gamma.has(sp.atan2, sp.atan) or not gamma.is_number:
                gamma = sp.S.Zero  # not a clean angle: only compactness is lost, the results stay exact
            return (sp.S.Zero if sign == 1 else sp.pi), gamma
        return sp.nan, sp.S.Zero

    def angle_basis(self, frame: Frame) -> AngleBasis:
        r"""The angles results expressed in ``frame`` read best in (see :mod:`symjac.symbolic.simplify`).

        Within a group of parallel joints j..m, let :math:`\Theta_f` be the summed joint angles from j up to frame f
        (:math:`\Theta_{j-1} = 0`; an anti-parallel twist flips the sign of later angles). Relative to a reference
        frame r of the group (``frame`` itself if it is in the group, else the group frame nearest to it) the
        basis angles are :math:`\Theta_f - \Theta_r`: for frame {0} of a planar arm :math:`\theta_1, \theta_{12},
        \theta_{123}`; for its frame {1}, :math:`-\theta_1, \theta_2, \theta_{23}`.
        """
        k = self.position(frame)
        references = [k if g[0] <= k <= g[-1] else (g[0] - 1 if k < g[0] else g[-1]) for g in self.parallel_groups]
        return self._basis(tuple(references))

    def angle_bases(self, frame: Frame) -> tuple[AngleBasis, ...]:
        """:meth:`angle_basis` first, then the bases that measure one parallel group from another of its frames.

        A textbook entry may mix references (the arm of the lecture slides in its tool frame has :math:`s_3` next to
        :math:`L_1 + L_2 c_2 + L_3 c_{23}`); :func:`symjac.symbolic.simplify.simplify_matrix` keeps, per entry, the
        shortest. The other references of a group are its two ends and the frames next to ``frame`` (see
        :func:`_alternative_references`).
        """
        default = self.angle_basis(frame)
        k = self.position(frame)
        references = [k if g[0] <= k <= g[-1] else (g[0] - 1 if k < g[0] else g[-1]) for g in self.parallel_groups]
        bases = [default]
        for index, group in enumerate(self.parallel_groups):
            if sum(self.robot.joints[i - 1].is_revolute for i in group) < 2:
                continue
            for reference in _alternative_references(group, references[index]):
                bases.append(self._basis((*references[:index], reference, *references[index + 1:])))
        return tuple(bases)

    def all_angle_bases(self) -> tuple[AngleBasis, ...]:
        """Every angle basis of every frame, the trivial one (each joint angle with its offset) first.

        Results that belong to no frame (determinant factors, joint rates) are laid out in the shortest of these.
        """
        def compute() -> tuple[AngleBasis, ...]:
            revolute = [joint for joint in self.robot.joints if joint.is_revolute]
            bases = [AngleBasis(tuple(j.variable for j in revolute), tuple(j.angle for j in revolute))]
            for frame in range(self.n_joints + 1):
                bases += [basis for basis in self.angle_bases(frame) if basis not in bases]
            return tuple(bases)

        return self.memo(MemoKey(Chain.all_angle_bases, ()), compute)

    def _one_link_bases(self, position: int) -> tuple[AngleBasis, ...]:
        """The basis of the one link ending at frame position ``position``: its own joint angle, if revolute.

        A link transform depends on no other joint, so a basis of all n angles (and their alternatives) would write
        the same result after n times the work: a 200-joint ``symjac show`` built 200 such bases. The angle is the
        one :meth:`_new_basis` measures from the frame before: the joint angle with its offset, plus the constant
        turn about z from the previous axis when that axis is parallel (general joints), so
        ``cos(theta3 + pi/6)`` stays one cosine.
        """
        joint = self.robot.joints[position - 1] if 1 <= position <= self.n_joints else None
        if joint is None or not joint.is_revolute:
            return (AngleBasis((), ()),)
        group = next(g for g in self.parallel_groups if position in g)
        angle = joint.angle + (self._z_offset(position) if position > group[0] else 0)
        return (AngleBasis((joint.variable,), (angle,)),)

    def _basis(self, references: tuple[int, ...]) -> AngleBasis:
        """The angle basis measuring each parallel group from its reference frame (kept: frames share most)."""
        return self.memo(MemoKey(Chain._new_basis, references), lambda: self._new_basis(references))

    def _new_basis(self, references: tuple[int, ...]) -> AngleBasis:
        joints = self.robot.joints
        variables = tuple(joint.variable for joint in joints if joint.is_revolute)
        angles: list[sp.Expr] = []
        for group, reference in zip(self.parallel_groups, references, strict=True):
            first = group[0]
            cumulative = {first - 1: sp.S.Zero}
            total, sign = sp.S.Zero, 1
            for i in group:
                if i > first and abs(self._twist_between(i - 1)) == sp.pi:
                    sign = -sign
                if i > first:
                    total += sign * self._z_offset(i)
                if joints[i - 1].is_revolute:  # the angle with its offset: cos(theta1 - 1/5) stays one cosine
                    total += sign * joints[i - 1].angle
                cumulative[i] = total
            seen: set[sp.Expr] = set()
            for f in sorted(cumulative):  # one angle per joint-angle combination (a constant offset is not new)
                value = sp.expand(cumulative[f] - cumulative[reference])
                _, varying = value.as_independent(*variables, as_Add=True)
                if varying != 0 and varying not in seen:
                    seen.add(varying)
                    angles.append(value)
        return AngleBasis(variables, _order_like(tuple(angles), variables))


def _alternative_references(group: tuple[int, ...], reference: int) -> list[int]:
    r"""The frames of a parallel group, other than ``reference``, worth measuring its angles from.

    Those are where textbook forms start: either end of the group (:math:`\theta_1, \theta_{12}, \dots` from its
    first frame, relative angles from its last) and the frames next to the reference. A group of up to three
    joints keeps all its frames; a longer run keeps at most five, so laying out an n-joint planar arm costs its
    :math:`O(n^2)` entries times a constant rather than times n (30 joints: 4 bases instead of 31).
    """
    first, last = group[0] - 1, group[-1]
    near = {first, first + 1, last - 1, last, reference - 1, reference + 1}
    return [frame for frame in range(first, last + 1) if frame in near and frame != reference]


def _order_like(angles: tuple[sp.Expr, ...], variables: tuple[sp.Symbol, ...]) -> tuple[sp.Expr, ...]:
    """Sort basis angles by the first joint they involve, so generator order follows the chain (base first)."""
    position = {v: i for i, v in enumerate(variables)}
    def key(angle: sp.Expr) -> tuple[int, int]:
        used = [position[s] for s in angle.free_symbols if s in position]
        return min(used), len(used)

    return tuple(sorted(angles, key=key))


CHAINS_KEPT = 32
"""How many chains :func:`chain_of` keeps (least recently used first out)."""


@lru_cache(maxsize=CHAINS_KEPT)
def chain_of(robot: Robot) -> Chain:
    """The :class:`Chain` of ``robot``, built on first use.

    Robots are immutable and compared by value, so equal robots (the same file loaded twice) share one chain and
    everything derived in it. This is the only registry in symjac; it keeps the :data:`CHAINS_KEPT` most recently
    used chains. Hold a chain yourself (``Chain(robot)``) to control its lifetime exactly.
    """
    return Chain(robot)


def as_chain(robot: Robot | Chain) -> Chain:
    """The chain an algorithm works on: ``robot`` itself if it is a :class:`Chain`, else :func:`chain_of` it."""
    if isinstance(robot, Chain):
        return robot
    if not isinstance(robot, Robot):
        raise TypeError(f"expected a symjac Robot or Chain, got {type(robot).__name__}")
    return chain_of(robot)


def clear_caches() -> None:
    """Forget every chain and so every derived quantity (for cold-start benchmarks, or to free memory)."""
    chain_of.cache_clear()


def forward_kinematics(robot: Robot | Chain, source: Frame = 0, target: Frame | None = None) -> sp.Matrix:
    r"""The pose :math:`{}^{\text{source}}_{\text{target}}T` compact, in the coordinates; default {0} to the end.

    The end (:func:`~symjac.model.ends.last_frame`, the tool frame, else {n}) is where Jacobians and code default.

    >>> from symjac import load_robot
    >>> forward_kinematics(load_robot("planar3r"))[0, 3]  # planar3r has a tool: L3 beyond frame {3}
    L1*cos(theta1) + L2*cos(theta1 + theta2) + L3*cos(theta1 + theta2 + theta3)
    """
    chain = as_chain(robot)
    target = last_frame(chain) if target is None else target
    try:
        T = chain.simplified_transform(source, target)
    except ResultTooLargeError:  # too large written out: nested instead
        if chain.nested or limit_lowered():
            raise
        T = chain.nested_twin.simplified_transform(source, target)
    return presented(in_coordinates(chain, sp.Matrix(T)))


forward_kinematics.coupling_law = COUPLING_LAWS["rates"]  # type: ignore[attr-defined]  # applied above, as memoized
