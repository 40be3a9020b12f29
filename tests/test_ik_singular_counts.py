"""Solution counts at and near singular configurations of the PUMA 560, the IRB 140 and the UR5, against EAIK.

The round trips elsewhere skip EAIK's count where the Jacobian's smallest singular value is below 1e-5. Here the
configurations are singular on purpose: joint 5 at 0 (the wrist), the elbow stretched or folded and the wrist centre
at the shoulder's singular place (roots of det J in joint 3 and in joint 2), each exactly and moved by 1e-7 and 1e-4
in that joint. The comparison, exactly:

- EAIK's solutions are those it returns (least-squares flag or not) whose forward kinematics reaches the pose to
  1e-9; an entry that does not is a failure of EAIK's (it returns a least-squares configuration where it lost a
  branch) and is counted as such, not as a solution.
- Two solutions coincide when every joint differs by less than ``SAME`` (modulo 2 pi): the joint-space form of the
  subproblems' merge rule (two angles merge when their half difference is below 3.4e-7 rad). EAIK's solutions are
  clustered by it (single linkage); ours must already be distinct by it.
- Every EAIK solution is within ``SAME`` of one of ours, or on the continuum one of ours describes (its ``singular``
  note: the joints it names excluded, the fixed signed sum it states compared); the number of EAIK's clusters equals
  the number of our solutions, except that a solution of ours that EAIK lacks is accepted only where EAIK returned a
  failed entry with the same theta1 (then ours is checked by forward kinematics alone).
- Every solution of ours reaches the pose (1e-9) and the generating configuration is among ours (or on the
  continuum of one of ours).
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
REACHED = 1e-9
OFFSETS = (0.0, 1e-7, 1e-4)
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


def _continuum(note):
    """From a ``singular`` note: the 0-based joints it names, and (signs, value) of the fixed sum it states."""
    named = {int(n) - 1 for n in re.findall(r"theta(\d+)", note)}
    fixed = re.search(r"((?:theta\d+ [+-] )*theta\d+) = (-?[\d.]+(?:e[+-]?\d+)?) is fixed", note)
    if fixed is None:
        return named, None
    terms = re.findall(r"([+-]?) ?theta(\d+)", fixed.group(1))
    return named, ([(int(j) - 1, -1.0 if s == "-" else 1.0) for s, j in terms], float(fixed.group(2)))


def covers(solution, x):
    """Whether ``x`` is ``solution`` (joint by joint) or on the continuum its note describes."""
    if not solution.singular:
        return bool(differences([solution.q], [x], True)[0, 0] < SAME)
    named, fixed = _continuum(solution.singular)
    others = [j for j in range(len(x)) if j not in named]
    if differences([solution.q[others]], [np.asarray(x)[others]], True)[0, 0] >= SAME:
        return False
    if fixed is None:
        return True
    total = sum(sign * x[j] for j, sign in fixed[0])
    return abs(np.angle(np.exp(1j * (total - fixed[1])))) < 1e-5  # the note prints 6 significant digits


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
    if not any(covers(s, q) for s in ours):
        failures.append("the generating configuration is not among ours")
    if len(ours) > 1 and (differences([s.q for s in ours], [s.q for s in ours], True)
                          + np.eye(len(ours)) * 10 < SAME).any():
        failures.append("two of our solutions coincide")
    for x in reached:
        if not any(covers(s, x) for s in ours):
            failures.append(f"EAIK's {np.round(x, 6)} is none of ours")
    unmatched = [s for s in ours if not any(covers(s, x) for x in reached)]
    for s in unmatched:
        if not any(differences([s.q[:1]], [x[:1]], True)[0, 0] < SAME for x in failed):
            failures.append(f"ours {s.branch} {np.round(s.q, 6)} is none of EAIK's (which did not fail there)")
    if len(clusters(reached)) != len(ours) - len(unmatched):
        failures.append(f"EAIK's {len(reached)} solutions form {len(clusters(reached))} clusters; "
                        f"ours: {len(ours)}, {len(unmatched)} of them EAIK lacks")
    return failures, len(failed)


KNOWN = {  # label prefix -> why the closed form fails there (the executor's, reported in NOTES-46.md)
    "ur5 wrist q5=0.000000+1e-07": "theta5 merged by rounding (half angle 1e-7 < 3.4e-7), then theta6 has no solution",
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


def test_the_comparison_fails_on_a_lost_branch_a_duplicate_and_a_missed_merge():
    robot = load_robot("puma560")
    plan, model, eaik = closed_form_plan(robot), numeric_model(robot, backend="numpy"), eaik_robot(robot)
    cases = dict(singular_configurations(model, "puma560"))
    q = next(x for label, x in cases.items() if "elbow" in label and label.endswith("+1e-07"))
    ours = solve_plan(plan, model.fk(q)).solutions
    assert compare(ours, model, eaik, q)[0] == []
    assert compare(ours[1:], model, eaik, q)[0]  # a lost solution
    assert compare((*ours, ours[0]), model, eaik, q)[0]  # a duplicate
    moved = dataclasses.replace(ours[0], q=ours[0].q + np.array([0, 0, 5e-7, 0, 0, 0]))
    assert compare((*ours, moved), model, eaik, q)[0]  # a merge missed: two elbows 5e-7 apart
