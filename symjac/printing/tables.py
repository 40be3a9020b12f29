r"""Denavit-Hartenberg tables as text, LaTeX and rows of strings (for JSON).

A DH robot has one row :math:`(\alpha, a, d, \theta)` per joint (:math:`\alpha_{i-1}, a_{i-1}` in the modified
convention); a general chain one row of origin ``xyz``, ``rpy``, joint ``axis``, offset and angle, as in URDF.
"""

from __future__ import annotations

import sympy as sp

from symjac.model.robot import Robot
from symjac.printing.latex import latex

__all__ = ["dh_headers", "dh_rows", "dh_table_latex", "dh_table_text", "text_table"]


def dh_headers(robot: Robot) -> list[str]:
    """Plain-text column names after ``joint`` and ``type``."""
    if robot.convention == "general":  # origin and axis per joint, as in URDF
        return ["xyz", "rpy", "axis", "d_i", "theta_i"]
    return ["alpha_{i-1}", "a_{i-1}", "d_i", "theta_i"] if robot.convention == "modified" else [
        "alpha_i", "a_i", "d_i", "theta_i"]


def dh_rows(robot: Robot) -> list[list[str]]:
    """One row of strings per joint: index, type, then the columns of :func:`dh_headers` (SymPy strings)."""
    if robot.convention == "general":
        zero = (sp.S.Zero,) * 3
        return [[str(joint.index), joint.type.value,
                 *(sp.sstr(list(v)) for v in (joint.origin.xyz if joint.origin else zero,
                                              joint.origin.rpy if joint.origin else zero,
                                              joint.axis or (0, 0, 1))),
                 sp.sstr(joint.offset), sp.sstr(joint.angle)] for joint in robot.joints]
    return [[str(joint.index), joint.type.value, *(sp.sstr(e) for e in (joint.alpha, joint.a, joint.offset,
                                                                         joint.angle))]
            for joint in robot.joints]


def text_table(headers: list[str], rows: list[list[str]]) -> str:
    """Left-aligned columns two spaces apart, header first."""
    widths = [max(len(row[i]) for row in [headers, *rows]) for i in range(len(headers))]
    lines = ["  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
             for row in [headers, *rows]]
    return "\n".join(lines) + "\n"


def dh_table_text(robot: Robot) -> str:
    """The DH table as aligned plain text."""
    return text_table(["joint", "type", *dh_headers(robot)], dh_rows(robot))


def dh_table_latex(robot: Robot) -> str:
    r"""The DH table as a LaTeX ``array`` (entries in textbook shorthand; a general chain's vectors in brackets)."""
    if robot.convention == "general":
        zero = (sp.S.Zero,) * 3

        def vector(values: tuple[sp.Expr, ...]) -> str:
            return r"\left[" + ",\\ ".join(latex(v) for v in values) + r"\right]"

        cells = r" \\ ".join(" & ".join([str(joint.index), rf"\text{{{joint.type.value}}}",
                                          *(vector(tuple(v)) for v in (joint.origin.xyz if joint.origin else zero,
                                                                       joint.origin.rpy if joint.origin else zero,
                                                                       joint.axis or (0, 0, 1))),
                                          latex(joint.offset), latex(joint.angle)])
                              for joint in robot.joints)
        columns = r"\text{type} & \text{xyz} & \text{rpy} & \text{axis} & d_i & \theta_i"
        return r"\begin{array}{c|cccccc} i & " + columns + r" \\ \hline " + cells + r" \end{array}"
    headers = [r"\alpha_{i-1}", "a_{i-1}", "d_i", r"\theta_i"] if robot.convention == "modified" else [
        r"\alpha_i", "a_i", "d_i", r"\theta_i"]
    body = r" \\ ".join(" & ".join([str(joint.index)] + [latex(e) for e in (joint.alpha, joint.a, joint.offset,
                                                                              joint.angle)])
                        for joint in robot.joints)
    return r"\begin{array}{c|cccc} i & " + " & ".join(headers) + r" \\ \hline " + body + r" \end{array}"
