r"""The numeric inverse-kinematics solver in generated code: which functions it runs on and its joint tables.

A module asked for it (``ModuleRequest(..., numeric_ik=True)``, the c99, cpp and python targets) gets a function
``inverse_kinematics_numeric`` that runs Levenberg-Marquardt with Sugihara's damping, as
:func:`symjac.analysis.inverse_kinematics.numeric.solve_numeric` does, on the module's own forward kinematics and
its first Jacobian in frame {0} with all six rows (which must be at the forward kinematics' point: the default
point, the end of the chain). The solver itself is the runtime section ``ik_numeric`` (``templates/runtime/c99.h``,
``eigen.hpp``, ``python.py``); its emitted wrapper lives in ``templates/c99/ik_numeric.c.j2``,
``templates/cpp/ik_numeric.hpp.j2`` and ``templates/python/ik_numeric.py.j2``.

Seeds are drawn by splitmix64 from the caller's ``seed``, uniformly within the joint limits, in ``[-pi, pi]`` for a
revolute joint without limits (which is also wrapped to ``(-pi, pi]``) and in ``[-1, 1]`` for a prismatic one.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from symjac.codegen.printers import float_literal
from symjac.errors import CodegenError

if TYPE_CHECKING:  # description.py imports this module (through inverse_kinematics.py)
    from symjac.codegen.description import JacobianInfo, ModuleDescription

__all__ = ["NUMERIC_IK_TARGETS", "NumericIkTables", "numeric_ik_jacobian", "numeric_ik_tables"]

NUMERIC_IK_TARGETS = ("c99", "cpp", "python", "numpy", "lambdify", "c", "jax", "casadi")
"""The targets that generate ``inverse_kinematics_numeric`` (jax and casadi: a fixed graph,
:mod:`symjac.codegen.ik_numeric_traced`)."""


def numeric_ik_jacobian(target: str, infos: Sequence[JacobianInfo], coupled: bool) -> str:
    """The name of the Jacobian the solver runs on: the first request in frame {0} with all six rows."""
    if target not in NUMERIC_IK_TARGETS:
        raise CodegenError(f"numeric_ik: the {target} target has no numeric inverse kinematics yet; "
                           f"use one of {', '.join(NUMERIC_IK_TARGETS)}")
    if coupled and target not in ("jax", "casadi"):  # their fixed graphs run on the functions of the coordinates
        raise CodegenError("numeric_ik: a coupled robot's modules have no numeric inverse kinematics yet")
    for info in infos:
        if info.frame == "{0}" and tuple(info.rows) == tuple(range(6)):
            return info.jacobian
    raise CodegenError("numeric_ik needs a Jacobian in frame {0} with all six rows, at the forward kinematics' "
                       "point (the default request); none of the requested Jacobians is one")


@dataclass(frozen=True)
class NumericIkTables:
    """What the templates write: the C names of the functions it runs on, per joint its kind and its seeds' box.

    ``pose_function`` is the forward kinematics, ``velocity_function`` the Jacobian; a joint's kind is 0 for a
    prismatic joint, 1 for a revolute joint with limits (shifted by 2 pi into them), 2 for one without (wrapped).
    """

    pose_function: str
    velocity_function: str
    kind: tuple[str, ...]
    low: tuple[str, ...]
    high: tuple[str, ...]


def numeric_ik_tables(description: ModuleDescription, prefixed: bool = True) -> NumericIkTables | None:
    """The solver's tables for a module that has it (``description.numeric_ik``), else None.

    ``prefixed``: function names start with ``<robot>_`` (C), else they are bare (C++, in the robot's namespace).
    """
    if not description.numeric_ik:
        return None
    kind, low, high = [], [], []
    for entry in description.joint_entries:
        limited = math.isfinite(entry.lower) and math.isfinite(entry.upper)
        wraps = not limited and entry.type != "prismatic"
        span = math.pi if wraps else 1.0
        kind.append("0" if entry.type == "prismatic" else "2" if wraps else "1")
        low.append(float_literal(entry.lower if limited else -span))
        high.append(float_literal(entry.upper if limited else span))
    prefix = f"{description.robot}_" if prefixed else ""
    return NumericIkTables(f"{prefix}forward_kinematics", f"{prefix}{description.numeric_ik}", tuple(kind),
                           tuple(low), tuple(high))
