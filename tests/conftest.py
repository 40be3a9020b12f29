"""Test configuration: hypothesis runs the same examples on every run unless asked to explore.

Symbolic examples vary a lot in cost (a chain whose every twist is 0.3 rad is far larger than a real arm), so a
random draw can double the suite's time, and a failure's shrinking can run for minutes. The default profile is
derandomized: reproducible examples and times. ``HYPOTHESIS_PROFILE=explore`` draws new random examples (run it
locally now and then; it found the regressions tested in test_urdf, test_codegen and test_representations).
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

settings.register_profile("symjac", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", derandomize=False, deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "symjac"))


# A two-joint arm whose flange carries two fingers: two leaves, so a URDF command must be told --tip-link.
GRIPPER_URDF = """<?xml version="1.0"?>
<robot name="gripper_arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="flange"/>
  <link name="finger_a"/><link name="finger_b"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.4 0 0" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2"/></joint>
  <joint name="mount" type="fixed"><parent link="l2"/><child link="flange"/><origin xyz="0.3 0 0"/></joint>
  <joint name="fa" type="fixed"><parent link="flange"/><child link="finger_a"/><origin xyz="0 0.02 0.05"/></joint>
  <joint name="fb" type="fixed"><parent link="flange"/><child link="finger_b"/><origin xyz="0 -0.02 0.05"/></joint>
</robot>
"""


@pytest.fixture
def gripper(tmp_path) -> str:
    """:data:`GRIPPER_URDF` written to a file; its path."""
    path = tmp_path / "arm.urdf"
    path.write_text(GRIPPER_URDF, encoding="utf-8")
    return str(path)
