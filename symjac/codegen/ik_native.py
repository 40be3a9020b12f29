"""The closed-form inverse kinematics a numeric model's ``ik`` runs in C: the c99 target's, in a shared library.

:func:`native_inverse_kinematics` generates the robot's c99 files with ``inverse_kinematics``, adds a loop over a
batch of poses, compiles them once into a shared library kept in the cache folder the ``"c"`` target uses
(``$SYMJAC_CACHE_DIR``, else ``$XDG_CACHE_HOME/symjac`` or ``~/.cache/symjac``), named by a hash of the sources and
the compiler, and calls it through :mod:`ctypes`: one pose or a batch, without NumPy's per-operation cost.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import subprocess
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path

import numpy as np

from symjac.codegen.module import ModuleRequest, describe, render_files
from symjac.kinematics.chain import Chain

__all__ = ["NativeIK", "native_inverse_kinematics"]

NativeIK = Callable[[np.ndarray, float], tuple[np.ndarray, np.ndarray]]
"""``solve(poses, tolerance) -> (solutions, counts)`` for C-contiguous float64 poses of shape (N, 4, 4)."""

_LOOP = """#include <math.h>
#include <stddef.h>

#include "{name}.h"

/* Every pose of a batch: row k of out holds pose k's count, then its solutions, then NaN up to the most. */
void sj_ik_batch(const double *poses, long count, double tolerance, double *out);

void sj_ik_batch(const double *poses, long count, double tolerance, double *out)
{{
    const int size = {macro}_IK_MAX_SOLUTIONS * {macro}_N_COORDINATES;
    for (long k = 0; k < count; ++k) {{
        double *row = out + k * (size + 1);
        const int found = {name}_inverse_kinematics(poses + 16 * k, NULL, tolerance, row + 1);
        row[0] = (double)found;
        for (int i = found * {macro}_N_COORDINATES; i < size; ++i) {{
            row[1 + i] = NAN;
        }}
    }}
}}
"""


def _cache_directory() -> Path:
    configured = os.environ.get("SYMJAC_CACHE_DIR")
    if configured:
        return Path(configured)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "symjac"


def native_inverse_kinematics(chain: Chain, name: str, compiler: str) -> tuple[NativeIK, int]:
    """The compiled closed form of ``chain``'s robot (module ``name``) and its most solutions per pose.

    Raises whatever stops it (no closed form, a compiler error); the caller falls back to NumPy.
    """
    files = render_files(describe(ModuleRequest(chain, "c99", strategy="raw", name=name, inverse_kinematics=True)))
    loop = _LOOP.format(name=name, macro=name.upper())
    key = hashlib.sha256("\0".join([*files.values(), loop, compiler]).encode()).hexdigest()[:16]
    library = _cache_directory() / f"{name}_ik_{key}.so"
    if not library.is_file():
        library.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(dir=library.parent) as work:
            for file_name, text in files.items():
                (Path(work) / file_name).write_text(text, encoding="utf-8")
            (Path(work) / "loop.c").write_text(loop, encoding="utf-8")
            target = Path(work) / library.name
            result = subprocess.run([compiler, "-std=c99", "-O2", "-fPIC", "-shared", f"{name}.c", "loop.c", "-o",
                                     str(target), "-lm"], cwd=work, capture_output=True, text=True, check=False)
            if result.returncode != 0:
                raise RuntimeError(f"{compiler} failed: {result.stderr.strip()[-1000:]}")
            os.replace(target, library)
    batch = ctypes.CDLL(str(library)).sj_ik_batch
    batch.restype = None
    batch.argtypes = [ctypes.c_void_p, ctypes.c_long, ctypes.c_double, ctypes.c_void_p]
    header = files[f"{name}.h"]
    most = int(next(line.split()[-1] for line in header.splitlines()
                    if line.startswith(f"#define {name.upper()}_IK_MAX_SOLUTIONS ")))
    n = chain.robot.n_coordinates
    local = threading.local()  # one pose's buffers, per thread: ctypes releases the GIL during the call

    def solve(poses: np.ndarray, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
        count = poses.size // 16
        if count == 1:
            buffers = getattr(local, "buffers", None)
            if buffers is None:
                pose, out = np.empty(16), np.empty(most * n + 1)
                buffers = local.buffers = (pose, out, pose.ctypes.data, out.ctypes.data)
            pose, out, pose_address, out_address = buffers
            pose[:] = poses.reshape(16)
            batch(pose_address, 1, tolerance, out_address)
            return out[1:].reshape(1, most, n).copy(), np.array([int(out[0])])
        table = np.empty((count, most * n + 1))
        batch(poses.ctypes.data, count, tolerance, table.ctypes.data)
        return table[:, 1:].reshape(count, most, n), table[:, 0].astype(np.intp)

    return solve, most
