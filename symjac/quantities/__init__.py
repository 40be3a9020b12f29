r"""Derived quantities as plug-ins: one module per quantity, each holding one :class:`~.spec.Quantity`.

A quantity's spec names its derivation, the coupling law that moves it to a coupled robot's coordinates, its
document (LaTeX, pretty text and JSON all print that document), its ``symjac`` command and options, and what
generated modules compute it with (a :class:`~.spec.Generated` kind). The command line builds its per-quantity
commands from :data:`QUANTITIES`, code generation its table of kinds and the functions of every module; nothing else
lists them.

Adding a quantity is one module here with a ``QUANTITY`` and its name in :data:`MEMBERS`, nothing more. Importing this
package loads no SymPy: entry points are imported when called.

Examples
--------
>>> QUANTITIES["jacobian"].coupling
'columns'
>>> [q.name for q in QUANTITIES.values() if q.command == "jacobian"]
['jacobian', 'bias_acceleration']
"""

from __future__ import annotations

from collections.abc import Mapping
from importlib import import_module
from types import MappingProxyType

from symjac.quantities.spec import Generated, LawName, Quantity

__all__ = ["MEMBERS", "QUANTITIES", "Generated", "LawName", "Quantity"]

MEMBERS = ("forward_kinematics", "jacobian", "hessian", "bias_acceleration", "joint_torques", "manipulability",
           "inverse_dynamics", "mass_matrix", "coriolis_matrix", "gravity_torques", "regressor", "base_regressor",
           "inverse_kinematics")
"""The quantity modules, in the order the command line lists their commands and generated modules their functions
(within a Jacobian request, those that need ``acceleration`` after the others)."""


def _registry() -> Mapping[str, Quantity]:
    quantities = [import_module(f"{__name__}.{member}").QUANTITY for member in MEMBERS]
    return MappingProxyType({quantity.name: quantity for quantity in quantities})


QUANTITIES: Mapping[str, Quantity] = _registry()
"""Every quantity by name, in :data:`MEMBERS` order."""
