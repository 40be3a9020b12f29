"""The numeric runtime of the plain-Python target: linear algebra and the self-test, standard library only.

Every generated module of the "python" target carries the part of this file below the runtime mark, unchanged, so
that it imports without symjac installed; the part above (this docstring and the imports) is the module's own.
Tested on its own: ``tests/test_codegen_runtime.py`` imports this file and checks it against ``numpy.linalg``.

Matrices are sequences of rows; every routine is a plain loop over floats.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping, Sequence, Sized
from math import acos, pi, sin, sqrt
from typing import Any

# ---- runtime: everything below is copied into every generated module of the target ----


def _selftest_error(checks: Sequence[tuple[str, tuple[Callable[..., Any], ...], tuple[int, ...]]],
                    revolute: Sequence[bool], samples: int, seed: int) -> float:
    """The largest error of the self-test's ``checks`` at ``samples`` random configurations (seeded).

    Each check is (routine, functions, rows): ``"pose"`` (forward kinematics: R^T R = I), ``"jacobian"`` (Jacobian,
    torques, kinematics: the Jacobian against central differences of the kinematics, the torques against J^T F)
    or the check of a runtime section, ``_<routine>_error(*functions, q, qdot)``, found by name (a module carries
    only the sections it uses). Angles are drawn in (-pi, pi), prismatic joints in (-1, 1).
    """
    generator = random.Random(seed)
    worst = 0.0
    for _ in range(samples):
        q = [generator.uniform(-pi, pi) if flag else generator.uniform(-1.0, 1.0) for flag in revolute]
        qdot: list[float] = []
        for routine, functions, rows in checks:
            if routine == "pose":
                worst = max(worst, _pose_error(functions[0], q))
            elif routine == "jacobian":
                worst = max(worst, _jacobian_error(*functions, rows, q, generator))
            else:
                qdot = qdot or [generator.uniform(-1.0, 1.0) for _ in q]  # drawn once per configuration
                worst = max(worst, globals()[f"_{routine}_error"](*functions, q, qdot))
    return worst


def _pose_error(forward_kinematics: Callable[..., Sequence[Sequence[float]]], q: Sequence[float]) -> float:
    """Largest entry of R^T R - I of the pose at ``q``."""
    pose = forward_kinematics(q)
    worst = 0.0
    for r in range(3):
        for c in range(3):
            dot = sum(pose[k][r] * pose[k][c] for k in range(3))
            worst = max(worst, abs(dot - (1.0 if r == c else 0.0)))
    return worst


def _jacobian_error(jacobian_function: Callable[..., Sequence[Sequence[float]]],
                    torque_function: Callable[..., Sequence[float]], kinematics: Callable[..., Sequence[float]],
                    rows: Sequence[int], q: Sequence[float], generator: random.Random) -> float:
    """Largest relative error of a Jacobian (central differences of its kinematics) and its torques (J^T F)."""
    worst = 0.0
    expected = _finite_difference_jacobian(kinematics, q)
    actual = jacobian_function(q)
    for k, row in enumerate(rows):
        for i in range(len(q)):
            worst = max(worst, abs(actual[k][i] - expected[row][i]) / (1.0 + abs(expected[row][i])))
    wrench = [generator.uniform(-1.0, 1.0) for _ in rows]
    torques = torque_function(q, wrench)
    for i in range(len(q)):
        expected_torque = sum(actual[k][i] * wrench[k] for k in range(len(rows)))
        worst = max(worst, abs(torques[i] - expected_torque) / (1.0 + abs(expected_torque)))
    return worst


# ---- runtime section: acceleration ----


def _acceleration_error(
    jacobian_function: Callable[..., Sequence[Sequence[float]]],
    hessian_function: Callable[..., Sequence[Sequence[Sequence[float]]]],
    bias_function: Callable[..., Sequence[float]],
    manipulability_function: Callable[..., float],
    gradient_function: Callable[..., Sequence[float]],
    q: Sequence[float],
    qdot: Sequence[float],
    step: float = 1e-6,
) -> float:
    """Largest relative error of the Hessian, Jdot qdot and the manipulability gradient against central differences.

    Hessian slice m: (J(q + h e_m) - J(q - h e_m)) / 2h; Jdot qdot: (J(q + h qdot) - J(q - h qdot)) / 2h @ qdot;
    gradient entry m through w^2 = det(J J^T): 2 w dw/dq_m against (w(q + h e_m)^2 - w(q - h e_m)^2) / 2h (near a
    singularity the square root in w turns the rounding of det into an error of w divided by w, which a central
    difference divides by h again).
    """
    H = hessian_function(q)
    gradient = gradient_function(q)
    w = manipulability_function(q)
    worst = 0.0
    for m in range(len(q)):
        plus, minus = list(q), list(q)
        plus[m] += step
        minus[m] -= step
        for i, (above, below) in enumerate(zip(jacobian_function(plus), jacobian_function(minus), strict=True)):
            for j in range(len(q)):
                expected = (above[j] - below[j]) / (2.0 * step)
                worst = max(worst, abs(H[i][j][m] - expected) / (1.0 + abs(expected)))
        slope = (manipulability_function(plus) ** 2 - manipulability_function(minus) ** 2) / (2.0 * step)
        worst = max(worst, abs(2.0 * w * gradient[m] - slope) / (1.0 + abs(slope)))
    forward = jacobian_function([x + step * v for x, v in zip(q, qdot, strict=True)])
    backward = jacobian_function([x - step * v for x, v in zip(q, qdot, strict=True)])
    for value, above, below in zip(bias_function(q, qdot), forward, backward, strict=True):
        expected = sum((a - b) / (2.0 * step) * v for a, b, v in zip(above, below, qdot, strict=True))
        worst = max(worst, abs(value - expected) / (1.0 + abs(expected)))
    return worst


# ---- runtime section: ik_numeric ----


def _ik_splitmix64(state: int) -> tuple[int, int]:
    """splitmix64 (Steele, Lea and Flood 2014): the next state and its output, as the c99 runtime draws seeds."""
    state = (state + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
    z = state
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
    return state, z ^ (z >> 31)


def _ik_wrap(x: float) -> float:
    """The angle x wrapped to (-pi, pi] (unchanged when it is in already)."""
    return pi - (pi - x) % (2 * pi) if x > pi or x <= -pi else x


def _ik_error(target: Sequence[Sequence[float]], pose: Sequence[Sequence[float]]) -> list[float]:
    """The error [p* - p; log(R* R^T)], the rotation vector robust near 0 and pi."""
    r = [[sum(target[i][k] * pose[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    w = [r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]]
    angle = acos(min(1.0, max(-1.0, (r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0)))
    if angle < 1e-6:
        w = [x / 2.0 for x in w]
    elif pi - angle > 1e-4:
        w = [x * angle / (2.0 * sin(angle)) for x in w]
    else:  # near pi: the axis from the symmetric part (r + I) / 2, its largest diagonal entry's row
        m = max(range(3), key=lambda k: r[k][k])
        axis = [(r[m][k] + (1.0 if k == m else 0.0)) / 2.0 for k in range(3)]
        norm = sqrt(sum(x * x for x in axis))
        scale = (-angle if sum(a * b for a, b in zip(axis, w, strict=True)) < 0 else angle) / norm
        w = [x * scale for x in axis]
    return [target[i][3] - pose[i][3] for i in range(3)] + w


def _ik_solve(normal: Sequence[Sequence[float]], b: Sequence[float], damping: float,
              held: Sequence[bool]) -> list[float]:
    """(J^T J + damping I)^-1 b over the joints not held (0 for those), by Cholesky."""
    free = [i for i in range(len(b)) if not held[i]]
    a = [[normal[i][j] + (damping if i == j else 0.0) for j in free] for i in free]
    x = [b[i] for i in free]
    m = len(free)
    for j in range(m):
        d = sqrt(a[j][j] - sum(a[j][k] * a[j][k] for k in range(j)))
        a[j][j] = d
        for i in range(j + 1, m):
            a[i][j] = (a[i][j] - sum(a[i][k] * a[j][k] for k in range(j))) / d
    for i in range(m):
        x[i] = (x[i] - sum(a[i][k] * x[k] for k in range(i))) / a[i][i]
    for i in reversed(range(m)):
        x[i] = (x[i] - sum(a[k][i] * x[k] for k in range(i + 1, m))) / a[i][i]
    out = [0.0] * len(b)
    for index, i in enumerate(free):
        out[i] = x[index]
    return out


def _ik_descend(forward_kinematics: Callable[..., Any], jacobian: Callable[..., Any], target: Sequence[Sequence[float]],
                x: list[float], limits: tuple[Sequence[float], Sequence[float]] | None, kind: Sequence[int],
                parameters: Mapping[str, float], patience: int = 4) -> tuple[list[float], list[float], float, int]:
    """One start, as the c99 runtime's sj_ik_descend: the configuration, its error and cost, the steps taken."""

    def project(y: list[float]) -> list[float]:
        return [_ik_wrap(v) if kind[k] == 2 else v if limits is None else min(max(v, limits[0][k]), limits[1][k])
                for k, v in enumerate(y)]

    def converged(e: Sequence[float]) -> bool:
        return sum(v * v for v in e[:3]) <= 1e-20 and sum(v * v for v in e[3:]) <= 1e-20

    n = len(x)
    x = project(x)
    e = _ik_error(target, forward_kinematics(x, **parameters))
    cost = reference = sum(v * v for v in e)
    mu, stalled, steps, moved = 1.0, 0, 0, True
    J: Sequence[Sequence[float]] = ()
    normal: list[list[float]] = []
    for _ in range(100):
        if converged(e):
            break
        steps += 1
        if moved:
            J = jacobian(x, **parameters)
            normal = [[sum(J[r][i] * J[r][j] for r in range(6)) for j in range(n)] for i in range(n)]
        gradient = [sum(J[r][i] * e[r] for r in range(6)) for i in range(n)]
        damping = mu * (cost / 2.0 + 1e-3)
        held = [False] * n
        step = _ik_solve(normal, gradient, damping, held)
        while limits is not None:
            outward = [not held[i] and ((x[i] <= limits[0][i] and step[i] < 0)
                                        or (x[i] >= limits[1][i] and step[i] > 0)) for i in range(n)]
            if not any(outward):
                break
            held = [h or o for h, o in zip(held, outward, strict=True)]
            step = _ik_solve(normal, gradient, damping, held)
        if cost < 1e-6:  # geodesic acceleration: -f_vv from the error at x + 0.1 step
            probe = _ik_error(target, forward_kinematics([a + 0.1 * b for a, b in zip(x, step, strict=True)],
                                                         **parameters))
            curvature = [20.0 * ((probe[r] - e[r]) / 0.1 + sum(J[r][k] * step[k] for k in range(n))) for r in range(6)]
            acceleration = _ik_solve(normal, [sum(J[r][i] * curvature[r] for r in range(6)) for i in range(n)],
                                     damping, held)
            if 4.0 * sum(a * a for a in acceleration) <= 0.5625 * sum(s * s for s in step):
                step = [s + a / 2.0 for s, a in zip(step, acceleration, strict=True)]
        trial = project([a + b for a, b in zip(x, step, strict=True)])
        e_trial = _ik_error(target, forward_kinematics(trial, **parameters))
        c = sum(v * v for v in e_trial)
        moved = c < cost
        if moved:
            x, e, cost, mu = trial, e_trial, c, max(mu / 2.0, 1e-6)
        else:
            mu *= 4.0
        if cost < 0.9 * reference or cost < 1e-10:
            reference, stalled = cost, 0
        else:
            stalled += 1
            if stalled >= patience:
                break
    return x, e, cost, steps


def _ik_into_limits(x: list[float], lower: Sequence[float], upper: Sequence[float],
                    kind: Sequence[int]) -> tuple[list[float], bool]:
    """Each angle shifted by 2 pi k into its limits where a shift fits (the same pose), else clipped; all fit."""
    out, inside = [], True
    for k, v in enumerate(x):
        value = _ik_wrap(v) if kind[k] else v
        shifts = (0.0, 2 * pi, -2 * pi, 4 * pi, -4 * pi) if kind[k] else (0.0,)
        fits = [value + s for s in shifts if lower[k] <= value + s <= upper[k]]
        inside = inside and bool(fits)
        out.append(fits[0] if fits else min(max(value, lower[k]), upper[k]))
    return out, inside


def _ik_numeric(forward_kinematics: Callable[..., Any], jacobian: Callable[..., Any],
                pose: Sequence[Sequence[float]], seed: int, start: Sequence[float] | None, lower: Sequence[float],
                upper: Sequence[float], kind: Sequence[int], low: Sequence[float], high: Sequence[float],
                parameters: Mapping[str, float]) -> tuple[list[float], bool, int, float, float]:
    """Numeric inverse kinematics, as the c99 runtime's sj_ik_numeric (the same seeds and steps).

    Each start descends by Levenberg-Marquardt without limits first; a solution is shifted by 2 pi into the limits,
    and when a joint does not fit, the descent goes on from the clipped configuration with the limits respected (a
    redundant arm, more than six joints; an arm with at most six has isolated solutions, so it restarts). At
    most 64 starts: ``start`` (when given), then seeds drawn uniformly in [low, high] by splitmix64 from ``seed``.
    When none converges, the closest configuration reached (the least cost, clipped into the limits) descends once
    more within the limits. Returns ``(q, found, steps, position_error, orientation_error)``, the errors of ``q``.
    """
    target = [[float(v) for v in row] for row in pose]
    state, steps, best, best_e, best_cost = int(seed) & 0xFFFFFFFFFFFFFFFF, 0, None, [0.0] * 6, float("inf")
    found = False
    for attempt in range(64):
        x = []
        for k in range(len(kind)):
            state, bits = _ik_splitmix64(state)
            u = (bits >> 11) * (1.0 / 9007199254740992.0)
            x.append(float(start[k]) if attempt == 0 and start is not None else low[k] + u * (high[k] - low[k]))
        x, e, cost, taken = _ik_descend(forward_kinematics, jacobian, target, x, None, kind, parameters)
        steps += taken
        found = max(sum(v * v for v in e[:3]), sum(v * v for v in e[3:])) <= 1e-20
        x, inside = _ik_into_limits(x, lower, upper, kind)  # else clipped into them
        if found and not inside and len(kind) > 6:
            x, e, cost, taken = _ik_descend(forward_kinematics, jacobian, target, x, (lower, upper), kind,
                                            parameters)
            steps += taken
            found = max(sum(v * v for v in e[:3]), sum(v * v for v in e[3:])) <= 1e-20
        elif not inside:  # not converged, or isolated solutions (six joints or fewer) outside the limits: restart
            found = False
            e = _ik_error(target, forward_kinematics(x, **parameters))
            cost = sum(v * v for v in e)
        if found or cost < best_cost or best is None:
            best, best_e, best_cost = x, e, cost
        if found:
            break
    if not found and best is not None:  # the closest configuration reached: one more descent, within the limits
        x, e, cost, taken = _ik_descend(forward_kinematics, jacobian, target, best, (lower, upper), kind, parameters,
                                        100)
        steps += taken
        found = max(sum(v * v for v in e[:3]), sum(v * v for v in e[3:])) <= 1e-20
        if found or cost < best_cost:
            best, best_e = x, e
    return (list(best or []), found, steps, sqrt(sum(v * v for v in best_e[:3])),
            sqrt(sum(v * v for v in best_e[3:])))


# ---- runtime section: core ----


def _finite_difference_jacobian(kinematics: Callable[..., Sequence[float]], q: Sequence[float],
                                step: float = 1e-6) -> list[list[float]]:
    """The 6 x n Jacobian [v; omega] in frame {k} by central differences of (point, ^0_nR) with ^0_kR."""
    values = kinematics(q)
    R_0_n, R_0_k = values[3:12], values[12:21]
    columns = []
    for i in range(len(q)):
        plus, minus = list(q), list(q)
        plus[i] += step
        minus[i] -= step
        above, below = kinematics(plus), kinematics(minus)
        d = [(a - b) / (2.0 * step) for a, b in zip(above, below, strict=True)]
        # (dR/dq_i) R^T is the skew matrix of the angular velocity column, both in frame {0}
        W = [[sum(d[3 + 3 * r + m] * R_0_n[3 * c + m] for m in range(3)) for c in range(3)] for r in range(3)]
        v = d[0:3]
        w = [(W[2][1] - W[1][2]) / 2.0, (W[0][2] - W[2][0]) / 2.0, (W[1][0] - W[0][1]) / 2.0]
        # into frame {k}: x_k = (^0_kR)^T x_0
        columns.append([sum(R_0_k[3 * m + r] * x[m] for m in range(3)) for x in (v, w) for r in range(3)])
    return [[column[k] for column in columns] for k in range(6)]


# ---- runtime section: determinant ----


def _determinant(matrix: Sequence[Sequence[float]]) -> float:
    """Determinant by Gaussian elimination with partial pivoting: the product of the pivots, signed by the swaps."""
    a = [list(row) for row in matrix]
    size = len(a)
    result = 1.0
    for k in range(size):
        pivot = max(range(k, size), key=lambda r: abs(a[r][k]))
        if a[pivot][k] == 0.0:
            return 0.0
        if pivot != k:
            a[k], a[pivot] = a[pivot], a[k]
            result = -result
        result *= a[k][k]
        for r in range(k + 1, size):
            factor = a[r][k] / a[k][k]
            for c in range(k + 1, size):
                a[r][c] -= factor * a[k][c]
    return result


# ---- runtime section: manipulability; needs: determinant, gram ----


def _manipulability(J: Sequence[Sequence[float]]) -> float:
    """The manipulability: |det J| for a square J, else sqrt(det G), G the Gram matrix J J^T (wide) or J^T J (tall)."""
    rows, columns = len(J), len(J[0])
    if rows == columns:
        return abs(_determinant(J))
    small = min(rows, columns)
    # the Gram matrix of the shorter side: J J^T (wide J) or J^T J (tall J)
    gram = [[sum(_entry(J, r, k, rows < columns) * _entry(J, c, k, rows < columns) for k in range(max(rows, columns)))
             for c in range(small)] for r in range(small)]
    return sqrt(max(_determinant(gram), 0.0))


# ---- runtime section: gram ----


def _entry(J: Sequence[Sequence[float]], i: int, k: int, by_row: bool) -> float:
    return J[i][k] if by_row else J[k][i]


# ---- runtime section: manipulability_gradient; needs: determinant, gram, solve ----


def _manipulability_gradient(J: Sequence[Sequence[float]],
                             H: Sequence[Sequence[Sequence[float]]]) -> tuple[float, ...]:
    """The gradient w trace(J^+ H_m) for every m, J^+ from one solve with the Gram matrix; zero where w = 0."""
    rows, columns = len(J), len(J[0])
    wide = rows <= columns
    small, large = min(rows, columns), max(rows, columns)
    gram = [[sum(_entry(J, r, k, wide) * _entry(J, c, k, wide) for k in range(large)) for c in range(small)]
            for r in range(small)]
    w = sqrt(max(_determinant(gram), 0.0))
    if w == 0.0:
        return (0.0,) * columns
    # the pseudo-inverse: J^T (J J^T)^-1 = ((J J^T)^-1 J)^T for a wide J, (J^T J)^-1 J^T for a tall one
    if wide:
        solved = _solve(gram, J)
        inverse = [[solved[i][j] for i in range(rows)] for j in range(columns)]
    else:
        inverse = _solve(gram, [[J[k][j] for k in range(rows)] for j in range(columns)])
    return tuple(w * sum(inverse[j][i] * H[i][j][m] for i in range(rows) for j in range(columns))
                 for m in range(columns))


# ---- runtime section: solve ----


def _solve(matrix: Sequence[Sequence[float]], right: Sequence[Sequence[float]]) -> list[list[float]]:
    """X with matrix @ X = right, by Gauss-Jordan elimination with partial pivoting (matrix not singular)."""
    a = [[*row, *extra] for row, extra in zip(matrix, right, strict=True)]
    size = len(a)
    for k in range(size):
        pivot = max(range(k, size), key=lambda r: abs(a[r][k]))
        a[k], a[pivot] = a[pivot], a[k]
        for r in range(size):
            if r != k:
                factor = a[r][k] / a[k][k]
                a[r] = [x - factor * y for x, y in zip(a[r], a[k], strict=True)]
    return [[x / a[k][k] for x in a[k][size:]] for k in range(size)]


# ---- runtime section: cholesky_solve ----


def _cholesky_solve(matrix: Sequence[Sequence[float]], right: Sequence[float]) -> list[float]:
    """The solution x of M x = b, M symmetric positive definite (a mass matrix): M = L L^T, two triangular solves.

    L[i][i] = sqrt(M[i][i] - sum_k<i L[i][k]^2), L[r][i] = (M[r][i] - sum_k<i L[r][k] L[i][k]) / L[i][i]; then
    L y = b forwards and L^T x = y backwards. Raises ValueError if M is not positive definite (a pivot <= 0).
    """
    size = len(matrix)
    L = [[0.0] * size for _ in range(size)]
    for i in range(size):
        pivot = matrix[i][i] - sum(L[i][k] * L[i][k] for k in range(i))
        if not pivot > 0.0:
            raise ValueError(f"the matrix is not positive definite (pivot {i} is {pivot!r})")
        L[i][i] = sqrt(pivot)
        for r in range(i + 1, size):
            L[r][i] = (matrix[r][i] - sum(L[r][k] * L[i][k] for k in range(i))) / L[i][i]
    y = [0.0] * size
    for i in range(size):
        y[i] = (right[i] - sum(L[i][k] * y[k] for k in range(i))) / L[i][i]
    x = [0.0] * size
    for i in reversed(range(size)):
        x[i] = (y[i] - sum(L[k][i] * x[k] for k in range(i + 1, size))) / L[i][i]
    return x


# ---- runtime section: forward_dynamics; needs: cholesky_solve ----


def _forward_dynamics(M: Sequence[Sequence[float]], bias: Sequence[float], tau: Sequence[float]) -> tuple[float, ...]:
    """The accelerations qddot = M^-1 (tau - b) by a Cholesky solve: M the mass matrix, b = C qdot + g."""
    return tuple(_cholesky_solve(M, [t - b for t, b in zip(tau, bias, strict=True)]))


# ---- runtime section: dynamics; needs: cholesky_solve ----


def _dynamics_error(
    inverse_dynamics: Callable[..., Sequence[float]],
    mass_matrix: Callable[..., Sequence[Sequence[float]]],
    coriolis_matrix: Callable[..., Sequence[Sequence[float]]],
    bias_forces: Callable[..., Sequence[float]],
    gravity_torques: Callable[..., Sequence[float]],
    forward_dynamics: Callable[..., Sequence[float]],
    potential_energy: Callable[..., float],
    q: Sequence[float],
    qdot: Sequence[float],
    step: float = 1e-6,
) -> float:
    """Largest relative error of the dynamics against each other and central differences of M and V.

    M symmetric and positive definite (a Cholesky solve succeeds); Mdot - 2C skew, Mdot = (M(q + h qdot) -
    M(q - h qdot)) / 2h; g = tau(q, 0, 0); column j of M = tau(q, 0, e_j) - g; tau(q, qdot, qddot) = M qddot +
    C qdot + g; b = C qdot + g; forward dynamics of tau(q, qdot, qddot) gives qddot back; g_j = (V(q + h e_j) -
    V(q - h e_j)) / 2h, V the potential energy.
    """
    n = len(q)
    qddot = [0.5 - 0.25 * k + 0.3 * v for k, v in enumerate(qdot)]
    zero = [0.0] * n
    M, C, g = mass_matrix(q), coriolis_matrix(q, qdot), gravity_torques(q)
    worst = 0.0

    def differs(value: float, expected: float) -> float:
        return abs(value - expected) / (1.0 + abs(expected))

    try:
        _cholesky_solve(M, [1.0] * n)
    except ValueError:
        return float("inf")
    above = mass_matrix([x + step * v for x, v in zip(q, qdot, strict=True)])
    below = mass_matrix([x - step * v for x, v in zip(q, qdot, strict=True)])
    for i in range(n):
        for j in range(n):
            worst = max(worst, differs(M[i][j], M[j][i]))
            skew = (above[i][j] - below[i][j]) / (2.0 * step) - 2.0 * C[i][j]
            mirror = (above[j][i] - below[j][i]) / (2.0 * step) - 2.0 * C[j][i]
            worst = max(worst, differs(skew, -mirror))
    for i, value in enumerate(inverse_dynamics(q, zero, zero)):
        worst = max(worst, differs(g[i], value))
    for j in range(n):
        column = inverse_dynamics(q, zero, [1.0 if k == j else 0.0 for k in range(n)])
        for i in range(n):
            worst = max(worst, differs(M[i][j], column[i] - g[i]))
        above_j = potential_energy([x + step if k == j else x for k, x in enumerate(q)])
        below_j = potential_energy([x - step if k == j else x for k, x in enumerate(q)])
        worst = max(worst, differs(g[j], (above_j - below_j) / (2.0 * step)))
    tau = inverse_dynamics(q, qdot, qddot)
    bias = bias_forces(q, qdot)
    for i in range(n):
        Cqdot = sum(C[i][k] * qdot[k] for k in range(n))
        worst = max(worst, differs(bias[i], Cqdot + g[i]))
        worst = max(worst, differs(tau[i], sum(M[i][k] * qddot[k] for k in range(n)) + Cqdot + g[i]))
    for value, expected in zip(forward_dynamics(q, qdot, tau), qddot, strict=True):
        worst = max(worst, differs(value, expected))
    return worst


# ---- runtime section: identification ----


def _identification_error(
    inverse_dynamics: Callable[..., Sequence[float]],
    regressor: Callable[..., Sequence[Sequence[float]]],
    values: Callable[..., Sequence[float]],
    q: Sequence[float],
    qdot: Sequence[float],
) -> float:
    """Largest relative error of a regressor times the robot's own parameters against inverse dynamics."""
    qddot = [0.5 - 0.25 * k + 0.3 * v for k, v in enumerate(qdot)]
    Y, parameters = regressor(q, qdot, qddot), values(q)
    worst = 0.0
    for row, expected in zip(Y, inverse_dynamics(q, qdot, qddot), strict=True):
        value = sum(y * p for y, p in zip(row, parameters, strict=True))
        worst = max(worst, abs(value - expected) / (1.0 + abs(expected)))
    return worst


# ---- runtime section: core ----


def _length_error(name: str, value: object, length: int) -> str:
    got = f"{len(value)} values" if isinstance(value, Sized) else type(value).__name__
    return f"{name} must be a sequence of {length} numbers, got {got}"


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
