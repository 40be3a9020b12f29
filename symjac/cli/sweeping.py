"""``symjac sweep``: dexterity over a parameter grid, written as netCDF, CSV or JSON, with an optional plot."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from pathlib import Path
from typing import Any

from symjac.cli.args import load, parse_frame, parse_point, parse_rows
from symjac.errors import ArgumentError

__all__ = ["RESULT_SUFFIXES", "result_bytes", "sweep_command"]

RESULT_SUFFIXES = (".nc", ".csv", ".json")


def _param(text: str) -> tuple[str, tuple[float, float, int] | list[float]]:
    """``a2=0.3:0.6:16`` (low:high:count) or ``a2=0.3,0.45,0.6`` (values)."""
    name, equals, spec = text.partition("=")
    if not equals or not name.strip():
        raise ArgumentError(f"--param must be NAME=LOW:HIGH:COUNT or NAME=V1,V2,..., got {text!r}")
    try:
        if ":" in spec:
            low, high, count = spec.split(":")
            if not count.strip().isdigit():
                raise ValueError(count)
            return name.strip(), (float(low), float(high), int(count))
        return name.strip(), [float(v) for v in spec.split(",")]
    except ValueError:
        raise ArgumentError(f"--param {text!r}: give NAME=LOW:HIGH:COUNT (COUNT a whole number) or NAME=V1,V2,... "
                            "with numbers") from None


def _joint_range(text: str) -> tuple[str, tuple[float, float]]:
    """``theta2=-1:1``: the interval a coordinate is sampled over instead of its limits."""
    name, equals, spec = text.partition("=")
    try:
        low, high = (float(v) for v in spec.split(":"))
    except ValueError:
        raise ArgumentError(f"--range must be NAME=LOW:HIGH with numbers, got {text!r}") from None
    if not equals or not name.strip():
        raise ArgumentError(f"--range must be NAME=LOW:HIGH, got {text!r}")
    return name.strip(), (low, high)


def _once(pairs: list[tuple[str, Any]], option: str) -> dict[str, Any]:
    """``pairs`` as a mapping; a name given twice is an error, not a silent override."""
    names = [name for name, _ in pairs]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise ArgumentError(f"{option} names {twice[0]} twice")
    return dict(pairs)


def _samples(text: str) -> int:
    try:
        value = float(text)
    except ValueError:
        raise ArgumentError(f"--samples must be a number such as 1e6, got {text!r}") from None
    if not (math.isfinite(value) and value >= 1 and value == int(value)):
        raise ArgumentError(f"--samples must be a whole number >= 1, got {text!r}")
    return int(value)


def result_bytes(result: Any, suffix: str) -> bytes:
    """The sweep's Dataset as a netCDF (SciPy's writer), CSV (one row per design, scalar metrics) or JSON file."""
    if suffix == ".nc":
        return bytes(result.to_netcdf(engine="scipy"))
    if suffix == ".csv":  # one row per design: the scalar metrics (the distributions are in .nc and .json)
        scalars = result[[name for name in result.data_vars if "bin" not in result[name].dims]]
        return scalars.drop_vars([c for c in scalars.coords if c.startswith("bin_")]).to_dataframe().to_csv().encode()
    text = json.dumps(_no_nan(result.to_dict(data="list")), indent=1, sort_keys=True, default=float, allow_nan=False)
    return (text + "\n").encode("utf-8")


def _no_nan(value: Any) -> Any:
    """JSON has no NaN: a metric without a value (NaN) becomes null."""
    if isinstance(value, dict):
        return {key: _no_nan(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_no_nan(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def sweep_command(args: argparse.Namespace) -> str:
    """``sweep``: run :func:`symjac.sweep`, write the result (and ``--plot``) only when it is complete."""
    from symjac.files import write_files
    from symjac.sweeps import METRICS, sweep

    if args.output in (None, "-"):
        raise ArgumentError(f"sweep writes a file: give -o FILE with a suffix of {', '.join(RESULT_SUFFIXES)}")
    suffix = Path(args.output).suffix.lower()
    if suffix not in RESULT_SUFFIXES:
        raise ArgumentError(f"-o {args.output}: unknown suffix {suffix or '(none)'}; use {', '.join(RESULT_SUFFIXES)}")
    if args.plot is not None and Path(args.plot).suffix.lower() not in (".svg", ".png", ".pdf"):
        raise ArgumentError(f"--plot {args.plot}: use a .svg, .png or .pdf file")
    if not args.param:
        raise ArgumentError("give at least one --param NAME=LOW:HIGH:COUNT to sweep")
    params = _once([_param(text) for text in args.param], "--param")
    if args.plot is not None and len(params) > 2:
        raise ArgumentError(f"--plot draws one or two swept parameters, not {len(params)}")
    metrics = [m.strip() for text in (args.metric or ["gci,manipulability,sigma_min,near_singular"])
               for m in text.split(",")]
    unknown = [m for m in metrics if m not in METRICS]
    if unknown:
        raise ArgumentError(f"--metric: unknown metric {unknown[0]!r}; choose from {', '.join(METRICS)}")
    robot = load(args)
    ranges = _once([_joint_range(text) for text in args.range or []], "--range")
    options: dict[str, Any] = {
        "ranges": ranges or None, "samples": _samples(args.samples), "metrics": metrics, "sampling": args.sampling,
        "frame": parse_frame(args.frame), "point": parse_point(args.point, robot), "seed": args.seed,
        "rows": None if args.rows is None else parse_rows(args.rows), "scheduler": args.scheduler}
    result = _with_progress(lambda: sweep(robot, params, **options))
    files: dict[Path, str | bytes] = {Path(args.output): result_bytes(result, suffix)}
    if args.plot is not None:
        from symjac.drawing.animation import figure_bytes
        from symjac.sweeps.plot import sweep_figure

        files[Path(args.plot)] = figure_bytes(sweep_figure(result), Path(args.plot).suffix.lower())
    write_files(files)  # both or neither
    args.output = None
    return ""


def _with_progress(run: Any) -> Any:
    """``run()`` with dask's progress bar on stderr when it is a terminal (local schedulers only).

    Ctrl-C stops the sweep: one line says how many of its tasks had finished (nothing is written), then the
    command ends as any interrupted command does.
    """
    try:
        from dask.callbacks import Callback
        from dask.diagnostics import ProgressBar
    except ImportError:
        return run()

    class Count(Callback):  # type: ignore[misc]
        done = total = 0

        def _start_state(self, graph: Any, state: Any) -> None:
            Count.total += len(graph)

        def _posttask(self, *arguments: Any) -> None:
            Count.done += 1

    bar = ProgressBar(out=sys.stderr) if sys.stderr.isatty() else contextlib.nullcontext()
    try:
        with Count(), bar:
            return run()
    except KeyboardInterrupt:
        print(f"symjac: sweep stopped after {Count.done} of {Count.total} tasks; nothing written", file=sys.stderr)
        raise
