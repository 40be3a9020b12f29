r"""Inertial data of one link: mass, centre of mass and inertia tensor, all in the link's own frame {i}.

Carried by :attr:`symjac.model.robot.Robot.inertials` (one per link 1..n) and read and written by robot files and
URDF; the dynamics use it. The tensor is stored about the **centre of mass**, with the axes of frame {i}:

.. math:: I_c = \int \left(\lVert r - c\rVert^2 E - (r - c)(r - c)^T\right)\,dm

A tensor given about the link origin :math:`o_i` is converted by the parallel-axis theorem
(:meth:`Inertial.from_origin`):

.. math:: I_c = I_o - m\left(\lVert c\rVert^2 E - c\,c^T\right)

Entries are SymPy expressions: numbers, or parameters of the robot (``m2``, ``cx2``, ``Ixx2``, ... with numeric
defaults, :func:`symbolic_inertial`). Physical validity (:func:`inertial_problem`: mass not negative, tensor symmetric,
positive semi-definite, principal moments obeying the triangle inequality) is checked where the values are numbers once
parameters take their defaults; an entry left purely symbolic cannot be checked and passes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Literal

import sympy as sp

from symjac.model.expressions import exact_number, expression_text

__all__ = ["INERTIAL_KEYS", "INERTIA_NAMES", "Inertial", "combined_inertial", "inertial_from_table", "inertial_problem",
           "inertial_table", "symbolic_inertial"]

INERTIA_NAMES: tuple[str, ...] = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
"""The six independent entries of a symmetric tensor, in the order robot files and URDF list them."""

_INDEX = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}
_RELATIVE_TOLERANCE = 1e-9  # numbers from files carry ~15 digits; a tensor off by less is taken as meant


def _expr(value: object) -> sp.Expr:
    """A number or SymPy expression as an expression (Python numbers exactly, as robot files read them)."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return exact_number(value)
    return sp.sympify(value)


def _spread(c: Sequence[sp.Expr], mass: sp.Expr) -> sp.ImmutableMatrix:
    r""":math:`m\left(\lVert c\rVert^2 E - c\,c^T\right)`, the tensor of a point mass at :math:`c` about the origin."""
    v = sp.Matrix(c)
    return sp.ImmutableMatrix((mass * ((v.T * v)[0, 0] * sp.eye(3) - v * v.T)).applyfunc(sp.expand))


@dataclass(frozen=True)
class Inertial:
    r"""The inertial data of one link, in its frame {i}.

    Parameters
    ----------
    mass : sympy.Expr
        :math:`m`.
    com : tuple of 3 sympy.Expr
        The centre of mass :math:`c`, coordinates in frame {i}.
    inertia : sympy.ImmutableMatrix, shape (3, 3)
        The symmetric tensor :math:`I_c` about the centre of mass, axes of frame {i}.
    given_about : ``"com"`` or ``"origin"``
        About which point the source gave the tensor (the centre of mass, or the origin of the frame it gave it in;
        ignored by ``==``, kept to write it back that way): the stored one is always about the centre of mass.
    keep_impossible : bool
        Keep data that no rigid body can have (:func:`inertial_problem`), knowingly: published parameters kept as
        published (the PUMA 560's link 3). Without it the dynamics refuse such a link, naming it.

    Examples
    --------
    >>> rod = Inertial.from_origin(2, (sp.Rational(1, 2), 0, 0), sp.diag(0, sp.Rational(2, 3), sp.Rational(2, 3)))
    >>> rod.inertia
    Matrix([
    [0,   0,   0],
    [0, 1/6,   0],
    [0,   0, 1/6]])
    """

    mass: sp.Expr
    com: tuple[sp.Expr, sp.Expr, sp.Expr] = (sp.S.Zero, sp.S.Zero, sp.S.Zero)
    inertia: sp.ImmutableMatrix = field(default_factory=lambda: sp.ImmutableMatrix(sp.zeros(3, 3)))
    given_about: Literal["com", "origin"] = field(default="com", compare=False)
    keep_impossible: bool = False

    def __post_init__(self) -> None:
        """Turn the entries into SymPy expressions; refuse a centre of mass or tensor of the wrong shape."""
        com = tuple(self.com)
        if len(com) != 3:
            raise ValueError(f"the centre of mass has 3 coordinates, got {len(com)}")
        inertia = sp.Matrix(self.inertia)
        if inertia.shape != (3, 3):
            raise ValueError(f"the inertia tensor is 3 x 3, got {inertia.shape[0]} x {inertia.shape[1]}")
        if self.given_about not in ("com", "origin"):
            raise ValueError(f"given_about is 'com' or 'origin', got {self.given_about!r}")
        object.__setattr__(self, "mass", _expr(self.mass))
        object.__setattr__(self, "com", tuple(_expr(v) for v in com))
        object.__setattr__(self, "inertia", sp.ImmutableMatrix(inertia.applyfunc(_expr)))

    @classmethod
    def from_origin(cls, mass: object, com: Sequence[object], inertia_about_origin: object) -> Inertial:
        r"""The link whose tensor about the origin of frame {i} is ``inertia_about_origin``.

        .. math:: I_c = I_o - m\left(\lVert c\rVert^2 E - c\,c^T\right)

        (the parallel-axis theorem; :math:`E` is the identity).
        """
        m, c = _expr(mass), tuple(_expr(v) for v in com)
        I_o = sp.Matrix(inertia_about_origin).applyfunc(_expr)
        if I_o.shape != (3, 3):
            raise ValueError(f"the inertia tensor is 3 x 3, got {I_o.shape[0]} x {I_o.shape[1]}")
        return cls(m, c, sp.ImmutableMatrix((I_o - _spread(c, m)).applyfunc(sp.expand)),  # type: ignore[arg-type]
                   given_about="origin")

    @property
    def inertia_about_origin(self) -> sp.ImmutableMatrix:
        r""":math:`I_o = I_c + m\left(\lVert c\rVert^2 E - c\,c^T\right)`, about the origin of frame {i}."""
        return sp.ImmutableMatrix((self.inertia + _spread(self.com, self.mass)).applyfunc(sp.expand))

    def inertia_about(self, point: Sequence[object]) -> sp.ImmutableMatrix:
        r"""The tensor about ``point`` (in {i}): :math:`I_c + m(\lVert r\rVert^2 E - r r^T)`, :math:`r = c - p`."""
        r = [c - _expr(p) for c, p in zip(self.com, point, strict=True)]
        return sp.ImmutableMatrix((self.inertia + _spread(r, self.mass)).applyfunc(sp.expand))

    def expressed_in(self, T: sp.MatrixBase) -> Inertial:
        r"""The same body in another frame {j} fixed to the link, ``T`` the pose of {i} in {j} (4 x 4).

        .. math:: c' = R\,c + p, \qquad I_c' = R\,I_c\,R^T
        """
        R, p = sp.Matrix(T[:3, :3]), sp.Matrix(T[:3, 3])
        com = (R * sp.Matrix(self.com) + p).applyfunc(sp.expand)
        inertia = (R * self.inertia * R.T).applyfunc(sp.expand)
        return Inertial(self.mass, tuple(com), sp.ImmutableMatrix(inertia),  # type: ignore[arg-type]
                        given_about=self.given_about, keep_impossible=self.keep_impossible)

    @property
    def entries(self) -> dict[str, sp.Expr]:
        """The six independent entries of the tensor about the centre of mass, by :data:`INERTIA_NAMES`."""
        return {name: self.inertia[i, j] for name, (i, j) in _INDEX.items()}

    @classmethod
    def from_entries(cls, mass: object, com: Sequence[object], entries: Mapping[str, object],
                     about: Literal["com", "origin"] = "com") -> Inertial:
        """The link from the six entries ``ixx .. izz`` (missing ones are zero) of a tensor about ``about``."""
        unknown = sorted(set(entries) - set(INERTIA_NAMES))
        if unknown:
            raise ValueError(f"unknown inertia entries {', '.join(unknown)}; known: {', '.join(INERTIA_NAMES)}")
        M = sp.zeros(3, 3)
        for name, (i, j) in _INDEX.items():
            M[i, j] = M[j, i] = _expr(entries.get(name, 0))
        return cls.from_origin(mass, com, M) if about == "origin" else cls(_expr(mass), tuple(com), M)  # type: ignore


def inertial_problem(inertial: Inertial, defaults: Mapping[sp.Symbol, sp.Expr] | None = None, *,
                     physical: bool = True) -> str | None:
    r"""What is physically wrong with ``inertial`` once parameters take ``defaults``, in a few words, or None.

    Checked where the values are numbers: the mass is finite and not negative; the centre of mass is finite; the
    tensor about the centre of mass is symmetric, positive semi-definite, and its principal moments
    :math:`\lambda_1 \le \lambda_2 \le \lambda_3` obey the triangle inequality :math:`\lambda_1 + \lambda_2 \ge
    \lambda_3` (then every permutation does), all to a relative tolerance of 1e-9. Entries that stay symbolic pass.
    ``physical=False`` checks only that the data is well formed (a mass that is not negative, finite values, a
    symmetric tensor), not that a rigid body can have it.

    Examples
    --------
    >>> inertial_problem(Inertial(-1))
    'the mass -1 is negative'
    >>> inertial_problem(Inertial(1, inertia=sp.diag(1, 1, 3)))
    'the principal moments 1, 1, 3 break the triangle inequality (1 + 1 < 3)'
    """
    subs = dict(defaults or {})

    def number(e: sp.Expr) -> float | None:
        value = sp.sympify(e.xreplace(subs)) if subs else e
        if not value.is_number:
            return None
        try:
            return float(value)
        except TypeError:  # complex or zoo
            return float("nan")

    mass = number(inertial.mass)
    if mass is not None:
        if not math.isfinite(mass):
            return f"the mass {inertial.mass} is not a finite number"
        if mass < 0:
            return f"the mass {inertial.mass} is negative"
    for axis, c in zip("xyz", inertial.com, strict=True):
        value = number(c)
        if value is not None and not math.isfinite(value):
            return f"the centre of mass {axis} = {c} is not a finite number"
    values = [[number(inertial.inertia[i, j]) for j in range(3)] for i in range(3)]
    flat = [v for row in values for v in row if v is not None]
    if any(not math.isfinite(v) for v in flat):
        return "the inertia tensor has an entry that is not a finite number"
    scale = max((abs(v) for v in flat), default=0.0)
    tolerance = _RELATIVE_TOLERANCE * max(scale, 1e-300)
    for i, j in ((0, 1), (0, 2), (1, 2)):
        a, b = inertial.inertia[i, j], inertial.inertia[j, i]
        if sp.expand(a - b) == 0:
            continue
        x, y = values[i][j], values[j][i]
        if x is None or y is None or abs(x - y) > tolerance:
            return f"the inertia tensor is not symmetric (I[{i + 1},{j + 1}] = {a}, I[{j + 1},{i + 1}] = {b})"
    if not physical or any(v is None for row in values for v in row):
        return None  # not asked, or symbolic entries: nothing more can be checked
    import numpy as np  # only for numeric tensors: loading a robot without inertial data needs no NumPy

    moments = np.linalg.eigvalsh(np.array(values, dtype=float))
    if moments[0] < -tolerance:
        return f"the inertia tensor is not positive semi-definite (principal moment {moments[0]:.6g})"
    low, mid, high = (max(float(v), 0.0) for v in moments)
    if low + mid < high - tolerance:
        shown = ", ".join(f"{v:.6g}" for v in (low, mid, high))
        return (f"the principal moments {shown} break the triangle inequality "
                f"({low:.6g} + {mid:.6g} < {high:.6g})")
    return None


def symbolic_inertial(link: int) -> Inertial:
    """Link *i*'s inertial data as symbols: mass ``m{i}``, centre ``cx{i}`` .., tensor ``Ixx{i}`` .. ``Izz{i}``.

    Each is a real symbol, as a robot's :class:`~symjac.model.robot.Parameter` stands for itself in derivations; give
    them numeric defaults as parameters (:func:`symjac.model.inertial_parameters.with_symbolic_inertials`).

    Examples
    --------
    >>> symbolic_inertial(2).inertia[0, 1]
    Ixy2
    """
    s = {name: sp.Symbol(f"{name}{link}", real=True)
         for name in ("m", "cx", "cy", "cz", "Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz")}
    inertia = sp.Matrix([[s["Ixx"], s["Ixy"], s["Ixz"]], [s["Ixy"], s["Iyy"], s["Iyz"]],
                         [s["Ixz"], s["Iyz"], s["Izz"]]])
    return Inertial(s["m"], (s["cx"], s["cy"], s["cz"]), sp.ImmutableMatrix(inertia))


def combined_inertial(parts: Sequence[Inertial]) -> Inertial:
    r"""One body made of ``parts`` (all in the same frame): masses add, centres average, tensors move to the new centre.

    .. math:: m = \sum_k m_k, \quad c = \frac{1}{m}\sum_k m_k c_k, \quad
        I_c = \sum_k \left(I_k + m_k(\lVert c_k - c\rVert^2 E - (c_k - c)(c_k - c)^T)\right)

    A total mass of exactly zero puts the centre at the origin.
    """
    if not parts:
        raise ValueError("combined_inertial needs at least one part")
    mass = sp.expand(sum((p.mass for p in parts), sp.S.Zero))
    moment = [sp.expand(sum((p.mass * p.com[k] for p in parts), sp.S.Zero)) for k in range(3)]
    com = (sp.S.Zero,) * 3 if mass == 0 else tuple(sp.cancel(v / mass) for v in moment)
    inertia = sp.zeros(3, 3)
    for part in parts:
        inertia += part.inertia_about(com)
    return Inertial(mass, com, sp.ImmutableMatrix(inertia.applyfunc(sp.cancel)),  # type: ignore[arg-type]
                    keep_impossible=any(part.keep_impossible for part in parts))


INERTIAL_KEYS: tuple[str, ...] = ("mass", "com", "about", *INERTIA_NAMES, "inertia", "keep_impossible")
"""The keys of a robot file's ``[joints.inertial]`` table, in the order they are written."""


def inertial_from_table(table: object, value: Callable[[object, str], sp.Expr],
                        fail: Callable[[str, str], Exception]) -> Inertial:
    """The :class:`Inertial` a robot file's ``inertial`` table gives, in the frame the file gives it in.

    ``mass`` (required), ``com`` (``[x, y, z]``, default the origin), ``about`` (``"com"``, the default, or
    ``"origin"``: the point the tensor is about) and the tensor as the six entries ``ixx ixy ixz iyy iyz izz`` (missing
    ones 0) or as ``inertia``, 3 rows of 3; ``keep_impossible = true`` keeps data no rigid body can have
    (:attr:`Inertial.keep_impossible`). ``value(raw, field)`` parses one entry; ``fail(message, field)`` is the
    error to raise.
    """
    if not isinstance(table, Mapping):
        raise fail("'inertial' must be a table with 'mass', 'com' and the tensor entries ixx .. izz", "inertial")
    unknown = sorted(set(table) - set(INERTIAL_KEYS))
    if unknown:
        raise fail(f"unknown key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(INERTIAL_KEYS)}",
                   "inertial")
    if "mass" not in table:
        raise fail("'mass' is required", "inertial.mass")
    about = table.get("about", "com")
    if about not in ("com", "origin"):
        raise fail(f"'about' must be 'com' (the centre of mass) or 'origin' (of the link frame), got {about!r}",
                   "inertial.about")
    com = table.get("com", [0, 0, 0])
    if not isinstance(com, Sequence) or isinstance(com, str) or len(com) != 3:
        raise fail("'com' must be a list of 3 numbers or expressions", "inertial.com")
    keep = table.get("keep_impossible", False)
    if not isinstance(keep, bool):
        raise fail(f"'keep_impossible' must be true or false, got {keep!r}", "inertial.keep_impossible")
    inertial = _tensor_from_table(table, value, fail, about)
    return replace(inertial, keep_impossible=True) if keep else inertial


def _tensor_from_table(table: Mapping[str, object], value: Callable[[object, str], sp.Expr],
                       fail: Callable[[str, str], Exception], about: Literal["com", "origin"]) -> Inertial:
    """:func:`inertial_from_table`'s body and tensor, either as six entries or as 3 rows of 3."""
    com: Sequence[object] = table.get("com", [0, 0, 0])  # type: ignore[assignment]
    entries = {name: value(table[name], f"inertial.{name}") for name in INERTIA_NAMES if name in table}
    mass = value(table["mass"], "inertial.mass")
    centre = tuple(value(v, "inertial.com") for v in com)
    if "inertia" not in table:
        return Inertial.from_entries(mass, centre, entries, about)
    rows = table["inertia"]
    if entries:
        raise fail("give the tensor either as 'inertia' or as ixx .. izz, not both", "inertial.inertia")
    if not (isinstance(rows, Sequence) and not isinstance(rows, str) and len(rows) == 3
            and all(isinstance(r, Sequence) and not isinstance(r, str) and len(r) == 3 for r in rows)):
        raise fail("'inertia' must be 3 rows of 3 entries", "inertial.inertia")
    matrix = sp.Matrix([[value(v, "inertial.inertia") for v in row] for row in rows])
    return Inertial.from_origin(mass, centre, matrix) if about == "origin" else Inertial(mass, centre, matrix)


def inertial_table(inertial: Inertial) -> dict[str, object]:
    """The ``inertial`` table of a robot file for ``inertial`` (about the point it was given about)."""
    tensor = inertial.inertia_about_origin if inertial.given_about == "origin" else inertial.inertia
    table: dict[str, object] = {"mass": expression_text(inertial.mass),
                                "com": [expression_text(v) for v in inertial.com], "about": inertial.given_about}
    if all(sp.expand(tensor[i, j] - tensor[j, i]) == 0 for i, j in ((0, 1), (0, 2), (1, 2))):
        table.update({name: expression_text(tensor[i, j]) for name, (i, j) in _INDEX.items()})
    else:  # only symbols can be unequal across the diagonal (numbers are refused): keep both
        table["inertia"] = [[expression_text(tensor[i, j]) for j in range(3)] for i in range(3)]
    if inertial.keep_impossible:
        table["keep_impossible"] = True
    return table
