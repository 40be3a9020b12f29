"""The base parameters: their number against an independent numeric rank, their expressions against Y pi.

Independent checks of ``base_parameters``: (a) the count equals the rank of Y evaluated here with ``sympy.lambdify``
at random motions and stacked (an SVD, nothing of the base-parameter code), on random chains (hypothesis) and on
every catalog arm; (b) Y_b pi_b = Y pi, exactly on the planar arms (normal forms) and at random points and random
standard parameters elsewhere; (c) the planar 2R arm's base parameters as derived by hand; (d) the PUMA 560's count
against the published one.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from marks import marked
from strategies import general_robots, robots

from symjac import load_robot, regressor, robot_from_mapping
from symjac.analysis.dynamics import Gravity
from symjac.analysis.identification import BaseParameters, base_parameters
from symjac.model.io import catalog
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import lambdify_cse
from symjac.symbolic.simplify import is_identity


def _p(name: str) -> sp.Symbol:
    return sp.Symbol(name, real=True)


def _motion(Y) -> list[sp.Symbol]:
    robot = Y.robot
    return [*robot.q, *robot.coordinate_rates, *robot.coordinate_accelerations]


def _fixed(Y, geometry: dict | None = None) -> dict:
    """Numbers for everything but the motion: the robot's parameters (or ``geometry``) and gravity's magnitude."""
    values = dict(Y.robot.defaults if geometry is None else geometry)
    if isinstance(Y.gravity.magnitude, sp.Symbol):
        values[Y.gravity.magnitude] = Y.gravity.value
    return values


def _function(Y, matrix, geometry: dict | None = None):
    """``matrix`` as a function of the motion, everything else at the robot's values (or ``geometry``)."""
    fixed = _fixed(Y, geometry)
    others = sorted(matrix.free_symbols - set(_motion(Y)), key=sp.default_sort_key)
    f = sp.lambdify([*_motion(Y), *others], matrix, "numpy", cse=lambdify_cse)
    return lambda x: np.array(f(*x, *(float(fixed[o]) for o in others)), dtype=float)


def numeric_rank(Y, geometry: dict | None = None, seed: int = 1) -> int:
    """The rank of Y stacked over 2p random motions (columns scaled to unit size), by lambdify and an SVD."""
    rng = np.random.default_rng(seed)
    f = _function(Y, Y.matrix, geometry)
    n, p = Y.matrix.shape
    stacked = np.vstack([f(rng.uniform(-2, 2, 3 * n)).reshape(n, p) for _ in range(2 * p)])
    norms = np.linalg.norm(stacked, axis=0)
    seen = norms > 1e-11 * norms.max()  # generic geometry's floats leave junk such as 1e-19 qdot^2: no effect
    return int(np.linalg.matrix_rank(stacked[:, seen] / norms[seen]))


def check_torques_numerically(Y, base: BaseParameters, seed: int = 2, points: int = 4) -> None:
    """Y_b pi_b = Y pi at random motions, for random standard parameters, at the robot's geometry.

    Y_b is checked to be the kept columns of Y exactly, so both sides are evaluated from one lambdified Y.
    """
    rng = np.random.default_rng(seed)
    kept = [Y.parameters.index(p) for p in base.standard]
    assert base.matrix == Y.matrix[:, kept]
    standard = {p: sp.Rational(int(v), 7) for p, v in zip(Y.parameters, rng.integers(-20, 21, len(Y.parameters)),
                                                          strict=True)}
    fixed = _fixed(Y)
    pi = np.array([float(standard[p]) for p in Y.parameters])
    based = base.values(standard)
    pi_b = np.array([float(sp.sympify(based[b]).xreplace(fixed)) for b in base.symbols])
    f = _function(Y, Y.matrix)
    n, p = Y.matrix.shape
    for _ in range(points):
        values = f(rng.uniform(-2, 2, len(_motion(Y)))).reshape(n, p)
        a, b = values @ pi, values[:, kept] @ pi_b
        assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * (1 + np.abs(a).max()))


def check_torques_exactly(Y, base: BaseParameters) -> None:
    """Y_b pi_b = Y pi with every parameter a symbol, as identities in the joint angles."""
    left = Y.matrix * sp.Matrix(Y.parameters)
    right = base.matrix * sp.Matrix(base.expressions)
    basis = AngleBasis.of([q for q, j in zip(Y.robot.q, Y.robot.joints, strict=True) if j.is_revolute])
    assert all(is_identity(a, b, basis) for a, b in zip(left, right, strict=True))


def test_planar_2r_base_parameters_by_hand():
    r"""The planar 2R arm (standard DH: frame {1} at the elbow, {2} at the tip) with gravity in its plane.

    By hand: only planar quantities act. Link 2 turns about the elbow, so what it shows is its moment of inertia about
    the elbow, ZZ2 + 2 L2 MX2 + L2^2 M2 (ZZ2 is about the tip, L2 from the elbow along x2), and its first moment
    about the elbow, (MX2 + L2 M2, MY2). Link 1 shows the same about the shoulder (ZZ1 + 2 L1 MX1 + L1^2 M1,
    (MX1 + L1 M1, MY1)), plus link 2's mass carried at the elbow: L1^2 M2 in the moment of inertia, L1 M2 in the
    first moment. Writing J_i, h_i for these and the torques as tau = y_J1 J1 + y_h1 h1 + ..., the columns are
    Y_ZZ1 = y_J1, Y_MX1 = 2 L1 y_J1 + y_h1, Y_M1 = L1^2 y_J1 + L1 y_h1, Y_M2 = Y_M1 + L2^2 y_J2 + L2 y_h2, so
    Y_M1 = L1 Y_MX1 - L1^2 Y_ZZ1 and Y_M2 = L1 Y_MX1 - L1^2 Y_ZZ1 + L2 Y_MX2 - L2^2 Y_ZZ2: six base parameters,
    M1 and M2 grouped into the ZZ and MX of their links. Out-of-plane entries (XX, XY, XZ, YY, YZ, MZ) do nothing.
    """
    Y = regressor(load_robot("planar2r"), Gravity(direction=(0, -1, 0)))
    base = base_parameters(Y)
    L1, L2 = (next(x for x in Y.matrix.free_symbols if x.name == name) for name in ("L1", "L2"))
    ZZ1, MX1, MY1, M1, ZZ2, MX2, MY2, M2 = map(_p, ["ZZ1", "MX1", "MY1", "M1", "ZZ2", "MX2", "MY2", "M2"])
    expected = {
        "ZZR1": ZZ1 - L1**2 * (M1 + M2),
        "MXR1": MX1 + L1 * (M1 + M2),
        "MY1": MY1,
        "ZZR2": ZZ2 - L2**2 * M2,
        "MXR2": MX2 + L2 * M2,
        "MY2": MY2,
    }
    assert [b.name for b in base.symbols] == list(expected)
    for b, e in zip(base.symbols, base.expressions, strict=True):
        assert sp.expand(e - expected[b.name]) == 0, b
    assert base.grouped == {M1: L1 * MX1 - L1**2 * ZZ1, M2: L1 * MX1 - L1**2 * ZZ1 + L2 * MX2 - L2**2 * ZZ2}
    assert {p.name for p in base.unidentifiable} == {f"{n}{i}" for n in ("XX", "XY", "XZ", "YY", "YZ", "MZ")
                                                     for i in (1, 2)}
    assert base.rank == 6 == numeric_rank(Y)
    assert base.matrix == Y.matrix[:, [Y.names.index(n) for n in ("ZZ1", "MX1", "MY1", "ZZ2", "MX2", "MY2")]]
    check_torques_exactly(Y, base)


def test_drive_parameters_group_like_inertia():
    """Joint 1's armature adds to ZZ1's column (ZZR1 = ZZ1 + Ia1 + ...); joint 2's and the friction stay alone."""
    Y = regressor(load_robot("planar2r"), Gravity(direction=(0, -1, 0)), armature=True, viscous=True, coulomb=True)
    base = base_parameters(Y)
    named = dict(zip((b.name for b in base.symbols), base.expressions, strict=True))
    assert sp.expand(named["ZZR1"] - named["ZZR1"].subs(_p("Ia1"), 0)) == _p("Ia1")
    assert {"Ia2", "Fv1", "Fc1", "Fv2", "Fc2"} <= set(named)
    assert len(base.symbols) == base.rank == numeric_rank(Y) == 11
    check_torques_numerically(Y, base)


@pytest.mark.parametrize(("name", "gravity", "count"), [("planar3r", Gravity(direction=(1, -1, 0)), 9),
                                                        ("planar3r", Gravity(), 7)])
def test_planar_3r_exactly(name, gravity, count):
    """A planar nR arm has 3n base parameters with gravity in its plane (ZZR, MXR, MY per link), 3n - 2 without
    (link 1's first moment is then seen only through its moment of inertia)."""
    Y = regressor(load_robot(name), gravity)
    base = base_parameters(Y)
    assert len(base.symbols) == base.rank == numeric_rank(Y) == count
    check_torques_exactly(Y, base)


def test_puma560_count_is_the_published_one():
    """The PUMA 560 has 36 base inertial parameters.

    Source: Khalil and Dombre, *Modeling, Identification and Control of Robots* (Hermes Penton 2002), the chapter on
    base inertial parameters: for a 6R arm with the PUMA's axis arrangement (joint 1 vertical, axes 2 and 3 parallel,
    a spherical wrist; their example is the Staubli RX-90) the base parameters are ZZR1 and seven per link 2..6
    (XXR2, XY2, XZR2, YZ2, ZZR2, MXR2, MY2, and so on), 36 in all. The PUMA's offsets d3 and a3 change the
    expressions, not the count. What is counted: rigid-body parameters only; the motor inertias Ia and the friction
    (Fv, Fs) that Khalil and Dombre add for identification are not in this count (with them it is 52:
    test_puma560_with_motor_inertia_and_friction). The closed forms follow Khalil's
    grouping rules (Khalil's d_j is the modified-DH a_j), e.g. MXR3 = MX3 + a3 (M4 + M5 + M6), MYR5 = MY5 + MZ6,
    XXR6 = XX6 - YY6.
    """
    Y = regressor(load_robot("puma560"))
    base = base_parameters(Y)
    assert len(base.symbols) == base.rank == numeric_rank(Y) == 36
    names = [b.name for b in base.symbols]
    assert names[:8] == ["ZZR1", "XXR2", "XY2", "XZR2", "YZ2", "ZZR2", "MXR2", "MY2"]
    named = dict(zip(names, base.expressions, strict=True))
    a2, a3, d4 = (next(x for x in Y.matrix.free_symbols if x.name == n) for n in ("a2", "a3", "d4"))
    M4, M5, M6, MZ6, MZ4 = map(_p, ["M4", "M5", "M6", "MZ6", "MZ4"])
    assert sp.expand(named["MXR3"] - _p("MX3") - a3 * (M4 + M5 + M6)) == 0
    assert sp.expand(named["MYR5"] - _p("MY5") - MZ6) == 0
    assert sp.expand(named["XXR6"] - _p("XX6") + _p("YY6")) == 0
    assert sp.expand(named["MXR2"] - _p("MX2") - a2 * (_p("M3") + M4 + M5 + M6)) == 0
    assert sp.expand(named["ZZR3"] - _p("ZZ3") - _p("YY4") - 2 * d4 * MZ4 - (a3**2 + d4**2) * (M4 + M5 + M6)) == 0
    check_torques_numerically(Y, base)


@pytest.mark.parametrize("name", marked(sorted(catalog())))
def test_catalog_count_is_the_numeric_rank(name):
    """Every catalog arm: as many base parameters as the numeric rank, and Y_b pi_b = Y pi at random points."""
    Y = regressor(load_robot(name))
    base = base_parameters(Y)
    assert len(base.symbols) == base.rank == numeric_rank(Y)
    check_torques_numerically(Y, base, points=2)


def test_special_default_values_do_not_lower_the_count():
    """Two parallel vertical axes a apart: 4 base parameters (ZZR1; ZZR2, MXR2, MY2), but 2 where a = 0 (the axes
    coincide and link 2 only turns about its own axis). With a's default 0 the closed form, which holds for every
    value of a, keeps the general count."""
    arm = robot_from_mapping({"name": "coaxial", "convention": "modified", "parameters": {"a": 0},
                              "joints": [{"type": "revolute"}, {"type": "revolute", "a": "a"}]})
    Y = regressor(arm)
    base = base_parameters(Y)
    a = next(x for x in Y.matrix.free_symbols if x.name == "a")
    general = numeric_rank(Y, {a: sp.Rational(3, 10)})
    assert numeric_rank(Y) == 2 < general == len(base.symbols) == base.rank == 4
    check_torques_exactly(Y, base)


@settings(max_examples=12, deadline=None)
@given(robots(max_joints=4))
def test_random_chains(arm):
    """Random standard and modified DH chains with prismatic joints: count = numeric rank, Y_b pi_b = Y pi."""
    check_chain(arm)


@settings(max_examples=5, deadline=None)
@given(general_robots(max_joints=3))
def test_random_general_chains(arm):
    """Random URDF-style chains (axes such as (-2, 1, 2), origins turned by 0.3 rad: the least-squares route)."""
    check_chain(arm)


def check_chain(arm) -> None:
    Y = regressor(arm)
    base = base_parameters(Y)
    assert len(base.symbols) == base.rank == numeric_rank(Y)
    assert len(set(base.symbols)) == len(base.symbols)
    check_torques_numerically(Y, base, points=2)


@pytest.mark.slow  # the planar 2R drive test covers the grouping of drive parameters in the fast loop
def test_puma560_with_motor_inertia_and_friction():
    """With each joint's armature, viscous and Coulomb friction: 36 + 4 + 12 = 52. Ia1 and Ia2 have the columns of
    ZZ1 and ZZ2 (joint 2 is perpendicular to joint 1, so ZZ2 acts on joint 2 alone) and are grouped into ZZR1 and
    ZZR2, as Khalil's rules group them; Ia3 .. Ia6 and the friction parameters stay on their own."""
    Y = regressor(load_robot("puma560"), armature=True, viscous=True, coulomb=True)
    base = base_parameters(Y)
    names = [b.name for b in base.symbols]
    assert len(names) == base.rank == numeric_rank(Y) == 52
    assert {"Ia3", "Ia4", "Ia5", "Ia6"} <= set(names) and not {"Ia1", "Ia2"} & set(names)
    named = dict(zip(names, base.expressions, strict=True))
    assert named["ZZR1"].coeff(_p("Ia1")) == 1 and named["ZZR2"].coeff(_p("Ia2")) == 1
    check_torques_numerically(Y, base, points=2)
