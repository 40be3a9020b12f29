"""Titles and captions of the results the command line prints (:mod:`symjac.printing.results` builds them)."""

from __future__ import annotations

from symjac.model.robot import Robot
from symjac.printing.document import Inline

__all__ = [
    "BIAS_ACCELERATION",
    "HOME_POSE",
    "LATEX_TOO_LONG",
    "RATE_MATRIX",
    "REPRESENTATION_COORDINATES",
    "SCREW_JACOBIAN_CAPTIONS",
    "derivative_caption",
    "fixed_transform_caption",
    "forward_kinematics_caption",
    "hessian_caption",
    "jacobian_caption",
    "point_phrase",
    "representation_caption",
    "title",
    "torques_caption",
]

_TITLES = {
    "show": "DH table and link transforms",
    "fk": "forward kinematics",
    "jacobian": "Jacobian in frame {}",
    "screw_jacobian": "{} Jacobian",
    "representation": "{} representation Jacobian",
    "derivative": "time derivative of the Jacobian in frame {}",
    "hessian": "kinematic Hessian in frame {}",
    "torques": "joint torques",
    "singularities": "singular configurations",
}

REPRESENTATION_COORDINATES = ("Representation coordinates",)
RATE_MATRIX = ("Rate matrix, ", Inline(r"\dot{x} = E(x)\,[v;\ \omega]", "xdot = E(x) [v; omega]"))
BIAS_ACCELERATION = ("Bias acceleration, the acceleration at zero joint acceleration",)
LATEX_TOO_LONG = ("ask for less: a frame in the middle of the chain (--frame K), where the halves stay short; a few "
                  "task rows (--rows, with singularities and codegen); no --steps; the same result as data "
                  "(--format json, a nested result with its definitions); or numeric code (symjac codegen)")
"""What to ask for instead of a LaTeX result too long to read."""


def title(robot: Robot, result: str, detail: object = "") -> str:
    """A result's title: ``puma560: Jacobian in frame 0`` (``result`` names a command, ``detail`` fills it in)."""
    return f"{robot.name}: {_TITLES[result].format(detail)}"


def fixed_transform_caption(source: object, target: object) -> tuple[str, ...]:
    """``Fixed tool transform`` before the transform to the tool (or from the world); nothing for a link."""
    if target == "tool":
        return ("Fixed tool transform",)
    return ("Fixed base transform",) if source == "world" else ()


def point_phrase(point: str, link: int | None = None, n: int | None = None) -> str:
    """Which point a result is at, in words: a named point of the last link (``n`` its frame), or one of link k.

    For a point fixed in link k (``--link``) ``the point (x,y,z) of frame {k} (fixed in link k)``; its origin when
    ``point`` is ``"origin"`` (or ``"wrist"``/``"flange"``, the origin's names on the last link).

    Examples
    --------
    >>> point_phrase("tool"), point_phrase("flange", n=6), point_phrase("wrist", n=6)
    ('the tool point', 'the origin of frame {6} (flange)', 'the origin of frame {6} (flange)')
    >>> point_phrase("wrist_centre"), point_phrase("0,0,1", n=2)
    ('the wrist centre (where the last three joint axes meet)', 'the point (0,0,1) of frame {2}')
    >>> point_phrase("origin", 2), point_phrase("0.1,0,0", 2)
    ('the origin of frame {2} (fixed in link 2)', 'the point (0.1,0,0) of frame {2} (fixed in link 2)')
    """
    last = "n" if n is None else n
    if link is None:
        named = {"tool": "the tool point", "flange": f"the origin of frame {{{last}}} (flange)",
                 "wrist": f"the origin of frame {{{last}}} (flange)",
                 "wrist_centre": "the wrist centre (where the last three joint axes meet)",
                 "reference": "the reference point"}
        return named.get(point, f"the point ({point}) of frame {{{last}}}")
    origin = point in ("origin", "wrist", "flange")
    where = f"the origin of frame {{{link}}}" if origin else f"the point ({point}) of frame {{{link}}}"
    return f"{where} (fixed in link {link})"


def forward_kinematics_caption(source: object, target: object, n: int) -> str:
    """Which pose ``symjac fk`` prints: of which frame, in which, and the point at its origin.

    Examples
    --------
    >>> forward_kinematics_caption(0, 6, 6)
    'Pose of frame {6} in frame {0}: the end of the chain, its origin the flange (the default point of the Jacobian)'
    """
    start = "the world frame" if source == "world" else f"frame {{{source}}}"
    end = "the tool frame" if target == "tool" else f"frame {{{target}}}"
    origin = "the tool point" if target == "tool" else "the flange" if target == n else f"the origin of {end}"
    return f"Pose of {end} in {start}: the end of the chain, its origin {origin} (the default point of the Jacobian)"


def jacobian_caption(point: str, method: str, link: int | None = None, n: int | None = None) -> str:
    """``Basic Jacobian at the tool point, differentiation``."""
    return f"Basic Jacobian at {point_phrase(point, link, n)}, {method.replace('_', ' ')}"


SCREW_JACOBIAN_CAPTIONS = {
    "space": ("Space Jacobian: column i is joint i's screw axis (w; v) in the space frame {0} at this configuration, "
              "V_s = J_s qdot",),
    "body": ("Body Jacobian: column i is joint i's screw axis (w; v) in the tool frame, V_b = J_b qdot = "
             "[Ad(T^-1)] J_s qdot",),
}
"""The caption of ``jacobian --kind space`` and ``--kind body`` (rows: angular part first, as in Lynch and Park)."""
HOME_POSE = ("Home pose of the tool frame; the forward kinematics is ",
             Inline(r"T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M",
                    "T(theta) = exp([S1] theta1) ... exp([Sn] thetan) M"))
"""The caption of a PoE robot's home pose M (``symjac show``)."""


def representation_caption(point: str, n: int | None = None) -> tuple[str]:
    r"""The caption of :math:`J_x = E(x)\,J`."""
    return (f"Representation Jacobian at {point_phrase(point, None, n)}",)


def derivative_caption(point: str, moving: bool, link: int | None = None, n: int | None = None) -> str:
    r"""The caption of :math:`\dot J`; ``moving`` when the frame turns with the joints."""
    turning = " (in a moving frame: its rotation is differentiated too)" if moving else ""
    return f"Time derivative of the basic Jacobian at {point_phrase(point, link, n)}{turning}"


def hessian_caption(joint: int, at: str = "") -> str:
    r"""The caption of the slice :math:`\partial J / \partial q_k` (``joint`` counts from 0; ``at`` the point)."""
    where = f" at {at}" if at else ""
    return f"Derivative of the Jacobian{where} with respect to joint {joint + 1}"


def torques_caption(frame: object, point: str, link: int | None = None, n: int | None = None) -> str:
    """``Joint torques for a wrench in frame 0 at the tool point``."""
    return f"Joint torques for a wrench in frame {frame} at {point_phrase(point, link, n)}"
