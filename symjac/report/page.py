r"""One self-contained HTML page with a robot's whole derivation: :func:`derivation_report`.

The page holds the DH table, the link transforms, the forward kinematics, the Jacobian in frame {0} and in the frame
where it is most compact, the exact comparison of the four derivation methods, the singularity report with its
explanations, the arm drawn at home and at each solved singular configuration (with the direction it loses there),
and two inline SVG pictures: the manipulability over two joints with the singular curves drawn from
the solved factors, and the joint rates along a path through a singularity; then the dynamics (the mass matrix, the
gravity torques and for a short arm the joint torques, or a sentence saying which links lack inertial data), after
the inverse kinematics (the closed form's family or why there is none, and every solution at an example pose,
drawn). Math is MathML Core (rendered natively by browsers); nothing is fetched when the page is viewed (no
scripts, fonts, or images from elsewhere). Every string that comes from the user (robot name, description, file
name) is HTML-escaped. Identical input gives identical bytes.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import sympy as sp

from symjac._version import __version__
from symjac.analysis.manipulability_map import ManipulabilityMap, SingularPath, manipulability_map, singular_path
from symjac.analysis.singularity.singularities import SingularFactor, SingularityReport, SingularSet, singularities
from symjac.analysis.spaces import jacobian_spaces
from symjac.drawing.geometry import arm_pose, home_configuration
from symjac.kinematics.chain import Frame, chain_of, forward_kinematics
from symjac.kinematics.jacobian import ROW_NAMES, jacobian
from symjac.kinematics.numeric import numeric_jacobian
from symjac.model.conventions import plugin
from symjac.model.ends import end_point, first_frame, last_frame
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import Document
from symjac.printing.nested import named_document
from symjac.printing.results import (
    forward_kinematics_document,
    jacobian_document,
    link_transforms,
    singularities_document,
    transforms_document,
)
from symjac.report.content import Agreement, block_html, caption_html, method_agreement
from symjac.report.dynamics import dynamics_html
from symjac.report.figures import CURVE_COLOURS, arm_svg, map_svg, rates_svg
from symjac.report.inverse_kinematics import inverse_kinematics_html
from symjac.resources import render_template

__all__ = ["Section", "derivation_report", "lost_arrow"]

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


def _html(document: Document) -> str:
    """The document's blocks as HTML, a nested result's intermediates named and defined (:func:`.named_document`)."""
    return "".join(block_html(block) for block in named_document(document).blocks)


def _dh_and_transforms(robot: Robot) -> tuple[Section, Section]:
    """The convention's table (DH parameters, screw axes, origins and axes) and the link transforms: ``symjac show``."""
    table, *transforms = named_document(transforms_document(robot, link_transforms(robot))).blocks
    return (Section("dh", _table_heading(robot), block_html(table)),
            Section("transforms", "Link transforms", "".join(block_html(block) for block in transforms)))


def _table_heading(robot: Robot) -> str:
    """The heading of the robot's table: what its convention calls it (``Standard Denavit-Hartenberg table``)."""
    name = plugin(robot.convention).table_name
    return name[:1].upper() + name[1:]


def _forward(robot: Robot) -> Section:
    """The forward kinematics: the document of ``symjac fk``."""
    source: Frame = first_frame(robot)
    target: Frame = last_frame(robot)
    document = forward_kinematics_document(robot, source, target, forward_kinematics(robot, source, target))
    return Section("fk", "Forward kinematics",
                   f"<p>{html.escape(prose.forward_kinematics_intro(source, target))}</p>" + _html(document))


def _jacobians(robot: Robot, frames: list[Frame], point: tuple[sp.Expr, ...],
               agreements: list[Agreement]) -> Section:
    """The Jacobian in each frame (the document of ``symjac jacobian``), and whether the four methods agree."""
    chain = chain_of(robot)
    words = prose.point_words(robot, point)
    parts = [f"<p>{html.escape(prose.jacobian_intro(words))}</p>"]
    name = end_point(robot) if robot.tool is not None or not any(point) else "reference"
    for frame in frames:
        parts.append(f"<h3>{html.escape(prose.jacobian_frame_heading(frame))}</h3>")
        J = jacobian(chain, frame=frame, point=point)
        parts.append(_html(jacobian_document(robot, J, frame, name, "differentiation")))
    rows = "".join(f"<tr><td>{html.escape(method.replace('_', ' '))}</td>"
                   + "".join(f"<td>{html.escape(a.verdicts[method])}</td>" for a in agreements) + "</tr>"
                   for method in agreements[0].verdicts)
    head = "".join(f"<th>frame {{{a.frame}}}</th>" for a in agreements)
    agree = all(a.agree for a in agreements)
    parts.append(f'<h3>{html.escape(prose.METHODS_HEADING)}</h3><p class="{"ok" if agree else "bad"}">'
                 f'{html.escape(prose.methods_verdict(agree))}</p>'
                 f'<table class="methods"><thead><tr><th>method</th>{head}</tr></thead><tbody>{rows}</tbody></table>')
    return Section("jacobian", "Jacobian", "".join(parts))


def _singularities(robot: Robot, report: SingularityReport) -> Section:
    """The singularity report: the document of ``symjac singularities``."""
    return Section("singularities", "Singular configurations", _html(singularities_document(robot, report)))


def lost_arrow(robot: Robot, report: SingularityReport,
               factor: SingularFactor | SingularSet) -> tuple[np.ndarray, Literal["linear", "angular", "mixed"]] | None:
    """The arrow drawn at the tool for a singular factor (or set): a unit world vector, and what it shows.

    ``linear``: the lost direction's translation half is lost on its own (no joint rate moves the point along it);
    ``angular``: its rotation half is (no joint rate turns the tool about it); ``mixed``: only the two together are
    lost, and the arrow is the translation half (or the rotation half when there is no translation). ``None``
    without a sample or a lost direction.
    """
    lost = factor.lost_direction
    if factor.sample is None or lost is None:
        return None
    J = numeric_jacobian(robot, list(factor.sample), report.frame, report.determinant.point)
    halves = {"linear": lost.full[:3], "angular": lost.full[3:]}
    tolerance = 1e-7 * max(1.0, float(np.abs(J).max()))
    alone = [name for name, half in halves.items() if np.linalg.norm(half) > 1e-9
             and np.abs(half @ J[(0 if name == "linear" else 3):][:3]).max() < tolerance * np.linalg.norm(half)]
    kind: Literal["linear", "angular", "mixed"] = "mixed" if not alone else alone[0]  # type: ignore[assignment]
    half = halves["angular"] if kind == "angular" or np.linalg.norm(halves["linear"]) <= 1e-9 else halves["linear"]
    frame = arm_pose(robot, factor.sample).frames[chain_of(robot).position(report.frame) + 1]
    direction = frame[:3, :3] @ half  # from the analysis frame to the world
    return direction / np.linalg.norm(direction), kind


def _arm_figure(svg: str, caption: str) -> str:
    return f'<figure class="arm">{svg}<figcaption>{caption}</figcaption></figure>'


def _arm_section(robot: Robot, report: SingularityReport) -> Section:
    """The arm at home, and at each solved singular configuration (or set) with the direction lost at the tool."""
    home = home_configuration(robot).tolist()
    figures = [_arm_figure(arm_svg(robot, home, "arm-home"),
                           html.escape(prose.arm_home_caption(", ".join(f"{v:.3g}" for v in home))))]
    singular: list[SingularFactor | SingularSet] = [*report.factors, *report.sets]
    for number, factor in enumerate(singular, start=1):
        arrow = lost_arrow(robot, report, factor)
        if arrow is None or factor.sample is None:
            continue
        direction, shown = arrow
        configuration = prose.sample_parts(factor.sample, robot.q, robot.angle_unit == "deg")
        where = factor.expression if isinstance(factor, SingularFactor) else sp.And(
            *[sp.Eq(condition.expression, 0) for condition in factor.conditions])
        caption = caption_html(prose.arm_singular_parts(where, str(factor.kind), configuration, shown))
        figures.append(_arm_figure(arm_svg(robot, factor.sample, f"arm-singular-{number}", direction.tolist()),
                                   caption))
    return Section("arm", "The arm", f"<p>{html.escape(prose.ARM_INTRO)}</p>"
                   f'<div class="arms">{"".join(figures)}</div>')


def _map_section(robot: Robot, report: SingularityReport, plane: ManipulabilityMap,
                 path: SingularPath | None) -> Section:
    names = (_joint_name(robot, plane.joints[0]), _joint_name(robot, plane.joints[1]))
    fixed = ", ".join(f"{_joint_name(robot, k)} = {value:.3f}" for k, value in enumerate(plane.configuration)
                      if k not in plane.joints)
    rows = ", ".join(ROW_NAMES[r] for r in plane.rows)
    items = []
    for number, curve in enumerate(plane.curves):
        swatch = f'<span class="swatch" style="background:{CURVE_COLOURS[number % len(CURVE_COLOURS)]}"></span>'
        parts = prose.curve_parts(curve.factor.expression, str(curve.factor.kind),
                                  [s.equation for s in curve.solutions])
        items.append(f"<li>{swatch}{caption_html(parts)}</li>")
    for number, mark in enumerate(plane.sets, start=len(plane.curves)):
        swatch = f'<span class="swatch" style="background:{CURVE_COLOURS[number % len(CURVE_COLOURS)]}"></span>'
        conditions = [c.expression for c in report.sets[mark.number - 1].conditions]
        items.append(f"<li>{swatch}{caption_html(prose.set_mark_parts(mark.number, conditions, bool(mark.points)))}"
                     "</li>")
    curves = f"<ul class='curves'>{''.join(items)}</ul>" if items else f"<p>{html.escape(prose.NO_SINGULAR_CURVE)}</p>"
    caption = (f"<p>{html.escape(prose.map_caption(plane.measure, rows, names, fixed))}</p>" + curves
               + (f"<p>{html.escape(prose.PATH_IN_MAP)}</p>" if path else ""))
    return Section("map", "Manipulability map", f'<div class="figure">{map_svg(plane, names, path)}</div>' + caption)


def _regular_self_motion(robot: Robot, report: SingularityReport, path: SingularPath) -> tuple[Any, ...]:
    """A redundant arm's self-motion at the start of the path (a regular configuration), as caption parts."""
    if len(path.rows) >= robot.n_coordinates:
        return ()
    J = numeric_jacobian(robot, path.configurations[0].tolist(), report.determinant.frame,
                         report.determinant.point)[list(path.rows), :]
    spaces = jacobian_spaces(J)
    if spaces.null_space.shape[1] != robot.n_coordinates - len(path.rows):
        return ()
    names = [_joint_name(robot, k) for k in range(robot.n_coordinates)]
    return prose.regular_self_motion_parts(float(path.t[0]), spaces.null_space[:, 0], names)


def _rates_section(robot: Robot, report: SingularityReport, path: SingularPath) -> Section:
    names = [_joint_name(robot, k) for k in range(robot.n_coordinates)]
    command = ", ".join(f"{ROW_NAMES[r]} {value:+.3f}" for r, value in zip(path.rows, path.xdot, strict=True))
    crossing = None if path.curve is None else path.curve.factor.expression
    if path.set_mark is not None:
        crossing = sp.And(*[sp.Eq(c.expression, 0) for c in report.sets[path.set_mark.number - 1].conditions])
    text = f"<p>{caption_html(prose.rates_parts(command, crossing, len(path.rows) == robot.n_coordinates))}</p>"
    motion = _regular_self_motion(robot, report, path)
    if motion:
        text += f"<p>{caption_html(motion)}</p>"
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
    sections = [*_dh_and_transforms(robot), _forward(robot), _jacobians(robot, frames, point, agreements),
                _singularities(robot, report), _arm_section(robot, report)]
    plane = manipulability_map(robot, report)
    if plane is not None:
        path = singular_path(robot, plane)
        sections += [_map_section(robot, report, plane, path), _rates_section(robot, report, path)]
    sections.append(Section("inverse-kinematics", "Inverse kinematics", inverse_kinematics_html(robot)))
    sections.append(Section("dynamics", "Dynamics", dynamics_html(robot)))
    return render_template(TEMPLATE, version=__version__, robot=robot.name, source=source or robot.name,
                           description=robot.description, sections=sections)
