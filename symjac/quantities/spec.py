r"""What a derived quantity is, in one frozen record: :class:`Quantity`.

A quantity (forward kinematics, the Jacobian, the joint torques, the Hessian, the bias acceleration, manipulability;
next the mass matrix, inverse dynamics, the regressor, inverse kinematics) is one module in
:mod:`symjac.quantities` holding one :class:`Quantity`: its derivation, the law by which it moves to a coupled
robot's coordinates, its document (what LaTeX, pretty text and JSON print), its command and options on the command
line, and what generated modules compute it with (its :class:`Generated` kind: where its functions sit in a module,
their arguments, documentation and lowering). Every front end and code generation read the spec; none lists the
quantities itself.

Entry points are ``"module:function"`` strings, imported on first use (:func:`entry_point`): the command line reads
every spec to build its parser, and ``symjac --version`` must not load SymPy.

A command-line handler gets a :class:`Request` (the parsed options, the robot, and the front end's parsers of
frames, points and values), so a quantity depends on no front end; :mod:`symjac.cli` builds the request.
"""

from __future__ import annotations

import argparse
import functools
from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module
from typing import TYPE_CHECKING, Any, Literal, Protocol, TypeVar, get_args

from symjac.errors import ArgumentError

if TYPE_CHECKING:
    import sympy as sp

    from symjac.kinematics.chain import Frame
    from symjac.kinematics.jacobian import Point
    from symjac.model.robot import Robot
    from symjac.printing.document import Document

__all__ = [
    "Generated",
    "Input",
    "LawName",
    "Quantity",
    "Request",
    "Scope",
    "entry_point",
    "lazily_memoized",
]

T = TypeVar("T")

LawName = Literal["columns", "transposed", "congruent", "rates"]
"""The coupling law a quantity follows, by its name in :data:`symjac.kinematics.coupling.COUPLING_LAWS` (where the
laws are written and applied; a test checks the two lists agree, so reading a spec loads no SymPy)."""


Scope = Literal["module", "request"]
"""Where a generated kind's functions sit: once per module (the pose), or once per Jacobian request (its frame,
point and task rows: the Jacobian, torques, Hessian)."""

Input = Literal["wrench", "qdot", "qddot", "tau"]
"""An argument a generated function takes after ``q``: the wrench entries of the request's task rows, the coordinate
rates (with ``acceleration`` or ``dynamics``), their accelerations, or one generalised force per coordinate (the last
two with ``dynamics``). Code generation knows how to describe each."""


def entry_point(path: str) -> Any:
    """The object a ``"module:name"`` string names, imported now.

    Examples
    --------
    >>> entry_point("symjac.kinematics.chain:forward_kinematics").__name__
    'forward_kinematics'
    """
    module, _, name = path.partition(":")
    if not module or not name:
        raise ArgumentError(f"an entry point is 'module:name', got {path!r}")
    return getattr(import_module(module), name)


def lazily_memoized(coupling: LawName, **normalisers: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """:func:`symjac.kinematics.memo.memoized` applied on the first call: a quantity module's own derivation.

    A quantity module is imported with the registry, which must load no SymPy, so its derivation cannot be decorated
    by ``memoized`` when the module loads. This decorator defers that: the first call imports ``memoized`` and the
    ``normalisers`` (entry points, ``frame="symjac.kinematics.memo:frame_of"``) and wraps the function, which is
    then kept per chain and moved to a coupled robot's coordinates by its law, as every derivation is. The wrapper
    carries ``coupling_law`` as a memoized function does.
    """
    def decorate(function: Callable[..., Any]) -> Callable[..., Any]:
        wrapped: list[Callable[..., Any]] = []

        @functools.wraps(function)
        def derivation(*args: Any, **kwargs: Any) -> Any:
            if not wrapped:
                from symjac.kinematics.memo import memoized

                found = {name: entry_point(path) for name, path in normalisers.items()}
                wrapped.append(memoized(coupling=coupling, **found)(function))
            return wrapped[0](*args, **kwargs)

        derivation.coupling_law = _LazyLaw(coupling)  # type: ignore[attr-defined]
        return derivation

    return decorate


class _LazyLaw:
    """A coupling law by name, its :class:`~symjac.kinematics.coupling.CouplingLaw` imported when it is used."""

    def __init__(self, name: LawName):
        self.name = name

    def __getattr__(self, attribute: str) -> Any:
        from symjac.kinematics.coupling import coupling_law

        return getattr(coupling_law(self.name), attribute)

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        from symjac.kinematics.coupling import coupling_law

        return coupling_law(self.name)(*args, **kwargs)


class Request(Protocol):
    """What a quantity's command-line handler is given: the parsed options, the robot, the front end's parsers.

    The parsers raise errors that name the option (``--frame must be a frame number ...``); ``progress`` runs a
    derivation, telling a person at a terminal what it derives.
    """

    @property
    def args(self) -> argparse.Namespace:
        """The parsed options."""
        ...

    @property
    def robot(self) -> Robot:
        """The robot the command names, loaded."""
        ...

    @property
    def digits(self) -> int | None:
        """``--numeric``: the significant digits printed; ``None``: exact."""
        ...

    def frame(self) -> Frame:
        """``--frame``, parsed."""
        ...

    def point(self) -> Point | None:
        """``--point``, parsed: a name (``tool``, ``flange``, ``wrist``, ``wrist_centre``) or three coordinates.

        Not given: None, the end of the chain (the tool point, else the flange), or with ``--link k`` the origin of
        {k}. With ``--link k`` the coordinates are in frame {k}, else in frame {n}.
        """
        ...

    def point_name(self) -> str:
        """The point as the documents name it: ``--point`` as typed, else the name of the end of the chain.

        With ``--link k`` and no ``--point``: ``origin`` (the origin of {k}).
        """
        ...

    def link(self) -> int | None:
        """``--link``: the link the point is fixed in (None: the last link, as without the option)."""
        ...

    def values(self, text: str, length: int, option: str, *, parameters: bool = True) -> list[sp.Expr]:
        """``length`` comma-separated values of ``option`` (numbers, ``pi``, with ``parameters`` their names)."""
        ...

    def configuration(self, text: str, option: str = "--q") -> list[sp.Expr]:
        """A configuration in radians and metres: ``30deg``, ``pi/4``, or numbers in the robot file's angle unit."""
        ...

    def progress(self, what: str, compute: Callable[[], T]) -> T:
        """``compute()``, reported as ``deriving {what}`` on a terminal."""
        ...


QuantityHandler = Callable[[Request], "Document"]
"""A quantity's command-line handler: the request in, the document to render out."""
QuantityOptions = Callable[[argparse.ArgumentParser], None]
"""A quantity's argparse hook: adds its own options to its command's parser (the common ones are there already)."""


@dataclass(frozen=True)
class Generated:
    r"""The codegen part of a quantity: one kind of generated function, its place, arguments, words and lowering.

    Code generation's table of kinds (:data:`symjac.codegen.kinds.KINDS`) is made of these: every quantity's, then
    code generation's own (the self-test's kinematics, scalar functions, the determinant and the manipulability
    gradient). Generated modules list, document, lay out and compute a function from its kind alone; no template
    names one.

    Texts are language-neutral ``str.format`` templates (a literal brace doubled). ``returns`` and ``listing`` may
    use ``{unit}`` ("joint" or "coordinate") and ``{shape}``; a module kind's ``summary`` and ``listing`` also
    ``{end}`` (the frame the chain ends at: "the tool frame" or "frame {6} (its origin the flange)"); a per-request
    kind's ``summary``, ``details`` and ``listing`` also ``{frame}``, ``{point}`` and ``{at}`` (both words for the
    point: "the tool point", "the origin of frame {6} (flange)"), ``{rows}``, ``{wrench}`` and the names of the
    request's other functions by kind (``{jacobian}``, ``{hessian}``, ``{manipulability}``).

    Parameters
    ----------
    name : str
        The kind (``"jacobian"``): the key of the table, and the base of its functions' names (a per-request
        function adds the request's suffix: ``jacobian_3_tool``).
    returns : str
        What the result is, for a docstring's Returns section.
    listing : str
        The line under the function's name in the module docstring's list of functions ("" for none).
    summary, details : str
        The function's docstring summary line and a further paragraph (derived kinds).
    output : str
        The C family's name of its output buffer (``"J"``; the name of its CasADi output); empty for a scalar,
        which is returned.
    returns_coupled, summary_coupled : str
        ``returns`` and ``summary`` for a coupled robot, when they differ.
    layout : str
        How a flat (C) output of three dimensions is indexed, with ``{shape[1]}``, ``{shape[2]}`` (else "").
    scope : Scope
        ``"module"``: one function per module, before the per-request ones; ``"request"``: one per Jacobian
        request. Within a request, the functions come in registry order, those needing ``acceleration`` last.
    acceleration : bool
        Generated only with ``acceleration=True`` (the Hessian, the bias acceleration, the manipulability gradient).
    dynamics : bool
        Generated only with ``dynamics=True`` (inverse and forward dynamics, M, C, the bias forces, g): once per
        module, and only for a robot with inertial data on every link.
    identification : bool
        Generated only with ``identification=True`` (the regressor and the base regressor, which imply the
        dynamics): once per module.
    lowering : str
        The entry point ``"module:function"`` of its lowering into straight-line code: called with the chain and
        those of ``frame``, ``point``, ``rows`` (the request's) and ``strategy`` it takes by name, it returns a
        :class:`~symjac.codegen.lower.LoweredFunction` in the robot's coordinates (``symjac.codegen.coupled``).
        Empty: code generation lowers the quantity's own derivation (called with the chain of the joints, plus
        ``frame`` and ``point`` for a per-request kind), one entry per value, a column as a vector, and moves it to
        the coordinates by the quantity's coupling law. A string, because code generation sits above the
        quantities (it imports them; they never import it).
    inputs : tuple of Input
        The arguments after ``q``, in order.
    task_rows : bool
        With the default lowering of a per-request kind: the derivation's rows are task rows (v, omega), and the
        request's rows are selected.
    routine, sources : str, tuple of str
        A *derived* kind is computed by the runtime routine ``routine`` (each target prefixes its runtime's:
        ``_manipulability``, ``sj_manipulability``) from the results of the request's (or, module-scoped, the
        module's) functions of kinds ``sources``, in that order, each called with ``q`` and those of the derived
        function's ``inputs`` its own kind takes; the routine then gets the ``inputs`` no source takes (forward
        dynamics: ``forward_dynamics(M, b, tau)`` from ``mass_matrix(q)`` and ``bias_forces(q, qdot)``). It has
        no lowering.
    per_coordinate : bool
        A derived result has one value per coordinate (else it is a scalar).
    square_only : bool
        Generated only when the request's Jacobian is square (the determinant).
    selftest_only : bool
        The function exists for the self-test only (private, no compiled kernel).
    function : str
        The base of its functions' names when it is not ``name`` (the self-test's ``_kinematics``).
    """

    name: str
    returns: str
    listing: str = ""
    summary: str = ""
    details: str = ""
    output: str = ""
    returns_coupled: str = ""
    summary_coupled: str = ""
    layout: str = ""
    scope: Scope = "request"
    acceleration: bool = False
    dynamics: bool = False
    identification: bool = False
    lowering: str = ""
    inputs: tuple[Input, ...] = ()
    task_rows: bool = False
    routine: str = ""
    sources: tuple[str, ...] = ()
    per_coordinate: bool = False
    square_only: bool = False
    selftest_only: bool = False
    function: str = ""

    def __post_init__(self) -> None:
        where = f"generated kind {self.name!r}"
        if not self.name.isidentifier():
            raise ArgumentError(f"{where}: a kind is an identifier")
        if self.scope not in get_args(Scope):
            raise ArgumentError(f"{where}: scope {self.scope!r} is none of {', '.join(get_args(Scope))}")
        unknown = [name for name in self.inputs if name not in get_args(Input)]
        if unknown:
            raise ArgumentError(f"{where}: inputs {unknown} are not among {', '.join(get_args(Input))}")
        if self.lowering and self.lowering.count(":") != 1:
            raise ArgumentError(f"{where}: an entry point is 'module:name', got {self.lowering!r}")
        if self.routine and (self.lowering or not self.sources or (self.scope != "request" and not self.dynamics)):
            raise ArgumentError(f"{where}: a derived kind has sources, no lowering, and one function per request "
                                f"(or, with dynamics, per module)")
        if (self.dynamics or self.identification) and (self.scope != "module" or self.acceleration):
            raise ArgumentError(f"{where}: a dynamics kind has one function per module and no acceleration level")

    @property
    def derived(self) -> bool:
        """Whether functions of this kind are computed by a runtime routine from other functions."""
        return bool(self.routine)

    @property
    def base(self) -> str:
        """The base of its functions' names."""
        return self.function or self.name

    def returns_text(self, coupled: bool, **fields: object) -> str:
        """The Returns sentence, its fields filled (``unit`` from ``coupled``)."""
        text = self.returns_coupled if coupled and self.returns_coupled else self.returns
        return text.format(unit="coordinate" if coupled else "joint", **fields)

    def summary_text(self, coupled: bool, **fields: object) -> str:
        """The docstring summary, its fields filled."""
        text = self.summary_coupled if coupled and self.summary_coupled else self.summary
        return text.format(unit="coordinate" if coupled else "joint", **fields)


@dataclass(frozen=True)
class Quantity:
    r"""One derived quantity: what it is, how it is derived, coupled, printed, asked for and generated.

    Parameters
    ----------
    name : str
        Its name in :data:`symjac.quantities.QUANTITIES` (``"jacobian"``).
    summary : str
        One line saying what it is (a command's help when it owns a command).
    derivation : str
        The entry point of its derivation in the API, ``"module:function"`` (:meth:`derive` calls it).
    coupling : LawName
        How it moves to a coupled robot's coordinates: the name of its law in
        :data:`symjac.kinematics.coupling.COUPLING_LAWS`, the one place that applies it (:attr:`law`).
    document : str or None
        The entry point of its document builder (:meth:`build_document`), or None when nothing prints it.
    codegen : Generated or None
        What generated modules compute it with (its kind in code generation's table of kinds), or None when they
        do not compute it.
    command : str or None
        The ``symjac`` command that prints it; several quantities may share one (``jacobian --derivative``).
    flag : str or None
        Within a shared command, the option (its ``dest``) that selects this quantity; None for the command's
        own quantity, which prints when no flag is given.
    options : QuantityOptions or None
        Adds the quantity's options to its command's parser (``--frame``, ``--method``, its ``flag``).
    handler : QuantityHandler or None
        Turns a :class:`Request` into the document to print.
    """

    name: str
    summary: str
    derivation: str
    coupling: LawName
    document: str | None = None
    codegen: Generated | None = None
    command: str | None = None
    flag: str | None = None
    options: QuantityOptions | None = None
    handler: QuantityHandler | None = None

    def __post_init__(self) -> None:
        where = f"quantity {self.name!r}"
        if self.coupling not in get_args(LawName):
            raise ArgumentError(f"{where}: coupling law {self.coupling!r} is none of {', '.join(get_args(LawName))}")
        if (self.command is None) != (self.handler is None):
            raise ArgumentError(f"{where}: a command needs a handler and a handler a command")
        if self.flag is not None and (self.command is None or self.options is None):
            raise ArgumentError(f"{where}: flag {self.flag!r} selects it within a command whose options add it")
        for path in (self.derivation, self.document):
            if path is not None and path.count(":") != 1:
                raise ArgumentError(f"{where}: an entry point is 'module:name', got {path!r}")

    @property
    def kind(self) -> str | None:
        """The name of its codegen kind (:attr:`codegen`), or None."""
        return None if self.codegen is None else self.codegen.name

    @property
    def law(self) -> Any:
        """Its :class:`~symjac.kinematics.coupling.CouplingLaw` (name, equation, and how it is applied)."""
        from symjac.kinematics.coupling import coupling_law

        return coupling_law(self.coupling)

    def derive(self, *args: Any, **kwargs: Any) -> Any:
        """Derive the quantity: the :attr:`derivation` entry point called with these arguments."""
        return entry_point(self.derivation)(*args, **kwargs)

    def build_document(self, *args: Any, **kwargs: Any) -> Document:
        """The quantity's document: the :attr:`document` entry point called with these arguments."""
        if self.document is None:
            raise ArgumentError(f"quantity {self.name!r} has no document (nothing prints it)")
        return entry_point(self.document)(*args, **kwargs)  # type: ignore[no-any-return]
