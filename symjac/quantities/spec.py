r"""What a derived quantity is, in one frozen record: :class:`Quantity`.

A quantity (forward kinematics, the Jacobian, the joint torques, the Hessian, the bias acceleration, manipulability;
next the mass matrix, inverse dynamics, the regressor, inverse kinematics) is one module in
:mod:`symjac.quantities` holding one :class:`Quantity`: its derivation, the law by which it moves to a coupled
robot's coordinates, its document (what LaTeX, pretty text and JSON print), its command and options on the command
line, and the codegen function kind that generated modules compute it with. Every front end reads the spec; none
lists the quantities itself.

Entry points are ``"module:function"`` strings, imported on first use (:func:`entry_point`): the command line reads
every spec to build its parser, and ``symjac --version`` must not load SymPy.

A command-line handler gets a :class:`Request` (the parsed options, the robot, and the front end's parsers of
frames, points and values), so a quantity depends on no front end; :mod:`symjac.cli` builds the request.
"""

from __future__ import annotations

import argparse
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
    "LawName",
    "Quantity",
    "Request",
    "entry_point",
]

T = TypeVar("T")

LawName = Literal["columns", "transposed", "congruent", "rates"]
"""The coupling law a quantity follows, by its name in :data:`symjac.kinematics.coupling.COUPLING_LAWS` (where the
laws are written and applied; a test checks the two lists agree, so reading a spec loads no SymPy)."""


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

    def point(self) -> Point:
        """``--point``, parsed (``wrist``, ``tool`` or three coordinates in frame {n})."""
        ...

    def values(self, text: str, length: int, option: str, *, parameters: bool = True) -> list[sp.Expr]:
        """``length`` comma-separated values of ``option`` (numbers, ``pi``, with ``parameters`` their names)."""
        ...

    def progress(self, what: str, compute: Callable[[], T]) -> T:
        """``compute()``, reported as ``deriving {what}`` on a terminal."""
        ...


Handler = Callable[[Request], "Document"]
"""A quantity's command-line handler: the request in, the document to render out."""
Options = Callable[[argparse.ArgumentParser], None]
"""A quantity's argparse hook: adds its own options to its command's parser (the common ones are there already)."""


@dataclass(frozen=True)
class Quantity:
    r"""One derived quantity: what it is, how it is derived, coupled, printed, asked for and generated.

    Attributes
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
    kind : str or None
        The codegen function kind generated modules compute it with (the key of codegen's table of kinds).
    command : str or None
        The ``symjac`` command that prints it; several quantities may share one (``jacobian --derivative``).
    flag : str or None
        Within a shared command, the option (its ``dest``) that selects this quantity; None for the command's
        own quantity, which prints when no flag is given.
    options : Options or None
        Adds the quantity's options to its command's parser (``--frame``, ``--method``, its ``flag``).
    handler : Handler or None
        Turns a :class:`Request` into the document to print.
    """

    name: str
    summary: str
    derivation: str
    coupling: LawName
    document: str | None = None
    kind: str | None = None
    command: str | None = None
    flag: str | None = None
    options: Options | None = None
    handler: Handler | None = None

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
