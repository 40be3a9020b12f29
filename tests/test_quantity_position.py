"""The throwaway quantity: the position of a point, one module and its registry entry, in every front end."""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp
from reference import evaluate, frame_index, frames, random_configuration

from symjac.model.io import load_robot
from symjac.quantities import QUANTITIES
from symjac.quantities.position import point_position

CASES = [("planar3r", 0, "wrist"), ("puma560", 3, "wrist"), ("stanford", 0, (0.1, -0.2, 0.3)),
         ("ur5_poe", 2, "tool"), ("ur5.urdf", "world", "wrist"), ("palletizer", 2, "wrist"),
         ("planar3r", "tool", "tool")]


@pytest.mark.parametrize(("name", "frame", "point"), CASES)
def test_position_matches_the_reference_frames(name, frame, point):
    robot = load_robot(name)
    p = QUANTITIES["position"].derive(robot, point=point, frame=frame)
    assert p.shape == (3, 1)
    rng = np.random.default_rng(11)
    for _ in range(3):
        q = random_configuration(robot, rng)
        poses = frames(robot, q)
        if point == "tool":  # the tool point: the tool transform's origin in frame {n}
            local = np.array(robot.tool.matrix.subs(robot.defaults)[:3, 3], dtype=float).ravel()
        else:
            local = np.zeros(3) if point == "wrist" else np.asarray(point, dtype=float)
        world = poses[robot.n_joints + 1] @ np.append(local, 1.0)
        expected = (np.linalg.inv(poses[frame_index(robot, frame)]) @ world)[:3]
        assert np.allclose(evaluate(p, robot, q).ravel(), expected, atol=1e-10), q


@pytest.mark.parametrize("fmt", ["latex", "pretty", "json"])
def test_position_in_every_format(cli, fmt):
    out = cli.ok("position", "planar2r", "--format", fmt)
    if fmt == "latex":
        assert out.startswith(r"{}^{0}p = \begin{bmatrix}") and "c_{12}" in out
    elif fmt == "pretty":
        assert out.startswith("p in frame 0 =")
    else:
        data = json.loads(out)
        assert data["robot"] == "planar2r" and data["frame"] == 0 and data["point"] == "wrist"
        L1, L2, t1, t2 = sp.symbols("L1 L2 theta1 theta2")
        expected = [L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2), L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2), 0]
        assert all(sp.simplify(sp.sympify(got) - want) == 0 for got, want in zip(data["position"], expected,
                                                                                    strict=True))
        assert data["latex"] == cli.ok("position", "planar2r").strip()


def test_position_options_and_errors(cli):
    assert "0.4318" in cli.ok("position", "puma560", "--numeric", "--frame", "1")
    assert cli.one_line_error("position", "planar2r", "--frame", "x").startswith("symjac: error: --frame must be")


def test_position_is_listed_in_the_help(capsys):
    from symjac.cli.main import main

    with pytest.raises(SystemExit):
        main(["--help"])
    assert "position of a point fixed in the last link" in capsys.readouterr().out


def test_point_position_is_the_python_api():
    robot = load_robot("planar2r")
    assert point_position(robot, frame=2) == sp.zeros(3, 1)
