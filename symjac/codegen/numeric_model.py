r"""A robot compiled for numbers: forward kinematics and one Jacobian as fast NumPy functions, from Python.

:func:`numeric_model` generates the robot's numeric module (the ``"c"`` target, else ``"numpy"`` with the plain
``"python"`` target for single configurations), loads it in memory and wraps its functions in a
:class:`NumericModel`: ``model.fk(q)`` and ``model.jacobian(q)`` take one configuration (shape ``(n,)``) or a batch
(shape ``(N, n)``, or any ``(..., n)``) and return NumPy arrays. The model is kept in the robot's chain, one per
frame, point and backend; the C extension is compiled once per user and cached on disk, as the ``"c"`` target's
modules do (``$SYMJAC_CACHE_DIR`` or ``~/.cache/symjac``).

:func:`numeric_jacobian` is the thin wrapper over it that ``symjac.numeric_jacobian`` names.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import types
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any, Literal, get_args

import numpy as np

from symjac.codegen.inverse_kinematics import IK_TOLERANCE, inverse_kinematics_of
from symjac.codegen.module import generate
from symjac.codegen.request import JacobianRequest
from symjac.errors import ArgumentError, CodegenError
from symjac.kinematics.chain import Chain, Frame, MemoKey, as_chain
from symjac.kinematics.jacobian import Point
from symjac.kinematics.memo import frame_of, memoized, one_of
from symjac.kinematics.numeric import numeric_jacobian as lambdified_jacobian
from symjac.kinematics.points import point_vector
from symjac.model.ends import end_point
from symjac.model.robot import Robot

__all__ = ["BACKEND_CHOICES", "BackendChoice", "NumericModel", "c_compiler", "numeric_jacobian", "numeric_model"]

BackendChoice = Literal["auto", "c", "numpy"]
"""How a :class:`NumericModel` evaluates: compiled C kernels, NumPy, or C when it builds (``"auto"``)."""
BACKEND_CHOICES: tuple[str, ...] = get_args(BackendChoice)
"""The values of :data:`BackendChoice`."""


def c_compiler() -> str | None:
    """The C compiler the ``"c"`` target would use (``$CC``, ``cc``, ``gcc``, ``clang``), or None without one."""
    return os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")


@dataclass(frozen=True, eq=False)
class NumericModel:
    r"""Forward kinematics and one Jacobian of a robot, compiled: one configuration or a batch per call.

    Built by :func:`numeric_model`; its functions are those of a generated module (``"c"`` or ``"numpy"``) with the
    parameters at their defaults. Inputs are validated (shape ``(n,)`` or ``(..., n)``, finite values) before they
    reach the kernels; ``out=``, a C-contiguous float64 array of the result's shape, is written and returned
    without allocating.

    Parameters
    ----------
    robot : str
        The robot's name.
    names : tuple of str
        The coordinates as the robot's file names them (URDF and MJCF joint names, else ``theta1``), in the order
        ``q`` gives them; :meth:`coordinates` builds ``q`` from names.
    frame : int or str
        The frame the Jacobian is expressed in.
    point : str or tuple of float
        Where the Jacobian's linear velocity is taken: a named point of the last link or its coordinates in {n}.
    backend : "c" or "numpy"
        What runs: the compiled C kernels, or NumPy (with plain Python floats for one configuration).
    note : str
        Why an ``"auto"`` model runs NumPy (the compiler's error), else empty.
    """

    robot: str
    names: tuple[str, ...]
    frame: Frame
    point: str | tuple[float, float, float]
    backend: Literal["c", "numpy"]
    note: str
    _batch: types.ModuleType = field(repr=False)
    _single: types.ModuleType | None = field(repr=False)
    _ik_modules: Callable[[], _IKSolvers] | None = field(default=None, repr=False)
    _one: tuple[int] = field(init=False, repr=False)  # the shape of one configuration
    _fast: tuple[Any, Any] | None = field(init=False, repr=False)  # C's fk and jacobian, for the common call

    def __post_init__(self) -> None:
        object.__setattr__(self, "_one", (len(self.names),))
        fast = (self._batch.forward_kinematics, self._batch.jacobian) if self._single is None else None
        object.__setattr__(self, "_fast", fast)

    @property
    def n(self) -> int:
        """The number of coordinates (entries of one configuration)."""
        return len(self.names)

    def coordinates(self, values: Any, positions: Any = None) -> np.ndarray:
        """``q`` from ``{name: value}`` or from names and positions, as the generated modules' ``coordinates``.

        The mapping names every coordinate and nothing else; names and positions (a ROS JointState) may come in any
        order and carry other joints, which are ignored.
        """
        return np.asarray(self._batch.coordinates(values, positions), dtype=float)

    def fk(self, q: Any, out: np.ndarray | None = None) -> np.ndarray:
        """The pose of the end of the chain in {0}: shape (4, 4) for one configuration, (..., 4, 4) for a batch.

        The end is the tool frame when the robot has a tool, else frame {n}, as for
        :func:`~symjac.kinematics.chain.forward_kinematics` with ``target="tool"`` where there is one.
        """
        # the common call (C, one float64 configuration, no out) checked inline: 0.9 us a call instead of 1.5 us
        if (self._fast is not None and out is None and type(q) is np.ndarray and q.shape == self._one
                and q.dtype is _FLOAT64 and math.isfinite(sum(q.tolist()))):
            return self._fast[0](q, None)  # type: ignore[no-any-return]
        return self._call("forward_kinematics", q, out, (4, 4))

    def jacobian(self, q: Any, out: np.ndarray | None = None) -> np.ndarray:
        """The basic Jacobian [v; omega] in :attr:`frame` at :attr:`point`: shape (6, n), or (..., 6, n)."""
        if (self._fast is not None and out is None and type(q) is np.ndarray and q.shape == self._one
                and q.dtype is _FLOAT64 and math.isfinite(sum(q.tolist()))):
            return self._fast[1](q, None)  # type: ignore[no-any-return]
        return self._call("jacobian", q, out, (6, len(self.names)))

    def ik(self, pose: Any, tolerance: float = IK_TOLERANCE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every closed-form solution for a pose (4, 4) or a batch (..., 4, 4), as the generated ``inverse_kinematics``.

        Returns ``(solutions, count, branches)``: solutions of shape (..., m, n), each pose's solutions first in branch
        order and rows of NaN after, m the most a pose has (a row equal to an earlier one within ``tolerance``, where
        branches coincide, is dropped); count of shape (...), 0 for an unreachable or NaN pose; branches of shape
        (..., m), each row's branch as its index in :attr:`ik_branches`, -1 for the rows of NaN.
        Revolute angles are in (-pi, pi] (or shifted by 2 pi into the limits). The first call derives the closed
        form and generates its module (a :class:`~symjac.errors.NoClosedFormError` for an arm without one); one
        pose goes through plain Python floats with the numpy backend, a batch through NumPy, vectorised over the
        poses; a C model runs the c target's compiled closed form for both.
        """
        poses = pose if type(pose) is np.ndarray and pose.dtype == np.float64 else _as_array(pose)
        if poses.ndim < 2 or poses.shape[-2:] != (4, 4):
            raise ArgumentError(f"pose must have shape (4, 4) or (..., 4, 4), got shape {poses.shape}")
        batch, single = self._ik_solvers_made()
        if single is not None and poses.ndim == 2:
            rows, count, indices = single.inverse_kinematics(poses.tolist(), tolerance)
            solutions = np.full((int(batch.IK_MAX_SOLUTIONS), self.n), np.nan)
            branches = np.full(int(batch.IK_MAX_SOLUTIONS), -1, dtype=np.intp)
            if count:
                solutions[:count] = rows
                branches[:count] = indices
            return solutions, np.array(count), branches
        return batch.inverse_kinematics(poses, tolerance)  # type: ignore[no-any-return]

    @property
    def ik_branches(self) -> tuple[str, ...]:
        """The names of the closed form's branches, which :meth:`ik`'s ``branches`` index (``IK_BRANCHES``).

        For example ``"shoulder left, elbow up, no flip"``; the first use derives the closed form.
        """
        return tuple(self._ik_solvers_made()[0].IK_BRANCHES)

    def _ik_solvers_made(self) -> Any:
        if self._ik_modules is None:
            raise CodegenError(f"no inverse kinematics for {self.robot}: the model was built without its chain")
        solvers = self.__dict__.get("_ik_solvers")
        if solvers is None:
            solvers = self._ik_modules()
            object.__setattr__(self, "_ik_solvers", solvers)
        return solvers

    def _call(self, function: str, q: Any, out: np.ndarray | None, shape: tuple[int, ...]) -> np.ndarray:
        values = q if type(q) is np.ndarray and q.dtype == np.float64 else _as_array(q)
        n = len(self.names)
        if values.ndim == 0 or values.shape[-1] != n:
            raise ArgumentError(f"q must have shape ({n},) or (N, {n}) for {self.robot} ({', '.join(self.names)}), "
                                f"got shape {values.shape}")
        small = values.size <= _SMALL * n
        entries = values.ravel().tolist() if small else []
        # a sum of finite numbers is finite unless it overflows (then numpy.isfinite decides): 0.15 us for six
        # numbers, where numpy.isfinite costs 1 us
        if not (small and math.isfinite(sum(entries))) and not np.isfinite(values).all():
            raise ArgumentError(f"q must be finite; {_first_bad(values)}")
        if out is not None:
            _check_out(out, (*values.shape[:-1], *shape))
        if self._single is None or not small:
            return getattr(self._batch, function)(values, out)  # type: ignore[no-any-return]
        # plain Python floats for one configuration or a few: NumPy costs 50-80 us a call on tiny arrays
        single = getattr(self._single, function)
        if values.ndim == 1:
            result = np.array(single(entries))
        else:
            results = [single(entries[k:k + n]) for k in range(0, len(entries), n)]
            result = np.array(results).reshape(*values.shape[:-1], *shape)
        if out is None:
            return result
        out[...] = result
        return out


_SMALL = 16
"""Up to this many configurations, the numpy backend evaluates them one by one in plain Python floats (about 3 us
each for a 6-joint arm, where a NumPy call costs 50-80 us however few there are)."""


_FLOAT64 = np.dtype(np.float64)
"""NumPy's float64 dtype: arrays of native doubles share this one object, so ``is`` tests it (anything else takes the
general path)."""


def _check_out(out: Any, expected: tuple[int, ...]) -> None:
    if (type(out) is not np.ndarray or out.shape != expected or out.dtype != np.float64
            or not out.flags.c_contiguous or not out.flags.writeable):
        got = f"shape {out.shape}, {out.dtype}" if isinstance(out, np.ndarray) else type(out).__name__
        raise ArgumentError(f"out must be a writable C-contiguous float64 array of shape {expected}, got {got}")


def _as_array(q: Any) -> np.ndarray:
    if isinstance(q, str | bytes) or q is None:
        raise ArgumentError(f"q must be numbers (one configuration or a batch), got {type(q).__name__}")
    try:
        return np.asarray(q, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ArgumentError(f"q must be numbers (one configuration or a batch): {error}") from None


def _first_bad(values: np.ndarray) -> str:
    index = tuple(int(i) for i in np.argwhere(~np.isfinite(values))[0])
    where = index[0] if len(index) == 1 else index
    return f"q[{where}] is {values[index]}"


def _point_key(chain: Chain, point: Point | None) -> Hashable:
    """A point validated, as its name (None: the end of the chain; "wrist": "flange") or its coordinates in {n}."""
    coordinates = point_vector(chain, point)  # a FrameError for a point the robot does not have
    if point is None:
        return end_point(chain.robot)
    if isinstance(point, str):
        return "flange" if point == "wrist" else point
    return coordinates


backend_of = one_of(BACKEND_CHOICES, "backend")
"""The :func:`~symjac.kinematics.memo.memoized` normaliser of a backend choice."""


@memoized(frame=frame_of, point=_point_key, backend=backend_of)
def _model(chain: Chain, frame: Frame, point: Point | None, backend: BackendChoice) -> NumericModel:
    robot = chain.robot
    request = JacobianRequest(frame, point)
    name = re.sub(r"\W", "_", robot.name) if robot.name.isascii() else "robot"
    name = name if name[:1].isalpha() else f"robot_{name}"
    shown: str | tuple[float, float, float] = (
        point if isinstance(point, str)
        else tuple(float(v.subs(robot.defaults)) for v in point_vector(chain, point)))  # type: ignore[assignment]

    def made(backend: Literal["c", "numpy"], note: str, batch: types.ModuleType,
             single: types.ModuleType | None) -> NumericModel:
        return NumericModel(robot.name, tuple(batch.JOINT_NAMES), frame, shown, backend, note, batch, single,
                            lambda: _ik_modules(chain, name, backend))

    note = ""
    if backend in ("auto", "c"):
        if c_compiler() is None:
            note = "no C compiler found (set CC)"
        else:
            module = _load(generate(chain, "c", jacobians=[request], strategy="raw", name=name), name)
            if module.BACKEND == "c":
                return made("c", "", module, None)
            note = module.BUILD_ERROR
        if backend == "c":
            raise CodegenError(f"the C kernels of {robot.name} did not build: {note}")
    batch = _load(generate(chain, "numpy", jacobians=[request], strategy="raw", name=name), name)
    single = _load(generate(chain, "python", jacobians=[request], strategy="raw", name=name), name)
    return made("numpy", note, batch, single)


_IKSolvers = tuple[types.ModuleType, types.ModuleType | None]
"""What a model's ``ik`` runs: the batched module (``"c"`` or ``"numpy"``) and, for NumPy, the python one."""


@memoized()
def _ik_modules(chain: Chain, name: str, backend: str) -> _IKSolvers:
    """The modules with the closed form a model's ``ik`` calls.

    A C model's is the c target's module (its compiled closed form, the C of the c99 target); a NumPy model has
    NumPy for batches and plain Python floats for one pose.
    """
    made = f"{name}_ik"
    inverse_kinematics_of(chain)  # NoClosedFormError for an arm without one (generate would give the numeric solver)
    if backend == "c":
        return _load(generate(chain, "c", strategy="raw", name=made, inverse_kinematics=True), made), None
    return (_load(generate(chain, "numpy", strategy="raw", name=made, inverse_kinematics=True), made),
            _load(generate(chain, "python", strategy="raw", name=made, inverse_kinematics=True), made))


def _load(source: str, name: str) -> types.ModuleType:
    """A generated module, executed in memory (its C extension, if any, compiled or found in the cache)."""
    module = types.ModuleType(f"symjac_numeric_{name}")
    module.__file__ = f"<symjac numeric model {name}>"
    exec(compile(source, module.__file__, "exec"), module.__dict__)  # our own generated source
    return module


def numeric_model(robot: Robot | Chain, frame: Frame = 0, point: Point | None = None,
                  backend: BackendChoice = "auto") -> NumericModel:
    r"""Compile ``robot``'s forward kinematics and its Jacobian in ``frame`` at ``point`` into a :class:`NumericModel`.

    The first call per robot, frame, point and backend derives and generates the module (a fraction of a second
    for a 6-joint arm) and, for C, compiles its extension (about a second, then cached on disk); later calls return
    the same model.

    Parameters
    ----------
    robot : Robot or Chain
    frame : int or "world" or "tool"
        The frame the Jacobian is expressed in (default {0}).
    point : "tool", "flange", "wrist", "wrist_centre" or three coordinates in frame {n}, optional
        Where the Jacobian's linear velocity is taken; default the end of the chain (the tool point when the robot
        has a tool, else the flange).
    backend : "auto", "c" or "numpy"
        ``"c"``: C kernels compiled into a CPython extension (a :class:`~symjac.errors.CodegenError` when they do
        not build); ``"numpy"``: NumPy for batches and plain Python floats for one configuration; ``"auto"``
        (default): C when a compiler builds it, else NumPy (``model.backend`` says which, ``model.note`` why).

    Returns
    -------
    NumericModel
        ``model.fk(q)`` (4 x 4) and ``model.jacobian(q)`` (6 x n), or with a leading batch axis for ``q`` of shape
        (N, n); parameters at their defaults.

    Examples
    --------
    >>> from symjac import load_robot
    >>> model = numeric_model(load_robot("planar2r"), backend="numpy")
    >>> model.jacobian([0.0, 1.5707963267948966])[:2].round(6).tolist()
    [[-0.4, -0.4], [0.5, 0.0]]
    >>> model.fk([[0.0, 0.0], [0.0, 3.141592653589793]])[:, 0, 3].round(6).tolist()
    [0.9, 0.1]
    """
    return _model(robot, frame, point, backend)


def numeric_jacobian(robot: Robot | Chain, q: Any, frame: Frame = 0, point: Point | None = None, *,
                     backend: BackendChoice = "numpy") -> np.ndarray:
    r"""The basic Jacobian at ``q`` as floats: shape (6, n) for one configuration, (N, 6, n) for a batch.

    A thin wrapper over :func:`numeric_model`: the first call per robot, frame and point generates the model,
    later ones cost microseconds (a few for one configuration with the default ``"numpy"`` backend, well under one
    with ``backend="c"``, which compiles C kernels on its first call). Frame and point are as for
    :func:`~symjac.kinematics.jacobian.jacobian`: default {0} and the end of the chain. A robot whose parameter
    names cannot appear in generated code is evaluated through ``sympy.lambdify``, one configuration at a time.

    Examples
    --------
    >>> from symjac import load_robot
    >>> numeric_jacobian(load_robot("planar2r"), [0.0, 1.5707963267948966])[:2].round(6).tolist()
    [[-0.4, -0.4], [0.5, 0.0]]
    """
    chain = as_chain(robot)
    raw = (frame, point if point is None or isinstance(point, str) else tuple(point), backend)
    model: NumericModel | None
    try:
        hash(raw)
    except TypeError:
        model = numeric_model(chain, frame, point, backend)
    else:  # the raw arguments as key: no point or frame is normalised on later calls
        model = chain.memo(MemoKey(numeric_jacobian, raw), lambda: _model_or_none(chain, frame, point, backend))
    if model is None:
        return _lambdified(chain, q, frame, point)
    return model.jacobian(q)


def _model_or_none(chain: Chain, frame: Frame, point: Point | None, backend: BackendChoice) -> NumericModel | None:
    try:
        return numeric_model(chain, frame, point, backend)
    except CodegenError:
        if backend == "c":
            raise
        return None


def _lambdified(chain: Chain, q: Any, frame: Frame, point: Point | None) -> np.ndarray:
    values = _as_array(q)
    if values.ndim == 1:
        return lambdified_jacobian(chain, values.tolist(), frame, point)
    n = chain.robot.n_coordinates
    flat = values.reshape(-1, n) if values.ndim and values.shape[-1] == n else values
    rows = [lambdified_jacobian(chain, row.tolist(), frame, point) for row in flat]
    return np.array(rows).reshape((*values.shape[:-1], 6, n))
