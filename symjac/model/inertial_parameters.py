"""Symbolic inertial data as robot parameters: ``m{i}``, ``cx{i}``, ``Ixx{i}``, ... with numeric defaults."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.inertia import Inertial, symbolic_inertial
from symjac.model.robot import Parameter, Robot

__all__ = ["with_symbolic_inertials"]


def with_symbolic_inertials(robot: Robot, values: Sequence[Inertial | None] | None = None,
                            links: Sequence[int] | None = None) -> Robot:
    """``robot`` with symbolic inertial data (``m{i}``, ``cx{i}``, ``Ixx{i}``, ...) on ``links`` (default: every link).

    Each symbol becomes a :class:`Parameter` whose default is the matching entry of ``values[i - 1]`` (numeric
    inertial data in frame {i}, about the centre of mass; without ``values``, the robot's own data where it is numeric
    once its parameters take their defaults, as the catalog's PUMA 560 and Panda carry; None gives the placeholder of
    unit mass at the origin of {i} with unit principal moments), so derivations stay symbolic and numbers are used
    only where asked.

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
        default = given[link - 1] or Inertial(1, inertia=sp.eye(3))
        symbolic = symbolic_inertial(link)
        pairs = [(symbolic.mass, default.mass), *zip(symbolic.com, default.com, strict=True),
                 *((symbolic.inertia[i, j], default.inertia[i, j]) for i in range(3) for j in range(i, 3))]
        for symbol, value in pairs:
            if symbol.name in taken:
                raise RobotFileError(f"link {link}: the parameter {symbol.name} exists already", source=robot.source,
                                     joint=link, field="inertial")
            if not value.is_number:
                raise RobotFileError(f"link {link}: the default of {symbol.name} must be a number, got {value}",
                                     source=robot.source, joint=link, field="inertial")
            parameters.append(Parameter(symbol.name, sp.nsimplify(value, rational=True)))
        # defaults kept as published keep the link's word for it (the PUMA 560's link 3)
        inertials[link - 1] = replace(symbolic, keep_impossible=default.keep_impossible)
    return replace(robot, parameters=tuple(parameters), inertials=tuple(inertials))


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
