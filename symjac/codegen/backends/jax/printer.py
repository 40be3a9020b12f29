"""The jax target's printer: ``jax.numpy`` functions (``jnp.sin``), arithmetic as in the python target."""

from __future__ import annotations

from symjac.codegen.backends.python.printer import PythonPrinter

__all__ = ["JaxPrinter"]


class JaxPrinter(PythonPrinter):
    """``jnp.sin``, ``jnp.cos``, ``jnp.sqrt`` on traced arrays; numbers stay Python floats.

    Python floats are weakly typed: results follow the dtype of ``q`` (float32 by default, float64 with
    ``jax_enable_x64``), and ``vmap`` does not broadcast constant entries.
    """

    _function_prefix = "jnp."
