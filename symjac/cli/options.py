"""The options of each ``symjac`` command, added only to the command given (:data:`symjac.cli.main.COMMANDS`).

Each function takes the command's subparser and its name; heavy modules are imported only inside the function of
the command that needs them. A derived quantity's own options are in its spec (:mod:`symjac.quantities`).
"""

from __future__ import annotations

import argparse

from symjac.cli.args import add_robot_arguments
from symjac.quantities.options import POINT_HELP

__all__ = [
    "codegen_options",
    "convert_options",
    "draw_options",
    "errata_options",
    "no_options",
    "result_options",
    "robot_options",
    "sweep_options",
]


def no_options(sub: argparse.ArgumentParser, name: str) -> None:
    """No options beyond the common ones."""


def errata_options(sub: argparse.ArgumentParser, name: str) -> None:
    """``symjac errata``: the sheet's format."""
    from symjac.teaching.errata import SHEET_FORMATS

    sub.add_argument("--format", dest="sheet_format", choices=SHEET_FORMATS, default="markdown",
                     help="markdown or a standalone LaTeX document (default markdown)")


def codegen_options(sub: argparse.ArgumentParser, name: str) -> None:
    """``symjac codegen``: target, Jacobians (frames, points, rows), strategy, acceleration level, dynamics."""
    from symjac.codegen import BACKENDS, STRATEGIES, TARGETS

    add_robot_arguments(sub)
    sub.add_argument("--target", choices=TARGETS, default="python",
                     help="; ".join(f"{b.name} ({b.summary})" for b in BACKENDS.values()) + "; default python")
    sub.add_argument("--frame", action="append", default=None, metavar="K",
                     help="frame to express the Jacobian in: 0..n, world or tool (repeatable; default 0)")
    sub.add_argument("--point", action="append", default=None, metavar="P",
                     help=f"repeatable: {POINT_HELP}; forward_kinematics always ends at the end of the chain")
    sub.add_argument("--rows", default=None,
                     help="task rows, comma-separated from v_x,v_y,v_z,omega_x,omega_y,omega_z (default all)")
    sub.add_argument("--strategy", choices=STRATEGIES, default="fastest",
                     help="expressions to start from (default: fewest operations after CSE)")
    sub.add_argument("--acceleration", action="store_true",
                     help="also generate hessian, bias_acceleration (Jdot qdot) and manipulability_gradient")
    sub.add_argument("--dynamics", action="store_true",
                     help="also generate inverse_dynamics, mass_matrix, coriolis_matrix, bias_forces, gravity_torques "
                          "and forward_dynamics (the robot needs inertial data on every link)")
    sub.add_argument("--identification", action="store_true",
                     help="also generate regressor and base_regressor (tau = Y pi = Y_b pi_b; the parameters' names "
                          "in order as REGRESSOR_PARAMETERS, BASE_PARAMETERS); implies --dynamics")
    sub.add_argument("--inverse-kinematics", action="store_true",
                     help="also generate inverse_kinematics(pose): every closed-form solution (an arm with a closed "
                          "form) into IK_MAX_SOLUTIONS rows, their count and branches")
    sub.add_argument("--free-joint", type=int, default=None, metavar="K",
                     help="with --inverse-kinematics: the closed form with joint K (1..n) given, a 7-joint arm's "
                          "redundancy parameter; inverse_kinematics then takes its value q_free after the pose")
    sub.add_argument("--name", default=None,
                     help="the module's name: file names, C prefix, C++ namespace (default: the robot's name)")


def robot_options(sub: argparse.ArgumentParser, name: str) -> None:
    """The robot and its URDF chain only."""
    add_robot_arguments(sub)


def convert_options(sub: argparse.ArgumentParser, name: str) -> None:
    """``symjac convert``: the convention to convert to."""
    add_robot_arguments(sub)
    sub.add_argument("--to", choices=("modified", "standard", "poe", "general", "toml"), required=True,
                     help="the convention to convert to (poe: screw axes and home pose; general: from poe only), "
                          "or toml to keep the robot as it is")


def draw_options(sub: argparse.ArgumentParser, name: str) -> None:
    """``symjac draw``: configurations, view, ellipsoids, limits, frames, and a path to animate."""
    add_robot_arguments(sub)
    sub.add_argument("--q", action="append", metavar="Q",
                     help="a configuration q1,...,qn: 30deg, 0.5rad, expressions with pi, numbers in the robot file's "
                          "angle unit (radians unless it says angle_unit = \"deg\"), metres (default: zero, or "
                          "mid-range where a joint's limits exclude zero); repeat it to draw configurations side by "
                          "side, or to give the waypoints of --path; write --q=-1,0 when it starts with a minus")
    sub.add_argument("--view", default=None, metavar="AZIMUTH,ELEVATION",
                     help="the view in degrees (default: --view=-60,25; the = is needed before a minus)")
    sub.add_argument("--ellipsoid", action="append", choices=("velocity", "force"), default=None,
                     help="the velocity or force ellipsoid at the tool point (repeat for both)")
    sub.add_argument("--limits", action="store_true", help="colour each joint by its distance to its limits")
    sub.add_argument("--frames", action=argparse.BooleanOptionalAction, default=None,
                     help="draw every frame labelled {i} (default: up to 8 joints)")
    sub.add_argument("--path", action="store_true",
                     help="animate the arm along straight joint-space lines through the --q waypoints "
                          "(-o FILE.gif or FILE.mp4)")
    sub.add_argument("--path-steps", type=int, default=30, metavar="N",
                     help="with --path: frames per segment between waypoints (default 30)")
    sub.add_argument("--fps", type=int, default=20, help="with --path: frames per second (default 20)")
    sub.add_argument("--ik-pose", default=None, metavar="POSE",
                     help="draw every inverse-kinematics solution reaching this pose of the end of the chain in {0}, "
                          "side by side: x,y,z,roll,pitch,yaw (URDF rpy, radians), x,y,z,w,qx,qy,qz (unit quaternion, "
                          "scalar first), the 4 x 4 matrix row by row (16 or the top 12 numbers), or x,y,z alone "
                          "for an arm that sets no orientation")
    sub.add_argument("--within-limits", action=argparse.BooleanOptionalAction, default=True,
                     help="with --ik-pose: draw only solutions within the joint limits (default); "
                          "--no-within-limits draws all, each outside one titled so")


def sweep_options(sub: argparse.ArgumentParser, name: str) -> None:
    """``symjac sweep``: the parameters swept, the joint samples, the metrics, the Jacobian, where it runs."""
    add_robot_arguments(sub)
    sub.add_argument("--param", action="append", metavar="NAME=LOW:HIGH:COUNT",
                     help="a parameter to sweep: COUNT values from LOW to HIGH, or NAME=V1,V2,...; repeat for a grid")
    sub.add_argument("--samples", default="100000", help="joint configurations per design, e.g. 1e6 (default 1e5)")
    sub.add_argument("--sampling", choices=("sobol", "grid"), default="sobol",
                     help="a scrambled Sobol sequence over the joint limits (default) or a regular grid")
    sub.add_argument("--range", action="append", metavar="NAME=LOW:HIGH",
                     help="sample a coordinate over this interval instead of its joint limits (repeatable; write "
                          "--range=theta2=-1:1 before a minus)")
    sub.add_argument("--metric", action="append", metavar="M1,M2",
                     help="gci, gci_frobenius, manipulability, sigma_min, near_singular, workspace_volume "
                          "(default gci,manipulability,sigma_min,near_singular)")
    sub.add_argument("--frame", default="0", help="the Jacobian's frame (default 0)")
    sub.add_argument("--point", default=None, help=POINT_HELP)
    sub.add_argument("--rows", default=None, help="task rows from v_x,v_y,v_z,omega_x,omega_y,omega_z (default all)")
    sub.add_argument("--seed", type=int, default=0, help="seed of the Sobol scrambling (default 0)")
    sub.add_argument("--scheduler", default=None, metavar="NAME|tcp://HOST:PORT",
                     help="threads (default), processes, synchronous, or a dask.distributed scheduler's address")
    sub.add_argument("--plot", default=None, metavar="FILE", help="also draw each metric over the parameters")


def result_options(sub: argparse.ArgumentParser, name: str) -> None:
    """The options of the commands that print a result as a document (LaTeX, pretty or JSON).

    A quantity's command adds its own after these (:mod:`symjac.cli.quantities`).
    """
    from symjac.printing.document import FORMATS
    from symjac.printing.latex import DIGITS

    add_robot_arguments(sub)
    sub.add_argument("--format", choices=FORMATS, default="latex", help="output format (default: latex)")
    sub.add_argument("--numeric", action="store_true", help="substitute the parameters' numeric defaults")
    sub.add_argument("--standalone", action="store_true", help="with --format latex: a complete LaTeX document")
    if name != "singularities":
        sub.add_argument("--digits", type=int, default=None, metavar="N",
                         help=f"with --numeric (or torques --q): significant digits printed (default {DIGITS})")
    if name == "singularities":
        sub.add_argument("--frame", default=None, help="frame to analyse in (default: the most compact one)")
        sub.add_argument("--point", default=None, help=POINT_HELP)
        sub.add_argument("--rows", default=None,
                         help="task rows, comma-separated from v_x,v_y,v_z,omega_x,omega_y,omega_z "
                              "(default: chosen automatically)")
