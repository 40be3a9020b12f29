"""The functions of a generated module, as language-neutral descriptions: named, documented from the kinds table.

The module-scoped kinds (forward kinematics), then per Jacobian request its kinds in the order of
:func:`~symjac.codegen.kinds.generated_kinds` (the Jacobian, torques, the self-test's kinematics; with
``acceleration`` the Hessian and bias acceleration), each lowered by its kind's lowering (coupled robots through
:mod:`~symjac.codegen.coupled`); the functions derived from those by the runtime (manipulability, determinant,
gradient); the module docstring's list of functions. Which kinds exist, what each returns and how it is documented
comes from :data:`~symjac.codegen.kinds.KINDS`, made from the quantities' specs: this is the one place that fills
it in, and a new quantity needs no line here.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping, Sequence

import sympy as sp

from symjac.codegen.coupled import coordinate_derivation
from symjac.codegen.description import (
    Argument,
    Check,
    DerivedFunction,
    FunctionDescription,
    FunctionSpec,
    JacobianInfo,
)
from symjac.codegen.kinds import KINDS, SCALAR, generated_kinds, kind_spec, quantity_of
from symjac.codegen.lower import LoweredFunction, angle_expansion, lower_function
from symjac.codegen.names import RESERVED, IdentifierRule
from symjac.codegen.printers import float_literal
from symjac.codegen.request import (
    JacobianRequest,
    Strategy,
    check_rows,
    end_words,
    frame_text,
    function_labels,
    point_text,
    point_words,
)
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain, Frame
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import WRENCH_NAMES, Robot
from symjac.quantities.spec import Generated, entry_point

__all__ = [
    "defined_names",
    "derived_functions",
    "dynamics_functions",
    "function_descriptions",
    "input_arguments",
    "listing",
    "lowered",
    "request_lines",
    "scalar_descriptions",
    "self_checks",
]

MAX_SUMMARY = 110
"""The longest docstring summary (a line of 120 characters holds it after an indent, quotes and a comment sign)."""


def lowered(kind: Generated, chain: Chain, strategy: Strategy, frame: Frame | None = None,
            point: tuple[sp.Expr, ...] = (), rows: tuple[int, ...] = ()) -> LoweredFunction:
    """A function of ``kind`` lowered: by its spec's lowering, or (none named) its quantity's derivation.

    The lowering is called with the chain and those of ``frame``, ``point``, ``rows`` and ``strategy`` its
    signature names (a module-scoped kind is offered the strategy only).
    """
    if not kind.lowering:
        quantity = quantity_of(kind.name)
        if quantity is None:
            raise CodegenError(f"internal error: function kind {kind.name!r} has no lowering and is no quantity")
        where = () if kind.scope == "module" else (frame, point)
        return coordinate_derivation(chain, quantity.derivation, quantity.coupling, where,
                                     rows if kind.task_rows else ())
    lowering = entry_point(kind.lowering)
    offered: dict[str, object] = {"strategy": strategy}
    if kind.scope == "request":
        offered |= {"frame": frame, "point": point, "rows": rows}
    taken = inspect.signature(lowering).parameters
    return lowering(chain, **{name: value for name, value in offered.items() if name in taken})  # type: ignore[no-any-return]


def input_arguments(chain: Chain, selected: tuple[int, ...] = ()) -> dict[str, Argument]:
    """The arguments a generated function may take after ``q`` (:data:`~symjac.quantities.spec.Input`), by name."""
    model = chain.robot
    coupled = model.coupling is not None
    return {"wrench": Argument("wrench", tuple(WRENCH_NAMES[r] for r in selected),
                               "Wrench (force, moment) at the point"),
            "qdot": Argument("qdot", tuple(s.name for s in joint_rate_symbols(chain)),
                             "Coordinate rates" if coupled else "Joint rates"),
            "qddot": Argument("qddot", tuple(s.name for s in model.coordinate_accelerations),
                              "Coordinate accelerations" if coupled else "Joint accelerations"),
            "tau": Argument("tau", tuple(f"tau_{s.name}" for s in model.q),
                            "Generalised forces, one per coordinate" if coupled else
                            "Joint torques (forces at prismatic joints)")}


def function_descriptions(chain: Chain, requests: Sequence[JacobianRequest], strategy: Strategy, acceleration: bool,
                          dynamics: bool = False, identification: bool = False
                          ) -> tuple[list[FunctionDescription], list[JacobianInfo]]:
    """The module-scoped functions, then per Jacobian request its functions (:func:`generated_kinds` order).

    With ``dynamics`` the module-scoped functions include the dynamics' lowered kinds (forward dynamics, derived,
    is :func:`dynamics_functions`'s), with ``identification`` the regressors and their self-test's values.
    """
    model = chain.robot
    q_argument = Argument("q", tuple(s.name for s in model.q), _q_words(model))
    coupled = model.coupling is not None
    functions: list[FunctionDescription] = []

    def add(function: LoweredFunction, name: str, kind: Generated, selected: tuple[int, ...],
            **fields: object) -> None:
        inputs = input_arguments(chain, selected)
        returns = kind.returns_text(coupled, shape=function.shape)
        summary = kind.summary_text(coupled, **fields)
        if len(summary) > MAX_SUMMARY and "at" in fields:  # a long point: its words stay in the module's listing
            summary = kind.summary_text(coupled, **{**fields, "at": "the point the module docstring names"})
        spec = FunctionSpec(name, kind.name, summary,
                            (q_argument, *(inputs[i] for i in kind.inputs)), returns)
        functions.append(FunctionDescription(spec, function))

    for kind in generated_kinds("module", acceleration, dynamics, identification):
        if not kind.derived:
            add(lowered(kind, chain, strategy), kind.base, kind, (), end=end_words(model))
    infos: list[JacobianInfo] = []
    n = model.n_coordinates
    for request, label in zip(requests, function_labels(model, requests), strict=True):
        point_name, point = point_text(model, request.point)
        selected = check_rows(request.rows)
        kinds = [kind for kind in generated_kinds("request", acceleration)
                 if not (kind.square_only and len(selected) != n)]
        names = {kind.name: f"{kind.base}{label}" for kind in kinds}
        at = point_words(point_name, model.n_joints)
        fields = {**dict.fromkeys(KINDS, ""), **names, "frame": frame_text(request.frame), "at": at}
        records: list[tuple[str, str, tuple[int, ...]]] = []
        for kind in kinds:
            if kind.derived:
                records.append((kind.name, names[kind.name], (n,) if kind.per_coordinate else ()))
                continue
            function = lowered(kind, chain, strategy, request.frame, point, selected)
            add(function, names[kind.name], kind, selected, **fields)
            records.append((kind.name, names[kind.name], function.shape))
        infos.append(JacobianInfo(
            jacobian=names["jacobian"], joint_torques=names["joint_torques"], manipulability=names["manipulability"],
            determinant=names.get("jacobian_determinant"), kinematics=names["kinematics"],
            frame=frame_text(request.frame), point=at,
            point_values=tuple(float_literal(v.subs(model.defaults)) for v in point),  # type: ignore[arg-type]
            rows=selected, row_names=tuple(ROW_NAMES[r] for r in selected),
            wrench_names=tuple(WRENCH_NAMES[r] for r in selected),
            hessian=names.get("hessian"), bias_acceleration=names.get("bias_acceleration"),
            manipulability_gradient=names.get("manipulability_gradient"), functions=tuple(records),
        ))
    return functions, infos


def derived_functions(infos: Sequence[JacobianInfo], n: int, coupled: bool) -> list[DerivedFunction]:
    """Per Jacobian request, its derived functions (manipulability, determinant, gradient), in kinds-table order.

    Each is computed at run time by the runtime routine of its kind (:data:`~symjac.codegen.kinds.KINDS`) from the
    results of its sources, the request's functions of the kinds it names: the Jacobian, and the Hessian for the
    gradient.
    """
    found: list[DerivedFunction] = []
    for info in infos:
        names = {kind: name for kind, name, _ in info.functions}
        shapes = {kind: shape for kind, _, shape in info.functions}
        fields = {**dict.fromkeys(KINDS, ""), **names}
        for kind_name, name, shape in info.functions:
            spec = kind_spec(kind_name)
            if not spec.derived:
                continue
            found.append(DerivedFunction(
                name=name, kind=kind_name, summary=spec.summary.format(**fields),
                details=spec.details.format(**fields), returns=spec.returns_text(coupled, shape=shape),
                sources=tuple(names[s] for s in spec.sources), source_kinds=spec.sources,
                source_shapes=tuple(shapes[s] for s in spec.sources), routine=spec.routine, shape=shape))
    return found


def dynamics_functions(chain: Chain, functions: Sequence[FunctionDescription]) -> list[DerivedFunction]:
    """The module-scoped derived functions (forward dynamics), from the module's functions of their sources' kinds.

    Each source is called with ``q`` and those of the derived function's inputs its own kind takes; the inputs no
    source takes go to the routine after the sources' results.
    """
    model = chain.robot
    coupled = model.coupling is not None
    by_kind = {function.kind: function for function in functions}
    found: list[DerivedFunction] = []
    arguments = input_arguments(chain)
    for kind in KINDS.values():
        if not (kind.derived and kind.scope == "module") or not all(s in by_kind for s in kind.sources):
            continue
        names = {**dict.fromkeys(KINDS, ""), **{k: f.name for k, f in by_kind.items()}}
        taken = {name for s in kind.sources for name in kind_spec(s).inputs}
        shape = (model.n_coordinates,) if kind.per_coordinate else ()
        found.append(DerivedFunction(
            name=kind.base, kind=kind.name, summary=kind.summary_text(coupled, **names),
            details=kind.details.format(**names), returns=kind.returns_text(coupled, shape=shape),
            sources=tuple(by_kind[s].name for s in kind.sources), source_kinds=kind.sources,
            source_shapes=tuple(by_kind[s].shape for s in kind.sources), routine=kind.routine, shape=shape,
            inputs=tuple(arguments[i] for i in kind.inputs),
            source_inputs=tuple(tuple(i for i in kind.inputs if i in kind_spec(s).inputs) for s in kind.sources),
            routine_inputs=tuple(i for i in kind.inputs if i not in taken)))
    return found


def listing(functions: Sequence[FunctionDescription], derived: Sequence[DerivedFunction],
            infos: Sequence[JacobianInfo], n: int, coupled: bool, end: str = "the tool frame"
            ) -> tuple[tuple[str, str], ...]:
    """Every public function with its line for the module docstring, in the order of the docstring.

    The module-scoped functions; each request's, its velocity level (lowered, then derived) before its acceleration
    level; the scalars. The lines are :attr:`~symjac.quantities.spec.Generated.listing`; ``end`` is the frame the
    forward kinematics ends at (:func:`~symjac.codegen.request.end_words`).
    """
    entries: list[tuple[str, str]] = []
    unit = "coordinate" if coupled else "joint"

    def add(name: str, kind: Generated, **fields: object) -> None:
        if kind.listing and not name.startswith("_"):
            entries.append((name, kind.listing.format(unit=unit, **fields)))

    requested = {name for info in infos for _, name, _ in info.functions}
    for function in functions:
        if function.name not in requested and function.kind != "scalar":
            add(function.name, kind_spec(function.kind), shape=str(function.shape), end=end)
    for made in derived:
        if kind_spec(made.kind).scope == "module":
            add(made.name, kind_spec(made.kind), shape=str(made.shape), end=end)
    for info in infos:
        fields = {"frame": info.frame, "point": info.point, "at": info.point, "rows": ", ".join(info.row_names),
                  "wrench": ", ".join(info.wrench_names)}
        records = sorted(info.functions, key=lambda record: (kind_spec(record[0]).acceleration,
                                                             kind_spec(record[0]).derived))
        for kind, name, shape in records:
            add(name, kind_spec(kind), shape=str(shape), **fields)
    for function in functions:
        if function.kind == "scalar":  # the scalars follow the Jacobians' families
            add(function.name, kind_spec("scalar"))
    return tuple(entries)


def self_checks(infos: Sequence[JacobianInfo], dynamics: Sequence[str] = ()) -> tuple[Check, ...]:
    """The self-test: the pose, every Jacobian (with its torques), every acceleration-level family, the dynamics.

    ``dynamics`` names the functions the dynamics check calls (inverse dynamics, M, C, bias forces, g, forward
    dynamics), or nothing.
    """
    checks = [Check("pose", ("forward_kinematics",))]
    checks += [Check("jacobian", (info.jacobian, info.joint_torques, info.kinematics), info.rows) for info in infos]
    checks += [Check("acceleration", (info.jacobian, info.hessian, info.bias_acceleration, info.manipulability,
                                      info.manipulability_gradient), info.rows)
               for info in infos if info.hessian and info.bias_acceleration and info.manipulability_gradient]
    if dynamics:
        checks.append(Check("dynamics", tuple(dynamics)))
    return tuple(checks)


def request_lines(infos: Sequence[JacobianInfo]) -> tuple[tuple[str, str], ...]:
    """Each requested Jacobian's name and what it is, for the header of every file: frame, point and rows."""
    return tuple((info.jacobian, f"frame {info.frame}, at {info.point}, "
                  + ("all six rows [v; omega]." if len(info.rows) == 6 else f"rows {', '.join(info.row_names)}."))
                 for info in infos)


def defined_names(functions: Sequence[FunctionDescription], infos: Sequence[JacobianInfo]) -> set[str]:
    """Every function name the module defines: the lowered ones and those computed from a Jacobian."""
    return {f.name for f in functions} | {name for info in infos for _, name, _ in info.functions}


def scalar_descriptions(chain: Chain, scalars: Mapping[str, sp.Expr], functions: Sequence[FunctionDescription],
                        infos: Sequence[JacobianInfo], identifiers: IdentifierRule) -> list[FunctionDescription]:
    """The extra scalar functions of the joint variables and parameters, names checked against everything else."""
    model = chain.robot
    defined = defined_names(functions, infos)
    q_argument = Argument("q", tuple(s.name for s in model.q), _q_words(model))
    found: list[FunctionDescription] = []
    for scalar_name, expr in scalars.items():
        identifiers.check(scalar_name, "scalar function name", {**RESERVED, **{n: "a function" for n in defined}})
        if scalar_name.startswith("_") or scalar_name in {p.name for p in model.parameters}:
            raise CodegenError(f"scalar function name {scalar_name!r} is private or a parameter name")
        lowered = lower_function(angle_expansion(chain), [sp.sympify(expr)], (), (("q", model.q),),
                                 model.parameter_symbols, "given expression")
        returns = SCALAR.returns_text(model.coupling is not None, shape=())
        found.append(FunctionDescription(FunctionSpec(scalar_name, "scalar", f"The scalar function {scalar_name}",
                                                      (q_argument,), returns), lowered))
        defined.add(scalar_name)
    return found


def _q_words(robot: Robot) -> str:
    """What the entries of ``q`` are: the joint values, or a coupled robot's independent coordinates."""
    return "Joint values" if robot.coupling is None else "Independent coordinates"


