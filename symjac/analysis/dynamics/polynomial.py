r"""The Newton-Euler recursion run in the polynomial image: every quantity a normal form, no layout between links.

:func:`~symjac.analysis.dynamics.newton_euler.recursion` with ``simplify=True`` used to lay every step out as a
SymPy expression (:func:`~symjac.analysis.dynamics.bodies.tidy`) and multiply those trees with the next link's
rotation; most of its time went into building trees and converting them back. Here every input of the recursion
(rotations, offsets, axes, inertial data, rates, accelerations, gravity) is converted once into one polynomial ring
(:func:`~symjac.symbolic.trigpoly.image_of`, sines and cosines of frame {0}'s angle basis as generators), and the
recursion multiplies normal forms, reduced modulo :math:`S_j^2 + C_j^2 - 1` after each product: terms that vanish are
gone before the next link multiplies them, exactly (the normal form is unique). Each quantity is laid out only when
it is asked for (:class:`PolynomialSteps`); the torques are then the same normal forms the tree route gave, laid out
the same way.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.polys.rings import PolyElement

from symjac.analysis.dynamics.bodies import joint_axis, link_bodies
from symjac.kinematics.chain import Chain
from symjac.symbolic.layout import nested_expr
from symjac.symbolic.trigpoly import TrigImage, image_of, reduce_image

__all__ = ["PolynomialSteps", "christoffel_coriolis", "polynomial_recursion"]

Vector = tuple[PolyElement, PolyElement, PolyElement]


class _Algebra:
    """3-vectors and 3 x 3 matrices of normal forms, each entry reduced once after its products are summed."""

    def __init__(self, image: TrigImage):
        self.image = image
        self.zero = image.ring_and_gens[0].zero

    def reduce(self, poly: PolyElement) -> PolyElement:
        return reduce_image(poly, self.image) if poly else poly

    def cross(self, u: Vector, v: Vector) -> Vector:
        if not any(u) or not any(v):
            return (self.zero, self.zero, self.zero)
        return (self.reduce(u[1] * v[2] - u[2] * v[1]), self.reduce(u[2] * v[0] - u[0] * v[2]),
                self.reduce(u[0] * v[1] - u[1] * v[0]))

    def times(self, R: Sequence[Sequence[PolyElement]], v: Vector) -> Vector:
        if not any(v):
            return (self.zero, self.zero, self.zero)
        entries = []
        for row in R:
            total = self.zero
            for a, b in zip(row, v, strict=True):
                if a and b:
                    total += a * b
            entries.append(self.reduce(total))
        return (entries[0], entries[1], entries[2])

    def scaled(self, s: PolyElement, v: Vector) -> Vector:
        if not s:
            return (self.zero, self.zero, self.zero)
        return (self.reduce(s * v[0]), self.reduce(s * v[1]), self.reduce(s * v[2]))

    @staticmethod
    def add(*vectors: Vector) -> Vector:
        return (sum((v[0] for v in vectors[1:]), vectors[0][0]), sum((v[1] for v in vectors[1:]), vectors[0][1]),
                sum((v[2] for v in vectors[1:]), vectors[0][2]))

    def dot(self, u: Vector, v: Vector) -> PolyElement:
        total = self.zero
        for a, b in zip(u, v, strict=True):
            if a and b:
                total += a * b
        return self.reduce(total)


class PolynomialSteps:
    """Each link's quantities as normal forms (``values[k - 1][name]``) and the torques, with the image to lay out."""

    def __init__(self, image: TrigImage, values: list[dict[str, Vector]], torques: list[PolyElement]):
        self.image = image
        self.values = values
        self.torques = torques

    def expression(self, poly: PolyElement) -> sp.Expr:
        """A normal form as a nested SymPy expression (frame {0}'s basis)."""
        return nested_expr(poly, self.image)

    def vector(self, link: int, name: str) -> sp.ImmutableMatrix:
        """Quantity ``name`` of link ``link`` (1-based) as a 3 x 1 matrix of nested expressions."""
        return sp.ImmutableMatrix([self.expression(p) for p in self.values[link - 1][name]])


def polynomial_recursion(chain: Chain, rates: Sequence[sp.Expr], accelerations: Sequence[sp.Expr],
                         gravity_vector: Sequence[sp.Expr]) -> PolynomialSteps:
    """The recursion of :func:`~symjac.analysis.dynamics.newton_euler.recursion` on normal forms (module docstring)."""
    n = chain.n_joints
    bodies = link_bodies(chain)
    inputs: list[Any] = [*rates, *accelerations, *gravity_vector]
    layout = []
    for k in range(1, n + 1):
        axis = joint_axis(chain, k)
        R, p = chain.rotation(k, k - 1), chain.transform(k - 1, k)[:3, 3]
        body = bodies[k - 1]
        start = len(inputs)
        inputs += [*R, *p, *axis.z, *axis.r, body.mass, *body.com, *body.inertia]
        layout.append((start, axis.revolute))
    image, polys = image_of([sp.sympify(e) for e in inputs], chain.angle_basis(0))
    algebra = _Algebra(image)
    zero3: Vector = (algebra.zero, algebra.zero, algebra.zero)
    qd, qdd, g = polys[:n], polys[n:2 * n], polys[2 * n:2 * n + 3]
    links = []
    for start, revolute in layout:
        R = [polys[start:start + 3], polys[start + 3:start + 6], polys[start + 6:start + 9]]
        p, z, r = (tuple(polys[start + i:start + i + 3]) for i in (9, 12, 15))
        mass, com = polys[start + 18], tuple(polys[start + 19:start + 22])
        inertia = [polys[start + 22:start + 25], polys[start + 25:start + 28], polys[start + 28:start + 31]]
        links.append((R, p, z, r, mass, com, inertia, revolute))
    omega, alpha = zero3, zero3
    a: Vector = (-g[0], -g[1], -g[2])
    values: list[dict[str, Vector]] = []
    for k, (R, p, z, r, mass, c, inertia, revolute) in enumerate(links):
        turn = algebra.scaled(qd[k], z) if revolute else zero3
        turning = algebra.scaled(qdd[k], z) if revolute else zero3
        slide = zero3 if revolute else algebra.scaled(qd[k], z)
        sliding = zero3 if revolute else algebra.scaled(qdd[k], z)
        omega_rotated = algebra.times(R, omega)
        a = algebra.times(R, algebra.add(a, algebra.cross(alpha, p), algebra.cross(omega, algebra.cross(omega, p))))
        u = algebra.add(algebra.cross(turn, r), slide)
        a = algebra.add(a, algebra.cross(turning, r), algebra.cross(turn, algebra.cross(turn, r)), sliding,
                        algebra.scaled(image.ring_and_gens[0](2), algebra.cross(omega_rotated, u)))
        alpha = algebra.add(algebra.times(R, alpha), algebra.cross(omega_rotated, turn), turning)
        omega = algebra.add(omega_rotated, turn)
        a_c = algebra.add(a, algebra.cross(alpha, c), algebra.cross(omega, algebra.cross(omega, c)))
        F = algebra.scaled(mass, a_c)
        N = algebra.add(algebra.times(inertia, alpha), algebra.cross(omega, algebra.times(inertia, omega)))
        values.append({"omega": omega, "alpha": alpha, "a": a, "a_c": a_c, "F": F, "N": N})
    f, m = zero3, zero3
    torques: list[PolyElement] = [algebra.zero] * n
    for k in range(n - 1, -1, -1):
        R, p, z, r, mass, c, inertia, revolute = links[k]
        F, N = values[k]["F"], values[k]["N"]
        if k < n - 1:
            R_next, p_next = links[k + 1][0], links[k + 1][1]
            R_back = [[R_next[j][i] for j in range(3)] for i in range(3)]  # (^{k+1}_kR)^T = ^k_{k+1}R
            f_rotated = algebra.times(R_back, f)
            m = algebra.add(N, algebra.times(R_back, m), algebra.cross(c, F), algebra.cross(p_next, f_rotated))
            f = algebra.add(f_rotated, F)
        else:
            f, m = F, algebra.add(N, algebra.cross(c, F))
        values[k]["f"], values[k]["n"] = f, m
        torques[k] = algebra.dot(z, algebra.add(m, algebra.cross(r, f))) if revolute else algebra.dot(z, f)
    return PolynomialSteps(image, values, torques)


def christoffel_coriolis(chain: Chain, M: sp.MatrixBase, q: Sequence[sp.Symbol], rates: Sequence[sp.Symbol]
                         ) -> list[sp.Expr] | None:
    r"""The Coriolis matrix of the Christoffel symbols of ``M``, differentiated on normal forms; row-major.

    .. math:: C_{kj} = \sum_i \tfrac12 (\partial_i M_{kj} + \partial_j M_{ki} - \partial_k M_{ij})\,\dot q_i

    with :math:`\partial S_b/\partial\theta_i = m_{bi} C_b` and :math:`\partial C_b/\partial\theta_i = -m_{bi} S_b`
    for the basis angles :math:`\psi_b = \sum_i m_{bi}\theta_i + o_b` (frame {0}'s basis, the first result basis), a
    prismatic variable being a generator of its own. The entries come back laid out in that basis. ``None`` when the
    ring holds an atom that depends on a coordinate otherwise (the caller then differentiates the trees).
    """
    basis = chain.angle_basis(0)
    n = len(q)
    image, polys = image_of([*M, *rates], basis)
    coordinates = set(q)
    if any(getattr(atom, "free_symbols", set()) & coordinates for atom in image.atoms if atom not in coordinates):
        return None
    _, gens = image.ring_and_gens
    offset = 2 * image.angle_count
    slopes = [sp.expand(angle) for angle in basis.angles]
    entries, qd = polys[:n * n], polys[n * n:]
    zero = image.ring_and_gens[0].zero

    def derivative(poly: PolyElement, variable: sp.Symbol) -> PolyElement:
        result = zero
        if variable in basis.variables:
            for b, slope in enumerate(slopes):
                m = slope.coeff(variable)
                if m:
                    S, C = image.sine(b), image.cosine(b)
                    result += int(m) * (poly.diff(S) * C - poly.diff(C) * S)
        elif variable in image.atoms:
            result = poly.diff(gens[offset + image.atoms.index(variable)])
        return reduce_image(result, image) if result else result

    dM = [[derivative(entry, variable) for entry in entries] for variable in q]  # dM[i][k * n + j]
    half = image.ring_and_gens[0](sp.Rational(1, 2))
    result = []
    for k in range(n):
        for j in range(n):
            total = zero
            for i in range(n):
                christoffel = dM[i][k * n + j] + dM[j][k * n + i] - dM[k][i * n + j]
                if christoffel and qd[i]:
                    total += christoffel * qd[i]
            result.append(nested_expr(reduce_image(half * total, image), image) if total else sp.S.Zero)
    return result
