"""The ``"c"`` target: the NumPy module plus C kernels compiled at first import into a CPython extension.

The extension is cached per user; sines and cosines are vectorised through glibc's libmvec where the CPU has AVX2.
Without a compiler, headers or a writable cache the module silently falls back to its NumPy functions
(``BACKEND`` says which runs).
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping

from symjac.codegen.backends._c_family import c_statements
from symjac.codegen.backends._python_family import GeneratedFunction, generated_function, python_module_renderer
from symjac.codegen.backends.c.printer import CPrinter
from symjac.codegen.backends.numpy import numpy_function
from symjac.codegen.coupled import coordinate_angles
from symjac.codegen.description import PYTHON_IDENTIFIERS, Backend, FunctionSpec, IdentifierRule, ModuleDescription
from symjac.codegen.lower import LoweredFunction, symbol_names
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain
from symjac.resources import render_template

__all__ = ["BACKEND", "C_KEYWORDS", "IDENTIFIERS", "c_function", "c_sources"]

KERNELS_TEMPLATE = "c/kernels.c.j2"

C_KEYWORDS = frozenset((
    "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum", "extern",
    "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return", "short", "signed",
    "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void", "volatile", "while",
))
_KERNEL_LOCALS = frozenset(("x", "w", "wk", "p", "o", "k", "q", "out", "S", "C", "m", "A"))  # never a temporary

IDENTIFIERS: IdentifierRule = PYTHON_IDENTIFIERS | IdentifierRule.of("C", C_KEYWORDS)
"""A Python module with C kernels: names must be neither Python nor C keywords (nor Python builtins)."""


def c_function(chain: Chain, lowered: LoweredFunction, spec: FunctionSpec, taken: frozenset[str]
               ) -> GeneratedFunction:
    """The per-configuration C body: sines ``S[j][k]``, cosines ``C[j][k]`` (vectorised before), outputs ``o[k]``."""
    robot = chain.robot
    indent = "        "
    names = symbol_names(robot, lowered, taken | C_KEYWORDS | _KERNEL_LOCALS)
    mapping = dict(names.mapping)
    for argument, symbols in lowered.inputs:
        pointer = "x" if argument == "q" else "wk"
        for k, symbol in enumerate(symbols):
            mapping[symbol] = f"{pointer}[{k}]"
    for parameter_index, symbol in enumerate(robot.parameter_symbols):
        mapping[symbol] = f"p[{parameter_index}]"
    angle_index = {a: k for k, a in enumerate(coordinate_angles(chain))}
    for sine, cosine, angle in lowered.angles:
        mapping[sine] = f"S[{angle_index[angle]}][k]"
        mapping[cosine] = f"C[{angle_index[angle]}][k]"
    printer = CPrinter(mapping)
    statements = c_statements(lowered, mapping, printer, indent, "double", lambda k: f"o[{k}]", precomputed=True)
    outputs = tuple(printer.doprint(e) for e in lowered.outputs)
    body, lines = list(statements.temporaries), list(statements.outputs)
    return generated_function(lowered, spec, body, outputs, lines, printer.used)


def c_sources(description: ModuleDescription, taken: frozenset[str]) -> Mapping[str, str]:
    """The C extension's source and module name (``_symjac_<module>_<hash of the source>``).

    The self-test's kinematics stay in NumPy; every other function gets a C kernel.
    """
    chain, functions, name = description.chain, description.functions, description.robot
    assert chain is not None  # the renderer checked it
    robot = chain.robot
    kernels = tuple(c_function(chain, f.lowered, f.spec, taken) for f in functions if f.kind != "kinematics")
    printer = CPrinter({**{v: f"x[{k}]" for k, v in enumerate(robot.q)},
                        **{s: f"p[{k}]" for k, s in enumerate(robot.parameter_symbols)}})
    angle_code = tuple(printer.doprint(angle) for angle in coordinate_angles(chain))
    data = {"robot": name, "dof": robot.n_coordinates, "angles": angle_code, "functions": kernels,
            "parameter_count": len(robot.parameters)}
    # The name carries a hash of the source so that a changed module never loads a stale cached extension.
    body = render_template(KERNELS_TEMPLATE, module="MODULE_NAME", **data)
    module = f"_symjac_{name}_{hashlib.sha256(body.encode()).hexdigest()[:16]}"
    source = render_template(KERNELS_TEMPLATE, module=module, **data)
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
    templates=("c/module.py.j2", "c/kernels.c.j2", "numpy/module.py.j2", "python_common/macros.py.j2"),
    title="Kinematics and Jacobians in C, compiled at first import, with a NumPy fallback",
    description="The NumPy functions are the reference and the fallback; C kernels replace them when a C compiler and\n"
                "the Python headers are present (``BACKEND`` is \"c\" or \"numpy\", ``BUILD_ERROR`` says why not).\n"
                "The extension is cached in $SYMJAC_CACHE_DIR or ~/.cache/symjac.",
    nan_policy="Wrong shapes raise ValueError; NaN and infinite angles give NaN outputs (no warning from C).",
    render=python_module_renderer(numpy_function, extras=c_sources),
    dependencies=("numpy",),
    exports=("BACKEND",),
)
