"""Symbolic inertial data as robot parameters: ``m{i}``, ``cx{i}``, ``Ixx{i}``, ... with numeric defaults."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.inertia import Inertial, symbolic_inertial
from symjac.model.robot import Parameter, Robot

__all__ = ["PLACEHOLDER", "placeholder_defaults", "symbolic_links", "symbolic_where_missing", "with_symbolic_inertials"]

PLACEHOLDER = Inertial(1, inertia=sp.eye(3))
"""The defaults of a link's symbolic inertial parameters where no numbers are known: unit mass at the origin of its
frame, unit principal moments. A stand-in that keeps generated code and numeric checks physical, not a model."""


def with_symbolic_inertials(robot: Robot, values: Sequence[Inertial | None] | None = None,
                            links: Sequence[int] | None = None) -> Robot:
    """``robot`` with symbolic inertial data (``m{i}``, ``cx{i}``, ``Ixx{i}``, ...) on ``links`` (default: every link).

    Each symbol becomes a :class:`Parameter` whose default is the matching entry of ``values[i - 1]`` (numeric
    inertial data in frame {i}, about the centre of mass; without ``values``, the robot's own data where it is numeric
    once its parameters take their defaults, as the catalog's PUMA 560 and Panda carry; None gives the
    :data:`PLACEHOLDER`), so derivations stay symbolic and numbers are used only where asked. The parameters are
    marked :attr:`~symjac.model.robot.Parameter.inertial`. A link whose data are these symbols already keeps them.

    Examples
    --------
    >>> from symjac import load_robot
    >>> arm = with_symbolic_inertials(load_robot("planar2r"))
    >>> arm.inertials[1].mass, arm.defaults[arm.inertials[1].mass]
    (m2, 1)
    >>> puma = with_symbolic_inertials(load_robot("puma560"))  # its published data as the defaults
    >>> puma.defaults[puma.inertials[1].mass]
    87/5
    """
    chosen = range(1, robot.n_joints + 1) if links is None else links
    given = list(values) if values is not None else [_numeric(inertial, robot) for inertial in robot.inertials]
    inertials = list(robot.inertials)
    parameters = list(robot.parameters)
    taken = {parameter.name for parameter in parameters}
    for link in chosen:
        symbolic = symbolic_inertial(link)
        known = inertials[link - 1]
        if known is not None and _same_symbols(known, symbolic):
            continue  # symbolic already (a catalog file's ``inertials = "symbolic"``): its defaults stay
        default = given[link - 1] or PLACEHOLDER
        pairs = [(symbolic.mass, default.mass), *zip(symbolic.com, default.com, strict=True),
                 *((symbolic.inertia[i, j], default.inertia[i, j]) for i in range(3) for j in range(i, 3))]
        for symbol, value in pairs:
            if symbol.name in taken:
                raise RobotFileError(f"link {link}: the parameter {symbol.name} exists already", source=robot.source,
                                     joint=link, field="inertial")
            if not value.is_number:
                raise RobotFileError(f"link {link}: the default of {symbol.name} must be a number, got {value}",
                                     source=robot.source, joint=link, field="inertial")
            parameters.append(Parameter(symbol.name, sp.nsimplify(value, rational=True), inertial=True))
        # defaults kept as published keep the link's word for it (the PUMA 560's link 3)
        inertials[link - 1] = replace(symbolic, keep_impossible=default.keep_impossible)
    return replace(robot, parameters=tuple(parameters), inertials=tuple(inertials))


def symbolic_where_missing(robot: Robot) -> Robot:
    """``robot`` with symbolic inertial parameters on every link without data (a file's ``inertials = "symbolic"``).

    A parameter the robot already has under one of their names gives its default, the others default to the
    :data:`PLACEHOLDER`. Every parameter named so (``m<i>``, ``cx<i>`` .. ``Izz<i>`` of any
    link) is marked :attr:`~symjac.model.robot.Parameter.inertial`, also where data in other frames use them.

    Examples
    --------
    >>> from symjac import load_robot
    >>> arm = load_robot("planar2r")  # its file says inertials = "symbolic"
    >>> [p.name for p in arm.parameters if p.inertial][:4], arm.inertials[1].mass
    (['m1', 'cx1', 'cy1', 'cz1'], m2)
    """
    missing = [link for link, inertial in enumerate(robot.inertials, start=1) if inertial is None]
    given = {parameter.name: parameter.default for parameter in robot.parameters}
    values: list[Inertial | None] = [None] * robot.n_joints
    names: set[str] = set()
    for link in missing:
        symbolic = symbolic_inertial(link)
        entries = _entries(symbolic)
        names |= {str(entry) for entry in entries}
        placeholder = placeholder_defaults([link])
        defaults = {entry: given.get(str(entry), placeholder[str(entry)]) for entry in entries}
        values[link - 1] = Inertial(defaults[symbolic.mass], tuple(c.xreplace(defaults) for c in symbolic.com),
                                    sp.ImmutableMatrix(symbolic.inertia.xreplace(defaults)))  # type: ignore[arg-type]
    kept = tuple(parameter for parameter in robot.parameters if parameter.name not in names)
    robot = with_symbolic_inertials(replace(robot, parameters=kept), values, links=missing)
    # names of the pattern stay inertial where data of converted frames spell them out (com = ["L1 + cx1", ...])
    order = {str(entry): k for k, entry in enumerate(
        entry for link in range(1, robot.n_joints + 1) for entry in _entries(symbolic_inertial(link)))}
    geometric = [parameter for parameter in robot.parameters if parameter.name not in order]
    inertial = sorted((replace(parameter, inertial=True) for parameter in robot.parameters
                       if parameter.name in order), key=lambda parameter: order[parameter.name])
    return replace(robot, parameters=(*geometric, *inertial))  # link by link, whatever order a file gave


def placeholder_defaults(links: Sequence[int]) -> dict[str, sp.Expr]:
    """The placeholder default of every symbolic inertial parameter of ``links``, by name (``{"m2": 1, ...}``)."""
    return {str(entry): value for link in links
            for entry, value in zip(_entries(symbolic_inertial(link)), _entries(PLACEHOLDER), strict=True)}


def _entries(inertial: Inertial) -> list[sp.Expr]:
    """Mass, centre, then the tensor's upper triangle row by row: the parameters' order."""
    return [inertial.mass, *inertial.com, *(inertial.inertia[i, j] for i in range(3) for j in range(i, 3))]


def symbolic_links(robot: Robot) -> list[int]:
    """The links whose inertial data are their own symbolic parameters (a file leaves their tables out)."""
    inertial = {parameter.name for parameter in robot.parameters if parameter.inertial}
    return [link for link, data in enumerate(robot.inertials, start=1)
            if data is not None and _same_symbols(data, symbolic_inertial(link))
            and {str(s) for s in _entries(data)} <= inertial]


def _same_symbols(inertial: Inertial, symbolic: Inertial) -> bool:
    return (inertial.mass == symbolic.mass and inertial.com == symbolic.com
            and sp.ImmutableMatrix(inertial.inertia) == sp.ImmutableMatrix(symbolic.inertia))


def _numeric(inertial: Inertial | None, robot: Robot) -> Inertial | None:
    """``inertial`` with the robot's parameters at their defaults, if that makes every entry a number, else None."""
    if inertial is None:
        return None
    defaults = robot.defaults
    mass, com = inertial.mass.xreplace(defaults), tuple(c.xreplace(defaults) for c in inertial.com)
    tensor = sp.ImmutableMatrix(inertial.inertia.xreplace(defaults))
    if not all(entry.is_number for entry in (mass, *com, *tensor)):
        return None
    return Inertial(mass, com, tensor, keep_impossible=inertial.keep_impossible)  # type: ignore[arg-type]
