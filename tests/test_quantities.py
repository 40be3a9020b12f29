"""Derived quantities as plug-ins: one spec each, the commands built from the registry, JSON from the document."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

from symjac.cli.main import COMMANDS
from symjac.errors import ArgumentError
from symjac.kinematics.acceleration import bias_acceleration
from symjac.kinematics.jacobian import jacobian
from symjac.model.io import load_robot
from symjac.printing.document import Block, Document, Equation, JsonKey, equation_latex, render
from symjac.printing.json import document_data, matrix_strings
from symjac.printing.results import jacobian_document
from symjac.quantities import MEMBERS, QUANTITIES, LawName, Quantity
from symjac.quantities.spec import entry_point

ROOT = Path(__file__).resolve().parent.parent
DYNAMICS = ("inverse_dynamics", "mass_matrix", "coriolis_matrix", "gravity_torques", "regressor", "base_regressor")


@pytest.mark.parametrize("name", list(QUANTITIES))
def test_every_spec_names_what_exists(name):
    quantity = QUANTITIES[name]
    assert callable(entry_point(quantity.derivation)), quantity.derivation
    assert quantity.document is None or callable(entry_point(quantity.document)), quantity.document
    assert quantity.law.name == quantity.coupling  # a law of symjac.kinematics.coupling, the one place applying it
    derived = entry_point(quantity.derivation)
    # the derivation applies the law the spec states (kinematics.memo), or is computed from J_q, which does, or (the
    # dynamics) moves its result to the coordinates in its own code, as the law says (tests/test_dynamics*.py)
    law = getattr(derived, "coupling_law", None)
    assert law is not None or name in {"manipulability", "joint_torques", "inverse_kinematics", *DYNAMICS}, \
        f"{quantity.derivation} applies no law"
    assert law is None or law.name == quantity.coupling, (name, law)
    assert quantity.kind is None or quantity.kind.isidentifier()
    assert quantity.command is None or quantity.command in COMMANDS


def test_one_module_per_quantity_in_members_order():
    assert [q.name for q in QUANTITIES.values()] == list(MEMBERS)
    for member in MEMBERS:
        path = ROOT / "symjac" / "quantities" / f"{member}.py"
        assert path.exists(), path


def test_the_quantity_commands_come_from_the_registry():
    own = {q.command: q for q in QUANTITIES.values() if q.command is not None and q.flag is None}
    assert {"fk", "jacobian", "hessian", "torques"} <= own.keys()
    for command, quantity in own.items():
        handler, help_text, _options = COMMANDS[command]
        assert help_text == quantity.summary
        assert handler.__module__ == "symjac.cli.quantities"
    assert QUANTITIES["bias_acceleration"].command == "jacobian"  # jacobian --derivative


def test_the_specs_laws_are_the_kinematics_laws():
    from typing import get_args

    from symjac.kinematics.coupling import LAW_NAMES

    assert set(get_args(LawName)) == set(LAW_NAMES)


def test_a_spec_says_what_is_wrong_with_it():
    with pytest.raises(ArgumentError, match=r"quantity 'q': coupling law 'rows' is none of columns, transposed"):
        Quantity("q", "a quantity", "symjac.kinematics.jacobian:jacobian", "rows")  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match=r"quantity 'q': a command needs a handler"):
        Quantity("q", "a quantity", "symjac.kinematics.jacobian:jacobian", "columns", command="q")
    with pytest.raises(ArgumentError, match=r"an entry point is 'module:name', got 'jacobian'"):
        Quantity("q", "a quantity", "jacobian", "columns")
    with pytest.raises(ArgumentError, match=r"quantity 'manipulability' has no document"):
        QUANTITIES["manipulability"].build_document()


def test_derive_and_build_document_are_the_api():
    robot = load_robot("planar3r")
    J = QUANTITIES["jacobian"].derive(robot, frame=0, point="tool")
    assert jacobian(robot, frame=0, point="tool") == J
    assert QUANTITIES["bias_acceleration"].derive(robot) == bias_acceleration(robot)
    document = QUANTITIES["jacobian"].build_document(robot, J, 0, "tool", "differentiation")
    assert render(document, "latex") == render(jacobian_document(robot, J, 0, "tool", "differentiation"), "latex")


def test_json_is_built_from_the_document_it_renders():
    robot = load_robot("planar2r")
    J = jacobian(robot)
    document = jacobian_document(robot, J, 0, "wrist", "differentiation")
    data = document.json_data()
    (equation,) = document.blocks[-1].math
    assert data["entries"] == matrix_strings(equation.rhs) and data["latex"] == equation_latex(equation)
    assert data["robot"] == "planar2r" and data["shape"] == [6, 2] and data["frame"] == 0
    assert render(document, "json") == json.dumps(data, indent=2) + "\n"


def test_json_keys_place_items_records_flat_vectors_and_stacks():
    x, y = sp.symbols("x y")
    A, B = sp.Matrix([[x, 1], [2, y]]), sp.Matrix([[0, x], [y, 3]])
    blocks = (Block((), (Equation("A", "A", A, key=JsonKey("slices", latex="tex", item="a", stacked="all")),
                         Equation("B", "B", B, key=JsonKey("slices", latex="tex", item="b", stacked="all")))),
              Block((), (Equation("v", "v", sp.Matrix([x, y]), key=JsonKey("v", flat=True)),
                         Equation("s", "s", sp.Matrix([x]), key=JsonKey("steps", record=True)),
                         Equation("u", "u", x))))
    data = document_data(Document("t", "demo", blocks, facts={"kind": "demo"}))
    assert list(data) == ["kind", "all", "slices", "tex", "v", "steps"]  # u has no key: printed only
    assert data["slices"] == {"a": [["x", "1"], ["2", "y"]], "b": [["0", "x"], ["y", "3"]]}
    assert data["all"] == [[["x", "0"], ["1", "x"]], [["2", "y"], ["y", "3"]]]  # all[i][j][k] = item k's [i, j]
    assert data["tex"]["a"].startswith("A = ") and data["v"] == ["x", "y"]
    assert data["steps"] == [{"name": "s", "latex": equation_latex(blocks[1].math[1]), "entries": ["x"]}]


def test_a_document_with_its_own_data_keeps_it():
    document = Document("t", "demo", (), data=lambda: {"answer": 42})
    assert json.loads(render(document, "json")) == {"answer": 42}


def test_derivative_does_not_take_a_representation(cli):
    line = cli.one_line_error("jacobian", "planar2r", "--derivative", "--representation", "zyz")
    assert line == ("symjac: error: --derivative does not apply with --representation (the derivative is of the "
                    "basic Jacobian)")


def test_the_registry_loads_no_sympy():
    code = ("import sys, symjac.quantities, symjac.cli.main\n"
            "print(len(symjac.quantities.QUANTITIES) > 5, 'sympy' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120,
                            env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}, cwd=ROOT)
    assert result.stdout.split() == ["True", "False"]


@pytest.mark.parametrize(("extra", "named"), [(["--frame", "2"], "--frame"),
                                              (["--frame", "2", "--derivative"], "--frame or --derivative")])
def test_a_screw_jacobian_refuses_the_options_it_ignores_in_one_line(capsys, extra, named):
    from symjac.cli.main import main

    assert main(["jacobian", "planar2r", "--kind", "space", *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"symjac: error: --kind space does not take {named}: ")


@pytest.mark.parametrize("name", ["mass_matrix", "gravity_torques", "regressor"])
def test_a_dynamics_specs_law_moves_the_joints_result_to_the_coordinates(name):
    """What code generation does with a spec's law (derive on the joints, move) gives the coupled robot's result."""
    from symjac.kinematics.chain import as_chain
    from symjac.model.inertial_parameters import with_symbolic_inertials

    robot = with_symbolic_inertials(load_robot("palletizer"))  # theta4 = -(theta2 + theta3)
    quantity, chain = QUANTITIES[name], as_chain(robot)
    on_the_joints = quantity.derive(chain.joint_chain)
    moved = quantity.law(chain, on_the_joints)
    assert moved.shape[0] == robot.n_coordinates == on_the_joints.shape[0] - 1
    assert sp.simplify(sp.expand(sp.Matrix(moved) - sp.Matrix(quantity.derive(robot)))).is_zero_matrix
