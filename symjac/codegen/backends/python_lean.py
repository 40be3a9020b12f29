"""The ``"python_lean"`` target (worked example): the python target's functions under a shorter module docstring."""

from __future__ import annotations

from symjac.codegen.backends.python import python_function
from symjac.codegen.description import Backend

__all__ = ["BACKEND"]

BACKEND = Backend(
    name="python_lean",
    order=4,
    summary="standard library, lean docstring",
    template="python_lean_module.py.j2",
    title="Kinematics and Jacobians in plain Python (worked example of a new target)",
    description="Each function takes one configuration as a sequence of floats and returns floats or nested tuples.",
    nan_policy="Wrong lengths raise ValueError; NaN inputs propagate to NaN outputs.",
    emit=python_function,
    batched=False,
    imports=("pi", "sqrt"),
)
