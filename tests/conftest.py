"""Test configuration: hypothesis runs the same examples on every run unless asked to explore.

Symbolic examples vary a lot in cost (a chain whose every twist is 0.3 rad is far larger than a real arm), so a
random draw can double the suite's time, and a failure's shrinking can run for minutes. The default profile is
derandomized: reproducible examples and times. ``HYPOTHESIS_PROFILE=explore`` draws new random examples (run it
locally now and then; it found the regressions tested in test_urdf, test_codegen and test_representations).
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("symjac", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", derandomize=False, deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "symjac"))
