r"""Acceleration propagation: Craig's outward iteration of link velocities and accelerations, frame by frame.

Each quantity belongs to the origin of frame {k} (or to the rigid body of link k) and is written in {k}'s own
axes. Joint k turns about, or slides along, the axis :math:`z_a` through the origin of frame {a} (a = k in the
modified and general conventions, k - 1 in the standard one; see :meth:`symjac.kinematics.chain.Chain.axis_frame`). With
:math:`R = {}^k_{k-1}R`, :math:`p = {}^{k-1}p_k` (origin of {k} seen from {k-1}), :math:`r = {}^kp_{ak}` (origin of
{k} seen from the axis point; zero unless the convention is standard), :math:`\omega' = R\,{}^{k-1}\omega_{k-1}`
and :math:`\dot\theta_k = 0` for a prismatic, :math:`\dot d_k = 0` for a revolute joint:

.. math::
    {}^k\omega_k &= \omega' + \dot\theta_k\,z_a \\
    {}^k\dot\omega_k &= R\,{}^{k-1}\dot\omega_{k-1} + \omega' \times \dot\theta_k z_a + \ddot\theta_k\,z_a \\
    {}^kv_k &= R\,({}^{k-1}v_{k-1} + {}^{k-1}\omega_{k-1} \times p) + u, \qquad
        u = \dot\theta_k\,z_a \times r + \dot d_k\,z_a \\
    {}^k\dot v_k &= R\,\big({}^{k-1}\dot v_{k-1} + {}^{k-1}\dot\omega_{k-1} \times p
        + {}^{k-1}\omega_{k-1} \times ({}^{k-1}\omega_{k-1} \times p)\big)
        + \ddot\theta_k\,z_a \times r + \dot\theta_k z_a \times (\dot\theta_k z_a \times r) + \ddot d_k\,z_a
        + 2\,\omega' \times u

The first term of each line carries link k-1's motion rigidly to the origin of {k}; the rest is joint k's motion
relative to link k-1, with the Coriolis term :math:`2\,\omega' \times u`. For the modified convention r = 0, and
these are Craig's (6.45)-(6.47) (his :math:`2\,\omega_{k} \times \dot d_k z_k` equals ours: a prismatic joint adds
no rotation). Past frame {n} a rigid step (no joint) reaches the tool frame or a point fixed in {n} (axes of {n});
for a point fixed in an earlier link l (``link=l``) the iteration stops at {l} and the rigid step starts there.
:math:`\dot v` is the classical acceleration :math:`\ddot p` of the origin, expressed in the moving frame.

With :math:`\ddot q = 0` the tip acceleration, rotated into {0}, is the bias acceleration :math:`\dot J\dot q` of
:func:`symjac.kinematics.acceleration.bias_acceleration`; in general it is :math:`J\ddot q + \dot J\dot q`.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from symjac.errors import FrameError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.coupling import CouplingLaw
from symjac.kinematics.memo import memoized
from symjac.kinematics.points import Point, link_of, link_point
from symjac.model.robot import Robot
from symjac.symbolic.simplify import simplify_matrix

__all__ = [
    "AccelerationPropagation",
    "AccelerationStep",
    "acceleration_propagation",
    "joint_accelerations",
]

_ZERO = sp.ImmutableMatrix.zeros(3, 1)


def joint_accelerations(robot: Robot | Chain) -> tuple[sp.Symbol, ...]:
    r"""The acceleration symbols :math:`\ddot q` of the coordinates, in order.

    Without a coupling these are the joint accelerations :math:`\ddot\theta_i` (``thetaddot{i}``) or
    :math:`\ddot d_i` (``dddot{i}``); a coupled robot's are those of its coordinates.

    Examples
    --------
    >>> from symjac import load_robot
    >>> joint_accelerations(load_robot("scara"))
    (thetaddot1, thetaddot2, dddot3, thetaddot4)
    """
    return as_chain(robot).robot.coordinate_accelerations


@dataclass(frozen=True)
class AccelerationStep:
    r"""Motion of one frame's origin, in that frame's axes: :math:`\omega, \dot\omega, v, \dot v` (3 x 1 each).

    ``frame`` is 0..n, ``"tool"``, or ``"point"`` (a point fixed in the last link propagated, in its axes).
    """

    frame: Frame | str
    omega: sp.ImmutableMatrix
    omegadot: sp.ImmutableMatrix
    v: sp.ImmutableMatrix
    vdot: sp.ImmutableMatrix


@dataclass(frozen=True)
class AccelerationPropagation:
    """The outward iteration: one :class:`AccelerationStep` per frame, base to tip, and the symbols used."""

    rates: tuple[sp.Symbol, ...]
    accelerations: tuple[sp.Symbol, ...]
    steps: tuple[AccelerationStep, ...]

    @property
    def tip(self) -> AccelerationStep:
        """The last step: the tool frame, the point, or frame {n}."""
        return self.steps[-1]

    @property
    def acceleration(self) -> sp.Matrix:
        r"""The tip's :math:`[\dot v; \dot\omega]` (6 x 1) in the tip frame's axes, in q and its two derivatives."""
        return sp.Matrix.vstack(sp.Matrix(self.tip.vdot), sp.Matrix(self.tip.omegadot))

    @property
    def bias(self) -> sp.Matrix:
        r"""The tip acceleration at :math:`\ddot q = 0`, in the tip frame's axes: :math:`\dot J\dot q` rotated there."""
        return self.acceleration.xreplace(dict.fromkeys(self.accelerations, sp.S.Zero))

    def in_coordinates(self, chain: Chain, law: CouplingLaw) -> AccelerationPropagation:
        r"""Written in ``chain``'s coordinates: every vector moved by ``law`` (the rates law, :math:`\vartheta(q)`)."""
        return AccelerationPropagation(chain.robot.coordinate_rates, chain.robot.coordinate_accelerations, tuple(
            AccelerationStep(s.frame, *(law(chain, m) for m in (s.omega, s.omegadot, s.v, s.vdot)))
            for s in self.steps))


def _coordinates(chain: Chain, point: Point | None, link: int) -> tuple[sp.Expr, ...] | None:
    """``None`` (the tool frame, on the last link only) or the point's coordinates in {link}, validated."""
    if point == "end":
        point = None if chain.robot.tool is not None and link == chain.n_joints else (0, 0, 0)
    if point is None:
        if link != chain.n_joints:
            raise FrameError(f"the tool frame is fixed in the last link ({chain.n_joints}), not in link {link}")
        return None
    return link_point(chain, point, link)  # floats become exact rationals


@memoized(link=link_of, point=_coordinates, coupling="rates")
def acceleration_propagation(
    chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr] | str | None = "end", *, simplify: bool = True,
    link: int | None = None,
) -> AccelerationPropagation:
    r"""Propagate angular and linear velocities and accelerations from the base to the tip (module docstring).

    Parameters
    ----------
    robot : Robot or Chain
    point : tuple of 3, or None
        The tip, as for :func:`symjac.kinematics.propagation.velocity_propagation`: a point given in frame {l} of its
        link, or ``None`` for the tool frame; default ``"end"``, the end of the chain (the tool frame when the robot
        has one and l is the last link, else the origin of {l}).
    simplify : bool
        Lay every step out in compact textbook form (default); ``False`` keeps the raw products. The iteration
        always runs on the raw products.
    link : int, optional
        The link l the point is fixed in (default n): the iteration stops at frame {l}.

    Returns
    -------
    AccelerationPropagation
        Steps for frames 0..l (then the tool frame or the point), each in the joint variables, the rates of
        :func:`symjac.kinematics.propagation.joint_rate_symbols` and the accelerations of :func:`joint_accelerations`.

    Examples
    --------
    >>> from symjac import load_robot
    >>> result = acceleration_propagation(load_robot("planar2r"))
    >>> result.steps[1].vdot.T  # the end of link 1, in frame {1}: centripetal along -x, tangential along y
    Matrix([[-L1*thetadot1**2, L1*thetaddot1, 0]])
    >>> result.tip.omegadot.T
    Matrix([[0, 0, thetaddot1 + thetaddot2]])
    """
    # coupled: theta = theta(q), thetadot = C qdot, thetaddot = C qddot (the rates law)
    return _derive(chain, point, simplify, link)  # type: ignore[arg-type]  # normalised by @memoized


def _derive(chain: Chain, point: tuple[sp.Expr, ...] | None, simplify: bool, link: int) -> AccelerationPropagation:
    if not simplify:
        return _propagate(chain, point, link)
    raw = acceleration_propagation(chain, point, simplify=False, link=link)

    def layout(step: AccelerationStep) -> AccelerationStep:
        frame: Frame = link if step.frame == "point" else step.frame  # type: ignore[assignment]  # "point": {l}
        stacked = sp.Matrix.vstack(step.omega, step.omegadot, step.v, step.vdot)
        flat = _collect_rates(simplify_matrix(stacked, chain.angle_bases(frame)), raw.rates)
        parts = [sp.ImmutableMatrix(flat[i:i + 3, :]) for i in (0, 3, 6, 9)]
        return AccelerationStep(step.frame, *parts)

    return AccelerationPropagation(raw.rates, raw.accelerations, tuple(layout(step) for step in raw.steps))


def _collect_rates(matrix: sp.MatrixBase, rates: tuple[sp.Symbol, ...]) -> sp.Matrix:
    """Factor sums of rates where that is shorter: ``thetadot1*(thetadot1 + 2*thetadot2) + thetadot2**2``."""
    symbols = frozenset(rates)

    def is_rate_sum(expr: sp.Expr) -> bool:
        return expr.is_Add and bool(expr.free_symbols) and expr.free_symbols <= symbols

    def shorter(expr: sp.Expr) -> sp.Expr:
        factored = sp.factor(expr)
        return factored if sp.count_ops(factored) < sp.count_ops(expr) else expr

    return sp.Matrix(matrix).applyfunc(lambda entry: entry.replace(is_rate_sum, shorter))


def _rigid(omega: sp.Matrix, omegadot: sp.Matrix, v: sp.Matrix, vdot: sp.Matrix,
           p: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    """Velocity and acceleration of the point at ``p`` of a rigid body whose origin moves with (v, vdot)."""
    return v + omega.cross(p), vdot + omegadot.cross(p) + omega.cross(omega.cross(p))


def _propagate(chain: Chain, point: tuple[sp.Expr, ...] | None, link: int) -> AccelerationPropagation:
    model = chain.robot
    rates, accelerations = model.coordinate_rates, model.coordinate_accelerations  # uncoupled: the joints' own
    omega, omegadot, v, vdot = (sp.zeros(3, 1) for _ in range(4))
    steps = [AccelerationStep(0, _ZERO, _ZERO, _ZERO, _ZERO)]
    for k, joint in enumerate(model.joints[:link], start=1):
        R = sp.Matrix(chain.rotation(k, k - 1))
        p = sp.Matrix(chain.transform(k - 1, k)[:3, 3])
        v_moved, vdot_moved = _rigid(omega, omegadot, v, vdot, p)
        omega_prev = R * omega  # link k-1's rotation, in the axes of {k}
        axis = chain.axis_frame(k)
        z = sp.Matrix(chain.rotation(k, axis)[:, 2])
        r = -sp.Matrix(chain.transform(k, axis)[:3, 3])  # axis point -> origin of {k}; zero unless standard DH
        rate, acceleration = rates[k - 1], accelerations[k - 1]
        if joint.is_revolute:
            spin = rate * z
            u = spin.cross(r)
            relative = (acceleration * z).cross(r) + spin.cross(u)
            omega = omega_prev + spin
            omegadot = R * omegadot + omega_prev.cross(spin) + acceleration * z
        else:
            u = rate * z
            relative = acceleration * z
            omega = omega_prev
            omegadot = R * omegadot
        v = R * v_moved + u
        vdot = R * vdot_moved + relative + 2 * omega_prev.cross(u)
        steps.append(_step(k, omega, omegadot, v, vdot))
    if point is None:
        R_t_n = sp.Matrix(chain.rotation("tool", chain.n_joints))
        v_t, vdot_t = _rigid(omega, omegadot, v, vdot, sp.Matrix(chain.transform(chain.n_joints, "tool")[:3, 3]))
        steps.append(_step("tool", R_t_n * omega, R_t_n * omegadot, R_t_n * v_t, R_t_n * vdot_t))
    elif any(c != 0 for c in point):
        v_p, vdot_p = _rigid(omega, omegadot, v, vdot, sp.Matrix(point))
        steps.append(_step("point", omega, omegadot, v_p, vdot_p))
    return AccelerationPropagation(rates, accelerations, tuple(steps))


def _step(frame: Frame | str, *vectors: sp.Matrix) -> AccelerationStep:
    omega, omegadot, v, vdot = (sp.ImmutableMatrix(vector) for vector in vectors)
    return AccelerationStep(frame, omega, omegadot, v, vdot)
