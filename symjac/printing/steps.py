r"""Velocity, acceleration and force propagation step by step, as equations for lecture notes.

Outward :math:`{}^{i}\omega_i, {}^{i}v_i` (and :math:`{}^{i}\dot\omega_i, {}^{i}\dot v_i`), inward
:math:`{}^{i}f_i, {}^{i}n_i`, then :math:`\tau`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from symjac.errors import ArgumentError
from symjac.kinematics.acceleration_propagation import AccelerationPropagation
from symjac.kinematics.propagation import ForcePropagation, VelocityPropagation
from symjac.printing.document import Equation, Style, equation_latex, equation_text

__all__ = ["Propagation", "propagation_steps", "step_equations"]


Propagation = VelocityPropagation | AccelerationPropagation | ForcePropagation
"""Any of the three iterations whose steps can be printed one by one."""


def step_equations(propagation: Propagation, values: Mapping[Any, Any] | None = None) -> list[Equation]:
    """Every step of a propagation as an :class:`Equation`, in order (``values`` substituted first)."""
    rows: list[tuple[Any, ...]]
    names: tuple[tuple[str, str], ...]
    if isinstance(propagation, VelocityPropagation):
        rows = list(propagation.velocities())
        names = ((r"\omega", "ω"), ("v", "v"))
    elif isinstance(propagation, AccelerationPropagation):
        rows = [(s.frame, s.omega, s.omegadot, s.v, s.vdot) for s in propagation.steps]
        names = ((r"\omega", "ω"), (r"\dot\omega", "ω̇"), ("v", "v"), (r"\dot v", "v̇"))
    else:
        rows = list(propagation.wrenches())
        names = (("f", "f"), ("n", "n"))
    substitution = dict(values or {})
    last = max(row[0] for row in rows if isinstance(row[0], int))
    equations = []
    for frame, *vectors in rows:
        where, subscript = {"tool": ("T", "T"), "point": (str(last), "P")}.get(str(frame), (str(frame), str(frame)))
        for (tex_name, text_name), vector in zip(names, vectors, strict=True):
            upright = where if where.isdigit() else rf"\mathrm{{{where}}}"
            equations.append(Equation(f"{{}}^{{{upright}}}{tex_name}_{{{subscript}}}",
                                      f"{text_name}_{subscript} (in frame {where})", vector.xreplace(substitution)))
    if isinstance(propagation, ForcePropagation):
        equations.append(Equation(r"\tau", "tau", propagation.joint_torques().xreplace(substitution)))
    return equations


def propagation_steps(
    propagation: Propagation, style: Style = "latex", values: Mapping[Any, Any] | None = None
) -> list[str]:
    r"""Every step of a velocity, acceleration or force propagation, one equation per string, ready for lecture notes.

    ``style`` is ``"latex"`` or ``"pretty"`` (Unicode); ``values`` (symbol -> number) are substituted first.

    Examples
    --------
    >>> from symjac import load_robot, velocity_propagation
    >>> propagation_steps(velocity_propagation(load_robot("planar2r")))[3]
    '{}^{1}v_{1} = \\begin{bmatrix}0\\\\L_{1} \\dot{\\theta}_{1}\\\\0\\end{bmatrix}'
    >>> from symjac.kinematics.acceleration_propagation import acceleration_propagation
    >>> propagation_steps(acceleration_propagation(load_robot("planar2r")))[7]
    '{}^{1}\\dot v_{1} = \\begin{bmatrix}- L_{1} \\dot{\\theta}_{1}^{2}\\\\L_{1} \\ddot{\\theta}_{1}\\\\0\\end{bmatrix}'
    """
    if style not in ("latex", "pretty"):
        raise ArgumentError(f"style must be 'latex' or 'pretty', got {style!r}")
    show = equation_latex if style == "latex" else equation_text
    return [show(equation) for equation in step_equations(propagation, values)]
