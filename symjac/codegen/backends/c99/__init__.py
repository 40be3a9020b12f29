"""The ``"c99"`` target: a standalone ``<robot>.h`` and ``<robot>.c`` in C99, for controllers and firmware.

No Python, no allocation, no global state: every function takes the coordinates ``q``, a parameter vector ``params``
(``NULL`` for the defaults) and the caller's output buffer, row-major. The real type is ``double`` unless the
including code defines ``<ROBOT>_REAL`` (``-DPUMA560_REAL=float`` for a single-precision controller); literals are
cast to it and ``<tgmath.h>`` picks ``sinf`` or ``sin`` accordingly. ``<robot>_selftest()`` checks every function
against central differences in C. The functions are those the c target compiles into its extension: one template
(``c_common/functions.c.j2``) and one printer (:class:`~symjac.codegen.backends.c.printer.RealPrinter`) for both;
each public function computes the sines and cosines of the angles it uses and passes them to its body.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

from symjac.codegen.backends._c_family import (
    C_DIALECT,
    block_comment,
    c_function,
    call_statement,
    comment,
    declaration,
    header_comments,
)
from symjac.codegen.backends.c import C_KEYWORDS
from symjac.codegen.backends.c.printer import RealPrinter
from symjac.codegen.description import Backend, IdentifierRule, ModuleDescription
from symjac.codegen.ik_numeric import numeric_ik_tables
from symjac.codegen.ik_printing import c_inverse_kinematics
from symjac.codegen.printers import float_literal
from symjac.codegen.runtime import runtime_source
from symjac.codegen.source_layout import check_layout
from symjac.resources import render_template

__all__ = ["BACKEND", "C99_KEYWORDS", "IDENTIFIERS", "LIBRARY_NAMES", "joint_arrays", "render"]

C99_KEYWORDS = C_KEYWORDS | {"_Bool", "_Complex", "_Imaginary"}

LIBRARY_NAMES = frozenset((
    # <math.h> and <tgmath.h> (type-generic macros: a robot or parameter named so would be expanded), <stddef.h>
    "acos", "asin", "atan", "atan2", "cbrt", "ceil", "copysign", "cos", "cosh", "erf", "exp", "exp2", "fabs", "floor",
    "fma", "fmax", "fmin", "fmod", "hypot", "isfinite", "isinf", "isnan", "log", "log10", "log2", "lround", "pow",
    "remainder", "round", "sin", "sinh", "sqrt", "tan", "tanh", "trunc", "HUGE_VAL", "INFINITY", "NAN", "M_PI",
    "M_E", "NULL", "offsetof", "size_t", "ptrdiff_t", "errno", "main", "complex", "imaginary", "bool", "true",
    "false",
))

GENERATED_NAMES = frozenset(("sj", "real", "kinematics", "selftest"))
"""Names the generated files use themselves (the ``sj_`` helpers, ``<robot>_real``, ``<robot>_kinematics``)."""

IDENTIFIERS = IdentifierRule.of("C", C99_KEYWORDS, LIBRARY_NAMES | GENERATED_NAMES, prefixes=("sj_",))
"""C99's rule: no keyword, no name of the standard library a generated file includes (``NULL``, ``sin``), none of
the names the generated files use themselves, and no name starting with ``sj_`` (their helpers and function bodies:
a robot ``sj_body`` would name its Jacobian like the Jacobian's body)."""

def joint_arrays(description: ModuleDescription) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The source file's joint tables: (declaration head, printed entries) for names, types, lower and upper limits."""
    prefix, entries = description.robot, description.joint_entries

    def bound(value: float) -> str:
        return float_literal(value) if math.isfinite(value) else ("INFINITY" if value > 0 else "-INFINITY")

    return ((f"const char *const {prefix}_joint_names", tuple(f'"{e.name}"' for e in entries)),
            (f"const char *const {prefix}_joint_types", tuple(f'"{e.type}"' for e in entries)),
            (f"const real {prefix}_lower", tuple(bound(e.lower) for e in entries)),
            (f"const real {prefix}_upper", tuple(bound(e.upper) for e in entries)))


def render(description: ModuleDescription, backend: Backend) -> Mapping[str, str]:
    """The header and the source file: ``{"<robot>.h": ..., "<robot>.c": ...}``."""
    dialect = dataclasses.replace(C_DIALECT, reserved=C99_KEYWORDS | LIBRARY_NAMES | GENERATED_NAMES)
    functions = tuple(c_function(description, f, dialect) for f in description.functions)
    ik = c_inverse_kinematics(description, "c99", dialect.reserved, RealPrinter)
    data = {
        "ik_header": ik.header,
        "ik_source": ik.text,
        "module": description,
        "functions": functions,
        "prefix": description.robot,
        "macro": description.robot.upper(),
        "defaults": tuple(float_literal(value) for _, value in description.parameters),
        "dimension": max([6, description.n_coordinates]),
        "declaration": declaration,
        "wrap_call": call_statement,
        "comment": comment,
        "size": math.prod,
        "c_names": lambda names: [f"{description.robot}{'' if name.startswith('_') else '_'}{name}" for name in names],
        "runtime": runtime_source(backend.runtime, description.runtime_sections).rstrip("\n"),
        "block_comment": block_comment,
        "joint_arrays": joint_arrays(description),
        "numeric_ik": numeric_ik_tables(description),
        **header_comments(description),
    }
    header, source = (name.format(robot=description.robot) for name in backend.files)
    return check_layout({header: render_template("c99/header.h.j2", **data),
                         source: render_template("c99/source.c.j2", **data)})


BACKEND = Backend(
    name="c99",
    order=4,
    summary="standalone C99 header and source",
    emits="a C99 header and source file (<math.h> only, no allocation)",
    identifiers=IDENTIFIERS,
    files=("{robot}.h", "{robot}.c"),
    templates=("c99/header.h.j2", "c99/source.c.j2", "c_common/functions.c.j2", "c99/ik_numeric.h.j2",
               "c99/ik_numeric.c.j2"),
    title="Kinematics and Jacobians in standalone C99",
    description="Row-major outputs in the caller's buffers; params == NULL means the defaults.",
    nan_policy="NaN and infinite inputs give NaN outputs; nothing is checked at run time.",
    render=render,
    dependencies=(),
    batched=False,
    language="C",
    runtime="c99.h",
)
