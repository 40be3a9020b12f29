"""Derivation speed: the same robot from its URDF file (general chain) and from the catalog's DH table.

Run: ``python benchmarks/urdf_vs_dh.py``. For each pair, every cache is cleared, then the same quantities are
derived from both: the simplified Jacobian in frame {0} at the wrist (the origin of frame {n}) and the forward
kinematics from frame {0} to frame {n}; the best of five cold runs is reported, with the ratio URDF / DH (the goal:
within 1.5). Like with like matters: the UR5 URDF ends in a tool link (``ee_link``) that the catalog's DH UR5 does
not have, and a Jacobian at that tool point costs about 1.5x one at the wrist.
"""

from __future__ import annotations

import time

from symjac import clear_caches, forward_kinematics, jacobian, load_robot

PAIRS = [("panda", "panda.urdf", "panda_link8"), ("ur5", "ur5.urdf", None)]


def cold(robot) -> float:
    """Best of five cold derivations (all caches cleared) of the wrist Jacobian and the forward kinematics to {n}."""
    best = float("inf")
    for _ in range(5):
        clear_caches()
        start = time.perf_counter()
        jacobian(robot, frame=0, point="wrist")
        forward_kinematics(robot, 0, robot.n_joints)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    """Print the timings and ratios."""
    for dh_name, urdf_name, tip in PAIRS:
        dh, urdf = load_robot(dh_name), load_robot(urdf_name, tip_link=tip)
        t_dh, t_urdf = cold(dh), cold(urdf)
        print(f"{dh_name:6s} DH {t_dh:6.2f} s   URDF {t_urdf:6.2f} s   ratio {t_urdf / t_dh:4.2f}")


if __name__ == "__main__":
    main()
