"""The numeric inverse kinematics of the NumPy-family targets (numpy, lambdify, c), as module text.

Their ``inverse_kinematics_numeric(pose, seed=0, start=None, **parameters) -> (q, found, iterations)`` runs the
NumPy runtime's solver (section ``ik_numeric`` of ``templates/runtime/numpy.py``: the python runtime's
Levenberg-Marquardt, the same seeds and steps, in NumPy) on the module's own forward kinematics and Jacobian; the
template ``templates/ik/numeric_numpy.py.j2`` lays out the joint tables
(:func:`~symjac.codegen.ik_numeric.numeric_ik_tables`) and the function.
"""

from __future__ import annotations

from symjac.codegen.description import ModuleDescription
from symjac.codegen.ik_numeric import numeric_ik_tables
from symjac.resources import render_template

__all__ = ["NUMPY_FAMILY", "numpy_numeric_ik"]

NUMPY_FAMILY = ("numpy", "lambdify", "c")
"""The targets whose modules carry the NumPy runtime, and with it this solver."""


def numpy_numeric_ik(description: ModuleDescription) -> str:
    """``inverse_kinematics_numeric`` and its tables as module text, or nothing for a module without it."""
    tables = numeric_ik_tables(description, prefixed=False)
    if tables is None or description.target not in NUMPY_FAMILY:
        return ""
    return render_template("ik/numeric_numpy.py.j2", ik=tables)
