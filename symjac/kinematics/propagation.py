r"""The iterative derivations of the Jacobian: velocities propagated outward, static forces propagated inward.

Both work link by link in the link's own frame, as Craig teaches them, and keep every intermediate result.

**Velocity propagation** (base to tip). With :math:`{}^{k}_{k-1}R` and :math:`{}^{k-1}p_k` from the link transform,
joint k turning at :math:`\dot\theta_k` or sliding at :math:`\dot d_k` about or along the axis :math:`z_a` (frame
{a} = {k} in the modified convention, {k-1} in the standard one):

.. math::
    {}^k\omega_k = {}^{k}_{k-1}R\,{}^{k-1}\omega_{k-1} + \dot\theta_k\,{}^kz_a, \qquad
    {}^kv_k = {}^{k}_{k-1}R\,({}^{k-1}v_{k-1} + {}^{k-1}\omega_{k-1} \times {}^{k-1}p_k)
              + \dot\theta_k\,{}^kz_a \times {}^kp_{ak} + \dot d_k\,{}^kz_a

For the modified convention :math:`p_{ak} = 0` and these are exactly Craig's (5.45)-(5.47). Past frame {n}, a rigid
step carries the motion to the tool frame or to a point fixed in {n}. For a point fixed in an earlier link l
(``link=l``) the iteration stops at {l} and the rigid step starts there; joints after l add nothing. Every quantity
is linear in the joint rates, so it is propagated as its coefficient matrix (3 x n), and the last one *is* the
Jacobian :math:`{}^nJ`.

**Force propagation** (tip to base). A wrench :math:`[f; n]` applied by the arm at the tip, expressed in the tip
frame, is carried to every frame origin:

.. math::
    {}^{k-1}f = {}^{k-1}_{k}R\,{}^kf, \qquad {}^{k-1}n = {}^{k-1}_{k}R\,{}^kn + {}^{k-1}p_k \times {}^{k-1}f,

and joint k bears :math:`\tau_k = {}^an \cdot z_a` (revolute) or :math:`{}^af \cdot z_a` (prismatic). The torques are
linear in the wrench; their coefficient matrix is :math:`{}^nJ^T` (the duality of velocity and force). A wrench at a
point of an earlier link l (``link=l``) starts at {l}: the joints after l bear none of it.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import sympy as sp

from symjac.errors import FrameError
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.coupling import COUPLING_LAWS, CouplingLaw
from symjac.kinematics.memo import memoized
from symjac.kinematics.points import link_of
from symjac.model.robot import WRENCH_NAMES, Robot
from symjac.progress import report
from symjac.symbolic.simplify import simplify_matrix
from symjac.symbolic.transforms import skew

__all__ = [
    "ForcePropagation",
    "ForceStep",
    "VelocityPropagation",
    "VelocityStep",
    "force_propagation",
    "joint_rate_symbols",
    "linear_combination",
    "velocity_propagation",
    "wrench_symbols",
]

_Z = sp.Matrix([0, 0, 1])


def joint_rate_symbols(robot: Robot | Chain) -> tuple[sp.Symbol, ...]:
    r"""The rate symbols :math:`\dot q` of the coordinates, in order: what Jacobian columns multiply.

    Without a coupling these are the joint rates :math:`\dot\theta_i` (``thetadot{i}``) or :math:`\dot d_i`
    (``ddot{i}``); a coupled robot's are the rates of its coordinates (:attr:`Robot.coordinate_rates
    <symjac.model.robot.Robot.coordinate_rates>`).

    Examples
    --------
    >>> from symjac import load_robot
    >>> joint_rate_symbols(load_robot("stanford"))
    (thetadot1, thetadot2, ddot3, thetadot4, thetadot5, thetadot6)
    """
    return as_chain(robot).robot.coordinate_rates


def wrench_symbols() -> tuple[sp.Symbol, ...]:
    r"""The components :math:`f_x, f_y, f_z, n_x, n_y, n_z` of a symbolic wrench."""
    return tuple(sp.Symbol(name, real=True) for name in WRENCH_NAMES)


@dataclass(frozen=True)
class VelocityStep:
    r"""Velocities of one frame, expressed in that frame, as coefficient matrices of the joint rates.

    ``omega`` and ``v`` (each 3 x n) give :math:`{}^k\omega_k = W_k\,\dot q` and :math:`{}^kv_k = V_k\,\dot q`.
    ``frame`` is 0..n, ``"tool"``, or ``"point"`` (a point fixed in the last link propagated, in its axes).
    """

    frame: Frame | str
    omega: sp.ImmutableMatrix
    v: sp.ImmutableMatrix


@dataclass(frozen=True)
class VelocityPropagation:
    """The outward iteration: one :class:`VelocityStep` per frame, base to tip, and the joint rates used."""

    rates: tuple[sp.Symbol, ...]
    steps: tuple[VelocityStep, ...]

    def velocities(self) -> list[tuple[Frame | str, sp.Matrix, sp.Matrix]]:
        r"""Per step: the frame, :math:`{}^k\omega_k` and :math:`{}^kv_k` as vectors in the joint rates."""
        rates = sp.Matrix(self.rates)
        return [(s.frame, linear_combination(s.omega, rates), linear_combination(s.v, rates)) for s in self.steps]

    @property
    def jacobian(self) -> sp.Matrix:
        """The Jacobian read off the last step, expressed in the tip frame: rows [v; omega]."""
        tip = self.steps[-1]
        return sp.Matrix.vstack(sp.Matrix(tip.v), sp.Matrix(tip.omega))

    def in_coordinates(self, chain: Chain, law: CouplingLaw) -> VelocityPropagation:
        """The steps of a joint chain written in ``chain``'s coordinates: each coefficient matrix moved by ``law``."""
        return VelocityPropagation(joint_rate_symbols(chain), tuple(
            VelocityStep(s.frame, law(chain, s.omega), law(chain, s.v)) for s in self.steps))


@dataclass(frozen=True)
class ForceStep:
    """Force and moment at one frame origin, in that frame, as 3 x 6 coefficient matrices of the tip wrench."""

    frame: Frame | str
    force: sp.ImmutableMatrix
    moment: sp.ImmutableMatrix


@dataclass(frozen=True)
class ForcePropagation:
    r"""The inward iteration: steps tip to base, and the joint torques :math:`\tau = M\,[f; n]` (M is n x 6)."""

    wrench: tuple[sp.Symbol, ...]
    steps: tuple[ForceStep, ...]
    torques: sp.ImmutableMatrix

    def wrenches(self) -> list[tuple[Frame | str, sp.Matrix, sp.Matrix]]:
        r"""Per step: the frame, :math:`{}^kf_k` and :math:`{}^kn_k` as vectors in the tip wrench components."""
        wrench = sp.Matrix(self.wrench)
        return [(s.frame, linear_combination(s.force, wrench), linear_combination(s.moment, wrench))
                for s in self.steps]

    def joint_torques(self) -> sp.Matrix:
        r""":math:`\tau` as a vector in the tip wrench components."""
        return linear_combination(self.torques, sp.Matrix(self.wrench))

    @property
    def jacobian(self) -> sp.Matrix:
        """The Jacobian in the tip frame, the transpose of the torque map: :math:`J = M^T`."""
        return sp.Matrix(self.torques).T

    def in_coordinates(self, chain: Chain, law: CouplingLaw) -> ForcePropagation:
        """Written in ``chain``'s coordinates: the torque map moved by ``law``, the steps by substitution."""
        rates = COUPLING_LAWS["rates"]
        return ForcePropagation(self.wrench, tuple(
            ForceStep(s.frame, rates(chain, s.force), rates(chain, s.moment)) for s in self.steps),
            law(chain, self.torques))


def linear_combination(coefficients: sp.MatrixBase, values: sp.MatrixBase) -> sp.Matrix:
    r"""The product :math:`M x` laid out as :math:`\sum_j M_{rj} x_j`, keeping each coefficient whole.

    Examples
    --------
    >>> L, c, x, y = sp.symbols("L c x y")
    >>> linear_combination(sp.Matrix([[-L - c, L]]), sp.Matrix([x, y]))
    Matrix([[L*y - x*(L + c)]])
    """
    def term(coefficient: sp.Expr, value: sp.Expr) -> sp.Expr:
        # -f_z*(L1 + L2*c2) reads better than f_z*(-L1 - L2*c2)
        return -((-coefficient) * value) if coefficient.is_Add and coefficient.could_extract_minus_sign() else (
            coefficient * value)

    return sp.Matrix(coefficients.rows, 1, lambda r, _: sp.Add(*[term(coefficients[r, j], values[j])
                                                              for j in range(coefficients.cols)]))


def _tip(chain: Chain, point: tuple[sp.Expr, ...] | None, link: int) -> str | None:
    """Where the iteration ends past frame {l}: ``"tool"``, ``"point"`` or nowhere (``None``: the origin of {l})."""
    if point is None:
        if link != chain.n_joints:
            raise FrameError(f"the tool frame is fixed in the last link ({chain.n_joints}), not in link {link}")
        return "tool"
    return None if all(c == 0 for c in point) else "point"


def _layout(chain: Chain, simplify: bool) -> Callable[[sp.MatrixBase, Frame], sp.ImmutableMatrix]:
    """Per-step output: simplified in the step frame's angle bases (for people), or the raw products.

    The iteration itself always runs on the raw products: simplifying every step and multiplying the nested results
    again was measured 100x slower on arms with generic twists; one simplification of the raw result is not.
    """
    if not simplify:
        return lambda matrix, frame: sp.ImmutableMatrix(matrix)
    return lambda matrix, frame: sp.ImmutableMatrix(simplify_matrix(matrix, chain.angle_bases(frame)))


def _coordinates(chain: Chain, point: Sequence[sp.Expr] | str | None, link: int) -> tuple[sp.Expr, ...] | None:
    """The tip: ``None`` (the tool frame) or coordinates; ``"end"`` is the end of the chain when ``link`` is the last.

    That is the tool frame when the robot has a tool (as for forward kinematics and the Jacobian), else the origin.
    """
    if isinstance(point, str):
        if point != "end":
            raise FrameError(f"a propagation's tip is 'end', None (the tool frame) or 3 coordinates, got {point!r}")
        return None if chain.robot.tool is not None and link == chain.n_joints else (sp.S.Zero,) * 3
    return None if point is None else tuple(point)


@memoized(link=link_of, point=_coordinates, coupling="columns")
def velocity_propagation(
    chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr] | str | None = "end", *, simplify: bool = True,
    link: int | None = None,
) -> VelocityPropagation:
    r"""Propagate link velocities from the base to the tip (see the module docstring).

    Parameters
    ----------
    robot : Robot
    point : tuple of 3, or None
        The tip: a point given in frame {l} of its link, or ``None`` for the tool frame. Default ``"end"``: the end
        of the chain (the tool frame when the robot has one and l is the last link, else the origin of {l}), the
        default of forward kinematics and the Jacobian.
    simplify : bool
        Lay every step out in compact textbook form (default); ``False`` keeps the raw products.
    link : int, optional
        The link l the point is fixed in (default n): the iteration stops at frame {l}.

    Returns
    -------
    VelocityPropagation
        Steps for frames 0..l (and the tool frame or the point); ``.jacobian`` is the 6 x n Jacobian expressed in
        the last frame.

    Examples
    --------
    >>> from symjac import load_robot
    >>> steps = velocity_propagation(load_robot("planar2r")).steps
    >>> steps[-1].v * sp.Matrix(joint_rate_symbols(load_robot("planar2r")))
    Matrix([
    [                      L1*thetadot1*sin(theta2)],
    [L2*thetadot2 + thetadot1*(L1*cos(theta2) + L2)],
    [                                             0]])
    """
    return _velocity_propagation(chain, point, simplify, link)  # type: ignore[arg-type]  # normalised by @memoized


def _velocity_propagation(chain: Chain, point: tuple[sp.Expr, ...] | None, simplify: bool,
                          link: int) -> VelocityPropagation:
    robot = chain.robot
    layout = _layout(chain, simplify)
    n = chain.n_joints
    omega, v = sp.zeros(3, n), sp.zeros(3, n)
    steps = [VelocityStep(0, sp.ImmutableMatrix(omega), sp.ImmutableMatrix(v))]
    tip = _tip(chain, point, link)
    for k, joint in enumerate(robot.joints[:link], start=1):
        report(f"velocity propagation, link {k} of {n}")
        R_k_prev = chain.rotation(k, k - 1)
        p_prev_k = chain.transform(k - 1, k)[:3, 3]
        v = sp.Matrix(R_k_prev * (v + skew(-p_prev_k) * omega))  # w x p = -p x w
        omega = sp.Matrix(R_k_prev * omega)
        axis_frame = chain.axis_frame(k)
        z_a = chain.rotation(k, axis_frame)[:, 2]
        column = k - 1
        if joint.is_revolute:
            omega[:, column] += z_a
            if axis_frame != k:  # standard DH: the axis passes through the origin of {k-1}, not of {k}
                v[:, column] += z_a.cross(-chain.transform(k, axis_frame)[:3, 3])
        else:
            v[:, column] += z_a
        steps.append(VelocityStep(k, layout(omega, k), layout(v, k)))
    if tip == "tool":
        R_t_n, p_n_t = chain.rotation("tool", n), chain.transform(n, "tool")[:3, 3]
        v_t = R_t_n * (v + skew(-p_n_t) * omega)
        steps.append(VelocityStep("tool", layout(R_t_n * omega, "tool"), layout(v_t, "tool")))
    elif tip == "point":
        steps.append(VelocityStep("point", layout(omega, link), layout(v + skew(-sp.Matrix(point)) * omega, link)))
    return VelocityPropagation(tuple(joint.rate for joint in robot.joints), tuple(steps))


@memoized(link=link_of, point=_coordinates, coupling="transposed")
def force_propagation(
    chain: Chain, point: tuple[sp.Expr, sp.Expr, sp.Expr] | str | None = "end", *, simplify: bool = True,
    link: int | None = None,
) -> ForcePropagation:
    r"""Propagate a tip wrench from the tip to the base and project it on the joint axes (module docstring).

    Parameters
    ----------
    robot : Robot
    point : tuple of 3, or None
        Where the wrench acts: a point given in frame {l} of its link (the wrench is then expressed in {l}), or
        ``None`` for the origin of the tool frame (the wrench expressed in the tool frame). Default ``"end"``: the
        end of the chain, as for :func:`velocity_propagation`.
    simplify : bool
        Lay every step out in compact textbook form (default); ``False`` keeps the raw products.
    link : int, optional
        The link l the point is fixed in (default n): the wrench starts at frame {l}.

    Returns
    -------
    ForcePropagation
        Steps from the tip down to frame {0}; ``.torques`` (n x 6) maps :math:`[f; n]` to :math:`\tau` (rows of
        joints after l zero).

    Examples
    --------
    >>> from symjac import load_robot
    >>> force_propagation(load_robot("planar2r")).torques[:, :2]
    Matrix([
    [L1*sin(theta2), L1*cos(theta2) + L2],
    [             0,                  L2]])
    """
    return _force_propagation(chain, point, simplify, link)  # type: ignore[arg-type]  # normalised by @memoized


def _force_propagation(chain: Chain, point: tuple[sp.Expr, ...] | None, simplify: bool,
                       link: int) -> ForcePropagation:
    robot = chain.robot
    layout = _layout(chain, simplify)
    n = chain.n_joints
    force = sp.Matrix.hstack(sp.eye(3), sp.zeros(3, 3))
    moment = sp.Matrix.hstack(sp.zeros(3, 3), sp.eye(3))
    steps: list[ForceStep] = []
    tip = _tip(chain, point, link)
    if tip is not None:
        steps.append(ForceStep(tip, sp.ImmutableMatrix(force), sp.ImmutableMatrix(moment)))
        if tip == "tool":
            R_n_t, p_n_t = chain.rotation(n, "tool"), chain.transform(n, "tool")[:3, 3]
        else:
            R_n_t, p_n_t = sp.eye(3), sp.Matrix(point)
        force = R_n_t * force
        moment = R_n_t * moment + skew(p_n_t) * force
    frames: dict[int, ForceStep] = {}
    for k in range(link, -1, -1):
        report(f"force propagation, frame {k} of {n}")
        if k < link:
            R_k_next, p_k_next = chain.rotation(k, k + 1), chain.transform(k, k + 1)[:3, 3]
            force = R_k_next * force
            moment = R_k_next * moment + skew(p_k_next) * force
        frames[k] = ForceStep(k, layout(force, k), layout(moment, k))
        steps.append(frames[k])
    torques = sp.zeros(n, 6)
    for k, joint in enumerate(robot.joints[:link], start=1):  # joints after the link bear nothing
        step = frames[chain.axis_frame(k)]
        torques[k - 1, :] = (_Z.T * (step.moment if joint.is_revolute else step.force))
    return ForcePropagation(wrench_symbols(), tuple(steps), sp.ImmutableMatrix(torques))

