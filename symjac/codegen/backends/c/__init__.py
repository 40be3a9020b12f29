"""The ``"c"`` target: the NumPy module plus C kernels compiled at first import into a CPython extension.

The extension holds the bodies of the c99 target's functions, from the same template (``c_common/functions.c.j2``)
and printer, and a loop over the configurations of a batch around each: the angles of a block of 64 configurations
first, their sines and cosines through glibc's libmvec (four at a time, where the CPU has AVX2), then the bodies.
The extension is cached per user. Without a compiler, headers or a writable cache the module silently falls back to
its NumPy functions (``BACKEND`` says which runs).
"""

from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Mapping

from symjac.codegen.backends._c_family import C_DIALECT, CFunction, block_comment, c_function
from symjac.codegen.backends._python_family import kernel_name, python_module_renderer
from symjac.codegen.backends.c.printer import CPrinter
from symjac.codegen.backends.numpy import numpy_function
from symjac.codegen.backends.numpy.printer import NumPyPrinter
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, IdentifierRule, ModuleDescription
from symjac.codegen.ik_printing import c_inverse_kinematics
from symjac.errors import CodegenError
from symjac.resources import render_template

__all__ = ["BACKEND", "C_KEYWORDS", "IDENTIFIERS", "batch_call", "c_sources"]

KERNELS_TEMPLATE = "c/kernels.c.j2"

C_KEYWORDS = frozenset((
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum", "extern",
    "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return", "short", "signed",
    "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void", "volatile", "while",
))
_MATH = frozenset(("sin", "cos", "fabs", "sqrt", "pow"))
"""The functions of ``<math.h>`` the bodies may call: a temporary may not take their names."""

IDENTIFIERS: IdentifierRule = PYTHON_IDENTIFIERS | IdentifierRule.of("C", C_KEYWORDS)
"""A Python module with C kernels: names must be neither Python nor C keywords (nor Python builtins)."""


def batch_call(function: CFunction) -> str:
    """The body's call for configuration ``i`` of a batch, ``k`` of its block: inputs and output at row ``i``."""
    inputs = tuple(f"w[{k}] + i * {length}" for k, (_, length, _) in enumerate(function.inputs))
    n = len(function.angles)
    call = function.body_call("qs + i * DOF", "p", inputs, f"out + i * {function.size}", f"S + k * {n}",
                              f"C + k * {n}")
    return call if function.output else f"out[i] = {call.removeprefix('return ')}"


def c_sources(description: ModuleDescription, taken: frozenset[str]) -> Mapping[str, str]:
    """The C extension's source and module name (``_symjac_<module>_<hash of the source>``).

    The self-test's kinematics stay in NumPy; every other function gets its body (a C function of one
    configuration) and a batch loop around it. The C names are the extension's own (``taken``, the Python module's
    names, do not constrain them).
    """
    del taken
    dialect = dataclasses.replace(C_DIALECT, reserved=C_KEYWORDS | _MATH)
    functions = tuple(c_function(description, f, dialect) for f in description.functions if not f.selftest_only)
    data = {
        "ik_kernel": c_inverse_kinematics(description, "c", C_KEYWORDS | _MATH, CPrinter).text,
        "module": description,
        "functions": functions,
        "kernel_names": {f.name: kernel_name(f.base) for f in functions},
        "dof": description.n_coordinates,
        "block_comment": block_comment,
        "batch_call": batch_call,
    }
    # The name carries a hash of the source so that a changed module never loads a stale cached extension; it is
    # defined in the source's first line, so the source is rendered once and hashed without it.
    body = render_template(KERNELS_TEMPLATE, **data)
    module = f"_symjac_{description.robot}_{hashlib.sha256(body.encode()).hexdigest()[:16]}"
    source = f"#define SJ_EXTENSION {module}\n{body}"
    if '"""' in source or "\\" in source:
        raise CodegenError("internal error: the C source cannot be embedded in a Python raw string")
    return {"c_source": source, "c_module": module}


BACKEND = Backend(
    name="c",
    order=3,
    summary="compiled at first import, NumPy fallback",
    emits="one Python module embedding the C source of its extension",
    identifiers=IDENTIFIERS,
    files=("{robot}.py",),
    templates=("c/module.py.j2", "c/kernels.c.j2", "c_common/functions.c.j2", "numpy/module.py.j2",
               "python_common/macros.py.j2"),
    title="Kinematics and Jacobians in C, compiled at first import, with a NumPy fallback",
    description="The NumPy functions are the reference and the fallback; C kernels replace them when a C compiler and\n"
                "the Python headers are present (``BACKEND`` is \"c\" or \"numpy\", ``BUILD_ERROR`` says why not).\n"
                "The extension is cached in $SYMJAC_CACHE_DIR or ~/.cache/symjac.",
    nan_policy="Wrong shapes raise ValueError; NaN and infinite angles give NaN outputs (no warning from C).",
    # NumPy's angle lines
    render=python_module_renderer(numpy_function, extras=c_sources, sections=("sincos",),
                                  ik_printer=("numpy", NumPyPrinter)),
    dependencies=("numpy",),
    exports=("BACKEND",),
    runtime="numpy.py",
)
