"""The table of function kinds: what each kind of generated function returns, how it is documented and computed.

Every generated function has a kind, a :class:`~symjac.quantities.spec.Generated` record. The kind decides, in this
one place, what the templates would otherwise decide by branching on its name: where its functions sit in a module
(once per module or once per Jacobian request; with ``acceleration`` only), their arguments, the words that document
their result, the line that lists them in the module docstring, the name of their output buffer in the C family, the
flat index layout of a three-dimensional output, whether they exist only for the self-test, and either their lowering
or, for a kind *derived* from others (the manipulability from a Jacobian, its gradient from the Jacobian and the
Hessian), which runtime routine computes it from which functions.

:data:`KINDS` holds every quantity's kind (:data:`symjac.quantities.QUANTITIES`, in registry order), then code
generation's own, which are no quantity: the kinematics the self-test differentiates, scalar functions, the Jacobian's
determinant and the manipulability gradient. A new quantity brings its kind in its spec; nothing here changes, and
the templates iterate over function descriptions and never name a kind.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from symjac.errors import CodegenError
from symjac.quantities import QUANTITIES, Quantity
from symjac.quantities.spec import Generated, Scope

__all__ = ["CHECK_WORDS", "COUPLED_WORDS", "DYNAMICS_CHECKED", "IDENTIFICATION_CHECKED", "KINDS", "SCALAR",
           "generated_kinds", "kind_spec", "quantity_of"]

SCALAR = Generated("scalar", "The value of the expression.", "A scalar function of the joint values.",
                   scope="module")
"""The kind of the extra scalar functions a module is asked for (``scalars=``): no quantity, no lowering of its own."""

_DYNAMICS = "symjac.codegen.dynamics"
"""The module of the dynamics' lowerings."""

DYNAMICS_CHECKED = ("inverse_dynamics", "mass_matrix", "coriolis_matrix", "bias_forces", "gravity_torques",
                    "forward_dynamics", "potential_energy")
"""The dynamics' kinds, generated with ``dynamics=True`` once per module, in the order the self-test's dynamics check
takes their functions (the quantities' kinds are in their specs; the bias forces, forward dynamics and the
self-test's potential energy here)."""

_DYNAMICS_OWN = (
    Generated("bias_forces", "C(q, qdot) qdot + g(q), one per {unit}.",
              "The bias forces C(q, qdot) qdot + g(q): inverse dynamics at qddot = 0.", output="b", scope="module",
              dynamics=True, inputs=("qdot",), summary="Bias forces b = C(q, qdot) qdot + g(q)",
              lowering=f"{_DYNAMICS}:lowered_bias_forces"),
    Generated("forward_dynamics", "qddot, one acceleration per {unit}.",
              "Forward dynamics qddot = M^-1 (tau - b), by a Cholesky solve of M.", output="qddot", scope="module",
              dynamics=True, inputs=("qdot", "tau"), routine="forward_dynamics",
              sources=("mass_matrix", "bias_forces"), per_coordinate=True,
              summary="Forward dynamics qddot = M(q)^-1 (tau - C(q, qdot) qdot - g(q))",
              details="M = L L^T by Cholesky, then two triangular solves (no inverse is formed); M is the mass "
                      "matrix ``{mass_matrix}``, C qdot + g the bias forces ``{bias_forces}``."),
    Generated("potential_energy", "V(q), the potential energy of gravity.", scope="module", dynamics=True,
              selftest_only=True, function="_potential_energy",
              summary="Potential energy V(q) = -sum_i m_i g0^T p_ci (the self-test checks g = dV/dq with it)",
              lowering=f"{_DYNAMICS}:lowered_potential_energy"),
)
"""Code generation's own dynamics kinds: no quantity. Forward dynamics is derived (a Cholesky solve of the runtime
from the mass matrix and the bias forces); the potential energy exists for the self-test only (g = dV/dq)."""

IDENTIFICATION_CHECKED = (("regressor", "standard_values"), ("base_regressor", "base_values"))
"""With ``identification=True``: each regressor kind and the self-test-only kind of its parameters' values (the
robot's own), checked against inverse dynamics (Y(q, qdot, qddot) pi = tau)."""

_IDENTIFICATION_OWN = (
    Generated("standard_values", "The robot's own standard parameters, in the order of ``REGRESSOR_PARAMETERS``.",
              output="pi",
              scope="module", identification=True, selftest_only=True, function="_standard_values",
              summary="The robot's standard parameters pi (the self-test checks regressor pi = tau with them)",
              lowering="symjac.codegen.dynamics:lowered_standard_values"),
    Generated("base_values", "The robot's own base parameters, in the order of ``BASE_PARAMETERS``.",
              output="pi_b",
              scope="module", identification=True, selftest_only=True, function="_base_values",
              summary="The robot's base parameters pi_b (the self-test checks base_regressor pi_b = tau with them)",
              lowering="symjac.codegen.dynamics:lowered_base_values"),
)
"""Code generation's own identification kinds: the parameters' values the self-test multiplies the regressors by."""

_OWN = (
    Generated("kinematics", "Point position, ^0_nR and ^0_kR, row by row.", output="out", selftest_only=True,
              function="_kinematics",
              summary="Point position, ^0_nR and ^0_kR (the self-test differentiates them numerically)",
              lowering="symjac.codegen.coupled:coordinate_kinematics"),
    *_DYNAMICS_OWN,
    *_IDENTIFICATION_OWN,
    SCALAR,
    Generated("jacobian_determinant", "det J, LU with partial pivoting.", "det J of that (square) Jacobian.",
              output="det", routine="determinant", sources=("jacobian",), square_only=True,
              summary="Determinant of the square Jacobian ``{jacobian}``"),
    Generated("manipulability_gradient", "One derivative per {unit}.",
              "The gradient of its manipulability w with respect to q: dw/dq_m = w trace(J^+ H[:, :, m]).",
              output="gradient", routine="manipulability_gradient", sources=("jacobian", "hessian"),
              per_coordinate=True, acceleration=True,
              summary="Gradient of ``{manipulability}``: dw/dq_m = w trace(J^+ H[:, :, m])",
              details="J^+ is the pseudo-inverse through the Gram matrix of the shorter side (J J^T, or J^T J for a "
                      "tall Jacobian), H the Hessian ``{hessian}``. Where w = 0 (a singular configuration) w has a "
                      "kink, not a gradient, and the result is zero there (zero lies in its subdifferential)."),
)


def _table() -> Mapping[str, Generated]:
    kinds: dict[str, Generated] = {}
    for kind in (*(q.codegen for q in QUANTITIES.values() if q.codegen is not None), *_OWN):
        if kind.name in kinds:
            raise CodegenError(f"internal error: two function kinds are called {kind.name!r}")
        kinds[kind.name] = kind
    return MappingProxyType(kinds)


KINDS: Mapping[str, Generated] = _table()
"""Every kind of generated function, by name: the quantities' in registry order, then code generation's own."""

_QUANTITY_OF = MappingProxyType({q.codegen.name: q for q in QUANTITIES.values() if q.codegen is not None})


def quantity_of(kind: str) -> Quantity | None:
    """The quantity whose kind ``kind`` is (its derivation and coupling law), or None for one of codegen's own."""
    return _QUANTITY_OF.get(kind)


def generated_kinds(scope: Scope, acceleration: bool, dynamics: bool = False, identification: bool = False
                    ) -> tuple[Generated, ...]:
    """The kinds a module generates once per module or once per request, in the order it defines their functions.

    Lowered kinds first, in :data:`KINDS` order with those needing ``acceleration`` last (after the self-test's
    kinematics): within a request, the velocity level, then the acceleration level. Then the derived kinds, in
    :data:`KINDS` order. Scalar functions are asked for by name and are not among them; the dynamics' kinds only
    with ``dynamics``, the identification's (regressors) only with ``identification``.
    """
    wanted = [kind for kind in KINDS.values() if kind.scope == scope and kind is not SCALAR
              and (acceleration or not kind.acceleration) and (dynamics or not kind.dynamics)
              and (identification or not kind.identification)]
    lowered = [kind for kind in wanted if not kind.derived]
    lowered.sort(key=lambda kind: 2 if kind.acceleration else 1 if kind.selftest_only else 0)
    return (*lowered, *(kind for kind in wanted if kind.derived))


CHECK_WORDS: Mapping[str, str] = MappingProxyType({
    "jacobian": "every Jacobian against central differences of the module's own kinematics, and its joint torques "
                "against J^T F",
    "pose": "that the forward kinematics is a rigid transform",
    "acceleration": "the Hessians, bias accelerations and manipulability gradients against central differences of "
                    "the Jacobians and manipulabilities",
    "dynamics": "that M is symmetric positive definite, Mdot - 2C is skew (central differences of M along qdot), g "
                "and the columns of M are inverse dynamics at rest, tau = M qddot + C qdot + g, the bias forces are "
                "C qdot + g, forward dynamics inverts inverse dynamics, and g is the gradient of the potential energy "
                "(central differences)",
    "identification": "that the regressor times the robot's standard parameters, and the base regressor times its "
                      "base parameters, give inverse dynamics",
})
"""What each check of the self-test (:class:`~symjac.codegen.description.Check`) checks, for docstrings."""

COUPLED_WORDS = ("Every function takes q in these coordinates and computes theta(q) first: Jacobians are "
                 "J_q = J(theta(q)) C, joint torques C^T J^T F (one generalised force per coordinate), Hessians and "
                 "bias accelerations are those of J_q, with the coordinate rates qdot")
"""What the functions of a coupled robot's module compute, for its docstring."""


def kind_spec(kind: str) -> Generated:
    """The :class:`~symjac.quantities.spec.Generated` record of ``kind`` (an unknown kind: CodegenError)."""
    try:
        return KINDS[kind]
    except KeyError:
        known = ", ".join(KINDS)
        raise CodegenError(f"internal error: unknown function kind {kind!r}; the kinds are {known}") from None
