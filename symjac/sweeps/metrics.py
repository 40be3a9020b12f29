r"""The dexterity of one design over its joint samples, reduced chunk by chunk (:class:`Tally`).

For each configuration, from the singular values :math:`\sigma_1 \ge \dots \ge \sigma_m` of the analysed rows of
the Jacobian (an m x n matrix):

* the inverse condition number in the 2-norm, :math:`1/\kappa = \sigma_m / \sigma_1` (0 at a singularity); its
  workspace mean is Gosselin and Angeles' global conditioning index (``gci``);
* for a square J, the inverse of the normalised Frobenius condition number,
  :math:`1/\kappa_F = n / (\|J\|_F \|J^{-1}\|_F) = n / \sqrt{\sum \sigma_k^2 \sum \sigma_k^{-2}}`
  (``gci_frobenius``, its mean);
* the manipulability :math:`w = \prod \sigma_k` (:math:`\sqrt{\det J J^T}` for a wide or square J): mean,
  minimum, maximum, standard deviation, and its distribution (counts over the bins :data:`HISTOGRAM_EDGES`, a
  quarter decade each);
* the smallest singular value :math:`\sigma_m` (mean, minimum, distribution over the same bins);
* whether :math:`1/\kappa` is below ``near`` (the fraction of such samples: ``near_singular``). By the
  Eckart-Young theorem :math:`\sigma_m` is the distance (in the 2-norm) from J to the nearest singular matrix, so
  :math:`1/\kappa` is that distance relative to the size of J: these samples lie within a relative distance
  ``near`` of a singular Jacobian;
* the voxel (edge ``voxel``) holding the tool point: the reachable workspace volume is the number of distinct voxels
  times the voxel's volume.

A tally holds sums, extremes and the sorted voxel keys (8 bytes a voxel), so tallies of chunks combine exactly (up
to the rounding of sums) in any order.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from symjac.errors import ArgumentError

__all__ = ["HISTOGRAM_EDGES", "METRICS", "Tally"]

_BITS = 21
"""Bits per axis of a voxel's key: voxel indices from -2**20 to 2**20 - 1 (a million voxels along each axis)."""

HISTOGRAM_EDGES = np.concatenate([[0.0], 10.0 ** np.arange(-12.0, 2.01, 0.25), [np.inf]])
"""Bin edges of the distributions: [0, 1e-12), then quarter decades up to 100, then [100, inf)."""

METRICS = ("gci", "gci_frobenius", "manipulability", "sigma_min", "near_singular", "workspace_volume")
"""The metric names a sweep accepts."""


@dataclass
class Tally:
    """Running sums and extremes of one design's samples; :meth:`add` a chunk, :meth:`merge` another tally."""

    count: int = 0
    inverse_kappa: float = 0.0
    inverse_kappa_f: float = 0.0
    w_mean: float = 0.0
    w_spread: float = 0.0  # the sum of squared deviations from the mean (merged by Chan's formula)
    w_min: float = np.inf
    w_max: float = -np.inf
    sigma_sum: float = 0.0
    sigma_min: float = np.inf
    near: int = 0
    w_histogram: np.ndarray = field(default_factory=lambda: np.zeros(len(HISTOGRAM_EDGES) - 1, dtype=np.int64))
    sigma_histogram: np.ndarray = field(default_factory=lambda: np.zeros(len(HISTOGRAM_EDGES) - 1, dtype=np.int64))
    voxels: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64))  # sorted keys, see _keys

    def add(self, J: np.ndarray, points: np.ndarray | None, near: float, voxel: float, sigma: bool = True) -> Tally:
        r"""Take in a chunk: Jacobians ``J`` (k, m, n) and tool points (k, 3) or None.

        With ``sigma=False`` no singular values are taken: the manipulability (the product of the singular values)
        comes from a determinant (LU): :math:`|\det J|`, :math:`\sqrt{\det J J^T}` for a wide J,
        :math:`\sqrt{\det J^T J}` for a tall one; the Frobenius conditioning of a square J comes from its inverse;
        the metrics that need :math:`\sigma_m` are left out.
        """
        if not sigma:
            rows, columns = J.shape[1:]
            square = rows == columns
            Jt = np.swapaxes(J, 1, 2)
            gram = J if square else J @ Jt if rows < columns else Jt @ J  # the Gram matrix of the shorter side
            determinant = np.linalg.det(gram)
            self._add_manipulability(np.abs(determinant) if square else np.sqrt(np.maximum(determinant, 0.0)))
            if square:  # 1/kappa_F = n |det J| / (||J||_F ||adj J||_F) = n / (||J||_F ||J^-1||_F), by LU
                regular = determinant != 0
                inverse = np.linalg.inv(np.where(regular[:, None, None], J, np.eye(J.shape[1])))
                norms = np.linalg.norm(J, axis=(1, 2)) * np.linalg.norm(inverse, axis=(1, 2))
                self.inverse_kappa_f += float(np.sum(np.where(regular, J.shape[2] / norms, 0.0)))
            self._add_points(points, voxel)
            return self
        values = np.linalg.svd(J, compute_uv=False)  # (k, min(m, n)), largest first
        largest, smallest = values[:, 0], values[:, -1]
        with np.errstate(divide="ignore", invalid="ignore"):
            inverse = np.where(largest > 0, smallest / np.where(largest > 0, largest, 1.0), 0.0)
            if J.shape[1] == J.shape[2]:
                squares, inverses = np.sum(values**2, axis=1), np.sum(1.0 / values**2, axis=1)
                frobenius = np.where(smallest > 0, J.shape[2] / np.sqrt(squares * inverses), 0.0)
                self.inverse_kappa_f += float(np.sum(frobenius))
        self._add_manipulability(np.prod(values, axis=1))
        self.inverse_kappa += float(np.sum(inverse))
        self.sigma_sum += float(np.sum(smallest))
        self.sigma_min = min(self.sigma_min, float(np.min(smallest)))
        self.near += int(np.count_nonzero(inverse < near))
        self.sigma_histogram = self.sigma_histogram + np.histogram(smallest, HISTOGRAM_EDGES)[0]
        self._add_points(points, voxel)
        return self

    def _add_manipulability(self, w: np.ndarray) -> None:
        mean = float(np.mean(w))
        self.count, self.w_mean, self.w_spread = _pooled(self.count, self.w_mean, self.w_spread, len(w), mean,
                                                         float(np.sum((w - mean) ** 2)))
        self.w_min = min(self.w_min, float(np.min(w)))
        self.w_max = max(self.w_max, float(np.max(w)))
        self.w_histogram = self.w_histogram + np.histogram(w, HISTOGRAM_EDGES)[0]

    def _add_points(self, points: np.ndarray | None, voxel: float) -> None:
        if points is not None:
            self.voxels = np.union1d(self.voxels, _keys(points, voxel))

    def merge(self, other: Tally) -> Tally:
        """The tally of both chunks: ``self`` and ``other`` together (a new tally)."""
        count, mean, spread = _pooled(self.count, self.w_mean, self.w_spread, other.count, other.w_mean,
                                      other.w_spread)
        return Tally(count, self.inverse_kappa + other.inverse_kappa,
                     self.inverse_kappa_f + other.inverse_kappa_f, mean, spread,
                     min(self.w_min, other.w_min), max(self.w_max, other.w_max),
                     self.sigma_sum + other.sigma_sum, min(self.sigma_min, other.sigma_min), self.near + other.near,
                     self.w_histogram + other.w_histogram, self.sigma_histogram + other.sigma_histogram,
                     np.union1d(self.voxels, other.voxels))

    def values(self, metrics: tuple[str, ...], square: bool, voxel: float) -> dict[str, float | np.ndarray]:
        """The requested metrics, named as in the result (``manipulability`` gives five values, one a histogram)."""
        n = self.count
        out: dict[str, float | np.ndarray] = {}
        for metric in metrics:
            if metric == "gci":
                out["gci"] = self.inverse_kappa / n
            elif metric == "gci_frobenius":
                out["gci_frobenius"] = self.inverse_kappa_f / n if square else np.nan
            elif metric == "manipulability":
                out |= {"manipulability_mean": self.w_mean, "manipulability_min": self.w_min,
                        "manipulability_max": self.w_max, "manipulability_std": float(np.sqrt(self.w_spread / n)),
                        "manipulability_histogram": self.w_histogram}
            elif metric == "sigma_min":
                out |= {"sigma_min_mean": self.sigma_sum / n, "sigma_min_min": self.sigma_min,
                        "sigma_min_histogram": self.sigma_histogram}
            elif metric == "near_singular":
                out["near_singular"] = self.near / n
            elif metric == "workspace_volume":
                out["workspace_volume"] = len(self.voxels) * voxel**3
        return out


def _pooled(n_a: int, mean_a: float, spread_a: float, n_b: int, mean_b: float,
            spread_b: float) -> tuple[int, float, float]:
    """Count, mean and sum of squared deviations of two groups together (Chan, Golub and LeVeque)."""
    n = n_a + n_b
    if n == 0:
        return 0, 0.0, 0.0
    delta = mean_b - mean_a
    return n, mean_a + delta * n_b / n, spread_a + spread_b + delta * delta * n_a * n_b / n


def _keys(points: np.ndarray, voxel: float) -> np.ndarray:
    """The sorted distinct voxels holding ``points``, each packed into one int64 (21 bits per axis)."""
    cells = np.floor(points / voxel).astype(np.int64) + (1 << (_BITS - 1))
    if np.any(cells < 0) or np.any(cells >= 1 << _BITS):
        raise ArgumentError(f"the workspace spans more than 2**{_BITS} voxels of {voxel} along an axis: give a "
                            "larger voxel")
    return np.unique((cells[:, 0] << (2 * _BITS)) | (cells[:, 1] << _BITS) | cells[:, 2])
