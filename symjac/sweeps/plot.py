"""A sweep's result as a picture: each metric as a curve over one swept parameter, or a heat map over two."""

from __future__ import annotations

from typing import Any

from symjac.drawing.figure import matplotlib_figure
from symjac.errors import ArgumentError

__all__ = ["sweep_figure"]


def sweep_figure(result: Any) -> Any:
    """One panel per metric of ``result`` (an :func:`~symjac.sweeps.run.sweep` Dataset) over its parameters."""
    names = [name for name in result.dims if name != "bin"]  # the swept parameters
    if len(names) not in (1, 2):
        raise ArgumentError(f"a plot shows one or two swept parameters, this sweep has {len(names)}: "
                            f"{', '.join(names)}")
    variables = [name for name in result.data_vars if "bin" not in result[name].dims]  # not the distributions
    columns = min(3, len(variables))
    rows = -(-len(variables) // columns)
    figure = matplotlib_figure(figsize=(4.2 * columns, 3.4 * rows), layout="constrained")
    for index, variable in enumerate(variables):
        axes = figure.add_subplot(rows, columns, index + 1)
        data = result[variable]
        if len(names) == 1:
            axes.plot(result[names[0]].values, data.values, marker="o", markersize=3)
            axes.set_xlabel(names[0])
            axes.set_ylabel(variable)
        else:
            image = axes.pcolormesh(result[names[1]].values, result[names[0]].values, data.values, shading="nearest")
            figure.colorbar(image, ax=axes, label=variable)
            axes.set_xlabel(names[1])
            axes.set_ylabel(names[0])
        axes.set_title(variable, fontsize=9)
    figure.suptitle(f"{result.attrs.get('robot', '')}: {result.attrs.get('samples', '')} samples per design")
    return figure
