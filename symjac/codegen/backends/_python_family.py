"""What the Python-family targets share (python, numpy, lambdify, c): printed functions and the module view.

Each of those targets writes one Python module from a template in ``templates/<target>/`` that imports the shared
macros of ``templates/python_common/``. :func:`python_module_renderer` is their :attr:`Backend.render
<symjac.codegen.description.Backend.render>`: it prints every function with the target's emitter and lays the module
out. The registry skips this module (a leading underscore: not a target).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from symjac.codegen.description import Backend, FunctionDescription, FunctionKind, FunctionSpec, ModuleDescription
from symjac.codegen.ik_numeric import NumericIkTables, numeric_ik_tables
from symjac.codegen.ik_numeric_numpy import numpy_numeric_ik
from symjac.codegen.ik_numeric_traced import traced_numeric_ik
from symjac.codegen.ik_printing import IKText, PrinterClass, python_inverse_kinematics
from symjac.codegen.kinds import kind_spec
from symjac.codegen.lower import LoweredFunction
from symjac.codegen.names import RESERVED
from symjac.codegen.runtime import runtime_source
from symjac.codegen.source_layout import (
    LINE_WIDTH,
    check_layout,
    comment_lines,
    tuple_lines,
    tuple_literal,
    wrap_statement,
)
from symjac.resources import render_template

__all__ = [
    "Emitter",
    "Extras",
    "GeneratedFunction",
    "PythonModule",
    "generated_function",
    "kernel_name",
    "python_module_renderer",
]


@dataclass(frozen=True)
class GeneratedFunction:
    """Everything a template needs to lay out one generated function, already printed for its target.

    ``body`` holds the statements (indented for the template), ``outputs`` the printed value of every entry in
    row-major order of ``shape`` (constant entries included), ``op_count`` the arithmetic operations per
    configuration after CSE (``sympy.count_ops``) and ``trig_count`` the sine and cosine evaluations.
    """

    name: str
    kind: FunctionKind
    summary: str
    arguments: tuple[Any, ...]
    shape: tuple[int, ...]
    op_count: int
    trig_count: int
    origin: str
    body: tuple[str, ...]
    outputs: tuple[str, ...]
    output_lines: tuple[str, ...] = ()
    constant: tuple[bool, ...] = ()
    uses: tuple[str, ...] = ()
    returns: str = ""
    selftest_only: bool = False

    @property
    def kernel_name(self) -> str:
        """Name of the block kernel (NumPy) or C function that evaluates it."""
        return kernel_name(self.name)

    @property
    def shape_literal(self) -> str:
        """The output shape as Python source: ``(6, 7)``."""
        return tuple_literal(str(extent) for extent in self.shape) if self.shape else "()"

    @property
    def inputs_literal(self) -> str:
        """``((q, 6, "q"), (wrench, 6, "wrench"))``: each array argument, its length and its name."""
        return tuple_literal(f'({a.name}, {len(a.entries)}, "{a.name}")' for a in self.arguments)

    def call_lines(self, head: str, first: str) -> list[str]:
        """``head(first, inputs, shape, out, parameters)`` laid out within the line width (one line if it fits)."""
        arguments = f"{first}, {self.inputs_literal}, {self.shape_literal}, out, parameters"
        line = f"{head}({arguments})"
        if len(line) <= LINE_WIDTH:
            return [line]
        indent = " " * (len(head) - len(head.lstrip()))
        return [f"{head}(", *wrap_statement(f"{indent}    ", arguments, ",", language="c"), f"{indent})"]

    @property
    def lengths_literal(self) -> str:
        """The lengths of the array arguments as Python source: ``(6, 6)``."""
        return tuple_literal(str(len(a.entries)) for a in self.arguments)

    @property
    def size(self) -> int:
        """Number of output entries."""
        size = 1
        for extent in self.shape:
            size *= extent
        return size


def kernel_name(function: str) -> str:
    """The name of the kernel that evaluates ``function`` on a batch: ``_jacobian_kernel``.

    The numpy module defines it in Python; the c module's extension exports a C function of that name.
    """
    return f"_{function.lstrip('_')}_kernel"


def generated_function(lowered: LoweredFunction, spec: FunctionSpec, body: Sequence[str], outputs: Sequence[str],
                       output_lines: Sequence[str], uses: Iterable[str]) -> GeneratedFunction:
    """Bundle a backend's printed statements with the facts of ``lowered`` (shape, counts, constant entries)."""
    constant = tuple(not e.free_symbols for e in lowered.outputs)
    used = set(uses) | ({"sin", "cos"} if lowered.angles else set())
    return GeneratedFunction(
        name=spec.name, kind=spec.kind, summary=spec.summary, arguments=spec.arguments, shape=lowered.shape,
        op_count=lowered.op_count, trig_count=lowered.trig_count, origin=lowered.origin, body=tuple(body),
        outputs=tuple(outputs), output_lines=tuple(output_lines), constant=constant, uses=tuple(sorted(used)),
        returns=spec.returns, selftest_only=kind_spec(spec.kind).selftest_only,
    )


Emitter = Callable[[ModuleDescription, FunctionDescription, frozenset[str]], GeneratedFunction]
"""Print one function of a module for a target: ``emit(description, function, taken_names)``."""

Extras = Callable[[ModuleDescription, frozenset[str]], Mapping[str, str]]
"""Module-level text a target needs besides its functions (the C target's kernel source and extension name)."""




@dataclass(frozen=True)
class PythonModule:
    """A :class:`ModuleDescription` as its Python-family template sees it: printed functions and source lines.

    Every attribute the description has is available too (``module.robot``, ``module.jacobians``).
    """

    description: ModuleDescription
    template: str
    title: str
    description_text: str
    nan_policy: str
    functions: tuple[GeneratedFunction, ...]
    imports: tuple[str, ...]
    extras: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    runtime: str = ""  # the runtime's text, copied into the module at its end
    ik_text: str = ""  # the closed-form inverse kinematics (symjac.codegen.ik_printing), or nothing

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.description, name)

    @property
    def numeric_ik(self) -> NumericIkTables | None:
        """The numeric inverse kinematics' tables when the module has it (``ModuleRequest(numeric_ik=True)``)."""
        return numeric_ik_tables(self.description, prefixed=False)

    @property
    def command_lines(self) -> tuple[str, ...]:
        """The regenerating command as header comment lines (a shell line continues with a backslash)."""
        return comment_lines(self.description.command, continuation=" \\" if self.description.shell_command else "")

    @property
    def command_note_lines(self) -> tuple[str, ...]:
        """``command_note`` in parentheses, broken into header comment lines (none without a note)."""
        note = self.description.command_note
        return comment_lines(f"({note})") if note else ()

    @property
    def rate_names_lines(self) -> tuple[str, ...]:
        """``_RATE_NAMES = ("thetadot1", "ddot2")``: the joint rate names as Python source lines."""
        return tuple(tuple_lines("_RATE_NAMES = ", (f'"{name}"' for name in self.description.rates)))

    @property
    def parameter_tuple_lines(self) -> tuple[str, ...]:
        """``PARAMETER_NAMES = ("a2", "d4")`` and ``PARAMETER_DEFAULTS = (0.4, 0.1)`` as source lines (CasADi)."""
        names = tuple_lines("PARAMETER_NAMES = ", (f'"{name}"' for name in self.description.parameter_names))
        defaults = tuple_lines("PARAMETER_DEFAULTS = ", (repr(value) for _, value in self.description.parameters))
        return (*names, *defaults)

    @property
    def acceleration_names_lines(self) -> tuple[str, ...]:
        """``_ACCELERATION_NAMES = ("thetaddot1", "dddot2")``: the names of the entries of qddot as source lines."""
        return tuple(tuple_lines("_ACCELERATION_NAMES = ",
                                 (f'"{name}"' for name in self.description.accelerations)))

    @property
    def check_lines(self) -> tuple[str, ...]:
        """The self-test's checks as the entries of a tuple: ``("jacobian", (jacobian, ...), (0, 1)),`` each.

        ``module.checks`` laid out for the runtime's ``_selftest_error``: routine, functions, rows; one line per check
        if it fits, else one line per part.
        """
        lines: list[str] = []
        for check in self.description.checks:
            parts = [f'"{check.routine}"', tuple_literal(check.functions),
                     tuple_literal(str(row) for row in check.rows) if check.rows else "()"]
            single = f"    ({', '.join(parts)}),"
            if len(single) <= LINE_WIDTH:
                lines.append(single)
                continue
            lines += ["    (", f"        {parts[0]},"]
            for items in (check.functions, tuple(str(row) for row in check.rows)):
                part = tuple_lines("        ", items) if items else ["        ()"]
                lines += [*part[:-1], part[-1] + ","]
            lines.append("    ),")
        return tuple(lines)

    @property
    def coordinates_lines(self) -> tuple[str, ...]:
        """``COORDINATES = ("theta1", "theta2")`` as Python source lines, then ``JOINTS``, its older name."""
        names = tuple_lines("COORDINATES = ", (f'"{name}"' for name in self.description.coordinate_names))
        return (*names, "JOINTS = COORDINATES  # the older name of the same tuple")

    @property
    def joint_lines(self) -> tuple[str, ...]:
        """``JOINT_NAMES``, ``JOINT_TYPES``, ``LOWER``, ``UPPER`` and ``TIP_FRAME`` as Python source lines."""
        entries = self.description.joint_entries
        lines = [*tuple_lines("JOINT_NAMES = ", (f'"{entry.name}"' for entry in entries)),
                 *tuple_lines("JOINT_TYPES = ", (f'"{entry.type}"' for entry in entries)),
                 *tuple_lines("LOWER = ", (_bound(entry.lower) for entry in entries)),
                 *tuple_lines("UPPER = ", (_bound(entry.upper) for entry in entries)),
                 f'TIP_FRAME = "{self.description.tip_frame}"']
        for constant, names in self.description.name_lists:  # the regressors' columns, in order
            lines += tuple_lines(f"{constant} = ", (f'"{name}"' for name in names))
        return tuple(lines)

    @property
    def revolute_lines(self) -> tuple[str, ...]:
        """``_REVOLUTE = (True, False)`` as Python source lines."""
        return tuple(tuple_lines("_REVOLUTE = ", (str(flag) for flag in self.description.revolute)))

    @property
    def parameter_lines(self) -> tuple[str, ...]:
        """``parameters = (a2, d4)``: the keyword parameters gathered into one tuple, within the line width."""
        names = self.description.parameter_names
        return tuple(wrap_statement("    parameters = ", "(" + ", ".join(names) + ("," if len(names) == 1 else "")
                                    + ")"))


def _bound(value: float) -> str:
    """A position limit as Python source: ``-6.283185307179586``, ``float("inf")`` when there is none."""
    return repr(value) if math.isfinite(value) else f'float("{value}")'


def _inverse_kinematics(description: ModuleDescription, target: str, taken: frozenset[str],
                        ik_printer: tuple[str, PrinterClass] | None) -> Any:
    """The module's closed-form inverse kinematics printed for ``target``'s family, or empty text.

    The c and lambdify targets carry the NumPy version (batched over poses, as their other functions); the c
    target's calls its extension's compiled closed form first.
    """
    if ik_printer is None:
        return IKText("")
    family, printer = ik_printer
    closed = python_inverse_kinematics(description, family, taken, printer, c_kernel=target == "c")
    numeric = numpy_numeric_ik(description) or traced_numeric_ik(description)  # the numeric solver, if it has one
    return IKText("\n\n\n".join(t for t in (closed.text.strip("\n"), numeric) if t), closed.uses, closed.header)


def python_module_renderer(emit: Emitter, extras: Extras | None = None, imports: Iterable[str] = (),
                           sections: Iterable[str] = (), ik_printer: tuple[str, PrinterClass] | None = None,
                           ) -> Callable[[ModuleDescription, Backend], Mapping[str, str]]:
    """The ``render`` of a Python-family backend: print each function with ``emit``, fill ``backend.template``.

    ``extras`` builds module-level text from every function (templates read ``module.extras.<key>``); ``imports``
    are names the module imports whatever its expressions use (the python target's ``pi`` and ``sqrt``);
    ``sections`` are runtime sections the emitted functions call (the numpy emitter's ``sincos``), carried besides
    those the description uses (:attr:`~symjac.codegen.description.ModuleDescription.runtime_sections`);
    ``ik_printer`` is the family (python, numpy, jax or casadi) and printer the closed-form inverse kinematics is
    printed with, ``None`` for a target without it.
    """
    always = tuple(imports)
    own = frozenset(sections)

    def render(description: ModuleDescription, backend: Backend) -> Mapping[str, str]:
        taken = frozenset(RESERVED) | set(description.parameter_names)
        functions = tuple(emit(description, f, taken) for f in description.functions)
        ik = _inverse_kinematics(description, backend.name, taken, ik_printer)
        module = PythonModule(
            description=description, template=backend.template, title=backend.title,
            description_text=backend.description, nan_policy=backend.nan_policy, functions=functions,
            imports=tuple(sorted(set().union(*(f.uses for f in functions)) | set(always) | set(ik.uses)
                                 | ({"acos", "sin"} if description.numeric_ik else set()))),
            ik_text=ik.text,
            extras=MappingProxyType(dict(extras(description, taken))) if extras else
            MappingProxyType({}),
            runtime=runtime_source(backend.runtime, description.runtime_sections | own) if backend.runtime else "",
        )
        name = backend.files[0].format(robot=description.robot)
        return check_layout({name: render_template(backend.template, module=module)})

    return render
