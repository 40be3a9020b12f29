"""The frozen, language-neutral data of code generation: what a module contains, and a target's :class:`Backend` spec.

A :class:`ModuleDescription` holds no syntax of any language: names (validated), shapes, parameter defaults as
numbers and each function's lowered assignments as SymPy data (:class:`~symjac.codegen.lower.LoweredFunction`: the
temporaries ``(symbol, expression)`` in evaluation order and the outputs). A backend's printer and templates turn it
into files of its language.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy as sp

from symjac.codegen.inverse_kinematics import InverseKinematics
from symjac.codegen.joint_table import JointEntry, convention_words
from symjac.codegen.kinds import CHECK_WORDS, COUPLED_WORDS, kind_spec
from symjac.codegen.lower import LoweredFunction
from symjac.codegen.names import PYTHON_IDENTIFIERS, IdentifierRule

__all__ = [
    "PYTHON_IDENTIFIERS",
    "Argument",
    "Backend",
    "Check",
    "DerivedFunction",
    "FunctionDescription",
    "FunctionKind",
    "FunctionSpec",
    "IdentifierRule",
    "JacobianInfo",
    "ModuleDescription",
    "Renderer",
]

FunctionKind = str
"""A kind of :data:`~symjac.codegen.kinds.KINDS` (its table says what each returns and how it is laid out): the
quantities' kinds (``"forward_kinematics"``, ``"jacobian"``, ...) and code generation's own (``"kinematics"``,
``"scalar"``, ``"jacobian_determinant"``, ``"manipulability_gradient"``)."""


@dataclass(frozen=True)
class Argument:
    """An array argument of a generated function: its name and the names of its entries."""

    name: str
    entries: tuple[str, ...]
    description: str


@dataclass(frozen=True)
class FunctionSpec:
    """What one generated function is, before any target prints it: name, kind, docstring summary, arguments.

    ``returns`` documents the result (from :data:`~symjac.codegen.kinds.KINDS`, its fields filled).
    """

    name: str
    kind: FunctionKind
    summary: str
    arguments: tuple[Argument, ...]
    returns: str = ""


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
    def returns(self) -> str:
        """What the result is, for a docstring."""
        return self.spec.returns

    @property
    def selftest_only(self) -> bool:
        """Whether the function exists for the self-test only (private, no compiled kernel)."""
        return kind_spec(self.kind).selftest_only

    @property
    def op_count(self) -> int:
        """Arithmetic operations per configuration after CSE (``sympy.count_ops``)."""
        return self.lowered.op_count

    @property
    def trig_count(self) -> int:
        """Sine and cosine evaluations per configuration."""
        return self.lowered.trig_count


@dataclass(frozen=True)
class DerivedFunction:
    """A function computed by a runtime routine from the results of other functions of the module.

    ``sources`` name those functions, in the order the routine takes their results (all called with ``q`` and the
    parameters), ``source_kinds`` and ``source_shapes`` say what they return; ``routine`` is the routine's base
    name (:attr:`~symjac.quantities.spec.Generated.routine`), which each target prefixes with its runtime's
    (``_manipulability``, ``sj_manipulability``, ``runtime::manipulability``).
    ``shape`` is the result's (``()``: a scalar), ``summary``, ``details`` and ``returns`` its documentation.
    ``inputs`` are its arguments after ``q`` (forward dynamics: ``qdot``, ``tau``), ``source_inputs`` the names of
    those each source takes after ``q``, and ``routine_inputs`` those passed to the routine after the sources'
    results (``forward_dynamics(M, b, tau)``); all empty for a function of ``q`` alone.
    """

    name: str
    kind: FunctionKind
    summary: str
    details: str
    returns: str
    sources: tuple[str, ...]
    source_kinds: tuple[FunctionKind, ...]
    source_shapes: tuple[tuple[int, ...], ...]
    routine: str
    shape: tuple[int, ...]
    inputs: tuple[Argument, ...] = ()
    source_inputs: tuple[tuple[str, ...], ...] = ()
    routine_inputs: tuple[str, ...] = ()

    @property
    def input_names(self) -> tuple[str, ...]:
        """The names of its arguments after ``q``."""
        return tuple(argument.name for argument in self.inputs)

    @property
    def output(self) -> str:
        """The C family's output buffer of a non-scalar result (``gradient``), else ``""`` (a scalar is returned)."""
        return kind_spec(self.kind).output if self.shape else ""

    @property
    def result_name(self) -> str:
        """The result's name where every result has one (a CasADi output: ``w``, ``det``, ``gradient``)."""
        return kind_spec(self.kind).output or "value"

    @property
    def source_outputs(self) -> tuple[str, ...]:
        """The C family's buffer names of the sources' results (``J``, ``H``), from their kinds."""
        return tuple(kind_spec(kind).output for kind in self.source_kinds)


@dataclass(frozen=True)
class Check:
    """One check of a module's self-test: the runtime's check ``routine`` applied to module functions.

    ``routine`` is ``"pose"`` (the forward kinematics is a rigid transform), ``"jacobian"`` (a Jacobian against
    central differences of its kinematics, its torques against J^T F), ``"acceleration"`` (the Hessian, bias
    acceleration and manipulability gradient against central differences) or ``"dynamics"`` (inverse dynamics, M,
    C, the bias forces, g and forward dynamics against each other) or ``"identification"`` (a regressor times the
    robot's own parameters against inverse dynamics); ``functions`` are the names it calls, in the routine's order;
    ``rows`` the Jacobian's task rows (none for the pose; for ``"identification"`` the regressor's column count).
    The checks run in the order given.
    """

    routine: str
    functions: tuple[str, ...]
    rows: tuple[int, ...] = ()


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
    runtime : str
        The numeric runtime its files carry, a file of ``templates/runtime/`` (:mod:`symjac.codegen.runtime`):
        ``"python.py"``, ``"numpy.py"``, ``"c99.h"``, ``"eigen.hpp"``; empty for none.
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
    runtime: str = ""

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
    """Names and meaning of the functions generated for one Jacobian request.

    ``functions`` holds every function of the request, (kind, name, shape), lowered ones in module order then the
    derived ones: what a new quantity's per-request function is found by. The named fields are the functions the
    self-test's checks and headers name.
    """

    jacobian: str
    joint_torques: str
    manipulability: str
    determinant: str | None
    kinematics: str
    frame: str
    point: str
    """Which point, in words after "at": ``the tool point``, ``the origin of frame {6} (flange)``, ..."""
    point_values: tuple[str, str, str]
    rows: tuple[int, ...]
    row_names: tuple[str, ...]
    wrench_names: tuple[str, ...]
    hessian: str | None = None
    bias_acceleration: str | None = None
    manipulability_gradient: str | None = None
    functions: tuple[tuple[str, str, tuple[int, ...]], ...] = ()


@dataclass(frozen=True)
class ModuleDescription:
    """The whole generated module as language-neutral data: what a backend's ``render`` prints.

    ``parameters`` are (name, default) with the default a float; ``functions`` hold their lowered assignments as
    SymPy data; ``command`` is how to regenerate the module (the command line typed when ``shell_command``, else the
    equivalent Python call) and ``command_note`` what else the reader needs to know to run it (the folder a relative
    path is relative to, which robot ``robot`` is), or nothing. ``coordinates`` are the entries of ``q`` (name, type):
    the joint variables, or for a coupled robot its independent coordinates, and then ``coupling`` holds each other
    joint variable as an equation in them (``theta4 = -theta2 - theta3``). ``coordinate_symbols`` and
    ``parameter_symbols`` are the SymPy symbols of the entries of ``q`` and of the parameters (in the order of
    ``coordinates`` and ``parameters``): what the lowered assignments read, which a printer names. Nothing here refers
    to the robot's derivation (no ``Chain``): a backend prints from this data alone. ``derived`` are the functions
    computed by the runtime from others (manipulability, determinant, gradient), ``listing`` every public function
    with its line for the module docstring, in order, ``checks`` the self-test's checks in order and
    ``request_lines`` each requested Jacobian's name with what it is (frame, point, rows), for headers. ``rates``
    and ``accelerations`` name the entries of ``qdot`` and ``qddot`` when functions take them.
    ``joint_entries`` describe the entries of ``q`` as the robot's source names them (name, identifier-safe variant,
    type, limits: :class:`~symjac.codegen.joint_table.JointEntry`), ``tip_frame`` names the frame the chain ends at
    and ``origin`` says where the robot came from (``URDF file ur5.urdf``). ``name_lists`` are module constants
    holding names in order (``REGRESSOR_PARAMETERS``: the regressor's columns), each (constant, names).
    """

    target: str
    version: str
    robot: str
    convention: str
    n_joints: int
    n_coordinates: int
    coordinates: tuple[tuple[str, str], ...]
    parameters: tuple[tuple[str, float], ...]
    functions: tuple[FunctionDescription, ...]
    jacobians: tuple[JacobianInfo, ...]
    scalars: tuple[str, ...]
    exports: tuple[str, ...]
    command: str
    shell_command: bool = False
    command_note: str = ""
    rates: tuple[str, ...] = ()
    accelerations: tuple[str, ...] = ()
    coupling: tuple[str, ...] = ()
    derived: tuple[DerivedFunction, ...] = ()
    listing: tuple[tuple[str, str], ...] = ()
    checks: tuple[Check, ...] = ()
    request_lines: tuple[tuple[str, str], ...] = ()
    coordinate_symbols: tuple[sp.Symbol, ...] = ()
    parameter_symbols: tuple[sp.Symbol, ...] = ()
    joint_entries: tuple[JointEntry, ...] = ()
    tip_frame: str = ""
    origin: str = ""
    name_lists: tuple[tuple[str, tuple[str, ...]], ...] = ()
    inverse_kinematics: InverseKinematics | None = None
    """The closed-form inverse kinematics, lowered (:mod:`symjac.codegen.inverse_kinematics`), when asked for."""
    numeric_ik: str = ""

    @property
    def joint_names(self) -> tuple[str, ...]:
        """The names of the entries of ``q`` as the robot's source writes them (``JOINT_NAMES``)."""
        return tuple(entry.name for entry in self.joint_entries)

    @property
    def convention_words(self) -> str:
        """The convention as headers say it: ``standard DH``, ``general (fixed origins and joint axes, ...)``."""
        return convention_words(self.convention)

    @property
    def symbols(self) -> tuple[sp.Symbol, ...]:
        """The symbols that keep their own names in every function: the coordinates, then the parameters."""
        return (*self.coordinate_symbols, *self.parameter_symbols)

    @property
    def acceleration(self) -> bool:
        """Whether the module has the acceleration-level functions (Hessian, bias acceleration, gradient)."""
        return any(info.hessian for info in self.jacobians)

    @property
    def runtime_sections(self) -> frozenset[str]:
        """The runtime sections the module uses: its derived functions' routines and its self-test's checks.

        :func:`~symjac.codegen.runtime.runtime_source` adds the sections they need and the core (which holds the
        pose and Jacobian checks): what the backends copy into the module.
        """
        return (frozenset(d.routine for d in self.derived) | frozenset(check.routine for check in self.checks)
                | frozenset(("ik_numeric",) if self.numeric_ik else ()))

    @property
    def check_words(self) -> str:
        """What the self-test checks, for its docstring: the words of each routine of ``checks``, once each."""
        routines = list(dict.fromkeys(check.routine for check in self.checks))
        routines.sort(key=lambda routine: list(CHECK_WORDS).index(routine))
        return "; ".join(CHECK_WORDS[routine] for routine in routines)

    @property
    def coupled_words(self) -> str:
        """What the functions compute for a coupled robot (empty for another)."""
        return COUPLED_WORDS if self.coupling else ""

    @property
    def q_words(self) -> str:
        """What the entries of ``q`` are, for docstrings: joint values, or a coupled robot's coordinates."""
        return "Coordinates" if self.coupling else "Joint values"

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Parameter names, in robot-file order."""
        return tuple(name for name, _ in self.parameters)

    @property
    def coordinate_names(self) -> tuple[str, ...]:
        """The names of the entries of ``q``: the joint variables, or a coupled robot's coordinates, in order."""
        return tuple(name for name, _ in self.coordinates)

    @property
    def revolute(self) -> tuple[bool, ...]:
        """Whether each coordinate is an angle (revolute)."""
        return tuple(kind == "revolute" for _, kind in self.coordinates)
