"""Names in generated code: the identifier rules of the target languages and the names a module keeps for itself.

A leaf of :mod:`symjac.codegen` (it imports nothing else of it): the request, the lowering, the printers and the
description all check names against these rules, so none of them needs another for that.
"""

from __future__ import annotations

import builtins
import keyword
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from symjac.errors import CodegenError

__all__ = ["PYTHON_IDENTIFIERS", "RESERVED", "IdentifierRule"]

_ASCII_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


@dataclass(frozen=True)
class IdentifierRule:
    """Which names a target's language accepts as identifiers: a pattern, keywords, and names not to shadow.

    ``keywords`` and ``shadowed`` map each word to the language it belongs to, so that one rule can serve a file
    that mixes two languages (the c target: a Python module embedding C) and the error still names the right one.

    Examples
    --------
    >>> PYTHON_IDENTIFIERS.check("a2", "parameter name")
    'a2'
    >>> PYTHON_IDENTIFIERS.check("lambda", "parameter name")
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: parameter name 'lambda' is a Python keyword
    """

    keywords: Mapping[str, str]
    shadowed: Mapping[str, str]
    pattern: re.Pattern[str] = _ASCII_IDENTIFIER
    prefixes: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))  # kept by the generated code

    @classmethod
    def of(cls, language: str, keywords: Iterable[str], shadowed: Iterable[str] = (),
           prefixes: Iterable[str] = ()) -> IdentifierRule:
        """The rule of one language: its keywords, names not to shadow, and its generated code's own prefixes.

        ``shadowed`` are the builtins a generated name must not hide; a name starting with one of ``prefixes`` could
        collide with a name the generated code makes itself.
        """
        return cls(MappingProxyType(dict.fromkeys(keywords, language)),
                   MappingProxyType(dict.fromkeys(shadowed, language)),
                   prefixes=MappingProxyType(dict.fromkeys(prefixes, language)))

    def __or__(self, other: IdentifierRule) -> IdentifierRule:
        """A rule that refuses whatever either rule refuses (the first one's pattern)."""
        return IdentifierRule(MappingProxyType({**other.keywords, **self.keywords}),
                              MappingProxyType({**other.shadowed, **self.shadowed}), self.pattern,
                              MappingProxyType({**other.prefixes, **self.prefixes}))

    def check(self, name: object, what: str, reserved: Mapping[str, str] | None = None) -> str:
        """Return ``name`` if it may be an identifier of the generated code, else raise :class:`CodegenError`.

        ``reserved`` maps names the generated module uses itself to the reason (the error says which).
        """
        if not isinstance(name, str) or not self.pattern.match(name):
            raise CodegenError(f"{what} {name!r} is not an ASCII identifier (letters, digits, underscore)")
        if name in self.keywords:
            raise CodegenError(f"{what} {name!r} is a {self.keywords[name]} keyword")
        if name in self.shadowed:
            raise CodegenError(f"{what} {name!r} would shadow the {self.shadowed[name]} builtin of that name")
        for prefix, language in self.prefixes.items():
            if name.startswith(prefix):
                raise CodegenError(f"{what} {name!r} starts with {prefix!r}, which the generated {language} keeps for "
                                   "its own names")
        if reserved is not None and name in reserved:
            raise CodegenError(f"{what} {name!r} clashes with {reserved[name]} in the generated module")
        return name


PYTHON_IDENTIFIERS = IdentifierRule.of("Python", (*keyword.kwlist, *keyword.softkwlist), dir(builtins))
"""Python's rule: ASCII identifiers, no keyword or soft keyword, no builtin (a parameter ``len`` would shadow it)."""

# Names every generated module defines or imports for itself, with the reason a parameter may not take them.
RESERVED: Mapping[str, str] = MappingProxyType({
    **{name: "an argument of the generated functions" for name in ("q", "qdot", "out", "wrench", "samples",
                                                                    "seed", "tolerance", "threads")},
    **{name: "an import of the generated module" for name in ("annotations", "np", "sympy", "math", "os", "sys",
                                                               "cos", "sin", "sqrt", "pi", "random", "threading",
                                                               "importlib", "sysconfig", "hashlib", "shutil",
                                                               "subprocess", "tempfile", "Path", "Sequence",
                                                               "ArrayLike", "MappingProxyType", "Any",
                                                               "Mapping")},
    **{name: "a constant of the generated module" for name in ("PARAMETERS", "COORDINATES", "JOINTS", "ROBOT",
                                                                "CONVENTION", "SYMJAC_VERSION", "JACOBIANS",
                                                                "BACKEND", "THREADS", "BUILD_ERROR", "DOF",
                                                                "JOINT_NAMES", "JOINT_TYPES", "LOWER", "UPPER",
                                                                "TIP_FRAME")},
    **{name: "a function of the generated module" for name in ("selftest", "forward_kinematics", "jacobian",
                                                                "joint_torques", "manipulability",
                                                                "jacobian_determinant", "hessian",
                                                                "bias_acceleration", "manipulability_gradient",
                                                                "kinematics", "coordinates")},
    **{name: "a table of the generated C and C++ code" for name in ("joint_names", "joint_types", "lower", "upper",
                                                                     "tip_frame", "joint")},
})
