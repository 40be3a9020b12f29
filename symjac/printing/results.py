r"""One document builder per result: what the command line prints and what the report shows, assembled once.

Each builder takes a result the API derived and returns a :class:`~symjac.printing.document.Document`: captioned
equations for LaTeX, pretty text and MathML, and (built only when asked for) its JSON data. ``digits``, when given,
substitutes the parameters' defaults and rounds every number to that many significant digits (``--numeric``): the
derivation stays exact, only the printed result is rounded (``0.4318``, not ``2159/5000``).

Left-hand sides follow Craig: :math:`{}^{0}_{6}T` is frame {6} relative to frame {0}, :math:`{}^{k}J` the
Jacobian expressed in frame {k}.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from types import ModuleType
from typing import TYPE_CHECKING, Any

import sympy as sp

from symjac.kinematics.chain import Frame, chain_of
from symjac.model.conventions.poe import PRODUCT_OF_EXPONENTIALS, home_pose
from symjac.model.robot import Robot
from symjac.printing import prose
from symjac.printing.document import Block, DHTable, Document, Equation, Prescripted
from symjac.printing.latex import rounded

if TYPE_CHECKING:
    from symjac.printing.steps import Propagation

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


def _json() -> ModuleType:
    """:mod:`symjac.printing.json`, imported when a document's data is built (only for ``--format json``)."""
    from symjac.printing import json

    return json


def frame_tex(frame: Frame | str) -> str:
    r"""A frame as a LaTeX index: ``3``, or an upright name (``\mathrm{tool}``)."""
    return str(frame) if isinstance(frame, int) else rf"\mathrm{{{frame}}}"


def shown(robot: Robot, matrix: Any, digits: int | None) -> Any:
    """``matrix`` as printed: exact, or with the parameters' defaults and ``digits`` significant digits."""
    return matrix if digits is None else rounded(matrix.xreplace(robot.defaults), digits)


def transform_equation(source: Frame, target: Frame, T: sp.MatrixBase) -> Equation:
    r""":math:`{}^{source}_{target}T = T`."""
    return Equation(f"{{}}^{{{frame_tex(source)}}}_{{{frame_tex(target)}}}T", f"T_{source}_{target}", T,
                    Prescripted("T", source, target))


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
    equations = [transform_equation(source, target, shown(robot, T, digits)) for source, target, T in transforms]
    blocks = [Block((prose.dh_caption(robot),), (DHTable(robot),))]
    home = []
    if robot.convention == PRODUCT_OF_EXPONENTIALS:  # the home pose M, with the product of exponentials it ends
        home = [Equation("M", "M", shown(robot, home_pose(robot), digits))]
        blocks.append(Block(prose.HOME_POSE, tuple(home)))
    blocks += [Block(prose.fixed_transform_caption(source, target), (e,))
               for (source, target, _), e in zip(transforms, equations, strict=True)]
    return Document(prose.title(robot, "show"), robot.name, tuple(blocks),
                    lambda: _json().show_data(robot, {e.text: e.rhs for e in (*home, *equations)}))


def forward_kinematics_document(robot: Robot, source: Frame, target: Frame, T: sp.MatrixBase,
                                digits: int | None = None) -> Document:
    """``symjac fk``: the pose of ``target`` relative to ``source``."""
    equation = transform_equation(source, target, shown(robot, T, digits))
    return Document(prose.title(robot, "fk"), robot.name, (Block((), (equation,)),),
                    lambda: _json().forward_kinematics_data(robot, equation, source, target))


def _steps(robot: Robot, propagation: Propagation | None, digits: int | None) -> list[Equation]:
    if propagation is None:
        return []
    from symjac.printing.steps import step_equations

    return [dataclasses.replace(step, rhs=shown(robot, step.rhs, digits)) for step in step_equations(propagation)]


def _jacobian_name(frame: Frame) -> Prescripted:
    return Prescripted("J", frame)


def jacobian_document(robot: Robot, J: sp.MatrixBase, frame: Frame, point: str, method: str,
                      propagation: Propagation | None = None, digits: int | None = None) -> Document:
    """``symjac jacobian``: the basic Jacobian in ``frame`` at ``point`` (``--steps``: the propagation first)."""
    steps = _steps(robot, propagation, digits)
    equation = Equation(f"{{}}^{{{frame_tex(frame)}}}J", f"J in frame {frame}", shown(robot, J, digits),
                        _jacobian_name(frame))
    blocks = [Block((), (step,)) for step in steps] + [Block((prose.jacobian_caption(point, method),), (equation,))]
    return Document(prose.title(robot, "jacobian", frame), robot.name, tuple(blocks),
                    lambda: _json().jacobian_data(robot, equation, frame, point, method,
                                               steps if propagation is not None else None))


def screw_jacobian_document(robot: Robot, J: sp.MatrixBase, kind: str, digits: int | None = None) -> Document:
    """``symjac jacobian --kind space|body``: :math:`J_s` or :math:`J_b`, rows angular part first."""
    letter = kind[0]
    equation = Equation(f"J_{letter}", f"J_{letter}", shown(robot, J, digits))
    return Document(prose.title(robot, "screw_jacobian", kind), robot.name,
                    (Block(prose.SCREW_JACOBIAN_CAPTIONS[kind], (equation,)),),
                    lambda: _json().screw_jacobian_data(robot, equation, kind))


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
    blocks = [Block(prose.REPRESENTATION_COORDINATES, (Equation("x", "x", sp.Matrix(result.coordinates)),)),
              Block(prose.RATE_MATRIX, (Equation("E(x)", "E(x)", result.E),)),
              Block(prose.representation_caption(point),
                    (Equation(rf"J_x = E(x)\,{{}}^{{{frame_tex(result.frame)}}}J", f"J_x = E(x) J_{result.frame}",
                              J_x),))]
    blocks += [Block(prose.representation_parts(s)) for s in result.singularities]
    return Document(prose.title(robot, "representation", orientation), robot.name, tuple(blocks),
                    lambda: _json().representation_data(robot, result, J_0, J_x, point, orientation, position),
                    comments=True)


def derivative_document(robot: Robot, Jdot: sp.MatrixBase, bias: sp.MatrixBase, frame: Frame, point: str,
                        moving: bool, rates: Sequence[sp.Symbol], propagation: Propagation | None = None,
                        digits: int | None = None) -> Document:
    r"""``symjac jacobian --derivative``: :math:`\dot J` and the bias acceleration :math:`\dot J \dot q`.

    ``moving``: ``frame`` turns with the joints, so its rotation is differentiated too (the caption says so).
    """
    steps = _steps(robot, propagation, digits)
    Jdot_equation = Equation(rf"{{}}^{{{frame_tex(frame)}}}\dot{{J}}", f"Jdot in frame {frame}",
                             shown(robot, Jdot, digits))
    bias_equation = Equation(rf"{{}}^{{{frame_tex(frame)}}}\dot{{J}}\,\dot{{q}}", f"Jdot qdot in frame {frame}",
                             shown(robot, bias, digits))
    blocks = (*(Block((), (step,)) for step in steps),
              Block((prose.derivative_caption(point, moving),), (Jdot_equation,)),
              Block(prose.BIAS_ACCELERATION, (bias_equation,)))
    return Document(prose.title(robot, "derivative", frame), robot.name, blocks,
                    lambda: _json().jacobian_derivative_data(robot, Jdot_equation, bias_equation, frame, point,
                                                          [str(r) for r in rates],
                                                          steps if propagation is not None else None))


def hessian_document(robot: Robot, slices: Sequence[sp.MatrixBase], frame: Frame, point: str,
                     digits: int | None = None) -> Document:
    r"""``symjac hessian``: one slice :math:`\partial J / \partial q_k` per joint."""
    equations = [Equation(rf"\frac{{\partial\,{{}}^{{{frame_tex(frame)}}}J}}{{\partial {sp.latex(q)}}}", f"dJ/d{q}",
                          shown(robot, H_k, digits)) for q, H_k in zip(robot.q, slices, strict=True)]
    blocks = tuple(Block((prose.hessian_caption(k),), (equation,)) for k, equation in enumerate(equations))
    return Document(prose.title(robot, "hessian", frame), robot.name, blocks,
                    lambda: _json().hessian_data(robot, equations, frame, point))


def torques_document(robot: Robot, tau: sp.MatrixBase, frame: Frame, point: str, wrench: str | None,
                     q: str | None, wrench_names: Sequence[sp.Symbol], digits: int | None = None,
                     evaluated_digits: int | None = None) -> Document:
    r"""``symjac torques``: :math:`\tau = J^T F` for the wrench given as text (``None``: the symbolic one).

    ``evaluated_digits``: the torques are numbers (at a configuration ``q``), shown as decimals of that many digits.
    """
    tau = shown(robot, tau, digits)
    if evaluated_digits is not None:
        tau = rounded(tau, evaluated_digits)
    equation = Equation(r"\tau", "tau", tau)
    return Document(prose.title(robot, "torques"), robot.name, (Block((prose.torques_caption(frame, point),),
                                                                      (equation,)),),
                    lambda: _json().torques_data(robot, equation, frame, point, wrench, q,
                                              [str(s) for s in wrench_names]))


def singularities_document(robot: Robot, report: Any) -> Document:
    """``symjac singularities``: the determinant, then each factor with its solutions and its meaning.

    ``report`` is a :class:`~symjac.analysis.singularity.singularities.SingularityReport`.
    """
    from symjac.printing.summary import singularity_blocks

    return Document(prose.title(robot, "singularities"), robot.name, tuple(singularity_blocks(report)),
                    lambda: {**_json().metadata(robot), **_json().singularity_data(report)}, comments=True)

