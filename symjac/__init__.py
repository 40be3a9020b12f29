"""symjac: symbolic kinematics and Jacobians of serial robot arms, printed in textbook form.

The public API, in pipeline order: load a robot (:func:`load_robot`, :func:`robot_from_mapping`), derive its
kinematics (:func:`chain_of`, :func:`forward_kinematics`) and Jacobians (:func:`jacobian`, by four methods; the
iterations themselves with :func:`velocity_propagation` and :func:`force_propagation`), the acceleration level
(:func:`hessian`, :func:`jacobian_derivative`, :func:`bias_acceleration`, :func:`acceleration_propagation`,
:func:`manipulability_gradient`, :func:`log_det_gradient`, :func:`representation_jacobian_derivative`), statics
(:func:`joint_torques`, :func:`wrench_transform`, :func:`twist_transform`), screw theory (:func:`space_jacobian`,
:func:`body_jacobian`, :func:`screw_exponential`, :func:`exponential_product`, :func:`adjoint`), singular configurations
(:func:`singularities`, :func:`determinant`, :func:`jacobian_spaces`), joint rates (:func:`inverse_rates`,
:func:`damped_least_squares`), representation Jacobians (:func:`representation_jacobian`); print them
(:func:`latex`) and generate fast numeric modules from them (:func:`generate`, :func:`write_module`).

Every name is imported on first use (PEP 562), so ``import symjac`` costs nothing until a name is asked for and
``symjac --version`` does not load SymPy; ``from symjac import jacobian``, ``symjac.jacobian`` and ``dir(symjac)``
work as if everything had been imported up front.
"""

import os as _os
from importlib import import_module as _import_module
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

# SymPy keeps 1000 results in its cache unless told otherwise, and reads the size once, when it is first imported.
# Deriving a long chain needs more: with 1000 a planar 30R Jacobian thrashed the cache (90 s instead of 7 s). A size
# the user has set wins; so does an earlier import of SymPy. Set here, before any submodule can import SymPy.
_os.environ.setdefault("SYMPY_CACHE_SIZE", "10000")

from symjac._version import __version__

_MODULES: dict[str, tuple[str, ...]] = {
    "symjac.analysis.inverse_rates": ("damped_least_squares", "inverse_rates", "rates_along_path"),
    "symjac.analysis.manipulability": ("BarrierTerm", "LogDetGradient", "ManipulabilityGradient", "log_det_gradient",
        "manipulability_gradient"),
    "symjac.analysis.representations": ("REPRESENTATIONS", "EulerConvention", "RepresentationJacobian",
        "RepresentationJacobianDerivative", "coordinate_rates", "extract", "rate_matrix", "representation_jacobian",
        "representation_jacobian_at", "representation_jacobian_derivative", "representation_jacobian_derivative_at",
        "rotation_from"),
    "symjac.analysis.singularity.determinant": ("Determinant", "determinant"),
    "symjac.analysis.singularity.singularities": ("LimitStatus", "SingularFactor", "SingularityReport",
        "singularities"),
    "symjac.analysis.spaces": ("JacobianSpaces", "SymbolicSpaces", "jacobian_spaces", "symbolic_spaces", "task_rows"),
    "symjac.codegen": ("JacobianRequest", "generate", "write_module"),
    "symjac.drawing.animation": ("animate", "joint_path"),
    "symjac.drawing.figure": ("ArmDrawing", "draw"),
    "symjac.drawing.geometry": ("ArmPose", "Ellipsoid", "arm_pose", "ellipsoid"),
    "symjac.errors": ("ArgumentError", "CodegenError", "ConversionError", "ExpressionError", "FrameError",
        "RepresentationError", "ResultTooLargeError", "RobotFileError", "SymjacError", "UnknownRobotError"),
    "symjac.kinematics.acceleration": ("DERIVATIVE_METHODS", "bias_acceleration", "hessian", "hessian_slice",
        "jacobian_derivative"),
    "symjac.kinematics.acceleration_propagation": ("AccelerationPropagation", "AccelerationStep",
        "acceleration_propagation", "joint_accelerations"),
    "symjac.kinematics.chain": ("Chain", "Frame", "as_chain", "chain_of", "clear_caches", "forward_kinematics"),
    "symjac.kinematics.jacobian": ("METHODS", "ROW_NAMES", "change_frame", "jacobian", "jacobian_of",
        "rows_from_names", "shift_point"),
    "symjac.kinematics.numeric": ("evaluate_at", "numeric_jacobian"),
    "symjac.kinematics.screws": ("SCREW_ROWS", "body_jacobian", "exponential_product", "screw_exponential",
        "space_jacobian"),
    "symjac.kinematics.propagation": ("ForcePropagation", "VelocityPropagation", "force_propagation",
        "joint_rate_symbols", "velocity_propagation", "wrench_symbols"),
    "symjac.kinematics.statics": ("joint_torques", "wrench_between"),
    "symjac.model.io": ("catalog", "load_robot", "robot_from_toml", "robot_to_toml", "urdf_catalog"),
    "symjac.sweeps.run": ("sweep",),
    "symjac.model.robot": ("Convention", "FixedTransform", "Joint", "JointType", "Parameter", "Robot"),
    "symjac.model.robot_file": ("robot_from_mapping", "robot_to_mapping"),
    "symjac.model.urdf": ("robot_from_urdf",),
    "symjac.printing": ("latex", "pretty"),
    "symjac.symbolic.angles": ("AngleBasis",),
    "symjac.symbolic.simplify": ("is_identity", "simplify_expr", "simplify_matrix"),
    "symjac.symbolic.transforms": ("adjoint", "twist_transform", "wrench_transform"),
}
"""Each module of the public API and the names :mod:`symjac` re-exports from it."""

_HOME = {name: module for module, names in _MODULES.items() for name in names}

__all__ = [
    "DERIVATIVE_METHODS",
    "METHODS",
    "REPRESENTATIONS",
    "ROW_NAMES",
    "SCREW_ROWS",
    "AccelerationPropagation",
    "AccelerationStep",
    "AngleBasis",
    "ArgumentError",
    "ArmDrawing",
    "ArmPose",
    "BarrierTerm",
    "Chain",
    "CodegenError",
    "Convention",
    "ConversionError",
    "Determinant",
    "Ellipsoid",
    "EulerConvention",
    "ExpressionError",
    "FixedTransform",
    "ForcePropagation",
    "Frame",
    "FrameError",
    "JacobianRequest",
    "JacobianSpaces",
    "Joint",
    "JointType",
    "LimitStatus",
    "LogDetGradient",
    "ManipulabilityGradient",
    "Parameter",
    "RepresentationError",
    "RepresentationJacobian",
    "RepresentationJacobianDerivative",
    "ResultTooLargeError",
    "Robot",
    "RobotFileError",
    "SingularFactor",
    "SingularityReport",
    "SymbolicSpaces",
    "SymjacError",
    "UnknownRobotError",
    "VelocityPropagation",
    "__version__",
    "acceleration_propagation",
    "adjoint",
    "animate",
    "arm_pose",
    "as_chain",
    "bias_acceleration",
    "body_jacobian",
    "catalog",
    "chain_of",
    "change_frame",
    "clear_caches",
    "coordinate_rates",
    "damped_least_squares",
    "determinant",
    "draw",
    "ellipsoid",
    "evaluate_at",
    "exponential_product",
    "extract",
    "force_propagation",
    "forward_kinematics",
    "generate",
    "hessian",
    "hessian_slice",
    "inverse_rates",
    "is_identity",
    "jacobian",
    "jacobian_derivative",
    "jacobian_of",
    "jacobian_spaces",
    "joint_accelerations",
    "joint_path",
    "joint_rate_symbols",
    "joint_torques",
    "latex",
    "load_robot",
    "log_det_gradient",
    "manipulability_gradient",
    "numeric_jacobian",
    "pretty",
    "rate_matrix",
    "rates_along_path",
    "representation_jacobian",
    "representation_jacobian_at",
    "representation_jacobian_derivative",
    "representation_jacobian_derivative_at",
    "robot_from_mapping",
    "robot_from_toml",
    "robot_from_urdf",
    "robot_to_mapping",
    "robot_to_toml",
    "rotation_from",
    "rows_from_names",
    "screw_exponential",
    "shift_point",
    "simplify_expr",
    "simplify_matrix",
    "singularities",
    "space_jacobian",
    "sweep",
    "symbolic_spaces",
    "task_rows",
    "twist_transform",
    "urdf_catalog",
    "velocity_propagation",
    "wrench_between",
    "wrench_symbols",
    "wrench_transform",
    "write_module",
]


def __getattr__(name: str) -> _Any:
    """Import a public name on first use and keep it, so later lookups are plain attribute reads."""
    module = _HOME.get(name)
    if module is None:
        raise AttributeError(f"module 'symjac' has no attribute {name!r}")
    value = getattr(_import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


if _TYPE_CHECKING:  # static checkers see the names as if imported eagerly
    from symjac.analysis.inverse_rates import damped_least_squares, inverse_rates, rates_along_path
    from symjac.analysis.manipulability import (
        BarrierTerm,
        LogDetGradient,
        ManipulabilityGradient,
        log_det_gradient,
        manipulability_gradient,
    )
    from symjac.analysis.representations import (
        REPRESENTATIONS,
        EulerConvention,
        RepresentationJacobian,
        RepresentationJacobianDerivative,
        coordinate_rates,
        extract,
        rate_matrix,
        representation_jacobian,
        representation_jacobian_at,
        representation_jacobian_derivative,
        representation_jacobian_derivative_at,
        rotation_from,
    )
    from symjac.analysis.singularity.determinant import Determinant, determinant
    from symjac.analysis.singularity.singularities import LimitStatus, SingularFactor, SingularityReport, singularities
    from symjac.analysis.spaces import JacobianSpaces, SymbolicSpaces, jacobian_spaces, symbolic_spaces, task_rows
    from symjac.codegen import JacobianRequest, generate, write_module
    from symjac.drawing.animation import animate, joint_path
    from symjac.drawing.figure import ArmDrawing, draw
    from symjac.drawing.geometry import ArmPose, Ellipsoid, arm_pose, ellipsoid
    from symjac.errors import (
        ArgumentError,
        CodegenError,
        ConversionError,
        ExpressionError,
        FrameError,
        RepresentationError,
        ResultTooLargeError,
        RobotFileError,
        SymjacError,
        UnknownRobotError,
    )
    from symjac.kinematics.acceleration import (
        DERIVATIVE_METHODS,
        bias_acceleration,
        hessian,
        hessian_slice,
        jacobian_derivative,
    )
    from symjac.kinematics.acceleration_propagation import (
        AccelerationPropagation,
        AccelerationStep,
        acceleration_propagation,
        joint_accelerations,
    )
    from symjac.kinematics.chain import Chain, Frame, as_chain, chain_of, clear_caches, forward_kinematics
    from symjac.kinematics.jacobian import (
        METHODS,
        ROW_NAMES,
        change_frame,
        jacobian,
        jacobian_of,
        rows_from_names,
        shift_point,
    )
    from symjac.kinematics.numeric import evaluate_at, numeric_jacobian
    from symjac.kinematics.propagation import (
        ForcePropagation,
        VelocityPropagation,
        force_propagation,
        joint_rate_symbols,
        velocity_propagation,
        wrench_symbols,
    )
    from symjac.kinematics.screws import (
        SCREW_ROWS,
        body_jacobian,
        exponential_product,
        screw_exponential,
        space_jacobian,
    )
    from symjac.kinematics.statics import joint_torques, wrench_between
    from symjac.model.io import catalog, load_robot, robot_from_toml, robot_to_toml, urdf_catalog
    from symjac.model.robot import Convention, FixedTransform, Joint, JointType, Parameter, Robot
    from symjac.model.robot_file import robot_from_mapping, robot_to_mapping
    from symjac.model.urdf import robot_from_urdf
    from symjac.printing import latex, pretty
    from symjac.sweeps.run import sweep
    from symjac.symbolic.simplify import AngleBasis, is_identity, simplify_expr, simplify_matrix
    from symjac.symbolic.transforms import adjoint, twist_transform, wrench_transform
