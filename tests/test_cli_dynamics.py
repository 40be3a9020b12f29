"""``symjac dynamics``: the parts of the equations of motion as the command line prints them, checked by hand.

The 2R arm's mass matrix against the textbook's closed form, the printed parts against each other
(tau = M qddot + C qdot + g, Newton-Euler against Lagrange), the gravity torques against the potential energy written
here, ``--steps`` link by link, and the errors.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

ARM = ("dynamics", "planar2r", "--symbolic-inertials")
S = sp.Symbol


def parsed(entries):
    """Printed SymPy strings as a matrix of plain symbols (every name its own Symbol)."""
    return sp.Matrix(sp.sympify(entries)) if isinstance(entries, list) else sp.sympify(entries)


def is_zero(matrix) -> bool:
    return sp.simplify(sp.expand_trig(sp.expand(matrix))) == sp.zeros(*matrix.shape)


def test_the_2r_mass_matrix_is_the_textbooks(cli):
    M = parsed(cli.json(*ARM, "--mass-matrix")["mass_matrix"])
    # centres of mass on the link lines, lc_i from joint i: in standard DH frame {i} sits at the link's far end
    m1, m2, L1, L2, lc1, lc2, I1, I2, c2 = S("m1"), S("m2"), S("L1"), S("L2"), S("lc1"), S("lc2"), S("I1"), S("I2"), \
        sp.cos(S("theta2"))
    textbook = sp.Matrix([
        [m1 * lc1**2 + m2 * (L1**2 + lc2**2 + 2 * L1 * lc2 * c2) + I1 + I2, m2 * (lc2**2 + L1 * lc2 * c2) + I2],
        [m2 * (lc2**2 + L1 * lc2 * c2) + I2, m2 * lc2**2 + I2]])
    on_the_line = {S("cx1"): lc1 - L1, S("cx2"): lc2 - L2, S("cy1"): 0, S("cy2"): 0, S("cz1"): 0, S("cz2"): 0,
                   S("Izz1"): I1, S("Izz2"): I2}
    assert is_zero(M.xreplace(on_the_line) - textbook)
    assert not is_zero(M.xreplace(on_the_line) - textbook.xreplace({I2: 0}))  # the check can fail


def test_the_printed_parts_make_the_torques_and_both_methods_agree(cli):
    both = ("--gravity=-y", "--torques", "--mass-matrix", "--coriolis", "--gravity-torques")
    data = cli.json(*ARM, *both)
    tau, M, C, g = (parsed(data[key]) for key in ("torques", "mass_matrix", "coriolis_matrix", "gravity_torques"))
    qd, qdd = sp.Matrix([S(r) for r in data["rates"]]), sp.Matrix([S(a) for a in data["accelerations"]])
    assert data["rates"] == ["thetadot1", "thetadot2"] and data["method"] == "newton-euler"
    assert is_zero(tau - (M * qdd + C * qd + g))
    lagrange = parsed(cli.json(*ARM, "--gravity=-y", "--method", "lagrange")["torques"])
    assert is_zero(tau - lagrange)
    # laid out alike, the two routes print the same line, symbol for symbol
    assert cli.ok(*ARM, "--gravity=-y") == cli.ok(*ARM, "--gravity=-y", "--method", "lagrange")
    assert not is_zero(tau - parsed(cli.json(*ARM)["torques"]))  # gravity along -z0 is normal to the arm's plane


def test_the_gravity_torques_are_the_gradient_of_the_potential_energy_written_here(cli):
    data = cli.json(*ARM, "--gravity=0,-1,0:9.81", "--gravity-torques", "--energy", "--numeric")
    assert data["gravity"] == {"direction": ["0", "-1", "0"], "magnitude": "981/100", "value": 9.81}
    g = parsed(data["gravity_torques"])
    t1, t2 = S("theta1"), S("theta2")
    # unit masses at the frame origins (the symbolic parameters' defaults), L1 = 0.5, L2 = 0.4: heights y1, y2
    V = 9.81 * (0.5 * sp.sin(t1) + 0.5 * sp.sin(t1) + 0.4 * sp.sin(t1 + t2))
    at = {t1: 0.3, t2: -1.1}
    expected = [float(V.diff(t).subs(at)) for t in (t1, t2)]
    assert np.allclose([float(e.subs(at)) for e in g], expected)
    assert np.isclose(float(parsed(data["potential_energy"]).subs(at)), float(V.subs(at)))


def test_steps_print_every_quantity_of_every_link(cli):
    steps = cli.json(*ARM, "--steps")["steps"]
    names = [step["name"] for step in steps]
    for link in (1, 2):
        for name in ("ω", "\N{GREEK SMALL LETTER ALPHA}", "a", "F", "N", "f", "n"):
            assert f"{name}_{link} (in frame {link})" in names
        assert f"a_c{link} (in frame {link})" in names and f"tau_{link}" in names
    assert len(names) == 2 * 9
    assert names.index("n_2 (in frame 2)") < names.index("f_1 (in frame 1)")  # inward from the tip
    latex = cli.ok(*ARM, "--steps")
    assert r"{}^{2}a_{c_2} = " in latex and r"\tau_{1} = " in latex
    pretty = cli.ok(*ARM, "--steps", "--format", "pretty", "--gravity=-y")
    assert "c₁₂" in pretty  # textbook shorthand


def test_a_robot_without_inertial_data_says_which_links(cli, tmp_path):
    bare = tmp_path / "bare.toml"
    bare.write_text('name = "bare"\nconvention = "standard"\n[[joints]]\ntype = "revolute"\na = 1\n'
                    '[[joints]]\ntype = "revolute"\na = 1\n', encoding="utf-8")
    line = cli.one_line_error("dynamics", str(bare))
    assert "bare: links 1, 2 have no inertial data" in line and "--symbolic-inertials" in line
    # the catalog's planar2r has symbolic parameters of its own: the option changes nothing
    assert cli.json("dynamics", "planar2r", "--mass-matrix") == cli.json(*ARM, "--mass-matrix")


@pytest.mark.parametrize(("option", "message"), [
    ("--gravity=1,2", "the direction is 3 numbers"),
    ("--gravity=:-3", "the magnitude must not be negative"),
    ("--gravity=0,0,0", "must not be the zero vector"),
    ("--gravity=x,0,0", "must be a number"),
])
def test_bad_gravity_is_one_line(cli, option, message):
    assert message in cli.one_line_error(*ARM, option)


def test_steps_are_newton_eulers(cli):
    assert "does not apply with --method lagrange" in cli.one_line_error(*ARM, "--steps", "--method", "lagrange")


ROD_ARM = """\
name = "rods"
convention = "standard"
[parameters]
L1 = 0.5
L2 = 0.4
[[joints]]
type = "revolute"
a = "L1"
inertial = {mass = 2.0, com = [-0.25, 0, 0], iyy = 0.0416667, izz = 0.0416667}  # a slender rod along x
[[joints]]
type = "revolute"
a = "L2"
inertial = {mass = 1.5, com = [-0.2, 0, 0], iyy = 0.02, izz = 0.02}
"""


def test_a_robots_own_data_are_the_defaults_of_its_symbols(cli, tmp_path):
    path = tmp_path / "rods.toml"
    path.write_text(ROD_ARM, encoding="utf-8")
    # by hand: g1 = g (m1 lc1 + m2 L1) c1 + g m2 lc2 c12, g2 = g m2 lc2 c12 (lc1 = 0.25, lc2 = 0.2)
    expected = sp.Matrix([9.81 * (2.0 * 0.25 + 1.5 * 0.5) * sp.cos(S("theta1")),
                          9.81 * 1.5 * 0.2 * sp.cos(S("theta1") + S("theta2"))])
    expected[0] += expected[1]
    for symbolic in ((), ("--symbolic-inertials",)):
        data = cli.json("dynamics", str(path), "--gravity=-y", "--gravity-torques", "--numeric", "--digits", "6",
                        *symbolic)
        g = parsed(data["gravity_torques"])
        at = {S("theta1"): 0.4, S("theta2"): 0.9}
        assert np.allclose([float(v) for v in g.xreplace(at)], [float(v) for v in expected.xreplace(at)], rtol=1e-5)
    assert "m1" in cli.json("dynamics", str(path), "--symbolic-inertials", "--gravity=-y",
                            "--gravity-torques")["gravity_torques"][0]
