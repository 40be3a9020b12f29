"""A convention added as one module: Hayati's parameters load, derive, print and convert like every other."""

from __future__ import annotations

import json

import numpy as np
import sympy as sp

from symjac import Chain, jacobian, load_robot, robot_from_mapping, robot_to_mapping
from symjac.cli.main import main
from symjac.kinematics.convert import convert

TOML = """
name = "tilted"
description = "three joints with Hayati parameters"
convention = "hayati"
parameters = { L1 = 0.5 }
[[joints]]
type = "revolute"
a = "L1"
d = 0.3
[[joints]]
type = "revolute"
a = 0.4
alpha = "pi/2"
beta = "pi/6"
[[joints]]
type = "prismatic"
theta = "pi/4"
beta = "-pi/2"
"""


def rot(axis: int, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    T = np.eye(4)
    T[j, j], T[j, k], T[k, j], T[k, k] = c, -s, s, c
    return T


def trans(axis: int, value: float) -> np.ndarray:
    T = np.eye(4)
    T[axis, 3] = value
    return T


def reference_fk(q: np.ndarray) -> np.ndarray:
    """Rz(theta) Tz(d) Tx(a) Rx(alpha) Ry(beta) per joint, with the numbers of TOML, in plain NumPy."""
    rows = [(0, 0.5, 0, 0.3, 0), (np.pi / 2, 0.4, np.pi / 6, 0, 0), (0, 0, -np.pi / 2, 0, np.pi / 4)]
    T = np.eye(4)
    for i, ((alpha, a, beta, d, theta), value) in enumerate(zip(rows, q, strict=True)):
        theta, d = (theta + value, d) if i < 2 else (theta, d + value)
        T = T @ rot(2, theta) @ trans(2, d) @ trans(0, a) @ rot(0, alpha) @ rot(1, beta)
    return T


def test_a_hayati_robot_file_loads_derives_prints_and_converts(tmp_path, capsys):
    path = tmp_path / "tilted.toml"
    path.write_text(TOML)
    robot = load_robot(str(path))
    assert robot.convention == "hayati" and robot.joints[1].placement.beta == sp.pi / 6
    assert robot_from_mapping(robot_to_mapping(robot)) == robot

    chain = Chain(robot)
    assert chain.parallel_groups == ((1, 2), (3,))  # row 1 keeps axis 2 parallel; row 2 turns axis 3 away
    assert [chain.axis_frame(i) for i in (1, 2, 3)] == [0, 1, 2]

    rng = np.random.default_rng(7)
    q = rng.uniform(-1, 1, 3)
    subs = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
    fk = np.array(chain.transform(0, 3).subs(subs), dtype=float)
    assert np.allclose(fk, reference_fk(q), atol=1e-12)
    J = np.array(jacobian(robot).subs(subs), dtype=float)
    h = 1e-6
    for k in range(3):
        step = np.eye(3)[k] * h
        plus, minus = reference_fk(q + step), reference_fk(q - step)
        assert np.allclose(J[:3, k], (plus[:3, 3] - minus[:3, 3]) / (2 * h), atol=1e-6)
        omega = (plus[:3, :3] - minus[:3, :3]) / (2 * h) @ reference_fk(q)[:3, :3].T
        assert np.allclose(J[3:, k], [omega[2, 1], omega[0, 2], omega[1, 0]], atol=1e-6)

    assert main(["show", str(path), "--format", "pretty"]) == 0
    shown = capsys.readouterr().out
    assert "Hayati table" in shown and "beta_i" in shown.splitlines()[1] + shown
    assert main(["show", str(path), "--format", "latex"]) == 0
    assert r"\beta_i" in capsys.readouterr().out
    assert main(["show", str(path), "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["convention"] == "hayati"

    numeric = tmp_path / "numeric.toml"  # a DH table is measured from the axes: exact numbers, no parameters
    numeric.write_text(TOML.replace('parameters = { L1 = 0.5 }\n', "").replace('"L1"', "0.5"))
    assert main(["convert", str(numeric), "--to", "modified"]) == 0
    assert 'convention = "modified"' in capsys.readouterr().out
    for target in ("modified", "standard"):
        converted = convert(load_robot(str(numeric)), target)
        assert converted.convention == target
        world_tool = np.array(Chain(converted).transform("world", "tool").subs(subs), dtype=float)
        assert np.allclose(world_tool, fk, atol=1e-12)
