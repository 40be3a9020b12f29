"""Solution counts at and near singular configurations of the PUMA 560, the IRB 140 and the UR5, against EAIK.

The round trips elsewhere skip EAIK's count where the Jacobian's smallest singular value is below 1e-5. Here the
configurations are singular on purpose: joint 5 at 0 (the wrist), the elbow stretched or folded and the wrist centre
at the shoulder's singular place (roots of det J in joint 3 and in joint 2), each exactly and moved by 1e-8, 1e-7
and 1e-4 in that joint. The comparison, exactly:

- EAIK's solutions are those it returns (least-squares flag or not) whose forward kinematics reaches the pose to
  1e-9; an entry that does not is a failure of EAIK's (it returns a least-squares configuration where it lost a
  branch) and is counted as such, not as a solution.
- Two solutions coincide when every joint differs by less than ``SAME`` = 1e-6 (modulo 2 pi), a joint-space bound
  for the subproblems' merge rule (two angles merge when their half difference is below 3.4e-7 rad; the other joints
  of a merged pair differ by a few times that). Both sides are clustered by it (single linkage); ours must
  moreover be ``DISTINCT``: no two within 6.8e-7 in every joint (the subproblems would have merged them).
- Every EAIK solution is within ``SAME`` of one of ours, or on the continuum one of ours stands for: from our
  solution, the joint its ``singular`` note shows at 0 is turned to EAIK's value in small steps, the other joints
  pulled back onto the pose by Gauss-Newton (independent of the plan), and the end must be EAIK's solution. EAIK's
  clusters, those on one continuum of ours counted once, are as many as our clusters. A solution of ours that EAIK
  lacks is accepted only where EAIK returned a failed entry with the same theta1 (ours is then checked by forward
  kinematics alone).
- Every solution of ours reaches the pose (1e-9) and the generating configuration is among ours, within
  ``max(SAME, 1e-12 / smallest singular value)`` (the conditioning), or on the continuum of one of ours.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest
from scipy.optimize import brentq
from test_ik_spherical_wrist import differences, eaik_robot

from symjac import load_robot
from symjac.analysis.inverse_kinematics import closed_form_plan, solve_plan
from symjac.codegen.numeric_model import numeric_model

SAME = 1e-6
DISTINCT = 2 * np.sqrt(2 * 256 * np.finfo(float).eps)  # two unmerged solutions differ by more in the merged joint
REACHED = 1e-9
OFFSETS = (0.0, 1e-8, 1e-7, 1e-4)
GENERIC = {"puma560": [0.3, -0.7, 0.4, 1.1, 0.8, -0.5], "irb140": [0.3, 0.5, -0.4, 1.1, 0.8, -0.5],
           "ur5": [0.3, -1.1, 1.2, -0.6, 0.8, 0.4]}


def _roots(model, q, joint):
    """The values of ``joint`` (others as in ``q``) where det J changes sign: singular configurations, to 1e-15."""
    def det(value):
        x = np.array(q, dtype=float)
        x[joint] = value
        return float(np.linalg.det(model.jacobian(x)))

    grid = np.linspace(-np.pi, np.pi, 181)
    signs = np.sign([det(v) for v in grid])
    return [brentq(det, a, b, xtol=1e-15) for a, b, sa, sb in zip(grid, grid[1:], signs, signs[1:], strict=False)
            if sa * sb < 0]


def singular_configurations(model, name):
    """(label, q) at each kind of singularity, exactly and moved by each offset in the singular joint."""
    q = np.array(GENERIC[name])
    kinds = [("wrist", 4, [0.0]), ("elbow", 2, _roots(model, q, 2)), ("shoulder", 1, _roots(model, q, 1))]
    cases = []
    for kind, joint, values in kinds:
        assert values, f"{name}: no {kind} singularity found"
        for value in values:
            for offset in OFFSETS:
                x = q.copy()
                x[joint] = value + offset
                cases.append((f"{name} {kind} q{joint + 1}={value:.6f}{offset:+.0e}", x))
    return cases


def _free_joint(note):
    """The 0-based joint a ``singular`` note shows at 0 (the parameter of its continuum), None for a note without a
    continuum (two branches that merge)."""
    found = re.search(r"theta(\d+) (?:shown at 0|takes every value)", note)
    return None if found is None else int(found.group(1)) - 1


def _follow(model, q, joint, value, pose):
    """From ``q`` on the pose's solution set, turn ``joint`` to ``value`` in small steps, the other joints pulled back
    onto the pose by Gauss-Newton: the continuum a singular solution stands for, followed independently of the plan."""
    x = np.array(q, dtype=float)
    others = [j for j in range(len(x)) if j != joint]
    step = np.angle(np.exp(1j * (value - x[joint])))
    for t in np.linspace(0.0, 1.0, 33)[1:]:
        x[joint] = q[joint] + t * step
        for _ in range(30):
            current = model.fk(x)
            error = np.concatenate([pose[:3, 3] - current[:3, 3],  # position, then rotation (current to target)
                                    0.5 * np.cross(current[:3, :3].T, pose[:3, :3].T).sum(axis=0)])
            if np.abs(error).max() < 1e-14:
                break
            x[others] += np.linalg.lstsq(model.jacobian(x)[:, others], error, rcond=None)[0]
    return x


def covers(model, pose, solution, x, within=SAME):
    """Whether ``x`` is ``solution`` (joint by joint, within SAME) or on the continuum its ``singular`` note names."""
    if differences([solution.q], [x], True)[0, 0] < within:
        return True
    joint = _free_joint(solution.singular)
    if joint is None:
        return False
    return bool(differences([_follow(model, solution.q, joint, x[joint], pose)], [x], True)[0, 0] < 1e-5)


def clusters(solutions):
    """Single-linkage clusters of ``solutions`` under SAME (modulo 2 pi): a list of lists of indices."""
    groups: list[list[int]] = []
    for i, x in enumerate(solutions):
        touching = [g for g in groups if (differences([solutions[k] for k in g], [x], True) < SAME).any()]
        merged = [i] + [k for g in touching for k in g]
        groups = [g for g in groups if g not in touching] + [merged]
    return groups


def compare(ours, model, eaik, q):
    """The failures of the comparison of ``ours`` (solutions at FK(q)) with EAIK's, and EAIK's failed entries."""
    pose = model.fk(q)
    found = eaik.IK(pose)
    entries = [np.asarray(x) for x in found.Q]
    reached = [x for x in entries if np.abs(model.fk(x) - pose).max() < REACHED]
    failed = [x for x in entries if np.abs(model.fk(x) - pose).max() >= REACHED]
    failures = []
    for s in ours:
        if np.abs(model.fk(s.q) - pose).max() >= REACHED:
            failures.append(f"ours {s.branch} misses the pose by {np.abs(model.fk(s.q) - pose).max():.2g}")
    sigma = np.linalg.svd(model.jacobian(q), compute_uv=False)[-1]
    if not any(covers(model, pose, s, q, max(SAME, 1e-12 / max(sigma, 1e-300))) for s in ours):
        failures.append("the generating configuration is not among ours")
    apart = differences([s.q for s in ours], [s.q for s in ours], True) + 10 * np.eye(len(ours))
    if (apart <= DISTINCT).any():
        failures.append(f"two of our solutions are {apart.min():.2g} apart: the subproblems merge such pairs")
    for x in reached:
        if not any(covers(model, pose, s, x) for s in ours):
            failures.append(f"EAIK's {np.round(x, 6)} is none of ours")
    unmatched = [s for s in ours if not any(covers(model, pose, s, x) for x in reached)]
    for s in unmatched:
        if not any(differences([s.q[:1]], [x[:1]], True)[0, 0] < SAME for x in failed):
            failures.append(f"ours {s.branch} {np.round(s.q, 6)} is none of EAIK's (which did not fail there)")
    groups = clusters(reached)  # then EAIK's samples of one continuum of ours count once
    continua = {i for g in groups for i, s in enumerate(ours) if s.singular and covers(model, pose, s, reached[g[0]])}
    alone = [g for g in groups if not any(ours[i].singular and covers(model, pose, ours[i], reached[g[0]])
                                          for i in continua)]
    theirs = len(alone) + len(continua)
    mine = len(clusters([s.q for s in ours if not any(s is u for u in unmatched)]))
    if theirs != mine:
        failures.append(f"EAIK's solutions form {theirs} clusters, ours (those EAIK has) {mine}")
    return failures, len(failed)


KNOWN = {  # label prefix -> why the closed form fails there (the executor's, reported in NOTES-46.md)
    "ur5 wrist q5=0.000000+1e-08": "theta5 merged by rounding (half angle < 3.4e-7), then theta6 has no solution",
    "ur5 wrist q5=0.000000+1e-07": "the same",
}


@pytest.mark.parametrize("name", ["puma560", "irb140", "ur5"])
def test_counts_at_and_near_singular_configurations_equal_eaiks(name):
    robot = load_robot(name)
    plan, model, eaik = closed_form_plan(robot), numeric_model(robot, backend="numpy"), eaik_robot(robot)
    report, eaik_failures = [], 0
    for label, q in singular_configurations(model, name):
        failures, failed = compare(solve_plan(plan, model.fk(q)).solutions, model, eaik, q)
        eaik_failures += failed
        if label in KNOWN:
            assert failures, f"{label}: fixed? remove it from KNOWN ({KNOWN[label]})"
        elif failures:
            report.append(f"{label}: " + "; ".join(failures))
    assert report == []
    assert eaik_failures > 0  # EAIK loses branches at the wrist singularity: the rule above is exercised


def test_the_comparison_fails_on_a_lost_a_doubled_an_unmerged_or_a_wrong_solution():
    robot = load_robot("puma560")
    plan, model, eaik = closed_form_plan(robot), numeric_model(robot, backend="numpy"), eaik_robot(robot)
    cases = dict(singular_configurations(model, "puma560"))
    q = next(x for label, x in cases.items() if "elbow" in label and label.endswith("+1e-07"))
    ours = solve_plan(plan, model.fk(q)).solutions
    assert compare(ours, model, eaik, q)[0] == []
    assert compare(ours[1:], model, eaik, q)[0]  # a lost solution
    assert compare((*ours, ours[0]), model, eaik, q)[0]  # a duplicate
    near = dataclasses.replace(ours[0], q=ours[0].q + np.array([0, 0, 5e-7, 0, 0, 0]))
    assert compare((*ours, near), model, eaik, q)[0]  # a pair the subproblems would have merged
    moved = dataclasses.replace(ours[0], q=ours[0].q + np.array([0, 0, 1e-4, 0, 0, 0]))
    assert compare((*ours[1:], moved), model, eaik, q)[0]  # a solution off by 1e-4 in one joint


@pytest.mark.xfail(strict=True, reason="closed form: theta6 = 0 stands for the wrist-singular continuum, but there the "
                   "elbow cannot reach (cos = -1.03); the continuum reaches the pose only for theta6 near -1.3")
def test_the_ur5_at_a_wrist_singularity_where_theta6_at_0_is_out_of_reach():
    """Found by sampling q5 = 0 (11 of 300 random configurations): symjac says unreachable, EAIK returns only
    least-squares entries (0.0044 to 1.4 off); the configuration itself reaches the pose."""
    robot = load_robot("ur5")
    plan, model, eaik = closed_form_plan(robot), numeric_model(robot, backend="numpy"), eaik_robot(robot)
    q = np.array([2.197659, -0.666474, -0.12765, -2.222145, 0.0, -1.307037])
    assert compare(solve_plan(plan, model.fk(q)).solutions, model, eaik, q)[0] == []
