"""The frozen, language-neutral data of code generation: what a module contains, and a target's :class:`Backend` spec.

A :class:`ModuleDescription` holds no syntax of any language: names (validated), shapes, parameter defaults as
numbers and each function's lowered assignments as SymPy data (:class:`~symjac.codegen.lower.LoweredFunction`: the
temporaries ``(symbol, expression)`` in evaluation order and the outputs). A backend's printer and templates turn it
into files of its language.
"""

from __future__ import annotations

import builtins
import keyword
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Literal

from symjac.errors import CodegenError

if TYPE_CHECKING:  # lowering imports the request, which imports the identifier rules from here
    from symjac.codegen.lower import LoweredFunction
    from symjac.kinematics.chain import Chain

__all__ = [
    "PYTHON_IDENTIFIERS",
    "Argument",
    "Backend",
    "FunctionDescription",
    "FunctionKind",
    "FunctionSpec",
    "IdentifierRule",
    "JacobianInfo",
    "ModuleDescription",
    "Renderer",
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
class FunctionDescription:
    """One function of the module: its spec and its lowered assignments (SymPy data, target-independent)."""

    spec: FunctionSpec
    lowered: LoweredFunction

    @property
    def name(self) -> str:
        """The function's name."""
        return self.spec.name

    @property
    def kind(self) -> FunctionKind:
        """What the function computes."""
        return self.spec.kind

    @property
    def shape(self) -> tuple[int, ...]:
        """The output shape (``()`` for a scalar)."""
        return self.lowered.shape

    @property
    def op_count(self) -> int:
        """Arithmetic operations per configuration after CSE (``sympy.count_ops``)."""
        return self.lowered.op_count

    @property
    def trig_count(self) -> int:
        """Sine and cosine evaluations per configuration."""
        return self.lowered.trig_count


_ASCII_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


@dataclass(frozen=True)
class IdentifierRule:
    """Which names a target's language accepts as identifiers: a pattern, keywords, and names not to shadow.

    ``keywords`` and ``shadowed`` map each word to the language it belongs to, so that one rule can serve a file
    that mixes two languages (the c target: a Python module embedding C) and the error still names the right one.

    Examples
    --------
    >>> PYTHON_IDENTIFIERS.check("a2", "parameter name")
    'a2'
    >>> PYTHON_IDENTIFIERS.check("lambda", "parameter name")
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: parameter name 'lambda' is a Python keyword
    """

    keywords: Mapping[str, str]
    shadowed: Mapping[str, str]
    pattern: re.Pattern[str] = _ASCII_IDENTIFIER
    prefixes: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))  # kept by the generated code

    @classmethod
    def of(cls, language: str, keywords: Iterable[str], shadowed: Iterable[str] = (),
           prefixes: Iterable[str] = ()) -> IdentifierRule:
        """The rule of one language: its keywords, names not to shadow, and its generated code's own prefixes.

        ``shadowed`` are the builtins a generated name must not hide; a name starting with one of ``prefixes`` could
        collide with a name the generated code makes itself.
        """
        return cls(MappingProxyType(dict.fromkeys(keywords, language)),
                   MappingProxyType(dict.fromkeys(shadowed, language)),
                   prefixes=MappingProxyType(dict.fromkeys(prefixes, language)))

    def __or__(self, other: IdentifierRule) -> IdentifierRule:
        """A rule that refuses whatever either rule refuses (the first one's pattern)."""
        return IdentifierRule(MappingProxyType({**other.keywords, **self.keywords}),
                              MappingProxyType({**other.shadowed, **self.shadowed}), self.pattern,
                              MappingProxyType({**other.prefixes, **self.prefixes}))

    def check(self, name: object, what: str, reserved: Mapping[str, str] | None = None) -> str:
        """Return ``name`` if it may be an identifier of the generated code, else raise :class:`CodegenError`.

        ``reserved`` maps names the generated module uses itself to the reason (the error says which).
        """
        if not isinstance(name, str) or not self.pattern.match(name):
            raise CodegenError(f"{what} {name!r} is not an ASCII identifier (letters, digits, underscore)")
        if name in self.keywords:
            raise CodegenError(f"{what} {name!r} is a {self.keywords[name]} keyword")
        if name in self.shadowed:
            raise CodegenError(f"{what} {name!r} would shadow the {self.shadowed[name]} builtin of that name")
        for prefix, language in self.prefixes.items():
            if name.startswith(prefix):
                raise CodegenError(f"{what} {name!r} starts with {prefix!r}, which the generated {language} keeps for "
                                   "its own names")
        if reserved is not None and name in reserved:
            raise CodegenError(f"{what} {name!r} clashes with {reserved[name]} in the generated module")
        return name


PYTHON_IDENTIFIERS = IdentifierRule.of("Python", (*keyword.kwlist, *keyword.softkwlist), dir(builtins))
"""Python's rule: ASCII identifiers, no keyword or soft keyword, no builtin (a parameter ``len`` would shadow it)."""

Renderer = Callable[["ModuleDescription", "Backend"], Mapping[str, str]]
"""Turns a module description into the target's files: ``{relative file name: text}``, the primary file first."""


@dataclass(frozen=True)
class Backend:
    """Everything that makes a target: one instance in each ``symjac/codegen/backends/<target>/__init__.py``.

    Parameters
    ----------
    name : str
        The target's name (``generate(robot, name)``, ``symjac codegen --target name``).
    order : int
        Position in listings (:data:`~symjac.codegen.TARGETS`, the CLI's choices).
    summary : str
        A few words for the CLI's help (``"standard library"``).
    emits : str
        What the target writes (``"a Python module"``).
    title, description, nan_policy : str
        The generated module's first docstring line, what its functions take and return, and what wrong shapes
        and NaN or infinite inputs do.
    identifiers : IdentifierRule
        The target's own reserved words and identifier rule; every robot and parameter name passes it.
    files : tuple of str
        The files it writes, relative names (``{robot}`` is replaced by the robot's name), the primary one first
        (``write_module`` writes that one at the path given, the others beside it).
    templates : tuple of str
        Its jinja2 templates, in ``templates/<name>/`` (shared ones in ``templates/python_common/``).
    render : Renderer
        Prints the description: ``render(description, backend) -> {file name: text}``.
    dependencies : tuple of str
        Third-party modules the generated code imports (none: standard library only).
    batched : bool
        Whether functions take ``q`` of shape ``(..., n)`` and return arrays (else one configuration per call).
    exports : tuple of str
        Module constants the target adds to the exported names (the c target's ``BACKEND``).
    language : str
        The language of the files it writes: ``"Python"`` (a module with the API of the python and numpy targets),
        ``"Python/JAX"`` (pure functions of one configuration), ``"C"`` or ``"C++"`` (files to compile).
    """

    name: str
    order: int
    summary: str
    emits: str
    title: str
    description: str
    nan_policy: str
    identifiers: IdentifierRule
    files: tuple[str, ...]
    templates: tuple[str, ...]
    render: Renderer
    dependencies: tuple[str, ...] = ()
    batched: bool = True
    exports: tuple[str, ...] = ()
    language: str = "Python"

    @property
    def suffix(self) -> str:
        """The primary file's suffix (``".py"``)."""
        return "." + self.files[0].rsplit(".", 1)[-1] if "." in self.files[0] else ""

    @property
    def template(self) -> str:
        """The primary file's template."""
        return self.templates[0]


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
    """The whole generated module as language-neutral data: what a backend's ``render`` prints.

    ``parameters`` are (name, default) with the default a float; ``functions`` hold their lowered assignments as
    SymPy data; ``command`` is how to regenerate the module (the command line typed when ``shell_command``, else the
    equivalent Python call) and ``command_note`` what else the reader needs to know to run it (the folder a relative
    path is relative to, which robot ``robot`` is), or nothing. ``joints`` are the entries of ``q`` (name, type):
    the joint variables, or for a coupled robot its independent coordinates, and then ``coupling`` holds each other
    joint variable as an equation in them (``theta4 = -theta2 - theta3``). ``chain`` is the robot's cached derivation,
    for backends that need more of it (the c target's joint angles).
    """

    target: str
    version: str
    robot: str
    convention: str
    n_joints: int
    n_coordinates: int
    joints: tuple[tuple[str, str], ...]
    parameters: tuple[tuple[str, float], ...]
    functions: tuple[FunctionDescription, ...]
    jacobians: tuple[JacobianInfo, ...]
    scalars: tuple[str, ...]
    exports: tuple[str, ...]
    command: str
    shell_command: bool = False
    command_note: str = ""
    rates: tuple[str, ...] = ()
    coupling: tuple[str, ...] = ()
    chain: Chain | None = field(default=None, compare=False, repr=False)

    @property
    def acceleration(self) -> bool:
        """Whether the module has the acceleration-level functions (Hessian, bias acceleration, gradient)."""
        return any(info.hessian for info in self.jacobians)

    @property
    def q_words(self) -> str:
        """What the entries of ``q`` are, for docstrings: joint values, or a coupled robot's coordinates."""
        return "Coordinates" if self.coupling else "Joint values"

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
