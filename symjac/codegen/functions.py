"""The functions of a generated module, as language-neutral descriptions: named, documented from the kinds table.

Forward kinematics, then per Jacobian request its Jacobian, torques and kinematics (and with ``acceleration`` its
Hessian and bias acceleration), each lowered (:mod:`~symjac.codegen.lower`, coupled robots through
:mod:`~symjac.codegen.coupled`); the functions derived from those by the runtime (manipulability, determinant,
gradient); the module docstring's list of functions. What each kind returns and how it is documented comes from
:data:`~symjac.codegen.kinds.KINDS`: this is the one place that fills it in.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy as sp

from symjac.codegen.coupled import (
    coordinate_bias_acceleration,
    coordinate_forward_kinematics,
    coordinate_hessian,
    coordinate_jacobian,
    coordinate_kinematics,
    coordinate_torques,
)
from symjac.codegen.description import (
    Argument,
    Check,
    DerivedFunction,
    FunctionDescription,
    FunctionKind,
    FunctionSpec,
    JacobianInfo,
)
from symjac.codegen.kinds import kind_spec
from symjac.codegen.lower import LoweredFunction, angle_expansion, lower_function
from symjac.codegen.names import RESERVED, IdentifierRule
from symjac.codegen.printers import float_literal
from symjac.codegen.request import (
    JacobianRequest,
    Strategy,
    check_rows,
    frame_text,
    function_labels,
    point_text,
    point_words,
)
from symjac.errors import CodegenError
from symjac.kinematics.chain import Chain
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.model.robot import WRENCH_NAMES, Robot

__all__ = [
    "defined_names",
    "derived_functions",
    "function_descriptions",
    "listing",
    "request_lines",
    "scalar_descriptions",
    "self_checks",
]


def function_descriptions(chain: Chain, requests: Sequence[JacobianRequest], strategy: Strategy, acceleration: bool
                          ) -> tuple[list[FunctionDescription], list[JacobianInfo]]:
    """Forward kinematics, then per Jacobian request its Jacobian, torques, kinematics (and acceleration functions)."""
    model = chain.robot
    q_argument = Argument("q", tuple(s.name for s in model.q), _q_words(model))
    coupled = ", in the coordinates (J_q = J C)" if model.coupling is not None else ""
    rates = tuple(s.name for s in joint_rate_symbols(chain)) if acceleration else ()
    functions: list[FunctionDescription] = []

    def add(lowered: LoweredFunction, name: str, kind: FunctionKind, summary: str, *arguments: Argument) -> None:
        returns = kind_spec(kind).returns_text(bool(coupled), shape=lowered.shape)
        functions.append(FunctionDescription(FunctionSpec(name, kind, summary, (q_argument, *arguments), returns),
                                             lowered))

    add(coordinate_forward_kinematics(chain, strategy), "forward_kinematics", "forward_kinematics",
        "The pose of the tool frame in frame {0}")
    infos: list[JacobianInfo] = []
    for request, label in zip(requests, function_labels(model, requests), strict=True):
        point_name, point = point_text(model, request.point)
        selected = check_rows(request.rows)
        names = {kind: f"{kind}{label}" for kind in ("jacobian", "joint_torques", "manipulability",
                                                      "jacobian_determinant", "_kinematics", "hessian",
                                                      "bias_acceleration", "manipulability_gradient")}
        J = coordinate_jacobian(chain, request.frame, point, selected, strategy)
        where, at = frame_text(request.frame), point_words(point_name)
        add(J, names["jacobian"], "jacobian", f"The basic Jacobian [v; omega] at the {at}, in frame {where}{coupled}")
        add(coordinate_torques(chain, request.frame, point, selected, strategy), names["joint_torques"],
            "joint_torques", f"Joint torques tau = {'C^T ' if coupled else ''}J^T F holding a wrench F at the {at}, "
            f"F in frame {where}",
            Argument("wrench", tuple(WRENCH_NAMES[r] for r in selected), "Wrench (force, moment) at the point"))
        add(coordinate_kinematics(chain, request.frame, point), names["_kinematics"], "kinematics",
            "Point position, ^0_nR and ^0_kR (the self-test differentiates them numerically)")
        if acceleration:
            add(coordinate_hessian(chain, request.frame, point, selected, strategy), names["hessian"], "hessian",
                f"The kinematic Hessian H[i, j, m] = dJ[i, j]/dq_m of ``{names['jacobian']}``")
            add(coordinate_bias_acceleration(chain, request.frame, point, selected, strategy),
                names["bias_acceleration"], "bias_acceleration",
                f"The bias acceleration Jdot qdot of ``{names['jacobian']}`` (the acceleration at zero qddot)",
                Argument("qdot", rates, "Coordinate rates" if coupled else "Joint rates"))
        infos.append(JacobianInfo(
            jacobian=names["jacobian"], joint_torques=names["joint_torques"], manipulability=names["manipulability"],
            determinant=names["jacobian_determinant"] if len(selected) == model.n_coordinates else None,
            kinematics=names["_kinematics"], frame=where, point=point_name,
            point_values=tuple(float_literal(v.subs(model.defaults)) for v in point),  # type: ignore[arg-type]
            rows=selected, row_names=tuple(ROW_NAMES[r] for r in selected),
            wrench_names=tuple(WRENCH_NAMES[r] for r in selected),
            **({"hessian": names["hessian"], "bias_acceleration": names["bias_acceleration"],
                "manipulability_gradient": names["manipulability_gradient"]} if acceleration else {}),
        ))
    return functions, infos


def derived_functions(infos: Sequence[JacobianInfo], n: int, coupled: bool) -> list[DerivedFunction]:
    """Per Jacobian: its manipulability, its determinant (square only), its manipulability gradient (acceleration).

    Each is computed at run time by the runtime routine of its kind (:data:`~symjac.codegen.kinds.KINDS`) from the
    results of its sources: the Jacobian, and the Hessian for the gradient.
    """
    found: list[DerivedFunction] = []
    for info in infos:
        fields = {"jacobian": info.jacobian, "hessian": info.hessian or "", "manipulability": info.manipulability}
        Source = tuple[str, FunctionKind, tuple[int, ...]]
        jacobian: Source = (info.jacobian, "jacobian", (len(info.rows), n))
        hessian: Source = (info.hessian or "", "hessian", (len(info.rows), n, n))
        wanted: list[tuple[str | None, FunctionKind, tuple[Source, ...], tuple[int, ...]]] = [
            (info.manipulability, "manipulability", (jacobian,), ()),
            (info.determinant, "jacobian_determinant", (jacobian,), ()),
            (info.manipulability_gradient, "manipulability_gradient", (jacobian, hessian), (n,)),
        ]
        for name, kind, sources, shape in wanted:
            if name is None:
                continue
            spec = kind_spec(kind)
            found.append(DerivedFunction(
                name=name, kind=kind, summary=spec.summary.format(**fields), details=spec.details.format(**fields),
                returns=spec.returns_text(coupled, shape=shape), sources=tuple(s[0] for s in sources),
                source_kinds=tuple(s[1] for s in sources), source_shapes=tuple(s[2] for s in sources),
                routine=spec.routine, shape=shape))
    return found


def listing(functions: Sequence[FunctionDescription], derived: Sequence[DerivedFunction],
            infos: Sequence[JacobianInfo], n: int, coupled: bool) -> tuple[tuple[str, str], ...]:
    """Every public function with its line for the module docstring, in the order of the docstring.

    Forward kinematics, each Jacobian's family, the scalars; the lines from
    :attr:`~symjac.codegen.kinds.KindSpec.listing`.
    """
    kinds: dict[str, str] = {f.name: f.kind for f in functions}
    kinds |= {d.name: d.kind for d in derived}
    entries: list[tuple[str, str]] = []

    def add(name: str | None, **fields: object) -> None:
        if name is not None:
            text = kind_spec(kinds[name]).listing
            entries.append((name, text.format(unit="coordinate" if coupled else "joint", **fields)))

    add("forward_kinematics")
    for info in infos:
        fields = {"frame": info.frame, "point": info.point, "rows": ", ".join(info.row_names),
                  "wrench": ", ".join(info.wrench_names), "shape": f"({len(info.rows)}, {n}, {n})"}
        for name in (info.jacobian, info.joint_torques, info.manipulability, info.determinant, info.hessian,
                     info.bias_acceleration, info.manipulability_gradient):
            add(name, **fields)
    for function in functions:
        if function.kind == "scalar":  # the scalars follow the Jacobians' families
            add(function.name)
    return tuple(entries)


def self_checks(infos: Sequence[JacobianInfo]) -> tuple[Check, ...]:
    """The self-test: the pose, then every Jacobian (with its torques), then every acceleration-level family."""
    checks = [Check("pose", ("forward_kinematics",))]
    checks += [Check("jacobian", (info.jacobian, info.joint_torques, info.kinematics), info.rows) for info in infos]
    checks += [Check("acceleration", (info.jacobian, info.hessian, info.bias_acceleration, info.manipulability,
                                      info.manipulability_gradient), info.rows)
               for info in infos if info.hessian and info.bias_acceleration and info.manipulability_gradient]
    return tuple(checks)


def request_lines(infos: Sequence[JacobianInfo]) -> tuple[tuple[str, str], ...]:
    """Each requested Jacobian's name and what it is, for the header of every file: frame, point and rows."""
    return tuple((info.jacobian, f"frame {info.frame}, point {info.point}, rows {', '.join(info.row_names)}.")
                 for info in infos)


def defined_names(functions: Sequence[FunctionDescription], infos: Sequence[JacobianInfo]) -> set[str]:
    """Every function name the module defines: the lowered ones and those computed from a Jacobian."""
    defined = {f.name for f in functions} | {i.manipulability for i in infos}
    defined |= {i.determinant for i in infos if i.determinant}
    return defined | {i.manipulability_gradient for i in infos if i.manipulability_gradient}


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
        returns = kind_spec("scalar").returns_text(model.coupling is not None, shape=())
        found.append(FunctionDescription(FunctionSpec(scalar_name, "scalar", f"The scalar function {scalar_name}",
                                                      (q_argument,), returns), lowered))
        defined.add(scalar_name)
    return found


def _q_words(robot: Robot) -> str:
    """What the entries of ``q`` are: the joint values, or a coupled robot's independent coordinates."""
    return "Joint values" if robot.coupling is None else "Independent coordinates"


