"""The numeric runtime of the casadi target: manipulability, its gradient, solves and the self-test, in CasADi SX.

Every generated module of the "casadi" target carries the part of this file below the runtime mark, unchanged, so
that it imports with CasADi alone; the part above (this docstring and the imports) is the module's own. The
routines build graphs (SX) from graphs: ``Function.generate()`` sees them as any other node. Tested on its own:
``tests/test_codegen_runtime.py`` imports this file.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import casadi as ca

# ---- runtime: everything below is copied into every generated module of the target ----


def _selftest_error(checks: Sequence[tuple[str, tuple[ca.Function, ...], tuple[int, ...]]], n: int,
                    defaults: Sequence[float], samples: int) -> float:
    """The largest error of the self-test's ``checks``, relative to 1 + |entry|, at the default parameters.

    Each check is (routine, functions, rows): ``"pose"`` (forward kinematics: R^T R = I), ``"jacobian"`` (Jacobian,
    torques, kinematics: against central differences of the kinematics, the torques against J^T F) or the check of
    a runtime section, ``_<routine>_error(functions, q, qdot, p)``, found by name (a module carries only the
    sections it uses).
    """
    step = 1e-6
    p = ca.DM(defaults)
    worst = 0.0
    error = _relative_error
    for sample in range(samples):
        q = ca.DM([1.3 * math.sin(0.9 * (sample + 1) * (k + 1)) for k in range(n)])
        unit = ca.DM.eye(n)
        qdot = ca.DM([0.8 - 0.3 * k for k in range(n)])
        for routine, functions, rows in checks:
            if routine == "pose":
                rotation = functions[0](q, p)[:3, :3]
                worst = max(worst, error(ca.mtimes(rotation.T, rotation), ca.DM.eye(3)))
            elif routine == "jacobian":
                jacobian_function, torque_function, kinematics = functions
                at = kinematics(q, p)
                columns = []
                for m in range(n):
                    change = (kinematics(q + step * unit[:, m], p) - kinematics(q - step * unit[:, m], p)) / (2 * step)
                    W = ca.mtimes(ca.reshape(change[3:12], 3, 3).T, ca.reshape(at[3:12], 3, 3))  # dR R^T = [omega]x
                    frame = ca.reshape(at[12:21], 3, 3)  # column-major reshape of row-major entries: R^T
                    omega = ca.vertcat(W[2, 1], W[0, 2], W[1, 0])
                    twist = ca.vertcat(ca.mtimes(frame, change[:3]), ca.mtimes(frame, omega))
                    columns.append(ca.vertcat(*[twist[row] for row in rows]))
                J = jacobian_function(q, p)
                worst = max(worst, error(J, ca.horzcat(*columns)))
                wrench = ca.DM([0.3 + 0.2 * k for k in range(len(rows))])
                worst = max(worst, error(torque_function(q, wrench, p), ca.mtimes(J.T, wrench)))
            else:
                worst = max(worst, globals()[f"_{routine}_error"](functions, q, qdot, p))
    return worst


def _relative_error(actual: ca.DM, expected: ca.DM) -> float:
    """The largest |actual - expected| / (1 + |expected|)."""
    return float(ca.mmax(ca.fabs(actual - expected) / (1.0 + ca.fabs(expected))))


# ---- runtime section: acceleration ----


def _acceleration_error(functions: Sequence[ca.Function], q: ca.DM, qdot: ca.DM, p: ca.DM) -> float:
    """Largest error of the Hessian and Jdot qdot against central differences of the Jacobian.

    ``functions`` start with the Jacobian, Hessian and bias acceleration (CasADi differentiates the manipulability
    itself).
    """
    error = _relative_error
    step = 1e-6
    n = q.numel()
    unit = ca.DM.eye(n)
    jacobian_function, hessian_function, bias_function = functions[:3]
    H = hessian_function(q, p)
    worst = 0.0
    for m in range(n):
        change = (jacobian_function(q + step * unit[:, m], p) - jacobian_function(q - step * unit[:, m], p))
        worst = max(worst, error(H[:, m * n:(m + 1) * n], change / (2 * step)))
    change = (jacobian_function(q + step * qdot, p) - jacobian_function(q - step * qdot, p)) / (2 * step)
    return max(worst, error(bias_function(q, qdot, p), ca.mtimes(change, qdot)))


# ---- runtime section: determinant ----


def _determinant(J: ca.SX, q: ca.SX | None = None) -> ca.SX:
    """The determinant of a square Jacobian (CasADi's expansion); ``q``, the variables, is not needed."""
    return ca.det(J)


# ---- runtime section: manipulability ----


def _manipulability(J: ca.SX, q: ca.SX | None = None) -> ca.SX:
    """The manipulability: |det J| for a square J, else sqrt(det G), G = J J^T (wide) or J^T J (tall).

    ``q``, the variables, is not needed (every routine here takes its sources' results, then the variables).
    """
    rows, columns = J.shape
    if rows == columns:
        return ca.fabs(ca.det(J))
    return ca.sqrt(ca.fmax(ca.det(ca.mtimes(J, J.T) if rows < columns else ca.mtimes(J.T, J)), 0.0))


# ---- runtime section: manipulability_gradient; needs: manipulability ----


def _manipulability_gradient(J: ca.SX, H: ca.SX, q: ca.SX) -> ca.SX:
    """Dw/dq by CasADi's own differentiation of the manipulability of J(q); zero where w = 0 (a kink there).

    ``H`` (the Hessian) is not needed: CasADi differentiates the graph of w itself.
    """
    w = _manipulability(J)
    return ca.if_else(w > 0, ca.gradient(w, q), ca.SX.zeros(q.numel(), 1))


# ---- runtime section: cholesky_solve ----


def _cholesky_solve(M: ca.SX, b: ca.SX) -> ca.SX:
    """The solution x of M x = b, M symmetric positive definite: M = R^T R (``ca.chol``), R^T y = b, R x = y."""
    R = ca.chol(M)
    return ca.solve(R, ca.solve(R.T, b))


# ---- runtime section: forward_dynamics; needs: cholesky_solve ----


def _forward_dynamics(M: ca.SX, bias: ca.SX, tau: ca.SX, q: ca.SX) -> ca.SX:
    """The accelerations qddot = M^-1 (tau - b) by a Cholesky solve: M the mass matrix, b = C qdot + g (q unused)."""
    del q
    return _cholesky_solve(M, tau - bias)


# ---- runtime section: dynamics; needs: cholesky_solve ----


def _dynamics_error(functions: tuple[ca.Function, ...], q: ca.DM, qdot: ca.DM, p: ca.DM) -> float:
    """Largest relative error of the dynamics against each other and central differences of M and V.

    M symmetric positive definite (a Cholesky factor exists); Mdot - 2C skew (Mdot: central differences of M along
    qdot); g = tau(q, 0, 0); column j of M = tau(q, 0, e_j) - g; tau(q, qdot, qddot) = M qddot + C qdot + g;
    b = C qdot + g; forward dynamics of that tau gives qddot back; g_j = (V(q + h e_j) - V(q - h e_j)) / 2h, V the
    potential energy.
    """
    (inverse_dynamics, mass_matrix, coriolis_matrix, bias_forces, gravity_torques, forward_dynamics,
     potential_energy) = functions
    n, step, error = q.numel(), 1e-6, _relative_error
    qddot = ca.DM([0.5 - 0.25 * k + 0.3 * float(qdot[k]) for k in range(n)])
    zero = ca.DM.zeros(n, 1)
    M, C, g = mass_matrix(q, p), coriolis_matrix(q, qdot, p), gravity_torques(q, p)
    try:
        ca.chol(M)
    except RuntimeError:
        return float("inf")
    skew = (mass_matrix(q + step * qdot, p) - mass_matrix(q - step * qdot, p)) / (2 * step) - 2 * C
    worst = max(error(M, M.T), error(skew, -skew.T), error(g, inverse_dynamics(q, zero, zero, p)))
    unit = ca.DM.eye(n)
    for j in range(n):
        worst = max(worst, error(M[:, j], inverse_dynamics(q, zero, unit[:, j], p) - g))
        slope = (potential_energy(q + step * unit[:, j], p) - potential_energy(q - step * unit[:, j], p)) / (2 * step)
        worst = max(worst, error(g[j], slope))
    tau = inverse_dynamics(q, qdot, qddot, p)
    Cqdot = ca.mtimes(C, qdot)
    worst = max(worst, error(bias_forces(q, qdot, p), Cqdot + g), error(tau, ca.mtimes(M, qddot) + Cqdot + g))
    return max(worst, error(forward_dynamics(q, qdot, tau, p), qddot))


# ---- runtime section: identification ----


def _identification_error(functions: tuple[ca.Function, ...], q: ca.DM, qdot: ca.DM, p: ca.DM) -> float:
    """Largest relative error of a regressor times the robot's own parameters against inverse dynamics."""
    inverse_dynamics, regressor, values = functions
    qddot = ca.DM([0.5 - 0.25 * k + 0.3 * float(qdot[k]) for k in range(q.numel())])
    return _relative_error(ca.mtimes(regressor(q, qdot, qddot, p), values(q, p)), inverse_dynamics(q, qdot, qddot, p))


# ---- runtime section: ik_numeric ----


def _ik_error(target: ca.SX, pose: ca.SX) -> ca.SX:
    """The error [p* - p; log(R* R^T)] (the python runtime's), its rotation vector robust near 0 and pi, branch-free."""
    r = ca.mtimes(target[:3, :3], pose[:3, :3].T)
    w = ca.vertcat(r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1])
    angle = ca.acos(ca.fmin(1.0, ca.fmax(-1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0)))
    small, near_pi = angle < 1e-6, math.pi - angle <= 1e-4
    plain = ca.logic_or(small, near_pi)
    scale = ca.if_else(plain, 0.5, angle / (2.0 * ca.sin(ca.if_else(plain, 1.0, angle))))
    unit = ca.SX.eye(3)
    rows = [(r[m, :].T + unit[:, m]) / 2.0 for m in range(3)]  # near pi: the axis from the symmetric part's row
    first = ca.logic_and(r[0, 0] >= r[1, 1], r[0, 0] >= r[2, 2])  # of the largest diagonal entry
    axis = ca.if_else(first, rows[0], ca.if_else(r[1, 1] >= r[2, 2], rows[1], rows[2]))
    length = ca.norm_2(axis)
    turned = axis * (ca.if_else(ca.dot(axis, w) < 0, -angle, angle) / ca.if_else(length > 0, length, 1.0))
    rotation = ca.if_else(ca.logic_and(near_pi, ca.logic_not(small)), turned, w * scale)
    return ca.vertcat(target[:3, 3] - pose[:3, 3], rotation)


def _ik_splitmix64(state: int) -> tuple[int, int]:
    """splitmix64 (Steele, Lea and Flood 2014): the next state and its output, as the other runtimes draw seeds."""
    state = (state + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
    z = state
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
    return state, z ^ (z >> 31)


def _ik_numeric(forward: ca.Function, velocity: ca.Function, lower: Sequence[float], upper: Sequence[float],
                kind: Sequence[int], low: Sequence[float], high: Sequence[float], parameters: int, starts: int,
                iterations: int, tolerance: float, seed: int) -> ca.Function:
    """``inverse_kinematics_numeric(pose, start, p) -> (q, found, error)``: fixed Levenberg-Marquardt as a graph.

    One step, an SX function of (q and the damping mu, pose, p), solves (J^T J + mu (|e|^2 / 2 + 1e-3) I) dq =
    J^T e (Sugihara's damping) on ``forward`` and ``velocity`` and takes the step when it lowers |e|^2 (mu halves)
    or not (mu quadruples); a start that met ``tolerance`` stays. ``Function.fold`` repeats it ``iterations``
    times and ``Function.map`` runs it from ``starts`` starts: ``start`` and ``starts - 1`` seeds drawn by
    splitmix64 from ``seed`` in [low, high] (the other targets' first seeds). Angles without limits are wrapped to
    (-pi, pi]; a solution is shifted by 2 pi into the limits, one that does not fit counts as not found, except for
    a redundant arm (more than six joints), which descends again with the limits enforced (clipped). The result is
    the first start found, else the one with the least error (clipped into the limits); ``error`` holds its
    position (m) and rotation (rad) errors.
    """
    n = len(kind)
    two_pi = 2.0 * math.pi
    pose, p, start = ca.SX.sym("pose", 4, 4), ca.SX.sym("p", parameters), ca.SX.sym("start", n)
    state = ca.SX.sym("state", n + 1)
    x, mu = state[:n], state[n]

    def wrap(y: ca.SX, joints: Sequence[bool]) -> ca.SX:
        return ca.vertcat(*[y[k] - two_pi * ca.ceil((y[k] - math.pi) / two_pi) if joints[k] else y[k]
                            for k in range(n)])

    def error(y: ca.SX) -> ca.SX:
        return _ik_error(pose, forward(y, p))

    def met(e: ca.SX) -> ca.SX:
        return ca.fmax(ca.dot(e[:3], e[:3]), ca.dot(e[3:], e[3:])) <= tolerance**2

    def step_function(clipped: bool) -> ca.Function:
        e = error(x)
        cost = ca.dot(e, e)
        J = velocity(x, p)
        normal = ca.mtimes(J.T, J) + mu * (cost / 2.0 + 1e-3) * ca.SX.eye(n)
        trial = wrap(x + ca.solve(normal, ca.mtimes(J.T, e)), [k == 2 for k in kind])
        if clipped:
            trial = ca.vertcat(*[trial[k] if kind[k] == 2 else ca.fmin(ca.fmax(trial[k], lower[k]), upper[k])
                                 for k in range(n)])
        e_trial = error(trial)
        done = met(e)
        better = ca.logic_and(ca.dot(e_trial, e_trial) < cost, ca.logic_not(done))
        damping = ca.if_else(done, mu, ca.if_else(better, ca.fmax(mu / 2.0, 1e-6), mu * 4.0))
        return ca.Function("ik_step", [state, pose, p], [ca.vertcat(ca.if_else(better, trial, x), damping)])

    def into_limits(y: ca.SX) -> tuple[ca.SX, ca.SX]:
        wrapped = wrap(y, [k != 0 for k in kind])
        values, inside = [], ca.SX(1)
        for k in range(n):
            value = ca.fmin(ca.fmax(wrapped[k], lower[k]), upper[k])
            fits = ca.SX(0)
            for shift in ((-2.0, 2.0, -1.0, 1.0, 0.0) if kind[k] else (0.0,)):  # the last that fits wins: 0 first
                choice = wrapped[k] + shift * two_pi
                fit = ca.logic_and(choice >= lower[k], choice <= upper[k])
                value, fits = ca.if_else(fit, choice, value), ca.logic_or(fits, fit)
            values.append(value)
            inside = ca.logic_and(inside, fits)
        return ca.vertcat(*values), inside

    descend = step_function(False).fold(iterations)
    reached = descend(ca.vertcat(start, 1.0), pose, p)[:n]
    q, inside = into_limits(reached)
    e = error(reached)
    found, cost = ca.logic_and(met(e), inside), ca.if_else(inside, ca.dot(e, e), math.inf)
    if n > 6:  # self-motion: go on from the clipped configuration within the limits
        again = step_function(True).fold(iterations)(ca.vertcat(q, 1.0), pose, p)[:n]
        e_again = error(again)
        q, found = ca.if_else(inside, q, again), ca.if_else(inside, found, met(e_again))
        cost = ca.if_else(inside, cost, ca.dot(e_again, e_again))
    each = ca.Function("ik_start", [start, pose, p], [q, found, cost]).map(starts)
    seeds, state_bits = [], int(seed) & 0xFFFFFFFFFFFFFFFF
    for _ in range(starts - 1):
        draw = []
        for k in range(n):
            state_bits, bits = _ik_splitmix64(state_bits)
            draw.append(low[k] + (bits >> 11) * (1.0 / 9007199254740992.0) * (high[k] - low[k]))
        seeds.append(draw)
    pose_in, p_in, start_in = ca.MX.sym("pose", 4, 4), ca.MX.sym("p", parameters), ca.MX.sym("start", n)
    all_q, all_found, all_cost = each(ca.horzcat(start_in, ca.DM(seeds).T if seeds else ca.DM.zeros(n, 0)),
                                      pose_in, p_in)
    best, least = all_q[:, 0], all_cost[0]
    for k in range(1, starts):  # the least error
        lower_cost = all_cost[k] < least
        best, least = ca.if_else(lower_cost, all_q[:, k], best), ca.if_else(lower_cost, all_cost[k], least)
    for k in reversed(range(starts)):  # the first found
        best = ca.if_else(all_found[k], all_q[:, k], best)
    final = ca.Function("ik_error", [start, pose, p], [error(start)])(best, pose_in, p_in)
    errors = ca.vertcat(ca.norm_2(final[:3]), ca.norm_2(final[3:]))
    return ca.Function("inverse_kinematics_numeric", [pose_in, start_in, p_in],
                       [best, ca.mmax(all_found), errors], ["pose", "start", "p"], ["q", "found", "error"])


# ---- runtime section: core ----


def _coordinates_from(joint_names: Sequence[str], values: Mapping[str, float] | Sequence[str],
                      positions: Sequence[float] | None) -> list[float]:
    """The coordinate vector, in the order of ``joint_names``, from ``{name: value}`` or from names and positions.

    A mapping must give every joint and nothing else; names with positions (a ROS ``JointState``'s ``name`` and
    ``position``) must give every joint once, and may give other joints too, which are ignored. Anything missing,
    repeated or unknown raises ``ValueError`` naming it.
    """
    if positions is None:
        if not isinstance(values, Mapping):
            raise TypeError(f"give a mapping of joint name to value, or joint names and positions, got "
                            f"{type(values).__name__}")
        given = dict(values)
        unknown = [name for name in given if name not in joint_names]
        if unknown:
            raise ValueError(f"unknown joint name(s) {', '.join(map(repr, unknown))}; the joints are "
                             f"{', '.join(joint_names)}")
    else:
        names, numbers = list(values), list(positions)
        if len(names) != len(numbers):
            raise ValueError(f"{len(names)} joint names but {len(numbers)} positions")
        given = {}
        for name, number in zip(names, numbers, strict=True):
            if name in given:
                raise ValueError(f"joint name {name!r} is given twice")
            given[name] = number
    missing = [name for name in joint_names if name not in given]
    if missing:
        raise ValueError(f"no value for joint(s) {', '.join(missing)}")
    return [float(given[name]) for name in joint_names]
