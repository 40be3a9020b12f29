"""The numeric inverse kinematics of the traced targets (jax, casadi), as module text.

Their modules are graphs of fixed shape: the solver runs a fixed number of Levenberg-Marquardt steps from a fixed
number of starts, side by side, instead of the other targets' loops that stop and restart on the data.

- jax: ``inverse_kinematics_numeric(pose, seed=0, start=None, *, starts, iterations, tolerance, **parameters) ->
  (q, found, steps)`` runs the runtime section ``ik_numeric`` of ``templates/runtime/jax.py``
  (``jax.lax.fori_loop`` inside ``jax.vmap`` over the starts) on the module's own forward kinematics and Jacobian;
  ``jit`` and ``vmap`` compose with it. Template ``templates/ik/numeric_jax.py.j2``.
- casadi: ``inverse_kinematics_numeric(pose, start, p) -> (q, found, error)``, a ``casadi.Function`` built from
  CasADi's own tools (section ``ik_numeric`` of ``templates/runtime/casadi.py``, template
  ``templates/ik/numeric_casadi.py.j2``): one damped step as an SX function of the module's own functions, repeated
  by ``Function.fold`` and run from every start by ``Function.map``. It stays a plain expression graph as every other
  function of the module: differentiable, callable on MX inside ``casadi.Opti`` or an optimal-control problem, and
  written to C by ``Function.generate()`` with no solver plugin, with a cost fixed in advance (a real-time loop
  needs that). ``nlpsol``/``rootfinder`` would give a solve whose steps depend on the data, an IPOPT plugin that
  ``generate()`` cannot export, and (``rootfinder``) only square systems.
"""

from __future__ import annotations

from symjac.codegen.description import ModuleDescription
from symjac.codegen.ik_numeric import numeric_ik_tables
from symjac.resources import render_template

__all__ = ["TRACED_ITERATIONS", "TRACED_STARTS", "TRACED_TARGETS", "traced_numeric_ik"]

TRACED_TARGETS = ("jax", "casadi")
"""The targets whose numeric inverse kinematics is a fixed graph."""

TRACED_STARTS = {"jax": 16, "casadi": 16}
"""The default number of starts, computed side by side (jax: ``vmap``; casadi: ``Function.map`` of the folded step).
Measured on 200 random reachable poses per arm (casadi, 40 steps): 8 starts solved 96.5% (PUMA 560), 99% (UR5),
98.5% (Panda); 16 starts 98.5%, 100%, 99.5%."""

TRACED_ITERATIONS = {"jax": 64, "casadi": 40}
"""The default number of steps per start."""


def traced_numeric_ik(description: ModuleDescription) -> str:
    """``inverse_kinematics_numeric`` and its tables as module text, or nothing for a module without it."""
    tables = numeric_ik_tables(description, prefixed=False)
    if tables is None or description.target not in TRACED_TARGETS:
        return ""
    target = description.target
    return render_template(f"ik/numeric_{target}.py.j2", ik=tables, starts=TRACED_STARTS[target],
                           iterations=TRACED_ITERATIONS[target], n=len(tables.kind))
