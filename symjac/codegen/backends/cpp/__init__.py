"""The ``"cpp"`` target: one header-only C++17 file on Eigen 3.4, templated on the scalar type.

Everything sits in ``namespace symjac::<robot>``: ``template <class Scalar> Eigen::Matrix<Scalar, 6, N>
jacobian(const Eigen::Matrix<Scalar, N, 1>& q, const Params<Scalar>& p = Params<Scalar>{})`` and likewise
``forward_kinematics`` (4 x 4), ``joint_torques(q, F, p)``, ``manipulability``, ``jacobian_determinant`` and, with
the acceleration level, ``hessian`` (``std::array`` of ``N`` slices ``dJ/dq_m``), ``bias_acceleration(q, qdot, p)``
and ``manipulability_gradient``. ``Params`` is a struct holding the robot file's defaults. Fixed sizes, no heap:
the same code runs with ``double``, ``float``, ``Eigen::AutoDiffScalar`` or another solver's jets. The statements
are those of the c99 target (:mod:`symjac.codegen.backends._c_family`), with C++ casts and indices.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from symjac.codegen.backends._c_family import Dialect, c_function, header_comments, line_comment
from symjac.codegen.backends.c99 import C99_KEYWORDS, LIBRARY_NAMES
from symjac.codegen.backends.cpp.printer import CppPrinter
from symjac.codegen.description import Backend, IdentifierRule, ModuleDescription
from symjac.codegen.ik_numeric import numeric_ik_tables
from symjac.codegen.ik_printing import c_inverse_kinematics
from symjac.codegen.printers import float_literal
from symjac.codegen.runtime import runtime_source
from symjac.codegen.source_layout import check_layout
from symjac.resources import render_template

__all__ = ["BACKEND", "CPP_KEYWORDS", "IDENTIFIERS", "cpp_type", "joint_arrays", "render"]

CPP_KEYWORDS = C99_KEYWORDS | {
    "alignas", "alignof", "and", "and_eq", "asm", "bitand", "bitor", "bool", "catch", "char16_t", "char32_t",
    "class", "compl", "concept", "const_cast", "constexpr", "decltype", "delete", "dynamic_cast", "explicit",
    "export", "false", "friend", "mutable", "namespace", "new", "noexcept", "not", "not_eq", "nullptr", "operator",
    "or", "or_eq", "private", "protected", "public", "reinterpret_cast", "requires", "static_assert", "static_cast",
    "template", "this", "thread_local", "throw", "true", "try", "typeid", "typename", "using", "virtual", "wchar_t",
    "xor", "xor_eq", "co_await", "co_return", "co_yield", "char8_t", "consteval", "constinit",
}

GENERATED_NAMES = frozenset(("Scalar", "Params", "Eigen", "std", "symjac", "real", "detail", "n_coordinates"))
"""Names the generated header declares or uses itself: a robot or parameter may not take one."""

IDENTIFIERS = IdentifierRule.of("C++", CPP_KEYWORDS, LIBRARY_NAMES | GENERATED_NAMES)
"""C++17's rule: no keyword, no standard-library name the header uses, nothing the header declares itself."""


def _element(output: str, shape: tuple[int, ...], k: int) -> str:
    """Entry ``k`` (row-major) of an output: ``J(i, j)``, ``tau(i)``, and ``H[m](i, j)`` for a Hessian slice."""
    if len(shape) == 3:
        columns, slices = shape[1], shape[2]
        i, rest = divmod(k, columns * slices)
        j, m = divmod(rest, slices)
        return f"{output}[{m}]({i}, {j})"
    if len(shape) == 2:
        i, j = divmod(k, shape[1])
        return f"{output}({i}, {j})"
    return f"{output}({k})"


def cpp_type(shape: tuple[int, ...]) -> str:
    """The C++ type of an output of ``shape``: ``Scalar``, an Eigen vector or matrix, or an array of matrices."""
    if not shape:
        return "Scalar"
    if len(shape) == 1:
        return f"Eigen::Matrix<Scalar, {shape[0]}, 1>"
    matrix = f"Eigen::Matrix<Scalar, {shape[0]}, {shape[1]}>"
    return matrix if len(shape) == 2 else f"std::array<{matrix}, {shape[2]}>"


DIALECT = Dialect(CPP_KEYWORDS | LIBRARY_NAMES | GENERATED_NAMES, CppPrinter, lambda _, name: f"p.{name}", _element)
"""C++: parameters as members of ``Params``, outputs as Eigen matrices (Hessians as arrays of slices)."""


def joint_arrays(description: ModuleDescription) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The header's joint tables: (declaration head, printed entries) for names, types, lower and upper limits."""
    entries, n = description.joint_entries, description.n_coordinates
    infinity = "std::numeric_limits<double>::infinity()"

    def bound(value: float) -> str:
        return float_literal(value) if math.isfinite(value) else (infinity if value > 0 else f"-{infinity}")

    return ((f"inline constexpr std::array<const char*, {n}> joint_names", tuple(f'"{e.name}"' for e in entries)),
            (f"inline constexpr std::array<const char*, {n}> joint_types", tuple(f'"{e.type}"' for e in entries)),
            (f"inline constexpr std::array<double, {n}> lower", tuple(bound(e.lower) for e in entries)),
            (f"inline constexpr std::array<double, {n}> upper", tuple(bound(e.upper) for e in entries)))


def render(description: ModuleDescription, backend: Backend) -> Mapping[str, str]:
    """The header: ``{"<robot>.hpp": ...}``."""
    functions = tuple(c_function(description, f, DIALECT) for f in description.functions if not f.name.startswith("_"))
    data = {
        "ik": c_inverse_kinematics(description, "cpp", DIALECT.reserved, CppPrinter).text,
        "module": description,
        "functions": functions,
        "namespace": description.robot,
        "defaults": tuple(float_literal(value) for _, value in description.parameters),
        "line_comment": line_comment,
        "cpp_type": cpp_type,
        "joint_arrays": joint_arrays(description),
        "numeric_ik": numeric_ik_tables(description, prefixed=False),
        "runtime": runtime_source(backend.runtime, description.runtime_sections).rstrip("\n"),
        **header_comments(description),
    }
    name = backend.files[0].format(robot=description.robot)
    return check_layout({name: render_template("cpp/header.hpp.j2", **data)})


BACKEND = Backend(
    name="cpp",
    order=5,
    summary="header-only C++17 on Eigen, any scalar type",
    emits="one header-only C++17 file on Eigen 3.4",
    identifiers=IDENTIFIERS,
    files=("{robot}.hpp",),
    templates=("cpp/header.hpp.j2", "cpp/ik_numeric.hpp.j2"),
    title="Kinematics and Jacobians as a header-only C++17 library on Eigen",
    description="Templated on the scalar type; fixed sizes, no heap.",
    nan_policy="NaN and infinite inputs give NaN outputs; nothing is checked at run time.",
    render=render,
    batched=False,
    language="C++",
    runtime="eigen.hpp",
)
