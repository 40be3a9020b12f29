"""Hand-written branch programs for the code generation tests of inverse kinematics (the planar 2R arm)."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from symjac.codegen.inverse_kinematics import pose_symbols


@dataclass(frozen=True)
class Program:
    """The shape of a branch program (``closed_form.BranchProgram``), written by hand."""

    branch: tuple[str, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    conditions: tuple[sp.Symbol, ...]


def planar_2r_programs(robot):
    """Elbow up and down: c2 = (px^2 + py^2 - L1^2 - L2^2)/(2 L1 L2), q2 = atan2(+-sqrt(1 - c2^2), c2), then q1."""
    symbols = {symbol.name: symbol for symbol in pose_symbols()}
    px, py = symbols["px"], symbols["py"]
    L1, L2 = (p.symbol for p in robot.geometric_parameters)
    theta1, theta2 = robot.q
    c2, disc, s2 = sp.symbols("c2 disc s2", real=True)
    programs = []
    for name, sign in (("elbow up", 1), ("elbow down", -1)):
        programs.append(Program((name,), (
            (c2, (px**2 + py**2 - L1**2 - L2**2) / (2 * L1 * L2)),
            (disc, 1 - c2**2),
            (s2, sign * sp.sqrt(disc)),
            (theta2, sp.atan2(s2, c2)),
            (theta1, sp.atan2(py, px) - sp.atan2(L2 * s2, L1 + L2 * c2)),
        ), (disc,)))
    return tuple(programs)
