"""``symjac dynamics --regressor / --base-parameters``: the parameters' side of the dynamics on the command line.

The printed regressor times the standard parameters, written here from the symbolic inertial parameters by hand
(M = m, MX = m cx, ..., XX = Ixx + m (cy^2 + cz^2), ...), is the printed torques of ``--symbolic-inertials``; the
printed base regressor times the printed base parameters is the regressor times the standard ones; the documents
compile with pdflatex; misuse is one line.
"""

from __future__ import annotations

import pytest
import sympy as sp
from test_latex_compile import PDFLATEX, compile_tex

from symjac.cli.main import main

S = sp.Symbol


def parsed(entries):
    return sp.Matrix(sp.sympify(entries)) if isinstance(entries, list) else sp.sympify(entries)


def by_hand(link: int) -> dict[sp.Symbol, sp.Expr]:
    """Link ``link``'s ten standard parameters from m, c and the inertia about the centre of mass (axes of {i})."""
    m = S(f"m{link}")
    cx, cy, cz = (S(f"c{axis}{link}") for axis in "xyz")
    inertia = {pair: S(f"I{pair}{link}") for pair in ("xx", "xy", "xz", "yy", "yz", "zz")}
    return {S(f"XX{link}"): inertia["xx"] + m * (cy**2 + cz**2), S(f"XY{link}"): inertia["xy"] - m * cx * cy,
            S(f"XZ{link}"): inertia["xz"] - m * cx * cz, S(f"YY{link}"): inertia["yy"] + m * (cx**2 + cz**2),
            S(f"YZ{link}"): inertia["yz"] - m * cy * cz, S(f"ZZ{link}"): inertia["zz"] + m * (cx**2 + cy**2),
            S(f"MX{link}"): m * cx, S(f"MY{link}"): m * cy, S(f"MZ{link}"): m * cz, S(f"M{link}"): m}


ARM = "articulated3r"  # spatial, gravity acts: every kind of column appears


def test_the_regressor_times_the_standard_parameters_is_the_printed_torques(cli):
    data = cli.json("dynamics", ARM, "--regressor")
    Y, names = parsed(data["regressor"]), data["regressor_parameters"]
    assert names[:10] == ["XX1", "XY1", "XZ1", "YY1", "YZ1", "ZZ1", "MX1", "MY1", "MZ1", "M1"] and len(names) == 30
    values = {k: v for link in (1, 2, 3) for k, v in by_hand(link).items()}
    pi = sp.Matrix([values[S(name)] for name in names])
    tau = parsed(cli.json("dynamics", ARM, "--symbolic-inertials")["torques"])
    difference = sp.expand(sp.expand_trig(Y * pi - sp.Matrix(tau)))
    assert sp.simplify(difference) == sp.zeros(3, 1)
    wrong = pi.copy()
    wrong[names.index("MX3")] += 1
    assert sp.simplify(sp.expand(sp.expand_trig(Y * wrong - sp.Matrix(tau)))) != sp.zeros(3, 1)  # it can fail


def test_the_base_parameters_reproduce_the_regressor(cli):
    data = cli.json("dynamics", ARM, "--regressor", "--base-parameters")
    Y, names = parsed(data["regressor"]), data["regressor_parameters"]
    order = data["base_parameter_order"]
    assert set(data["base_parameters"]) == set(order) and data["rank"] == len(order) < len(names)
    Y_b = parsed(data["base_regressor"])
    pi_b = sp.Matrix([parsed(data["base_parameters"][name]) for name in order])
    pi = sp.Matrix([S(name) for name in names])
    assert sp.simplify(sp.expand(sp.expand_trig(Y_b * pi_b - Y * pi))) == sp.zeros(3, 1)
    for name in data["unidentifiable"]:  # a standard parameter that acts on no torque has a zero column
        assert Y[:, names.index(name)] == sp.zeros(3, 1)
    assert data["base_parameters_latex"][order[0]].startswith(sp.latex(S(order[0])) + " = ")


def test_the_pretty_table_and_the_2r_arms_four_base_parameters(cli):
    text = cli.ok("dynamics", "planar2r", "--base-parameters", "--format", "pretty")
    assert "4 identifiable combinations" in text and "not identifiable" in text
    assert "Y_1 =" not in text  # the regressor only with --regressor
    data = cli.json("dynamics", "planar2r", "--base-parameters")
    assert data["base_parameter_order"] == ["ZZR1", "ZZR2", "MXR2", "MY2"] and "regressor" not in data
    numeric = cli.json("dynamics", "planar2r", "--base-parameters", "--numeric")["base_parameters"]
    assert parsed(numeric["MXR2"]) == S("MX2") + sp.Float(0.4) * S("M2")  # L2 = 0.4


@pytest.mark.parametrize("argv, message", [
    (("--regressor", "--steps"), "take none of --steps"),
    (("--regressor", "--mass-matrix"), "ask for the other parts"),
    (("--base-parameters", "--symbolic-inertials"), "need no inertial data"),
])
def test_misuse_is_one_line(cli, argv, message):
    assert message in cli.one_line_error("dynamics", "planar2r", *argv)


@pytest.mark.external
@pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed; .ci/run installs it")
@pytest.mark.parametrize("robot, flags", [("articulated3r", ("--regressor", "--base-parameters")),
                                          ("puma560", ("--base-parameters",))])
def test_the_documents_compile(tmp_path, robot, flags):
    path = tmp_path / f"{robot}.tex"
    assert main(["dynamics", robot, *flags, "--standalone", "-o", str(path)]) == 0
    assert compile_tex(path) == []
