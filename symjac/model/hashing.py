"""A frozen dataclass's hash, computed once per live instance: ``__hash__ = cached_hash`` in the class body.

Every cached derivation finds its chain by the robot's hash (:func:`symjac.kinematics.chain.chain_of`), and hashing a
robot's whole tree of joints and expressions again cost about 4 us a call. The value is kept outside the instance, by
``id`` and dropped with it, so that a pickled robot never carries a hash made under another process's hash seed.
"""

from __future__ import annotations

import weakref
from dataclasses import fields
from typing import Any

__all__ = ["cached_hash"]

_HASHES: dict[int, int] = {}
"""Each live instance's hash, by ``id``."""


def cached_hash(instance: Any) -> int:
    """The hash of ``instance``'s compared fields (what ``dataclass(frozen=True)`` computes), kept while it lives.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Pair:
    ...     a: int
    ...     b: str
    ...     __hash__ = cached_hash
    >>> hash(Pair(1, "x")) == hash((1, "x"))
    True
    """
    key = id(instance)
    value = _HASHES.get(key)
    if value is None:
        value = _HASHES[key] = hash(tuple(getattr(instance, f.name) for f in fields(instance) if f.compare))
        weakref.finalize(instance, _HASHES.pop, key, None)
    return value
