r"""Design sweeps: :func:`sweep` evaluates dexterity metrics over joint samples for every design of a parameter grid.

The work is a task graph: one task per design and chunk of joint samples (the generated kernel evaluates the
Jacobian of the whole chunk at once, then :class:`~symjac.sweeps.metrics.Tally` reduces it), then one task per design
merging its chunks' tallies. Memory stays bounded by the chunk size, however many samples there are. The graph runs
on dask (its local threaded scheduler by default, or a ``distributed.Client``'s cluster), or in the calling process
without dask (``scheduler="synchronous"``). The kernel is the ``c`` code generation target: compiled C where a
compiler is present, its NumPy fallback elsewhere; a worker compiles or imports it from the module text it is sent.
"""

from __future__ import annotations

import concurrent.futures
import functools
import hashlib
import importlib.util
import itertools
import math
import shutil
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from symjac._version import __version__
from symjac.codegen import JacobianRequest, generate
from symjac.drawing.geometry import arm_pose
from symjac.errors import ArgumentError, SymjacError
from symjac.kinematics.chain import Frame
from symjac.model.ends import end_point
from symjac.model.robot import Robot
from symjac.sweeps.metrics import HISTOGRAM_EDGES, METRICS, Tally
from symjac.sweeps.sampling import JointSampler, Sampling, joint_ranges, parameter_grid

__all__ = ["MOST_TASKS", "SCHEDULERS", "kernel_module", "sweep"]

DEFAULT_METRICS = ("gci", "manipulability", "sigma_min", "near_singular")

SCHEDULERS = ("threads", "processes", "synchronous")
"""dask's local schedulers by name; anything with ``://`` is the address of a dask.distributed scheduler."""

MOST_TASKS = 1_000_000
"""A sweep of more tasks (designs times chunks) is refused before it starts: raise ``chunk`` or narrow the grid."""


@functools.cache
def kernel_module(source: str) -> ModuleType:
    """The generated module ``source``, imported once per process (from a private temporary folder)."""
    name = "symjac_sweep_" + hashlib.sha256(source.encode()).hexdigest()[:16]
    folder = Path(tempfile.mkdtemp(prefix="symjac-sweep-"))
    path = folder / f"{name}.py"
    path.write_text(source, encoding="utf-8")
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)  # the c target compiles into its own cache; the file is not needed after
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    if hasattr(module, "THREADS"):
        setattr(module, "THREADS", 1)  # noqa: B010  # the scheduler spreads the chunks over the cores
    return module


def _chunk_tally(source: str, design: dict[str, float], sampler: JointSampler, start: int, stop: int,
                 near: float, voxel: float, points: bool, sigma: bool) -> Tally:
    """One task: the tally of samples ``start`` to ``stop - 1`` for one design."""
    module = kernel_module(source)
    Q = sampler.chunk(start, stop)
    J = np.asarray(module.jacobian(Q, **design))
    tool = np.asarray(module.forward_kinematics(Q, **design))[:, :3, 3] if points else None
    return Tally().add(J, tool, near, voxel, sigma)


def _merged(tallies: Sequence[Tally]) -> Tally:
    return functools.reduce(Tally.merge, tallies, Tally())


def sweep(robot: Robot, params: Mapping[str, tuple[float, float, int] | Sequence[float]], *,
          samples: int = 100_000, metrics: Sequence[str] = DEFAULT_METRICS, frame: Frame = 0,
          point: Any = None, rows: Sequence[int] | None = None, sampling: Sampling = "sobol",
          ranges: Mapping[str, tuple[float, float]] | None = None, chunk: int = 65_536, near: float = 0.01,
          voxel: float | None = None, seed: int = 0, scheduler: str | None = None, client: Any = None) -> Any:
    r"""Dexterity metrics of every design of a parameter grid, over joint samples, as a labelled array.

    Parameters
    ----------
    robot : Robot
    params : mapping
        Parameter name to ``(low, high, count)`` (evenly spaced, ends included) or to a list of values; the grid is
        their product, the other parameters keep their defaults.
    samples : int
        Joint configurations per design (a grid rounds up to ``m ** n``).
    metrics : sequence of str
        From :data:`~symjac.sweeps.metrics.METRICS` (see :mod:`symjac.sweeps.metrics` for their definitions; the
        condition number of ``gci`` is in the 2-norm, that of ``gci_frobenius`` the normalised Frobenius one).
    frame, point, rows
        The Jacobian analysed, as for :func:`symjac.jacobian` (point: default the end of the chain, the tool point
        if the robot has one, else the flange; rows: task rows, default all six).
    sampling : "sobol" or "grid"
        Scrambled Sobol points (in independently scrambled blocks of 2**16, seeded by ``seed`` and the block) or a
        regular grid of cell centres.
    ranges : mapping, optional
        Coordinate name to ``(low, high)``, instead of the joint's limits (default; (-pi, pi) without limits).
    chunk : int
        Samples per task: memory per task is a few kB per sample of the chunk.
    near : float
        ``near_singular`` counts samples with :math:`1/\kappa` below this.
    voxel : float, optional
        Edge of the workspace voxels (default: the arm's reach at its home configuration over 50). The volume
        counts the voxels the tool frame's origin reaches among the samples: a lower bound that grows towards the
        workspace volume as the samples fill the voxels (``samples`` much larger than ``(reach / voxel) ** 3``).
    scheduler : str, optional
        A dask scheduler: ``"threads"`` (the default with dask), ``"processes"``, ``"synchronous"`` (one process,
        also the fallback without dask), or the address of a dask.distributed scheduler (``"tcp://host:8786"``).
    client : distributed.Client, optional
        Run on this client's cluster.

    Returns
    -------
    xarray.Dataset
        One variable per metric value, over one dimension per swept parameter (coordinates: its values).

    Examples
    --------
    >>> from symjac import load_robot
    >>> result = sweep(load_robot("planar2r"), {"L2": [0.2, 0.5]}, samples=256, metrics=["gci"],
    ...                rows=[0, 1], scheduler="synchronous")
    >>> result["gci"].dims, bool(result["gci"].sel(L2=0.5) > result["gci"].sel(L2=0.2))
    (('L2',), True)
    """
    metrics = tuple(metrics)
    unknown = [m for m in metrics if m not in METRICS]
    if unknown or not metrics:
        raise ArgumentError(f"unknown metric {unknown[0]!r}; choose from {', '.join(METRICS)}" if unknown
                            else "give at least one metric")
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ArgumentError(f"chunk must be a positive integer, got {chunk!r}")
    if isinstance(near, bool) or not (isinstance(near, int | float) and math.isfinite(near) and near >= 0):
        raise ArgumentError(f"near must be a finite number >= 0, got {near!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ArgumentError(f"seed must be a whole number >= 0, got {seed!r}")
    if scheduler is not None and scheduler not in SCHEDULERS and "://" not in str(scheduler):
        raise ArgumentError(f"unknown scheduler {scheduler!r}; choose {', '.join(SCHEDULERS)} or tcp://HOST:PORT")
    task_rows = tuple(range(6)) if rows is None else tuple(rows)
    square = len(task_rows) == robot.n_coordinates
    if "gci_frobenius" in metrics and not square:
        raise ArgumentError(f"gci_frobenius needs a square Jacobian: choose {robot.n_coordinates} rows, not "
                            f"{len(task_rows)}")
    grid = parameter_grid(robot, params)
    sampler = JointSampler(joint_ranges(robot, ranges), samples, sampling, seed)
    designs_count = math.prod(len(v) for v in grid.values())
    tasks = designs_count * -(-sampler.total // chunk)
    if tasks > MOST_TASKS:
        raise ArgumentError(f"{designs_count} designs x {-(-sampler.total // chunk)} chunks is {tasks} tasks, more "
                            f"than {MOST_TASKS}: raise chunk or sweep fewer values")
    size = voxel if voxel is not None else arm_pose(robot).reach / 50
    if isinstance(size, bool) or not (isinstance(size, int | float) and math.isfinite(size) and size > 0):
        raise ArgumentError(f"voxel must be a positive number, got {voxel!r}")
    source = generate(robot, "c", jacobians=[JacobianRequest(frame, point, None if rows is None else task_rows)])
    names = list(grid)
    designs = [dict(zip(names, map(float, values), strict=True)) for values in itertools.product(*grid.values())]
    bounds = [(start, min(start + chunk, sampler.total)) for start in range(0, sampler.total, chunk)]
    points = "workspace_volume" in metrics
    sigma = not set(metrics) <= {"manipulability", "workspace_volume", "gci_frobenius"}  # else LU is enough
    tallies = _run(source, designs, sampler, bounds, (near, size, points, sigma), scheduler, client)
    return _dataset(robot, grid, [t.values(metrics, square, size) for t in tallies],
                    {"symjac": __version__, "samples": sampler.total, "sampling": sampling, "seed": seed,
                     "metrics": ",".join(metrics), "frame": str(frame),
                     "point": str(end_point(robot) if point is None else point),
                     "rows": ",".join(map(str, task_rows)), "near": near, "voxel": size, "chunk": chunk,
                     "ranges": "; ".join(f"{name} {low:.17g}..{high:.17g}" for name, (low, high)
                                         in zip(map(str, robot.q), sampler.ranges, strict=True))})


def _run(source: str, designs: list[dict[str, float]], sampler: JointSampler, bounds: list[tuple[int, int]],
         settings: tuple[float, float, bool, bool], scheduler: str | None, client: Any) -> list[Tally]:
    """Every design's merged tally, on dask or in this process (``settings``: near, voxel, points, sigma)."""
    try:
        import dask
    except ImportError:
        if scheduler not in (None, "synchronous") or client is not None:
            raise SymjacError("running a sweep on dask needs dask: pip install 'symjac[sweep]'") from None
        return [_merged([_chunk_tally(source, d, sampler, a, b, *settings) for a, b in bounds]) for d in designs]
    shared = dask.delayed(source)  # one copy of the module text in the graph, not one per task
    graph = [_tree([dask.delayed(_chunk_tally)(shared, d, sampler, a, b, *settings) for a, b in bounds])
             for d in designs]
    if client is not None:
        return list(client.gather(client.compute(graph)))
    if scheduler is not None and "://" in scheduler:
        return _on_cluster(graph, scheduler)
    return list(dask.compute(*graph, scheduler=scheduler or "threads"))


def _tree(tallies: list[Any], fan_in: int = 8) -> Any:
    """Merge delayed tallies in groups of ``fan_in``, level by level: each merge frees its chunks' tallies early."""
    import dask

    while len(tallies) > 1:
        tallies = [dask.delayed(_merged)(tallies[k:k + fan_in]) for k in range(0, len(tallies), fan_in)]
    return tallies[0]


def _on_cluster(graph: list[Any], address: str, deadline: float = 10.0) -> list[Tally]:
    """The graph on the dask.distributed scheduler at ``address``; one clear error if none answers in time."""
    try:
        from distributed import Client
    except ImportError:
        raise SymjacError("a scheduler address needs dask.distributed: pip install 'symjac[sweep]'") from None
    pool = concurrent.futures.ThreadPoolExecutor(1)
    try:  # a server that accepts but never speaks dask's protocol must not hang the caller
        client = pool.submit(Client, address, timeout="5s").result(timeout=deadline)
    except Exception as error:
        raise SymjacError(f"no dask scheduler answers at {address} ({type(error).__name__})") from None
    finally:
        pool.shutdown(wait=False)
    with client:
        return list(client.gather(client.compute(graph)))


def _dataset(robot: Robot, grid: dict[str, np.ndarray], values: list[dict[str, Any]], attrs: dict[str, Any]) -> Any:
    """The labelled result: one variable per metric value over the swept parameters (a histogram over ``bin`` too)."""
    try:
        import xarray as xr
    except ImportError:
        raise SymjacError("a sweep's result is an xarray Dataset: pip install 'symjac[sweep]'") from None
    shape = tuple(len(v) for v in grid.values())
    names = list(grid)
    variables = {}
    for key in values[0]:
        data = np.array([v[key] for v in values])
        histogram = data.ndim == 2
        variables[key] = ([*names, "bin"] if histogram else names, data.reshape(shape + data.shape[1:]))
    coords: dict[str, Any] = dict(grid)
    if any(key.endswith("_histogram") for key in values[0]):
        coords |= {"bin_low": ("bin", HISTOGRAM_EDGES[:-1]), "bin_high": ("bin", HISTOGRAM_EDGES[1:])}
    return xr.Dataset(variables, coords=coords, attrs={"robot": robot.name, **attrs})
