r"""One way to keep a derived quantity in its chain: the :func:`memoized` decorator.

Every quantity symjac derives from a robot (a Jacobian in some frame at some point, a determinant on some rows, a
compiled numeric function) is computed once per :class:`~symjac.kinematics.chain.Chain` and per set of arguments.
A memoized function takes the chain as its first parameter; its callers may pass a Robot or a Chain, positionally or
as ``robot=`` (:func:`~symjac.kinematics.chain.as_chain` finds the chain). Before the value is looked up, the
arguments named in the decorator are normalised against the chain, so that requests for the same quantity share one
entry (frame ``3`` and ``numpy.int64(3)``; point ``"wrist"`` and ``(0, 0, 0)``) and invalid ones fail before anything
is derived. The key is a :class:`~symjac.kinematics.chain.MemoKey`: the function itself and its normalised arguments
in signature order, never a string.

It is also the one place a coupling is applied (:mod:`symjac.kinematics.coupling`): a function that names its law
(``coupling="columns"``) is derived, for a robot that couples joints, on the chain of its joints (kept there) and
moved to the coordinates by that law; the function itself never sees a coupled chain.

Examples
--------
>>> from symjac import load_robot
>>> from symjac.kinematics.chain import Chain
>>> calls = []
>>> @memoized(frame=frame_of)
... def origin(chain: Chain, frame=0):
...     calls.append(frame)
...     return chain.transform(0, frame)[:3, 3]
>>> chain = Chain(load_robot("planar2r"))
>>> origin(chain, 1) is origin(chain, frame=chain.n_joints - 1)  # derived once, whichever way the frame is given
True
>>> calls
[1]
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Collection
from typing import Any, Concatenate, ParamSpec, TypeVar

from symjac.errors import ArgumentError, ResultTooLargeError
from symjac.kinematics.chain import Chain, Frame, MemoKey, as_chain
from symjac.kinematics.coupling import CouplingLaw, LawName, coupling_law
from symjac.model.robot import Robot
from symjac.symbolic.size import limit_lowered

P = ParamSpec("P")
R = TypeVar("R")

__all__ = ["frame_of", "memoized", "one_of"]


def frame_of(chain: Chain, frame: Frame) -> Frame:
    """``frame`` validated and in its canonical form (``numpy.int64(3)`` becomes ``3``)."""
    return chain.frame_name(chain.position(frame))


def one_of(choices: Collection[str], what: str = "method") -> Callable[[Chain, str], str]:
    """A normaliser that accepts only ``choices`` and otherwise names them in an :class:`ArgumentError`."""
    def check(chain: Chain, value: str) -> str:
        if value not in choices:
            raise ArgumentError(f"unknown {what} {value!r}; choose one of {', '.join(choices)}")
        return value

    return check


def memoized(
    *, fresh: Callable[[Any], Any] | None = None, coupling: LawName | None = None, layout: str | int | None = None,
    **normalisers: Callable[..., Any],
) -> Callable[[Callable[Concatenate[Chain, P], R]], Callable[Concatenate[Robot | Chain, P], R]]:
    """Keep ``function(chain, ...)`` in ``chain`` under a :class:`~symjac.kinematics.chain.MemoKey`, derived once.

    Parameters
    ----------
    fresh : callable, optional
        Applied to the kept value on every call, e.g. ``sympy.Matrix`` to hand each caller its own mutable copy of a
        kept immutable matrix.
    coupling : "columns", "transposed", "congruent" or "rates", optional
        The quantity's coupling law (:data:`symjac.kinematics.coupling.COUPLING_LAWS`). With it, a coupled robot's
        value is the function's value on :attr:`Chain.joint_chain <symjac.kinematics.chain.Chain.joint_chain>`
        (same arguments) moved by the law; ``function`` is then only ever called with an uncoupled chain. Without
        it the function handles couplings itself. The law is kept as the wrapper's ``coupling_law`` attribute.
    layout : str or int, optional
        Where the law lays its result out again when the function's ``simplify`` argument is true (or it has none):
        the name of the argument that holds the frame (``"frame"``), or a fixed frame number.
    **normalisers
        One per argument that needs it, named like the argument: called as ``normalise(chain, value, *others)``
        where ``others`` are the arguments named by the normaliser's further parameters (already normalised when
        their normaliser comes earlier in this call). The result replaces the argument, in the key and in the call.
        Every argument must end up hashable.
    """
    law = None if coupling is None else coupling_law(coupling)

    def decorate(function: Callable[Concatenate[Chain, P], R]) -> Callable[Concatenate[Robot | Chain, P], R]:
        first, *rest = inspect.signature(function).parameters.values()
        names = [parameter.name for parameter in rest]
        if "robot" in names:
            raise TypeError(f"memoized {function.__name__}() may not name a later argument 'robot': its first one, "
                            "the chain, is called 'robot' by callers")
        # What callers see: the chain argument named ``robot`` (positional or by keyword), the others unchanged.
        public = inspect.signature(function).replace(
            parameters=[first.replace(name="robot", annotation="Robot | Chain"), *rest])
        needs = {name: _other_arguments(normalise, names, function.__name__, name)
                 for name, normalise in normalisers.items()}

        def kept(*args: Any, **kwargs: Any) -> R:
            """The value kept in the chain (not yet ``fresh``)."""
            bound = public.bind(*args, **kwargs)
            bound.apply_defaults()
            arguments = bound.arguments
            chain = arguments["robot"] = as_chain(arguments["robot"])
            for name, normalise in normalisers.items():
                arguments[name] = normalise(chain, arguments[name], *(arguments[other] for other in needs[name]))
            key = MemoKey(function, tuple(arguments[name] for name in names))
            if law is not None and chain.joint_chain is not chain:
                return chain.memo(key, lambda: _coupled(law, chain, kept, bound, layout))
            # ``robot`` comes first and is not keyword-only: bound.args[0] passes the chain positionally.
            return chain.memo(key, lambda: function(*bound.args, **bound.kwargs))

        @functools.wraps(function)
        def wrapper(*args: Any, **kwargs: Any) -> R:
            try:
                value = kept(*args, **kwargs)
            except ResultTooLargeError:
                # written out, the result would be too large: the same quantity from the robot's nested chain
                bound = public.bind(*args, **kwargs)
                chain = as_chain(bound.arguments["robot"])
                if chain.nested or limit_lowered() or not bound.arguments.get("simplify", True):
                    raise
                bound.arguments["robot"] = chain.nested_twin
                value = kept(*bound.args, **bound.kwargs)
            return value if fresh is None else fresh(value)

        wrapper.__signature__ = public  # type: ignore[attr-defined]
        wrapper.coupling_law = law  # type: ignore[attr-defined]  # read by whoever lists the quantities
        return wrapper

    return decorate


def _coupled(law: CouplingLaw, chain: Chain, kept: Callable[..., Any], bound: inspect.BoundArguments,
             layout: str | int | None) -> Any:
    """The value for a coupled chain: the same request on its joint chain (kept there), moved by ``law``."""
    arguments = bound.arguments
    joints = kept(chain.joint_chain, *bound.args[1:], **bound.kwargs)
    laid_out = arguments.get("simplify", True) and layout is not None
    return law(chain, joints, (arguments[layout] if isinstance(layout, str) else layout) if laid_out else None)


def _other_arguments(normalise: Callable[..., Any], names: list[str], function: str, name: str) -> tuple[str, ...]:
    """The arguments ``normalise`` reads besides (chain, value): its parameters after the second, by name."""
    if name not in names:
        raise TypeError(f"memoized {function}() has no argument {name!r} to normalise")
    others = tuple(list(inspect.signature(normalise).parameters)[2:])
    unknown = [other for other in others if other not in names]
    if unknown:
        raise TypeError(f"the normaliser of {name!r} reads {', '.join(unknown)}, which {function}() does not take")
    return others
