"""Dynamics, exact: the 2R arm's textbook closed forms, and the three routes (Newton-Euler, M qdd + C qd + g from the
link Jacobians and Christoffel symbols, Euler-Lagrange from the energies) as symbolic identities on 2R and 3R arms.

The textbook 2R arm (Spong, Hutchinson and Vidyasagar, section 7.4): links of lengths L1, L2 in the x-y plane of {0},
centres of mass lc1, lc2 from the joints, masses m1, m2, moments I1, I2 about the centres (about z), gravity g along
-y. In symjac's standard DH frames {1}, {2} sit at the far end of each link, so the centres are (lci - Li, 0, 0).
"""

from __future__ import annotations

import dataclasses

import pytest
import sympy as sp

from symjac import load_robot, robot_from_mapping
from symjac.analysis.dynamics import (
    EARTH,
    NO_GRAVITY,
    Gravity,
    coriolis_matrix,
    dynamics_defaults,
    euler_lagrange,
    gravity_torques,
    kinetic_energy,
    mass_matrix,
    newton_euler,
    newton_euler_mass_matrix,
    potential_energy,
)
from symjac.analysis.dynamics.gravity import GRAVITY_SYMBOL
from symjac.analysis.dynamics.lagrange import time_derivative
from symjac.errors import ArgumentError, NoInertialDataError
from symjac.kinematics.chain import chain_of
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.jacobian import jacobian
from symjac.model.inertia import Inertial
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.symbolic.simplify import is_identity

m1, m2, lc1, lc2, I1, I2 = sp.symbols("m1 m2 lc1 lc2 I1 I2", positive=True)
g = GRAVITY_SYMBOL
t1, t2 = sp.symbols("theta1 theta2", real=True)
td1, td2 = sp.symbols("thetadot1 thetadot2", real=True)
IN_PLANE = Gravity(direction=(0, -1, 0))


def _two_link(centred: bool) -> tuple:
    """The 2R arm with centres at lc (``centred``) or point masses at the link ends (lc = L, no moments)."""
    arm = load_robot("planar2r")
    arm = dataclasses.replace(arm, parameters=arm.geometric_parameters)  # the symbols below replace m1 .. Izz2
    L1, L2 = arm.parameter_symbols
    if centred:
        bodies = (Inertial(m1, (lc1 - L1, 0, 0), sp.diag(0, 0, I1)), Inertial(m2, (lc2 - L2, 0, 0), sp.diag(0, 0, I2)))
    else:
        bodies = (Inertial(m1), Inertial(m2))
    return dataclasses.replace(arm, inertials=bodies), L1, L2


def _textbook(L1, L2, centred: bool) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    a1, a2, J1, J2 = (lc1, lc2, I1, I2) if centred else (L1, L2, 0, 0)
    c2, s2 = sp.cos(t2), sp.sin(t2)
    M = sp.Matrix([[m1 * a1**2 + m2 * (L1**2 + a2**2 + 2 * L1 * a2 * c2) + J1 + J2, m2 * (a2**2 + L1 * a2 * c2) + J2],
                   [m2 * (a2**2 + L1 * a2 * c2) + J2, m2 * a2**2 + J2]])
    h = -m2 * L1 * a2 * s2
    C = sp.Matrix([[h * td2, h * (td1 + td2)], [-h * td1, 0]])
    G = sp.Matrix([(m1 * a1 + m2 * L1) * g * sp.cos(t1) + m2 * a2 * g * sp.cos(t1 + t2), m2 * a2 * g * sp.cos(t1 + t2)])
    return M, C, G


def _zero(matrix: sp.MatrixBase) -> bool:
    return all(sp.expand(sp.expand_trig(entry)) == 0 for entry in matrix)


@pytest.mark.parametrize("centred", [True, False], ids=["centres-at-lc", "point-masses-at-ends"])
def test_two_link_arm_is_the_textbooks(centred):
    arm, L1, L2 = _two_link(centred)
    M, C, G = _textbook(L1, L2, centred)
    assert _zero(mass_matrix(arm) - M)
    assert _zero(newton_euler_mass_matrix(arm) - M)
    assert _zero(coriolis_matrix(arm) - C)
    assert _zero(gravity_torques(arm, IN_PLANE) - G)
    assert t1 not in mass_matrix(arm).free_symbols  # the textbook form: c2 only, no theta1 left to cancel


def test_two_link_mass_matrix_is_laid_out_as_printed_in_the_book():
    arm, L1, _ = _two_link(True)
    M = mass_matrix(arm)
    assert M[1, 1] == I2 + lc2**2 * m2
    assert M[0, 1] == M[1, 0] == I2 + lc2 * m2 * (L1 * sp.cos(t2) + lc2)
    assert sp.count_ops(M[0, 0]) <= sp.count_ops(m1 * lc1**2 + m2 * (L1**2 + lc2**2 + 2 * L1 * lc2 * sp.cos(t2))
                                                   + I1 + I2)


def _routes(arm, gravity):
    """tau by Newton-Euler, by M qdd + C qd + g, and by Euler-Lagrange; the basis to compare them in."""
    q_dot, q_ddot = sp.Matrix(arm.coordinate_rates), sp.Matrix(arm.coordinate_accelerations)
    lagrangian = mass_matrix(arm) * q_ddot + coriolis_matrix(arm) * q_dot + gravity_torques(arm, gravity)
    return newton_euler(arm, gravity).torques, lagrangian, euler_lagrange(arm, gravity), \
        chain_of(arm).all_angle_bases()[0]


ARMS = {  # name: (robot with symbolic inertial data, gravity)
    "2r-centred": (_two_link(True)[0], IN_PLANE),
    "planar3r": (with_symbolic_inertials(load_robot("planar3r")), IN_PLANE),
    "articulated3r": (with_symbolic_inertials(load_robot("articulated3r")), EARTH),
}


@pytest.mark.parametrize("name", sorted(ARMS))
def test_newton_euler_lagrange_and_christoffel_agree_exactly(name):
    arm, gravity = ARMS[name]
    ne, mcg, el, basis = _routes(arm, gravity)
    for k in range(arm.n_coordinates):
        assert is_identity(ne[k], mcg[k], basis), f"tau_{k + 1}: Newton-Euler != M qdd + C qd + g"
        assert is_identity(ne[k], el[k], basis), f"tau_{k + 1}: Newton-Euler != Euler-Lagrange"


@pytest.mark.parametrize("name", sorted(ARMS))
def test_energies_mass_matrix_and_gravity_are_one_system(name):
    arm, gravity = ARMS[name]
    basis = chain_of(arm).all_angle_bases()[0]
    q_dot = sp.Matrix(arm.coordinate_rates)
    M = mass_matrix(arm)
    assert is_identity(kinetic_energy(arm), (q_dot.T * M * q_dot)[0] / 2, basis)
    assert M == M.T
    assert all(is_identity(a, b, basis) for a, b in zip(M, newton_euler_mass_matrix(arm), strict=True))
    G = gravity_torques(arm, gravity)
    V = potential_energy(arm, gravity)
    assert all(is_identity(G[k], V.diff(q), basis) for k, q in enumerate(arm.q))
    # the torque that holds the arm still (Newton-Euler, at rest) and the static route -sum J_ci^T m_i g0
    at_rest = {s: 0 for s in (*arm.coordinate_rates, *arm.coordinate_accelerations)}
    static = sp.zeros(arm.n_coordinates, 1)
    for i, body in enumerate(arm.inertials, start=1):
        static -= jacobian(arm, 0, point=body.com, link=i)[:3, :].T * body.mass * gravity.vector
    for k in range(arm.n_coordinates):
        assert is_identity(G[k], newton_euler(arm, gravity).torques[k].xreplace(at_rest), basis)
        assert is_identity(G[k], static[k], basis)


@pytest.mark.parametrize("name", sorted(ARMS))
def test_mdot_minus_twice_c_is_skew_symmetric(name):
    arm, _ = ARMS[name]
    basis = chain_of(arm).all_angle_bases()[0]
    M_dot = mass_matrix(arm).applyfunc(lambda entry: time_derivative(entry, arm))
    N = M_dot - 2 * coriolis_matrix(arm)
    n = arm.n_coordinates
    assert all(is_identity(N[i, j], -N[j, i], basis) for i in range(n) for j in range(i, n))
    assert not all(entry == 0 for entry in coriolis_matrix(arm))  # the test can fail: there is a Coriolis matrix


def test_every_step_is_named_and_the_angular_velocity_is_the_jacobians():
    arm, *_ = _two_link(True)
    result = newton_euler(arm, IN_PLANE)
    names = result.named()
    assert list(names[1]) == ["omega_2", "alpha_2", "a_2", "a_c_2", "F_2", "N_2", "f_2", "n_2", "tau_2"]
    for k, step in enumerate(result.steps, start=1):
        omega = jacobian(arm, k, link=k)[3:, :] * sp.Matrix(arm.coordinate_rates)
        assert _zero(step.omega - omega)
    assert _zero(names[1]["F_2"] - m2 * names[1]["a_c_2"])
    assert _zero(names[1]["f_2"] - names[1]["F_2"])  # the last link: nothing beyond it
    assert [step.tau for step in result.steps] == list(result.torques)


def test_prismatic_joint_carries_its_load():
    """A vertical slider (standard DH, axis z0 up) under gravity: tau = m (dddot + g), M = m, no Coriolis."""
    arm = robot_from_mapping({"name": "lift", "convention": "standard",
                              "joints": [{"type": "prismatic", "alpha": 0, "a": 0, "theta": 0}]})
    m = sp.Symbol("m", positive=True)
    arm = dataclasses.replace(arm, inertials=(Inertial(m, (0, 0, 0), sp.diag(1, 1, 1)),))
    dddot = arm.coordinate_accelerations[0]
    assert sp.expand(newton_euler(arm).torques[0] - m * (dddot + g)) == 0
    assert mass_matrix(arm) == sp.Matrix([[m]]) and coriolis_matrix(arm) == sp.zeros(1, 1)


def test_coupled_joints_give_results_in_the_coordinates():
    """theta4 = -(theta2 + theta3) (a parallelogram): tau_q = C^T tau, M_q = C^T M C, g_q = C^T g."""
    data = {"name": "arm", "convention": "modified", "parameters": {"L": 0.5},
            "joints": [{"type": "revolute", "alpha": a, "a": "L"} for a in (0, "pi/2", 0, 0)]}
    free = with_symbolic_inertials(robot_from_mapping(data))
    data["joints"][3]["coupled"] = "-(theta2 + theta3)"
    coupled = dataclasses.replace(with_symbolic_inertials(robot_from_mapping(data)))
    C = coupling_matrix(coupled)
    values = dict(zip(free.joint_variables, coupled.joint_values, strict=True))
    rates = dict(zip(free.coordinate_rates, C * sp.Matrix(coupled.coordinate_rates), strict=True))
    accelerations = dict(zip(free.coordinate_accelerations, C * sp.Matrix(coupled.coordinate_accelerations),
                             strict=True))
    basis = chain_of(coupled).all_angle_bases()[0]

    def moved(matrix):
        return matrix.xreplace(values).xreplace(rates).xreplace(accelerations)

    expected = {
        "M": C.T * moved(mass_matrix(free, simplify=False)) * C,
        "g": C.T * moved(gravity_torques(free, simplify=False)),
        "tau": C.T * moved(newton_euler(free, simplify=False).torques),
    }
    got = {"M": mass_matrix(coupled), "g": gravity_torques(coupled), "tau": newton_euler(coupled).torques}
    for key, value in got.items():
        assert value.shape == expected[key].shape
        assert all(is_identity(a, b, basis) for a, b in zip(value, expected[key], strict=True)), key
    assert all(is_identity(a, b, basis) for a, b in zip(newton_euler_mass_matrix(coupled), got["M"], strict=True))
    q_dot, q_ddot = sp.Matrix(coupled.coordinate_rates), sp.Matrix(coupled.coordinate_accelerations)
    mcg = got["M"] * q_ddot + coriolis_matrix(coupled) * q_dot + got["g"]
    assert all(is_identity(a, b, basis) for a, b in zip(got["tau"], mcg, strict=True))


def test_gravity_setting_defaults_and_errors():
    arm, *_ = _two_link(True)
    assert dynamics_defaults(arm)[g] == sp.Rational(981, 100)
    assert Gravity(direction=(0, 0, -2)).vector == sp.Matrix([0, 0, -g])
    assert g not in newton_euler(arm, NO_GRAVITY).torques.free_symbols
    numeric = Gravity(magnitude=sp.Rational(981, 100), direction=(0, -1, 0))
    assert _zero(gravity_torques(arm, numeric) - gravity_torques(arm, IN_PLANE).subs(g, sp.Rational(981, 100)))
    with pytest.raises(ArgumentError, match="zero vector"):
        Gravity(direction=(0, 0, 0))
    with pytest.raises(ArgumentError, match="3 real numbers"):
        Gravity(direction=(0, 0, "x"))
    assert Gravity(direction=(0, 0.6, -0.8)).vector == sp.Matrix([0, 3 * g / 5, -4 * g / 5])
    assert Gravity(magnitude=9.81).vector == sp.Matrix([0, 0, -sp.Rational(981, 100)])  # exact, not a float
    clash = robot_from_mapping({"name": "clash", "convention": "standard", "parameters": {"g": 1},
                                "joints": [{"type": "revolute", "alpha": 0, "a": "g"}]})
    with pytest.raises(ArgumentError, match="'g' has the name of gravity"):
        newton_euler(dataclasses.replace(clash, inertials=(Inertial(1),)))


def test_missing_inertial_data_names_the_links():
    arm = load_robot("planar3r")
    arm = dataclasses.replace(arm, parameters=arm.geometric_parameters, inertials=())
    with pytest.raises(NoInertialDataError, match="planar3r: links 1, 2, 3 have no inertial data"):
        mass_matrix(arm)
    partial = dataclasses.replace(arm, inertials=(Inertial(1), None, Inertial(1)))
    with pytest.raises(NoInertialDataError, match="planar3r: link 2 has no inertial data"):
        newton_euler(partial)
    # a URDF's links by the joints that move them, as the file names them
    from symjac.model.urdf import robot_from_urdf

    body = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    urdf = robot_from_urdf(f"""<robot name="two"><link name="base"/><link name="upper">{body}</link>
        <link name="fore"/><joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
        <joint name="elbow" type="continuous"><parent link="upper"/><child link="fore"/>
        <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/></joint></robot>""")
    with pytest.raises(NoInertialDataError, match=r"two: link 2 \(moved by joint elbow\) has no inertial data"):
        gravity_torques(urdf)


def test_puma_gravity_torques_and_mass_matrix_by_two_routes_exactly():
    """The PUMA 560 with ten symbolic inertial parameters per link: g three ways and M two ways, as identities."""
    puma = with_symbolic_inertials(load_robot("puma560"))
    basis = chain_of(puma).all_angle_bases()[0]
    G = gravity_torques(puma)
    at_rest = {s: 0 for s in (*puma.coordinate_rates, *puma.coordinate_accelerations)}
    held = newton_euler(puma, simplify=False).torques.xreplace(at_rest)
    static = sp.zeros(6, 1)
    for i, body in enumerate(puma.inertials, start=1):
        static -= jacobian(puma, 0, point=body.com, link=i)[:3, :].T * body.mass * EARTH.vector
    assert G[0] == 0 and G[5] != 0  # joint 1 turns about the vertical; the wrist carries link 6's weight
    assert all(is_identity(G[k], held[k], basis) and is_identity(G[k], static[k], basis) for k in range(6))
    M, M_ne = mass_matrix(puma), newton_euler_mass_matrix(puma)
    assert all(is_identity(M[i, j], M_ne[i, j], basis) for i in range(6) for j in range(i, 6))
