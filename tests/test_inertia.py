"""Inertial data in the model: the parallel-axis theorem, physical checks, robot files of every convention, conversion.

The references are independent: point-mass clouds summed in NumPy, a box whose tensor about its corner is worked out
by hand, and world poses of frames from ``tests/reference.py`` (plain NumPy, no symjac transforms).
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from marks import marked
from reference import frames

from symjac import load_robot
from symjac.analysis.dynamics import gravity_torques
from symjac.errors import ImpossibleInertiaError, InertialWarning, RobotFileError
from symjac.kinematics.convert import convert
from symjac.model.conventions import file_inertials, with_file_inertials
from symjac.model.inertia import Inertial, combined_inertial, inertial_problem, symbolic_inertial
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.model.io import robot_from_toml, robot_to_toml
from symjac.model.robot import Robot
from symjac.model.robot_file import robot_from_mapping, robot_to_mapping

# --- independent numeric references -------------------------------------------------------------------------------


def cloud_tensor(masses: np.ndarray, points: np.ndarray, about: np.ndarray) -> np.ndarray:
    r""":math:`\sum_k m_k (\lVert r_k\rVert^2 E - r_k r_k^T)`, :math:`r_k = x_k - p`, summed point by point."""
    total = np.zeros((3, 3))
    for m, x in zip(masses, points, strict=True):
        r = x - about
        total += m * (r @ r * np.eye(3) - np.outer(r, r))
    return total


def cloud(seed: int, count: int = 7) -> tuple[list[sp.Rational], list[list[sp.Rational]]]:
    """Exact random masses and points (rationals, so the symbolic side is exact)."""
    rng = np.random.default_rng(seed)
    masses = [sp.Rational(int(v), 10) for v in rng.integers(1, 30, count)]
    points = [[sp.Rational(int(v), 20) for v in rng.integers(-40, 40, 3)] for _ in range(count)]
    return masses, points


def as_float(matrix: sp.MatrixBase) -> np.ndarray:
    return np.array(sp.Matrix(matrix).evalf(), dtype=float)


# --- the parallel-axis theorem -----------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", range(4))
def test_from_origin_matches_a_point_mass_cloud(seed: int) -> None:
    masses, points = cloud(seed)
    m = np.array(masses, dtype=float)
    x = np.array(points, dtype=float)
    centre = (m[:, None] * x).sum(axis=0) / m.sum()
    about_origin = cloud_tensor(m, x, np.zeros(3))
    exact_origin = sp.zeros(3, 3)
    for mass, point in zip(masses, points, strict=True):
        r = sp.Matrix(point)
        exact_origin += mass * ((r.T * r)[0, 0] * sp.eye(3) - r * r.T)
    assert np.allclose(as_float(exact_origin), about_origin)
    total = sum(masses)
    com = [sum(mk * p[k] for mk, p in zip(masses, points, strict=True)) / total for k in range(3)]
    inertial = Inertial.from_origin(total, com, exact_origin)
    assert np.allclose(as_float(inertial.inertia), cloud_tensor(m, x, centre), atol=1e-12)
    assert np.allclose([float(c) for c in inertial.com], centre)
    assert inertial.inertia_about_origin == sp.ImmutableMatrix(exact_origin)  # and back, exactly
    point = np.array([0.3, -0.2, 0.5])
    assert np.allclose(as_float(inertial.inertia_about([sp.Rational(3, 10), -sp.Rational(1, 5), sp.Rational(1, 2)])),
                       cloud_tensor(m, x, point), atol=1e-12)
    assert inertial_problem(inertial) is None


def test_box_about_its_corner() -> None:
    """A solid box a x b x c with a corner at the origin: the tensor about the corner worked out by hand."""
    m, a, b, c = sp.symbols("m a b c", positive=True)
    corner = sp.Matrix([[m * (b**2 + c**2) / 3, -m * a * b / 4, -m * a * c / 4],
                        [-m * a * b / 4, m * (a**2 + c**2) / 3, -m * b * c / 4],
                        [-m * a * c / 4, -m * b * c / 4, m * (a**2 + b**2) / 3]])
    box = Inertial.from_origin(m, (a / 2, b / 2, c / 2), corner)
    centre = sp.diag(m * (b**2 + c**2) / 12, m * (a**2 + c**2) / 12, m * (a**2 + b**2) / 12)
    assert sp.simplify(box.inertia - centre) == sp.zeros(3, 3)
    assert box.given_about == "origin" and box == Inertial(m, (a / 2, b / 2, c / 2), centre.applyfunc(sp.expand))


@pytest.mark.parametrize("seed", range(3))
def test_expressed_in_and_combined_match_the_cloud(seed: int) -> None:
    masses, points = cloud(seed, count=8)
    m, x = np.array(masses, dtype=float), np.array(points, dtype=float)
    parts = []
    for group in (slice(0, 3), slice(3, 8)):
        part_masses, part_points = masses[group], points[group]
        origin = sp.zeros(3, 3)
        for mass, point in zip(part_masses, part_points, strict=True):
            r = sp.Matrix(point)
            origin += mass * ((r.T * r)[0, 0] * sp.eye(3) - r * r.T)
        total = sum(part_masses)
        com = [sum(mk * p[k] for mk, p in zip(part_masses, part_points, strict=True)) / total for k in range(3)]
        parts.append(Inertial.from_origin(total, com, origin))
    whole = combined_inertial(parts)
    centre = (m[:, None] * x).sum(axis=0) / m.sum()
    assert np.allclose(as_float(whole.inertia), cloud_tensor(m, x, centre), atol=1e-12)
    # the same body seen from a frame {j} where {i} sits at T: every point moves as x' = R x + p
    T = sp.Matrix(sp.rot_axis3(sp.pi / 3) * sp.rot_axis1(sp.Rational(1, 2))).row_join(sp.Matrix([1, -2, 3]))
    T = T.col_join(sp.Matrix([[0, 0, 0, 1]]))
    Tf = as_float(T)
    moved = (Tf[:3, :3] @ x.T).T + Tf[:3, 3]
    seen = whole.expressed_in(T)
    assert np.allclose([float(c) for c in seen.com], (m[:, None] * moved).sum(axis=0) / m.sum())
    assert np.allclose(as_float(seen.inertia), cloud_tensor(m, moved, (m[:, None] * moved).sum(axis=0) / m.sum()),
                       atol=1e-12)


def test_symbolic_inertial_names() -> None:
    inertial = symbolic_inertial(3)
    assert [str(s) for s in (inertial.mass, *inertial.com)] == ["m3", "cx3", "cy3", "cz3"]
    assert inertial.inertia == inertial.inertia.T and str(inertial.inertia[1, 2]) == "Iyz3"
    assert inertial_problem(inertial) is None  # nothing numeric to check


# --- physical checks ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("inertial", "message"), [
    (Inertial(-1), "the mass -1 is negative"),
    (Inertial(1, inertia=sp.Matrix([[1, sp.Rational(1, 2), 0], [0, 1, 0], [0, 0, 1]])), "not symmetric"),
    (Inertial(1, inertia=sp.diag(-1, 1, 1)), "not positive semi-definite"),
    (Inertial(1, inertia=sp.diag(1, 2, 4)), r"break the triangle inequality \(1 \+ 2 < 4\)"),
])
def test_physical_problems(inertial: Inertial, message: str) -> None:
    import re

    problem = inertial_problem(inertial)
    assert problem is not None and re.search(message, problem), problem


def test_symbols_are_checked_with_their_defaults() -> None:
    m = sp.Symbol("m", real=True)
    assert inertial_problem(Inertial(m), {m: -2}) == "the mass m is negative"
    assert inertial_problem(Inertial(m), {m: 2}) is None
    assert inertial_problem(Inertial(m)) is None  # purely symbolic: cannot be checked


PRINCIPAL = st.tuples(*(st.integers(1, 50) for _ in range(3)))
ANGLE = st.integers(-6, 6)


def rotated(moments: tuple[int, int, int], angles: tuple[int, int, int]) -> sp.Matrix:
    R = sp.rot_axis1(sp.pi * angles[0] / 6) * sp.rot_axis2(sp.pi * angles[1] / 6) * sp.rot_axis3(sp.pi * angles[2] / 6)
    return (R.T * sp.diag(*moments) * R).applyfunc(sp.expand)


@settings(max_examples=25, deadline=None)
@given(PRINCIPAL, st.tuples(ANGLE, ANGLE, ANGLE), st.tuples(*(st.integers(-5, 5) for _ in range(3))))
def test_random_tensors(moments: tuple[int, int, int], angles: tuple[int, int, int],
                        com: tuple[int, int, int]) -> None:
    """Valid exactly when the principal moments obey the triangle inequality; origin and centre forms agree."""
    inertial = Inertial(3, com, rotated(moments, angles))
    low, mid, high = sorted(moments)
    problem = inertial_problem(inertial)
    assert (problem is None) == (low + mid >= high), problem
    assert Inertial.from_origin(3, com, inertial.inertia_about_origin) == inertial
    flipped = Inertial(3, com, rotated((-moments[0], moments[1], moments[2]), angles))
    assert "not positive semi-definite" in (inertial_problem(flipped) or "")


# --- robot files of every convention -----------------------------------------------------------------------------

GENERAL = """
name = "bent"
convention = "general"
[parameters]
L = 0.4
[[joints]]
type = "revolute"
axis = [1, 0, 0]
xyz = [0, 0, "L"]
rpy = [0.3, 0, "pi/2"]
[[joints]]
type = "prismatic"
axis = [0, 1, 1]
xyz = [0.2, 0, 0]
[[joints]]
type = "revolute"
rpy = [0, "pi/2", 0]
"""


def sample_inertials(n: int, seed: int) -> list[Inertial]:
    rng = np.random.default_rng(seed)
    result = []
    for _ in range(n):
        moments = tuple(int(v) for v in rng.integers(5, 10, 3))
        angles = tuple(int(v) for v in rng.integers(-6, 6, 3))
        com = [sp.Rational(int(v), 20) for v in rng.integers(-10, 10, 3)]
        result.append(Inertial(sp.Rational(int(rng.integers(1, 40)), 10), com,
                               rotated(moments, angles) / 100))  # type: ignore[arg-type]
    return result


def _bare(name: str) -> Robot:
    """A catalog robot without its symbolic inertial parameters: links of unknown data."""
    robot = load_robot(name)
    return replace(robot, parameters=robot.geometric_parameters, inertials=())


ROBOTS = {"standard": lambda: _bare("planar2r"), "modified": lambda: _bare("planar3r"),
          "poe": lambda: _bare("ur5_poe"), "general": lambda: robot_from_toml(GENERAL, "bent.toml")}


@pytest.mark.parametrize("convention", list(ROBOTS))
def test_round_trip_every_convention(convention: str) -> None:
    robot = ROBOTS[convention]()
    inertials = sample_inertials(robot.n_joints, seed=len(convention))
    inertials[0] = None  # an unknown link stays unknown
    with_data = with_file_inertials(robot, inertials)
    text = robot_to_toml(with_data)
    assert "[joints.inertial]" in text
    again = robot_from_toml(text, "again.toml")
    assert again == with_data
    assert robot_to_toml(again) == text
    assert file_inertials(again) == tuple(inertials)
    symbolic = with_symbolic_inertials(robot)
    assert robot_from_toml(robot_to_toml(symbolic)) == symbolic


def test_origin_form_is_written_back_as_given() -> None:
    data = {"name": "r", "convention": "standard", "parameters": {"m2": 2},
            "joints": [{"type": "revolute", "a": 1,
                        "inertial": {"mass": "m2", "com": [0.5, 0, 0], "about": "origin",
                                     "ixx": 0.01, "iyy": 0.6, "izz": 0.6}}]}
    robot = robot_from_mapping(data)
    m2 = sp.Symbol("m2", real=True)
    assert robot.inertials[0].inertia[1, 1] == sp.Rational(6, 10) - m2 / 4
    text = robot_to_toml(robot)
    assert 'about = "origin"' in text and "iyy = 0.6" in text
    assert robot_from_toml(text) == robot


def world_body(robot, inertial: Inertial, link: int, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centre of mass and tensor of link ``link`` in the world frame, by the reference's frame poses."""
    T = frames(robot, q)[link + 1]
    R = T[:3, :3]
    com = np.array([float(c.xreplace(robot.defaults)) for c in inertial.com])
    return (T @ np.append(com, 1))[:3], R @ as_float(inertial.inertia.xreplace(robot.defaults)) @ R.T


def test_general_files_give_the_child_link_frame() -> None:
    """The child link frame (URDF's) computed by hand: parent frame, origin, then the motion about the axis."""
    robot = robot_from_toml(GENERAL, "bent.toml")
    inertials = sample_inertials(robot.n_joints, seed=9)
    with_data = with_file_inertials(robot, inertials)
    q = np.array([0.4, 0.15, -0.8])

    def rot(axis: np.ndarray, angle: float) -> np.ndarray:
        u = axis / np.linalg.norm(axis)
        K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
        return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K

    pose = np.eye(4)
    for joint, value, stated, inertial in zip(robot.joints, q, inertials, with_data.inertials, strict=True):
        origin = np.array(joint.placement.origin.matrix.subs(robot.defaults), dtype=float)
        axis = np.array(joint.placement.axis or (0, 0, 1), dtype=float)
        motion = np.eye(4)
        if joint.is_revolute:
            motion[:3, :3] = rot(axis, value)
        else:
            motion[:3, 3] = value * axis / np.linalg.norm(axis)
        pose = pose @ origin @ motion
        expected_com = (pose @ np.append(np.array(stated.com, dtype=float), 1))[:3]
        expected_inertia = pose[:3, :3] @ as_float(stated.inertia) @ pose[:3, :3].T
        com, inertia = world_body(with_data, inertial, joint.index, q)
        assert np.allclose(com, expected_com) and np.allclose(inertia, expected_inertia)


def test_poe_files_give_the_space_frame_at_home() -> None:
    robot = load_robot("ur5_poe")
    inertials = sample_inertials(robot.n_joints, seed=3)
    with_data = with_file_inertials(robot, inertials)
    for link, (stated, inertial) in enumerate(zip(inertials, with_data.inertials, strict=True), start=1):
        com, inertia = world_body(with_data, inertial, link, np.zeros(robot.n_joints))
        assert np.allclose(com, np.array(stated.com, dtype=float))
        assert np.allclose(inertia, as_float(stated.inertia))


@pytest.mark.parametrize(("name", "target"), marked([("planar2r", "modified"), ("planar3r", "standard"),
                                                      ("planar2r", "poe"), ("general", "modified"),
                                                      ("ur5_poe", "general")]))
def test_conversion_keeps_each_body_in_place(name: str, target: str) -> None:
    # exact DH extraction needs origin angles that are multiples of pi/12
    robot = robot_from_toml(GENERAL.replace("0.3", '"pi/6"'), "bent.toml") if name == "general" else load_robot(name)
    with_data = with_file_inertials(robot, sample_inertials(robot.n_joints, seed=5))
    converted = convert(with_data, target)
    q = np.random.default_rng(1).uniform(-1, 1, robot.n_joints)
    for link in range(1, robot.n_joints + 1):
        before = world_body(with_data, with_data.inertials[link - 1], link, q)
        after = world_body(converted, converted.inertials[link - 1], link, q)
        assert np.allclose(before[0], after[0]) and np.allclose(before[1], after[1])
        assert converted.inertials[link - 1].mass == with_data.inertials[link - 1].mass


# --- errors: one line naming the file and the link -----------------------------------------------------------------

ROW = {"type": "revolute", "a": 1}


@pytest.mark.parametrize(("inertial", "message"), [
    ({"mass": 1, "ixx": 1, "iyy": 1, "izz": 3}, r"link 2: the principal moments 1, 1, 3 break the triangle"),
    ({"mass": 1, "ixx": -1, "iyy": 1, "izz": 1}, r"link 2: the inertia tensor is not positive semi-definite"),
])
def test_data_no_body_can_have_is_kept_with_a_warning_naming_the_link(inertial: dict, message: str) -> None:
    # CAD exports round into these (URDF files of real arms do); kinematics does not need them, so the file reads
    data = {"name": "r", "convention": "standard", "parameters": {"L": 1},
            "joints": [ROW, {**ROW, "inertial": inertial}]}
    with pytest.warns(InertialWarning, match=rf"^arm\.toml, .*{message}.*\(kept as given; the dynamics refuse"):
        robot = robot_from_mapping(data, source="arm.toml")
    with pytest.warns(InertialWarning) as caught:
        robot_from_mapping(data, source="arm.toml")
    assert caught[0].filename == __file__  # the warning points at the caller's line, not into symjac
    assert robot.inertials[1] is not None and robot.inertials[1].mass == 1
    # ... but the dynamics refuse it, in one line naming the link and what is wrong
    with pytest.raises(ImpossibleInertiaError, match=rf"^r: {message}.*keep_impossible = true"):
        gravity_torques(replace(robot, inertials=(Inertial(1), robot.inertials[1])))


def test_data_kept_knowingly_reads_silently_the_dynamics_accept_and_files_keep_the_word() -> None:
    impossible = {"mass": 1, "ixx": 1, "iyy": 1, "izz": 3, "keep_impossible": True}
    data = {"name": "r", "convention": "standard", "parameters": {"L": 1},
            "joints": [{**ROW, "inertial": {"mass": 1}}, {**ROW, "inertial": impossible}]}
    with warnings.catch_warnings():
        warnings.simplefilter("error", InertialWarning)
        robot = robot_from_mapping(data, source="arm.toml")
    assert robot.inertials[1].keep_impossible and not robot.inertials[0].keep_impossible
    assert gravity_torques(robot).shape == (2, 1)
    assert robot_to_mapping(robot)["joints"][1]["inertial"]["keep_impossible"] is True
    assert with_symbolic_inertials(robot).inertials[1].keep_impossible  # the published numbers become defaults
    with pytest.raises(RobotFileError, match=r"'keep_impossible' must be true or false, got 'yes'"):
        robot_from_mapping({**data, "joints": [ROW, {**ROW, "inertial": {**impossible, "keep_impossible": "yes"}}]},
                           source="arm.toml")


@pytest.mark.parametrize(("inertial", "message"), [
    ({"mass": -1}, r"joint 2, field 'inertial': link 2: the mass -1 is negative"),
    ({"mass": 1, "inertia": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]}, r"link 2: the inertia tensor is not symmetric"),
    ({"mass": 1, "colour": "red"}, r"field 'inertial': link 2: unknown key\(s\) 'colour'"),
    ({"ixx": 1}, r"field 'inertial.mass': link 2: 'mass' is required"),
    ({"mass": 1, "com": [1, 2]}, r"field 'inertial.com': link 2: 'com' must be a list of 3"),
    ({"mass": 1, "about": "tip"}, r"field 'inertial.about': link 2: 'about' must be 'com'"),
    ({"mass": "q"}, r"field 'inertial.mass': link 2: unknown name 'q'"),
    ({"mass": "1/(L - 1)"}, r"link 2: value 1/\(L - 1\) is not a finite number"),
    ({"mass": 1, "ixx": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, r"link 2: give the tensor either"),
    ({"mass": 1, "inertia": [[1, 0, 0], [0, 1, 0]]}, r"link 2: 'inertia' must be 3 rows of 3"),
    ("heavy", r"link 2: 'inertial' must be a table"),
])
def test_file_errors_name_the_file_and_the_link(inertial: object, message: str) -> None:
    data = {"name": "r", "convention": "standard", "parameters": {"L": 1},
            "joints": [ROW, {**ROW, "inertial": inertial}]}
    with pytest.raises(RobotFileError, match=rf"^arm\.toml, {'' if message.startswith('joint') else '.*'}{message}"):
        robot_from_mapping(data, source="arm.toml")


def test_robot_checks_inertials_it_is_given() -> None:
    robot = robot_from_mapping({"name": "two", "convention": "standard", "parameters": {"L": 1},
                                "joints": [ROW, ROW]}, source="two.toml")
    with pytest.raises(RobotFileError, match=r"two\.toml, joint 2, field 'inertial': link 2: the mass -1"):
        with_file_inertials(robot, [None, Inertial(-1)])
    with pytest.raises(RobotFileError, match=r"3 inertial entries for 2 links"):
        replace(robot, inertials=(None, None, Inertial(1)))
    assert robot.inertials == (None, None)
    assert replace(robot, joints=robot.joints[:1]).inertials == (None,)  # nothing known: one None per link
    once = with_symbolic_inertials(robot, links=[1])
    assert with_symbolic_inertials(once, links=[1]) == once  # symbolic already: kept, defaults and all
    with pytest.raises(RobotFileError, match=r"link 1: the parameter m1 exists already"):
        with_symbolic_inertials(replace(once, inertials=(None, None)), links=[1])


@pytest.mark.parametrize("name", marked(["planar2r", "planar3r"]))
def test_dh_rewrites_move_the_bodies_and_come_back_exactly(name: str) -> None:
    from symjac.model.conventions.standard import modified_from_standard, standard_from_modified

    robot = load_robot(name)
    with_data = with_file_inertials(robot, sample_inertials(robot.n_joints, seed=2))
    there = (modified_from_standard if robot.convention == "standard" else standard_from_modified)(with_data)
    back = (standard_from_modified if robot.convention == "standard" else modified_from_standard)(there)
    assert back == with_data
    q = np.array([0.3, -1.1, 0.7][: robot.n_joints])
    for link in range(1, robot.n_joints + 1):
        before = world_body(with_data, with_data.inertials[link - 1], link, q)
        after = world_body(there, there.inertials[link - 1], link, q)
        assert np.allclose(before[0], after[0]) and np.allclose(before[1], after[1])


ENTRY = st.one_of(st.integers(-5, 5), st.floats(allow_nan=True, allow_infinity=True, width=32),
                  st.sampled_from(["L", "-L/2", "1/(L - 1)", "pi", "q", "", "L**9", "1e308*10", "1e-300*1e-300"]),
                  st.lists(st.integers(0, 2), max_size=4), st.none(), st.booleans())
TABLES = st.dictionaries(st.sampled_from(["mass", "com", "about", "ixx", "ixy", "iyy", "izz", "inertia", "bogus"]),
                         st.one_of(ENTRY, st.sampled_from(["com", "origin"]),
                                   st.lists(st.lists(st.integers(-2, 2), min_size=3, max_size=3), min_size=3,
                                            max_size=3)), max_size=6)


@settings(max_examples=60, deadline=None)
@given(TABLES, st.sampled_from(["standard", "general"]))
def test_any_inertial_table_gives_a_robot_or_one_line(table: dict, convention: str) -> None:
    """Hostile tables: a robot that writes back to itself, or a RobotFileError naming the file and link 1."""
    data = {"name": "r", "convention": convention, "parameters": {"L": 0.5},
            "joints": [{"type": "revolute", **({"axis": [1, 1, 0]} if convention == "general" else {}),
                        "inertial": {k: v for k, v in table.items() if v is not None}}]}
    try:
        robot = robot_from_mapping(data, source="fuzz.toml")
    except RobotFileError as error:
        assert str(error).startswith("fuzz.toml, joint 1, field 'inertial") and "link 1: " in str(error)
        assert "\n" not in str(error)
        return
    assert robot_from_toml(robot_to_toml(robot)) == robot
