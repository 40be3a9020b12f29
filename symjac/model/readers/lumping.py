r"""Lumping a tree's bodies into the chain links that carry them: inertial data in symjac's frames {i}.

A reader gives each link's inertial data in the link's own frame (:class:`~symjac.model.readers.tree.LinkInertial`);
the chain's link *i* is the child of moving joint *i* together with every body fixed to it, expressed in frame {i}
(the child link turned by the alignment that takes z onto the joint axis).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import sympy as sp

from symjac.errors import InertialWarning, RobotFileError, warn
from symjac.model.expressions import exact_number
from symjac.model.inertia import Inertial, combined_inertial, inertial_problem
from symjac.symbolic.transforms import alignment, compose, homogeneous

if TYPE_CHECKING:
    from symjac.model.readers.tree import LinkInertial

__all__ = ["link_inertial"]


def link_inertial(axis: Sequence[sp.Expr], link: str, bodies: Mapping[str, LinkInertial | None],
                  fixed_children: Mapping[str, Sequence[tuple[str, sp.MatrixBase]]],
                  source: str) -> Inertial | None:
    r"""The inertial data of chain ``link``, driven by a joint along ``axis``, in symjac's frame {i} (None if none).

    ``bodies`` holds every link's inertial data as its file gives it, ``fixed_children`` the links fixed to each
    link with the transform from its frame to theirs. The link is :math:`L` and every link fixed to it: through
    fixed joints, on the chain or beside it, and through moving joints off the chain, which symjac holds at zero
    (the Panda's fingers ride with its hand, a torso's head with the torso). Body :math:`X`, with its inertial
    frame {c} at :math:`T_{X,c}` and tensor :math:`I` about its centre, is expressed in {i} by :math:`T_{i,X} =
    A_i^{-1}\,T_{L,X}` (frame {i} is :math:`L` turned by the alignment :math:`A_i`): :math:`c_i = R\,p_{X,c} + p`,
    :math:`I_i = R\,R_{X,c}\,I\,R_{X,c}^T R^T`; several bodies are combined by the parallel-axis theorem
    (:func:`~symjac.model.inertia.combined_inertial`). A link without ``<inertial>`` has no mass.
    """
    R_A = compose(alignment(axis))[0]
    start = homogeneous(R_A.T, sp.zeros(3, 1))
    parts = []
    stack = [(link, start)]
    while stack:
        name, T_i_X = stack.pop()
        body = bodies[name]
        if body is not None:
            own = Inertial(body.mass, body.xyz, _rotated(body.tensor, sp.Matrix(body.origin.matrix)[:3, :3]))
            problem = inertial_problem(own, physical=False)
            if problem is not None:
                raise RobotFileError(problem, source=source, field=f"link {name} inertial")
            problem = inertial_problem(own)
            if problem is not None:  # CAD exports round into these: read the file, say so (pinocchio reads it too)
                warn(InertialWarning(f"{source}, link {name}: {problem} (kept as given; the dynamics refuse "
                                     f"it)"))
            parts.append(_plain(own.expressed_in(T_i_X)))
        # plain numbers as the bodies pile up: exact products of generic rotations grow with every joint of a tree
        stack += [(child, (T_i_X * transform).applyfunc(_plain_number))
                  for child, transform in fixed_children.get(name, ())]
    if not parts:
        return None
    return _plain(parts[0] if len(parts) == 1 else combined_inertial(parts))


def _plain_number(value: sp.Expr) -> sp.Expr:
    """``value`` if it is a rational number, else the rational of its float (``cos(3/10)/4`` as 0.2388...)."""
    return value if value.is_Rational else exact_number(float(value))


def _plain(inertial: Inertial) -> Inertial:
    """``inertial`` with every entry that is not a rational number (``cos(3/10)/4``) as the rational of its float.

    Exact forms pay for kinematics, where a textbook form exists; a tensor turned by a generic angle has none, and
    rational entries keep the data cheap for the dynamics and writable in a robot file. Lumping a humanoid's torso
    (both arms and the head held at zero) multiplies a dozen generic rotations: kept exact, that took minutes.
    """
    com = tuple(_plain_number(v) for v in inertial.com)
    tensor = sp.ImmutableMatrix(inertial.inertia.applyfunc(_plain_number))
    return Inertial(_plain_number(inertial.mass), com, tensor)  # type: ignore[arg-type]


def _rotated(tensor: sp.MatrixBase, R: sp.MatrixBase) -> sp.ImmutableMatrix:
    r""":math:`R\,I\,R^T`: a tensor given along the axes of a frame turned by ``R``, along the original axes."""
    return sp.ImmutableMatrix((R * tensor * R.T).applyfunc(sp.expand))
