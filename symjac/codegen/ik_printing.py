"""The closed-form ``inverse_kinematics`` of a generated module, printed for each target family.

:mod:`symjac.codegen.inverse_kinematics` lowers the closed form to one straight line (conditions, then every branch's
joint values); here each family's printer writes that line and the templates ``templates/ik/`` lay the function out
around it: the selection of valid branches, the wrapping of angles and the fixed-size result. One printer per target
gains ``atan2``, ``max`` and the inverse trigonometric functions the closed form uses (:func:`ik_printer`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp
from sympy.printing.precedence import PRECEDENCE

from symjac.codegen.backends._c_family import c_statements, comment
from symjac.codegen.description import ModuleDescription
from symjac.codegen.inverse_kinematics import IK_NOISE, IK_TOLERANCE, Q_FREE, InverseKinematics
from symjac.codegen.lower import SymbolNames, symbol_names
from symjac.codegen.printers import float_literal
from symjac.codegen.source_layout import entry_names, temporary_lines, tuple_lines, wrap_statement
from symjac.resources import render_template

__all__ = ["IKText", "PrinterClass", "c_inverse_kinematics", "ik_printer", "python_inverse_kinematics"]

PrinterClass = Any
"""A target's printer class: a SymPy code printer with :class:`~symjac.codegen.printers.SymbolPrinting` mixed in."""

_FUNCTIONS: Mapping[str, Mapping[str, str]] = {
    "python": {"atan2": "atan2", "atan": "atan", "asin": "asin", "acos": "acos", "Abs": "abs"},
    "numpy": {"atan2": "np.arctan2", "atan": "np.arctan", "asin": "np.arcsin",
              "acos": "np.arccos", "Abs": "np.abs"},
    "jax": {"atan2": "jnp.arctan2", "atan": "jnp.arctan", "asin": "jnp.arcsin",
            "acos": "jnp.arccos", "Abs": "jnp.abs"},
    "casadi": {"atan2": "ca.atan2", "atan": "ca.atan", "asin": "ca.asin", "acos": "ca.acos",
               "Abs": "ca.fabs"},
    "c": {"atan2": "atan2", "atan": "atan", "asin": "asin", "acos": "acos", "Abs": "fabs"},
}
"""What each family calls the functions of a closed form (the python family imports the bare names from math)."""

_IMPORTED = frozenset(("atan2", "atan", "asin", "acos"))
"""Names the python target imports from ``math`` when its inverse kinematics calls them."""


def ik_printer(base: PrinterClass, family: str) -> PrinterClass:
    """``base`` (a target's printer class) with the closed form's functions as ``family`` writes them."""
    names = _FUNCTIONS[family]

    class IKPrinter(base):  # type: ignore[valid-type,misc]
        def _call(self, kind: str, args: tuple[sp.Basic, ...]) -> str:
            name = names[kind]
            if name in _IMPORTED:
                self.used.add(name)
            return f"{name}({', '.join(self._print(a) for a in args)})"

        def _print_atan2(self, expr: sp.Expr) -> str:
            return self._call("atan2", expr.args)

        def _print_atan(self, expr: sp.Expr) -> str:
            return self._call("atan", expr.args)

        def _print_asin(self, expr: sp.Expr) -> str:
            return self._call("asin", expr.args)

        def _print_acos(self, expr: sp.Expr) -> str:
            return self._call("acos", expr.args)

        def _print_Abs(self, expr: sp.Expr) -> str:
            return self._call("Abs", expr.args)

        def _print_IKInverse(self, expr: sp.Expr) -> str:
            r = self._print(expr.args[0])
            return self._where(f"{r} > {self._number(IK_NOISE)}", f"{self._number(1)}/{r}", self._number(0))

        def _print_IKClamp(self, expr: sp.Expr) -> str:
            value = self._print(expr.args[0])
            return self._where(f"{value} > {self._number(IK_NOISE)}", value, self._number(0))

        def _print_IKAtan2(self, expr: sp.Expr) -> str:
            r2 = self._print(expr.args[2])
            return self._where(f"{r2} > {self._number(IK_NOISE**2)}", self._call("atan2", (expr.args[0], expr.args[1])),
                               self._number(0))

        def _print_IKCosine(self, expr: sp.Expr) -> str:
            value, inverse = (self._print(a) for a in expr.args)
            return self._where(f"{inverse} > {self._number(0)}", f"{value}*{inverse}", self._number(1))

        def _where(self, test: str, value: str, otherwise: str) -> str:
            """``value`` where ``test`` holds, else ``otherwise``, as the family writes a choice."""
            if family == "python":
                return f"({value} if {test} else {otherwise})"
            if family in ("numpy", "jax"):
                return f"{'np' if family == 'numpy' else 'jnp'}.where({test}, {value}, {otherwise})"
            if family == "casadi":
                return f"ca.if_else({test}, {value}, {otherwise})"
            return f"({test} ? {value} : {otherwise})"

        def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
            base, exponent = expr.args
            if exponent.is_Integer and 4 <= abs(int(exponent)) <= 8:  # products: pow() costs more in C
                product = "*".join([self.parenthesize(base, PRECEDENCE["Mul"] + 1)] * abs(int(exponent)))
                return product if exponent > 0 else f"{self._number(1)}/({product})"
            return super()._print_Pow(expr, rational)

    IKPrinter.__name__ = IKPrinter.__qualname__ = f"IK{base.__name__}"
    return IKPrinter


@dataclass(frozen=True)
class IKText:
    """A module's inverse kinematics as printed text: ``text`` (what the template inserts), ``uses`` (imports)."""

    text: str
    uses: tuple[str, ...] = ()
    header: str = ""


def _names(description: ModuleDescription, ik: InverseKinematics, taken: frozenset[str]) -> SymbolNames:
    names = symbol_names(description.symbols, ik.lowered, taken)
    for _, symbols in ik.lowered.inputs:
        for symbol in symbols:
            names.fresh(symbol, symbol.name)
    for k, (symbol, _) in enumerate(ik.lowered.temporaries):
        names.fresh(symbol, f"x{k}")
    return names


def _facts(description: ModuleDescription, ik: InverseKinematics, names: SymbolNames) -> dict[str, Any]:
    free = "" if ik.free_joint is None else names.mapping[Q_FREE]
    return {"free": free, "free_joint": ik.free_joint,
            "free_variable": ik.free_variable, "module": description, "ik": ik,
            "tolerance": float_literal(IK_TOLERANCE),
            "branches": ik.branch_names, "n": ik.n, "m": ik.max_solutions,
            "conditions": ik.branch_conditions, "n_conditions": ik.n_conditions,
            "family": ik.family or "closed form", "op_count": ik.lowered.op_count}


_PYTHON_LOCALS = frozenset(("pose", "tolerance", "values", "poses", "rows", "batch", "count", "solutions", "np",
                            "math", "parameters", "out", "q", "branches", "branch", "valid", "order"))


def python_inverse_kinematics(description: ModuleDescription, family: str, taken: frozenset[str],
                              printer_base: PrinterClass, c_kernel: bool = False) -> IKText:
    """``inverse_kinematics`` and its helpers as module text for a Python ``family`` (python, numpy, jax, casadi).

    Empty text when the module has no inverse kinematics. With ``c_kernel`` (the c target) the NumPy function
    first calls the extension's compiled closed form when it loaded.
    """
    ik = description.inverse_kinematics
    if ik is None:
        return IKText("")
    names = _names(description, ik, taken | _PYTHON_LOCALS)
    printer = ik_printer(printer_base, family)(names.mapping)
    indent = "        " if family in ("python", "numpy") else "    "
    lowered = ik.lowered
    pose = lowered.inputs[0][1]
    entries = entry_names(lowered, names, pose)
    if family in ("python", "numpy"):
        source = "pose[{r}][:4]" if family == "python" else "rows[{r}]"
        unpack = [f"{indent}{', '.join(entries[4 * r:4 * r + 4])} = {source.format(r=r)}" for r in range(3)]
    else:
        unpack = [f"{indent}{names.mapping[s]} = pose[{k // 4}, {k % 4}]" for k, s in enumerate(pose)
                  if s in lowered.used_symbols]
    parameter_line = ""
    if family == "casadi" and description.parameter_symbols:
        parameters = entry_names(lowered, names, description.parameter_symbols)
        parameter_line = f"{indent}{', '.join(parameters)}{',' if len(parameters) == 1 else ''} = ca.vertsplit(p)"
    values = [printer.doprint(e) for e in lowered.outputs]
    data = {**_facts(description, ik, names), "unpack": unpack, "parameter_line": parameter_line, "c_kernel": c_kernel,
            "body": temporary_lines(lowered, names, printer, indent),
            "value_lines": tuple_lines(f"{indent}values = ", values),
            "branch_lines": tuple_lines("IK_BRANCHES = ", (f'"{name}"' for name in ik.branch_names)),
            "revolute_lines": tuple_lines("_IK_REVOLUTE = ", (str(r) for r in ik.revolute)),
            "condition_lines": tuple_lines("_IK_CONDITIONS = ", (
                "(" + "".join(f"{k}, " for k in ks).rstrip(" ") + ")" for ks in ik.branch_conditions))}
    text = render_template(f"ik/{family}.py.j2", **data)
    uses = {"atan2", "ceil", "isfinite", "pi"} | set(printer.used) if family == "python" else set()
    return IKText(text, tuple(sorted(uses)))


_C_LOCALS = frozenset(("pose", "tolerance", "v", "count", "q", "p", "params", "solutions", "real", "row", "value",
                       "lower", "upper", "i", "k", "branches", "branch", "same"))


def c_inverse_kinematics(description: ModuleDescription, target: str, reserved: frozenset[str],
                         printer_base: PrinterClass) -> IKText:
    """``inverse_kinematics`` in C: the c99 target's (source and header), the cpp target's, or the c extension's.

    The c target's is the function of one pose and the wrapper over a batch; nothing without inverse kinematics.
    """
    ik = description.inverse_kinematics
    if ik is None:
        return IKText("")
    names = _names(description, ik, reserved | _C_LOCALS)
    mapping = dict(names.mapping)
    lowered = ik.lowered
    pose = lowered.inputs[0][1]
    used = lowered.used_symbols
    reads = []
    for k, symbol in enumerate(pose):
        if symbol in used:
            place = f"pose({k // 4}, {k % 4})" if target == "cpp" else f"pose[{4 * (k // 4) + k % 4}]"
            reads.append(f"    const real {mapping[symbol]} = {place};")
    if ik.free_joint is not None and target == "c":  # the extension's kernel carries it in the pose's last row
        reads.append(f"    const real {mapping[Q_FREE]} = pose[12];")
    for k, symbol in enumerate(description.parameter_symbols):
        mapping[symbol] = f"p.{symbol.name}" if target == "cpp" else f"p[{k}]"
    printer = ik_printer(printer_base, "c")(mapping)
    statements = c_statements(lowered, mapping, printer, "    ", "real", lambda k: f"v[{k}]")
    selection = []
    for b, conditions in enumerate(ik.branch_conditions):
        start = ik.joint_output(b, 0)
        store = (f"count += detail::ik_store(&v[{start}], solutions, branches, count, {b}, tolerance);"
                 if target == "cpp" else f"count += sj_cf_store(v + {start}, q, branches, count, {b}, tolerance);")
        test = " && ".join(f"v[{k}] >= -tolerance" for k in conditions)
        selection += wrap_statement(f"    if ({test}) ", store, language="c") if test else [f"    {store}"]
    data = {**_facts(description, ik, names), "reads": reads,
            "body": (*statements.temporaries, *statements.outputs), "selection": selection,
            "size": len(lowered.outputs), "prefix": description.robot, "macro": description.robot.upper(),
            "revolute": ", ".join("1" if r else "0" for r in ik.revolute),
            "branch_literals": [f'"{comment(name)}"' for name in ik.branch_names],
            "summary": comment(f"Closed-form inverse kinematics ({ik.family or 'closed form'})")}
    if target == "c99":
        data |= {"lower": f"{description.robot}_lower", "upper": f"{description.robot}_upper"}
        return IKText(render_template("ik/c99_source.c.j2", **data), (),
                      render_template("ik/c99_header.h.j2", **data))
    if target == "c":
        def bound(value: float) -> str:
            return float_literal(value) if math.isfinite(value) else ("INFINITY" if value > 0 else "-INFINITY")

        data |= {"lower": "sj_cf_lower", "upper": "sj_cf_upper",
                 "lower_literals": [bound(e.lower) for e in description.joint_entries],
                 "upper_literals": [bound(e.upper) for e in description.joint_entries]}
        return IKText(render_template("ik/c_kernel.c.j2", **data))
    return IKText(render_template("ik/cpp.hpp.j2", **data))
