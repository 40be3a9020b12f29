r"""Velocity and force propagation step by step, as equations for lecture notes.

Outward :math:`{}^{i}\omega_i, {}^{i}v_i`, inward :math:`{}^{i}f_i, {}^{i}n_i`, then :math:`\tau`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from symjac.errors import ArgumentError
from symjac.printing.document import Equation, Style, equation_latex, equation_text
from symjac.propagation import ForcePropagation, VelocityPropagation

__all__ = ["propagation_steps", "step_equations"]


def step_equations(
    propagation: VelocityPropagation | ForcePropagation, values: Mapping[Any, Any] | None = None
) -> list[Equation]:
    """Every step of a propagation as an :class:`Equation`, in order (``values`` substituted first)."""
    if isinstance(propagation, VelocityPropagation):
        rows = propagation.velocities()
        names = ((r"\omega", "ω"), ("v", "v"))
    else:
        rows = propagation.wrenches()
        names = (("f", "f"), ("n", "n"))
    substitution = dict(values or {})
    last = max(frame for frame, _, _ in rows if isinstance(frame, int))
    equations = []
    for frame, first, second in rows:
        where, subscript = {"tool": ("T", "T"), "point": (str(last), "P")}.get(str(frame), (str(frame), str(frame)))
        for (tex_name, text_name), vector in zip(names, (first, second), strict=True):
            equations.append(Equation(f"{{}}^{{{where}}}{tex_name}_{{{subscript}}}",
                                      f"{text_name}_{subscript} (in frame {where})", vector.xreplace(substitution)))
    if isinstance(propagation, ForcePropagation):
        equations.append(Equation(r"\tau", "tau", propagation.joint_torques().xreplace(substitution)))
    return equations


def propagation_steps(
    propagation: VelocityPropagation | ForcePropagation, style: Style = "latex", values: Mapping[Any, Any] | None = None
) -> list[str]:
    r"""Every step of a velocity or force propagation, one equation per string, ready for lecture notes.

    ``style`` is ``"latex"`` or ``"pretty"`` (Unicode); ``values`` (symbol -> number) are substituted first.

    Examples
    --------
    >>> from symjac import load_robot, velocity_propagation
    >>> propagation_steps(velocity_propagation(load_robot("planar2r")))[3]
    '{}^{1}v_{1} = \\begin{bmatrix}0\\\\L_{1} \\dot{\\theta}_{1}\\\\0\\end{bmatrix}'
    """
    if style not in ("latex", "pretty"):
        raise ArgumentError(f"style must be 'latex' or 'pretty', got {style!r}")
    show = equation_latex if style == "latex" else equation_text
    return [show(equation) for equation in step_equations(propagation, values)]
