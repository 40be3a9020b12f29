"""Reading URDF files (kept for compatibility): the reader lives in :mod:`symjac.model.readers.urdf`.

``robot_from_urdf`` and :data:`MAX_URDF_BYTES` are re-exported from there; the chain between two links, fixed joints
and mimic joints are the shared kinematic tree's (:mod:`symjac.model.readers.tree`).
"""

from __future__ import annotations

from symjac.model.readers.urdf import MAX_URDF_BYTES, robot_from_urdf

__all__ = ["MAX_URDF_BYTES", "robot_from_urdf"]
