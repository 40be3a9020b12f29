"""Assembling a generated module: requests to lowered functions, printed by the target's backend, into a template."""

from __future__ import annotations

import os
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import sympy as sp

from symjac._version import __version__
from symjac.analysis.dynamics.gravity import GRAVITY_SYMBOL, STANDARD_GRAVITY
from symjac.codegen.backends import backend
from symjac.codegen.coupled import (
    coupling_lines,
)
from symjac.codegen.description import (
    Check,
    FunctionDescription,
    JacobianInfo,
    ModuleDescription,
)
from symjac.codegen.dynamics import identification_base, identification_regressor
from symjac.codegen.functions import (
    defined_names,
    derived_functions,
    dynamics_functions,
    function_descriptions,
    listing,
    request_lines,
    scalar_descriptions,
    self_checks,
)
from symjac.codegen.ik_numeric import numeric_ik_jacobian
from symjac.codegen.inverse_kinematics import IK_EXPORTS, closed_or_numeric, ik_listing
from symjac.codegen.joint_table import joint_entries, source_words, tip_frame
from symjac.codegen.kinds import DYNAMICS_CHECKED, IDENTIFICATION_CHECKED
from symjac.codegen.printers import float_literal
from symjac.codegen.provenance import catalog_files, names_relative_file, robot_loader
from symjac.codegen.request import (
    STRATEGIES,
    JacobianRequest,
    Strategy,
    end_words,
    python_call,
    requests_from,
    validate_robot,
)
from symjac.errors import CodegenError
from symjac.files import write_files, write_text
from symjac.kinematics.chain import Chain, Frame, as_chain
from symjac.kinematics.jacobian import Point
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import Robot

__all__ = [
    "STRATEGIES",
    "ModuleRequest",
    "Strategy",
    "check_dynamics",
    "describe",
    "function_descriptions",
    "generate",
    "module_header",
    "primary",
    "render_files",
    "render_module",
    "scalar_descriptions",
    "single_or_written",
    "write_module",
]


@dataclass(frozen=True)
class ModuleRequest:
    """Everything one generated module is asked for: the arguments of :func:`generate` and :func:`describe`.

    See :func:`generate` for the meaning of each field; ``robot`` and ``target`` are checked by :func:`describe`.
    """

    robot: Robot | Chain
    target: str = "python"
    frames: Sequence[Frame] | Frame = (0,)
    points: Sequence[Point | None] | Point | None = (None,)
    rows: Sequence[int] | None = None
    jacobians: Sequence[JacobianRequest] | None = None
    scalars: Mapping[str, sp.Expr] | None = None
    strategy: Strategy = "fastest"
    command: str | None = None
    acceleration: bool = False
    name: str | None = None
    dynamics: bool = False
    identification: bool = False
    inverse_kinematics: bool = False
    numeric_ik: bool = False
    free_joint: int | None = None  # joint number (1-based) given in the closed form (q_free), a 7-joint arm's


def describe(request: ModuleRequest, *args: Any, **options: Any) -> ModuleDescription:
    """The language-neutral description of the module a :class:`ModuleRequest` asks for (what :func:`generate` renders).

    The old form ``describe(robot, target, ...)`` (the arguments of :func:`generate`) still works but is deprecated:
    it warns with a :class:`DeprecationWarning`; build ``ModuleRequest(robot, target, ...)`` instead.
    """
    if not isinstance(request, ModuleRequest):
        warnings.warn("describe(robot, target, ...) is deprecated; pass a ModuleRequest(robot, target, ...)",
                      DeprecationWarning, stacklevel=2)
        request = ModuleRequest(request, *args, **options)
    elif args or options:
        raise CodegenError("describe takes a ModuleRequest alone; put the options in the request")
    spec = backend(request.target)
    if request.strategy not in STRATEGIES:
        raise CodegenError(f"unknown strategy {request.strategy!r}; choose one of {', '.join(STRATEGIES)}")
    if not isinstance(request.robot, Robot | Chain):
        raise CodegenError(f"expected a symjac Robot or Chain, got {type(request.robot).__name__}")
    chain = as_chain(request.robot)
    validate_robot(chain.robot, spec.identifiers, request.name)
    given = request.robot if isinstance(request.robot, Robot) else chain.robot
    joint_entries(given, spec.identifiers)  # refuse unusable joint and tip names before deriving anything
    tip_frame(given)
    requests = requests_from(chain, request.frames, request.points, request.rows, request.jacobians)
    if not requests:
        raise CodegenError("at least one Jacobian (frame and point) must be requested")
    dynamics = request.dynamics or request.identification
    if dynamics:
        check_dynamics(chain)
    functions, infos = function_descriptions(chain, requests, request.strategy, request.acceleration, dynamics,
                                             request.identification)
    functions += scalar_descriptions(chain, request.scalars or {}, functions, infos, spec.identifiers)
    return module_header(request, chain, requests, functions, infos)


def module_header(request: ModuleRequest, chain: Chain, requests: Sequence[JacobianRequest],
                  functions: Sequence[FunctionDescription], infos: Sequence[JacobianInfo]) -> ModuleDescription:
    """The module around its functions: robot facts, exported names and the command that regenerates it."""
    model = chain.robot
    spec = backend(request.target)
    # the check's tau = M qddot + C qdot + g and b = C qdot + g leave friction out: a robot with friction goes without
    # it, and without the potential energy only the check calls
    friction = any(d is not None and (d.viscous != 0 or d.coulomb != 0) for d in model.drives)
    functions = [f for f in functions if not (friction and f.kind == "potential_energy")]
    exports = ({"PARAMETERS", "COORDINATES", "JOINTS", "ROBOT", "JOINT_NAMES", "JOINT_TYPES", "LOWER", "UPPER",
                "TIP_FRAME", "coordinates", "selftest", *spec.exports}
               | {name for name in defined_names(functions, infos) if not name.startswith("_")})
    command, shell = request.command, request.command is not None
    if command is None:
        loader, command_note = robot_loader(request.robot if isinstance(request.robot, Robot) else model)
        command = python_call(model, request.target, requests, request.scalars or {}, request.strategy, loader,
                              request.acceleration, request.name, request.dynamics, request.identification,
                              request.inverse_kinematics, request.numeric_ik, request.free_joint)
    else:
        source = request.robot.source if isinstance(request.robot, Robot) else model.source
        command_note = "in the folder it was run in" if names_relative_file(source, command) else ""
    coupled, n = model.coupling is not None, model.n_coordinates
    # names, tip frame and source take no part in a robot's equality: read them from the robot given, not the one
    # a cached chain was first built for
    given = request.robot if isinstance(request.robot, Robot) else model
    with_dynamics = request.dynamics or request.identification
    dynamics = dynamics_functions(chain, functions) if with_dynamics else []
    derived = [*dynamics, *derived_functions(infos, n, coupled)]
    exports |= {d.name for d in dynamics}
    kinds = {f.kind: f.name for f in functions} | {d.kind: d.name for d in dynamics}
    checked = [kinds[kind] for kind in DYNAMICS_CHECKED if kind in kinds] if with_dynamics and not friction else []
    name_lists, identification_checks = _identification(chain, functions) if request.identification else ((), ())
    exports |= {constant for constant, _ in name_lists}
    inverse_kinematics, numeric = closed_or_numeric(chain, request.target, request.inverse_kinematics,
                                                  request.free_joint)
    exports |= set(IK_EXPORTS) if inverse_kinematics is not None else set()
    exports |= {"inverse_kinematics_numeric"} if request.numeric_ik or numeric else set()
    # gravity's magnitude is a parameter when the lowered dynamics leave it a symbol (else its 9.81 is written in)
    symbolic_gravity = any(GRAVITY_SYMBOL in f.lowered.used_symbols for f in functions)
    gravity = ((GRAVITY_SYMBOL.name, float(STANDARD_GRAVITY)),) if symbolic_gravity else ()
    # symbolic inertial parameters are arguments of dynamics modules only
    parameters = model.parameters if with_dynamics else model.geometric_parameters
    return ModuleDescription(
        target=request.target, version=__version__, robot=request.name or model.name,
        convention=model.convention.value,
        n_joints=model.n_joints, n_coordinates=model.n_coordinates,
        coordinates=tuple((c.name, kind.value) for c, kind in zip(model.q, model.coordinate_types, strict=True)),
        coupling=coupling_lines(chain),
        parameters=(*((p.name, float(float_literal(p.default))) for p in parameters), *gravity),
        functions=tuple(functions), jacobians=tuple(infos),
        scalars=tuple(f.name for f in functions if f.kind == "scalar"),
        exports=tuple(_sorted_exports(exports)), command=command, shell_command=shell, command_note=command_note,
        rates=tuple(s.name for s in joint_rate_symbols(chain)) if request.acceleration or with_dynamics else (),
        accelerations=tuple(s.name for s in model.coordinate_accelerations) if with_dynamics else (),
        coordinate_symbols=tuple(model.q),
        parameter_symbols=(*(p.symbol for p in parameters), *((GRAVITY_SYMBOL,) if symbolic_gravity else ())),
        derived=tuple(derived), listing=(*listing(functions, derived, infos, n, coupled, end_words(model)),
                 *ik_listing(inverse_kinematics)),
        checks=(*self_checks(infos, checked), *identification_checks),
        request_lines=request_lines(infos),
        joint_entries=joint_entries(given, spec.identifiers), tip_frame=tip_frame(given),
        origin=source_words(given, catalog_files()),
        name_lists=name_lists,
        inverse_kinematics=inverse_kinematics,
        numeric_ik=numeric_ik_jacobian(request.target, infos, coupled) if request.numeric_ik or numeric else "",
    )


def _identification(chain: Chain, functions: Sequence[FunctionDescription]
                    ) -> tuple[tuple[tuple[str, tuple[str, ...]], ...], tuple[Check, ...]]:
    """The regressors' column names as module constants, and the self-test's checks of the regressors.

    Each regressor times the robot's own parameters (a self-test-only function) must give inverse dynamics; the
    check is told the regressor's column count (its ``rows``).
    """
    by_kind = {f.kind: f for f in functions}
    lists = [("REGRESSOR_PARAMETERS", identification_regressor(chain).names)]
    if "base_regressor" in by_kind:
        lists.append(("BASE_PARAMETERS", tuple(s.name for s in identification_base(chain).symbols)))
    checks = tuple(Check("identification", (by_kind["inverse_dynamics"].name, by_kind[kind].name,
                                            by_kind[values].name), (by_kind[kind].shape[1],))
                   for kind, values in IDENTIFICATION_CHECKED if kind in by_kind and values in by_kind)
    return tuple(lists), checks


def check_dynamics(chain: Chain) -> None:
    """Refuse dynamics for a robot without inertial data on every link (the error names them) or named ``g``.

    A robot parameter called ``g`` would clash with gravity's magnitude, which every dynamics module takes.
    """
    from symjac.analysis.dynamics.bodies import link_bodies
    from symjac.analysis.dynamics.gravity import EARTH, check_gravity

    link_bodies(chain)
    check_gravity(chain.robot, EARTH)


def _sorted_exports(names: Iterable[str]) -> list[str]:
    """``__all__`` in the order ruff's RUF022 expects: SCREAMING_CASE, then CamelCase, then the rest."""
    def key(name: str) -> tuple[int, str]:
        if name.isupper():
            return (0, name)
        if name[:1].isupper():
            return (1, name)
        return (2, name)

    return sorted(names, key=key)


def generate(
    robot: Robot | Chain,
    target: str = "python",
    frames: Sequence[Frame] | Frame = (0,),
    points: Sequence[Point | None] | Point | None = (None,),
    *,
    rows: Sequence[int] | None = None,
    jacobians: Sequence[JacobianRequest] | None = None,
    scalars: Mapping[str, sp.Expr] | None = None,
    strategy: Strategy = "fastest",
    command: str | None = None,
    acceleration: bool = False,
    name: str | None = None,
    dynamics: bool = False,
    identification: bool = False,
    inverse_kinematics: bool = False,
    numeric_ik: bool = False,
    free_joint: int | None = None,
) -> str:
    r"""The source text of a numeric module for ``robot``: FK, Jacobians, torques, manipulability, self-test.

    Parameters
    ----------
    robot : Robot or Chain
    target : str
        One of :data:`~symjac.codegen.TARGETS` (``"python"``, ``"numpy"``, ``"lambdify"``, ``"c"``, ``"c99"``,
        ``"cpp"``, ``"jax"``, ``"casadi"``; see :mod:`symjac.codegen.backends`). For a target that writes several
        files (``"c99"``), this returns the primary one; :func:`render_files` gives them all.
    frames : frame or sequence of frames
        Frames the Jacobians are expressed in (default {0}); every frame is combined with every point.
    points : point or sequence of points
        ``"tool"``, ``"flange"`` (or ``"wrist"``, the origin of {n}), ``"wrist_centre"`` or three coordinates in
        frame {n}; default (``None``) the end of the chain, the origin of the frame ``forward_kinematics`` ends at
        (the tool point when the robot has a tool, else the flange).
    rows : sequence of int, optional
        Task rows of the Jacobians (0..5 = v_x .. omega_z); default all six.
    jacobians : sequence of JacobianRequest, optional
        Explicit requests instead of ``frames`` x ``points``.
    scalars : mapping of str to sympy.Expr, optional
        Extra scalar functions of the joint variables and parameters, generated through the same pipeline (the
        place for a factored symbolic determinant: ``scalars={"det_factored": expr}``).
    strategy : "fastest", "raw" or "simplified"
        Which Jacobian expressions to start from: the candidate with fewest operations after CSE (default), the raw
        chain products only, or the compact textbook form only.
    command : str, optional
        How to regenerate the module, for its header: the command line that was typed (the CLI passes it; the
        header adds "in the folder it was run in" when it names a relative path). Default: the equivalent
        ``symjac.generate(...)`` call, which loads a catalog robot by name and a robot read from a file by the
        path it was read from; any other robot is written ``robot`` and the header says so.
    acceleration : bool
        Also generate, for every Jacobian ``jacobian<suffix>``, the acceleration-level functions with the same
        suffix: ``hessian<suffix>(q)`` (shape rows x n x n, ``H[i, j, m] = dJ[i, j]/dq_m``),
        ``bias_acceleration<suffix>(q, qdot)`` (``Jdot qdot``, one value per row) and
        ``manipulability_gradient<suffix>(q)`` (``dw/dq_m = w trace(J^+ dJ/dq_m)``, n values), all checked by the
        module's ``selftest`` against central differences of its own Jacobian. Off by default: the Hessian has
        rows x n x n entries, which would more than double the size of every module.

    name : str, optional
        The module's name: its file names, the C prefix, the C++ namespace, ``ROBOT`` (default: the robot's name,
        always an identifier). It must be an identifier of the target's language.
    dynamics : bool
        Also generate the equations of motion, in the coordinates, each function once per module:
        ``inverse_dynamics(q, qdot, qddot)`` (Newton-Euler), ``mass_matrix(q)``, ``coriolis_matrix(q, qdot)``
        (Christoffel symbols), ``bias_forces(q, qdot)`` (C qdot + g), ``gravity_torques(q)`` and
        ``forward_dynamics(q, qdot, tau)`` (qddot by a Cholesky solve of the generated M, in the runtime), all
        checked by ``selftest`` against each other. Gravity's magnitude ``g`` (default 9.81, along -z of {0}) joins
        the parameters, as do symbolic inertial parameters (``m2``, ``cx2``, ``Ixx2``, ...). The robot needs
        inertial data on every link (else a ``NoInertialDataError`` names the links without).
    identification : bool
        Also generate the dynamics linear in their parameters (and the dynamics, as ``dynamics=True``):
        ``regressor(q, qdot, qddot)`` (n x p, tau = Y pi, the columns named in order by the module constant
        ``REGRESSOR_PARAMETERS``: ten per link, ``XX1 XY1 XZ1 YY1 YZ1 ZZ1 MX1 MY1 MZ1 M1 XX2 ...``, about the link
        origin) and ``base_regressor(q, qdot, qddot)`` (n x b, tau = Y_b pi_b, ``BASE_PARAMETERS``); ``selftest``
        checks both against inverse dynamics with the robot's own parameters.
    inverse_kinematics : bool
        Also generate ``inverse_kinematics(pose)``, every solution of the closed form into a fixed array of
        ``IK_MAX_SOLUTIONS`` rows, their count and branches, in the coordinates (a coupled robot's too); an arm
        without one gets ``inverse_kinematics_numeric``. ``free_joint=k`` (a joint number, 1-based) asks for the
        closed form with joint k given: ``inverse_kinematics(pose, q_free)``.
    numeric_ik : bool
        Also generate ``inverse_kinematics_numeric``, Levenberg-Marquardt on the module's forward kinematics and its
        first six-row frame-{0} Jacobian (``symjac.codegen.ik_numeric``; jax, casadi: ``ik_numeric_traced``).

    Returns
    -------
    str
        The module source; identical input gives byte-identical output. The first Jacobian requested is always
        ``jacobian`` (with ``joint_torques``, ``manipulability``, ``jacobian_determinant`` and, with
        ``acceleration``, ``hessian``, ``bias_acceleration``, ``manipulability_gradient``); every other one adds
        the suffix ``_<frame>_<point>`` and, with ``rows``, ``_r<rows>``: ``jacobian_3_tool``, ``jacobian_0_p1``
        (``p1``, ``p2``: explicit points in the order given), ``hessian_0_flange_r012``.

    Raises
    ------
    CodegenError
        For an unknown target or strategy, a name that cannot be used in generated code, an unsupported expression.
    FrameError
        For a frame or point the robot does not have.

    Examples
    --------
    >>> from symjac import load_robot
    >>> source = generate(load_robot("planar2r"), "python")
    >>> namespace = {}
    >>> exec(compile(source, "planar2r_jacobian.py", "exec"), namespace)
    >>> [[round(v, 6) for v in row] for row in namespace["jacobian"]([0.0, 1.5707963267948966], L1=1.0)[:2]]
    [[-0.4, -0.4], [1.0, 0.0]]
    """
    request = ModuleRequest(robot, target, frames, points, rows=rows, jacobians=jacobians, scalars=scalars,
                            strategy=strategy, command=command, acceleration=acceleration, name=name,
                            dynamics=dynamics, identification=identification, inverse_kinematics=inverse_kinematics,
                            numeric_ik=numeric_ik, free_joint=free_joint)
    return primary(render_files(describe(request)))


def render_files(description: ModuleDescription) -> dict[str, str]:
    """Every file of the module, ``{relative file name: text}``, the primary one first (the target's ``render``)."""
    spec = backend(description.target)
    files = dict(spec.render(description, spec))
    if not files:
        raise CodegenError(f"internal error: target {spec.name} rendered no file")
    return files


def render_module(description: ModuleDescription) -> str:
    """The primary file's text (the module itself for every target today)."""
    return primary(render_files(description))


def primary(files: Mapping[str, str]) -> str:
    """The text of the primary (first) file of a rendered module."""
    return next(iter(files.values()))


def single_or_written(files: Mapping[str, str], output: str | None) -> str | None:
    """The text of a one-file module for the caller to write; several files are written to ``output`` here.

    Several files need a folder (``symjac codegen -o DIR``, made if it does not exist): stdout cannot hold them,
    and they name each other (``#include "<name>.h"``), so they keep their own names. Returns ``None`` when the
    files were written (all of them, or none on an error).
    """
    if len(files) == 1:
        return primary(files)
    needs = f"this target writes {len(files)} files ({', '.join(files)}): give -o DIR, a folder"
    if output is None or output == "-":
        raise CodegenError(needs)
    folder = Path(output)
    if folder.exists() and not folder.is_dir():
        raise CodegenError(f"{output} is not a folder; {needs}")
    folder.mkdir(parents=True, exist_ok=True)
    write_module(folder / next(iter(files)), files)
    return None


def write_module(path: str | os.PathLike[str], text: str | Mapping[str, str]) -> Path:
    """Write a generated module to ``path`` as ``symjac codegen -o`` does (:func:`symjac.files.write_files`).

    ``text`` is the module's text, or every file of it (``{relative name: text}``, as :func:`render_files` gives):
    the primary file goes to ``path``, the others beside it under their own names. All are written or none: each is
    first written to a temporary file, and only when all are there do they replace their targets. A regular file is
    replaced atomically and keeps its permissions; a new one gets the umask's.
    """
    if isinstance(text, str):
        return write_text(path, text)
    names = list(text)
    if not names:
        raise CodegenError("no file to write")
    folder = Path(path).parent
    targets = {Path(path): text[names[0]]}
    for name in names[1:]:
        if Path(name).is_absolute() or ".." in Path(name).parts:
            raise CodegenError(f"generated file name {name!r} must be relative and stay in the output folder")
        targets[folder / name] = text[name]
    write_files(targets)
    return Path(path)
