"""symjac: symbolic kinematics and Jacobians of serial robot arms, printed in textbook form.

The public API, in pipeline order: load a robot (:func:`load_robot`, :func:`robot_from_mapping`), derive its
kinematics (:func:`chain_of`, :func:`forward_kinematics`) and Jacobians (:func:`jacobian`, by four methods; the
iterations themselves with :func:`velocity_propagation` and :func:`force_propagation`), statics
(:func:`joint_torques`, :func:`wrench_transform`, :func:`twist_transform`), and print them (:func:`latex`).
"""

from symjac.chain import Chain, Frame, chain_of, forward_kinematics
from symjac.errors import ExpressionError, FrameError, RobotFileError, SymjacError, UnknownRobotError
from symjac.io import catalog, load_robot, robot_from_toml, robot_to_toml
from symjac.jacobian import METHODS, change_frame, clear_caches, jacobian, jacobian_of, shift_point
from symjac.model import (
    Convention,
    FixedTransform,
    Joint,
    JointType,
    Parameter,
    Robot,
    robot_from_mapping,
    robot_to_mapping,
)
from symjac.printing import latex, pretty
from symjac.propagation import (
    ForcePropagation,
    VelocityPropagation,
    force_propagation,
    joint_rates,
    velocity_propagation,
    wrench_symbols,
)
from symjac.simplify import AngleBasis, is_identity, simplify_expr, simplify_matrix
from symjac.statics import evaluate_at, joint_torques, wrench_between
from symjac.transforms import twist_transform, wrench_transform

__version__ = "0.1.0"

__all__ = [
    "METHODS",
    "AngleBasis",
    "Chain",
    "Convention",
    "ExpressionError",
    "FixedTransform",
    "ForcePropagation",
    "Frame",
    "FrameError",
    "Joint",
    "JointType",
    "Parameter",
    "Robot",
    "RobotFileError",
    "SymjacError",
    "UnknownRobotError",
    "VelocityPropagation",
    "__version__",
    "catalog",
    "chain_of",
    "change_frame",
    "clear_caches",
    "evaluate_at",
    "force_propagation",
    "forward_kinematics",
    "is_identity",
    "jacobian",
    "jacobian_of",
    "joint_rates",
    "joint_torques",
    "latex",
    "load_robot",
    "pretty",
    "robot_from_mapping",
    "robot_from_toml",
    "robot_to_mapping",
    "robot_to_toml",
    "shift_point",
    "simplify_expr",
    "simplify_matrix",
    "twist_transform",
    "velocity_propagation",
    "wrench_between",
    "wrench_symbols",
    "wrench_transform",
]
