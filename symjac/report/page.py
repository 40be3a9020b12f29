r"""One self-contained HTML page with a robot's whole derivation: :func:`derivation_report`.

The page holds the DH table, the link transforms, the forward kinematics, the Jacobian in frame {0} and in the frame
where it is most compact, the exact comparison of the four derivation methods, the singularity report with its
explanations, and two inline SVG pictures: the manipulability over two joints with the singular curves drawn from
the solved factors, and the joint rates along a path through a singularity. Math is MathML Core (rendered natively
by browsers); nothing is fetched when the page is viewed (no scripts, fonts, or images from elsewhere). Every string
that comes from the user (robot name, description, file name) is HTML-escaped. Identical input gives identical
bytes.
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import sympy as sp

from symjac._version import __version__
from symjac.analysis.manipulability_map import ManipulabilityMap, SingularPath, manipulability_map, singular_path
from symjac.analysis.singularity.singularities import SingularityReport, singularities
from symjac.kinematics.chain import Frame, chain_of
from symjac.kinematics.jacobian import ROW_NAMES, jacobian
from symjac.model.robot import Robot
from symjac.printing.prose import dh_caption
from symjac.printing.summary import singularity_blocks
from symjac.report.content import (
    Agreement,
    block_html,
    dh_table_html,
    equation_html,
    inline_math,
    jacobian_symbol,
    method_agreement,
    transform_symbol,
)
from symjac.report.figures import CURVE_COLOURS, map_svg, rates_svg
from symjac.resources import render_template

__all__ = ["Section", "derivation_report"]

TEMPLATE = "documents/report.html.j2"


@dataclass(frozen=True)
class Section:
    """A titled part of the page; ``body`` is HTML (already escaped)."""

    anchor: str
    title: str
    body: str


def _joint_name(robot: Robot, joint: int) -> str:
    name = str(robot.q[joint])
    return f"\u03b8{name[5:]}" if name.startswith("theta") else name


def _transforms(robot: Robot) -> Section:
    chain = chain_of(robot)
    parts = []
    for i in range(1, robot.dof + 1):
        parts.append(equation_html(chain.simplified_transform(i - 1, i), transform_symbol(i - 1, i)))
    ends: tuple[tuple[str, Frame, Frame], ...] = (("base", "world", 0), ("tool", robot.dof, "tool"))
    for key, source, target in ends:
        fixed = getattr(robot, key)
        if fixed is not None:
            symbol = transform_symbol(source, target)
            parts.append(f"<p>Fixed {key} transform:</p>" + equation_html(fixed.matrix, symbol))
    return Section("transforms", "Link transforms", "".join(parts))


def _forward(robot: Robot) -> Section:
    source: Frame = "world" if robot.base else 0
    target: Frame = "tool" if robot.tool else robot.dof
    T = chain_of(robot).simplified_transform(source, target)
    text = f"<p>The pose of frame {{{target}}} relative to frame {{{source}}}, the product of the link transforms.</p>"
    return Section("fk", "Forward kinematics", text + equation_html(T, transform_symbol(source, target)))


def _point_words(robot: Robot, point: tuple[sp.Expr, ...]) -> str:
    if robot.tool is not None:
        return "the tool point"
    return f"the wrist point (the origin of frame {{{robot.dof}}})" if not any(point) else "the reference point"


def _jacobians(robot: Robot, frames: list[Frame], point: tuple[sp.Expr, ...],
               agreements: list[Agreement]) -> Section:
    chain = chain_of(robot)
    parts = [f"<p>Basic Jacobian [v; &#969;] (linear velocity first) at {html.escape(_point_words(robot, point))}."
             "</p>"]
    for frame in frames:
        words = "the base frame" if frame == 0 else "the frame where it is most compact"
        parts.append(f"<h3>Expressed in frame {{{frame}}}, {words}</h3>")
        parts.append(equation_html(jacobian(chain, frame=frame, point=point), jacobian_symbol(frame)))
    rows = "".join(f"<tr><td>{html.escape(method.replace('_', ' '))}</td>"
                   + "".join(f"<td>{html.escape(a.verdicts[method])}</td>" for a in agreements) + "</tr>"
                   for method in agreements[0].verdicts)
    head = "".join(f"<th>frame {{{a.frame}}}</th>" for a in agreements)
    agree = all(a.agree for a in agreements)
    verdict = ("All four methods agree: each gives exactly the same matrix as differentiation, compared entry by "
               "entry as exact SymPy expressions." if agree else
               "The methods DISAGREE: see the table; this is a bug in symjac, please report it.")
    parts.append(f'<h3>Four methods, one Jacobian</h3><p class="{"ok" if agree else "bad"}">{verdict}</p>'
                 f'<table class="methods"><thead><tr><th>method</th>{head}</tr></thead><tbody>{rows}</tbody></table>')
    return Section("jacobian", "Jacobian", "".join(parts))


def _singularities(report: SingularityReport) -> Section:
    body = "".join(block_html(block) for block in singularity_blocks(report))
    return Section("singularities", "Singular configurations", body)


def _map_section(robot: Robot, plane: ManipulabilityMap, path: SingularPath | None) -> Section:
    names = (_joint_name(robot, plane.joints[0]), _joint_name(robot, plane.joints[1]))
    fixed = ", ".join(f"{_joint_name(robot, k)} = {value:.3f}" for k, value in enumerate(plane.configuration)
                      if k not in plane.joints)
    measure = "w = |det J|" if plane.measure == "|det J|" else "w = &#8730;det(J J<sup>T</sup>)"
    rows = ", ".join(ROW_NAMES[r] for r in plane.rows)
    items = []
    for number, curve in enumerate(plane.curves):
        swatch = f'<span class="swatch" style="background:{CURVE_COLOURS[number % len(CURVE_COLOURS)]}"></span>'
        if curve.solutions:
            how = "drawn exactly from its solutions " + ", ".join(inline_math(s.equation) for s in curve.solutions)
        else:
            how = "no solved form in this plane: its exact values on a 601 &#215; 601 grid, zero contour (dashed)"
        items.append(f"<li>{swatch}factor {inline_math(curve.factor.expression)} ({html.escape(str(curve.factor.kind))}"
                     f"): {how}</li>")
    curves = f"<ul class='curves'>{''.join(items)}</ul>" if items else (
        "<p>No singular curve crosses this plane (the singular factors do not involve these joints, or the arm is "
        "redundant and singular only where every minor vanishes).</p>")
    caption = (f"<p>Manipulability {measure} of the rows {html.escape(rows)} over {names[0]} and {names[1]}, the "
               f"other joints fixed ({html.escape(fixed) or 'none'}), parameters at their defaults. Singular sets:</p>"
               + curves + ("<p>The dashed white segment is the path of the next figure.</p>" if path else ""))
    return Section("map", "Manipulability map", f'<div class="figure">{map_svg(plane, names, path)}</div>' + caption)


def _rates_section(robot: Robot, path: SingularPath) -> Section:
    names = [_joint_name(robot, k) for k in range(robot.dof)]
    command = ", ".join(f"{ROW_NAMES[r]} {value:+.3f}" for r, value in zip(path.rows, path.xdot, strict=True))
    crossing = "" if path.curve is None else (" crossing the singular set of the factor "
                                             + inline_math(path.curve.factor.expression))
    square = len(path.rows) == robot.dof
    behaviour = ("The exact rates (solid) grow like 1/|t|; the damped least-squares rates (dashed) stay bounded at "
                 "the price of a tracking error." if square else
                 "The arm is redundant, so J has no inverse: the rates shown are the damped least-squares ones.")
    text = (f"<p>Joint rates q&#775; = J<sup>-1</sup> x&#775; for a constant commanded velocity x&#775; = "
            f"({html.escape(command)}) (the direction lost at the singular configuration), along the straight path "
            f"of the map{crossing} at t = 0. {behaviour}</p>")
    return Section("rates", "Joint rates through a singularity", f'<div class="figure">{rates_svg(path, names)}</div>'
                   + text)


def derivation_report(robot: Robot, source: str | None = None) -> str:
    """The whole derivation of ``robot`` as one self-contained HTML page (``source``: how the robot was named)."""
    report = singularities(robot)
    frames: list[Frame] = [0]
    compact = report.determinant.frame
    if compact != 0:
        frames.append(compact)
    point = report.determinant.point
    agreements = [method_agreement(robot, frame, point) for frame in frames]
    dh = Section("dh", "Denavit-Hartenberg table",
                 f"<p>{html.escape(dh_caption(robot))}.</p>" + dh_table_html(robot))
    sections = [dh, _transforms(robot), _forward(robot), _jacobians(robot, frames, point, agreements),
                _singularities(report)]
    plane = manipulability_map(robot, report)
    if plane is not None:
        path = singular_path(robot, plane)
        sections += [_map_section(robot, plane, path), _rates_section(robot, path)]
    return render_template(TEMPLATE, version=__version__, robot=robot.name, source=source or robot.name,
                           description=robot.description, sections=sections, escape=html.escape)
