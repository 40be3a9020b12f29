"""Typed errors raised by symjac.

Every error symjac raises on purpose derives from :class:`SymjacError`, so a caller (or the CLI) can catch the
whole family in one place. Messages say *what* is wrong and *where* (file, joint, field).
"""

from __future__ import annotations

__all__ = [
    "ArgumentError",
    "CodegenError",
    "ConversionError",
    "ExpressionError",
    "FrameError",
    "ImpossibleInertiaError",
    "InertialWarning",
    "NoClosedFormError",
    "NoInertialDataError",
    "OrientationNeededError",
    "RepresentationError",
    "ResultTooLargeError",
    "RobotFileError",
    "SymjacError",
    "UnknownRobotError",
    "warn",
]


class SymjacError(Exception):
    """Base class of every error symjac raises on purpose."""


class RobotFileError(SymjacError, ValueError):
    """A robot description (TOML file or mapping) is malformed.

    Parameters
    ----------
    message : str
        What is wrong, in one sentence.
    source : str
        The file path or ``"<mapping>"`` the description came from.
    joint : int, optional
        1-based joint number the problem is in.
    field : str, optional
        Name of the offending field (``"alpha"``, ``"parameters.a2"``, ...).
    """

    def __init__(self, message: str, *, source: str, joint: int | None = None, field: str | None = None):
        self.message = message
        self.source = source
        self.joint = joint
        self.field = field
        where = [source]
        if joint is not None:
            where.append(f"joint {joint}")
        if field is not None:
            where.append(f"field '{field}'")
        super().__init__(f"{', '.join(where)}: {message}")


class ExpressionError(SymjacError, ValueError):
    """A field expression is not in the accepted grammar (numbers, names, ``+ - * / **``, ``pi``)."""


class UnknownRobotError(SymjacError, LookupError):
    """A robot name is neither in the catalog nor an existing file."""


class FrameError(SymjacError, ValueError):
    """A frame, point or method argument does not exist for this robot."""


class ArgumentError(SymjacError, ValueError):
    """An argument is not one of its choices or has the wrong shape (unknown method, row name, wrench length, ...)."""


class OrientationNeededError(ArgumentError):
    """A target gave a position only, to an arm that sets its orientation too (inverse kinematics)."""


class RepresentationError(SymjacError, ValueError):
    """An unknown representation, a malformed input, or a pose at a representation singularity."""


class CodegenError(SymjacError, ValueError):
    """A request for generated code cannot be honoured (bad name, unsupported expression, unknown target, ...)."""


class ConversionError(SymjacError, ValueError):
    """A robot cannot be written in the requested convention."""


class InertialWarning(UserWarning):
    """Inertial data in a robot description that no rigid body can have, kept as the file gives it.

    A tensor that is not positive semi-definite or whose principal moments break the triangle inequality: CAD exports
    round into these often, and a URDF file is still read (its kinematics does not depend on them).
    """


def warn(warning: Warning) -> None:
    """Issue ``warning`` about the caller's input, pointing at the first frame outside symjac (the user's line)."""
    import sys
    import warnings
    from pathlib import Path

    package = str(Path(__file__).resolve().parent)
    frame = sys._getframe(1)
    level = 2  # stacklevel 2 is the frame that called this function
    while frame.f_back is not None and str(Path(frame.f_code.co_filename).resolve()).startswith(package):
        frame, level = frame.f_back, level + 1
    warnings.warn(warning, stacklevel=level)


class ResultTooLargeError(SymjacError, ArithmeticError):
    """A symbolic result would be too large to write out (see :data:`symjac.symbolic.size.TERM_LIMIT`).

    Raised early, as soon as the normal forms pass the limit, so that a request whose answer grows exponentially
    with the chain (the frame-{0} Jacobian of a long chain of non-parallel axes) ends in seconds, not hours.
    """

    def __init__(self, terms: int, limit: int):
        self.terms, self.limit = terms, limit
        super().__init__(
            f"written out, this result has more than {limit:,} terms ({terms:,} so far) and it grows with every link; "
            "narrow the request: fewer joints; a frame in the middle of the chain, where each half stays short (for a "
            "Jacobian: --frame K --method cross_product); or numeric code (`symjac codegen`; simplify=False in "
            "Python), which shares subexpressions instead")


class NoClosedFormError(SymjacError, ArithmeticError):
    """A closed form does not exist or is not available: generic geometry, or an arm no inverse-kinematics family fits.

    Analyses of results built nested (generic geometry, see :mod:`symjac.symbolic.nested`) raise it with the
    default message. Closed-form inverse kinematics raises it with ``reason=``, the one-line message saying why no
    family fits (which axes miss, by how much at the defaults).

    Determinants, singular factors and trigonometric identities need the expressions written out; for generic
    geometry (calibrated twists, identified screw axes) those have no textbook form and grow exponentially with the
    chain, so symjac says so instead of working for hours.
    """

    def __init__(self, what: str = "closed forms (determinants, singular sets, identities)", *,
                 reason: str | None = None):
        if reason is not None:  # closed-form inverse kinematics: the message is why no family fits
            super().__init__(reason)
            return
        super().__init__(
            f"{what} are not available for this robot: its geometry is generic (constant rotations between joint "
            "axes that are not multiples of pi/2), so its results are built nested, frame by frame, with named "
            "intermediate values; evaluate them numerically instead (symjac.numeric_jacobian, `symjac codegen`), "
            "or write the angles exactly (pi/2, or a parameter) where the design has them")



class NoInertialDataError(SymjacError, ValueError):
    """A dynamics request on a robot some of whose links have no inertial data (the message names them)."""


class ImpossibleInertiaError(SymjacError, ValueError):
    """A dynamics request on a link whose inertial data no rigid body can have (the message names the link and why).

    Files with such data are read, with an :class:`InertialWarning` (their kinematics do not depend on it); the
    dynamics refuse them unless the data say ``keep_impossible`` (published parameters kept as published).
    """
