# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 11. Identification: the PUMA 560's base parameters from simulated data
#
# **What you will learn**
#
# * why the torques are linear in the right parameters, $\tau = Y(q, \dot q, \ddot q)\,\pi$, and why only some
#   combinations of them, the *base parameters* $\pi_b$, can be found from motion and torques;
# * how an exciting trajectory (a finite Fourier series per joint) is judged by the condition number of the
#   regressor stacked along it;
# * how least squares recovers $\pi_b$ from sampled $(q, \dot q, \ddot q, \tau)$, and what its standard deviations
#   say once the torques are noisy.
#
# The "measurements" come from symjac's own generated inverse dynamics of the catalog PUMA 560, which carries
# published inertial data (Armstrong, Khatib and Burdick, 1986; as in Corke's Robotics Toolbox): we know the answer
# and can check it.

# %%
import importlib.util
import os
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Math, display

import symjac
from symjac import latex
from symjac.analysis.identification import (
    base_parameters,
    excitation_condition,
    fourier_trajectory,
    identify,
    joint_weights,
    optimise_excitation,
    regressor,
    stack,
    standard_values,
)
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The regressor and the base parameters
#
# Each link has ten standard parameters, its inertia tensor about the origin of its frame $\{i\}$ (`XX`, `XY`,
# `XZ`, `YY`, `YZ`, `ZZ`), its first moments $m\,c$ (`MX`, `MY`, `MZ`) and its mass `M`: 60 for the PUMA. Where
# the robot's model has drive data, each joint adds its motor inertia `Ia`, viscous friction `Fv` and Coulomb
# friction `Fc` (we ask for the columns the model carries, as generated code does). Many parameters never act on the
# torques (the first link only turns about the vertical), and others act only in fixed combinations. symjac finds
# those combinations in closed form:

# %%
puma = symjac.load_robot("puma560")
drives = [drive for drive in getattr(puma, "drives", ()) if drive is not None]
carried = {field: any(getattr(drive, field) != 0 for drive in drives) for field in ("armature", "viscous", "coulomb")}
Y = regressor(puma, **carried)
base = base_parameters(Y)
print(f"{len(Y.parameters)} standard parameters, {len(base.symbols)} base parameters, "
      f"{len(base.unidentifiable)} that act on nothing")
for symbol, expression in list(zip(base.symbols, base.expressions, strict=True))[:4]:
    display(Math(latex(symbol) + " = " + latex(expression)))

# %% [markdown]
# `ZZR1` gathers everything that turns with joint 1 about the vertical axis; `XXR2` is $XX_2 - YY_2$ plus mass
# terms: only the difference of two moments of link 2 shows in the torques. The robot's own data give the true
# values of the base parameters, which the identification must find:

# %%
values = standard_values(puma)
standard = {p: values.get(p, sp.S.Zero) for p in Y.parameters}
true_base = np.array([float(sp.sympify(e).xreplace(standard).xreplace(puma.defaults)) for e in base.expressions])
print(dict(zip((s.name for s in base.symbols[:6]), true_base[:6].round(4), strict=True)))

# %% [markdown]
# ## A generated module with the regressors
#
# `identification=True` adds `regressor(q, qdot, qddot)` and `base_regressor(q, qdot, qddot)` to a generated module
# (with the dynamics), and names their columns in order in `REGRESSOR_PARAMETERS` and `BASE_PARAMETERS`. The
# module's self-test checks that each regressor times the robot's own parameters is its inverse dynamics. (The
# same from the command line: `symjac codegen puma560 --identification --target numpy`.)

# %%
folder = Path(tempfile.mkdtemp())
(folder / "puma_identification.py").write_text(symjac.generate(puma, "numpy", identification=True))
spec = importlib.util.spec_from_file_location("puma_identification", folder / "puma_identification.py")
arm = importlib.util.module_from_spec(spec)
spec.loader.exec_module(arm)
print("self-test error:", arm.selftest())
assert tuple(symbol.name for symbol in base.symbols) == arm.BASE_PARAMETERS
print(arm.BASE_PARAMETERS[:8])

# %% [markdown]
# ## An exciting trajectory
#
# Each joint follows a finite Fourier series of $L = 3$ harmonics of $\omega_f = 2\pi/10$ rad/s (period 10 s):
#
# $$q_j(t) = q_{0,j} + \sum_{l=1}^{L} \frac{a_{jl}}{\omega_f l}\sin(\omega_f l t)
#   - \frac{b_{jl}}{\omega_f l}\cos(\omega_f l t)$$
#
# Its quality is the condition number of the base regressor stacked along it: the factor by which noise in the
# torques can be amplified in the estimate. Among a few random coefficient sets we keep the best, then let SciPy's
# SLSQP improve it a little (a few iterations here: a real experiment runs it to convergence), keeping every joint
# within $\pm 1.5$ rad of its offset, its rate under 2 rad/s and its acceleration under 6 rad/s$^2$.

# %%
joints, harmonics, w_f = 6, 3, 2 * np.pi / 10
t_design = np.linspace(0, 10, 30, endpoint=False)
rng = np.random.default_rng(11)
candidates = [rng.normal(0.0, 0.3, (joints, 2, harmonics)) for _ in range(8)]
kappas = [excitation_condition(arm.base_regressor, c, w_f, np.zeros(joints), t_design) for c in candidates]
best = candidates[int(np.argmin(kappas))]
print("random trajectories:", np.round(kappas, 1))
excitation = optimise_excitation(arm.base_regressor, joints, harmonics, w_f, t_design, q0=np.zeros(joints),
                                 lower=-1.5, upper=1.5, velocity_limit=2.0, acceleration_limit=6.0, initial=best,
                                 max_iterations=3)
print(f"condition number: {excitation.initial_condition_number:.1f} -> {excitation.condition_number:.1f}")

# %% [markdown]
# ## Simulated measurements
#
# 1000 samples over one period. The torques are the generated inverse dynamics; forward dynamics, from the same
# module, gives the accelerations back from them (the data are consistent with the model they came from).

# %%
t = np.linspace(0, 10, 1000, endpoint=False)
q, qdot, qddot = fourier_trajectory(excitation.coefficients, w_f, excitation.q0, t)
tau = arm.inverse_dynamics(q, qdot, qddot)
print("forward dynamics reproduces qddot to", np.abs(arm.forward_dynamics(q, qdot, tau) - qddot).max())
fig, axes = plt.subplots(1, 2, figsize=(11, 3.5))
axes[0].plot(t, q)
axes[0].set_title("joint angles q(t) (rad)")
axes[1].plot(t, tau)
axes[1].set_title("torques tau(t) (N m)")
for ax in axes:
    ax.set_xlabel("t (s)")
fig.tight_layout()
fig.savefig(OUTPUT / "11_trajectory.png", dpi=100)

# %% [markdown]
# ## Least squares, without noise
#
# Stacking the base regressor of every sample gives a tall system $W_s\,\pi_b = \tau_s$ (6000 rows, 36 columns);
# its least-squares solution is exact up to rounding when the data are exact:

# %%
W = stack(arm.base_regressor, q, qdot, qddot)
exact = identify(W, tau, names=arm.BASE_PARAMETERS)
error = np.abs(exact.parameters - true_base)
print(f"stacked regressor {W.shape}, condition number {exact.condition_number:.1f}")
print("largest error:", error.max())
assert np.all(error <= 1e-6 * np.maximum(1.0, np.abs(true_base)))

# %% [markdown]
# ## With noisy torques
#
# Now each joint's torque carries white noise, stronger on the big joints 2 and 3 (0.5 N m) than on the others
# (0.05 N m). The covariance $\hat\sigma^2 (W_s^T W W_s)^{-1}$ gives each estimate a standard deviation. Ordinary
# least squares treats every row alike and pools the noise into one $\hat\sigma^2$, so its deviations are right
# only when every joint is equally noisy; weighting each joint's rows by the inverse of its own noise variance
# (estimated from the data, `joint_weights`) makes the model of the noise right, and sharpens the parameters the
# quiet joints see.

# %%
noise_level = np.array([0.05, 0.5, 0.5, 0.05, 0.05, 0.05])
measured = tau + rng.normal(0.0, 1.0, tau.shape) * noise_level
ordinary = identify(W, measured, names=arm.BASE_PARAMETERS)
weighted = identify(W, measured, joint_weights(W, measured, joints), names=arm.BASE_PARAMETERS)
for name, result in (("ordinary", ordinary), ("weighted", weighted)):
    within = np.abs(result.parameters - true_base) / result.standard_deviations
    print(f"{name}: residual RMS {result.residual_rms:.3f} N m, condition number {result.condition_number:.1f}, "
          f"{np.mean(within <= 2):.0%} within 2 sigma, largest deviation {within.max():.2f} sigma")
assert within.max() <= 4.0  # the weighted estimate, whose noise model is right, within its stated confidence

# %% [markdown]
# The weighted estimates land within their stated confidence. Parameters that move the torques a lot (`ZZR1`, `MXR2`,
# `XXR2`: the big inertias and first moments of links 1 to 3) are found to a fraction of a percent; those of the
# small wrist links, a few grams and thousandths of kg m², drown in the noise: their relative deviations say so, and
# an experiment would excite the wrist harder, or measure longer, before trusting them.

# %%
order = np.argsort(weighted.relative_deviations)
fig, ax = plt.subplots(figsize=(11, 3.5))
ax.bar(range(len(order)), np.minimum(weighted.relative_deviations[order], 1000.0))
ax.set_yscale("log")
ax.set_xticks(range(len(order)))
ax.set_xticklabels([arm.BASE_PARAMETERS[k] for k in order], rotation=90, fontsize=7)
ax.set_ylabel("relative standard deviation (%)")
ax.set_title("How well each base parameter is known (weighted least squares, noisy torques)")
fig.tight_layout()
fig.savefig(OUTPUT / "11_deviations.png", dpi=100)
for k in order[:5]:
    print(f"{arm.BASE_PARAMETERS[k]:>6}: true {true_base[k]: .5f}, estimated {weighted.parameters[k]: .5f} "
          f"+- {weighted.standard_deviations[k]:.5f} ({weighted.relative_deviations[k]:.2f} %)")

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer and run the cell: `check` compares it with what symjac derives. Worked
# answers: `notebooks/solutions.py`. To see an answer, add `reveal=True` to the cell's `check(...)`.
#
# 1. How many base parameters of the PUMA 560 group parameters of its links (leave out the drives' `Ia`, `Fv`, `Fc`
#    columns, if any)? The published count for this arm is the same.
# 2. The planar 2R arm (`planar2r`) turns in a horizontal plane. Its base parameter `MXR2` groups link 2's first
#    moment `MX2` with a mass: write `MXR2` in the standard parameters and the link length `L2`.

# %%
answer_1 = ...  # your answer here
check(answer_1, sum(not symbol.name.startswith(("Ia", "Fv", "Fc")) for symbol in base.standard))

# %%
planar_base = base_parameters(regressor(symjac.load_robot("planar2r")))
MX2, M2, L2 = sp.symbols("MX2 M2 L2")
answer_2 = ...  # your answer here
check(answer_2, planar_base.expressions[[s.name for s in planar_base.symbols].index("MXR2")])
print("all answers correct")
