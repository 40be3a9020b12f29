r"""Inverse kinematics in one call: the closed form where the geometry has one, else numeric, every solution checked.

:func:`inverse_kinematics` picks the closed form where the arm's geometry has one, else the numeric solver, and
returns every solution checked by forward kinematics.

This is the front end the Python API, ``symjac ik``, the report and ``symjac draw --ik-pose`` share. It sits above
code generation (its numeric solver runs on :func:`~symjac.codegen.numeric_model.numeric_model`, the robot compiled
for numbers) and below the command line.

Each solution is checked against the compiled forward kinematics (not the solver's own), and its position and
orientation errors are reported with it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any, Literal, get_args

import numpy as np

from symjac.analysis.inverse_kinematics.numeric import seed_bounds, solve_numeric
from symjac.analysis.inverse_kinematics.poses import pose_from_matrix
from symjac.codegen.numeric_model import NumericModel, numeric_model
from symjac.errors import ArgumentError, NoClosedFormError, OrientationNeededError
from symjac.model.robot import Robot
from symjac.solvers.controlled import Controlled, controlled_components, coordinate_joints

__all__ = ["METHODS", "InverseKinematicsResult", "InverseKinematicsSolution", "Method", "inverse_kinematics"]

Method = Literal["auto", "closed_form", "numeric"]
"""How to solve: the closed form where the geometry has one, else numeric (``"auto"``); or one of them."""
METHODS: tuple[str, ...] = get_args(Method)
"""The values of :data:`Method`."""


@dataclass(frozen=True)
class InverseKinematicsSolution:
    r"""One configuration reaching the pose.

    Parameters
    ----------
    q : numpy.ndarray, shape (n,)
        Every joint (coordinate), radians and metres; revolute joints wrapped to (-pi, pi] (or shifted by 2 pi into
        their limits).
    branch : tuple of str
        The branch names along the closed form's steps ("shoulder left", "elbow up", ...); () from the numeric
        solver.
    within_limits : bool
        Whether every joint is within its limits.
    singular : str
        At a singular pose, the continuum this solution stands for ("theta4 + theta6 = 0.73 is fixed; theta4 shown
        at 0"); empty elsewhere.
    position_error, orientation_error : float
        :math:`\|p(q) - p^*\|` in metres and the angle of :math:`R(q) R^{*T}` in radians, from the compiled
        forward kinematics: over the whole pose, also for an arm that controls only part of it.
    continuum_dimension : int
        Numeric solver: 0 for an isolated solution, else ``d``: ``q`` is one sample of a ``d``-dimensional set of
        configurations reaching the pose (``n - rank J`` there; ``singular`` says so in words).
    """

    q: np.ndarray
    branch: tuple[str, ...] = ()
    within_limits: bool = True
    singular: str = ""
    position_error: float = 0.0
    orientation_error: float = 0.0
    continuum_dimension: int = 0


@dataclass(frozen=True)
class InverseKinematicsResult:
    """Every solution found for one pose, how they were found and why that way.

    Parameters
    ----------
    robot : str
        The robot's name.
    pose : numpy.ndarray, shape (4, 4)
        The target: the end of the chain in frame {0}.
    method : "closed_form" or "numeric"
        What solved it.
    why : str
        One sentence: the family and its reasons for a closed form, or why there is none (or why it was not used).
    family : str
        The closed form's family ("spherical wrist", "planar 2R", ...); empty for the numeric solver.
    reasons : tuple of str
        The exact facts that decide the family.
    solutions : tuple of InverseKinematicsSolution
        In the closed form's branch order, or in the order the numeric solver found them.
    outside_limits : int
        Solutions dropped because they leave the joint limits (``within_limits=True``).
    unreachable : str
        Why there is no solution, with how far out the pose is when known; empty when there are solutions.
    distance : float
        How far out (metres) when the closed form knows it; when the numeric solver found nothing, the position
        error of the closest configuration it reached (an upper bound on how far out, not a proof); 0 otherwise.
    controlled : Controlled
        Which pose components the arm sets and which it cannot (:func:`.controlled_components`).
    uncontrolled : str
        For an arm that does not set the whole pose: how far the pose its solutions reach is from the target in
        what it does not set (empty when they agree).
    plan : object
        The closed form's plan (``None`` for the numeric solver): its steps, for the derivation.
    continuum_dimension : int
        Numeric solver: the largest ``continuum_dimension`` of the solutions. When it is not 0 the solutions on a
        continuum (a redundant arm's self-motion, a singular pose's) are samples of it, as many as the starts
        happened to find, not a count of distinct solutions.
    position_alone : bool
        The target was a position alone (3 numbers): ``pose`` holds it with the identity rotation, a stand-in for
        the orientation that the arm does not set and that was not given.
    """

    robot: str
    pose: np.ndarray
    method: Literal["closed_form", "numeric"]
    why: str
    solutions: tuple[InverseKinematicsSolution, ...]
    controlled: Controlled
    family: str = ""
    reasons: tuple[str, ...] = ()
    outside_limits: int = 0
    unreachable: str = ""
    distance: float = 0.0
    uncontrolled: str = ""
    plan: Any = field(default=None, repr=False, compare=False)
    continuum_dimension: int = 0
    position_alone: bool = False

    def __str__(self) -> str:
        """A short summary: how it was solved, then one line per solution (q, branch, notes)."""
        how = f"closed form ({self.family})" if self.method == "closed_form" else "numeric"
        count = len(self.solutions)
        lines = [f"{self.robot}: {count} solution{'s' if count != 1 else ''}, {how}"]
        if self.continuum_dimension:
            lines[0] += f" (samples of a {self.continuum_dimension}-dimensional set of solutions)"
        if self.outside_limits:
            lines[0] += f"; {self.outside_limits} more outside the joint limits (within_limits=False keeps them)"
        for number, solution in enumerate(self.solutions, start=1):
            notes = [", ".join(solution.branch)] if solution.branch else []
            notes += [] if solution.within_limits else ["outside the joint limits"]
            notes += [solution.singular] if solution.singular else []
            q = np.array2string(np.asarray(solution.q, dtype=float), precision=4, suppress_small=True,
                                separator=", ", max_line_width=10_000)
            lines.append(f"  {number}. q = {q}" + (f"  ({'; '.join(notes)})" if notes else ""))
        if self.unreachable:
            lines.append(f"  unreachable: {self.unreachable}")
        if self.uncontrolled:
            lines.append(f"  not set by the arm: {self.uncontrolled}")
        return "\n".join(lines)


def _robot(robot: Robot | str) -> Robot:
    if isinstance(robot, Robot):
        return robot
    if isinstance(robot, str):
        from symjac.model.io import load_robot

        return load_robot(robot)
    raise ArgumentError(f"inverse_kinematics: robot must be a Robot or a robot's name, got {type(robot).__name__}")


def _errors(model: NumericModel, q: np.ndarray, target: np.ndarray) -> tuple[float, float]:
    T = np.asarray(model.fk(np.asarray(q, dtype=float)), dtype=float)
    R = T[:3, :3] @ target[:3, :3].T
    sine = np.linalg.norm([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2.0
    angle = np.arctan2(sine, (np.trace(R) - 1.0) / 2.0)  # accurate near 0, where arccos of the cosine is not
    return float(np.linalg.norm(T[:3, 3] - target[:3, 3])), float(angle)


def _closed_form(robot: Robot, free_joint: int | None, free_value: float | None) -> tuple[Any, str]:
    """The plan and the sentence saying why it applies; :class:`NoClosedFormError` with the reason when none does.

    A redundant arm given ``free_value`` without ``free_joint`` takes the first joint whose value leaves a six-joint
    arm with a closed form.
    """
    from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan

    candidates: list[int | None] = [free_joint]
    if free_joint is None and free_value is not None and robot.n_joints > 6:
        candidates = list(range(1, robot.n_joints + 1))
    first: NoClosedFormError | None = None
    for candidate in candidates:
        try:
            plan = closed_form_plan(robot, free_joint=candidate)
        except NoClosedFormError as error:
            first = first or error
            continue
        return plan, f"closed form ({plan.family}): {'; '.join(plan.reasons)}"
    assert first is not None
    if len(candidates) > 1:
        raise NoClosedFormError(reason=f"{robot.name}: no joint, its value given, leaves a six-joint arm with a "
                                       f"closed form ({first})")
    raise first


def inverse_kinematics(robot: Robot | str, pose: Any, *, method: Method = "auto", seed: Any = None, rng: int = 0,
                       free_value: float | None = None, free_joint: int | None = None, within_limits: bool = True,
                       restarts: int = 8, tolerance: float = 1e-10) -> InverseKinematicsResult:
    r"""Every configuration of ``robot`` whose end of the chain reaches ``pose``, and how they were found.

    Parameters
    ----------
    robot : Robot or str
        The robot, or a name :func:`~symjac.model.io.load_robot` knows.
    pose : array_like, shape (4, 4), (3, 4) or (3,)
        The end of the chain (the tool frame when the robot has one, else frame {n}) in frame {0}, as
        ``numeric_model(robot).fk(q)`` returns it; build one with
        :func:`~symjac.analysis.inverse_kinematics.poses.pose_from_rpy` or ``pose_from_quaternion``. Checked:
        finite, rigid. A position alone (3 numbers) is enough for an arm that sets no orientation of its own (the
        planar 2R, the articulated 3R: ``result.controlled.position_only``); it stands for that position with the
        identity rotation, and the orientation errors are then measured from the identity. Another arm raises
        :class:`~symjac.errors.OrientationNeededError`.
    method : "auto", "closed_form" or "numeric"
        ``"auto"`` (default): the closed form when the geometry has one (decided exactly on the symbolic model),
        else the numeric solver; the result's ``why`` says which and why. ``"closed_form"`` raises
        :class:`~symjac.errors.NoClosedFormError` (saying why) when there is none.
    seed : array_like, shape (n,), optional
        Numeric solver: the first start (then ``restarts`` random ones).
    rng : int
        Numeric solver: the seed of the random starts (the result is deterministic).
    free_value, free_joint : optional
        A 7-joint arm's redundancy parameter: the value of joint number ``free_joint`` (1-based; default the first joint
        whose value leaves a closed form) given as input, so the 6 joints left are solved in closed form. Without
        ``free_value`` such an arm is solved numerically under ``"auto"``.
    within_limits : bool
        Keep only solutions within the joint limits (default); ``False`` keeps all, each flagged.
    restarts, tolerance : int, float
        Numeric solver: random starts, and the error (m and rad) a start must reach.

    Returns
    -------
    InverseKinematicsResult

    Examples
    --------
    >>> from symjac import load_robot, numeric_model
    >>> robot = load_robot("planar3r")
    >>> pose = numeric_model(robot).fk([0.3, 0.5, -0.2])
    >>> result = inverse_kinematics(robot, pose, method="numeric")
    >>> any(np.allclose(s.q, [0.3, 0.5, -0.2]) for s in result.solutions)
    True
    """
    model_robot = _robot(robot)
    joints = coordinate_joints(model_robot, "inverse_kinematics")
    controlled = controlled_components(model_robot)
    target = _target(model_robot, pose, controlled)
    result = _solve(model_robot, joints, controlled, target, method, seed=seed, rng=rng, free_value=free_value,
                    free_joint=free_joint, within_limits=within_limits, restarts=restarts, tolerance=tolerance)
    if _position_alone(pose):  # no orientation was asked for: only the position can differ from the target
        missed = max((s.position_error for s in result.solutions), default=0.0)
        uncontrolled = "" if missed < 1e-9 else (f"the arm sets {controlled.sets} only: the target position "
                                                 f"differs from the one it reaches by {missed:.6g}")
        result = dataclasses.replace(result, uncontrolled=uncontrolled, position_alone=True)
    return result


def _solve(model_robot: Robot, joints: list[int], controlled: Controlled, target: np.ndarray, method: Method, *,
           seed: Any, rng: int, free_value: float | None, free_joint: int | None, within_limits: bool,
           restarts: int, tolerance: float) -> InverseKinematicsResult:
    """:func:`inverse_kinematics` once the robot and the target are checked."""
    if method not in METHODS:
        raise ArgumentError(f"inverse_kinematics: method must be one of {', '.join(METHODS)}, got {method!r}")
    n = model_robot.n_coordinates
    if free_joint is not None and (isinstance(free_joint, bool) or not isinstance(free_joint, int)
                                   or not 1 <= free_joint <= n):
        raise ArgumentError(f"inverse_kinematics: free_joint is a joint number, 1 to {n} for {model_robot.name}, "
                            f"got {free_joint!r}")
    model = numeric_model(model_robot)
    plan: Any = None
    why = ""
    none: NoClosedFormError | None = None  # why there is no closed form, the cause of a refused free_value
    if method != "numeric":
        try:
            plan, why = _closed_form(model_robot, free_joint, free_value)
        except NoClosedFormError as error:
            if method == "closed_form":  # the analysis's reason, then what to pass in Python (the CLI its options)
                given = free_value is None and n > 6 and _first_given_joint(model_robot)
                how = f"{'without free_value, ' if free_value is not None else ''}method='auto' or 'numeric'"
                hint = (f"; a redundant arm's closed form takes one joint's value: free_value=V (joint {given}'s, "
                        "or free_joint=K for joint K)" if given else _numeric_hint(str(error), how))
                raise NoClosedFormError(reason=f"{error}{hint}") from error
            why, none = f"numeric, as there is no closed form: {error}", error
        if plan is not None and plan.free_joint is not None and free_value is None:
            if method == "closed_form":
                raise ArgumentError(f"inverse_kinematics: {model_robot.name} is redundant; its closed form takes "
                                    f"joint {plan.free_joint} as given: pass free_value")
            plan, why = None, (f"numeric: the closed form takes joint {plan.free_joint} as given and no value of "
                               "it was given")
    if free_value is not None and (plan is None or plan.free_joint is None):
        reason = why.removeprefix("numeric, as there is no closed form: ")
        instead = ("its closed form takes no joint as given" if plan is not None
                   else "the numeric method was asked for" if method == "numeric" else f"there is none: {reason}")
        raise ArgumentError(f"inverse_kinematics: the free value (a given joint's value) applies to a redundant "
                            f"arm's closed form only, and for {model_robot.name} {instead}") from none
    if plan is not None:
        return _from_plan(model_robot, model, plan, target, why, controlled, free_value, within_limits, joints)
    why = why or "numeric: asked for"
    if model_robot.coupling is not None:
        raise ArgumentError(f"inverse_kinematics: {model_robot.name}'s joints are coupled and the numeric solver works "
                            f"joint by joint ({why})")
    return _numeric(model_robot, model, target, why, controlled, seed=seed, rng=rng, restarts=restarts,
                    tolerance=tolerance, within_limits=within_limits)


def _numeric_hint(reason: str, how: str) -> str:
    """After why there is no closed form: how to solve numerically, ``how`` in the words of the front end."""
    return f" ({how})" if reason.endswith("use the numeric solver") else f"; the numeric solver solves it: {how}"


def _first_given_joint(robot: Robot) -> int | None:
    """The first joint (from 1) whose value, given, leaves a redundant arm with a closed form; None when none does."""
    from symjac.analysis.inverse_kinematics.closed_form import closed_form_plan

    for joint in range(1, robot.n_coordinates + 1):
        try:
            closed_form_plan(robot, free_joint=joint)
        except NoClosedFormError:
            continue
        return joint
    return None


def _position_alone(pose: Any) -> bool:
    try:
        return not isinstance(pose, str) and np.shape(pose) == (3,)
    except ValueError:  # ragged: not a position (pose_from_matrix says what it is)
        return False


def _target(robot: Robot, pose: Any, controlled: Controlled) -> np.ndarray:
    """The checked 4 x 4 target: ``pose`` as given, or a position alone for an arm that sets no orientation."""
    if not _position_alone(pose):
        return pose_from_matrix(pose)
    if not controlled.position_only:
        raise OrientationNeededError(f"inverse_kinematics: {robot.name} sets {controlled.sets}, so a position "
                                     "alone is not a pose for it: give a 4 x 4 pose (pose_from_rpy, "
                                     "pose_from_quaternion)")
    x, y, z = pose
    return pose_from_matrix([[1.0, 0.0, 0.0, x], [0.0, 1.0, 0.0, y], [0.0, 0.0, 1.0, z]], name="position")


def _from_plan(robot: Robot, model: NumericModel, plan: Any, target: np.ndarray, why: str, controlled: Controlled,
               free_value: float | None, within_limits: bool, joints: list[int]) -> InverseKinematicsResult:
    from symjac.analysis.inverse_kinematics.closed_form import solve_plan

    solved = solve_plan(plan, target, free_value=free_value)
    solutions = []
    for s in solved.solutions:
        q = np.asarray(s.q, dtype=float)[joints]  # a coupled arm's coordinates: the joints that are coordinates
        solutions.append(InverseKinematicsSolution(q, tuple(s.branch), bool(s.within_limits), s.singular,
                                                   *_errors(model, q, target)))
    kept = tuple(s for s in solutions if s.within_limits or not within_limits)
    unreachable = solved.unreachable
    if not kept and solutions:
        unreachable = f"all {len(solutions)} solutions leave the joint limits"
    return InverseKinematicsResult(robot.name, target, "closed_form", why, kept, controlled, plan.family,
                                   tuple(plan.reasons), len(solutions) - len(kept), unreachable,
                                   float(solved.distance), solved.uncontrolled, plan)


def _numeric(robot: Robot, model: NumericModel, target: np.ndarray, why: str, controlled: Controlled, *, seed: Any,
             rng: int, restarts: int, tolerance: float, within_limits: bool) -> InverseKinematicsResult:
    n = robot.n_coordinates
    if seed is not None:
        seed = np.asarray(seed, dtype=float)
        if seed.shape != (n,) or not np.all(np.isfinite(seed)):
            raise ArgumentError(f"inverse_kinematics: seed must be {n} finite numbers for {robot.name}, got "
                                f"{np.asarray(seed).tolist()}")
    weight = 0.0 if controlled.position_only else 1.0
    found = solve_numeric(robot, target, model, seed=seed, rng=rng, restarts=restarts, tolerance=tolerance,
                          orientation_weight=weight, respect_limits=within_limits)
    lower, upper = seed_bounds(robot)
    limited = [joint.limits is not None and not joint.continuous for joint in robot.joints]
    solutions = []
    for s in found:
        inside = all(not bounded or lo - 1e-9 <= value <= hi + 1e-9
                     for value, lo, hi, bounded in zip(s.q, lower, upper, limited, strict=True))
        solutions.append(InverseKinematicsSolution(np.asarray(s.q, dtype=float), (), inside, _sample_words(s, n),
                                                   *_errors(model, s.q, target), s.continuum_dimension))
    unreachable, distance = "", 0.0
    if not solutions:
        closest = found.closest
        distance = float("nan") if closest is None else closest.position_error
        how_far = "" if closest is None else (
            f"; the closest configuration reached is {closest.position_error:.3g} m and "
            f"{math.degrees(closest.orientation_error):.3g} degrees away" + (
                " (the orientation was not asked for)" if controlled.position_only else ""))
        unreachable = (f"none of the numeric solver's {restarts + (seed is not None)} or more starts converged: no "
                       f"solution found{how_far}; the pose is probably out of reach (a numeric search proves "
                       "nothing)")
    uncontrolled = ""
    if solutions and controlled.position_only and solutions[0].orientation_error > 1e-6:
        uncontrolled = (f"the orientation reached differs from the target's by {solutions[0].orientation_error:.4g} "
                        "rad (the arm does not set it)")
    return InverseKinematicsResult(robot.name, target, "numeric", why, tuple(solutions), controlled,
                                   unreachable=unreachable, distance=distance, uncontrolled=uncontrolled,
                                   continuum_dimension=max((s.continuum_dimension for s in solutions), default=0))


def _sample_words(solution: Any, n: int) -> str:
    """The numeric solution's continuum in words (empty when it is isolated)."""
    d = solution.continuum_dimension
    return "" if not d else (f"one sample of a {d}-dimensional set of configurations reaching this pose (the "
                             f"Jacobian has rank {n - d} for {n} joints here)")
