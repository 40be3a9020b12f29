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
# # 6. From symbols to fast numbers: generating a module
#
# **What you will learn**
#
# * how symjac turns a symbolic Jacobian into a small Python module that a controller or simulator can import
#   without SymPy;
# * how to check such a module (its own `selftest()` compares the Jacobian with finite differences of its forward
#   kinematics) and compare it with an independent evaluation;
# * why common-subexpression elimination and writing into preallocated arrays matter, by timing the generated
#   code against a plain `sympy.lambdify`.

# %%
import importlib.util
import os
import sys
import timeit
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

from symjac import determinant, jacobian, load_robot, numeric_jacobian
from symjac.codegen import generate, write_module
from symjac.teaching.exercises import check

OUTPUT = Path(os.environ.get("SYMJAC_NOTEBOOK_OUTPUT", "figures"))
OUTPUT.mkdir(parents=True, exist_ok=True)
robot = load_robot("puma560")

# %% [markdown]
# ## Generate, write, import
#
# `generate` returns the source text; the same input always gives the same bytes, so generated files can be
# committed and reviewed. We also hand it the factored determinant derived in notebook 4, which evaluates in a
# handful of operations.

# %%
det = determinant(robot)
modules = {}
for target in ("python", "numpy"):
    source = generate(robot, target, scalars={"det_factored": det.expression})
    path = write_module(OUTPUT / f"puma560_{target}.py", source)
    spec = importlib.util.spec_from_file_location(f"puma560_{target}", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    modules[target] = module
print("\n".join(source.splitlines()[:5]))

# %% [markdown]
# ## Check it
#
# First the module's own check, then an independent one: symjac's numeric Jacobian at random configurations.

# %%
plain, batched = modules["python"], modules["numpy"]
plain.selftest()
batched.selftest()
rng = np.random.default_rng(1)
qs = rng.uniform(-np.pi, np.pi, size=(5, 6))
for q in qs:
    assert np.allclose(np.array(plain.jacobian(list(q))), numeric_jacobian(robot, q), atol=1e-12)
assert np.allclose(batched.jacobian(qs), np.array([numeric_jacobian(robot, q) for q in qs]), atol=1e-12)
print("generated Jacobians agree with symjac")

# %% [markdown]
# The factored determinant and the determinant of the numeric Jacobian agree too:

# %%
q = qs[0]
print(plain.det_factored(list(q)), np.linalg.det(numeric_jacobian(robot, q)))

# %% [markdown]
# ## Timing against `sympy.lambdify`
#
# The baseline is what one might write first: `lambdify` of the unsimplified Jacobian, no common subexpressions.
# One configuration per call, best of several repetitions.

# %%
q_sym = robot.q
raw = jacobian(robot, simplify=False).xreplace(robot.defaults)
baseline = sp.lambdify([q_sym], list(raw), modules="math", cse=False)
q_list = list(qs[0])
timings = {
    "lambdify, no CSE": min(timeit.repeat(lambda: baseline(q_list), number=2000, repeat=5)) / 2000,
    "generated python": min(timeit.repeat(lambda: plain.jacobian(q_list), number=2000, repeat=5)) / 2000,
}
batch = rng.uniform(-np.pi, np.pi, size=(20000, 6))
out = np.empty((20000, 6, 6))
per_config = min(timeit.repeat(lambda: batched.jacobian(batch, out=out), number=3, repeat=3)) / 3 / len(batch)
timings["generated numpy (per config, batched)"] = per_config
for name, seconds in timings.items():
    print(f"{name:>40}: {seconds * 1e6:8.3f} us")

fig, ax = plt.subplots(figsize=(7, 3))
ax.barh(list(timings), [t * 1e6 for t in timings.values()])
ax.set_xlabel("microseconds per configuration (PUMA 560 Jacobian)")
ax.set_xscale("log")
fig.tight_layout()
fig.savefig(OUTPUT / "06_timings.png", dpi=100)

# %% [markdown]
# ## Exercises
#
# Replace each `...` with your answer, in any equivalent form, and run the cell: `check` compares it exactly
# with what symjac derives (plain `sp.symbols("L2 theta1")` are fine). Worked answers: `notebooks/solutions.py`.
# A wrong answer gets a hint of what is wrong, never the answer; to see the answer, add `reveal=True` to the
# cell's `check(...)`.
#
# 1. The generated modules take the robot's parameters as keyword arguments. What is entry (1, 1) of the
#    Jacobian (row $v_x$, column $\theta_1$) at $q = 0$ when $d_3 = 0.2$? Compute it with the plain-Python module
#    and compare with the symbolic Jacobian.
# 2. Use the batched module to compute the manipulability $\sqrt{\det(J J^T)}$ of the first 50 configurations of
#    `batch` in one call (check it against `np.linalg.det` of the numeric Jacobians).

# %%
d3 = sp.Symbol("d3", real=True)
answer_1 = ...  # your answer here
expected_1 = jacobian(robot)[0, 0].xreplace({**robot.defaults, d3: sp.Rational(1, 5), **dict.fromkeys(q_sym, 0)})
check(answer_1, expected_1)

# %%
answer_2 = ...  # your answer here
expected_2 = [abs(np.linalg.det(numeric_jacobian(robot, q))) for q in batch[:50]]
check(answer_2, expected_2, tolerance=1e-9)
print("all answers correct")
