r"""The document of ``symjac dynamics --regressor / --base-parameters``: the dynamics linear in their parameters.

:math:`\tau = Y(q, \dot q, \ddot q)\,\pi = Y_b(q, \dot q, \ddot q)\,\pi_b`.

The regressor prints link by link, :math:`Y_i` the columns of link i's parameters (a 6 x 60 matrix fits no page);
its JSON form is the whole matrix under ``regressor`` with the columns' names, in order, under
``regressor_parameters``. The base parameters print as a table, one line per base parameter, ``name = expression``
(JSON ``base_parameters``: name -> expression, with ``base_parameters_latex``; the base regressor under
``base_regressor``, its columns under ``base_parameter_order``), then the standard parameters that do not act on
the torques.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import sympy as sp

from symjac.analysis.dynamics.gravity import dynamics_defaults
from symjac.model.robot import Robot
from symjac.printing.document import Block, Document, Equation, Inline, JsonKey
from symjac.printing.dynamics import gravity_words
from symjac.printing.latex import latex, rounded

if TYPE_CHECKING:
    from symjac.analysis.identification.base import BaseParameters
    from symjac.analysis.identification.regressor import Regressor

__all__ = ["identification_document"]


def _link_of(name: str) -> int:
    """The link (joint) number a standard parameter's name ends with: ``XX12`` -> 12."""
    digits = len(name) - len(name.rstrip("0123456789"))
    return int(name[-digits:])


def _symbols_tex(symbols: tuple[sp.Symbol, ...]) -> str:
    return ", ".join(latex(s) for s in symbols)


def identification_document(robot: Robot, regressor: Regressor, base: BaseParameters | None = None,
                            digits: int | None = None, show_regressor: bool = True) -> Document:
    r"""The regressor (link by link) and/or the base parameters of ``regressor`` (a table), one document.

    ``show_regressor``: print the regressor (else only the base parameters, which must be given). ``digits``:
    substitute the parameters' defaults and gravity's value, and round to that many significant digits.

    Examples
    --------
    >>> from symjac import load_robot
    >>> from symjac.analysis.identification import regressor
    >>> document = identification_document(load_robot("planar2r"), regressor(load_robot("planar2r")))
    >>> document.blocks[0].caption[0][:47]
    'Regressor of tau = Y(q, qdot, qddot) pi, link 1'
    >>> document.facts["regressor_parameters"][:3]
    ['XX1', 'XY1', 'XZ1']
    """
    values = dynamics_defaults(robot, regressor.gravity) if digits is not None else {}

    def shown(value: Any) -> Any:
        if digits is None:
            return value
        return rounded(sp.sympify(value).xreplace(values), digits)

    blocks: list[Block] = []
    extra: list[Equation] = []
    facts: dict[str, Any] = {"rates": [str(r) for r in robot.coordinate_rates],
                             "accelerations": [str(a) for a in robot.coordinate_accelerations],
                             "frame": "inertia about the origin of link frame {i}, axes of {i} (Khalil's names)"}
    facts["gravity"] = gravity_words(regressor.gravity)
    if show_regressor:
        Y = regressor.matrix
        facts["regressor_parameters"] = list(regressor.names)
        links = sorted({_link_of(name) for name in regressor.names})
        for link in links:
            columns = [c for c, name in enumerate(regressor.names) if _link_of(name) == link]
            part = sp.Matrix.hstack(*(Y[:, c] for c in columns))
            names = tuple(regressor.parameters[c] for c in columns)
            caption: tuple[str | sp.Basic | Inline, ...] = (
                f"Regressor of tau = Y(q, qdot, qddot) pi, link {link}: the columns of ",
                Inline(_symbols_tex(names), ", ".join(s.name for s in names)),
                f" ({gravity_words(regressor.gravity)})" if link == links[0] else "")
            blocks.append(Block(caption, (Equation(f"Y_{{{link}}}", f"Y_{link}", shown(part)),)))
        extra.append(Equation("Y", "Y", shown(Y), key=JsonKey("regressor", latex="regressor_latex")))
    if base is not None:
        facts["base_parameter_order"] = [s.name for s in base.symbols]
        facts["rank"] = base.rank
        facts["unidentifiable"] = [s.name for s in base.unidentifiable]
        for k, (symbol, expression) in enumerate(zip(base.symbols, base.expressions, strict=True)):
            caption = (f"Base parameters: {len(base.symbols)} identifiable combinations of the standard parameters "
                       f"(tau = Y_b pi_b)",) if k == 0 else ()
            blocks.append(Block(caption, (Equation(latex(symbol), symbol.name, shown(expression),
                                                   key=JsonKey("base_parameters", latex="base_parameters_latex",
                                                               item=symbol.name)),)))
        if base.unidentifiable:
            names = tuple(base.unidentifiable)
            blocks.append(Block(("Standard parameters that do not act on tau (not identifiable): ",
                                 Inline(_symbols_tex(names), ", ".join(s.name for s in names)))))
        extra.append(Equation("Y_b", "Y_b", shown(base.matrix), key=JsonKey("base_regressor")))
    title = "regressor form of the dynamics" if base is None else "base parameters"
    return Document(f"{robot.name}: {title}", robot.name, tuple(blocks), facts=facts, model=robot,
                    extra=tuple(extra))
