"""Representation Jacobians J_x = E(x) J_0: rate maps, extraction, representation singularities, robots.

Independent checks: finite differences of coordinates extracted from plain-NumPy forward kinematics
(tests/reference.py), finite differences of rotation matrices for angular velocities, exact SymPy identities against
the printed matrices of the course notes, and round trips through extraction (also at gimbal lock).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from marks import marked
from reference import frames, random_configuration
from strategies import robots

from symjac import load_robot, robot_from_mapping
from symjac.analysis.representations import (
    EULER_CONVENTIONS,
    EULER_ORDERS,
    POSITIONS,
    REPRESENTATIONS,
    EulerConvention,
    RepresentationError,
    angular_velocity_matrix,
    coordinate_rates,
    coordinates,
    extract,
    extract_position,
    point_from,
    position_rate_matrix,
    rate_matrix,
    representation,
    representation_jacobian,
    representation_jacobian_at,
    representation_jacobian_derivative,
    representation_jacobian_derivative_at,
    representation_singularities,
    rotation_from,
)
from symjac.errors import ArgumentError
from symjac.kinematics.acceleration import jacobian_derivative
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.symbolic.transforms import rotation_rpy, skew

SETTINGS = settings(deadline=None, max_examples=20, suppress_health_check=[HealthCheck.too_slow])
# all 24 Euler / Tait-Bryan conventions (12 intrinsic, 12 extrinsic including "rpy")
PROPER = [c.name for c in EULER_CONVENTIONS if c.is_proper]
TAIT_BRYAN = [c.name for c in EULER_CONVENTIONS if not c.is_proper]
ANGLE_SETS = [c.name for c in EULER_CONVENTIONS]
H = 1e-6


# --- numeric helpers ---------------------------------------------------------------------------------------------


def numeric(matrix: sp.MatrixBase) -> np.ndarray:
    return np.array(sp.Matrix(matrix).evalf(), dtype=float)


def rotation_numeric(name: str, x) -> np.ndarray:
    return numeric(rotation_from(name, [float(v) for v in x]))


def rate_numeric(name: str, x) -> np.ndarray:
    return numeric(rate_matrix(name, [float(v) for v in x]))


def exp_so3(w: np.ndarray) -> np.ndarray:
    angle = float(np.linalg.norm(w))
    if angle == 0.0:
        return np.eye(3)
    K = np.array(skew(list(w / angle)), dtype=float)
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    return rotation_numeric("quaternion", q)


def vee(W: np.ndarray) -> np.ndarray:
    return np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]]) / 2


def angle_indices(name: str) -> list[int]:
    """Coordinates that are angles and may wrap by 2 pi between neighbouring samples."""
    return {"spherical": [1, 2], "cylindrical": [1]}.get(name, [0, 1, 2] if name in ANGLE_SETS else [])


def align(name: str, x: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """``x`` moved to the branch of ``centre``: angles unwrapped, quaternion sign and axis-angle flip undone."""
    x = x.copy()
    if name == "quaternion" and x @ centre < 0:
        x = -x
    if name == "axis_angle" and x[:3] @ centre[:3] < 0:
        x[:3], x[3] = -x[:3], 2 * math.pi - x[3]
    for i in angle_indices(name):
        x[i] = centre[i] + math.remainder(x[i] - centre[i], 2 * math.pi)
    return x


def central_difference(name: str, extract_at, h: float = H) -> np.ndarray:
    centre = extract_at(0.0)
    return (align(name, extract_at(h), centre) - align(name, extract_at(-h), centre)) / (2 * h)


def factor_values(name: str, x) -> list[float]:
    values = dict(zip(coordinates(name), [float(v) for v in x], strict=True))
    return [float(s.factor.xreplace(values)) for s in representation_singularities(name)]


# --- definitions against the seeds --------------------------------------------------------------------------------


def test_zyz_rotation_is_seed_002_matrix():
    a, b, g = coordinates("zyz")
    ca, sa, cb, sb, cg, sg = sp.cos(a), sp.sin(a), sp.cos(b), sp.sin(b), sp.cos(g), sp.sin(g)
    seed = sp.Matrix([[ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb],
                      [sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb],
                      [-sb * cg, sb * sg, cb]])
    assert (rotation_from("zyz") - seed).expand() == sp.zeros(3, 3)


def test_printed_rate_matrix_of_seed_000_is_zxz_and_zyz_differs():
    """Course chapter (4.31): E_r of Z-X-Z angles with omega in {0}; the Z-Y-Z wrist angles give another matrix."""
    a, b, _ = coordinates("zxz")
    ca, sa, cb, sb = sp.cos(a), sp.sin(a), sp.cos(b), sp.sin(b)
    printed = sp.Matrix([[-sa * cb / sb, ca * cb / sb, 1], [ca, sa, 0], [sa / sb, -ca / sb, 0]])
    assert rate_matrix("zxz") == printed
    zyz = sp.Matrix([[-ca * cb / sb, -sa * cb / sb, 1], [-sa, ca, 0], [ca / sb, sa / sb, 0]])
    assert rate_matrix("zyz") == zyz


def test_rpy_is_the_robot_file_convention_and_reversed_zyx():
    phi, theta, psi = coordinates("rpy")
    assert rotation_from("rpy") == rotation_rpy(phi, theta, psi)
    assert rotation_from("zyx", [psi, theta, phi]) == rotation_from("rpy")


@pytest.mark.parametrize("order", EULER_ORDERS)
def test_euler_rotation_is_the_product_about_moving_axes(order):
    from symjac.symbolic.transforms import rotation

    a, b, g = coordinates(order)
    assert rotation_from(order) == rotation(order[0], a) * rotation(order[1], b) * rotation(order[2], g)


def test_quaternion_and_axis_angle_describe_the_same_rotation():
    rng = np.random.default_rng(1)
    for _ in range(5):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        angle = rng.uniform(0, math.pi)
        R = rotation_numeric("axis_angle", [*k, angle])
        np.testing.assert_allclose(R, exp_so3(angle * k), atol=1e-14)
        np.testing.assert_allclose(rotation_numeric("quaternion", [math.cos(angle / 2), *(math.sin(angle / 2) * k)]),
                                   R, atol=1e-14)


def test_position_maps():
    r, _, _ = coordinates("spherical")
    p = point_from("spherical")
    assert sp.simplify(p.dot(p) - r**2) == 0
    assert point_from("cartesian", [1, 2, 3]) == sp.Matrix([1, 2, 3])
    assert point_from("cylindrical", [2, sp.pi / 2, 5]) == sp.Matrix([0, 2, 5])
    assert position_rate_matrix("cartesian") == sp.eye(3)


# --- all 24 Euler / Tait-Bryan conventions as values -----------------------------------------------------------


def test_registry_names_every_convention_once():
    assert len(EULER_CONVENTIONS) == len(set(EULER_CONVENTIONS)) == 24
    assert sum(c.extrinsic for c in EULER_CONVENTIONS) == 12
    assert tuple(c.name for c in EULER_CONVENTIONS if not c.extrinsic) == EULER_ORDERS
    assert set(EULER_ORDERS) == {"zyz", "zxz", "xyx", "xzx", "yxy", "yzy", "xyz", "xzy", "yxz", "yzx", "zxy", "zyx"}
    assert len(set(REPRESENTATIONS)) == len(REPRESENTATIONS)
    assert set(ANGLE_SETS) | {"direction_cosines", "quaternion", "axis_angle"} <= set(REPRESENTATIONS)
    assert all(representation(name).kind == "orientation" for name in REPRESENTATIONS)
    for convention in EULER_CONVENTIONS:
        assert representation(convention.name) == convention
        assert representation(convention) is convention
        expected = "rpy" if convention.is_rpy else convention.axes + ("_extrinsic" if convention.extrinsic else "")
        assert convention.name == expected
    assert {"cartesian", "spherical", "cylindrical"} <= set(POSITIONS)
    assert all(representation(name).kind == "position" for name in POSITIONS)
    with pytest.raises(RepresentationError, match="Euler axes must be one of"):
        EulerConvention("zzy")
    with pytest.raises(RepresentationError, match="unknown orientation representation 'cartesian'"):
        rotation_from("cartesian")


def test_rpy_is_the_extrinsic_xyz_convention():
    rpy = EulerConvention("xyz", extrinsic=True)
    assert representation("rpy") == rpy and representation("xyz_extrinsic") == rpy
    assert coordinates(rpy) == coordinates("rpy") == coordinates("xyz_extrinsic")
    assert rotation_from(rpy) == rotation_from("rpy") == rotation_from("xyz_extrinsic")
    assert rate_matrix(rpy) == rate_matrix("rpy")


@pytest.mark.parametrize("convention", EULER_CONVENTIONS, ids=lambda c: c.name)
def test_convention_rotation_is_the_product_of_elementary_rotations(convention):
    """Intrinsic: about the moving axes, left to right; extrinsic: about the fixed axes, so right to left."""
    from symjac.symbolic.transforms import rotation

    a, b, c = coordinates(convention)
    first, second, third = (rotation(axis, angle) for axis, angle in zip(convention.axes, (a, b, c), strict=True))
    expected = third * second * first if convention.extrinsic else first * second * third
    assert rotation_from(convention) == expected
    assert rotation_from(convention.name) == expected


@pytest.mark.parametrize("axes", [c.axes for c in EULER_CONVENTIONS if not c.extrinsic])
def test_extrinsic_is_intrinsic_with_axes_and_angles_reversed(axes):
    a, b, c = sp.symbols("a b c", real=True)
    extrinsic = rotation_from(EulerConvention(axes, extrinsic=True), [a, b, c])
    assert extrinsic == rotation_from(EulerConvention(axes[::-1]), [c, b, a])


@pytest.mark.parametrize("name", ANGLE_SETS)
def test_every_convention_B_from_rotation_differences_and_E_B_identity(name):
    """omega = B xdot against vee(R_dot R^T) by central differences; E B = I at the same points."""
    rng = np.random.default_rng(sum(map(ord, name)))
    checked = 0
    while checked < 3:
        x0 = rng.uniform(-math.pi, math.pi, 3)
        if min(abs(v) for v in factor_values(name, x0)) < 0.1:
            continue
        x_dot = rng.normal(size=3)
        R_dot = (rotation_numeric(name, x0 + H * x_dot) - rotation_numeric(name, x0 - H * x_dot)) / (2 * H)
        omega = vee(R_dot @ rotation_numeric(name, x0).T)
        B = numeric(angular_velocity_matrix(name, list(x0)))
        np.testing.assert_allclose(B @ x_dot, omega, atol=1e-8, err_msg=name)
        np.testing.assert_allclose(rate_numeric(name, x0) @ B, np.eye(3), atol=1e-12, err_msg=name)
        checked += 1


@pytest.mark.parametrize("name", ANGLE_SETS)
def test_every_convention_extraction_round_trip_random_and_at_gimbal_lock(name):
    rng = np.random.default_rng(sum(map(ord, name)) + 1)
    for _ in range(5):
        R = random_rotation(rng)
        np.testing.assert_allclose(rotation_numeric(name, extract(name, R)), R, atol=1e-12, err_msg=name)
    (singularity,) = representation_singularities(name)
    for lock in singularity.solutions:
        for offset in (0.0, 1e-10):
            x = np.array([rng.uniform(-3, 3), float(lock) + offset, rng.uniform(-3, 3)])
            R = rotation_numeric(name, x)
            y = extract(name, R)
            np.testing.assert_allclose(rotation_numeric(name, y), R, atol=1e-12, err_msg=f"{name} {lock} {offset}")
            if offset == 0.0:
                assert y[representation(name).leftmost] == 0.0


@pytest.mark.parametrize("name", ANGLE_SETS)
def test_every_convention_is_singular_exactly_where_det_B_vanishes(name):
    convention = representation(name)
    (singularity,) = representation_singularities(name)
    middle = coordinates(name)[1]
    assert singularity.variable == middle
    assert str(singularity.factor) == f"{'sin' if convention.is_proper else 'cos'}({middle})"
    assert sp.simplify(angular_velocity_matrix(name).det() ** 2 - singularity.factor**2) == 0
    assert "gimbal lock" in str(singularity)


def test_a_convention_value_is_accepted_wherever_a_name_is():
    convention = EulerConvention("zyx", extrinsic=True)
    R = random_rotation(np.random.default_rng(29))
    np.testing.assert_array_equal(extract(convention, R), extract("zyx_extrinsic", R))
    assert angular_velocity_matrix(convention) == angular_velocity_matrix("zyx_extrinsic")
    assert representation_singularities(convention) == representation_singularities("zyx_extrinsic")
    robot = load_robot("puma560")
    by_value = representation_jacobian(robot, convention, "spherical")
    assert by_value == representation_jacobian(robot, "zyx_extrinsic", "spherical")
    assert by_value.orientation == "zyx_extrinsic"
    q = _configuration(robot, np.random.default_rng(31), convention, "spherical", 0, "wrist")
    rates = np.ones(robot.n_coordinates)
    value = _check_against_finite_differences(robot, q, rates, convention, "spherical", 0, "wrist")
    assert value.x.shape == (6,)


def test_package_all_is_sorted_and_complete():
    import symjac.analysis.representations as package

    def group(name):
        return (0 if name.isupper() else 1 if name[0].isupper() else 2, name)

    assert package.__all__ == sorted(package.__all__, key=group)
    assert all(hasattr(package, name) for name in package.__all__)


# --- rate matrices ---------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ANGLE_SETS)
def test_rate_matrix_inverts_angular_velocity_matrix_exactly(name):
    product = (rate_matrix(name) * angular_velocity_matrix(name)).applyfunc(sp.simplify)
    assert product == sp.eye(3)


@pytest.mark.parametrize("kind", POSITIONS)
def test_position_rate_matrix_inverts_the_coordinate_jacobian_exactly(kind):
    B_p = point_from(kind).jacobian(sp.Matrix(coordinates(kind)))
    assert (position_rate_matrix(kind) * B_p).applyfunc(sp.simplify) == sp.eye(3)


def test_redundant_rate_maps_have_their_left_inverses():
    eta, *eps = coordinates("quaternion")
    norm = eta**2 + sum(e**2 for e in eps)
    assert (angular_velocity_matrix("quaternion") * rate_matrix("quaternion") - norm * sp.eye(3)).expand() == \
        sp.zeros(3, 3)
    rng = np.random.default_rng(3)
    for name in ("direction_cosines", "axis_angle"):
        for _ in range(5):
            x = extract(name, random_rotation(rng))
            B = numeric(angular_velocity_matrix(name, list(x)))
            np.testing.assert_allclose(B @ rate_numeric(name, x), np.eye(3), atol=1e-12, err_msg=name)


def test_redundant_rates_keep_their_constraints_exactly():
    """q^T qdot = 0 (unit quaternion), k^T kdot = 0 (unit axis), d(R^T R)/dt = 0, for every omega."""
    q = sp.Matrix(coordinates("quaternion"))
    assert (q.T * rate_matrix("quaternion")).expand() == sp.zeros(1, 3)
    k = sp.Matrix(coordinates("axis_angle")[:3])
    assert (k.T * rate_matrix("axis_angle")[:3, :]).applyfunc(sp.simplify) == sp.zeros(1, 3)
    R = sp.Matrix(3, 3, coordinates("direction_cosines"))
    w = sp.symbols("w_x w_y w_z", real=True)
    R_dot = (rate_matrix("direction_cosines") * sp.Matrix(w)).reshape(3, 3)
    assert (R.T * R_dot + R_dot.T * R).expand() == sp.zeros(3, 3)
    assert (R_dot - skew(w) * R).expand() == sp.zeros(3, 3)


@SETTINGS
@given(name=st.sampled_from(ANGLE_SETS), seed=st.integers(0, 2**16))
def test_angular_velocity_from_rotation_differences(name, seed):
    """omega = E_r^-1 xdot against (R(t + h) - R(t - h)) R(t)^T / 2h along x(t) = x0 + t xdot."""
    rng = np.random.default_rng(seed)
    x0 = rng.uniform(-math.pi, math.pi, 3)
    assume(min(abs(v) for v in factor_values(name, x0)) > 0.05)
    x_dot = rng.normal(size=3)
    R_plus, R_minus = rotation_numeric(name, x0 + H * x_dot), rotation_numeric(name, x0 - H * x_dot)
    omega = vee((R_plus - R_minus) / (2 * H) @ rotation_numeric(name, x0).T)
    np.testing.assert_allclose(np.linalg.solve(rate_numeric(name, x0), x_dot), omega, atol=1e-7)
    np.testing.assert_allclose(numeric(angular_velocity_matrix(name, list(x0))) @ x_dot, omega, atol=1e-7)


@SETTINGS
@given(name=st.sampled_from(REPRESENTATIONS), seed=st.integers(0, 2**16))
def test_rates_of_extracted_coordinates_are_E_omega(name, seed):
    """xdot = E_r(x) omega against central differences of extract(exp(t omega^) R0)."""
    rng = np.random.default_rng(seed)
    R0 = random_rotation(rng)
    x0 = extract(name, R0)
    assume(min((abs(v) for v in factor_values(name, x0)), default=1.0) > 0.05)
    omega = rng.normal(size=3)
    x_dot = central_difference(name, lambda t: extract(name, exp_so3(t * omega) @ R0))
    np.testing.assert_allclose(rate_numeric(name, x0) @ omega, x_dot, rtol=1e-5, atol=1e-6)


@SETTINGS
@given(kind=st.sampled_from(POSITIONS), seed=st.integers(0, 2**16))
def test_position_rates_of_extracted_coordinates_are_E_v(kind, seed):
    rng = np.random.default_rng(seed)
    p0, v = rng.normal(size=3), rng.normal(size=3)
    x0 = extract_position(kind, p0)
    assume(min((abs(f) for f in factor_values(kind, x0)), default=1.0) > 0.05)
    x_dot = central_difference(kind, lambda t: extract_position(kind, p0 + t * v))
    E_p = numeric(position_rate_matrix(kind, list(x0)))
    np.testing.assert_allclose(E_p @ v, x_dot, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(numeric(point_from(kind, list(x0))).ravel(), p0, atol=1e-12)


# --- representation singularities ------------------------------------------------------------------------------


def test_zyz_singular_condition_is_exactly_sin_beta():
    _, beta, _ = coordinates("zyz")
    assert sp.simplify(angular_velocity_matrix("zyz").det() + sp.sin(beta)) == 0
    (singularity,) = representation_singularities("zyz")
    assert singularity.factor == sp.sin(beta)
    assert singularity.variable == beta and set(singularity.solutions) == {0, sp.pi}
    assert "gimbal lock" in str(singularity)


@pytest.mark.parametrize("name", [*ANGLE_SETS, "cartesian", "spherical", "cylindrical"])
def test_det_is_a_constant_times_the_reported_factors(name):
    """det B = c * prod(factor^m) with c a nonzero number: B (and E) fail exactly on the reported set."""
    B = angular_velocity_matrix(name) if name in ANGLE_SETS else \
        point_from(name).jacobian(sp.Matrix(coordinates(name)))
    constant, factors = sp.factor_list(sp.simplify(B.det()))
    singularities = representation_singularities(name)
    assert constant != 0
    assert {base for base, _ in factors} == {s.factor for s in singularities}, (name, factors)
    for singularity in singularities:
        for solution in singularity.solutions:
            assert singularity.factor.subs(singularity.variable, solution) == 0
    expected = {"cartesian": [], "spherical": ["r", "sin(theta_s)"], "cylindrical": ["rho"], "rpy": ["cos(theta)"]}
    default = ["sin(beta)"] if name in PROPER else ["cos(beta)"]
    assert [str(s.factor) for s in singularities] == expected.get(name, default)


@pytest.mark.parametrize("name", [*ANGLE_SETS, "spherical", "cylindrical"])
def test_E_blows_up_on_the_singular_set_and_is_invertible_elsewhere(name):
    is_angles = name in ANGLE_SETS
    E = rate_matrix(name) if is_angles else position_rate_matrix(name)
    B = angular_velocity_matrix(name) if is_angles else point_from(name).jacobian(sp.Matrix(coordinates(name)))
    rng = np.random.default_rng(5)
    generic = {s: sp.Float(rng.uniform(0.3, 1.2)) for s in coordinates(name)}
    for singularity in representation_singularities(name):
        for solution in singularity.solutions:
            at = {**generic, singularity.variable: solution}
            assert B.xreplace(at).rank() < 3
            assert any(entry.has(sp.zoo, sp.nan) for entry in E.xreplace(at)), (name, solution)
    for _ in range(5):
        at = {s: sp.Float(rng.uniform(-3, 3)) for s in coordinates(name)}
        if not is_angles:
            at[coordinates(name)[0]] = sp.Float(rng.uniform(0.1, 2))
        if min(abs(float(s.factor.xreplace(at))) for s in representation_singularities(name)) < 1e-3:
            continue
        np.testing.assert_allclose(numeric(E.xreplace(at) * B.xreplace(at)), np.eye(3), atol=1e-12)


def test_redundant_representations_are_singular_only_where_reported():
    """Restricted to the constraint's tangent space, B is invertible except at the reported set."""
    assert representation_singularities("quaternion") == ()
    assert representation_singularities("direction_cosines") == ()
    (axis,) = representation_singularities("axis_angle")
    rng = np.random.default_rng(8)
    for _ in range(5):
        R = random_rotation(rng)
        B = numeric(angular_velocity_matrix("direction_cosines", list(extract("direction_cosines", R))))
        assert np.linalg.svd(B, compute_uv=False).min() == pytest.approx(1 / math.sqrt(2))
        B = numeric(angular_velocity_matrix("quaternion", list(extract("quaternion", R))))
        np.testing.assert_allclose(B @ B.T, 4 * np.eye(3), atol=1e-12)
    for angle in [0.0, 1e-3, 0.7, 2.0, math.pi]:
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        u = np.cross(k, rng.normal(size=3))
        u /= np.linalg.norm(u)
        tangent = np.zeros((4, 3))
        tangent[:3, 0], tangent[:3, 1], tangent[3, 2] = u, np.cross(k, u), 1.0
        B = numeric(angular_velocity_matrix("axis_angle", [*k, angle]))
        value = float(axis.factor.subs(axis.variable, angle))
        assert abs(np.linalg.det(B @ tangent)) == pytest.approx(4 * value**2, abs=1e-12)
        assert (value == 0) == (angle == 0)


# --- extraction ------------------------------------------------------------------------------------------------------


@SETTINGS
@given(name=st.sampled_from(REPRESENTATIONS), seed=st.integers(0, 2**16))
def test_extraction_round_trip_on_random_rotations(name, seed):
    R = random_rotation(np.random.default_rng(seed))
    x = extract(name, R)
    np.testing.assert_allclose(rotation_numeric(name, x), R, atol=1e-12)
    if name in PROPER:
        assert 0 <= x[1] <= math.pi
    elif name in ANGLE_SETS:
        assert -math.pi / 2 <= x[1] <= math.pi / 2
    if name in ANGLE_SETS:
        assert all(-math.pi < v <= math.pi for v in x)
    if name == "quaternion":
        assert x[0] >= 0 and np.linalg.norm(x) == pytest.approx(1)
    if name == "axis_angle":
        assert 0 <= x[3] <= math.pi and np.linalg.norm(x[:3]) == pytest.approx(1)


@pytest.mark.parametrize("name", ANGLE_SETS)
def test_extraction_recovers_principal_angles(name):
    rng = np.random.default_rng(11)
    middle = (0.2, math.pi - 0.2) if name in PROPER else (-math.pi / 2 + 0.2, math.pi / 2 - 0.2)
    for _ in range(10):
        x = np.array([rng.uniform(-3, 3), rng.uniform(*middle), rng.uniform(-3, 3)])
        np.testing.assert_allclose(extract(name, rotation_numeric(name, x)), x, atol=1e-12)


def _lock_angles(name):
    return [0.0, math.pi] if name in PROPER else [-math.pi / 2, math.pi / 2]


@pytest.mark.parametrize("name", ANGLE_SETS)
@pytest.mark.parametrize("offset", [0.0, 1e-13, 1e-9, 1e-6])
def test_gimbal_lock_first_angle_zero_and_round_trip(name, offset):
    """Near beta = 0, pi or +-pi/2 the pose is reproduced; exactly there the first angle is 0 (lecture slides)."""
    rng = np.random.default_rng(13)
    first = representation(name).leftmost  # the leftmost factor: yaw for roll-pitch-yaw, the last angle if extrinsic
    for lock in _lock_angles(name):
        for _ in range(4):
            x = np.array([rng.uniform(-3, 3), lock - math.copysign(offset, lock - 0.1), rng.uniform(-3, 3)])
            R = rotation_numeric(name, x)
            y = extract(name, R)
            np.testing.assert_allclose(rotation_numeric(name, y), R, atol=1e-12, err_msg=f"{name} {lock} {offset}")
            if offset <= 1e-13:
                assert y[first] == 0.0
                assert y[1] == pytest.approx(lock, abs=1e-12)


def test_zyz_gimbal_lock_follows_seed_002_formulas():
    rng = np.random.default_rng(17)
    for _ in range(5):
        alpha, gamma = rng.uniform(-3, 3, 2)
        R = rotation_numeric("zyz", [alpha, 0.0, gamma])
        assert extract("zyz", R) == pytest.approx([0.0, 0.0, math.atan2(-R[0, 1], R[0, 0])], abs=1e-15)
        R = rotation_numeric("zyz", [alpha, math.pi, gamma])
        assert extract("zyz", R) == pytest.approx([0.0, math.pi, math.atan2(R[0, 1], -R[0, 0])], abs=1e-15)


def test_quaternion_and_axis_angle_at_half_turns_and_identity():
    for axis in np.eye(3):
        R = exp_so3(math.pi * axis)
        for name in ("quaternion", "axis_angle"):
            np.testing.assert_allclose(rotation_numeric(name, extract(name, R)), R, atol=1e-14)
        np.testing.assert_allclose(extract("axis_angle", R), [*axis, math.pi], atol=1e-14)
    np.testing.assert_array_equal(extract("quaternion", np.eye(3)), [1, 0, 0, 0])
    np.testing.assert_array_equal(extract("axis_angle", np.eye(3)), [0, 0, 1, 0])
    np.testing.assert_allclose(extract("axis_angle", exp_so3(np.array([0, 1e-9, 0]))), [0, 1, 0, 1e-9], atol=1e-15)


def test_position_extraction_round_trip_and_axis_conventions():
    rng = np.random.default_rng(19)
    for kind in POSITIONS:
        for _ in range(5):
            p = rng.normal(size=3)
            np.testing.assert_allclose(numeric(point_from(kind, list(extract_position(kind, p)))).ravel(), p,
                                       atol=1e-12)
    np.testing.assert_allclose(extract_position("spherical", [0, 0, -2]), [2, math.pi, 0])
    np.testing.assert_allclose(extract_position("cylindrical", [0, 0, 3]), [0, 0, 3])


def test_extraction_input_errors():
    with pytest.raises(RepresentationError, match="unknown orientation representation 'euler'"):
        extract("euler", np.eye(3))  # type: ignore[arg-type]
    with pytest.raises(RepresentationError, match="not a rotation"):
        extract("zyz", 2 * np.eye(3))
    with pytest.raises(RepresentationError, match="3 x 3"):
        extract("zyz", np.eye(4))
    with pytest.raises(RepresentationError, match="3 finite coordinates"):
        extract_position("spherical", [1.0, math.nan, 0.0])
    with pytest.raises(RepresentationError, match="has 3 coordinates, got 2"):
        rotation_from("zyz", [1, 2])


# --- robots: J_x against finite differences of extracted coordinates -----------------------------------------------


def _reference_x(robot, q, orientation, position, frame, point):
    """[x_p; x_r] from tests/reference.py forward kinematics (no symjac transforms)."""
    poses = frames(robot, q)
    n = robot.n_coordinates
    source = np.eye(4) if frame == "world" else poses[1]
    if point == "tool":
        T = np.linalg.solve(source, poses[n + 2])
        p = T[:3, 3]
    else:
        T = np.linalg.solve(source, poses[n + 1])
        offset = np.zeros(3) if point == "wrist" else np.asarray(point, dtype=float)
        p = T[:3, :3] @ offset + T[:3, 3]
    return np.concatenate([extract_position(position, p), extract(orientation, T[:3, :3])])


def _check_against_finite_differences(robot, q, q_dot, orientation, position, frame, point):
    value = representation_jacobian_at(robot, q, orientation, position, point, frame)
    difference = value.x - _reference_x(robot, q, orientation, position, frame, point)
    angles = {"spherical": [1, 2], "cylindrical": [1]}.get(position, [])
    if orientation in ANGLE_SETS:
        angles += [3, 4, 5]
    difference[angles] = (difference[angles] + np.pi) % (2 * np.pi) - np.pi  # -pi and pi are the same azimuth
    np.testing.assert_allclose(difference, 0, atol=1e-9)

    def x_along(t):
        return _reference_x(robot, q + t * q_dot, orientation, position, frame, point)

    centre = x_along(0.0)
    plus, minus = x_along(H), x_along(-H)
    x_dot = np.concatenate([
        (align(position, plus[:3], centre[:3]) - align(position, minus[:3], centre[:3])) / (2 * H),
        (align(orientation, plus[3:], centre[3:]) - align(orientation, minus[3:], centre[3:])) / (2 * H),
    ])
    np.testing.assert_allclose(value.J_x @ q_dot, x_dot, rtol=1e-5, atol=1e-6,
                               err_msg=f"{robot.name} {orientation} {position} {frame} {point}")
    return value


def _far_from_representation_singularities(value, margin=0.05):
    return all(abs(f) > margin for f in value.factors)


def _configuration(robot, rng, orientation, position, frame, point, tries=20):
    """A random configuration whose pose is not near a representation singularity (None if none found)."""
    for _ in range(tries):
        q = random_configuration(robot, rng)
        try:
            value = representation_jacobian_at(robot, q, orientation, position, point, frame)
        except RepresentationError:
            continue
        if _far_from_representation_singularities(value):
            return q
    return None


SPATIAL = ["puma560", "stanford", "ur5", "panda", "articulated3r", "scara"]


@pytest.mark.parametrize("name", marked(SPATIAL))
def test_catalog_robots_every_representation_against_finite_differences(name):
    robot = load_robot(name)
    rng = np.random.default_rng(sum(map(ord, name)))
    point = "tool" if robot.tool is not None else "wrist"
    checked = 0
    for index, orientation in enumerate(REPRESENTATIONS):
        position = POSITIONS[index % 3]
        frame = "world" if index % 2 else 0
        q = _configuration(robot, rng, orientation, position, frame, point)
        if q is None:  # every pose of this arm is near a singularity of this representation (SCARA and z-z orders)
            continue
        q_dot = rng.normal(size=robot.n_coordinates)
        _check_against_finite_differences(robot, q, q_dot, orientation, position, frame, point)
        checked += 1
    # SCARA turns about z only: every z-z convention (intrinsic or extrinsic) is in gimbal lock at every pose
    z_z = [c for c in EULER_CONVENTIONS if c.axes[0] == c.axes[2] == "z"]
    assert checked >= len(REPRESENTATIONS) - (len(z_z) if name == "scara" else 0)


def test_planar_arm_is_always_in_gimbal_lock_for_zyz():
    """Planar arms turn about z only: beta = 0 for Z-Y-Z everywhere, so J_x does not exist; X-Y-X is fine."""
    robot = load_robot("planar3r")
    q = np.array([0.3, -0.4, 0.9])
    with pytest.raises(RepresentationError, match=r"sin\(beta\) = 0"):
        representation_jacobian_at(robot, q, "zyz")
    value = _check_against_finite_differences(robot, q, np.array([0.5, -1.0, 0.2]), "quaternion", "cylindrical", 0,
                                              "tool")
    np.testing.assert_allclose(value.x[3:], [math.cos(0.4), 0, 0, math.sin(0.4)], atol=1e-12)


def test_tool_point_uses_the_tool_frame_orientation():
    joints = [{"type": "revolute", "alpha": "pi/2", "a": 0.3, "d": 0.1, "theta": 0},
              {"type": "revolute", "alpha": 0, "a": 0.25, "d": 0, "theta": 0}]
    robot = robot_from_mapping({"name": "tooled", "convention": "standard", "joints": joints,
                                "tool": {"xyz": [0.1, 0, 0.2], "rpy": [0.3, -0.2, 0.5]}})
    q, q_dot = np.array([0.4, -0.7]), np.array([0.6, 1.1])
    T_n_tool = np.array(robot.tool.matrix, dtype=float)
    for point, R_offset in [("tool", T_n_tool[:3, :3]), (tuple(T_n_tool[:3, 3]), np.eye(3))]:
        value = _check_against_finite_differences(robot, q, q_dot, "direction_cosines", "cartesian", 0, point)
        R_0_n = np.linalg.solve(frames(robot, q)[1], frames(robot, q)[robot.n_joints + 1])[:3, :3]
        np.testing.assert_allclose(value.x[3:].reshape(3, 3), R_0_n @ R_offset, atol=1e-12)
        np.testing.assert_allclose(value.x[:3], (frames(robot, q)[-1])[:3, 3], atol=1e-12)


def test_symbolic_J_x_matches_the_numeric_evaluation():
    robot = load_robot("puma560")
    rng = np.random.default_rng(23)
    for orientation, position in [("zyz", "spherical"), ("axis_angle", "cartesian"), ("direction_cosines",
                                                                                       "cylindrical")]:
        result = representation_jacobian(robot, orientation, position)
        q = _configuration(robot, rng, orientation, position, 0, "wrist")
        value = representation_jacobian_at(robot, q, orientation, position)
        values = {**dict(zip(result.coordinates, value.x, strict=True)), **dict(zip(robot.q, q, strict=True)),
                  **robot.defaults}
        np.testing.assert_allclose(numeric(result.J_x.xreplace(values)), value.J_x, atol=1e-10)
        assert result.J_x.shape == (3 + len(coordinates(orientation)), robot.n_coordinates)
        assert result.coordinates == (*coordinates(position), *coordinates(orientation))
        E = sp.diag(position_rate_matrix(position), rate_matrix(orientation))
        assert result.E == E


@SETTINGS
@given(robot=robots(), data=st.data())
@pytest.mark.slow
def test_random_chains_against_finite_differences(robot, data):
    orientation = data.draw(st.sampled_from(REPRESENTATIONS), label="orientation")
    position = data.draw(st.sampled_from(POSITIONS), label="position")
    frame = data.draw(st.sampled_from([0, "world"]), label="frame")
    point = data.draw(st.sampled_from(["wrist", "tool", (0.2, -0.1, 0.3)]), label="point")
    if point == "tool" and robot.tool is None:
        point = "wrist"
    rng = np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed"))
    q = _configuration(robot, rng, orientation, position, frame, point, tries=5)
    assume(q is not None)
    rates = rng.normal(size=robot.n_coordinates)
    _check_against_finite_differences(robot, q, rates, orientation, position, frame, point)


# --- time derivative of J_x: the bias term of an analytic-Jacobian controller --------------------------------------

DERIVATIVE_ROBOT = "puma560"  # the full sweep runs on one six-joint arm; the symbolic identities on the 2R arm


def _away_from_branch_cuts(orientation, x, margin=0.05):
    """Extraction is continuous here: no quaternion sign flip (eta ~ 0), no axis-angle flip (vartheta ~ pi)."""
    if orientation == "quaternion":
        return x[3] > margin
    if orientation == "axis_angle":
        return x[6] < math.pi - margin
    return True


def _derivative_state(robot, rng, orientation, position):
    for _ in range(30):
        q = random_configuration(robot, rng)
        try:
            value = representation_jacobian_at(robot, q, orientation, position)
        except RepresentationError:
            continue
        if _far_from_representation_singularities(value, 0.1) and _away_from_branch_cuts(orientation, value.x):
            return q, rng.normal(size=robot.n_coordinates)
    raise AssertionError(f"no configuration away from the singularities of {orientation}/{position}")


@pytest.fixture(scope="module")
def derivative_robot():
    return load_robot(DERIVATIVE_ROBOT)


@pytest.mark.parametrize(("orientation", "position"),  # every orientation, the positions in turn (CI time)
                         [(name, POSITIONS[index % len(POSITIONS)]) for index, name in enumerate(REPRESENTATIONS)])
def test_Jdot_x_is_the_derivative_of_J_x_along_the_motion(derivative_robot, orientation, position):
    robot = derivative_robot
    rng = np.random.default_rng(sum(map(ord, orientation + position)))
    q, q_dot = _derivative_state(robot, rng, orientation, position)
    value = representation_jacobian_derivative_at(robot, q, q_dot, orientation, position)
    h = 1e-5

    def J_x(t):
        return representation_jacobian_at(robot, q + t * q_dot, orientation, position).J_x

    difference = (J_x(h) - J_x(-h)) / (2 * h)
    scale = max(np.abs(difference).max(), 1.0)
    np.testing.assert_allclose(value.Jdot_x, difference, rtol=1e-6, atol=1e-6 * scale)
    np.testing.assert_allclose(value.bias, value.Jdot_x @ q_dot, atol=1e-12)
    np.testing.assert_allclose(value.x_dot, value.J_x @ q_dot, atol=1e-12)


@pytest.mark.parametrize(("orientation", "position"), [("zyz", "cartesian"), ("rpy", "spherical"),
                                                       ("quaternion", "cylindrical")])
def test_bias_is_the_second_derivative_of_extracted_coordinates(derivative_robot, orientation, position):
    """At zero joint acceleration (q = q0 + t q_dot), x'' is the bias: second differences of reference FK."""
    robot = derivative_robot
    rng = np.random.default_rng(5)
    q, q_dot = _derivative_state(robot, rng, orientation, position)
    value = representation_jacobian_derivative_at(robot, q, q_dot, orientation, position)
    h = 1e-4

    def x_at(t):
        return _reference_x(robot, q + t * q_dot, orientation, position, 0, "wrist")

    centre = x_at(0.0)
    aligned = [np.concatenate([align(position, x[:3], centre[:3]), align(orientation, x[3:], centre[3:])])
               for x in (x_at(h), x_at(-h))]
    second = (aligned[0] - 2 * centre + aligned[1]) / h**2
    np.testing.assert_allclose(value.bias, second, rtol=1e-4, atol=1e-4)


def test_Jdot_x_in_the_world_frame_at_the_tool_point():
    """A base transform and a tool: x measured in "world" at the tool frame, against differences of J_x."""
    joints = [{"type": "revolute", "alpha": "pi/2", "a": 0.3, "d": 0.1, "theta": 0},
              {"type": "prismatic", "alpha": "-pi/2", "a": 0.05, "d": 0.2, "theta": 0.4},
              {"type": "revolute", "alpha": "pi/2", "a": 0.25, "d": 0, "theta": 0}]
    robot = robot_from_mapping({"name": "based", "convention": "standard", "joints": joints,
                                "base": {"xyz": [0.2, -0.1, 0.5], "rpy": [0.4, 0.1, -0.3]},
                                "tool": {"xyz": [0.1, 0, 0.2], "rpy": [0.3, -0.2, 0.5]}})
    q, q_dot, h = np.array([0.4, 0.5, -0.7]), np.array([0.6, -0.3, 1.1]), 1e-5
    for orientation, position in [("zyx", "cylindrical"), ("direction_cosines", "spherical")]:
        value = representation_jacobian_derivative_at(robot, q, q_dot, orientation, position, "tool", "world")
        plus, minus = (representation_jacobian_at(robot, q + t * q_dot, orientation, position, "tool", "world").J_x
                       for t in (h, -h))
        np.testing.assert_allclose(value.Jdot_x, (plus - minus) / (2 * h), rtol=1e-6, atol=1e-8)


def test_symbolic_Jdot_x_matches_the_numeric_evaluation(derivative_robot):
    robot = derivative_robot
    rng = np.random.default_rng(41)
    for orientation, position in [("zyz", "spherical"), ("axis_angle", "cartesian")]:
        result = representation_jacobian_derivative(robot, orientation, position)
        q, q_dot = _derivative_state(robot, rng, orientation, position)
        value = representation_jacobian_derivative_at(robot, q, q_dot, orientation, position)
        values = {**dict(zip(result.coordinates, value.x, strict=True)), **dict(zip(robot.q, q, strict=True)),
                  **dict(zip(result.joint_rate_symbols, q_dot, strict=True)), **robot.defaults}
        np.testing.assert_allclose(numeric(result.Jdot_x.xreplace(values)), value.Jdot_x, atol=1e-9)
        np.testing.assert_allclose(numeric(result.bias.xreplace(values)).ravel(), value.bias, atol=1e-9)
        rates = dict(zip(result.coordinate_rates, value.x_dot, strict=True))
        np.testing.assert_allclose(numeric(result.E_dot.xreplace({**values, **rates})), value.E_dot, atol=1e-9)
        assert result.coordinate_rates == (*coordinate_rates(position), *coordinate_rates(orientation))


def test_planar_arm_Jdot_x_identities():
    robot = load_robot("planar2r")
    result = representation_jacobian_derivative(robot, "rpy", "cartesian")
    # the yaw of a planar arm is theta1 + theta2, so its rate row is constant
    assert result.Jdot_x[5, :] == sp.zeros(1, 2)
    # cartesian coordinates have E_p = I: their rows are those of the basic Jacobian's derivative, exactly
    assert result.Jdot_x[:3, :] == jacobian_derivative(robot)[:3, :]
    assert result.E_dot[:3, :] == sp.zeros(3, 6)
    assert set(result.Jdot_x.free_symbols) <= {*robot.q, *robot.parameter_symbols, *joint_rate_symbols(robot),
                                               *result.coordinates}
    # cylindrical coordinates: the rho row of E_p, [c_phi, s_phi, 0], turns with the azimuth phi_c
    cylindrical = representation_jacobian_derivative(robot, "rpy", "cylindrical")
    phi_c, phidot_c = coordinates("cylindrical")[1], coordinate_rates("cylindrical")[1]
    assert cylindrical.E_dot[0, :3] == sp.Matrix([[-sp.sin(phi_c), sp.cos(phi_c), 0]]) * phidot_c
    assert cylindrical.Jdot_x[5, :] == sp.zeros(1, 2)


def test_representation_jacobian_derivative_errors(derivative_robot):
    robot = derivative_robot
    with pytest.raises(ArgumentError, match="q_dot must be 6 finite numbers"):
        representation_jacobian_derivative_at(robot, [0.1] * 6, [0.1] * 5)
    with pytest.raises(RepresentationError, match=r"sin\(beta\) = 0"):
        representation_jacobian_derivative_at(load_robot("planar2r"), [0.3, 0.4], [1.0, 1.0], "zyz")
    with pytest.raises(RepresentationError, match="fixed frame"):
        representation_jacobian_derivative(robot, frame=3)


# --- API errors --------------------------------------------------------------------------------------------------


def test_representation_jacobian_argument_errors():
    robot = load_robot("puma560")
    with pytest.raises(RepresentationError, match="unknown position representation 'polar'"):
        representation_jacobian(robot, "zyz", "polar")  # type: ignore[arg-type]
    with pytest.raises(RepresentationError, match="fixed frame"):
        representation_jacobian(robot, frame=3)
    clashing = robot_from_mapping({"name": "clash", "convention": "standard", "parameters": {"rho": 0.5},
                                   "joints": [{"type": "revolute", "alpha": 0, "a": "rho", "d": 0, "theta": 0}]})
    with pytest.raises(RepresentationError, match="rho"):
        representation_jacobian(clashing, "quaternion", "cylindrical")

