r"""Converting robot descriptions between conventions, with the base/tool transforms that make them equal.

Every conversion passes through a modified DH table. A convention's plug-in rewrites its table exactly when it can
(standard DH <-> modified DH: :mod:`symjac.model.conventions.standard`, where the algebra is written out); any other
chain (general joints, or a convention without an exact rewrite) gets its table from its joint axes at :math:`q = 0`
(:func:`dh_from_general`). Joint variables, offsets and parameters are unchanged, so forward kinematics from the
world frame to the tool frame and every Jacobian expressed in the world frame at the tool point are equal.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import sympy as sp

from symjac.errors import ConversionError
from symjac.kinematics.chain import Chain, chain_of
from symjac.model.conventions import carried_inertials, plugin
from symjac.model.conventions.dh import DHPlacement
from symjac.model.conventions.standard import modified_from_standard, standard_from_modified
from symjac.model.ends import last_frame
from symjac.model.exact_transforms import fixed_transform_from_matrix
from symjac.model.expressions import snap_angle
from symjac.model.robot import Convention, Joint, Robot
from symjac.symbolic.nested import inline, substitute
from symjac.symbolic.transforms import homogeneous, inverse_transform

__all__ = ["ConversionError", "DHExtraction", "axes_at_home", "convert", "converted",
           "dh_from_general", "modified_from_standard", "standard_from_modified"]


def convert(robot: Robot, to: Convention | str) -> Robot:
    """``robot`` in the convention ``to``; unchanged if it already is.

    Every robot converts to ``"standard"`` and ``"modified"`` DH (with base and tool transforms where no DH table
    alone describes it) and to ``"poe"`` (screws from its axes at home); a PoE robot also converts to ``"general"``.

    Examples
    --------
    >>> from symjac import load_robot
    >>> convert(load_robot("puma560"), "modified").convention
    Convention('modified')
    """
    return converted(robot, to)[0]


def converted(robot: Robot, to: Convention | str) -> tuple[Robot, tuple[str, ...]]:
    """:func:`convert`, and notes in words when the table needed a base or tool transform (measured axes only)."""
    target = Convention(to)
    if robot.convention is target:
        return robot, ()
    source, destination = plugin(robot.convention), plugin(target)
    notes: tuple[str, ...] = ()
    result = source.rewrite(robot, target) or destination.from_axes(robot.uncoupled, lambda: axes_at_home(robot))
    if result is None:  # through a modified-DH table: exact when the source's plug-in has one, else measured
        modified = source.to_modified(robot)
        if modified is None:
            frames, home = axes_at_home(robot)
            numeric = not any(F.free_symbols for F in (*frames, home))
            extraction = dh_from_general(robot, substitute_defaults=not numeric)
            modified, notes = extraction.robot, extraction.notes
            if not numeric:  # axes measured exactly need numbers: the table is the defaults', its limits too
                joints = tuple(replace(joint, limits=None if joint.limits is None else tuple(
                    limit.subs(robot.defaults) for limit in joint.limits)) for joint in modified.joints)
                modified = replace(modified, parameters=(), joints=joints)
                notes = (*notes, f"the DH table is numeric: its axes were measured with the parameters "
                                 f"({', '.join(p.name for p in robot.parameters)}) at their defaults")
        result = destination.from_modified(modified)
    if result is None:
        raise ConversionError(f"cannot convert {robot.name} from {robot.convention.value} to {target.value}")
    if robot.coupling is not None:  # the same joints in the same order keep their variables: the coupling carries over
        if result.joint_variables != robot.joint_variables:
            raise ConversionError(f"cannot convert {robot.name}: its joints are coupled and the {target.value} table "
                                  f"would change its joint variables")
        result = replace(result, coupling=robot.coupling)
    return _carried_drives(robot, carried_inertials(robot, result)), notes


def _carried_drives(source: Robot, result: Robot) -> Robot:
    """``result`` with ``source``'s drives: joint-space data, whatever the frames (lost parameters as numbers)."""
    if all(drive is None for drive in source.drives):
        return result
    lost = {s: v for s, v in source.defaults.items() if s not in set(result.parameter_symbols)}
    drives = tuple(None if drive is None else replace(drive, armature=drive.armature.xreplace(lost),
                                                      viscous=drive.viscous.xreplace(lost),
                                                      coulomb=drive.coulomb.xreplace(lost))
                   for drive in source.drives)
    return replace(result, drives=drives)


def axes_at_home(robot: Robot) -> tuple[list[sp.Matrix], sp.Matrix]:
    """The poses in frame {0} at zero joint values of each joint's axis frame and of the tool frame.

    A joint's axis frame has its z-axis along the axis and its origin on it; without a tool, frame {n} stands in.
    """
    chain = _exact_chain(robot.uncoupled)
    zero = dict.fromkeys(robot.joint_variables, sp.S.Zero)
    frames = [_at(chain.transform(0, chain.axis_frame(joint.index)), zero) for joint in robot.joints]
    home = _at(chain.transform(0, last_frame(robot)), zero)
    return frames, home


def _exact_chain(robot: Robot) -> Chain:
    """The robot's chain, exact even for generic geometry: a converted file keeps the numbers the source gave."""
    chain = chain_of(robot)
    return chain if not chain.nested else Chain(robot, nested=False)


def _at(transform: sp.MatrixBase, values: dict[sp.Symbol, sp.Expr]) -> sp.Matrix:
    """A transform of the chain with ``values`` substituted, written out (a nested chain's intermediates too)."""
    return sp.Matrix(transform.rows, transform.cols, inline(substitute(list(transform), values)))


@dataclass(frozen=True)
class DHExtraction:
    """A DH table found for a general chain: the modified-DH robot, and whether it needed base/tool transforms.

    ``needs_base`` / ``needs_tool`` say that frame {0} / the tool frame of the general chain is not a DH frame, so no
    DH table describes the chain without an extra fixed transform there; ``notes`` says so in words.
    """

    robot: Robot
    needs_base: bool
    needs_tool: bool
    notes: tuple[str, ...]


def _exact(expr: sp.Expr) -> sp.Expr:
    return sp.nsimplify(sp.radsimp(sp.expand(expr)), [sp.pi]) if expr.has(sp.Float) else sp.radsimp(sp.expand(expr))


def _unit(v: sp.Matrix) -> sp.Matrix:
    return (v / sp.sqrt(_exact(v.dot(v)))).applyfunc(_exact)


def _angle(sine: sp.Expr, cosine: sp.Expr) -> sp.Expr:
    angle = sp.atan2(_exact(sine), _exact(cosine))
    if angle.has(sp.atan2, sp.atan):
        snapped = snap_angle(sp.Rational(float(angle)))
        if not snapped.is_Rational:
            return snapped
    return angle


def dh_from_general(robot: Robot, *, substitute_defaults: bool = False) -> DHExtraction:
    r"""Extract a modified-DH table from a general chain (the joint axes at :math:`q = 0`), exactly.

    Frame {i} of the table lies on joint axis i at the foot of the common normal to axis i+1, with x along that
    normal (Craig's rules; for parallel axes the foot keeps :math:`d_i = 0`, for intersecting or coincident ones x is
    the cross product or the previous x). Frame {0} is the chain's frame {0} when its x-axis is a common normal to
    axis 1, otherwise frame {1} at :math:`q_1 = 0` and a base transform is needed; likewise a tool transform carries
    the last DH frame to the chain's frame {n} or tool frame. Joint variables keep their names and senses.

    With ``substitute_defaults`` the parameters take their numeric defaults first (the table is then numeric).

    Raises
    ------
    ConversionError
        If ``robot`` is not general or its frames are not numeric (symbolic parameters).

    Examples
    --------
    >>> from symjac import load_robot
    >>> extraction = dh_from_general(load_robot("panda.urdf", tip_link="panda_link8"))
    >>> [str(j.placement.alpha) for j in extraction.robot.joints]
    ['0', '-pi/2', 'pi/2', 'pi/2', '-pi/2', 'pi/2', 'pi/2']
    >>> extraction.needs_base, extraction.robot.tool.xyz
    (False, (0, 0, 107/1000))
    """
    if plugin(robot.convention).to_modified(robot) is not None:
        raise ConversionError(f"{robot.name} is already a DH table ({robot.convention.value})")
    if chain_of(robot).nested:  # exact geometry on generic axes does not reduce: refuse rather than work for minutes
        raise ConversionError(f"{robot.name}: its geometry is generic (joint axes not turned by multiples of pi/2), "
                              "and DH extraction is exact; keep it in its own convention (or as general joints)")
    chain = _exact_chain(robot)
    zero: dict[sp.Symbol, sp.Expr] = {q: sp.S.Zero for q in robot.joint_variables}
    if substitute_defaults:
        zero.update(robot.defaults)

    def at_zero(frame: int) -> sp.Matrix:
        return _at(chain.transform(0, frame), zero).applyfunc(_exact)

    # frames[i] is the frame on joint axis i (its z-axis), frames[0] the chain's frame {0}, last the chain's {n}
    frames = [at_zero(0), *(at_zero(chain.axis_frame(i)) for i in range(1, robot.n_joints + 1))]
    last = at_zero(robot.n_joints)
    if any(not e.is_number for F in (*frames, last) for e in F):
        raise ConversionError(f"{robot.name}: DH extraction needs numeric frames; substitute the parameters first")
    if any(F.has(sp.sin, sp.cos) for F in (*frames, last)):
        # exact geometry on sin/cos of generic constants (rpy = 0.3) does not reduce; refuse rather than hang
        raise ConversionError(f"{robot.name}: exact DH extraction needs origin angles that are multiples of pi/12")
    n = robot.n_joints
    origin = [F[:3, 3] for F in frames]
    z = [F[:3, 2] for F in frames]

    # frame {0}: the chain's own, if its x-axis is a common normal to axis 1
    x0, needs_base = frames[0][:3, 0], False
    if _exact(x0.dot(z[1])) == 0 and _exact((origin[1] - origin[0]).dot(x0.cross(z[1]))) == 0:
        D = [sp.eye(4)]
    else:
        D, needs_base = [frames[1]], True
    # frames {1}..{n}: origins p_i on axis i, x_i along the common normal to axis i+1
    for i in range(1, n + 1):
        previous = D[i - 1]
        x_prev, p_prev = previous[:3, 0], previous[:3, 3]
        # foot of the previous common normal on axis i: p_prev + a x_prev, then along z_i
        w = origin[i] - p_prev
        a_prev = _exact(w.dot(x_prev))
        foot = (p_prev + a_prev * x_prev).applyfunc(_exact)
        if i == n:
            x_i, p_i = _perpendicular(last[:3, 0], z[i]), foot
        else:
            c = z[i].cross(z[i + 1]).applyfunc(_exact)
            if any(e != 0 for e in c):
                x_i = _unit(c)
                between = origin[i + 1] - origin[i]
                s = _exact(between.cross(z[i + 1]).dot(c) / c.dot(c))
                p_i = (origin[i] + s * z[i]).applyfunc(_exact)
                x_i = _oriented(x_i, frames[i][:3, 0], origin[i + 1] - p_i)
            else:  # parallel axes: keep d_i = 0
                p_i = foot
                between = origin[i + 1] - p_i
                perpendicular = (between - between.dot(z[i]) * z[i]).applyfunc(_exact)
                x_i = _unit(perpendicular) if any(e != 0 for e in perpendicular) else _perpendicular(x_prev, z[i])
                x_i = _oriented(x_i, frames[i][:3, 0], perpendicular)
        y_i = z[i].cross(x_i).applyfunc(_exact)
        D.append(homogeneous(sp.Matrix.hstack(x_i, y_i, z[i]), p_i))
    joints = []
    for i, joint in enumerate(robot.joints, start=1):
        previous, current = D[i - 1], D[i]
        x_prev, z_prev = previous[:3, 0], previous[:3, 2]
        x_i, z_i = current[:3, 0], current[:3, 2]
        w = current[:3, 3] - previous[:3, 3]
        alpha = _angle(z_prev.cross(z_i).dot(x_prev), z_prev.dot(z_i))
        a = _exact(w.dot(x_prev))
        d = _exact(w.dot(z_i))
        theta = _angle(x_prev.cross(x_i).dot(z_i), x_prev.dot(x_i))
        if any(_exact(e) != 0 for e in w - a * x_prev - d * z_i):
            raise ConversionError(f"{robot.name}, joint {i}: internal error, frames are not DH frames")
        # the frames were taken at q = 0 with the joints' own offsets, so d and theta are the DH offsets
        joints.append(Joint(index=i, type=joint.type, placement=DHPlacement(alpha, a), d=d, theta=theta,
                            limits=joint.limits))
    # the chain's frame {n} seen from the last DH frame is constant (both turn with joint n)
    E = (inverse_transform(D[n]) * last).applyfunc(_exact)
    tool_matrix = E * sp.Matrix(robot.tool.matrix).xreplace(zero) if robot.tool is not None else E
    tool_matrix = tool_matrix.applyfunc(_exact)
    needs_tool = tool_matrix != sp.eye(4)
    base_matrix = (sp.Matrix(robot.base.matrix).xreplace(zero) if robot.base else sp.eye(4)) * D[0]
    base_matrix = base_matrix.applyfunc(_exact)
    notes = []
    if needs_base:
        notes.append("frame {0} of the chain is not a DH frame: the table needs a base transform")
    if needs_tool:
        notes.append("the tool frame is not the last DH frame: the table needs a tool transform")
    result = Robot(name=robot.name, convention=Convention.MODIFIED, joints=tuple(joints),
                   parameters=() if substitute_defaults else robot.parameters, description=robot.description,
                   base=None if base_matrix == sp.eye(4) else fixed_transform_from_matrix(base_matrix),
                   tool=None if not needs_tool else fixed_transform_from_matrix(tool_matrix), source=robot.source)
    return DHExtraction(result, needs_base, needs_tool, tuple(notes))


def _oriented(x: sp.Matrix, chain_x: sp.Matrix, towards: sp.Matrix) -> sp.Matrix:
    """``x`` or ``-x``: along the chain's own x-axis when it is not perpendicular (fewest offsets), else a >= 0."""
    for reference in (chain_x, towards):
        sign = _exact(x.dot(reference))
        if sign != 0:
            return x if sign > 0 else -x
    return x


def _perpendicular(x: sp.Matrix, z: sp.Matrix) -> sp.Matrix:
    """``x`` made perpendicular to the unit ``z`` (or any perpendicular when ``x`` is parallel to it), unit."""
    v = (x - x.dot(z) * z).applyfunc(_exact)
    if all(e == 0 for e in v):
        for e in (sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0])):
            v = (e - e.dot(z) * z).applyfunc(_exact)
            if any(c != 0 for c in v):
                break
    return _unit(v)
