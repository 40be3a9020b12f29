"""The compiled numeric model from Python, against pinocchio and the Robotics Toolbox: ``python benchmarks/numeric_model.py``.

One run prints four Markdown tables (best of five repeats of ``timeit``; nothing is asserted):

1. **One call** from Python, microseconds: ``symjac.numeric_model`` with the ``c`` and ``numpy`` backends
   (``model.jacobian(q)``, ``model.fk(q)``), ``symjac.numeric_jacobian`` (the thin wrapper, ``numpy`` backend), the
   analyses' own ``sympy.lambdify`` path (``symjac.kinematics.numeric.numeric_jacobian``, what
   ``symjac.numeric_jacobian`` was before), pinocchio's ``computeFrameJacobian`` (``LOCAL_WORLD_ALIGNED``) and
   ``forwardKinematics`` + ``updateFramePlacement`` on the UR5 read from the same URDF file (``tool0``; the script
   first checks that pinocchio's Jacobian and symjac's agree), and the Robotics Toolbox's ``jacob0`` and ``fkine``
   on its ``models.DH.Puma560()`` (its own standard-DH PUMA; symjac's is Craig's modified-DH one: same size, timing
   only).
2. **A batch**, nanoseconds per configuration (N configurations in one call; pinocchio and the Toolbox have no batch
   call from Python, so theirs is a loop).
3. **Growth with the batch size**, PUMA 560 Jacobian, nanoseconds per configuration.
4. **Growth with the joints**: catalog arms of 2 to 7 joints, one call and per configuration of a batch.

The first call per robot and request derives, generates and (for ``c``) compiles; it is timed once, in a cache
directory of its own unless ``--warm`` is given. Pinocchio (PyPI ``pin``) and the Robotics Toolbox
(``roboticstoolbox-python``) are optional: without them their rows say so. ``--quick`` runs small batches and
few repeats (a check that the script runs). The C kernels split batches of 16384 configurations or more over the
machine's cores (``THREADS`` of the generated module).
"""  # noqa: E501  # the summary line names the command

from __future__ import annotations

import argparse
import os
import tempfile
import time
import timeit
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import symjac
from symjac import clear_caches, load_robot, numeric_model
from symjac.kinematics.numeric import numeric_jacobian as lambdified_jacobian

__all__ = ["main"]

URDF = Path(symjac.__file__).resolve().parent / "robots" / "urdf" / "ur5.urdf"
GROWTH = ["planar2r", "planar3r", "scara", "puma560", "ur5", "panda"]


def per_call(function: Callable[[], Any], seconds: float) -> float:
    """Seconds per call: the best of five repeats, each about ``seconds`` long."""
    timer = timeit.Timer(function)
    number, _ = timer.autorange()
    number = max(1, int(number * seconds / 0.2))
    return min(timer.repeat(repeat=5, number=number)) / number


def configurations(count: int, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (count, n))


def optional(name: str) -> Any:
    try:
        return __import__(name)
    except ImportError:
        return None


def first_calls(seconds_note: list[str]) -> dict[str, Any]:
    """Build the models once each, timing the first call (derive, generate, compile)."""
    models: dict[str, Any] = {}
    for key, name, frame, point in (("puma", "puma560", 0, None), ("ur5", "ur5.urdf", "world", "tool")):
        robot = load_robot(name)
        for backend in ("c", "numpy"):
            clear_caches()
            start = time.perf_counter()
            models[key, backend] = numeric_model(robot, frame, point, backend)
            seconds_note.append(f"{name} {backend}: {time.perf_counter() - start:.2f} s")
    return models


def single_table(models: dict[str, Any], seconds: float) -> None:
    pin, rtb = optional("pinocchio"), optional("roboticstoolbox")
    q = configurations(1, 6)[0]
    puma, ur5 = load_robot("puma560"), load_robot("ur5.urdf")
    rows: list[tuple[str, str, str, str]] = []

    def us(function: Callable[[], Any]) -> str:
        return f"{per_call(function, seconds) * 1e6:.2f}"

    for backend in ("c", "numpy"):
        m_puma, m_ur5 = models["puma", backend], models["ur5", backend]
        rows.append((f"symjac numeric_model, {m_puma.backend}", us(lambda m=m_puma: m.jacobian(q)),
                     us(lambda m=m_ur5: m.jacobian(q)), us(lambda m=m_puma: m.fk(q))))
    qs = q.tolist()
    rows.append(("symjac.numeric_jacobian (numpy)", us(lambda: symjac.numeric_jacobian(puma, qs)),
                 us(lambda: symjac.numeric_jacobian(ur5, qs, "world", "tool")), "-"))
    rows.append(("sympy.lambdify path (the analyses')", us(lambda: lambdified_jacobian(puma, qs)),
                 us(lambda: lambdified_jacobian(ur5, qs, "world", "tool")), "-"))
    if pin is not None:
        model = pin.buildModelFromUrdf(str(URDF))
        data = model.createData()
        frame = model.getFrameId("tool0")
        J = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)
        error = float(np.abs(J - models["ur5", "c"].jacobian(q)).max())
        assert error < 1e-12, f"pinocchio and symjac disagree on the UR5 Jacobian by {error}"

        def pin_fk() -> None:
            pin.forwardKinematics(model, data, q)
            pin.updateFramePlacement(model, data, frame)

        rows.append((f"pinocchio {pin.__version__} (UR5 URDF)", "-",
                     us(lambda: pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)),
                     us(pin_fk)))
    else:
        rows.append(("pinocchio", "not installed", "not installed", "not installed"))
    if rtb is not None:
        arm = rtb.models.DH.Puma560()
        rows.append((f"Robotics Toolbox {rtb.__version__} (its Puma560)", us(lambda: arm.jacob0(q)), "-",
                     us(lambda: arm.fkine(q))))
    else:
        rows.append(("Robotics Toolbox", "not installed", "-", "not installed"))
    print("| one call, us | PUMA 560 Jacobian | UR5 (URDF) Jacobian at tool0 | PUMA 560 FK |")
    print("|---|---:|---:|---:|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


def batch_table(models: dict[str, Any], count: int, seconds: float) -> None:
    pin, rtb = optional("pinocchio"), optional("roboticstoolbox")
    Q = configurations(count, 6, seed=1)
    print(f"\n| batch of {count}, ns per configuration | PUMA 560 Jacobian | UR5 (URDF) Jacobian | PUMA 560 FK |")
    print("|---|---:|---:|---:|")

    def ns(function: Callable[[], Any], size: int) -> str:
        return f"{per_call(function, seconds) * 1e9 / size:.1f}"

    for backend in ("c", "numpy"):
        m_puma, m_ur5 = models["puma", backend], models["ur5", backend]
        J, T = np.empty((count, 6, 6)), np.empty((count, 4, 4))
        jac_puma = ns(lambda m=m_puma, J=J: m.jacobian(Q, J), count)
        jac_ur5 = ns(lambda m=m_ur5, J=J: m.jacobian(Q, J), count)
        fk_puma = ns(lambda m=m_puma, T=T: m.fk(Q, T), count)
        print(f"| symjac numeric_model, {m_puma.backend}, out= | {jac_puma} | {jac_ur5} | {fk_puma} |")
    loop = Q[: min(count, 200)]
    if pin is not None:
        model = pin.buildModelFromUrdf(str(URDF))
        data = model.createData()
        frame = model.getFrameId("tool0")

        def pin_loop() -> None:
            for q in loop:
                pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)

        print(f"| pinocchio, a Python loop | - | {ns(pin_loop, len(loop))} | - |")
    if rtb is not None:
        arm = rtb.models.DH.Puma560()

        def rtb_loop() -> None:
            for q in loop:
                arm.jacob0(q)

        print(f"| Robotics Toolbox, a Python loop | {ns(rtb_loop, len(loop))} | - | "
              f"{ns(lambda: arm.fkine(loop), len(loop))} (fkine of a batch) |")


def growth_with_batch(models: dict[str, Any], sizes: list[int], seconds: float) -> None:
    print("\n| configurations N | " + " | ".join(str(size) for size in sizes) + " |")
    print("|---|" + "---:|" * len(sizes))
    for backend in ("c", "numpy"):
        model = models["puma", backend]
        cells = []
        for size in sizes:
            Q, J = configurations(size, 6, seed=2), np.empty((size, 6, 6))
            cells.append(f"{per_call(lambda m=model, Q=Q, J=J: m.jacobian(Q, J), seconds) * 1e9 / size:.1f}")
        print(f"| {model.backend}, ns per configuration | " + " | ".join(cells) + " |")


def growth_with_joints(names: list[str], count: int, seconds: float) -> None:
    print(f"\n| arm (joints) | c: one call, us | c: batch of {count}, ns each | numpy: one call, us | "
          f"numpy: batch, ns each |")
    print("|---|---:|---:|---:|---:|")
    for name in names:
        robot = load_robot(name)
        cells = []
        for backend in ("c", "numpy"):
            model = numeric_model(robot, backend=backend)
            q, Q = configurations(1, model.n)[0], configurations(count, model.n, seed=3)
            J = np.empty((count, 6, model.n))
            cells += [f"{per_call(lambda m=model, q=q: m.jacobian(q), seconds) * 1e6:.2f}",
                      f"{per_call(lambda m=model, Q=Q, J=J: m.jacobian(Q, J), seconds) * 1e9 / count:.1f}"]
        print(f"| {name} ({robot.n_coordinates}) | " + " | ".join(cells) + " |")


def main(argv: list[str] | None = None) -> None:
    """Print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="small batches, short repeats (the script runs)")
    parser.add_argument("--warm", action="store_true", help="use the user's C cache for the first calls")
    options = parser.parse_args(argv)
    seconds = 0.02 if options.quick else 0.2
    count = 1000 if options.quick else 10000
    sizes = [1, 10, 100, 1000] if options.quick else [1, 10, 100, 1000, 10000, 100000, 1000000]
    with tempfile.TemporaryDirectory() as cache:
        if not options.warm:
            os.environ["SYMJAC_CACHE_DIR"] = cache
        notes: list[str] = []
        models = first_calls(notes)
        print("First call (derive, generate, compile for c): " + "; ".join(notes) + "\n")
        single_table(models, seconds)
        batch_table(models, count, seconds)
        growth_with_batch(models, sizes, seconds)
        growth_with_joints(GROWTH[:3] if options.quick else GROWTH, count, seconds)


if __name__ == "__main__":
    main()
