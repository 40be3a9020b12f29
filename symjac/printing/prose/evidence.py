"""What the checked evidence at a sample of a singular set supports, in words; the names of landmarks.

Every clause here words a fact :class:`~symjac.analysis.singularity.evidence.Evidence` holds, and nothing else: a joint
"no longer moves" a point only when its speed there is zero and was not generically, it "still moves" it only at the
speed computed there. Like the rest of :mod:`symjac.printing.prose`, it names the analyses' types only for checkers.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from symjac.analysis.singularity.evidence import Evidence
    from symjac.analysis.singularity.geometry import Cause, Finding, Landmark

__all__ = ["evidence_clauses", "landmark_name"]


def landmark_name(landmark: Landmark) -> str:
    """``the reference point``, ``the origin of frame {4}``, ``the axis of joint 3``."""
    if landmark.kind == "frame origin":
        return f"the origin of frame {{{landmark.index}}}"
    if landmark.kind == "joint axis":
        return f"the axis of joint {int(landmark.index or 0) + 1}"
    return "the reference point"


def _listed(words: Sequence[str]) -> str:
    return words[0] if len(words) == 1 else f"{', '.join(words[:-1])} and {words[-1]}"


def _joints_named(facts: Evidence, coordinates: Sequence[int]) -> str:
    """``joint 2``, ``joints 1 and 3``, or a coupled robot's coordinates ``theta2 and theta3``."""
    if facts.coupled:
        return _listed([facts.names[c] for c in coordinates])
    return f"joint{'s' if len(coordinates) > 1 else ''} {_listed([str(c + 1) for c in coordinates])}"


def evidence_clauses(facts: Evidence | None, cause: Cause | None = None) -> tuple[str, ...]:
    """What the numbers at the sample support, one clause each (``()`` without evidence).

    Only facts :class:`~symjac.analysis.singularity.evidence.Evidence` holds are stated: joints whose linear column
    vanished there (and not generically), pairs of analysed columns that became parallel, and for a shoulder
    singularity which of its joints no longer move the finding's point (a wrist centre) and how fast the others
    still move it; failing these, for a
    square Jacobian, the joints whose columns are dependent (the support of the null motion).
    """
    if facts is None:
        return ()
    clauses: list[str] = []
    everywhere = [c for c in facts.stopped if c in facts.stopped_on_set]
    there = [c for c in facts.stopped if c not in facts.stopped_on_set]
    for joints, why in ((everywhere, "anywhere on the set (its linear column vanishes there identically)"),
                        (there, "(its linear column is zero at this configuration)")):
        if joints:
            verb = "moves" if len(joints) == 1 else "move"
            clauses.append(f"{_joints_named(facts, joints)} no longer {verb} the reference point {why}")
    clauses += [f"the columns of {_joints_named(facts, pair)} are parallel (one's motion is now a multiple of "
                "the other's)" for pair in facts.parallel]
    if cause is not None and cause.kind == "shoulder" and cause.findings:
        clauses += _landmark_clauses(facts, cause.findings[0])
    if not clauses and facts.dependent and len(facts.rows) == len(facts.columns):
        clauses.append(f"the columns of {_joints_named(facts, facts.dependent)} are dependent")
    return tuple(clauses)


def _landmark_clauses(facts: Evidence, finding: Finding) -> list[str]:
    """How the finding's joints move its landmark (the reference point, a wrist centre) at the sample, if known."""
    speeds = facts.point(finding.landmark) if finding.landmark is not None else facts.points[0] if facts.points \
        else None
    if speeds is None:
        return []
    name, clauses = landmark_name(speeds.landmark), []
    stopped = [k for k in finding.joints if k in speeds.stopped and k not in facts.stopped]
    if stopped and speeds.landmark.kind != "reference point":  # the reference point's stopped joints are said already
        clauses.append(f"{_joints_named(facts, stopped)} no longer {'moves' if len(stopped) == 1 else 'move'} {name}")
    still = [k for k in finding.joints if k in speeds.moving and facts.revolute[k]]
    if still:
        rates = _listed([f"{speeds.speeds[k]:.3g}" for k in still])
        clauses.append(f"{_joints_named(facts, still)} still {'moves' if len(still) == 1 else 'move'} {name}, at "
                       f"{rates} m/rad")
    return clauses
