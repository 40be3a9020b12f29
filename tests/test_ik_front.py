"""The inverse-kinematics front end: solutions checked by an independent forward kinematics, method and errors.

The independent forward kinematics is the symbolic chain's (``forward_kinematics`` from {0} to the end of the chain,
evaluated by SymPy at the solution), not the compiled model the solver and the front end's own check run on.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize

import symjac
from symjac import inverse_kinematics, load_robot, numeric_model, pose_from_rpy
from symjac.analysis.inverse_kinematics import seed_bounds, solve_numeric
from symjac.errors import ArgumentError, OrientationNeededError, UnknownRobotError
from symjac.kinematics.chain import forward_kinematics
from symjac.kinematics.numeric import numeric_at
from symjac.model.ends import last_frame
from symjac.solvers import controlled_components


def independent_fk(robot, q) -> np.ndarray:
    return numeric_at(robot, forward_kinematics(robot, 0, last_frame(robot)), list(map(float, q)))


def assert_reaches(robot, result, *, position_only=False):
    for solution in result.solutions:
        T = independent_fk(robot, solution.q)
        assert np.allclose(T[:3, 3], result.pose[:3, 3], atol=1e-9), (solution.q, T, result.pose)
        if not position_only:
            assert np.allclose(T[:3, :3], result.pose[:3, :3], atol=1e-8)
        assert solution.position_error < 1e-9


def test_the_api_is_at_the_top_level():
    assert symjac.inverse_kinematics is inverse_kinematics
    assert {"inverse_kinematics", "InverseKinematicsResult", "pose_from_rpy", "pose_from_quaternion"} <= set(
        symjac.__all__)


@pytest.mark.parametrize(("name", "q"), [("planar3r", [0.3, 0.5, -0.2]),
                                         ("puma560", [0.3, -0.5, 0.4, 0.2, 0.6, -0.1]),
                                         ("panda", [0.1, 0.2, 0.3, -1.5, 0.2, 1.0, 0.3])])
def test_numeric_solutions_reach_the_pose_and_include_the_one_that_made_it(name, q):
    robot = load_robot(name)
    pose = independent_fk(robot, q)
    result = inverse_kinematics(robot, pose, method="numeric", seed=q)
    assert result.method == "numeric" and result.why == "numeric: asked for"
    assert result.solutions and not result.unreachable and result.family == ""
    assert_reaches(robot, result)
    assert any(np.allclose(s.q, q, atol=1e-7) for s in result.solutions)
    assert all(s.within_limits and s.branch == () for s in result.solutions)


def test_the_numeric_solver_is_deterministic_for_a_given_rng():
    robot = load_robot("puma560")
    pose = independent_fk(robot, [0.3, -0.5, 0.4, 0.2, 0.6, -0.1])
    first, again = (inverse_kinematics(robot, pose, method="numeric", rng=3) for _ in range(2))
    assert [s.q.tolist() for s in first.solutions] == [s.q.tolist() for s in again.solutions]


def test_an_arm_that_places_a_point_finds_both_elbows():
    robot = load_robot("planar2r")
    pose = pose_from_rpy([0.6, 0.3, 0.0], [0.0, 0.0, 1.0])  # the orientation is not the arm's to set
    result = inverse_kinematics(robot, pose, method="numeric")
    assert result.controlled.position_only and result.controlled.not_set.endswith("(it follows from the position)")
    assert len(result.solutions) == 2
    assert_reaches(robot, result, position_only=True)
    turned = sum(result.solutions[0].q) - 1.0  # the 2R arm's tool turns by theta1 + theta2 about z
    assert result.uncontrolled == (f"the orientation reached differs from the target's by "
                                   f"{abs(np.angle(np.exp(1j * turned))):.4g} rad (the arm does not set it)")
    elbows = sorted(np.sign(s.q[1]) for s in result.solutions)
    assert elbows == [-1.0, 1.0]  # elbow down and up
    L1, L2 = 0.5, 0.4  # the defaults: theta2 = +-acos((x^2 + y^2 - L1^2 - L2^2) / (2 L1 L2))
    expected = np.arccos((0.6**2 + 0.3**2 - L1**2 - L2**2) / (2 * L1 * L2))
    assert np.allclose(sorted(abs(s.q[1]) for s in result.solutions), [expected, expected])


def test_an_unreachable_pose_says_so():
    robot = load_robot("planar2r")
    result = inverse_kinematics(robot, pose_from_rpy([2.0, 0.0, 0.0], [0, 0, 0]), method="numeric")
    assert result.solutions == () and abs(result.distance - (2.0 - 0.9)) < 1e-5  # |p| - (L1 + L2)
    assert result.unreachable.startswith("none of the numeric solver's 8 or more starts converged: no solution found; "
                                         "the closest configuration reached is 1.1 m and")
    assert "probably out of reach (a numeric search proves nothing)" in result.unreachable


def test_within_limits_false_keeps_and_flags_solutions_outside():
    robot = load_robot("planar2r")
    pose = independent_fk(robot, [0.2, 0.9])
    inside = inverse_kinematics(robot, pose, method="numeric")
    every = inverse_kinematics(robot, pose, method="numeric", within_limits=False)
    assert len(every.solutions) >= len(inside.solutions)
    assert all(isinstance(s.within_limits, bool) for s in every.solutions)


@pytest.mark.parametrize(("name", "sets", "not_set"), [
    ("planar2r", "x and y", "z (fixed by the arm's geometry); the orientation (it follows from the position)"),
    ("planar3r", "x, y and the rotation about z", "z, the rotation about x and the rotation about y (fixed by the "
                 "arm's geometry)"),
    ("articulated3r", "x, y and z", "the orientation (it follows from the position)"),
    ("scara", "x, y, z and the rotation about z", "the rotation about x and the rotation about y (fixed by the arm's "
              "geometry)"),
    ("puma560", "the whole pose", ""),
])
def test_the_components_an_arm_sets(name, sets, not_set):
    controlled = controlled_components(load_robot(name))
    assert (controlled.sets, controlled.not_set) == (sets, not_set)


def test_the_components_follow_the_jacobians_rows():
    """Independent of the words: the fixed rows are zero in the symbolic Jacobian, the rank is its generic rank."""
    import sympy as sp

    from symjac import jacobian

    for name in ("planar2r", "planar3r", "scara"):
        robot = load_robot(name)
        controlled = controlled_components(robot)
        J = jacobian(robot).xreplace(robot.defaults)
        zero = tuple(k for k in range(6) if all(sp.simplify(entry) == 0 for entry in J.row(k)))
        assert set(controlled.fixed) == {k for k in zero if k < 3 or not controlled.position_only}
        at = dict(zip(robot.q, [0.3, 0.7, 0.2, 0.1][:robot.n_coordinates], strict=True))
        assert controlled.rank == J.xreplace(at).rank()


@pytest.mark.parametrize(("call", "error", "message"), [
    (lambda: inverse_kinematics("planar2r", np.full((4, 4), np.nan)), ArgumentError, r"pose: the pose matrix entry"),
    (lambda: inverse_kinematics("planar2r", np.eye(3)), ArgumentError, r"must have shape 3 x 4, got shape 3 x 3"),
    (lambda: inverse_kinematics("planar2r", pose_from_rpy([0, 0, 0], [0, 0, 0]) * 2), ArgumentError,
     r"last row of a pose"),
    (lambda: inverse_kinematics("no_such_robot", np.eye(4)), UnknownRobotError, r"no_such_robot"),
    (lambda: inverse_kinematics("planar2r", np.eye(4), method="fastest"), ArgumentError,  # type: ignore[arg-type]
     r"method must be one of auto, closed_form, numeric, got 'fastest'"),
    (lambda: inverse_kinematics("planar2r", np.eye(4), method="numeric", seed=[0.0]), ArgumentError,
     r"seed must be 2 finite numbers for planar2r"),
    (lambda: inverse_kinematics("planar2r", np.eye(4), free_joint=5), ArgumentError,
     r"free_joint is a joint number, 1 to 2 for planar2r, got 5"),
    (lambda: inverse_kinematics("palletizer", np.eye(4), method="numeric"), ArgumentError,
     r"palletizer's joints are coupled and the numeric solver works joint by joint \(numeric: asked for"),
    (lambda: inverse_kinematics(3, np.eye(4)), ArgumentError, r"robot must be a Robot or a robot's name, got int"),
    (lambda: inverse_kinematics("puma560", [0.5, 0.1, 0.2]), OrientationNeededError,
     r"puma560 sets the whole pose, so a position alone is not a pose for it"),
    (lambda: inverse_kinematics("planar2r", [0.5, np.nan, 0.0]), ArgumentError, r"position: .* is nan"),
    (lambda: inverse_kinematics("puma560", np.eye(4), free_value=0.3), ArgumentError,
     r"the free value \(a given joint's value\) applies to a redundant arm's closed form only, and for puma560 its"),
])
def test_each_bad_argument_is_one_line(call, error, message):
    with pytest.raises(error, match=message) as raised:
        call()
    assert "\n" not in str(raised.value)


def test_the_front_ends_check_uses_the_compiled_model():
    """The reported errors are the compiled forward kinematics' (the same numbers the test's FK gives)."""
    robot = load_robot("planar3r")
    pose = independent_fk(robot, [0.3, 0.5, -0.2])
    result = inverse_kinematics(robot, pose, method="numeric")
    model = numeric_model(robot)
    for solution in result.solutions:
        T = model.fk(solution.q)
        assert solution.position_error == pytest.approx(np.linalg.norm(T[:3, 3] - pose[:3, 3]), abs=1e-15)
        assert solution.orientation_error < 1e-9


# --- the closed form, where the geometry has one ---------------------------------------------------------------------

PUMA_Q = [0.4, -0.6, 0.3, 0.5, 0.7, -0.2]


def test_the_puma_is_solved_in_closed_form_with_its_eight_postures():
    robot = load_robot("puma560")
    pose = independent_fk(robot, PUMA_Q)
    result = inverse_kinematics(robot, pose, within_limits=False)
    assert result.method == "closed_form" and result.family == "spherical wrist"
    assert result.why.startswith("closed form (spherical wrist): the axes of joints 4, 5 and 6 meet at the wrist")
    assert result.reasons and result.plan is not None and result.controlled.whole_pose
    assert len(result.solutions) == 8 and len({s.branch for s in result.solutions}) == 8
    assert_reaches(robot, result)
    assert any(np.allclose(s.q, PUMA_Q, atol=1e-9) for s in result.solutions)
    inside = inverse_kinematics(robot, pose)
    assert len(inside.solutions) + inside.outside_limits == 8
    assert all(s.within_limits for s in inside.solutions)


def test_auto_says_why_there_is_no_closed_form_and_closed_form_refuses():
    from symjac.errors import NoClosedFormError

    robot = load_robot("panda")
    pose = independent_fk(robot, [0.1, 0.2, 0.3, -1.5, 0.2, 1.0, 0.3])
    result = inverse_kinematics(robot, pose)
    assert result.method == "numeric" and result.why.startswith("numeric, as there is no closed form: panda: ")
    with pytest.raises(NoClosedFormError, match=r"^panda: no closed-form family fits") as raised:
        inverse_kinematics(robot, pose, method="closed_form")
    assert "\n" not in str(raised.value)


def test_a_redundant_arm_in_closed_form_with_its_free_joint_given():
    robot = load_robot("iiwa7")
    q = [0.1, 0.2, 0.3, -1.5, 0.2, 1.0, 0.3]
    pose = independent_fk(robot, q)
    result = inverse_kinematics(robot, pose, free_value=0.3, free_joint=3, within_limits=False)
    assert result.method == "closed_form" and "joint 3 is given" in result.why
    assert_reaches(robot, result)
    assert any(np.allclose(s.q, q, atol=1e-9) for s in result.solutions)
    assert inverse_kinematics(robot, pose).method == "numeric"  # no free_value: numeric


def test_a_pose_out_of_reach_says_how_far():
    robot = load_robot("puma560")
    pose = pose_from_rpy([3.0, 0.0, 0.5], [0.0, 0.0, 0.0])
    result = inverse_kinematics(robot, pose)
    assert result.method == "closed_form" and result.solutions == ()
    assert result.unreachable and result.distance > 1.0


def test_a_wrist_singularity_is_described_not_divided_by(cli):
    robot = load_robot("puma560")
    q = [0.4, -0.6, 0.3, 0.5, 0.0, -0.2]  # theta5 = 0: axes 4 and 6 line up
    result = inverse_kinematics(robot, independent_fk(robot, q), within_limits=False)
    assert_reaches(robot, result)
    (singular,) = [s for s in result.solutions if s.singular]
    assert singular.singular == "theta4 + theta6 = 0.3 is fixed; theta4 shown at 0; wrist flip and no flip coincide"
    assert abs(singular.q[3] + singular.q[5] - (q[3] + q[5])) < 1e-9
    data = cli.json("ik", "puma560", "--q", ",".join(map(str, q)), "--no-within-limits")
    assert [s["singular"] for s in data["solutions"] if s["singular"]] == [singular.singular]
    text = cli.ok("ik", "puma560", "--q", ",".join(map(str, q)), "--no-within-limits", "--format", "pretty")
    assert "singular: theta4 + theta6 = 0.3 is fixed; theta4 shown at 0" in text


@pytest.mark.parametrize("name", ["puma560", "stanford", "irb140"])
def test_random_reachable_poses_round_trip(name):
    """Poses from random configurations within the limits: the one that made each pose is among its solutions."""
    from symjac.analysis.inverse_kinematics import seed_bounds

    robot = load_robot(name)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(46)
    for q in generator.uniform(lower, upper, size=(12, robot.n_coordinates)):
        pose = independent_fk(robot, q)
        result = inverse_kinematics(robot, pose)
        assert result.method == "closed_form"
        assert_reaches(robot, result)
        # revolute joints compare modulo 2 pi: a joint with limits wider than 2 pi reports one of its aliases
        revolute = np.array([joint.is_revolute for joint in robot.joints])
        same = [np.allclose(np.where(revolute, np.angle(np.exp(1j * (s.q - q))), s.q - q), 0.0, atol=1e-8)
                for s in result.solutions]
        assert any(same), (q, [s.q for s in result.solutions])


def test_a_coupled_arm_is_solved_in_its_coordinates():
    """The palletizer (theta4 = -theta2 - theta3 keeps link 4 level): solutions give its four coordinates."""
    robot = load_robot("palletizer")
    q = [0.3, 0.4, 0.5, 0.2]
    pose = independent_fk(robot, q)
    result = inverse_kinematics(robot, pose, within_limits=False)
    assert result.method == "closed_form" and result.family == "palletizer"
    assert all(s.q.shape == (4,) for s in result.solutions)
    assert_reaches(robot, result)
    assert any(np.allclose(s.q, q, atol=1e-9) for s in result.solutions)


def test_a_numeric_pose_out_of_reach_says_how_far_the_closest_configuration_is():
    robot = load_robot("panda")
    # the reach from the shoulder (joint 2's axis, 0.333 m up) by an independent search: the farthest tool point of
    # random configurations, polished by Nelder-Mead on the symbolic forward kinematics
    shoulder, (lower, upper) = np.array([0.0, 0.0, 0.333]), seed_bounds(robot)
    generator = np.random.default_rng(3)

    def far(q):
        return -np.linalg.norm(independent_fk(robot, np.clip(q, lower, upper))[:3, 3] - shoulder)

    best = min((generator.uniform(lower, upper) for _ in range(300)), key=far)
    reach = -minimize(far, best, method="Nelder-Mead", options={"xatol": 1e-8, "fatol": 1e-10}).fun
    pose = pose_from_rpy([2.0, 0.0, 0.333], [0.0, 0.0, 0.0])
    gap = 2.0 - reach
    position_only = solve_numeric(robot, pose, numeric_model(robot), orientation_weight=0.0)
    assert position_only == [] and abs(position_only.closest.position_error - gap) < 5e-3
    result = inverse_kinematics(robot, pose, method="numeric")
    assert result.solutions == () and gap - 5e-3 < result.distance < gap + 0.1  # position traded for orientation
    assert f"the closest configuration reached is {result.distance:.3g} m and " in result.unreachable


def test_a_position_alone_is_a_target_for_an_arm_that_sets_no_orientation():
    robot = load_robot("articulated3r")
    q = [0.4, -0.3, 0.9]
    position = independent_fk(robot, q)[:3, 3]
    result = inverse_kinematics(robot, position)
    assert result.controlled.position_only and result.uncontrolled == ""
    assert any(np.allclose(s.q, q, atol=1e-9) for s in result.solutions)
    assert_reaches(robot, result, position_only=True)
    assert np.allclose(result.pose, np.block([[np.eye(3), position[:, None]], [np.zeros((1, 3)), 1.0]]))


def test_str_is_a_short_summary_and_repr_stays_whole():
    robot = load_robot("puma560")
    result = inverse_kinematics(robot, independent_fk(robot, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]))
    lines = str(result).splitlines()
    kept = len(result.solutions)
    assert lines[0] == (f"puma560: {kept} solutions, closed form (spherical wrist); {result.outside_limits} more "
                        "outside the joint limits (within_limits=False keeps them)")
    assert len(lines) == 1 + kept and "shoulder left, elbow up, no flip" in str(result)
    assert "q = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]" in str(result)
    assert repr(result).startswith("InverseKinematicsResult(robot='puma560'")


def test_a_position_alone_out_of_the_plane_differs_in_position_only():
    result = inverse_kinematics("planar2r", [0.5, 0.3, 0.2])  # the arm's plane is z = 0
    assert len(result.solutions) == 2
    assert result.uncontrolled == ("the arm sets x and y only: the target position differs from the one it "
                                   "reaches by 0.2")
    assert "orientation" not in str(result) and result.position_alone  # none was given, so none can differ


@pytest.mark.parametrize(("name", "options", "hint"), [
    ("iiwa7", {}, "; a redundant arm's closed form takes one joint's value: free_value=V (joint 1's, or free_joint=K "
                  "for joint K)"),
    ("panda", {}, "; use the numeric solver (method='auto' or 'numeric')"),  # no joint given leaves a closed form
    ("panda", {"free_value": 0.2, "free_joint": 4},
     "; use the numeric solver (without free_value, method='auto' or 'numeric')"),
])
def test_no_closed_form_ends_with_what_to_pass_in_python(name, options, hint):
    pose = numeric_model(load_robot(name)).fk([0, 0.3, 0, -1, 0, 1, 0.2])
    with pytest.raises(symjac.errors.NoClosedFormError) as raised:
        inverse_kinematics(name, pose, method="closed_form", **options)
    assert str(raised.value).endswith(hint) and "--" not in str(raised.value)
