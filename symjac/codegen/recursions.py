r"""Customised recursions for generated dynamics: straight-line code over sines, cosines and numbers.

The recursions of :mod:`symjac.analysis.dynamics` are run here on values that are either numbers, single symbols
or names of temporaries (a :class:`Trace`): every product of two known zeros is never formed, a unit entry of a
rotation multiplies nothing, a constant stays a number, and nothing is multiplied out from link to link, so the code
grows linearly with the chain and common subexpression elimination only has to share the small rest. This is the
"customised Newton-Euler" of Khalil and Kleinfinger: inverse dynamics with the inertial data about each link's origin
(mass :math:`m`, first moment :math:`h = m\,c`, tensor :math:`J = I_c + m(c^Tc\,E - c\,c^T)`, frame {k}),

.. math::
    F_k = m_k\dot v_k + \dot\omega_k \times h_k + \omega_k \times (\omega_k \times h_k), \qquad
    N_k = J_k\dot\omega_k + \omega_k \times J_k\omega_k + h_k \times \dot v_k,

the mass matrix by composite rigid bodies (:func:`mass_matrix_trace`), the gravity torques from the composite first
moments alone (:func:`gravity_trace`), and derivatives by forward-mode differentiation of a trace
(:meth:`Trace.derivative`), which gives the Coriolis matrix from the Christoffel symbols of the traced mass matrix.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import sympy as sp

from symjac.analysis.dynamics.bodies import joint_axis, link_bodies
from symjac.kinematics.chain import Chain
from symjac.symbolic.angles import AngleExpansion

__all__ = ["Trace", "gravity_trace", "mass_matrix_trace", "newton_euler_trace", "potential_energy_trace"]

Vector = tuple[sp.Expr, sp.Expr, sp.Expr]
Matrix3 = tuple[Vector, Vector, Vector]
ZERO: Vector = (sp.S.Zero, sp.S.Zero, sp.S.Zero)


def _is_simple(expr: sp.Expr) -> bool:
    """A number, a symbol, or a number times a symbol: kept inline rather than named."""
    if expr.is_Atom:
        return True
    return bool(expr.is_Mul and len(expr.args) == 2 and expr.args[0].is_Number and expr.args[1].is_Symbol)


def _cross(u: Vector, v: Vector) -> Vector:
    """``u x v`` entry by entry (a zero entry's products vanish as they are formed)."""
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _add(*vectors: Vector) -> Vector:
    """The sum of 3-vectors."""
    return (sp.Add(*(v[0] for v in vectors)), sp.Add(*(v[1] for v in vectors)), sp.Add(*(v[2] for v in vectors)))


def _scaled(s: sp.Expr, v: Vector) -> Vector:
    """``s v``."""
    return (s * v[0], s * v[1], s * v[2])


def _times(R: Matrix3, v: Vector) -> Vector:
    """``R v``."""
    return (R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2], R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2],
            R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2])


def _transposed(R: Matrix3) -> Matrix3:
    """``R^T``."""
    return ((R[0][0], R[1][0], R[2][0]), (R[0][1], R[1][1], R[2][1]), (R[0][2], R[1][2], R[2][2]))


def _dot(u: Vector, v: Vector) -> sp.Expr:
    """``u . v``."""
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


class Trace:
    """Straight-line code being built: temporaries in evaluation order, each a small expression of earlier ones.

    Values are numbers, symbols (arguments, sines and cosines ``_s{i}``/``_c{i}``, parameters) or temporaries
    ``_t0, _t1, ...``; :meth:`value` names anything larger, so no expression is ever multiplied out.
    """

    def __init__(self, chain: Chain, expansion: AngleExpansion):
        self.chain = chain
        self.expansion = expansion
        self.temporaries: list[tuple[sp.Symbol, sp.Expr]] = []
        self._fresh = sp.numbered_symbols("_t", real=True)
        self._names: dict[sp.Expr, sp.Symbol] = {}

    def value(self, expr: sp.Expr) -> sp.Expr:
        """``expr`` itself if it is simple, else a temporary holding it (one per distinct expression)."""
        expr = sp.sympify(expr)
        if _is_simple(expr):
            return expr
        if expr.could_extract_minus_sign():  # -x named as x, negated where used: one temporary for both
            return -self.value(-expr)
        if expr not in self._names:
            symbol = next(self._fresh)
            self.temporaries.append((symbol, expr))
            self._names[expr] = symbol
        return self._names[expr]

    def vector(self, v: Iterable[sp.Expr]) -> Vector:
        """Each entry named (:meth:`value`)."""
        a, b, c = (self.value(e) for e in v)
        return (a, b, c)

    def expanded(self, matrix: sp.MatrixBase) -> sp.Matrix:
        """A matrix of the chain (rotation, offset) with its sines and cosines those of single joint angles."""
        return sp.Matrix(matrix.shape[0], matrix.shape[1], self.expansion.expand_all(list(matrix)))

    def rotation(self, source: int, target: int) -> Matrix3:
        r""":math:`{}^{\text{source}}_{\text{target}}R`, each entry named when it is not simple."""
        R = self.expanded(self.chain.rotation(source, target))
        return (self.vector(R[0, :]), self.vector(R[1, :]), self.vector(R[2, :]))

    def offset(self, source: int, target: int) -> Vector:
        r""":math:`{}^{\text{source}}p_{\text{target}}`, named."""
        return self.vector(self.expanded(self.chain.transform(source, target)[:3, 3]))

    def derivative(self, exprs: Sequence[sp.Expr], direction: Mapping[int, sp.Expr]) -> list[sp.Expr]:
        r"""The directional derivative :math:`\sum_j \partial e / \partial q_j\,\mathrm{d}q_j` of each of ``exprs``.

        ``direction`` maps joint indices (0-based) to :math:`\mathrm{d}q_j` (missing: 0). Forward mode over the
        temporaries: each temporary that depends on a moved joint gets its derivative as a new temporary, so the
        derivative costs about as much as the values (and nothing where a joint does not reach).
        """
        joints = self.chain.robot.joints
        revolute = [j for j, joint in enumerate(joints) if joint.is_revolute]  # the expansion's order
        seeds: dict[sp.Symbol, sp.Expr] = {}
        for j, s, c in zip(revolute, self.expansion.sines, self.expansion.cosines, strict=True):
            if direction.get(j, 0) != 0:
                seeds[s], seeds[c] = c * direction[j], -s * direction[j]
        for j, joint in enumerate(joints):
            if not joint.is_revolute and direction.get(j, 0) != 0:
                seeds[joint.variable] = sp.sympify(direction[j])
        known = dict(seeds)
        for symbol, expr in list(self.temporaries):
            moved = self._moved(expr, known)
            if moved != 0:
                known[symbol] = self.value(moved)
        return [self._moved(sp.sympify(e), known) for e in exprs]

    @staticmethod
    def _moved(expr: sp.Expr, known: Mapping[sp.Symbol, sp.Expr]) -> sp.Expr:
        return sp.Add(*(expr.diff(u) * known[u] for u in expr.free_symbols if u in known))


def _body(trace: Trace, k: int) -> tuple[sp.Expr, Vector, Matrix3]:
    """Link k's mass, first moment and tensor about the origin of {k} (module docstring), named."""
    body = link_bodies(trace.chain)[k - 1]
    m = trace.value(body.mass)
    c = sp.Matrix(body.com)
    J = sp.Matrix(body.inertia) + body.mass * ((c.T * c)[0, 0] * sp.eye(3) - c * c.T)
    h = trace.vector(sp.expand(body.mass * v) for v in c)
    rows = [[trace.value(sp.expand(J[i, j])) for j in range(3)] for i in range(3)]
    return m, h, ((rows[0][0], rows[0][1], rows[0][2]), (rows[0][1], rows[1][1], rows[1][2]),
                  (rows[0][2], rows[1][2], rows[2][2]))


def _axis(trace: Trace, k: int) -> tuple[Vector, Vector, bool]:
    axis = joint_axis(trace.chain, k)
    z, r = trace.expanded(axis.z), trace.expanded(axis.r)
    return (z[0], z[1], z[2]), trace.vector(r), axis.revolute


def newton_euler_trace(trace: Trace, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr],
                       gravity: Sequence[sp.Expr]) -> list[sp.Expr]:
    r"""The joint torques by the customised Newton-Euler recursion (module docstring); gravity :math:`g_0` in {0}.

    The kinematic part is that of :func:`symjac.analysis.dynamics.newton_euler.recursion` (joint axes through the
    origin of {k-1} or {k}, prismatic joints), with every vector named as it is formed.
    """
    chain = trace.chain
    n = chain.n_joints
    w, wd = ZERO, ZERO
    vd: Vector = trace.vector(-sp.sympify(g) for g in gravity)
    forces = []
    for k in range(1, n + 1):
        z, r, revolute = _axis(trace, k)
        R, p = trace.rotation(k, k - 1), trace.offset(k - 1, k)
        qd, qdd = rates[k - 1], accelerations[k - 1]
        wr = trace.vector(_times(R, w))
        vd = _times(R, _add(vd, _cross(wd, p), _cross(w, trace.vector(_cross(w, p)))))
        if revolute:
            turn = _scaled(qd, z)
            rz = _cross(turn, r)
            vd = _add(vd, _cross(_scaled(qdd, z), r), _cross(turn, trace.vector(rz)), _scaled(2, _cross(wr, rz)))
            wd = trace.vector(_add(_times(R, wd), _cross(wr, turn), _scaled(qdd, z)))
            w = trace.vector(_add(wr, turn))
        else:
            vd = _add(vd, _scaled(qdd, z), _scaled(2, _cross(wr, _scaled(qd, z))))
            wd = trace.vector(_times(R, wd))
            w = wr
        vd = trace.vector(vd)
        m, h, J = _body(trace, k)
        F = trace.vector(_add(_scaled(m, vd), _cross(wd, h), _cross(w, trace.vector(_cross(w, h)))))
        N = trace.vector(_add(_times(J, wd), _cross(w, trace.vector(_times(J, w))), _cross(h, vd)))
        forces.append((z, r, revolute, F, N))
    f, nm = ZERO, ZERO
    tau: list[sp.Expr] = []
    for k in range(n, 0, -1):
        z, r, revolute, F, N = forces[k - 1]
        if k < n:
            R, p = trace.rotation(k, k + 1), trace.offset(k, k + 1)
            fr = trace.vector(_times(R, f))
            nm = trace.vector(_add(N, _times(R, nm), _cross(p, fr)))
            f = trace.vector(_add(F, fr))
        else:
            f, nm = F, N
        tau.append(_dot(z, _add(nm, _cross(r, f))) if revolute else _dot(z, f))
    return tau[::-1]


def gravity_trace(trace: Trace, gravity: Sequence[sp.Expr]) -> list[sp.Expr]:
    r"""The gravity torques from composite bodies: :math:`\tau_k = z^T((H_k + M_k r) \times a_k)` (revolute).

    :math:`a_k = {}^k_{k-1}R\,a_{k-1}` with :math:`a_0 = -g_0`; :math:`M_k` and :math:`H_k` are the mass and the first
    moment (about the origin of {k}, in {k}) of links k..n; a prismatic joint carries :math:`M_k z^T a_k`.
    """
    chain = trace.chain
    n = chain.n_joints
    a: Vector = tuple(-sp.sympify(g) for g in gravity)  # type: ignore[assignment]
    accelerations = []
    for k in range(1, n + 1):
        a = trace.vector(_times(trace.rotation(k, k - 1), a))
        accelerations.append(a)
    mass, H = sp.S.Zero, ZERO
    tau: list[sp.Expr] = []
    for k in range(n, 0, -1):
        m, h, _ = _body(trace, k)
        if k < n:
            R, p = trace.rotation(k, k + 1), trace.offset(k, k + 1)
            H = trace.vector(_add(h, _times(R, H), _scaled(mass, p)))
        else:
            H = h
        mass = trace.value(mass + m)
        z, r, revolute = _axis(trace, k)
        a = accelerations[k - 1]
        tau.append(_dot(z, _cross(_add(H, _scaled(mass, r)), a)) if revolute else mass * _dot(z, a))
    return tau[::-1]


def potential_energy_trace(trace: Trace, gravity: Sequence[sp.Expr]) -> sp.Expr:
    r"""The potential energy :math:`V = -\sum_i m_i\,g_0^T p_{ci}` from the masses beyond each joint and first moments.

    With :math:`a_k = {}^k_{k-1}R\,a_{k-1}`, :math:`a_0 = -g_0` (gravity's opposite in {k}) and :math:`M_k` the mass
    of links k..n: :math:`V = \sum_k M_k\,a_{k-1}^T\,{}^{k-1}p_k + \sum_k a_k^T h_k` (:math:`h_k = m_k c_k`).
    """
    n = trace.chain.n_joints
    a: Vector = tuple(-sp.sympify(g) for g in gravity)  # type: ignore[assignment]
    bodies = [_body(trace, k)[:2] for k in range(1, n + 1)]
    terms: list[sp.Expr] = []
    masses = [sp.S.Zero] * (n + 1)
    for k in range(n, 0, -1):
        masses[k - 1] = masses[k] + bodies[k - 1][0]
    for k in range(1, n + 1):
        terms.append(trace.value(masses[k - 1]) * _dot(a, trace.offset(k - 1, k)))
        a = trace.vector(_times(trace.rotation(k, k - 1), a))
        terms.append(_dot(a, bodies[k - 1][1]))
    return sp.Add(*terms)


def _skew_product(u: Vector, v: Vector) -> Matrix3:
    """The matrix of ``x -> u x (v x x)``, i.e. ``[u][v] = v u^T - (u . v) E``."""
    d = _dot(u, v)
    return tuple(tuple(v[i] * u[j] - (d if i == j else 0) for j in range(3)) for i in range(3))  # type: ignore[return-value]


def mass_matrix_trace(trace: Trace) -> list[list[sp.Expr]]:
    r"""The mass matrix by composite rigid bodies, in each link's frame.

    The composite body of links k..n has mass :math:`M`, first moment :math:`H` and tensor :math:`\mathcal J` about
    the origin of {k}; moving a body from {k+1} to {k} (:math:`R = {}^k_{k+1}R`, :math:`p = {}^kp_{k+1}`,
    :math:`\hat h = R h`): :math:`h' = \hat h + M p`, :math:`J' = R J R^T - [\hat h][p] - [p][\hat h] - M[p]^2`.
    Joint j's unit motion (:math:`\omega = z`, :math:`v = z \times r`; or :math:`v = z`) meets the force
    :math:`f = M v + \omega \times H`, :math:`n = \mathcal J \omega + H \times v`; moved down the chain it gives
    :math:`M_{ij} = z_i^T(n_i + r_i \times f_i)` (or :math:`z_i^T f_i`).
    """
    chain = trace.chain
    n = chain.n_joints
    composite: list[tuple[sp.Expr, Vector, Matrix3]] = [None] * n  # type: ignore[list-item]
    for k in range(n, 0, -1):
        m, h, J = _body(trace, k)
        if k < n:
            mc, hc, Jc = composite[k]
            R, p = trace.rotation(k, k + 1), trace.offset(k, k + 1)
            hr = trace.vector(_times(R, hc))
            RJ = [trace.vector(_times(R, column)) for column in _transposed(Jc)]  # columns of R J
            RJRt = [trace.vector(_times(R, row)) for row in zip(*RJ, strict=True)]  # columns of R (R J)^T
            a, b, pp = _skew_product(hr, p), _skew_product(p, hr), _skew_product(p, p)
            entries = {(i, j): trace.value(J[i][j] + RJRt[j][i] - a[i][j] - b[i][j] - mc * pp[i][j])
                       for i in range(3) for j in range(i, 3)}
            J = tuple(tuple(entries[min(i, j), max(i, j)] for j in range(3)) for i in range(3))  # type: ignore[assignment]
            h = trace.vector(_add(h, hr, _scaled(mc, p)))
            m = trace.value(m + mc)
        composite[k - 1] = (m, h, J)
    axes = [_axis(trace, k) for k in range(1, n + 1)]
    M = [[sp.S.Zero] * n for _ in range(n)]
    for j in range(n, 0, -1):
        m, h, J = composite[j - 1]
        z, r, revolute = axes[j - 1]
        if revolute:
            v = _cross(z, r)
            f = trace.vector(_add(_scaled(m, v), _cross(z, h)))
            nm = trace.vector(_add(_times(J, z), _cross(h, v)))
        else:
            f, nm = trace.vector(_scaled(m, z)), trace.vector(_cross(h, z))
        for i in range(j, 0, -1):
            if i < j:
                R, p = trace.rotation(i, i + 1), trace.offset(i, i + 1)
                f = trace.vector(_times(R, f))
                nm = trace.vector(_add(_times(R, nm), _cross(p, f)))
            zi, ri, rev = axes[i - 1]
            M[i - 1][j - 1] = M[j - 1][i - 1] = _dot(zi, _add(nm, _cross(ri, f))) if rev else _dot(zi, f)
    return M
