r"""Every singularity explanation is computed and checked against an independent Jacobian at its stated sample.

For every catalog robot and for published arms written here from their DH tables (ABB IRB 2400, Fanuc LR Mate 200iD,
Staubli TX90 in degrees, Kinova Gen3, a cylindrical RPP, a spherical RRP with d2 = 0.1, a SCARA RRPR, a 3R with a
tool offset, ROBOTIS OpenManipulator-X), the report's numbers are checked against the SVD of :math:`J` from
central differences of a plain-NumPy forward kinematics (``tests/reference.py``): the lost direction :math:`u`
satisfies :math:`u^T J = 0` (orthogonal to the range), the null motion lies in the null space, a joint said to no
longer move a point has zero speed there, a joint said to still move it has the stated speed. The reverse too: the
words state exactly the clauses the checked evidence supports, and every "no longer moves" / "still moves" phrase
printed is checked against the independent numbers.
"""

from __future__ import annotations

import json
import re
from functools import cache

import numpy as np
import pytest
import sympy as sp
from marks import BUILT_IN_ROBOTS, marked
from reference import finite_difference_jacobian, frame_index, frames
from truth_arms import ARMS, EXPLAINED

from symjac import load_robot, robot_from_toml, singularities
from symjac.printing import prose
from symjac.printing.document import Inline
from symjac.printing.json import singularity_data
from symjac.printing.pretty import one_line
from symjac.printing.summary import singularity_summary

SLOW_ARMS = {"gen3"}  # a redundant 7R: about 7 s for its singular sets
SLOW_CATALOG = {"panda", "panda.urdf", "iiwa7"}  # measured: 2.5-5 s each on the development machine


@cache
def report_of(name: str):
    robot = robot_from_toml(ARMS[name]) if name in ARMS else load_robot(name)
    return robot, singularities(robot)


def cases() -> list:
    catalog = [pytest.param(name, marks=pytest.mark.slow) if name in SLOW_CATALOG else name
               for name in sorted(BUILT_IN_ROBOTS)]
    arms = [pytest.param(name, marks=pytest.mark.slow) if name in SLOW_ARMS else name for name in EXPLAINED]
    return marked(catalog, keep=BUILT_IN_ROBOTS - SLOW_CATALOG) + arms


def explained(report) -> list:
    """Every factor and singular set with checked evidence."""
    return [item for item in (*report.factors, *report.sets) if item.evidence is not None]


def reference_jacobian(robot, report, q) -> np.ndarray:
    """The 6 x n Jacobian from central differences of the reference forward kinematics (frame and point analysed)."""
    det = report.determinant
    point = np.array([float(sp.sympify(c).subs(robot.defaults)) for c in det.point])
    return finite_difference_jacobian(robot, np.asarray(q, dtype=float), det.frame, point)


def landmark_position(robot, report, landmark, q) -> np.ndarray:
    """A landmark point in the world, from the reference forward kinematics."""
    poses = frames(robot, np.asarray(q, dtype=float))
    if landmark.kind == "frame origin":
        return poses[frame_index(robot, landmark.index)][:3, 3]
    point = np.array([float(sp.sympify(c).subs(robot.defaults)) for c in report.determinant.point] + [1.0])
    return (poses[robot.n_joints + 1] @ point)[:3]


def landmark_speeds(robot, report, landmark, q, h: float = 1e-6) -> np.ndarray:
    """How fast each coordinate moves ``landmark``: central differences of its position."""
    q = np.asarray(q, dtype=float)
    speeds = []
    for k in range(len(q)):
        step = np.zeros(len(q))
        step[k] = h
        difference = landmark_position(robot, report, landmark, q + step) - landmark_position(robot, report,
                                                                                               landmark, q - step)
        speeds.append(float(np.linalg.norm(difference)) / (2 * h))
    return np.array(speeds)


@pytest.mark.parametrize("name", cases())
def test_every_explanation_holds_at_its_stated_sample(name):
    robot, report = report_of(name)
    for item in explained(report):
        facts = item.evidence
        assert facts.sample == item.sample
        full = reference_jacobian(robot, report, item.sample)
        J = full[list(facts.rows), :][:, list(facts.columns)]
        U, sigma, Vt = np.linalg.svd(J)
        scale = sigma[0]
        tolerance = 1e-5 * scale
        rank = int(np.sum(sigma > tolerance))
        assert np.allclose(facts.jacobian, J, atol=tolerance), "the evidence is J at its stated sample"
        assert rank < min(J.shape), f"{name}: the stated sample is not singular"
        if item.lost_direction is not None and prose.lost_words(item):
            u = np.array(item.lost_direction.vector)
            assert abs(np.linalg.norm(u) - 1) < 1e-9
            assert np.linalg.norm(u @ J) <= tolerance  # a wrench that loads no joint
            assert np.linalg.norm(U[:, :rank].T @ u) <= 1e-5  # orthogonal to the range
        if item.self_motion is not None:
            rates = np.zeros(len(robot.q))
            rates[list(item.self_motion.columns)] = item.self_motion.rates
            assert np.linalg.norm(full[list(facts.rows), :] @ rates) <= tolerance  # moves nothing
            null = Vt[rank:].T
            motion = rates[list(facts.columns)]
            assert np.linalg.norm(motion - null @ (null.T @ motion)) <= 1e-5  # in the null space
        speeds = np.linalg.norm(full[:3, list(facts.columns)], axis=0)
        assert np.allclose(facts.speeds, speeds, atol=tolerance)
        for c in facts.stopped:
            assert speeds[facts.columns.index(c)] <= tolerance, f"{name}: joint {c + 1} still moves the point"
        for c in facts.moving:
            assert speeds[facts.columns.index(c)] > 1e-3 * scale
        for i, j in facts.parallel:
            pair = J[:, [facts.columns.index(i), facts.columns.index(j)]]
            assert np.linalg.svd(pair, compute_uv=False)[-1] <= tolerance
        if facts.dependent and len(facts.rows) == len(facts.columns):
            columns = [facts.columns.index(c) for c in facts.dependent]
            assert np.linalg.svd(J[:, columns], compute_uv=False)[-1] <= tolerance
        for point in facts.points:
            independent = landmark_speeds(robot, report, point.landmark, item.sample)
            for k, stated in enumerate(point.speeds):
                if not np.isnan(stated):
                    assert abs(stated - independent[k]) <= 1e-5 * max(1.0, scale), (name, point.landmark, k)
            assert all(independent[k] <= tolerance for k in point.stopped)
            assert all(independent[k] > 1e-3 * scale for k in point.moving)


@pytest.mark.parametrize("name", ["spherical_rrp", "cylindrical_rpp", "tool3r", "stanford"])
def test_a_joint_said_to_stop_on_the_whole_set_stops_at_other_points_of_it(name):
    robot, report = report_of(name)
    rng = np.random.default_rng(7)
    proven = [f for f in report.factors if f.evidence is not None and f.evidence.stopped_on_set]
    assert proven
    for factor in proven:
        values = dict(zip(report.variables, factor.sample, strict=True))
        (solution,) = [s for s in factor.solutions
                       if abs(values[s.lhs] - float(s.rhs.subs(robot.defaults).subs(values))) < 1e-9
                       or abs(np.sin(values[s.lhs] - float(s.rhs.subs(robot.defaults).subs(values)))) < 1e-9][:1]
        for _ in range(3):
            q = {v: values[v] + rng.uniform(-0.5, 0.5) for v in report.variables}
            q[solution.lhs] = float(solution.rhs.subs(robot.defaults).subs(q))
            full = reference_jacobian(robot, report, [q[v] for v in report.variables])
            for c in factor.evidence.stopped_on_set:
                assert np.linalg.norm(full[:3, c]) <= 1e-6 * np.linalg.norm(full, 2), (name, factor.expression, c)


def _joints(text: str) -> list[int]:
    return [int(number) - 1 for number in re.findall(r"\d+", text)]


_NO_LONGER = re.compile(r"joints? ([\d, and]+?) no longer moves? (the reference point|the origin of frame \{(\d+)\})")
_STILL = re.compile(r"joints? ([\d, and]+?) still moves? (the reference point|the origin of frame \{(\d+)\}), at "
                    r"([\d., and]+) m/rad")


@pytest.mark.parametrize("name", cases())
def test_the_words_state_only_what_the_numbers_support(name):
    """The words are the evidence's clauses; every motion claim printed agrees with the independent numbers."""
    robot, report = report_of(name)
    data = singularity_data(report)
    entries = [*data["factors"], *data["sets"]]
    items = [*report.factors, *report.sets]
    for item, entry in zip(items, entries, strict=True):
        words = entry.get("reason") or entry.get("explanation")
        if item.evidence is None:
            assert entry["evidence"] is None
            continue
        for clause in entry["evidence"]["clauses"]:
            assert clause in words
        assert entry["evidence"]["stopped"] == [c + 1 for c in item.evidence.stopped]
        assert "sideways" not in words and "two wrist rotations" not in words  # no template left
        assert not contradicted(robot, report, item, words), name


def contradicted(robot, report, item, words: str) -> list[str]:
    """The "no longer moves" and "still moves ... at" claims of ``words`` that the independent numbers contradict."""
    sample = item.sample
    full = reference_jacobian(robot, report, sample)
    scale = np.linalg.svd(full[list(item.evidence.rows), :][:, list(item.evidence.columns)], compute_uv=False)[0]
    wrong = []
    for claim in _NO_LONGER.finditer(words):
        speeds = landmark_speeds(robot, report, _landmark(item, claim.group(3)), sample)
        if any(speeds[k] > 1e-5 * scale for k in _joints(claim.group(1))):
            wrong.append(claim.group(0))
    for claim in _STILL.finditer(words):
        speeds = landmark_speeds(robot, report, _landmark(item, claim.group(3)), sample)
        stated = [float(x) for x in re.findall(r"\d+(?:\.\d+)?", claim.group(4))]
        joints = _joints(claim.group(1))
        if len(stated) != len(joints) or any(speeds[k] != pytest.approx(value, rel=5e-3, abs=5e-4)
                                             for k, value in zip(joints, stated, strict=False)):
            wrong.append(claim.group(0))
    return wrong


def test_the_check_catches_the_old_false_sentence():
    """The check can fail: the templated shoulder words, said of the spherical RRP, are contradicted."""
    robot, report = report_of("spherical_rrp")
    (extended,) = [f for f in report.factors if str(f.expression) == "d3"]
    assert contradicted(robot, report, extended, "joint 1 no longer moves the reference point")
    assert contradicted(robot, report, extended, "joint 1 still moves the reference point, at 0.2 m/rad")
    assert not contradicted(robot, report, extended, "joint 2 no longer moves the reference point")


def test_an_unchecked_direction_or_motion_is_not_stated():
    from dataclasses import replace

    _, report = report_of("planar2r")
    (elbow,) = [f for f in report.factors if f.sample is not None]
    assert prose.lost_words(elbow) and prose.self_motion_words(elbow)
    wrong = replace(elbow, evidence=replace(elbow.evidence, lost_residual=0.1, motion_residual=0.1))
    assert prose.lost_words(wrong) == "" and prose.self_motion_words(wrong) == ""


def _landmark(item, frame: str | None):
    wanted = "reference point" if frame is None else "frame origin"
    found = [p.landmark for p in item.evidence.points
             if p.landmark.kind == wanted and (frame is None or p.landmark.index == int(frame))]
    assert found, f"the words name a point the evidence did not examine: {frame}"
    return found[0]


def test_the_offset_shoulders_say_which_joint_stops_and_how_fast_the_other_moves():
    """The issue's cases: the spherical RRP with d2 = 0.1 and the TX90's shoulder set."""
    _, report = report_of("spherical_rrp")
    (extended,) = [f for f in report.factors if str(f.expression) == "d3"]
    assert extended.evidence.stopped == (1,) and extended.evidence.speed(0) == pytest.approx(0.1)
    assert "joint 2 no longer moves the reference point" in prose.reason(extended)
    assert "joint 1 still moves the reference point, at 0.1 m/rad" in prose.reason(extended)
    assert "joint 1 no longer" not in prose.reason(extended)
    _, report = report_of("tx90")
    (shoulder,) = [f for f in report.factors if f.kind == "shoulder"]
    centre = shoulder.cause.findings[0].landmark
    assert shoulder.evidence.point(centre).speeds[0] == pytest.approx(0.05)  # the offset d3 = 50 mm
    assert f"joints 1 and 2 still move {prose.landmark_name(centre)}, at 0.05 and" in prose.reason(shoulder)


@pytest.mark.parametrize("name", ["planar2r", "puma560", "spherical_rrp", "scara", "palletizer"])
def test_the_sample_is_stated_in_every_format(name):
    _, report = report_of(name)
    with_sample = [f for f in report.factors if f.sample is not None]
    assert with_sample
    pretty = [caption for caption, _ in singularity_summary(report, "pretty") if caption.startswith("Factor")]
    latex = [caption for caption, _ in singularity_summary(report, "latex") if caption.startswith("Factor")]
    data = singularity_data(report)
    for factor in with_sample:
        number = report.factors.index(factor)
        values = dict(zip(map(str, report.variables), factor.sample, strict=True))
        assert data["factors"][number]["sample"] == values
        assert json.loads(json.dumps(data))["factors"][number]["sample"] == values
        shown = "".join(part if isinstance(part, str) else part.text if isinstance(part, Inline) else one_line(part)
                        for part in prose.sample_parts(factor.sample, report.variables))
        assert shown.startswith("at ") and shown in pretty[number]
        first = sp.latex(report.variables[0])
        assert f", at ${first} = " in latex[number]


def test_a_degree_file_states_its_sample_in_degrees(tmp_path, capsys):
    from symjac.cli.main import main

    path = tmp_path / "tx90.toml"
    path.write_text(ARMS["tx90"], encoding="utf-8")
    assert main(["singularities", str(path), "--format", "pretty"]) == 0
    text = capsys.readouterr().out
    _, report = report_of("tx90")
    for factor in report.factors:
        if factor.sample is None:
            continue
        caption = next(line for line in text.splitlines() if line.startswith("Factor ") and f"({factor.kind})" in line)
        stated = [float(x) for x in re.findall(r"θ\S+ = (-?[\d.]+)°", caption.split(":")[0])]
        assert np.allclose(np.radians(stated), factor.sample, atol=np.radians(5e-4) + 1e-12)
    assert main(["singularities", str(path), "--format", "latex"]) == 0
    assert r"\theta_{5} = 0^{\circ}$" in capsys.readouterr().out


def test_a_redundant_arms_sets_state_their_sample(capsys):
    from symjac.cli.main import main

    assert main(["singularities", "iiwa7", "--format", "pretty"]) == 0
    sets = [line for line in capsys.readouterr().out.splitlines() if line.startswith("Set ")]
    assert sets and all(re.match(r"Set \d+: .* \(\w+\), at θ₁ = ", line) for line in sets)
    _, report = report_of("iiwa7")
    for entry, singular_set in zip(singularity_data(report)["sets"], report.sets, strict=True):
        assert entry["sample"] == dict(zip(map(str, singular_set.variables), singular_set.sample, strict=True))


def test_the_html_report_states_the_sample():
    pytest.importorskip("matplotlib")
    from symjac.report import derivation_report

    robot, report = report_of("planar2r")
    page = derivation_report(robot)
    section = page[page.index('id="singularities"'):page.index('id="arm"')]
    (elbow,) = [f for f in report.factors if f.sample is not None]
    assert "(elbow), at <math>" in section
    arm = page[page.index('id="arm"'):]
    assert "(elbow), at <math>" in arm[arm.index("Singular where"):]  # the drawn arm's caption: the same sample
    for value in elbow.sample:
        assert prose.readable_number(abs(value)).replace("-", "") in section
