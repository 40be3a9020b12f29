r"""The printed formulas of the course notes, as data: where each one is, what it says, and what it should say.

The data file ``formulas.toml`` beside this module holds one ``[[formula]]`` table per printed matrix, vector or
equation that symjac can derive in the three course texts: the chapter "The Jacobian", the lecture slides "Jacobian:
implications and applications" and the notes "Jacobians: velocities and static forces" (each entry names its
section). Entries are transcribed in textbook shorthand, which the whitelisted expression parser reads (nothing in
the file is executed):

* ``s1``, ``c23``, ``s123``: the sine or cosine of a sum of joint angles of the formula's robot
  (:math:`\sin\theta_1`, :math:`\cos(\theta_2 + \theta_3)`);
* ``s_alpha``, ``c_beta``: the sine or cosine of a symbol the formula declares in ``symbols``;
* robot parameters (``d2``, ``L1``), joint variables (``theta1``, ``d3``), rates (``thetadot1``, ``ddot3``), wrench
  components (``f_x`` .. ``n_z``) and declared symbols by name.

Fields: ``id`` (unique), ``document`` (``"000"``, ``"002"`` or ``"003"``), ``where`` (section, slide or equation),
``what`` (one line), ``quantity`` and ``args`` (what symjac derives, see :mod:`symjac.teaching.errata.derive`),
``robot`` (a catalog name or an inline robot table), ``symbols`` (extra symbol names), ``printed`` (rows of entries as
printed), ``verdict`` (``"ok"``, ``"erratum"`` or ``"convention"``) and, for an erratum, ``corrected`` (the printed
matrix with the fix applied) and ``why`` (one line); for a convention note, ``convention`` (what differs).

A prose formula (``quantity = "relation"``, ``args = { check = NAME }``) has ``printed`` (and ``corrected``) as
LaTeX text instead of a matrix: the named check in :data:`symjac.teaching.errata.derive.RELATIONS` evaluates that form
on an example arm against the derivation.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from typing import Any

import sympy as sp

from symjac.kinematics.propagation import joint_rate_symbols, wrench_symbols
from symjac.model.expressions import parse_expression
from symjac.model.io import load_robot
from symjac.model.robot import Robot
from symjac.model.robot_file import robot_from_mapping

__all__ = ["DOCUMENTS", "VERDICTS", "Formula", "formula", "formulas", "shorthand_names"]

DOCUMENTS: Mapping[str, str] = {
    "000": "course chapter 'The Jacobian'",
    "002": "lecture slides 'Jacobian: implications and applications'",
    "003": "web notes 'Jacobians: velocities and static forces'",
}
VERDICTS = ("ok", "erratum", "convention")
_SOURCE = "symjac/teaching/errata/formulas.toml"
_SHORTHAND = re.compile(r"([sc])_?([0-9]+|[A-Za-z][A-Za-z0-9]*)")


@dataclass(frozen=True)
class Formula:
    """One printed formula of the notes, read from the data file (see the module docstring for the fields)."""

    id: str
    document: str
    where: str
    what: str
    quantity: str
    args: Mapping[str, Any]
    robot: Robot | None
    symbols: tuple[sp.Symbol, ...]
    printed: sp.ImmutableMatrix
    verdict: str
    corrected: sp.ImmutableMatrix | None = None
    why: str = ""
    convention: str = ""
    printed_text: str = ""
    corrected_text: str = ""
    names: Mapping[str, sp.Expr] = field(default_factory=dict, repr=False, compare=False)


def shorthand_names(robot: Robot | None, symbols: tuple[sp.Symbol, ...] = ()) -> dict[str, sp.Expr]:
    """Every name a transcription may use, mapped to its expression (``"c23"`` -> ``cos(theta2 + theta3)``)."""
    names: dict[str, sp.Expr] = {str(s): s for s in symbols}
    names.update({str(s): s for s in (*wrench_symbols(),)})
    if robot is not None:
        names.update({str(s): s for s in (*robot.q, *robot.parameter_symbols, *joint_rate_symbols(robot))})
        angles = {str(j.index): j.variable for j in robot.joints if j.is_revolute}
        for digits in _index_sums(robot.n_joints):
            if all(d in angles for d in digits):
                total = sum(angles[d] for d in digits)
                names[f"s{digits}"], names[f"c{digits}"] = sp.sin(total), sp.cos(total)
    for symbol in symbols:
        names[f"s_{symbol}"], names[f"c_{symbol}"] = sp.sin(symbol), sp.cos(symbol)
    return names


def _index_sums(n: int) -> list[str]:
    """'1', '2', '12', '23', '123', ...: runs of consecutive joint indices (joints 1..9)."""
    digits = "".join(str(i) for i in range(1, min(n, 9) + 1))
    return [digits[i:j] for i in range(len(digits)) for j in range(i + 1, len(digits) + 1)]


def _matrix(rows: Any, names: Mapping[str, sp.Expr], where: str) -> sp.ImmutableMatrix:
    if not isinstance(rows, list) or not rows or not all(isinstance(row, list) and row for row in rows):
        raise ValueError(f"{where}: a matrix is a non-empty list of rows")
    if len({len(row) for row in rows}) != 1:
        raise ValueError(f"{where}: rows of different lengths")
    try:
        return sp.ImmutableMatrix([[parse_expression(str(entry), names) for entry in row] for row in rows])
    except Exception as error:
        raise ValueError(f"{where}: {error}") from None


def _robot(spec: Any, where: str) -> Robot | None:
    if spec is None:
        return None
    if isinstance(spec, str):
        return load_robot(spec)
    return robot_from_mapping(spec, source=where)


def _formula(table: Mapping[str, Any], index: int) -> Formula:
    where = f"{_SOURCE}, formula {index + 1} ({table.get('id', '?')})"
    robot = _robot(table.get("robot"), where)
    symbols = tuple(sp.Symbol(name, real=True) for name in table.get("symbols", []))
    names = shorthand_names(robot, symbols)
    verdict = table.get("verdict", "ok")
    if verdict not in VERDICTS:
        raise ValueError(f"{where}: verdict must be one of {', '.join(VERDICTS)}, got {verdict!r}")
    if table.get("document") not in DOCUMENTS:
        raise ValueError(f"{where}: document must be one of {', '.join(DOCUMENTS)}")
    corrected = table.get("corrected")
    if (verdict == "erratum") != (corrected is not None and bool(table.get("why"))):
        raise ValueError(f"{where}: an erratum (and only an erratum) has 'corrected' and 'why'")
    relation = table["quantity"] == "relation"
    if relation and not (isinstance(table["printed"], str) and isinstance(corrected, str | None)):
        raise ValueError(f"{where}: a relation is printed (and corrected) as LaTeX text")
    return Formula(
        id=table["id"], document=table["document"], where=table["where"], what=table["what"],
        quantity=table["quantity"], args=dict(table.get("args", {})), robot=robot, symbols=symbols,
        printed=sp.ImmutableMatrix([[0]]) if relation else _matrix(table["printed"], names, where), verdict=verdict,
        corrected=None if corrected is None else (
            sp.ImmutableMatrix([[0]]) if relation else _matrix(corrected, names, where)),
        why=table.get("why", ""), convention=table.get("convention", ""),
        printed_text=table["printed"] if relation else "", corrected_text=corrected if relation and corrected else "",
        names=names)


@cache
def formulas() -> tuple[Formula, ...]:
    """Every transcribed formula, in the order of the data file."""
    text = resources.files("symjac.teaching.errata").joinpath("formulas.toml").read_text(encoding="utf-8")
    tables = tomllib.loads(text).get("formula", [])
    result = tuple(_formula(table, index) for index, table in enumerate(tables))
    ids = [f.id for f in result]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    if duplicates:
        raise ValueError(f"{_SOURCE}: repeated ids {', '.join(duplicates)}")
    return result


def formula(identifier: str) -> Formula:
    """The formula with this ``id``."""
    for entry in formulas():
        if entry.id == identifier:
            return entry
    raise KeyError(identifier)
