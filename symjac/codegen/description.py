"""The frozen data of code generation: a target's :class:`Backend` spec, and the module description it fills.

Templates only lay these out; every value is already printed and validated when it gets here.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Literal

from symjac.codegen.lower import LoweredFunction
from symjac.codegen.source_layout import LINE_WIDTH, comment_lines, tuple_lines, tuple_literal, wrap_statement
from symjac.kinematics.chain import Chain

__all__ = [
    "Argument",
    "Backend",
    "Emitter",
    "Extras",
    "FunctionKind",
    "FunctionSpec",
    "GeneratedFunction",
    "JacobianInfo",
    "ModuleDescription",
    "generated_function",
]

FunctionKind = Literal["forward_kinematics", "jacobian", "joint_torques", "scalar", "kinematics", "hessian",
                       "bias_acceleration"]


@dataclass(frozen=True)
class Argument:
    """An array argument of a generated function: its name and the names of its entries."""

    name: str
    entries: tuple[str, ...]
    description: str


@dataclass(frozen=True)
class FunctionSpec:
    """What one generated function is, before any target prints it: name, kind, docstring summary, arguments."""

    name: str
    kind: FunctionKind
    summary: str
    arguments: tuple[Argument, ...]


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
    arguments: tuple[Argument, ...]
    shape: tuple[int, ...]
    op_count: int
    trig_count: int
    origin: str
    body: tuple[str, ...]
    outputs: tuple[str, ...]
    output_lines: tuple[str, ...] = ()
    constant: tuple[bool, ...] = ()
    uses: tuple[str, ...] = ()

    @property
    def kernel_name(self) -> str:
        """Name of the block kernel (NumPy) or C function that evaluates it."""
        return f"_{self.name.lstrip('_')}_kernel"

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


def generated_function(lowered: LoweredFunction, spec: FunctionSpec, body: Sequence[str], outputs: Sequence[str],
                       output_lines: Sequence[str], uses: Iterable[str]) -> GeneratedFunction:
    """Bundle a backend's printed statements with the facts of ``lowered`` (shape, counts, constant entries)."""
    constant = tuple(not e.free_symbols for e in lowered.outputs)
    used = set(uses) | ({"sin", "cos"} if lowered.angles else set())
    return GeneratedFunction(
        name=spec.name, kind=spec.kind, summary=spec.summary, arguments=spec.arguments, shape=lowered.shape,
        op_count=lowered.op_count, trig_count=lowered.trig_count, origin=lowered.origin, body=tuple(body),
        outputs=tuple(outputs), output_lines=tuple(output_lines), constant=constant, uses=tuple(sorted(used)),
    )


Emitter = Callable[[Chain, LoweredFunction, FunctionSpec, frozenset[str]], GeneratedFunction]
"""Print one lowered function for a target: ``emit(chain, lowered, spec, taken_names)``."""

Extras = Callable[[Chain, Sequence[tuple[LoweredFunction, FunctionSpec]], frozenset[str]], Mapping[str, str]]
"""Module-level text a target needs besides its functions (the C target's kernel source and extension name)."""


@dataclass(frozen=True)
class Backend:
    """Everything that makes a target: one instance per module in :mod:`symjac.codegen.backends`.

    Parameters
    ----------
    name : str
        The target's name (``generate(robot, name)``, ``symjac codegen --target name``).
    order : int
        Position in listings (:data:`~symjac.codegen.TARGETS`, the CLI's choices).
    summary : str
        A few words for the CLI's help (``"standard library"``).
    template : str
        The jinja2 template in ``templates/`` that lays the module out.
    title, description, nan_policy : str
        The generated module docstring's first line, what its functions take and return, and what wrong shapes
        and NaN or infinite inputs do.
    emit : Emitter
        Prints one lowered function for the target.
    dependencies : tuple of str
        Third-party modules the generated module imports (none: standard library only).
    batched : bool
        Whether functions take ``q`` of shape ``(..., n)`` and return arrays (else one configuration per call as a
        sequence, results as nested tuples).
    suffix : str
        File suffix of the generated module.
    imports : tuple of str
        Names the module imports whatever its expressions use (the python target's ``pi`` and ``sqrt``).
    exports : tuple of str
        Module constants the target adds to ``__all__`` (the C target's ``BACKEND``).
    extras : Extras, optional
        Builds module-level text from every lowered function (templates read it as ``module.extras.<key>``).
    """

    name: str
    order: int
    summary: str
    template: str
    title: str
    description: str
    nan_policy: str
    emit: Emitter
    dependencies: tuple[str, ...] = ()
    batched: bool = True
    suffix: str = ".py"
    imports: tuple[str, ...] = ()
    exports: tuple[str, ...] = ()
    extras: Extras | None = None


@dataclass(frozen=True)
class JacobianInfo:
    """Names and meaning of the functions generated for one Jacobian request."""

    jacobian: str
    joint_torques: str
    manipulability: str
    determinant: str | None
    kinematics: str
    frame: str
    point: str
    point_values: tuple[str, str, str]
    rows: tuple[int, ...]
    row_names: tuple[str, ...]
    wrench_names: tuple[str, ...]
    hessian: str | None = None
    bias_acceleration: str | None = None
    manipulability_gradient: str | None = None


@dataclass(frozen=True)
class ModuleDescription:
    """The whole generated module as data: what :func:`symjac.codegen.render_module` renders.

    ``command`` is how to regenerate the module (the command line typed, or the equivalent Python call),
    ``command_lines`` the same broken into header comment lines and ``command_note`` what else the reader needs to
    know to run it (the folder a relative path is relative to, which robot ``robot`` is), or nothing.
    """

    target: str
    template: str
    version: str
    robot: str
    convention: str
    dof: int
    joints: tuple[tuple[str, str], ...]
    parameters: tuple[tuple[str, str], ...]
    functions: tuple[GeneratedFunction, ...]
    jacobians: tuple[JacobianInfo, ...]
    scalars: tuple[str, ...]
    exports: tuple[str, ...]
    command: str
    command_lines: tuple[str, ...]
    title: str
    description_text: str
    nan_policy: str
    imports: tuple[str, ...] = ()
    parameter_lines: tuple[str, ...] = ()
    extras: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    rates: tuple[str, ...] = ()
    command_note: str = ""

    @property
    def acceleration(self) -> bool:
        """Whether the module has the acceleration-level functions (Hessian, bias acceleration, gradient)."""
        return any(info.hessian for info in self.jacobians)

    @property
    def command_note_lines(self) -> tuple[str, ...]:
        """``command_note`` in parentheses, broken into header comment lines (none without a note)."""
        return comment_lines(f"({self.command_note})") if self.command_note else ()

    @property
    def rate_names_lines(self) -> tuple[str, ...]:
        """``_RATE_NAMES = ("thetadot1", "ddot2")``: the joint rate names as Python source lines."""
        return tuple(tuple_lines("_RATE_NAMES = ", (f'"{name}"' for name in self.rates)))

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Parameter names, in robot-file order."""
        return tuple(name for name, _ in self.parameters)

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Joint variable names, in chain order."""
        return tuple(name for name, _ in self.joints)

    @property
    def revolute(self) -> tuple[bool, ...]:
        """Whether each joint is revolute."""
        return tuple(kind == "revolute" for _, kind in self.joints)

    @property
    def joints_lines(self) -> tuple[str, ...]:
        """``JOINTS = ("theta1", "theta2")`` as Python source lines."""
        return tuple(tuple_lines("JOINTS = ", (f'"{name}"' for name in self.joint_names)))

    @property
    def revolute_lines(self) -> tuple[str, ...]:
        """``_REVOLUTE = (True, False)`` as Python source lines."""
        return tuple(tuple_lines("_REVOLUTE = ", (str(flag) for flag in self.revolute)))
