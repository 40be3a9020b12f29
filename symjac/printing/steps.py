r"""Every Jacobian method, and the Newton-Euler recursion of the dynamics, step by step, as equations for lecture notes.

Propagations: outward :math:`{}^{i}\omega_i, {}^{i}v_i` (and :math:`{}^{i}\dot\omega_i, {}^{i}\dot v_i`), inward
:math:`{}^{i}f_i, {}^{i}n_i`, then :math:`\tau`. Cross products, per joint i with its axis in frame {a}:
:math:`{}^kz_a`, :math:`{}^kp_{aP}` (revolute) and the column :math:`{}^kJ_i = [z_a \times p_{aP}; z_a]` or
:math:`[z_a; 0]`. Differentiation: :math:`{}^0p_P`, per joint :math:`{}^0J_{v,i} = \partial\,{}^0p_P/\partial q_i` and
:math:`{}^0J_{\omega,i}`, then :math:`{}^k_0R` for a frame {k} other than {0}.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from symjac.analysis.dynamics.newton_euler import NewtonEuler
from symjac.errors import ArgumentError
from symjac.kinematics.acceleration_propagation import AccelerationPropagation
from symjac.kinematics.column_steps import CrossProductSteps, DifferentiationSteps
from symjac.kinematics.propagation import ForcePropagation, VelocityPropagation
from symjac.printing.document import Equation, Style, equation_latex, equation_text

__all__ = ["Propagation", "Steps", "propagation_steps", "step_equations"]


Propagation = VelocityPropagation | AccelerationPropagation | ForcePropagation
"""Any of the three iterations whose steps can be printed one by one."""
Steps = Propagation | CrossProductSteps | DifferentiationSteps | NewtonEuler
"""Any derivation whose steps can be printed: a propagation, the columns of the cross-product or differentiation
method (:mod:`symjac.kinematics.column_steps`), or the Newton-Euler recursion of the dynamics."""

_OUTWARD = (("omega", r"\omega", "ω"), ("alpha", r"\alpha", "\N{GREEK SMALL LETTER ALPHA}"), ("a", "a", "a"),
            ("a_c", "a_{{c_{i}}}", "a_c{i}"), ("F", "F", "F"), ("N", "N", "N"))
_INWARD = (("f", "f", "f"), ("n", "n", "n"))


def _newton_euler_equations(recursion: NewtonEuler) -> list[Equation]:
    """Outward link by link (omega, alpha, a, a_c, F, N), then inward from the tip (f, n, tau), each in its frame."""
    equations = []
    for step in recursion.steps:
        i = step.link
        for field, tex, text in _OUTWARD:
            tex_name = tex.format(i=i) if "{i}" in tex else f"{tex}_{{{i}}}"
            text_name = text.format(i=i) if "{i}" in text else f"{text}_{i}"
            equations.append(Equation(f"{{}}^{{{i}}}{tex_name}", f"{text_name} (in frame {i})", getattr(step, field)))
    for step in reversed(recursion.steps):
        i = step.link
        equations += [Equation(f"{{}}^{{{i}}}{tex}_{{{i}}}", f"{text}_{i} (in frame {i})", getattr(step, field))
                      for field, tex, text in _INWARD]
        equations.append(Equation(rf"\tau_{{{i}}}", f"tau_{i}", step.tau))
    return equations


def _frame(frame: Any) -> str:
    return str(frame) if isinstance(frame, int) else rf"\mathrm{{{frame}}}"


def _cross_product_equations(steps: CrossProductSteps) -> list[Equation]:
    k, equations = _frame(steps.frame), []
    for step in steps.columns:
        a, i = step.axis_frame, step.joint
        equations.append(Equation(f"{{}}^{{{k}}}z_{{{a}}}", f"z_{a} (in frame {steps.frame})", step.axis))
        if step.lever is None:
            tex, text = rf"\begin{{bmatrix}}z_{{{a}}}\\0\end{{bmatrix}}", f"[z_{a}; 0]"
        else:
            equations.append(Equation(f"{{}}^{{{k}}}p_{{{a}P}}", f"p_{a}P (in frame {steps.frame})", step.lever))
            tex = rf"\begin{{bmatrix}}z_{{{a}}} \times p_{{{a}P}}\\z_{{{a}}}\end{{bmatrix}}"
            text = f"[z_{a} \N{MULTIPLICATION SIGN} p_{a}P; z_{a}]"
        equations.append(Equation(f"{{}}^{{{k}}}J_{{{i}}} = {tex}", f"J_{i} = {text} (in frame {steps.frame})",
                                  step.column))
    return equations


def _differentiation_equations(steps: DifferentiationSteps) -> list[Equation]:
    equations = [Equation("{}^{0}p_{P}", "p_P (in frame 0)", steps.position)]
    for step in steps.columns:
        a, i, q = step.axis_frame, step.joint, step.variable
        partial = rf"\frac{{\partial\,{{}}^{{0}}p_{{P}}}}{{\partial {sp.latex(q)}}}"
        equations.append(Equation(rf"{{}}^{{0}}J_{{v,{i}}} = {partial}", f"Jv_{i} = ∂p_P/∂{q} (in frame 0)",
                                  step.linear))
        tex, text = (f"{{}}^{{0}}z_{{{a}}}", f"z_{a}") if step.revolute else ("0", "0")
        equations.append(Equation(rf"{{}}^{{0}}J_{{\omega,{i}}} = {tex}", f"Jω_{i} = {text} (in frame 0)",
                                  step.angular))
    if steps.rotation is not None:
        equations.append(Equation(f"{{}}^{{{_frame(steps.frame)}}}_{{0}}R", f"R_{steps.frame}_0", steps.rotation))
    return equations


def step_equations(propagation: Steps, values: Mapping[Any, Any] | None = None) -> list[Equation]:
    """Every step of a propagation or column method as an :class:`Equation`, in order (``values`` substituted)."""
    substitution = dict(values or {})
    if isinstance(propagation, CrossProductSteps | DifferentiationSteps | NewtonEuler):
        equations = (_cross_product_equations(propagation) if isinstance(propagation, CrossProductSteps)
                     else _newton_euler_equations(propagation) if isinstance(propagation, NewtonEuler)
                     else _differentiation_equations(propagation))
        return [Equation(e.tex, e.text, e.rhs.xreplace(substitution)) for e in equations]
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
    propagation: Steps, style: Style = "latex", values: Mapping[Any, Any] | None = None
) -> list[str]:
    r"""Every step of a propagation or column method, one equation per string, ready for lecture notes.

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
