"""The worked example target: the lowered assignments as text, evaluated back, agree with the python target."""

import math

from symjac import load_robot
from symjac.codegen import TARGETS, describe, generate, render_files


def test_text_target_lists_assignments_that_evaluate_to_the_python_jacobian():
    assert "text" in TARGETS
    files = render_files(describe(load_robot("planar2r"), "text"))
    text = files["planar2r.txt"]
    block = text.split("\njacobian (6, 2)\n")[1].split("\n\n")[0]
    q = [0.3, -0.7]
    scope = {"theta1": q[0], "theta2": q[1], "L1": 0.4, "L2": 0.3, "sin": math.sin, "cos": math.cos, "out": {}}
    source = {}
    exec(compile(generate(load_robot("planar2r"), "python"), "m", "exec"), source)
    for line in block.splitlines():
        exec(line.strip(), scope)
    J = source["jacobian"](q, L1=0.4, L2=0.3)
    assert [scope["out"][k] for k in range(12)] == [v for row in J for v in row]
