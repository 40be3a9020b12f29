"""Design sweeps: dexterity over joint samples times design parameters, chunked, on dask (:func:`sweep`)."""

from symjac.sweeps.metrics import HISTOGRAM_EDGES, METRICS, Tally
from symjac.sweeps.run import sweep
from symjac.sweeps.sampling import JointSampler, joint_ranges, parameter_grid

__all__ = ["HISTOGRAM_EDGES", "METRICS", "JointSampler", "Tally", "joint_ranges", "parameter_grid", "sweep"]
