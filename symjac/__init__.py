"""symjac: symbolic kinematics and Jacobians of serial robot arms, printed in textbook form.

The public API, in pipeline order: load a robot (:func:`load_robot`, :func:`robot_from_mapping`), derive its
kinematics (:func:`chain_of`, :func:`forward_kinematics`) and Jacobians (:func:`jacobian`, by four methods; the
iterations themselves with :func:`velocity_propagation` and :func:`force_propagation`), the acceleration level
(:func:`hessian`, :func:`jacobian_derivative`, :func:`bias_acceleration`, :func:`acceleration_propagation`,
:func:`manipulability_gradient`, :func:`log_det_gradient`, :func:`representation_jacobian_derivative`), statics
(:func:`joint_torques`, :func:`wrench_transform`, :func:`twist_transform`), screw theory (:func:`space_jacobian`,
:func:`body_jacobian`, :func:`screw_exponential`, :func:`exponential_product`, :func:`adjoint`), singular configurations
(:func:`singularities`, :func:`determinant`, :func:`jacobian_spaces`), joint rates (:func:`inverse_rates`,
:func:`damped_least_squares`), representation Jacobians (:func:`representation_jacobian`), dynamics
(:func:`newton_euler`, :func:`mass_matrix`, :func:`coriolis_matrix`, :func:`gravity_torques`, :func:`euler_lagrange`,
under a :class:`Gravity`; in regressor form, :func:`regressor`); print them (:func:`latex`) and generate fast numeric
modules from them (:func:`generate`, :func:`write_module`), or compile one in memory (:func:`numeric_model`,
:func:`numeric_jacobian`); solve the inverse kinematics (:func:`inverse_kinematics`, of a pose from
:func:`pose_from_rpy` or :func:`pose_from_quaternion`).

Every name is imported on first use (PEP 562), so ``import symjac`` costs nothing until a name is asked for and
``symjac --version`` does not load SymPy; ``from symjac import jacobian``, ``symjac.jacobian`` and ``dir(symjac)``
work as if everything had been imported up front.
"""

import ast as _ast
import os as _os
from importlib import import_module as _import_module
from pathlib import Path as _Path
from typing import TYPE_CHECKING as _TYPE_CHECKING
from typing import Any as _Any

# SymPy keeps 1000 results in its cache unless told otherwise, and reads the size once, when it is first imported.
# Deriving a long chain needs more: with 1000 a planar 30R Jacobian thrashed the cache (90 s instead of 7 s). A size
# the user has set wins; so does an earlier import of SymPy. Set here, before any submodule can import SymPy.
_os.environ.setdefault("SYMPY_CACHE_SIZE", "10000")

from symjac._version import __version__


def _public_names() -> dict[str, str]:
    """Each public name and the module it is imported from.

    The one list of the public API is the block of imports under ``if _TYPE_CHECKING`` at the end of this file:
    static checkers read it as eager imports (``name as name`` marks a re-export), and this reads it at run time.
    """
    tree = _ast.parse(_Path(__file__).read_text(encoding="utf-8"))
    block = next(node for node in tree.body if isinstance(node, _ast.If) and isinstance(node.test, _ast.Name)
                 and node.test.id == "_TYPE_CHECKING")
    return {alias.asname or alias.name: node.module for node in block.body if isinstance(node, _ast.ImportFrom)
            for alias in node.names if node.module}


_HOME = _public_names()
"""Each public name and the module it lives in."""

__all__ = ["__version__", *sorted(_HOME)]


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


if _TYPE_CHECKING:  # the public API: its only list (read at run time by _public_names)
    from symjac.analysis.dynamics.gravity import Gravity as Gravity
    from symjac.analysis.dynamics.lagrange import coriolis_matrix as coriolis_matrix
    from symjac.analysis.dynamics.lagrange import euler_lagrange as euler_lagrange
    from symjac.analysis.dynamics.lagrange import gravity_torques as gravity_torques
    from symjac.analysis.dynamics.lagrange import mass_matrix as mass_matrix
    from symjac.analysis.dynamics.newton_euler import newton_euler as newton_euler
    from symjac.analysis.identification.regressor import regressor as regressor
    from symjac.analysis.inverse_kinematics.poses import pose_from_matrix as pose_from_matrix
    from symjac.analysis.inverse_kinematics.poses import pose_from_quaternion as pose_from_quaternion
    from symjac.analysis.inverse_kinematics.poses import pose_from_rpy as pose_from_rpy
    from symjac.analysis.inverse_rates import damped_least_squares as damped_least_squares
    from symjac.analysis.inverse_rates import inverse_rates as inverse_rates
    from symjac.analysis.inverse_rates import rates_along_path as rates_along_path
    from symjac.analysis.manipulability import BarrierTerm as BarrierTerm
    from symjac.analysis.manipulability import LogDetGradient as LogDetGradient
    from symjac.analysis.manipulability import ManipulabilityGradient as ManipulabilityGradient
    from symjac.analysis.manipulability import log_det_gradient as log_det_gradient
    from symjac.analysis.manipulability import manipulability_gradient as manipulability_gradient
    from symjac.analysis.representations import REPRESENTATIONS as REPRESENTATIONS
    from symjac.analysis.representations import EulerConvention as EulerConvention
    from symjac.analysis.representations import RepresentationJacobian as RepresentationJacobian
    from symjac.analysis.representations import RepresentationJacobianDerivative as RepresentationJacobianDerivative
    from symjac.analysis.representations import coordinate_rates as coordinate_rates
    from symjac.analysis.representations import extract as extract
    from symjac.analysis.representations import rate_matrix as rate_matrix
    from symjac.analysis.representations import representation_jacobian as representation_jacobian
    from symjac.analysis.representations import representation_jacobian_at as representation_jacobian_at
    from symjac.analysis.representations import representation_jacobian_derivative as representation_jacobian_derivative
    from symjac.analysis.representations import (
        representation_jacobian_derivative_at as representation_jacobian_derivative_at,
    )
    from symjac.analysis.representations import rotation_from as rotation_from
    from symjac.analysis.singularity.determinant import Determinant as Determinant
    from symjac.analysis.singularity.determinant import determinant as determinant
    from symjac.analysis.singularity.singularities import LimitStatus as LimitStatus
    from symjac.analysis.singularity.singularities import SingularFactor as SingularFactor
    from symjac.analysis.singularity.singularities import SingularityReport as SingularityReport
    from symjac.analysis.singularity.singularities import singularities as singularities
    from symjac.analysis.spaces import JacobianSpaces as JacobianSpaces
    from symjac.analysis.spaces import SymbolicSpaces as SymbolicSpaces
    from symjac.analysis.spaces import jacobian_spaces as jacobian_spaces
    from symjac.analysis.spaces import symbolic_spaces as symbolic_spaces
    from symjac.analysis.spaces import task_rows as task_rows
    from symjac.codegen import JacobianRequest as JacobianRequest
    from symjac.codegen import generate as generate
    from symjac.codegen import write_module as write_module
    from symjac.codegen.numeric_model import NumericModel as NumericModel
    from symjac.codegen.numeric_model import numeric_jacobian as numeric_jacobian
    from symjac.codegen.numeric_model import numeric_model as numeric_model
    from symjac.drawing.animation import animate as animate
    from symjac.drawing.animation import joint_path as joint_path
    from symjac.drawing.figure import ArmDrawing as ArmDrawing
    from symjac.drawing.figure import draw as draw
    from symjac.drawing.geometry import ArmPose as ArmPose
    from symjac.drawing.geometry import Ellipsoid as Ellipsoid
    from symjac.drawing.geometry import arm_pose as arm_pose
    from symjac.drawing.geometry import ellipsoid as ellipsoid
    from symjac.errors import ArgumentError as ArgumentError
    from symjac.errors import CodegenError as CodegenError
    from symjac.errors import ConversionError as ConversionError
    from symjac.errors import ExpressionError as ExpressionError
    from symjac.errors import FrameError as FrameError
    from symjac.errors import InertialWarning as InertialWarning
    from symjac.errors import NoClosedFormError as NoClosedFormError
    from symjac.errors import RepresentationError as RepresentationError
    from symjac.errors import ResultTooLargeError as ResultTooLargeError
    from symjac.errors import RobotFileError as RobotFileError
    from symjac.errors import SymjacError as SymjacError
    from symjac.errors import UnknownRobotError as UnknownRobotError
    from symjac.kinematics.acceleration import DERIVATIVE_METHODS as DERIVATIVE_METHODS
    from symjac.kinematics.acceleration import bias_acceleration as bias_acceleration
    from symjac.kinematics.acceleration import hessian as hessian
    from symjac.kinematics.acceleration import hessian_slice as hessian_slice
    from symjac.kinematics.acceleration import jacobian_derivative as jacobian_derivative
    from symjac.kinematics.acceleration_propagation import AccelerationPropagation as AccelerationPropagation
    from symjac.kinematics.acceleration_propagation import AccelerationStep as AccelerationStep
    from symjac.kinematics.acceleration_propagation import acceleration_propagation as acceleration_propagation
    from symjac.kinematics.acceleration_propagation import joint_accelerations as joint_accelerations
    from symjac.kinematics.chain import Chain as Chain
    from symjac.kinematics.chain import Frame as Frame
    from symjac.kinematics.chain import as_chain as as_chain
    from symjac.kinematics.chain import chain_of as chain_of
    from symjac.kinematics.chain import clear_caches as clear_caches
    from symjac.kinematics.chain import forward_kinematics as forward_kinematics
    from symjac.kinematics.jacobian import METHODS as METHODS
    from symjac.kinematics.jacobian import ROW_NAMES as ROW_NAMES
    from symjac.kinematics.jacobian import change_frame as change_frame
    from symjac.kinematics.jacobian import jacobian as jacobian
    from symjac.kinematics.jacobian import jacobian_of as jacobian_of
    from symjac.kinematics.jacobian import rows_from_names as rows_from_names
    from symjac.kinematics.jacobian import shift_point as shift_point
    from symjac.kinematics.numeric import evaluate_at as evaluate_at
    from symjac.kinematics.points import point_position as point_position
    from symjac.kinematics.propagation import ForcePropagation as ForcePropagation
    from symjac.kinematics.propagation import VelocityPropagation as VelocityPropagation
    from symjac.kinematics.propagation import force_propagation as force_propagation
    from symjac.kinematics.propagation import joint_rate_symbols as joint_rate_symbols
    from symjac.kinematics.propagation import velocity_propagation as velocity_propagation
    from symjac.kinematics.propagation import wrench_symbols as wrench_symbols
    from symjac.kinematics.screws import SCREW_ROWS as SCREW_ROWS
    from symjac.kinematics.screws import body_jacobian as body_jacobian
    from symjac.kinematics.screws import exponential_product as exponential_product
    from symjac.kinematics.screws import screw_exponential as screw_exponential
    from symjac.kinematics.screws import space_jacobian as space_jacobian
    from symjac.kinematics.statics import joint_torques as joint_torques
    from symjac.kinematics.statics import wrench_between as wrench_between
    from symjac.model.drive import Drive as Drive
    from symjac.model.inertia import Inertial as Inertial
    from symjac.model.io import catalog as catalog
    from symjac.model.io import load_robot as load_robot
    from symjac.model.io import robot_from_toml as robot_from_toml
    from symjac.model.io import robot_to_toml as robot_to_toml
    from symjac.model.io import urdf_catalog as urdf_catalog
    from symjac.model.readers.mjcf import robot_from_mjcf as robot_from_mjcf
    from symjac.model.robot import Convention as Convention
    from symjac.model.robot import FixedTransform as FixedTransform
    from symjac.model.robot import Joint as Joint
    from symjac.model.robot import JointType as JointType
    from symjac.model.robot import Parameter as Parameter
    from symjac.model.robot import Robot as Robot
    from symjac.model.robot_file import robot_from_mapping as robot_from_mapping
    from symjac.model.robot_file import robot_to_mapping as robot_to_mapping
    from symjac.model.urdf import robot_from_urdf as robot_from_urdf
    from symjac.printing import latex as latex
    from symjac.printing import pretty as pretty
    from symjac.solvers.inverse_kinematics import InverseKinematicsResult as InverseKinematicsResult
    from symjac.solvers.inverse_kinematics import InverseKinematicsSolution as InverseKinematicsSolution
    from symjac.solvers.inverse_kinematics import inverse_kinematics as inverse_kinematics
    from symjac.sweeps.run import sweep as sweep
    from symjac.symbolic.angles import AngleBasis as AngleBasis
    from symjac.symbolic.nested import Intermediate as Intermediate
    from symjac.symbolic.nested import NestedMatrix as NestedMatrix
    from symjac.symbolic.nested import lambdify_cse as lambdify_cse
    from symjac.symbolic.simplify import is_identity as is_identity
    from symjac.symbolic.simplify import simplify_expr as simplify_expr
    from symjac.symbolic.simplify import simplify_matrix as simplify_matrix
    from symjac.symbolic.transforms import adjoint as adjoint
    from symjac.symbolic.transforms import twist_transform as twist_transform
    from symjac.symbolic.transforms import wrench_transform as wrench_transform
