"""Options several quantities' commands share, and choices read only when argparse needs them."""

from __future__ import annotations

import argparse
from collections.abc import Iterator, Sequence
from importlib import import_module
from typing import overload

__all__ = ["POINT_HELP", "LazyChoices", "frame_and_point_options"]

POINT_HELP = ("tool, flange (the origin of frame {n}; also called wrist), wrist_centre (where the last three axes "
              "meet), or x,y,z in frame {n} (default: the end of the chain, as fk: the tool point if the robot has a "
              "tool, else the flange)")
"""The help of every ``--point`` option: the named points and the one default."""


class LazyChoices(Sequence[str]):
    """An option's choices, read from ``module.name`` only when argparse checks a value or prints them.

    Give the option a ``metavar`` (argparse lists plain choices while it builds the parser) and name the choices
    in its help with ``%(choices)s`` (expanded only for ``--help``). Quantities' options and the
    command line's own (:mod:`symjac.cli.args`) use it.
    """

    def __init__(self, module: str, name: str):
        self.module, self.name = module, name

    def _values(self) -> Sequence[str]:
        return getattr(import_module(self.module), self.name)  # type: ignore[no-any-return]

    @overload
    def __getitem__(self, index: int) -> str: ...
    @overload
    def __getitem__(self, index: slice) -> Sequence[str]: ...
    def __getitem__(self, index: int | slice) -> str | Sequence[str]:
        return self._values()[index]

    def __len__(self) -> int:
        return len(self._values())

    def __iter__(self) -> Iterator[str]:
        return iter(self._values())

    def __contains__(self, value: object) -> bool:
        return value in self._values()


def frame_and_point_options(sub: argparse.ArgumentParser) -> None:
    """``--frame`` and ``--point``, as every quantity at a point of the arm takes them."""
    sub.add_argument("--frame", default="0", help="frame to express it in: 0..n, world or tool (default 0)")
    sub.add_argument("--point", default=None, help=POINT_HELP)
    sub.add_argument("--link", type=int, default=None, metavar="K",
                     help="a point fixed in link K (0 the base .. n): --point is then x,y,z in frame {K} (default its "
                          "origin)")
