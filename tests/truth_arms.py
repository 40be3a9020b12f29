"""Arms from published tables that are not in the catalog, as robot files: the truth tests' varied shapes.

Lengths in metres from the makers' DH tables (the Gen3's from its user guide, the OpenManipulator-X's second link as
one length with its angle offset beta), all in standard DH; the TX90 is written in degrees.
"""

from __future__ import annotations

R, P = "revolute", "prismatic"


def dh_file(name: str, rows: list[tuple], parameters: dict[str, float], *, degrees: bool = False,
            tool: tuple | None = None, base: tuple | None = None) -> str:
    """A standard-DH robot file: ``rows`` of (type, alpha, a, d, theta), lengths named in ``parameters``."""
    lines = [f'name = "{name}"', f'description = "{name}, published DH table"', 'convention = "standard"']
    lines += ['angle_unit = "deg"'] * degrees + ["", "[parameters]"] + [f"{k} = {v}" for k, v in parameters.items()]
    for kind, alpha, a, d, theta in rows:
        lines += ["", "[[joints]]", f'type = "{kind}"', f'alpha = "{alpha}"', f'a = "{a}"', f'd = "{d}"',
                  f'theta = "{theta}"']
    for label, transform in (("base", base), ("tool", tool)):
        if transform is not None:
            lines += ["", f"[{label}]", f"xyz = {list(transform[0])}", f"rpy = {list(transform[1])}"]
    return "\n".join(lines) + "\n"


WRIST_6R = [(R, "-pi/2", "a1", "d1", 0), (R, 0, "a2", 0, "-pi/2"), (R, "-pi/2", "a3", 0, 0), (R, "pi/2", 0, "d4", 0),
            (R, "-pi/2", 0, 0, 0), (R, 0, 0, "d6", 0)]
"""The standard DH table shared by the IRB 2400 and the LR Mate 200iD (shoulder offset a1, elbow offset a3)."""

EXPLAINED = {
    "irb2400": dh_file("irb2400", WRIST_6R, {"a1": 0.1, "d1": 0.615, "a2": 0.705, "a3": 0.135, "d4": 0.755,
                                             "d6": 0.085}),
    "lrmate200id": dh_file("lrmate200id", WRIST_6R, {"a1": 0.05, "d1": 0.33, "a2": 0.33, "a3": 0.035, "d4": 0.335,
                                                     "d6": 0.08}),
    "tx90": dh_file("tx90", [(R, -90, "a1", "d1", 0), (R, 0, "a2", 0, -90), (R, 90, 0, "d3", 90),
                             (R, -90, 0, "d4", 0), (R, 90, 0, 0, 0), (R, 0, 0, "d6", 0)],
                    {"a1": 0.05, "d1": 0.478, "a2": 0.425, "d3": 0.05, "d4": 0.425, "d6": 0.1}, degrees=True),
    "gen3": dh_file("gen3", [(R, "pi/2", 0, "-d1", 0), (R, "pi/2", 0, "-d2", "pi"), (R, "pi/2", 0, "-d3", "pi"),
                             (R, "pi/2", 0, "-d4", "pi"), (R, "pi/2", 0, "-d5", "pi"), (R, "pi/2", 0, 0, "pi"),
                             (R, "pi", 0, "-d7", "pi")],
                    {"d1": 0.2848, "d2": 0.0118, "d3": 0.4208, "d4": 0.0128, "d5": 0.3143, "d7": 0.1674},
                    base=([0, 0, 0], ["pi", 0, 0])),
    "cylindrical_rpp": dh_file("cylindrical_rpp", [(R, 0, 0, "d1", 0), (P, "-pi/2", 0, 0, 0), (P, 0, 0, 0, 0)],
                               {"d1": 0.5}),
    "spherical_rrp": dh_file("spherical_rrp", [(R, "-pi/2", 0, "d1", 0), (R, "pi/2", 0, "d2", 0), (P, 0, 0, 0, 0)],
                             {"d1": 0.3, "d2": 0.1}),
    "scara_rrpr": dh_file("scara_rrpr", [(R, 0, "a1", "d1", 0), (R, "pi", "a2", 0, 0), (P, 0, 0, 0, 0),
                                         (R, 0, 0, "d4", 0)], {"a1": 0.325, "a2": 0.275, "d1": 0.4, "d4": 0.1}),
    "tool3r": dh_file("tool3r", [(R, "pi/2", 0, "d1", 0), (R, 0, "a2", 0, 0), (R, 0, "a3", 0, 0)],
                      {"d1": 0.3, "a2": 0.4, "a3": 0.3}, tool=([0.1, 0.05, 0], [0, 0, 0])),
    "open_manipulator_x": dh_file("open_manipulator_x", [(R, "pi/2", 0, "d1", 0), (R, 0, "a2", 0, "-beta"),
                                                         (R, 0, "a3", 0, "beta"), (R, 0, "a4", 0, 0)],
                                  {"d1": 0.077, "a2": 0.1302, "a3": 0.124, "a4": 0.126, "beta": 1.3872}),
}
"""The arms whose every explanation is checked against the numbers (tests/test_explanations_checked.py)."""

FIVE_R = dh_file("five_r", [(R, "pi/2", 0, "d1", 0), (R, 0, "a2", 0, 0), (R, 0, "a3", 0, 0), (R, "pi/2", 0, 0, "pi/2"),
                            (R, 0, 0, "d5", 0)], {"d1": 0.147, "a2": 0.155, "a3": 0.135, "d5": 0.218})
"""A 5R arm: yaw, three pitch joints, a roll about the approach axis (no frame carries its rank in five rows)."""

YPPR_TOOL = dh_file("yppr_tool", [(R, "pi/2", 0, "d1", 0), (R, 0, "a2", 0, 0), (R, "pi/2", 0, 0, "pi/2"),
                                  (R, 0, 0, "a3", 0)], {"d1": 0.3, "a2": 0.4, "a3": 0.3},
                    tool=([0.05, 0, 0.1], [0, 0, 0]))
"""Yaw, pitch, pitch, roll with a tool off the roll axis: one singular set, once found fifteen times."""

ARMS = {**EXPLAINED, "five_r": FIVE_R, "yppr_tool": YPPR_TOOL}
"""Every arm above by name."""
