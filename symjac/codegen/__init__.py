r"""Generated numeric modules: forward kinematics, Jacobians, torques and manipulability as fast, dependency-free code.

A generated module is what a controller, a simulator or a script imports when it has no SymPy: small, readable,
correct (its own ``selftest`` compares the Jacobian with central differences of its forward kinematics) and fast.
The targets (``"python"``, ``"numpy"``, ``"lambdify"``, ``"c"`` for Python; ``"c99"`` and ``"cpp"`` to compile into
one's own program; ``"jax"`` and ``"casadi"``) are the folders of :mod:`symjac.codegen.backends`
(spec, printer; templates in ``templates/<target>/``), one frozen :class:`Backend` spec each; :data:`TARGETS` lists
them.

Pipeline (one function at a time)
----------------------------------
1. **Request** (:mod:`~symjac.codegen.request`): validate names, points, rows; every name and number that reaches
   the generated text is checked first, so nothing partial is ever written.
2. **Lowering** (:mod:`~symjac.codegen.lower`): candidate expressions, angle expansion, ``sympy.cse``, operation
   counts; cached in the robot's :class:`~symjac.kinematics.chain.Chain`. With ``acceleration=True`` the Hessian and the
   bias acceleration are lowered on top of the lowered Jacobian, as cross products of its entries
   (:mod:`~symjac.codegen.acceleration`).
3. **Description** (:mod:`~symjac.codegen.module`, :mod:`~symjac.codegen.functions`,
   :mod:`~symjac.codegen.description`): one :class:`ModuleRequest` becomes a frozen, language-neutral
   :class:`ModuleDescription` (names, shapes, parameter symbols and defaults, each function's lowered assignments as
   SymPy data, the functions derived from them, the self-test's checks; no ``Chain``); what each kind of function
   returns and how it is documented comes from one table, :mod:`~symjac.codegen.kinds`; every name passes the
   target's identifier rule (:mod:`~symjac.codegen.names`, a leaf module).
4. **Printing and rendering** (``backends/<target>/``): the target's printer maps symbols to validated names, its
   templates lay the files out (one jinja2 environment, :mod:`symjac.resources`) and carry the numeric runtime of
   the target's language family (:mod:`~symjac.codegen.runtime`: ``templates/runtime/``, the linear algebra and
   the self-test); :func:`render_files` gives ``{file name: text}`` and :func:`write_module` writes every file
   atomically, all or none.
"""

from symjac.codegen.backends import BACKENDS, TARGETS, backend
from symjac.codegen.backends._python_family import GeneratedFunction
from symjac.codegen.description import Backend, FunctionDescription, IdentifierRule, ModuleDescription
from symjac.codegen.lower import lower
from symjac.codegen.module import (
    STRATEGIES,
    ModuleRequest,
    Strategy,
    describe,
    generate,
    render_files,
    render_module,
    write_module,
)
from symjac.codegen.request import JacobianRequest
from symjac.errors import CodegenError

__all__ = [
    "BACKENDS",
    "STRATEGIES",
    "TARGETS",
    "Backend",
    "CodegenError",
    "FunctionDescription",
    "GeneratedFunction",
    "IdentifierRule",
    "JacobianRequest",
    "ModuleDescription",
    "ModuleRequest",
    "Strategy",
    "backend",
    "describe",
    "generate",
    "lower",
    "render_files",
    "render_module",
    "write_module",
]
