"""The numeric runtime of the jax target: manipulability, its gradient, solves and the self-test, in jax.numpy.

Every generated module of the "jax" target carries the part of this file below the runtime mark, unchanged, so that
it imports with JAX alone; the part above (this docstring and the imports) is the module's own. Every routine is a
pure function of arrays of one configuration (shape decisions are static), so ``jit``, ``vmap`` and ``grad``
compose with it. Tested on its own: ``tests/test_codegen_runtime.py`` imports this file.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

# ---- runtime: everything below is copied into every generated module of the target ----


def _selftest_error(checks: Sequence[tuple[str, tuple[Callable[..., Array], ...], tuple[int, ...]]], n: int,
                    samples: int, step: float) -> float:
    """The largest error of the self-test's ``checks``, relative to 1 + |entry|, at ``samples`` configurations.

    Each check is (routine, functions, rows): ``"pose"`` (forward kinematics: R^T R = I), ``"jacobian"`` (Jacobian,
    torques, kinematics: against central differences of the kinematics, the torques against J^T F) or the check of
    a runtime section, ``_<routine>_error(functions, q, qdot, error, central)``, found by name (a module carries
    only the sections it uses).
    """
    worst = 0.0

    def error(actual: ArrayLike, expected: ArrayLike) -> float:
        return float(jnp.max(jnp.abs(jnp.asarray(actual) - expected) / (1.0 + jnp.abs(jnp.asarray(expected)))))

    def central(function: Callable[[Array], Array], q: Array, direction: Array) -> Array:
        return (function(q + step * direction) - function(q - step * direction)) / (2.0 * step)

    for sample in range(samples):
        q = 1.3 * jnp.sin(0.9 * (sample + 1) * jnp.arange(1.0, n + 1.0))
        unit = jnp.eye(n, dtype=q.dtype)
        qdot = jnp.linspace(0.8, -0.6, n)
        for routine, functions, rows in checks:
            if routine == "pose":
                rotation = functions[0](q)[:3, :3]
                worst = max(worst, error(rotation.T @ rotation, jnp.eye(3)))
            elif routine == "jacobian":
                jacobian_function, torque_function, kinematics = functions
                at = kinematics(q)
                columns = []
                for m in range(q.shape[0]):
                    change = central(kinematics, q, unit[m])
                    W = change[3:12].reshape(3, 3) @ at[3:12].reshape(3, 3).T  # dR R^T = [omega]x
                    twist = jnp.concatenate([change[:3], jnp.stack([W[2, 1], W[0, 2], W[1, 0]])])
                    frame = at[12:21].reshape(3, 3)
                    columns.append(jnp.concatenate([frame.T @ twist[:3], frame.T @ twist[3:]])[jnp.asarray(rows)])
                J = jacobian_function(q)
                worst = max(worst, error(J, jnp.stack(columns, axis=1)))
                wrench = jnp.linspace(-0.7, 0.9, len(rows))
                worst = max(worst, error(torque_function(q, wrench), J.T @ wrench))
            else:
                worst = max(worst, globals()[f"_{routine}_error"](functions, q, qdot, error, central))
    return worst


# ---- runtime section: acceleration ----


def _acceleration_error(functions: Sequence[Callable[..., Array]], q: Array, qdot: Array,
                        error: Callable[[ArrayLike, ArrayLike], float],
                        central: Callable[[Callable[[Array], Array], Array, Array], Array]) -> float:
    """Largest error of the Hessian, the manipulability gradient and Jdot qdot against central differences.

    ``functions`` are the Jacobian, Hessian, bias acceleration, manipulability and gradient; ``error`` and
    ``central`` the self-test's relative error and central difference.
    """
    jacobian_function, hessian_function, bias_function, manipulability_function, gradient_function = functions
    unit = jnp.eye(q.shape[0], dtype=q.dtype)
    H = hessian_function(q)
    w = manipulability_function(q)

    def squared(x: Array) -> Array:  # w^2 = det(J J^T): no square root to amplify rounding near a singularity
        return manipulability_function(x) ** 2

    worst = 0.0
    for m in range(q.shape[0]):
        worst = max(worst, error(H[:, :, m], central(jacobian_function, q, unit[m])))
        worst = max(worst, error(2 * w * gradient_function(q)[m], central(squared, q, unit[m])))
    return max(worst, error(bias_function(q, qdot), central(jacobian_function, q, qdot) @ qdot))


# ---- runtime section: determinant ----


def _determinant(J: Array) -> Array:
    """The determinant of a square Jacobian (``jnp.linalg.det``: LU with partial pivoting)."""
    return jnp.linalg.det(J)


# ---- runtime section: manipulability ----


def _manipulability(J: Array) -> Array:
    """The manipulability: |det J| for a square J, else sqrt(det G), G = J J^T (wide) or J^T J (tall)."""
    rows, columns = J.shape
    if rows == columns:
        return jnp.abs(jnp.linalg.det(J))
    return jnp.sqrt(jnp.maximum(jnp.linalg.det(J @ J.T if rows < columns else J.T @ J), 0.0))


# ---- runtime section: manipulability_gradient ----


def _manipulability_gradient(J: Array, H: Array) -> Array:
    """Dw/dq_m = w trace(J^+ H[:, :, m]), J^+ from one solve with the Gram matrix of the shorter side; 0 where w = 0."""
    rows, columns = J.shape
    if rows <= columns:
        G = J @ J.T
        w = jnp.sqrt(jnp.maximum(jnp.linalg.det(G), 0.0))
        trace = jnp.einsum("ij,ijm->m", jnp.linalg.solve(G, J), H)  # J^+ = (G^-1 J)^T
    else:
        G = J.T @ J
        w = jnp.sqrt(jnp.maximum(jnp.linalg.det(G), 0.0))
        trace = jnp.einsum("ji,ijm->m", jnp.linalg.solve(G, J.T), H)  # J^+ = G^-1 J^T
    return jnp.where(w > 0.0, w * trace, 0.0)


# ---- runtime section: cholesky_solve ----


def _cholesky_solve(M: Array, b: Array) -> Array:
    """The solution x of M x = b, M symmetric positive definite: M = L L^T, then L y = b and L^T x = y (NaN if not)."""
    L = jnp.linalg.cholesky(M)
    y = jnp.linalg.solve(L, b)
    return jnp.linalg.solve(L.T, y)


# ---- runtime section: forward_dynamics; needs: cholesky_solve ----


def _forward_dynamics(M: Array, bias: Array, tau: ArrayLike) -> Array:
    """The accelerations qddot = M^-1 (tau - b) by a Cholesky solve: M the mass matrix, b = C qdot + g."""
    return _cholesky_solve(M, jnp.asarray(tau) - bias)


# ---- runtime section: dynamics ----


def _dynamics_error(functions: tuple[Callable[..., Array], ...], q: Array, qdot: Array,
                    error: Callable[[ArrayLike, ArrayLike], float],
                    central: Callable[[Callable[[Array], Array], Array, Array], Array]) -> float:
    """Largest relative error of the dynamics against each other and central differences of M and V.

    M symmetric positive definite (its Cholesky factor is finite); Mdot - 2C skew (Mdot: central differences of M
    along qdot); g = tau(q, 0, 0); column j of M = tau(q, 0, e_j) - g; tau(q, qdot, qddot) = M qddot + C qdot + g;
    b = C qdot + g; forward dynamics of that tau gives qddot back; g = dV/dq (central differences of the potential
    energy V along each e_j).
    """
    (inverse_dynamics, mass_matrix, coriolis_matrix, bias_forces, gravity_torques, forward_dynamics,
     potential_energy) = functions
    n = q.shape[0]
    qddot = 0.5 - 0.25 * jnp.arange(n) + 0.3 * qdot
    zero = jnp.zeros(n)
    M, C, g = mass_matrix(q), coriolis_matrix(q, qdot), gravity_torques(q)
    if not bool(jnp.all(jnp.isfinite(jnp.linalg.cholesky(M)))):
        return float("inf")
    skew = central(mass_matrix, q, qdot) - 2.0 * C
    worst = max(error(M, M.T), error(skew, -skew.T), error(g, inverse_dynamics(q, zero, zero)))
    unit = jnp.eye(n)
    columns = jnp.stack([inverse_dynamics(q, zero, unit[j]) for j in range(n)], axis=1)
    worst = max(worst, error(M, columns - g[:, None]))
    slopes = jnp.stack([central(potential_energy, q, unit[j]) for j in range(n)])
    worst = max(worst, error(g, slopes))
    tau = inverse_dynamics(q, qdot, qddot)
    worst = max(worst, error(bias_forces(q, qdot), C @ qdot + g), error(tau, M @ qddot + C @ qdot + g))
    return max(worst, error(forward_dynamics(q, qdot, tau), qddot))


# ---- runtime section: identification ----


def _identification_error(functions: tuple[Callable[..., Array], ...], q: Array, qdot: Array,
                          error: Callable[[ArrayLike, ArrayLike], float],
                          central: Callable[[Callable[[Array], Array], Array, Array], Array]) -> float:
    """Largest relative error of a regressor times the robot's own parameters against inverse dynamics."""
    del central
    inverse_dynamics, regressor, values = functions
    qddot = 0.5 - 0.25 * jnp.arange(q.shape[0]) + 0.3 * qdot
    return error(regressor(q, qdot, qddot) @ values(q), inverse_dynamics(q, qdot, qddot))


# ---- runtime section: ik_numeric ----


def _ik_error(target: Array, pose: Array) -> Array:
    """The error [p* - p; log(R* R^T)] (the python runtime's), its rotation vector robust near 0 and pi, branch-free."""
    r = target[:3, :3] @ pose[:3, :3].T
    w = jnp.stack([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    angle = jnp.arccos(jnp.clip((r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0, -1.0, 1.0))
    small, near_pi = angle < 1e-6, jnp.pi - angle <= 1e-4
    scale = jnp.where(small | near_pi, 0.5, angle / (2.0 * jnp.sin(jnp.where(small | near_pi, 1.0, angle))))
    m = jnp.argmax(jnp.diagonal(r))  # near pi: the axis from the symmetric part, its largest diagonal entry's row
    axis = (r[m] + jnp.eye(3, dtype=r.dtype)[m]) / 2.0
    length = jnp.sqrt(axis @ axis)
    turned = axis * (jnp.where(axis @ w < 0, -angle, angle) / jnp.where(length > 0, length, 1.0))
    rotation = jnp.where(near_pi & ~small, turned, w * scale)
    return jnp.concatenate([target[:3, 3] - pose[:3, 3], rotation])


def _ik_numeric(forward: Callable[..., Array], velocity: Callable[..., Array], pose: ArrayLike, seed: ArrayLike,
                start: ArrayLike | None, lower: Sequence[float], upper: Sequence[float], kind: Sequence[int],
                low: Sequence[float], high: Sequence[float], parameters: Mapping[str, float], starts: int,
                iterations: int, tolerance: float | None) -> tuple[Array, Array, Array]:
    """Numeric inverse kinematics of one pose: ``starts`` Levenberg-Marquardt descents of ``iterations`` steps each.

    Fixed shapes and a fixed number of steps (``jax.lax.fori_loop`` inside ``jax.vmap`` over the starts), so that
    ``jit`` and ``vmap`` compose with it. The starts are ``start`` (when given) and draws of ``jax.random`` from
    ``seed``, uniform in [low, high]. Each step solves (J^T J + mu (|e|^2 / 2 + 1e-3) I) dq = J^T e (Sugihara's
    damping) and is taken when it lowers |e|^2 (mu halves) or not (mu quadruples); a start that met the tolerance
    stays. Angles without limits are wrapped to (-pi, pi]; a solution is shifted by 2 pi into the limits, and one
    that does not fit counts as not found, except for a redundant arm (more than six joints), which descends again
    with the limits enforced (clipped) from the clipped configuration. Returns (q, found, steps): the first start
    found (else the one with the least error, clipped into the limits) and the steps taken by the starts up to it
    (the steps a start takes before it meets the tolerance).
    """
    target = jnp.asarray(pose, dtype=jnp.result_type(float))
    dtype, n = target.dtype, len(kind)
    tolerance = (1e-10 if dtype == jnp.float64 else 1e-4) if tolerance is None else tolerance
    wraps = jnp.asarray([k == 2 for k in kind])
    angles = jnp.asarray([k != 0 for k in kind])
    bounds = (jnp.asarray(lower, dtype=dtype), jnp.asarray(upper, dtype=dtype))
    box = (jnp.asarray(low, dtype=dtype), jnp.asarray(high, dtype=dtype))
    seeds = box[0] + jax.random.uniform(jax.random.PRNGKey(seed), (starts, n), dtype) * (box[1] - box[0])
    if start is not None:
        seeds = seeds.at[0].set(jnp.asarray(start, dtype=dtype).reshape(n))
    two_pi = 2.0 * jnp.pi

    def wrap(x: Array) -> Array:
        return jnp.where(wraps, x - two_pi * jnp.ceil((x - jnp.pi) / two_pi), x)

    def error(x: Array) -> Array:
        return _ik_error(target, jnp.asarray(forward(x, **parameters), dtype=dtype))

    def met(e: Array) -> Array:
        return jnp.maximum(e[:3] @ e[:3], e[3:] @ e[3:]) <= tolerance**2

    def descend(x: Array, clipped: bool) -> tuple[Array, Array, Array, Array]:
        def project(y: Array) -> Array:
            y = wrap(y)
            return jnp.where(wraps, y, jnp.clip(y, *bounds)) if clipped else y

        def step(_: int, state: tuple[Array, Array, Array, Array, Array]) -> tuple[Array, Array, Array, Array, Array]:
            x, e, cost, mu, taken = state
            done = met(e)
            J = jnp.asarray(velocity(x, **parameters), dtype=dtype)
            normal = J.T @ J + (mu * (cost / 2.0 + 1e-3)) * jnp.eye(n, dtype=dtype)
            trial = project(x + jnp.linalg.solve(normal, J.T @ e))
            e_trial = error(trial)
            c = e_trial @ e_trial
            better = (c < cost) & ~done
            return (jnp.where(better, trial, x), jnp.where(better, e_trial, e), jnp.where(better, c, cost),
                    jnp.where(done, mu, jnp.where(better, jnp.maximum(mu / 2.0, 1e-6), mu * 4.0)),
                    taken + jnp.where(done, 0, 1))

        x = project(x)
        e = error(x)
        state = (x, e, e @ e, jnp.asarray(1.0, dtype=dtype), jnp.asarray(0, dtype=jnp.int32))
        x, e, cost, _, taken = jax.lax.fori_loop(0, iterations, step, state)
        return x, met(e), cost, taken

    def into_limits(x: Array) -> tuple[Array, Array]:
        wrapped = jnp.where(angles, x - two_pi * jnp.ceil((x - jnp.pi) / two_pi), x)
        choices = [wrapped + s * two_pi for s in (0.0, 1.0, -1.0, 2.0, -2.0)]
        fits = [angles | (s == 0.0) for s in (0.0, 1.0, -1.0, 2.0, -2.0)]
        value, fitted = jnp.clip(wrapped, *bounds), jnp.zeros(n, dtype=bool)
        for choice, allowed in zip(choices[::-1], fits[::-1], strict=True):  # the first that fits wins
            inside = allowed & (choice >= bounds[0]) & (choice <= bounds[1])
            value, fitted = jnp.where(inside, choice, value), fitted | inside
        return value, jnp.all(fitted)

    def solve(x: Array) -> tuple[Array, Array, Array, Array]:
        x, found, cost, taken = descend(x, False)
        x, inside = into_limits(x)
        if n > 6:  # self-motion: go on from the clipped configuration within the limits
            y, again, cost_again, more = descend(x, True)
            x, found = jnp.where(inside, x, y), found & inside | again & ~inside
            cost, taken = jnp.where(inside, cost, cost_again), taken + jnp.where(inside, 0, more)
            return x, found, cost, taken
        return x, found & inside, jnp.where(inside, cost, jnp.inf), taken

    x, found, cost, taken = jax.vmap(solve)(seeds)
    index = jnp.where(jnp.any(found), jnp.argmax(found), jnp.argmin(cost))
    steps = jnp.sum(jnp.where(jnp.arange(starts) <= index, taken, 0))
    return x[index], jnp.any(found), steps


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
