"""The command line at the acceleration level: ``jacobian --derivative`` and ``hessian``, checked numerically."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from marks import marked

from symjac.kinematics.chain import chain_of
from symjac.kinematics.numeric import numeric_at, numeric_jacobian
from symjac.model.io import load_robot

STEP = 1e-6


def numeric(robot, strings, q, rates=None):
    """Entries printed by the CLI (SymPy strings) as floats at q (and joint rates)."""
    names = {str(s): s for s in (*robot.q, *robot.parameter_symbols)}
    matrix = sp.Matrix(sp.sympify(strings, locals=names))
    if rates is not None:
        matrix = matrix.xreplace({s: rates[str(s)] for s in matrix.free_symbols if str(s) in rates})
    return numeric_at(robot, matrix, list(q))


@pytest.mark.parametrize(("name", "frame"), marked([("planar3r", "0"), ("stanford", "0"), ("stanford", "3")]))
def test_derivative_json_matches_differences_of_the_jacobian(cli, name, frame):
    robot = load_robot(name)
    data = cli.json("jacobian", name, "--derivative", "--frame", frame)
    rng = np.random.default_rng(7)
    q, qdot = rng.uniform(-1, 1, robot.n_coordinates), rng.uniform(-1, 1, robot.n_coordinates)
    rates = dict(zip(data["rates"], qdot, strict=True))
    jdot = numeric(robot, data["entries"], q, rates)
    bias = numeric(robot, data["bias_acceleration"], q, rates).ravel()
    J = lambda x: numeric_jacobian(robot, list(x), frame=int(frame))  # noqa: E731
    expected = (J(q + STEP * qdot) - J(q - STEP * qdot)) / (2 * STEP)
    assert np.allclose(jdot, expected, atol=1e-7)
    assert np.allclose(bias, expected @ qdot, atol=1e-7)
    assert data["shape"] == [6, robot.n_coordinates]


def test_hessian_json_layout_matches_differences(cli):
    robot = load_robot("stanford")
    data = cli.json("hessian", "stanford")
    assert data["shape"] == [6, 6, 6]
    q = np.linspace(-0.9, 0.8, 6)
    H = np.stack([np.stack([numeric(robot, row, q) for row in rows]) for rows in
                  ([[entry] for entry in data["entries"][i][j]] for i in range(6) for j in range(6))])
    H = H.reshape(6, 6, 6)
    for k in range(6):
        step = STEP * np.eye(6)[k]
        expected = (numeric_jacobian(robot, list(q + step)) - numeric_jacobian(robot, list(q - step))) / (2 * STEP)
        assert np.allclose(H[:, :, k], expected, atol=1e-7), k
        assert np.allclose(numeric(robot, data["slices"][str(robot.q[k])], q), expected, atol=1e-7)


def test_derivative_latex_and_pretty(cli):
    status, out, err = cli.run("jacobian", "planar2r", "--derivative")
    assert status == 0, err
    jdot, bias = out.splitlines()
    assert jdot.startswith(r"{}^{0}\dot{J} = \begin{bmatrix}")
    assert r"\left(\dot{\theta}_{1} + \dot{\theta}_{2}\right)^{2}" in bias  # the textbook square of the sum
    status, out, _ = cli.run("jacobian", "planar2r", "--derivative", "--frame", "2", "--format", "pretty")
    assert status == 0
    assert "moving frame" in out


def test_hessian_latex_has_one_slice_per_joint(cli):
    status, out, err = cli.run("hessian", "stanford", "--numeric")
    assert status == 0, err
    lines = out.splitlines()
    assert [line.split(" = ")[0] for line in lines] == [
        rf"\frac{{\partial\,{{}}^{{0}}J}}{{\partial {q}}}" for q in
        (r"\theta_{1}", r"\theta_{2}", "d_{3}", r"\theta_{4}", r"\theta_{5}", r"\theta_{6}")]
    assert "d_{2}" not in out  # --numeric substituted the parameter


@pytest.mark.parametrize("argv", [("jacobian", "planar2r", "--derivative", "--steps", "--point", "tool"),
                                  ("hessian", "planar2r", "--frame", "7"),
                                  ("hessian", "planar2r", "--point", "1,2")])
def test_bad_acceleration_requests_are_one_line_errors(cli, argv):
    status, out, err = cli.run(*argv)
    assert (status, out, len(err.splitlines())) == (2, "", 1), err
    assert err.startswith("symjac: error: ")


def test_derivative_steps_end_with_the_bias_in_the_tip_frame(cli):
    robot = load_robot("stanford")
    data = cli.json("jacobian", "stanford", "--derivative", "--steps")
    names = [step["name"] for step in data["steps"]]
    assert len(names) == 4 * (robot.n_coordinates + 1) and names[-1].startswith("v̇_6")
    rng = np.random.default_rng(3)
    q, qdot = rng.uniform(-1, 1, 6), rng.uniform(-1, 1, 6)
    values = {**dict(zip(data["rates"], qdot, strict=True)), **{f"thetaddot{i}": 0.0 for i in range(1, 7)},
              "dddot3": 0.0}
    vdot_6 = numeric(robot, [[e] for e in data["steps"][-1]["entries"]], q, values).ravel()
    bias_0 = numeric(robot, [[e] for e in data["bias_acceleration"]], q, values).ravel()
    R_0_6 = numeric_at(robot, chain_of(robot).rotation(0, 6), list(q))
    assert np.allclose(R_0_6 @ vdot_6, bias_0[:3], atol=1e-12)
    assert np.linalg.norm(bias_0[:3]) > 0.01  # not trivially zero
