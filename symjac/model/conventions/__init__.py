"""Conventions as plug-ins: each registered :class:`~symjac.model.robot.Convention` value and the object that knows it.

A plug-in (:class:`~symjac.model.conventions.base.ConventionPlugin`) turns its joints into the one internal joint form
the chain works from (:class:`~symjac.model.conventions.base.JointForm`), and tells the robot-file reader and writer,
the table printers and the converter what they need. A new convention is one module in this folder (with a
``PLUGIN``) and its name in :data:`MEMBERS`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from importlib import import_module
from typing import Any

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.conventions.base import ConventionPlugin, JointForm, moved_inertial
from symjac.model.inertia import Inertial
from symjac.model.robot import Convention, Robot
from symjac.symbolic.transforms import Composition, homogeneous, inverse_transform

__all__ = ["MEMBERS", "PLUGINS", "carried_inertials", "convention_named", "file_inertials", "home_frames",
           "joint_forms", "plugin", "with_file_inertials"]

MEMBERS: tuple[str, ...] = ("standard", "modified", "general", "poe")
"""The modules of this folder that are conventions, each with a ``PLUGIN``; a new convention adds its name here."""

PLUGINS: dict[Convention, ConventionPlugin] = {
    spec.convention: spec for spec in (import_module(f"{__name__}.{name}").PLUGIN for name in MEMBERS)}
"""Every convention symjac reads, by its value, in the order error messages list them."""


def plugin(convention: Convention | str) -> ConventionPlugin:
    """The plug-in of ``convention`` (a ``ValueError`` listing the registered ones if there is none)."""
    if convention in PLUGINS:
        return PLUGINS[convention]  # type: ignore[index]
    raise ValueError(f"{convention!r} is not a registered convention: {_choices()}")


def convention_named(data: Mapping[str, Any], source: str) -> Convention:
    """The registered convention a robot description names in its ``convention`` field (one-line error otherwise)."""
    if "convention" not in data:
        raise RobotFileError(f"'convention' is required (there is no default): say {_choices()}", source=source,
                             field="convention")
    text = data["convention"]
    if not isinstance(text, str) or text not in PLUGINS:
        raise RobotFileError(f"'convention' is required and must be {_choices()}, got {text!r}", source=source,
                             field="convention")
    return Convention(text)


def joint_forms(robot: Robot) -> tuple[JointForm, ...]:
    """Each joint of ``robot`` in the internal form, by its convention's plug-in."""
    return plugin(robot.convention).forms(robot)


def _choices() -> str:
    names = [f"'{name}'" for name in PLUGINS]
    return ", ".join(names[:-1]) + f" or {names[-1]}" if len(names) > 1 else names[0]


def _exact(expr: sp.Expr) -> sp.Expr:
    expr = sp.radsimp(sp.expand(expr))
    return sp.trigsimp(expr) if expr.has(sp.sin, sp.cos) else expr


def with_file_inertials(robot: Robot, inertials: Sequence[Inertial | None]) -> Robot:
    r"""``robot`` with link *i*'s inertial data given in the frame its convention's robot files use.

    That frame is frame {i} for both DH conventions, the joint's child link frame (the one ``xyz``/``rpy`` place,
    before the axis alignment: URDF's link frame) for general joints, and for the product of exponentials the frame
    the screws are written in ({s}, or {b} with ``body = true``) at home. With :math:`T` its pose in {i}
    (:meth:`~symjac.model.conventions.base.ConventionPlugin.inertial_frames`), :math:`c_i = R c + p`,
    :math:`I_i = R I R^T`.
    """
    frames = plugin(robot.convention).inertial_frames(robot)
    moved = tuple(moved_inertial(inertial, T) for inertial, T in zip(inertials, frames, strict=True))
    return replace(robot, inertials=moved)


def file_inertials(robot: Robot) -> tuple[Inertial | None, ...]:
    """Each link's inertial data in the frame its convention's files use (inverse of :func:`with_file_inertials`)."""
    frames = plugin(robot.convention).inertial_frames(robot)
    return tuple(moved_inertial(inertial, None if T is None else inverse_transform(sp.Matrix(T)))
                 for inertial, T in zip(robot.inertials, frames, strict=True))


def home_frames(robot: Robot) -> tuple[sp.Matrix, ...]:
    """The world poses of frames {1} .. {n} with every joint variable zero (the base transform included)."""
    composition = Composition().then([sp.Matrix(robot.base.matrix)] if robot.base is not None else [])
    zero = dict.fromkeys(robot.joint_variables, sp.S.Zero)
    frames = []
    for form in joint_forms(robot.uncoupled):
        composition = composition.then(form.motions)
        R, p = composition.result()
        frames.append(homogeneous(R, p).xreplace(zero).applyfunc(_exact))
    return tuple(frames)


def carried_inertials(source: Robot, result: Robot) -> Robot:
    """``result`` (``source`` converted to another convention) with ``source``'s inertial data in its own frames.

    Frames {i} of both are fixed to link *i*, so :math:`{}^{i'}T_{i} = H'^{-1}_i H_i` from their world poses at zero
    joint values is constant. A result whose parameters took their defaults gets inertial data with defaults too.
    """
    if all(inertial is None for inertial in source.inertials):
        return result
    kept = set(result.parameter_symbols)
    lost = {symbol: value for symbol, value in source.defaults.items() if symbol not in kept}
    inertials = []
    for inertial, old, new in zip(source.inertials, home_frames(source), home_frames(result), strict=True):
        T = (inverse_transform(new) * old).applyfunc(_exact)
        moved = moved_inertial(inertial, None if T.equals(sp.eye(4)) else T)
        if moved is not None and lost:
            moved = Inertial(moved.mass.xreplace(lost), tuple(c.xreplace(lost) for c in moved.com),
                             moved.inertia.xreplace(lost), moved.given_about, moved.keep_impossible)
        inertials.append(moved)
    return replace(result, inertials=tuple(inertials))
