"""Where example-robot-data (PyPI, the ``compare`` extra) keeps its robot folders, for the tests that read them."""

from __future__ import annotations

from importlib import metadata
from pathlib import Path

import pytest


def example_robots() -> Path:
    """The ``robots`` folder of the installed example-robot-data; the calling test module is skipped without it."""
    try:
        files = metadata.distribution("example-robot-data").files or []
    except metadata.PackageNotFoundError:
        files = []
    marker = next((f for f in files if str(f).endswith("share/example-robot-data/package.xml")), None)
    if marker is None:
        pytest.skip("example-robot-data is not installed (pip install example-robot-data, or the [compare] extra)",
                    allow_module_level=True)
    return Path(marker.locate()).parent / "robots"
