r"""One document builder per result: what the command line prints and what the report shows, assembled once.

Each builder takes a result the API derived and returns a :class:`~symjac.printing.document.Document`: captioned
equations for LaTeX, pretty text and MathML, each with the key it has in the JSON form, and the facts beside them
(frame, point, shape, row names). The JSON form is built from the document, only when asked for
(:func:`symjac.printing.json.document_data`); no result has a JSON builder of its own. ``digits``, when given,
substitutes the parameters' defaults and rounds every number to that many significant digits (``--numeric``): the
derivation stays exact, only the printed result is rounded (``0.4318``, not ``2159/5000``).

Left-hand sides follow Craig: :math:`{}^{0}_{6}T` is frame {6} relative to frame {0}, :math:`{}^{k}J` the
Jacobian expressed in frame {k}.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import sympy as sp

from symjac.kinematics.chain import Frame, chain_of
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.model.conventions.poe import PRODUCT_OF_EXPONENTIALS, home_pose
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import Block, Document, Equation, JsonKey, ParameterTable, Prescripted
from symjac.printing.latex import rounded

if TYPE_CHECKING:
    from symjac.printing.steps import Propagation, Steps

__all__ = [
    "Transform",
    "derivative_document",
    "forward_kinematics_document",
    "frame_tex",
    "hessian_document",
    "jacobian_document",
    "link_transforms",
    "representation_document",
    "screw_jacobian_document",
    "shown",
    "singularities_document",
    "torques_document",
    "transform_equation",
    "transforms_document",
]

Transform = tuple[Frame, Frame, sp.MatrixBase]
"""``(source, target, T)``: the pose of frame ``target`` relative to frame ``source``."""


def frame_tex(frame: Frame | str) -> str:
    r"""A frame as a LaTeX index: ``3``, or an upright name (``\mathrm{tool}``)."""
    return str(frame) if isinstance(frame, int) else rf"\mathrm{{{frame}}}"


def shown(robot: Robot, matrix: Any, digits: int | None) -> Any:
    """``matrix`` as printed: exact, or with the parameters' defaults and ``digits`` significant digits."""
    return matrix if digits is None else rounded(matrix.xreplace(robot.defaults), digits)


def transform_equation(source: Frame, target: Frame, T: sp.MatrixBase, key: JsonKey | None = None) -> Equation:
    r""":math:`{}^{source}_{target}T = T` (``key``: where it goes in the JSON form)."""
    return Equation(f"{{}}^{{{frame_tex(source)}}}_{{{frame_tex(target)}}}T", f"T_{source}_{target}", T,
                    Prescripted("T", source, target), key)


def _columns(robot: Robot) -> dict[str, Any]:
    """The JSON facts of a 6 x n matrix in the coordinates: its row and column names."""
    return {"rows": list(ROW_NAMES), "columns": [str(q) for q in robot.q]}


def link_transforms(robot: Robot) -> list[Transform]:
    """Each link's transform, simplified, then the fixed base and tool transforms the robot has."""
    chain = chain_of(robot)  # no note for a long chain: each link is simplified alone, 200 links in about a second
    transforms: list[Transform] = [(i - 1, i, chain.simplified_transform(i - 1, i))
                                   for i in range(1, robot.n_joints + 1)]
    if robot.base is not None:
        transforms.append(("world", 0, robot.base.matrix))
    if robot.tool is not None:
        transforms.append((robot.n_joints, "tool", robot.tool.matrix))
    return transforms


def transforms_document(robot: Robot, transforms: Sequence[Transform], digits: int | None = None) -> Document:
    """``symjac show`` and the report's first sections: the DH table, then each transform of :func:`link_transforms`."""
    equations = [transform_equation(source, target, shown(robot, T, digits),
                                    JsonKey("transforms", item=f"T_{source}_{target}"))
                 for source, target, T in transforms]
    blocks = [Block((prose.table_caption(robot),), (ParameterTable(robot),))]
    if robot.convention == PRODUCT_OF_EXPONENTIALS:  # the home pose M, with the product of exponentials it ends
        home = Equation("M", "M", shown(robot, home_pose(robot), digits), key=JsonKey("transforms", item="M"))
        blocks.append(Block(prose.HOME_POSE, (home,)))
    blocks += [Block(prose.fixed_transform_caption(source, target), (e,))
               for (source, target, _), e in zip(transforms, equations, strict=True)]
    return Document(prose.title(robot, "show"), robot.name, tuple(blocks), model=robot)


def forward_kinematics_document(robot: Robot, source: Frame, target: Frame, T: sp.MatrixBase,
                                digits: int | None = None) -> Document:
    """``symjac fk``: the pose of ``target`` relative to ``source``."""
    equation = transform_equation(source, target, shown(robot, T, digits), JsonKey("entries", latex="latex"))
    caption = prose.forward_kinematics_caption(source, target, robot.n_joints)
    at = prose.point_phrase("tool" if target == "tool" else "flange", n=robot.n_joints) if target in (
        "tool", robot.n_joints) else None
    return Document(prose.title(robot, "fk"), robot.name, (Block((caption,), (equation,)),),
                    facts={"source": source, "target": target, **({"at": at} if at else {})}, model=robot)


def _steps(robot: Robot, propagation: Steps | None, digits: int | None) -> list[Equation]:
    if propagation is None:
        return []
    from symjac.printing.steps import step_equations

    return [dataclasses.replace(step, rhs=shown(robot, step.rhs, digits), key=JsonKey("steps", record=True))
            for step in step_equations(propagation)]


def _jacobian_name(frame: Frame) -> Prescripted:
    return Prescripted("J", frame)


def jacobian_document(robot: Robot, J: sp.MatrixBase, frame: Frame, point: str, method: str,
                      propagation: Steps | None = None, digits: int | None = None, *,
                      link: int | None = None) -> Document:
    """``symjac jacobian``: the basic Jacobian in ``frame`` at ``point`` (``--steps``: the propagation first).

    ``link``: the point is fixed in that link (``--link``), ``point`` its coordinates in its frame.
    """
    steps = _steps(robot, propagation, digits)
    equation = Equation(f"{{}}^{{{frame_tex(frame)}}}J", f"J in frame {frame}", shown(robot, J, digits),
                        _jacobian_name(frame), JsonKey("entries", latex="latex"))
    blocks = [Block((), (step,)) for step in steps]
    blocks.append(Block((prose.jacobian_caption(point, method, link, robot.n_joints),), (equation,)))
    return Document(prose.title(robot, "jacobian", frame), robot.name, tuple(blocks),
                    facts={"frame": frame, "point": point, "at": prose.point_phrase(point, link, robot.n_joints),
                           **_link(link), "method": method, "shape": list(J.shape),
                           **_columns(robot)}, model=robot)


def _link(link: int | None) -> dict[str, int]:
    """The ``link`` fact of a result at a point fixed in a link (``--link``), or none."""
    return {} if link is None else {"link": link}


def screw_jacobian_document(robot: Robot, J: sp.MatrixBase, kind: str, digits: int | None = None) -> Document:
    """``symjac jacobian --kind space|body``: :math:`J_s` or :math:`J_b`, rows angular part first."""
    from symjac.kinematics.screws import SCREW_ROWS

    letter = kind[0]
    equation = Equation(f"J_{letter}", f"J_{letter}", shown(robot, J, digits), key=JsonKey("entries", latex="latex"))
    return Document(prose.title(robot, "screw_jacobian", kind), robot.name,
                    (Block(prose.SCREW_JACOBIAN_CAPTIONS[kind], (equation,)),),
                    facts={"kind": kind, "shape": list(J.shape), "rows": list(SCREW_ROWS),
                           "columns": [str(q) for q in robot.q]}, model=robot)


def representation_document(robot: Robot, result: Any, point: str, orientation: str, position: str,
                            digits: int | None = None) -> Document:
    r"""``symjac jacobian --representation``: x, E(x), :math:`J_x = E(x)\,J_0`, then E's own singularities.

    ``result`` is a :class:`~symjac.analysis.representations.RepresentationJacobian`; its :math:`J_x` is printed
    multiplied out, each entry over one denominator.
    """
    from symjac.symbolic.simplify import simplify_matrix  # only this result prints a simplified product

    J_x = simplify_matrix(result.J_x, chain_of(robot).angle_basis(result.frame)).applyfunc(
        lambda entry: sp.factor_terms(sp.together(entry)))
    J_0, J_x = shown(robot, result.J_0, digits), shown(robot, J_x, digits)
    blocks = [Block(prose.REPRESENTATION_COORDINATES, (Equation("x", "x", sp.Matrix(result.coordinates),
                                                                key=JsonKey("coordinates", flat=True)),)),
              Block(prose.RATE_MATRIX, (Equation("E(x)", "E(x)", result.E, key=JsonKey("E")),)),
              Block(prose.representation_caption(point, robot.n_joints),
                    (Equation(rf"J_x = E(x)\,{{}}^{{{frame_tex(result.frame)}}}J", f"J_x = E(x) J_{result.frame}",
                              J_x),))]
    blocks += [Block(prose.representation_parts(s)) for s in result.singularities]
    # JSON only: the basic Jacobian the product starts from, and J_x under the name it had there
    extra = (Equation("J_0", "J_0", J_0, key=JsonKey("J_0")),
             Equation(r"J_x = E(x)\,J_0", "J_x", J_x, key=JsonKey("J_x", latex="latex")))
    facts = {"frame": result.frame, "point": point, "orientation": orientation, "position": position,
             "representation_singularities": [_representation_singularity(s) for s in result.singularities]}
    return Document(prose.title(robot, "representation", orientation), robot.name, tuple(blocks), comments=True,
                    facts=facts, model=robot, extra=extra)


def _representation_singularity(singularity: Any) -> str:
    """``factor = 0 (variable = values): what goes wrong there`` (:func:`.prose.representation_words`)."""
    values = " or ".join(str(value) for value in singularity.solutions)
    return f"{singularity.factor} = 0 ({singularity.variable} = {values}): {prose.representation_words(singularity)}"


def derivative_document(robot: Robot, Jdot: sp.MatrixBase, bias: sp.MatrixBase, frame: Frame, point: str,
                        moving: bool, rates: Sequence[sp.Symbol], propagation: Propagation | None = None,
                        digits: int | None = None, *, link: int | None = None) -> Document:
    r"""``symjac jacobian --derivative``: :math:`\dot J` and the bias acceleration :math:`\dot J \dot q`.

    ``moving``: ``frame`` turns with the joints, so its rotation is differentiated too (the caption says so).
    """
    steps = _steps(robot, propagation, digits)
    Jdot_equation = Equation(rf"{{}}^{{{frame_tex(frame)}}}\dot{{J}}", f"Jdot in frame {frame}",
                             shown(robot, Jdot, digits), key=JsonKey("entries", latex="latex"))
    bias_equation = Equation(rf"{{}}^{{{frame_tex(frame)}}}\dot{{J}}\,\dot{{q}}", f"Jdot qdot in frame {frame}",
                             shown(robot, bias, digits),
                             key=JsonKey("bias_acceleration", latex="bias_latex", flat=True))
    blocks = (*(Block((), (step,)) for step in steps),
              Block((prose.derivative_caption(point, moving, link, robot.n_joints),), (Jdot_equation,)),
              Block(prose.BIAS_ACCELERATION, (bias_equation,)))
    return Document(prose.title(robot, "derivative", frame), robot.name, blocks,
                    facts={"frame": frame, "point": point, **_link(link), "rates": [str(r) for r in rates],
                           "shape": list(Jdot.shape), **_columns(robot)}, model=robot)


def hessian_document(robot: Robot, slices: Sequence[sp.MatrixBase], frame: Frame, point: str,
                     digits: int | None = None, *, link: int | None = None) -> Document:
    r"""``symjac hessian``: one slice :math:`\partial J / \partial q_k` per joint."""
    equations = [Equation(rf"\frac{{\partial\,{{}}^{{{frame_tex(frame)}}}J}}{{\partial {sp.latex(q)}}}", f"dJ/d{q}",
                          shown(robot, H_k, digits),
                          key=JsonKey("slices", latex="slices_latex", item=str(q), stacked="entries"))
                 for q, H_k in zip(robot.q, slices, strict=True)]
    at = prose.point_phrase(point, link, robot.n_joints)
    blocks = tuple(Block((prose.hessian_caption(k, at),), (equation,)) for k, equation in enumerate(equations))
    n = robot.n_coordinates
    return Document(prose.title(robot, "hessian", frame), robot.name, blocks,
                    facts={"frame": frame, "point": point, **_link(link), "shape": [6, n, n],
                           "layout": "entries[i][j][k] = d J[i][j] / d q[k]", **_columns(robot)}, model=robot)


def torques_document(robot: Robot, tau: sp.MatrixBase, frame: Frame, point: str, wrench: str | None,
                     q: str | None, wrench_names: Sequence[sp.Symbol], digits: int | None = None,
                     evaluated_digits: int | None = None, *, link: int | None = None) -> Document:
    r"""``symjac torques``: :math:`\tau = J^T F` for the wrench given as text (``None``: the symbolic one).

    ``evaluated_digits``: the torques are numbers (at a configuration ``q``), shown as decimals of that many digits.
    """
    tau = shown(robot, tau, digits)
    if evaluated_digits is not None:
        tau = rounded(tau, evaluated_digits)
    equation = Equation(r"\tau", "tau", tau, key=JsonKey("torques", latex="latex", flat=True))
    caption = prose.torques_caption(frame, point, link, robot.n_joints)
    return Document(prose.title(robot, "torques"), robot.name, (Block((caption,), (equation,)),),
                    facts={"frame": frame, "point": point, **_link(link),
                           "wrench": wrench or [str(s) for s in wrench_names],
                           "q": q}, model=robot)


def singularities_document(robot: Robot, report: Any) -> Document:
    """``symjac singularities``: the determinant, then each factor with its solutions and its meaning.

    ``report`` is a :class:`~symjac.analysis.singularity.singularities.SingularityReport`.
    """
    from symjac.printing.summary import singularity_blocks

    def data() -> dict[str, Any]:  # a report, not equations: its own JSON form, built only for JSON
        from symjac.printing import json as json_form  # looked up when called, so that the JSON code loads only here

        return {**json_form.metadata(robot), **json_form.singularity_data(report)}

    blocks = singularity_blocks(report, robot.angle_unit == "deg")  # a degree file's sample in degrees
    return Document(prose.title(robot, "singularities"), robot.name, tuple(blocks), data, comments=True)

