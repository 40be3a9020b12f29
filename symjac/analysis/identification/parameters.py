r"""The standard dynamic parameters of an arm: ten per link, about the link origin, and optional drive parameters.

Link i (the body joint i moves, frame {i}) contributes, in this order (Khalil's names),

.. math::
    \pi_i = [XX_i, XY_i, XZ_i, YY_i, YZ_i, ZZ_i, MX_i, MY_i, MZ_i, M_i]^T

with :math:`M_i = m_i`, the first moments :math:`[MX_i, MY_i, MZ_i]^T = m_i c_i` and the inertia tensor **about the
origin of frame {i}, axes of {i}**:

.. math::
    I_{o,i} = \begin{bmatrix} XX_i & XY_i & XZ_i \\ XY_i & YY_i & YZ_i \\ XZ_i & YZ_i & ZZ_i \end{bmatrix}
    = I_{c,i} + m_i\left(\lVert c_i\rVert^2 E - c_i c_i^T\right)

(:math:`I_{c,i}` about the centre of mass, as :class:`~symjac.model.inertia.Inertial` stores it). The dynamics are
linear in these, not in :math:`m, c, I_c`. Joint j may add, after link j's ten and only when asked, its drive
parameters: the armature ``Ia{j}`` (reflected rotor inertia :math:`J_m G^2`), viscous friction ``Fv{j}``, Coulomb
friction ``Fc{j}`` and a torque offset ``Fo{j}``.
"""

from __future__ import annotations

import sympy as sp

from symjac.analysis.dynamics.bodies import link_bodies
from symjac.errors import ArgumentError
from symjac.kinematics.chain import Chain, as_chain
from symjac.model.robot import Robot

__all__ = ["DRIVE_NAMES", "LINK_NAMES", "standard_parameters", "standard_values"]

LINK_NAMES: tuple[str, ...] = ("XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M")
"""The ten parameters of a link, in order (the link number follows: ``XX2``)."""

DRIVE_NAMES: tuple[str, ...] = ("Ia", "Fv", "Fc", "Fo")
"""The drive parameters of a joint, in order: armature, viscous, Coulomb friction, offset (``Fv3``)."""


def _symbol(name: str, index: int) -> sp.Symbol:
    return sp.Symbol(f"{name}{index}", real=True)


def standard_parameters(robot: Robot | Chain, *, armature: bool = False, viscous: bool = False,
                        coulomb: bool = False, offset: bool = False) -> tuple[sp.Symbol, ...]:
    """The standard parameters of ``robot`` in column order: per link its ten, then the drive parameters asked for.

    A robot parameter with one of these names would be confused with it: that is refused.

    Examples
    --------
    >>> from symjac import load_robot
    >>> standard_parameters(load_robot("planar2r"), viscous=True)[8:]
    (MZ1, M1, Fv1, XX2, XY2, XZ2, YY2, YZ2, ZZ2, MX2, MY2, MZ2, M2, Fv2)
    """
    model = as_chain(robot).robot
    drives = [name for name, asked in zip(DRIVE_NAMES, (armature, viscous, coulomb, offset), strict=True) if asked]
    symbols = [_symbol(name, j) for j in range(1, model.n_joints + 1) for name in (*LINK_NAMES, *drives)]
    taken = {parameter.name for parameter in model.parameters}
    clash = [symbol.name for symbol in symbols if symbol.name in taken]
    if clash:
        raise ArgumentError(f"{model.name}: the parameter {clash[0]!r} has the name of a standard dynamic parameter "
                            f"(XX<i> .. M<i>, Ia<j>, Fv<j>, Fc<j>, Fo<j>); rename it in the robot file")
    return tuple(symbols)


def standard_values(robot: Robot | Chain) -> dict[sp.Symbol, sp.Expr]:
    r"""The robot's own inertial data as values of the standard parameters (module docstring), and its drive data.

    Entries are expressions in the robot's parameters where its inertial data are symbolic (``m2``, ``cx2``, ...).
    Drive parameters (``Ia{j}``, ``Fv{j}``, ``Fc{j}``) are given for the joints whose model carries drive data
    (``Robot.drives``, where the model has them); there is no offset in a model.

    Examples
    --------
    >>> from symjac import load_robot
    >>> values = standard_values(load_robot("planar2r"))
    >>> values[sp.Symbol("MX2", real=True)], values[sp.Symbol("ZZ2", real=True)]
    (cx2*m2, Izz2 + cx2**2*m2 + cy2**2*m2)
    """
    chain = as_chain(robot)
    model = chain.robot
    values: dict[sp.Symbol, sp.Expr] = {}
    for i, body in enumerate(link_bodies(chain), start=1):
        I_o = body.inertia_about_origin
        entries = [I_o[0, 0], I_o[0, 1], I_o[0, 2], I_o[1, 1], I_o[1, 2], I_o[2, 2],
                   *(sp.expand(body.mass * c) for c in body.com), body.mass]
        values.update({_symbol(name, i): value for name, value in zip(LINK_NAMES, entries, strict=True)})
    for j, drive in enumerate(getattr(model, "drives", None) or (), start=1):  # drive data, where the model has them
        if drive is not None:
            for name, field in zip(DRIVE_NAMES[:3], ("armature", "viscous", "coulomb"), strict=True):
                values[_symbol(name, j)] = sp.sympify(getattr(drive, field))
    return values
