"""Hypothesis strategies: random serial chains as robot mappings (all conventions, prismatic joints, 1-10 joints)."""

from __future__ import annotations

from typing import Any

from hypothesis import strategies as st

from symjac import Robot, robot_from_mapping

# Twists: the special angles real arms use (parallel, perpendicular, anti-parallel) and a generic one.
TWISTS = st.sampled_from([0, "pi/2", "-pi/2", "pi", 0.3, "-pi/3"])
LENGTHS = st.sampled_from([0, 0, 0.25, -0.4, "L", "L/2 + 0.1"])
OFFSETS = st.sampled_from([0, 0, "pi/2", -0.2])
SMALL = st.sampled_from([0, 0.1, -0.3, "L"])
ANGLES = st.sampled_from([0, "pi/2", -0.7, 1.1])


# Past 7 joints only the special twists: a generic twist makes the symbolic result itself grow about 3x per joint
# (benchmarks/growth.py), which would turn the property tests into a benchmark.
SPECIAL_TWISTS = st.sampled_from([0, "pi/2", "-pi/2", "pi"])
GENERIC_TWIST_JOINTS = 7


@st.composite
def joint_rows(draw: st.DrawFn) -> dict[str, Any]:
    return {
        "type": draw(st.sampled_from(["revolute", "revolute", "prismatic"])),
        "alpha": draw(TWISTS),
        "a": draw(LENGTHS),
        "d": draw(LENGTHS),
        "theta": draw(OFFSETS),
    }


@st.composite
def fixed_transforms(draw: st.DrawFn) -> dict[str, Any]:
    return {"xyz": [draw(SMALL) for _ in range(3)], "rpy": [draw(ANGLES) for _ in range(3)]}


@st.composite
def robots(draw: st.DrawFn, max_joints: int = 10) -> Robot:
    """A random, valid robot with a parameter L = 0.35 used by some fields."""
    data: dict[str, Any] = {
        "name": "random",
        "convention": draw(st.sampled_from(["standard", "modified"])),
        "parameters": {"L": 0.35},
        "joints": draw(st.lists(joint_rows(), min_size=1, max_size=max_joints)),
    }
    if len(data["joints"]) > GENERIC_TWIST_JOINTS:
        data["joints"] = [{**row, "alpha": draw(SPECIAL_TWISTS)} for row in data["joints"]]
    if draw(st.booleans()):
        data["base"] = draw(fixed_transforms())
    if draw(st.booleans()):
        data["tool"] = draw(fixed_transforms())
    return robot_from_mapping(data)


AXES = st.sampled_from([[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, -1, 0], [0, 0.6, 0.8], [1, 1, 0], [-2, 1, 2]])
RPY = st.sampled_from([0, "pi/2", "-pi/2", "pi", 0.3])


SPECIAL_RPY = st.sampled_from([0, "pi/2", "-pi/2", "pi", "pi/4"])


@st.composite
def general_joints(draw: st.DrawFn, rpy: st.SearchStrategy[Any] = RPY) -> dict[str, Any]:
    return {
        "type": draw(st.sampled_from(["revolute", "revolute", "prismatic"])),
        "xyz": [draw(SMALL) for _ in range(3)],
        "rpy": [draw(rpy) for _ in range(3)],
        "axis": draw(AXES),
    }


@st.composite
def general_robots(draw: st.DrawFn, max_joints: int = 7, rpy: st.SearchStrategy[Any] = RPY) -> Robot:
    """A random general (URDF-style origin and axis) chain, with a parameter L = 0.35 used by some fields.

    ``rpy`` draws the origin angles (``SPECIAL_RPY``: only multiples of pi/4, for exact DH extraction).
    """
    data: dict[str, Any] = {
        "name": "random_general",
        "convention": "general",
        "parameters": {"L": 0.35},
        "joints": draw(st.lists(general_joints(rpy), min_size=1, max_size=max_joints)),
    }
    if draw(st.booleans()):
        data["base"] = draw(fixed_transforms())
    if draw(st.booleans()):
        data["tool"] = draw(fixed_transforms())
    return robot_from_mapping(data)
