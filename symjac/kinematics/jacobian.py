r"""Basic Jacobians :math:`J = [J_v; J_\omega]` of a serial robot, by the textbook derivation methods.

For joint i with axis :math:`z_i` through the point :math:`p_i` (frame {i} in the modified convention, {i-1} in the
standard one), :math:`\epsilon_i = 1` for a prismatic and :math:`0` for a revolute joint, and the point P fixed to
the last link, the columns of the basic Jacobian are

.. math::
    J_i = \begin{bmatrix} \epsilon_i z_i + \bar\epsilon_i\, z_i \times p_{iP} \\ \bar\epsilon_i z_i \end{bmatrix}

expressed in any frame {k} as :math:`{}^kJ = \mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J`. For a point fixed in an
earlier link l (``link=l``, :mod:`symjac.kinematics.points`) the same holds with the chain cut at frame {l}: its
coordinates are given in {l}, only joints 1..l move it, and the columns of joints l+1..n are zero. Every method
then works up to {l} where it would work up to {n} (differentiation of :math:`{}^0_lT\,p`, cross products with
:math:`p_{iP}` read from {l}, velocities propagated out to {l}, a wrench propagated in from {l}).

Methods (all return the same matrix, simplified to the same unique normal form):

``"differentiation"``
    :math:`J_v = \partial\,{}^0x_P/\partial q` of the forward kinematics, :math:`J_\omega` from the z-axes
    :math:`{}^0z_i = {}^0_iR\,[0, 0, 1]^T`, then rotated into {k}.
``"cross_product"``
    :math:`{}^k(z_i \times p_{iP})` with every vector read where it is shortest. Usually both are read in {k}:
    :math:`{}^kz_i \times ({}^kp_P - {}^kp_i)` from :math:`{}^k_iT` and :math:`{}^k_nT` (in frame {0} the familiar
    :math:`z_{i-1} \times (o_n - o_{i-1})`). When P is nearer the axis than {k} is, counted in turns of the joint
    axes (a vector spanning m turns has about :math:`1.8^m` terms), :math:`p_{iP}` is read in {i}, where
    :math:`{}^iz_i = [0, 0, 1]^T` makes the cross product :math:`[-p_y, p_x, 0]^T`, and rotated:
    :math:`{}^k_iR\,(\hat{Z}\,{}^ip_{iP})`. A frame in the middle of a long chain then gives short results where
    frame {0} cannot.
``"velocity_propagation"``
    Link velocities iterated outward (:func:`symjac.kinematics.propagation.velocity_propagation`); the last step *is*
    :math:`{}^nJ`, then rotated into {k}.
``"force_propagation"``
    A tip wrench iterated inward (:func:`symjac.kinematics.propagation.force_propagation`); the torque map is
    :math:`{}^nJ^T`, transposed and rotated into {k}.

Which frame each method yields directly, and the 6 x 6 rotation that moves it to frame {k}:

=======================  ===================  =============================================================
method                   natural result       to frame {k}
=======================  ===================  =============================================================
differentiation          :math:`{}^0J`        :math:`\mathrm{diag}({}^k_0R, {}^k_0R)\,{}^0J`
cross_product            :math:`{}^kJ`        computed column by column in {k} (vectors read in {k} or {i})
velocity_propagation     :math:`{}^nJ`        :math:`\mathrm{diag}({}^k_nR, {}^k_nR)\,{}^nJ`
force_propagation        :math:`{}^nJ^T`      transpose, then :math:`\mathrm{diag}({}^k_nR, {}^k_nR)\,{}^nJ`
=======================  ===================  =============================================================
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal, get_args

import sympy as sp

from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.memo import frame_of, memoized, one_of
from symjac.kinematics.points import Point, link_of, link_point, point_vector
from symjac.kinematics.propagation import force_propagation, velocity_propagation
from symjac.model.robot import VELOCITY_NAMES
from symjac.progress import report
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import Intermediate, derivative, presented_matrix
from symjac.symbolic.simplify import simplify_matrix, simplify_product
from symjac.symbolic.transforms import block_rotation, point_shift

Method = Literal["differentiation", "cross_product", "velocity_propagation", "force_propagation"]

METHODS: tuple[str, ...] = get_args(Method)
"""The four derivations of the basic Jacobian; all give the same matrix."""

ROW_NAMES: tuple[str, ...] = VELOCITY_NAMES
"""The six rows of a basic Jacobian, linear velocity first: the one spelling symjac reads and prints."""

__all__ = [
    "METHODS",
    "ROW_NAMES",
    "Method",
    "Point",
    "change_frame",
    "check_row_indices",
    "jacobian",
    "jacobian_of",
    "point_vector",
    "rows_from_names",
    "shift_point",
]


def rows_from_names(names: str | Sequence[str]) -> tuple[int, ...]:
    """Row indices 0..5 of row names from :data:`ROW_NAMES` (a sequence, or one comma-separated string).

    Examples
    --------
    >>> rows_from_names("v_x,v_y,omega_z")
    (0, 1, 5)
    """
    parts = [part.strip() for part in (names.split(",") if isinstance(names, str) else names)]
    unknown = [part for part in parts if part not in ROW_NAMES]
    if unknown or not parts:
        raise ArgumentError(f"unknown row {unknown[0] if unknown else ''!r}; use {', '.join(ROW_NAMES)}")
    return check_row_indices(tuple(ROW_NAMES.index(part) for part in parts))


def check_row_indices(rows: Sequence[int]) -> tuple[int, ...]:
    """Task rows as distinct indices 0..5; the error names the rows (``v_x is given twice in v_x, v_y, v_x``).

    Examples
    --------
    >>> check_row_indices([0, 1, 5])
    (0, 1, 5)
    """
    values = tuple(rows)
    shown = ", ".join(ROW_NAMES[r] if isinstance(r, int) and 0 <= r < 6 else repr(r) for r in values)
    if not values or any(isinstance(r, bool) or not isinstance(r, int) or not 0 <= r < 6 for r in values):
        raise ArgumentError(f"rows must be row numbers 0..5 ({', '.join(ROW_NAMES)}), got [{shown}]")
    repeated = next((r for i, r in enumerate(values) if r in values[:i]), None)
    if repeated is not None:
        raise ArgumentError(f"rows must not repeat: {ROW_NAMES[repeated]} is given twice in {shown}")
    return values


@memoized(frame=frame_of, point=link_point, link=link_of, method=one_of(METHODS), fresh=presented_matrix,
          coupling="columns", layout="frame")
def jacobian(
    chain: Chain,
    frame: Frame = 0,
    point: Point | None = None,
    method: Method = "differentiation",
    *,
    simplify: bool = True,
    link: int | None = None,
) -> sp.Matrix:
    r"""The 6 x n basic Jacobian :math:`{}^kJ` of ``robot``, rows :math:`[v; \omega]`, one column per coordinate.

    For a robot with coupled joints (:mod:`symjac.kinematics.coupling`) this is :math:`J_q = J(\vartheta(q))\,C`,
    the map from coordinate rates :math:`\dot q` to :math:`[v; \omega]`; otherwise coordinates are joints.

    Parameters
    ----------
    robot : Robot or Chain
    frame : int or "world" or "tool"
        Frame {k} the Jacobian is expressed in (default {0}).
    point : "tool", "flange", "wrist", "wrist_centre" or sequence of 3, optional
        Where the linear velocity is taken. Default: the end of the chain, the point forward kinematics and generated
        code end at (the tool point when the robot has a tool, else the flange, the origin of frame {n}); with a
        ``link``, the origin of {l}. Coordinates are given in frame {l} of the ``link`` ({n} without one). The
        names belong to the last link: ``"tool"`` (the origin of the tool frame), ``"flange"`` (the origin of {n},
        also called ``"wrist"``) and ``"wrist_centre"`` (where the last three axes meet,
        :func:`~symjac.kinematics.points.wrist_centre`).
    method : "differentiation", "cross_product", "velocity_propagation" or "force_propagation"
        Derivation (see the module docstring); all give the same matrix.
    simplify : bool
        Lay the result out in compact textbook form (default). ``False`` returns the raw structured products. For
        generic geometry (a nested chain, :mod:`symjac.kinematics.generic`) no textbook form exists: the default
        result is then the cross-product form, whatever the method (all four give the same matrix), and ``False``
        gives each method's own nested form.
    link : int, optional
        The link l the point is fixed in: 0 (the base) .. n (default, the last link, which carries the tool). The
        columns of joints l+1..n are zero.

    Returns
    -------
    J : sympy.Matrix, shape (6, n_coordinates)
        Rows :math:`[v_x, v_y, v_z, \omega_x, \omega_y, \omega_z]` expressed in {k}; column i belongs to coordinate i
        (joint i without a coupling).

    Examples
    --------
    >>> from symjac import load_robot
    >>> jacobian(load_robot("planar2r"), frame=1)[:2, :]
    Matrix([
    [    -L2*sin(theta2), -L2*sin(theta2)],
    [L1 + L2*cos(theta2),  L2*cos(theta2)]])
    >>> jacobian(load_robot("planar2r"), link=1)[:2, :]  # the end of link 1 (standard DH: the origin of {1})
    Matrix([
    [-L1*sin(theta1), 0],
    [ L1*cos(theta1), 0]])
    """
    return _derive(chain, frame, point, method, simplify, link)  # type: ignore[arg-type]  # normalised by @memoized


def _derive(chain: Chain, frame: Frame, point: tuple[sp.Expr, sp.Expr, sp.Expr], method: Method,
            simplify: bool, link: int) -> sp.ImmutableMatrix:
    if simplify and chain.nested:  # no textbook form: the cheapest nested form, n + 1 frames and n cross products
        return jacobian(chain, frame, point, "cross_product", simplify=False, link=link)
    if simplify and method != "cross_product":  # from the frame the method works in, link by link on normal forms
        source = 0 if method == "differentiation" else link
        raw = jacobian(chain, source, point, method, simplify=False, link=link)
        report(f"simplifying the {method.replace('_', ' ')} Jacobian in frame {frame}")
        factors = [*_link_rotations(chain, frame, source), raw]
        return sp.ImmutableMatrix(simplify_product(factors, chain.angle_bases(frame)))
    if simplify:  # the compact form starts from the raw one, which is kept too (code generation wants both)
        raw = jacobian(chain, frame, point, method, simplify=False, link=link)
        report(f"simplifying the {method.replace('_', ' ')} Jacobian in frame {frame}")
        return sp.ImmutableMatrix(simplify_matrix(raw, chain.angle_bases(frame)))
    derive = {"differentiation": _differentiation, "cross_product": _cross_product,
              "velocity_propagation": _velocity_propagation, "force_propagation": _force_propagation}[method]
    return sp.ImmutableMatrix(derive(chain, frame, point, link))


def _differentiation(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], link: int) -> sp.Matrix:
    robot = chain.robot
    T_0_l = chain.transform(0, link)
    x_P = T_0_l[:3, :3] * sp.Matrix(point) + T_0_l[:3, 3]
    J_0 = sp.zeros(6, chain.n_joints)
    for i, joint in enumerate(robot.joints[:link]):  # later joints do not move the point: their columns are zero
        report(f"differentiation, joint {i + 1} of {chain.n_joints}")
        J_0[:3, i] = x_P.applyfunc(_Derivative(joint.variable))
        if joint.is_revolute:
            J_0[3:, i] = chain.rotation(0, chain.axis_frame(joint.index))[:, 2]
    if chain.position(frame) == 0:
        return J_0
    return block_rotation(chain.rotation(frame, 0)) * J_0


class _Derivative:
    r""":math:`\partial e / \partial x` by SymPy's own rules (the very same result), each shared node once.

    ``expr.diff(x)`` walks a chain product as a tree: every level repeats the free-symbol search and the
    differentiation of the subexpressions it shares with its neighbours, so its cost doubles with each link. The
    same product rule, :math:`(uv)' = u'v + uv'`, :math:`\sin(u)' = \cos(u)\,u'`, applied once per distinct node,
    gives the identical expression in time linear in the number of nodes.
    """

    def __init__(self, variable: sp.Symbol):
        self.variable = variable
        self._memo: dict[sp.Expr, sp.Expr] = {}
        self._depends: dict[sp.Expr, bool] = {}

    def depends(self, expr: sp.Expr) -> bool:
        """Whether ``expr`` contains the variable (memoized per node, unlike ``free_symbols``)."""
        if isinstance(expr, Intermediate):
            return self.variable in expr.free_symbols
        if expr.is_Atom:
            return expr == self.variable
        if expr not in self._depends:
            self._depends[expr] = any(self.depends(arg) for arg in expr.args)
        return self._depends[expr]

    def __call__(self, expr: sp.Expr) -> sp.Expr:
        if not self.depends(expr):
            return sp.S.Zero
        if expr in self._memo:
            return self._memo[expr]
        if isinstance(expr, Intermediate):  # its derivative is an intermediate too, kept in it
            result: sp.Expr = derivative(expr, self.variable)
        elif expr.is_Atom:
            result = sp.S.One
        elif isinstance(expr, sp.Add):
            result = sp.Add(*[self(arg) for arg in expr.args])
        elif isinstance(expr, sp.Mul):
            args, terms = list(expr.args), []
            for i, arg in enumerate(args):
                d = self(arg)
                if d:
                    terms.append(sp.Mul(*args[:i], d, *args[i + 1:]))
            result = sp.Add(*terms)
        elif isinstance(expr, sp.sin | sp.cos) and self(expr.args[0]):
            outer = sp.cos(expr.args[0]) if isinstance(expr, sp.sin) else -sp.sin(expr.args[0])
            result = sp.Add(outer * self(expr.args[0]))
        else:
            result = expr.diff(self.variable)
        self._memo[expr] = result
        return result


def _cross_product(chain: Chain, frame: Frame, point: tuple[sp.Expr, ...], link: int) -> sp.Matrix:
    k = chain.position(frame)
    T_k_l = chain.transform(frame, link)
    p_kP = T_k_l[:3, :3] * sp.Matrix(point) + T_k_l[:3, 3]  # the point P, in {k}
    n = chain.n_joints
    J = sp.zeros(6, n)
    for i, joint in enumerate(chain.robot.joints[:link]):  # the axes of joints 1..l all come before frame {l}
        report(f"cross product, joint {i + 1} of {n}")
        a = chain.axis_frame(joint.index)
        T_k_a = chain.transform(frame, a)
        z_a = T_k_a[:3, 2]
        if not joint.is_revolute:
            J[:3, i] = z_a
            continue
        if chain.nested or _turns(chain, k, link) <= _turns(chain, a, link):  # p_P is no longer in {k}: read all in {k}
            J[:3, i] = z_a.cross(p_kP - T_k_a[:3, 3])
        else:  # p_aP is shorter in {a}, where z_a = [0, 0, 1]: take the cross product there, then rotate
            T_a_l = chain.transform(a, link)
            p_aP = T_a_l[:3, :3] * sp.Matrix(point) + T_a_l[:3, 3]
            J[:3, i] = T_k_a[:3, :3] * sp.Matrix([-p_aP[1], p_aP[0], 0])
        J[3:, i] = z_a
    return J


def _turns(chain: Chain, start: int, end: int) -> int:
    """How many times the joint axis turns (leaves a parallel group) between frame positions ``start`` and ``end``.

    A vector spanning m turns of a chain has about :math:`1.8^m` terms in normal form; parallel joints add none.
    """
    low, high = sorted((start, end))
    return sum(low <= group[-1] < high for group in chain.parallel_groups[:-1])


def _velocity_propagation(chain: Chain, frame: Frame, point: tuple[sp.Expr, sp.Expr, sp.Expr],
                          link: int) -> sp.Matrix:
    return _from_tip_frame(chain, frame, velocity_propagation(chain, point, simplify=False, link=link).jacobian, link)


def _force_propagation(chain: Chain, frame: Frame, point: tuple[sp.Expr, sp.Expr, sp.Expr], link: int) -> sp.Matrix:
    return _from_tip_frame(chain, frame, force_propagation(chain, point, simplify=False, link=link).jacobian, link)


def _link_rotations(chain: Chain, frame: Frame, source: int) -> list[sp.Matrix]:
    r"""The link-by-link frame changes from {s} to {k}: :math:`D_{k,k\pm1}, \dots, D_{s\mp1,s}`, leftmost first.

    With :math:`D_{a,b} = \mathrm{diag}({}^a_bR, {}^a_bR)`, their product is :math:`\mathrm{diag}({}^k_sR, {}^k_sR)`;
    multiplied on normal forms one link at a time, every intermediate is the Jacobian in a frame between.
    """
    rotations = []
    position = chain.position(frame)
    while position != source:
        step = position + 1 if position < source else position - 1
        rotations.append(block_rotation(chain.rotation(chain.frame_name(position), chain.frame_name(step))))
        position = step
    return rotations


def _from_tip_frame(chain: Chain, frame: Frame, J_n: sp.Matrix, link: int) -> sp.Matrix:
    r"""Move :math:`{}^nJ` into frame {k}: :math:`{}^kJ = \mathrm{diag}({}^k_nR, {}^k_nR)\,{}^nJ`, raw.

    For a point of an earlier link l the propagation ends in {l}, and n reads l.

    One product with the chain's own (shared) :math:`{}^k_nR`: 36 n products of shared subexpressions, where moving
    link by link cost n times more (a generic 30-joint chain: 20 s). The compact form never starts from this one:
    it multiplies the link rotations on normal forms (:func:`_derive`).
    """
    if chain.position(frame) == link:
        return J_n
    return block_rotation(chain.rotation(frame, link)) * J_n


def change_frame(J: sp.MatrixBase, R_b_a: sp.MatrixBase) -> sp.Matrix:
    r"""Re-express a basic Jacobian: :math:`{}^BJ = \mathrm{diag}({}^B_AR, {}^B_AR)\,{}^AJ`."""
    return block_rotation(sp.Matrix(R_b_a)) * sp.Matrix(J)


def shift_point(J: sp.MatrixBase, p: Sequence[sp.Expr]) -> sp.Matrix:
    r"""Move the reference point of a basic Jacobian by :math:`p` (in J's frame).

    .. math:: J_E = \begin{bmatrix} I & -\hat p \\ 0 & I \end{bmatrix} J_W

    Examples
    --------
    >>> L = sp.Symbol("L")
    >>> shift_point(sp.Matrix([0, 0, 0, 0, 0, 1]), [L, 0, 0]).T
    Matrix([[0, L, 0, 0, 0, 1]])
    """
    return point_shift(p) * sp.Matrix(J)


def jacobian_of(
    f: Sequence[sp.Expr] | sp.MatrixBase, q: Sequence[sp.Symbol], basis: AngleBasis | None = None
) -> sp.Matrix:
    r"""The Jacobian :math:`\partial f / \partial q` of any vector function (course chapter, section 4.2).

    With an angle ``basis`` the entries are simplified (see :mod:`symjac.symbolic.simplify`).

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> l1, l2 = sp.symbols("l1 l2")
    >>> f = [l1 * sp.cos(t1) + l2 * sp.cos(t1 + t2), l1 * sp.sin(t1) + l2 * sp.sin(t1 + t2)]
    >>> jacobian_of(f, [t1, t2])
    Matrix([
    [-l1*sin(theta1) - l2*sin(theta1 + theta2), -l2*sin(theta1 + theta2)],
    [ l1*cos(theta1) + l2*cos(theta1 + theta2),  l2*cos(theta1 + theta2)]])
    """
    J = sp.Matrix(f).jacobian(sp.Matrix(list(q)))
    return simplify_matrix(J, basis) if basis is not None else J
