"""The commands of the derived quantities, built from their specs (:data:`symjac.quantities.QUANTITIES`).

Each command is one quantity's, or shared by several (``jacobian`` and ``jacobian --derivative``): its parser gets
the common options of a printed result (:func:`~symjac.cli.options.result_options`), then each quantity's own, and
its handler loads the robot and hands a :class:`CommandRequest` to the quantity the options select.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

from symjac.cli.args import configuration_values, load, parse_frame, parse_point, parse_values
from symjac.cli.options import result_options
from symjac.cli.output import note_if_large, progress
from symjac.model.ends import end_point
from symjac.quantities import QUANTITIES, Quantity

if TYPE_CHECKING:
    import sympy as sp

    from symjac.kinematics.chain import Frame
    from symjac.kinematics.jacobian import Point
    from symjac.model.robot import Robot
    from symjac.printing.document import Document

__all__ = ["CommandRequest", "quantity_commands", "selected"]

T = TypeVar("T")


@dataclass(frozen=True)
class CommandRequest:
    """A :class:`symjac.quantities.spec.Request` from the command line: the options parsed by :mod:`.args`."""

    args: argparse.Namespace
    robot: Robot

    @property
    def digits(self) -> int | None:
        """``--numeric``: the significant digits of the printed numbers (``--digits``, default DIGITS); else None."""
        if not self.args.numeric:
            return None
        from symjac.printing.latex import DIGITS

        return self.args.digits or DIGITS  # type: ignore[no-any-return]

    def frame(self) -> Frame:
        """``--frame``, parsed."""
        return parse_frame(self.args.frame)

    def point(self) -> Point | None:
        """``--point``, parsed; not given, None: the end of the chain, or with ``--link`` the origin of that link."""
        if self.args.point is None:
            return None
        return parse_point(self.args.point, self.robot)

    def point_name(self) -> str:
        """``--point`` as typed, else ``origin`` with ``--link``, else the end of the chain's name."""
        if self.args.point is not None:
            return self.args.point  # type: ignore[no-any-return]
        return "origin" if self.link() is not None else end_point(self.robot)

    def link(self) -> int | None:
        """``--link``, or None (the option is not given, or the command has none)."""
        return getattr(self.args, "link", None)  # type: ignore[no-any-return]

    def values(self, text: str, length: int, option: str, *, parameters: bool = True) -> list[sp.Expr]:
        """``length`` comma-separated values of ``option``."""
        return parse_values(text, length, option, self.robot, parameters=parameters)

    def configuration(self, text: str, option: str = "--q") -> list[sp.Expr]:
        """A configuration, as every command's ``--q`` reads it (``30deg``, ``pi/4``, numbers in the file's unit)."""
        return configuration_values(text, self.robot, option)

    def progress(self, what: str, compute: Callable[[], T]) -> T:
        """``compute()``, its progress shown on a terminal."""
        return progress(what, compute)  # type: ignore[no-any-return]


def selected(group: list[Quantity], args: argparse.Namespace) -> Quantity:
    """The quantity of a command the options ask for: the first whose flag is given, else the command's own."""
    for quantity in group:
        if quantity.flag is not None and getattr(args, quantity.flag):
            return quantity
    return _own(group)


def quantity_commands() -> dict[str, tuple[Callable[[argparse.Namespace], Document], str,
                                           Callable[[argparse.ArgumentParser, str], None]]]:
    """Each command that prints a quantity: its handler, its one-line help and its options (as ``COMMANDS``)."""
    groups: dict[str, list[Quantity]] = {}
    for quantity in QUANTITIES.values():
        if quantity.command is not None:
            groups.setdefault(quantity.command, []).append(quantity)
    return {name: (_handler(group), _own(group).summary, _options(group)) for name, group in groups.items()}


def _own(group: list[Quantity]) -> Quantity:
    """The command's own quantity: the one no flag selects."""
    return next(quantity for quantity in group if quantity.flag is None)


def _handler(group: list[Quantity]) -> Callable[[argparse.Namespace], Document]:
    def handle(args: argparse.Namespace) -> Document:
        """Load the robot, then let the selected quantity derive and build its document."""
        quantity = selected(group, args)
        robot = load(args)
        note_if_large(robot.name, robot.n_joints)
        assert quantity.handler is not None  # a spec with a command has one
        return quantity.handler(CommandRequest(args, robot))

    return handle


def _options(group: list[Quantity]) -> Callable[[argparse.ArgumentParser, str], None]:
    def add(sub: argparse.ArgumentParser, name: str) -> None:
        """The options of a printed result, then each quantity's own."""
        result_options(sub, name)
        for quantity in group:
            if quantity.options is not None:
                quantity.options(sub)

    return add
