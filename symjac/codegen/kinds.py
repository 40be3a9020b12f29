"""The table of function kinds: what each kind of generated function returns, how it is documented and computed.

Every generated function has a kind. The kind decides, in this one place, what the templates would otherwise decide
by branching on its name: the words that document its result, the line that lists it in the module docstring, the
name of its output buffer in the C family, the flat index layout of a three-dimensional output, whether it exists
only for the self-test, and, for a kind *derived* from others (the manipulability from a Jacobian, its gradient
from the Jacobian and the Hessian), which runtime routine computes it from which functions. A later quantity spec
(mass matrix, inverse dynamics) adds a row here; the templates iterate over function descriptions and never name a
kind.

Texts are language-neutral and may use these fields: ``{unit}`` ("joint" or "coordinate"), ``{shape}``,
``{frame}``, ``{point}``, ``{rows}``, ``{wrench}`` and the names of the functions of the same Jacobian
(``{jacobian}``, ``{hessian}``, ``{manipulability}``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from symjac.errors import CodegenError

__all__ = ["CHECK_WORDS", "COUPLED_WORDS", "KINDS", "KindSpec", "kind_spec"]


@dataclass(frozen=True)
class KindSpec:
    """One kind of generated function.

    Parameters
    ----------
    name : str
        The kind (``"jacobian"``); also the base of its functions' names.
    returns : str
        What the result is, for a docstring's Returns section (fields allowed, see the module docstring).
    listing : str
        The line under the function's name in the module docstring's list of functions ("" for none).
    output : str
        The C family's name of its output buffer (``"J"``; a scalar is returned, and the name is that of its
        CasADi output), or empty.
    returns_coupled : str
        ``returns`` for a coupled robot, when it differs.
    layout : str
        How a flat (C) output of three dimensions is indexed, with ``{shape[1]}``, ``{shape[2]}`` (else "").
    selftest_only : bool
        The function exists for the self-test only (private, no compiled kernel).
    routine : str
        For a derived kind: the runtime routine that computes it from the results of its sources
        (``manipulability``: Python ``_manipulability``, C ``sj_manipulability``, C++ ``runtime::manipulability``).
    summary, details : str
        A derived kind's docstring summary line and further paragraph (a lowered kind's summary is made with it).
    """

    name: str
    returns: str
    listing: str = ""
    output: str = ""
    returns_coupled: str = ""
    layout: str = ""
    selftest_only: bool = False
    routine: str = ""
    summary: str = ""
    details: str = ""

    @property
    def derived(self) -> bool:
        """Whether functions of this kind are computed by a runtime routine from other functions."""
        return bool(self.routine)

    def returns_text(self, coupled: bool, **fields: object) -> str:
        """The Returns sentence, its fields filled (``unit`` from ``coupled``)."""
        text = self.returns_coupled if coupled and self.returns_coupled else self.returns
        return text.format(unit="coordinate" if coupled else "joint", **fields)


KINDS: Mapping[str, KindSpec] = MappingProxyType({spec.name: spec for spec in (
    KindSpec("forward_kinematics", "The homogeneous transform [[R, p], [0, 0, 0, 1]], row by row.",
             "The 4 x 4 pose of the tool frame in frame {{0}}.", output="T"),
    KindSpec("jacobian", "Rows as listed in the module docstring; column i belongs to {unit} i.",
             "The Jacobian in frame {frame} at point {point}, rows {rows}.", output="J"),
    KindSpec("joint_torques", "One torque (force, for a prismatic joint) per joint.",
             "Joint torques tau = J^T F of that Jacobian, F = ({wrench}).", output="tau",
             returns_coupled="One generalised force per coordinate, C^T J^T F."),
    KindSpec("kinematics", "Point position, ^0_nR and ^0_kR, row by row.", output="out", selftest_only=True),
    KindSpec("hessian", "``H[i, j, m]`` is the derivative of row i, column j of the Jacobian with respect to {unit} m.",
             "Its kinematic Hessian: H[i, j, m] = dJ[i, j]/dq_m, shape {shape}.", output="H",
             layout="H[(i * {shape[1]} + j) * {shape[2]} + m] = dJ[i][j]/dq_m"),
    KindSpec("bias_acceleration", "The rows of Jdot qdot: the acceleration [dv/dt; domega/dt] at zero {unit} "
             "acceleration.", "Its bias acceleration Jdot qdot, from q and the {unit} rates qdot.", output="out"),
    KindSpec("scalar", "The value of the expression.", "A scalar function of the joint values."),
    KindSpec("manipulability", "Zero exactly at a singular configuration (up to rounding).",
             "sqrt(det(J J^T)) of that Jacobian.", output="w", routine="manipulability",
             summary="Manipulability of ``{jacobian}``: |det J| when square, else sqrt(det(J J^T)) or "
                     "sqrt(det(J^T J))"),
    KindSpec("jacobian_determinant", "det J, LU with partial pivoting.", "det J of that (square) Jacobian.",
             output="det", routine="determinant", summary="Determinant of the square Jacobian ``{jacobian}``"),
    KindSpec("manipulability_gradient", "One derivative per {unit}.",
             "The gradient of its manipulability w with respect to q: dw/dq_m = w trace(J^+ H[:, :, m]).",
             output="gradient", routine="manipulability_gradient",
             summary="Gradient of ``{manipulability}``: dw/dq_m = w trace(J^+ H[:, :, m])",
             details="J^+ is the pseudo-inverse through the Gram matrix of the shorter side (J J^T, or J^T J for a "
                     "tall Jacobian), H the Hessian ``{hessian}``. Where w = 0 (a singular configuration) w has a "
                     "kink, not a gradient, and the result is zero there (zero lies in its subdifferential)."),
)})
"""Every kind of generated function, by name: lowered kinds first, then the derived ones."""


CHECK_WORDS: Mapping[str, str] = MappingProxyType({
    "jacobian": "every Jacobian against central differences of the module's own kinematics, and its joint torques "
                "against J^T F",
    "pose": "that the forward kinematics is a rigid transform",
    "acceleration": "the Hessians, bias accelerations and manipulability gradients against central differences of "
                    "the Jacobians and manipulabilities",
})
"""What each check of the self-test (:class:`~symjac.codegen.description.Check`) checks, for docstrings."""

COUPLED_WORDS = ("Every function takes q in these coordinates and computes theta(q) first: Jacobians are "
                 "J_q = J(theta(q)) C, joint torques C^T J^T F (one generalised force per coordinate), Hessians and "
                 "bias accelerations are those of J_q, with the coordinate rates qdot")
"""What the functions of a coupled robot's module compute, for its docstring."""


def kind_spec(kind: str) -> KindSpec:
    """The :class:`KindSpec` of ``kind``; :class:`~symjac.errors.CodegenError` naming the kinds if unknown."""
    try:
        return KINDS[kind]
    except KeyError:
        known = ", ".join(KINDS)
        raise CodegenError(f"internal error: unknown function kind {kind!r}; the kinds are {known}") from None
