r"""Singular configurations: the factored determinant of the Jacobian, each factor solved and explained.

A square Jacobian :math:`J(q)` (the task rows an arm controls, see :func:`task_rows`) loses rank exactly where
:math:`\det J = 0`. The determinant is computed on the polynomial image of the simplified Jacobian (sines and
cosines of the basis angles as independent generators, :mod:`symjac.symbolic.simplify`): a cofactor expansion
reduced modulo :math:`s^2 + c^2 - 1` as it goes, factored as a function of the angles, and each factor laid out in the
angle basis where it is shortest (:mod:`symjac.symbolic.trigfactor`). Factors that reduce to a constant
(:math:`s^2 + c^2`) disappear; what remains reads as in a textbook, e.g. :math:`-L_2 L_3 s_3 (L_1 + L_2 c_2 + L_3
c_{23})`.

The determinant of the selected rows does not depend on the frame it is expressed in (a frame change multiplies it
by the determinant of an orthogonal block, 1), so it is computed in the frame where the Jacobian is most compact.

Each factor is then solved (:mod:`symjac.analysis.singularity.solve`), and at a sample of each solution the arm is
examined numerically (:mod:`symjac.analysis.singularity.geometry`) to classify the singularity and to find what it
loses;
:func:`symjac.analysis.singularity.singularities.singularities` puts it together and :mod:`symjac.printing.prose` says
it in words.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from symjac.analysis.singularity.rows import singular_rows
from symjac.analysis.spaces import task_rows
from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import ROW_NAMES, Point, check_row_indices, jacobian, point_vector
from symjac.kinematics.memo import memoized
from symjac.kinematics.numeric import numeric_at
from symjac.model.ends import end_point
from symjac.model.robot import Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.trigfactor import compact_expr, determinant_image, trig_factor_list
from symjac.symbolic.trigpoly import image_of, reduce_image

__all__ = ["Determinant", "default_rows", "determinant", "is_admissible_frame"]


def is_admissible_frame(robot: Robot | Chain, rows: Sequence[int], frame: Frame) -> bool:
    r"""Whether re-expressing the Jacobian in ``frame`` keeps the selected rows closed (their determinant unchanged).

    All six rows, or all three linear or angular rows, are closed in every frame; a planar subset
    (:math:`v_x, v_y, \omega_z`) only in frames rotated about z: every entry :math:`R_{ij}` of :math:`{}^k_0R` linking
    a chosen row :math:`i` to an unchosen one :math:`j` of the same block must vanish.

    Examples
    --------
    >>> from symjac import load_robot
    >>> robot = load_robot("articulated3r")
    >>> is_admissible_frame(robot, (0, 1, 2), 2), is_admissible_frame(robot, (0, 1, 5), 2)
    (True, False)
    """
    chosen = set(rows)
    blocks = [set(range(3)), set(range(3, 6))]
    if all(block <= chosen or not block & chosen for block in blocks):
        return True
    R = as_chain(robot).simplified_transform(frame, 0)[:3, :3]
    for block_start in (0, 3):
        inside = [r - block_start for r in rows if block_start <= r < block_start + 3]
        outside = [c for c in range(3) if c not in inside]
        if any(sp.simplify(R[i, j]) != 0 for i in inside for j in outside):
            return False
    return True


def _frame_sign(chain: Chain, rows: tuple[int, ...], frame: Frame) -> int:
    r"""The sign :math:`\det(S\,\mathrm{diag}(R, R)\,S^T) = \pm 1` between the rows' determinant in ``frame`` and {0}.

    It is 1 for all six rows or whole 3-row blocks; a planar subset in a frame whose z-axis is flipped (a twist of
    pi) has -1, and the determinant is reported as in frame {0}. The sign is constant, so any configuration shows it.
    """
    q = [0.3 + 0.1 * i for i in range(chain.robot.n_coordinates)]
    R = numeric_at(chain, chain.rotation(frame, 0), q)
    B = np.kron(np.eye(2), R)[np.ix_(rows, rows)]
    return 1 if np.linalg.det(B) > 0 else -1


# --- determinant -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Determinant:
    r"""A factored determinant :math:`\det J = c \prod_i f_i^{m_i}` and where it came from."""

    coefficient: sp.Expr
    factors: tuple[tuple[sp.Expr, int], ...]
    rows: tuple[int, ...]
    frame: Frame
    point: tuple[sp.Expr, sp.Expr, sp.Expr]
    columns: tuple[int, ...]

    @property
    def expression(self) -> sp.Expr:
        """The determinant as one product (unevaluated, so the factors stay visible)."""
        parts = [factor**m if m > 1 else factor for factor, m in self.factors]
        return sp.Mul(self.coefficient, *parts, evaluate=False) if self.coefficient != 1 else sp.Mul(*parts)

    @property
    def row_names(self) -> tuple[str, ...]:
        """Names of the rows used (``v_x`` ... ``omega_z``)."""
        return tuple(ROW_NAMES[r] for r in self.rows)


def _square_jacobian(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], rows: Sequence[int],
                     columns: Sequence[int], numeric: bool) -> sp.Matrix:
    J = jacobian(chain, frame=frame, point=point).extract(list(rows), list(columns))
    return J.xreplace(chain.robot.defaults) if numeric else J


def _layout(expr: sp.Expr, bases: Sequence[AngleBasis]) -> sp.Expr:
    """The shortest compact form of ``expr`` over ``bases`` (:func:`symjac.symbolic.trigfactor.compact_expr`)."""
    forms = [expr]
    for basis in bases:
        image, (poly,) = image_of([expr], basis)
        forms.append(compact_expr(poly, image))
    return min(forms, key=lambda form: (sp.count_ops(form), len(str(form))))


@memoized()
def _best_frame(chain: Chain, rows: tuple[int, ...], point: tuple[sp.Expr, ...]) -> int:
    """The admissible frame in which the selected rows of the Jacobian have the fewest operations.

    Kept in the chain: a redundant arm's minors all ask for it.
    """
    sizes = []
    for frame in range(chain.n_joints + 1):
        if is_admissible_frame(chain, rows, frame):
            J = jacobian(chain, frame=frame, point=point).extract(list(rows), list(range(chain.robot.n_coordinates)))
            sizes.append((int(sp.count_ops(J)), frame))
    return min(sizes)[1]


def _point(chain: Chain, point: Point | None) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """The point validated; by default the tool point when the robot has a tool, else the wrist."""
    return point_vector(chain, end_point(chain) if point is None else point)


def _rows(chain: Chain, rows: Sequence[int] | None) -> tuple[int, ...] | None:
    return None if rows is None else tuple(rows)


def _columns(chain: Chain, columns: Sequence[int] | None) -> tuple[int, ...]:
    return tuple(range(chain.robot.n_coordinates)) if columns is None else tuple(columns)


def default_rows(robot: Robot | Chain, point: Point | None = None, frame: Frame | None = None
                 ) -> tuple[tuple[int, ...], Frame | None]:
    """The rows (and their frame) a determinant is taken of when none are given.

    The exact choice of :func:`symjac.analysis.singularity.rows.singular_rows` when there is one (its determinant
    vanishes exactly where the arm loses a motion), else :func:`task_rows` in frame {0}.
    """
    chain = as_chain(robot)
    point_xyz = _point(chain, point)
    choice = singular_rows(chain, point_xyz, None if frame is None else chain.frame_name(chain.position(frame)))
    if choice.exact:  # rows closed under the rotation to its frame are those of {0}: the most compact frame then
        closed = choice.frame is None or is_admissible_frame(chain, choice.rows, choice.frame)
        return choice.rows, frame if closed else choice.frame
    return task_rows(chain, point_xyz), frame


@memoized(point=_point, rows=_rows, columns=_columns)
def determinant(
    chain: Chain,
    rows: Sequence[int] | None = None,
    frame: Frame | None = None,
    point: Point | None = None,
    *,
    columns: Sequence[int] | None = None,
    numeric: bool = False,
) -> Determinant:
    r"""The factored determinant of the square Jacobian made of ``rows`` (and ``columns``).

    Parameters
    ----------
    robot : Robot or Chain
    rows : sequence of int, optional
        Rows (0..5 for :math:`v_x .. \omega_z`) of the Jacobian in ``frame``; default :func:`default_rows`, rows
        whose determinant vanishes exactly where the arm loses a motion.
    frame : int, optional
        The frame of the rows. Rows closed under rotation (all six, the three linear or angular rows, a planar set in
        frames turned about z) give the same determinant in every such frame, reported as in frame {0}; by default
        they are computed in the frame where the Jacobian is most compact. Other rows are those of that frame's
        Jacobian.
    point : optional
        Reference point (see :func:`symjac.kinematics.jacobian`); default the tool point if the robot has a tool, else
        the wrist. It matters only when fewer than six rows are used.
    columns : sequence of int, optional
        Joints (0-based columns) to keep, for the minors of a redundant arm; default all.
    numeric : bool
        Substitute the parameters' exact defaults first (factors then hold numbers instead of lengths).

    Examples
    --------
    >>> from symjac import load_robot
    >>> determinant(load_robot("planar2r")).expression
    L1*L2*sin(theta2)
    """
    # Factoring costs seconds on a six-joint arm and the singularity report, the rates and the CLI all ask for it:
    # the chain keeps it per request (@memoized, arguments normalised first).
    if rows is None:
        rows, frame = default_rows(chain, point, frame)
        return determinant(chain, rows, frame, point, columns=columns, numeric=numeric)
    if len(rows) != len(columns) or not rows:  # type: ignore[arg-type]
        raise ArgumentError(f"a determinant needs as many rows as columns, got rows {rows} and columns {columns}")
    chosen = check_row_indices(rows)  # type: ignore[arg-type]
    n = chain.robot.n_coordinates
    if any(not 0 <= c < n for c in columns) or len(set(columns)) != len(columns):  # type: ignore[union-attr, arg-type]
        raise ArgumentError(f"columns must be distinct coordinate indices 0..{n - 1}, got {columns}")
    return _determinant(chain, chosen, frame, point, columns, numeric)  # type: ignore[arg-type]


def _determinant(chain: Chain, rows: tuple[int, ...], frame: Frame | None, point_xyz: tuple[sp.Expr, sp.Expr, sp.Expr],
                 columns: tuple[int, ...], numeric: bool) -> Determinant:
    if frame is None:
        frame = _best_frame(chain, rows, point_xyz)
    frame = chain.frame_name(chain.position(frame))
    sign = _frame_sign(chain, rows, frame) if is_admissible_frame(chain, rows, frame) else 1  # else: rows of {frame}
    J = _square_jacobian(chain, frame, point_xyz, rows, columns, numeric)
    coefficient, factors = _factored_determinant(J, chain.angle_basis(frame), chain.all_angle_bases())
    return Determinant(coefficient * sign, factors, rows, frame, point_xyz, columns)


def _factored_determinant(
    J: sp.Matrix, basis: AngleBasis, bases: Sequence[AngleBasis]
) -> tuple[sp.Expr, tuple[tuple[sp.Expr, int], ...]]:
    """The determinant by reduced cofactor expansion, its factors as functions of the angles, each laid out."""
    image, polys = image_of(list(J), basis)
    value = determinant_image([polys[i * J.cols:(i + 1) * J.cols] for i in range(J.rows)], image, reduced=False)
    if not reduce_image(value, image):
        return sp.S.Zero, ()
    coefficient, raw_factors = trig_factor_list(value, image)
    collected: dict[sp.Expr, int] = {}
    for raw, multiplicity in raw_factors:
        if raw.is_ground:
            coefficient *= _number(raw.LC) ** multiplicity
            continue
        factor = _layout(compact_expr(raw, image), bases)
        if not factor.free_symbols:  # a constant such as sqrt(2) (a generator of the image): no parameter, no angle
            coefficient *= factor ** multiplicity
            continue
        if factor.could_extract_minus_sign():
            factor, coefficient = -factor, coefficient * (-1) ** multiplicity
        collected[factor] = collected.get(factor, 0) + multiplicity
    ordered = sorted(collected.items(), key=lambda item: (_factor_rank(item[0]), sp.default_sort_key(item[0])))
    return coefficient, tuple(ordered)


def _number(value: Any) -> sp.Rational:
    return sp.Rational(int(value.numerator), int(value.denominator))


def _factor_rank(factor: sp.Expr) -> int:
    """Parameters first, then single sines/cosines, then longer factors (textbook order)."""
    if not any(isinstance(atom, sp.sin | sp.cos) for atom in factor.atoms(sp.Function)):
        return 0
    return 1 if isinstance(factor, sp.sin | sp.cos) else 2
