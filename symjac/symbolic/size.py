"""How large a symbolic result may grow before symjac refuses to write it out.

Normal forms (:mod:`symjac.symbolic.trigpoly`) count their terms as they are built; past the limit in force they raise
:class:`~symjac.errors.ResultTooLargeError` at once instead of working for minutes on something nobody can read.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["TERM_LIMIT", "current_term_limit", "limit_lowered", "term_limit"]

TERM_LIMIT = 200_000
"""The most terms the normal forms of one result may have together (and any intermediate on its own).

Past it, :func:`symjac.symbolic.trigpoly.image_of` and :func:`symjac.symbolic.trigpoly.product_image` raise
:class:`~symjac.errors.ResultTooLargeError` at once. A result that large is millions of operations once written
out: nobody reads it, SymPy takes minutes to build it, and it usually means a quantity that grows exponentially
with the chain (the frame-{0} Jacobian of a 20-joint snake). Raw forms (``simplify=False``) and generated code
share subexpressions and have no such limit.
"""

_budget: ContextVar[int | None] = ContextVar("symjac_term_budget", default=None)


@contextmanager
def term_limit(limit: int) -> Iterator[None]:
    """Within the block, refuse results past ``limit`` terms as well as past :data:`TERM_LIMIT` (the lower wins).

    Code generation tries its compact candidates this way: past a few ten thousand terms a compact form costs more
    time to derive than it can save in the generated code. Context-local, so threads and nested blocks keep theirs.
    """
    current = _budget.get()
    token = _budget.set(limit if current is None else min(limit, current))
    try:
        yield
    finally:
        _budget.reset(token)


def current_term_limit() -> int:
    """The term limit in force here: :data:`TERM_LIMIT`, or a lower one set by :func:`term_limit`."""
    budget = _budget.get()
    return TERM_LIMIT if budget is None else min(budget, TERM_LIMIT)


def limit_lowered() -> bool:
    """Whether a :func:`term_limit` block is in force here (code generation trying a compact form within a budget)."""
    return _budget.get() is not None

