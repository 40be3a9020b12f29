r"""Generated numeric modules: forward kinematics, Jacobians, torques and manipulability as fast, dependency-free code.

A generated module is what a controller, a simulator or a script imports when it has no SymPy: small, readable,
correct (its own ``selftest`` compares the Jacobian with central differences of its forward kinematics) and fast.
The targets (``"python"``, ``"numpy"``, ``"lambdify"``, ``"c"``) are the modules of :mod:`symjac.codegen.backends`,
one frozen :class:`Backend` spec each; :data:`TARGETS` lists them.

Pipeline (one function at a time)
----------------------------------
1. **Request** (:mod:`~symjac.codegen.request`): validate names, points, rows; every name and number that reaches
   the generated text is checked first, so nothing partial is ever written.
2. **Lowering** (:mod:`~symjac.codegen.lower`): candidate expressions, angle expansion, ``sympy.cse``, operation
   counts; cached in the robot's :class:`~symjac.kinematics.chain.Chain`. With ``acceleration=True`` the Hessian and the
   bias acceleration are lowered on top of the lowered Jacobian, as cross products of its entries
   (:mod:`~symjac.codegen.acceleration`).
3. **Printing** (:mod:`~symjac.codegen.printers`, :mod:`~symjac.codegen.source_layout`): printer subclasses map symbols
to
   validated names; statements are laid out within the line width by the target's backend.
4. **Rendering** (:mod:`~symjac.codegen.module`): a frozen :class:`ModuleDescription` fills the target's template
   through the single jinja2 environment (:mod:`symjac.resources`); :func:`write_module` replaces a file atomically.
"""

from symjac.codegen.backends import BACKENDS, TARGETS, backend
from symjac.codegen.description import Backend, GeneratedFunction, ModuleDescription
from symjac.codegen.lower import lower
from symjac.codegen.module import STRATEGIES, Strategy, describe, generate, render_module, write_module
from symjac.codegen.request import JacobianRequest
from symjac.errors import CodegenError

__all__ = [
    "BACKENDS",
    "STRATEGIES",
    "TARGETS",
    "Backend",
    "CodegenError",
    "GeneratedFunction",
    "JacobianRequest",
    "ModuleDescription",
    "Strategy",
    "backend",
    "describe",
    "generate",
    "lower",
    "render_module",
    "write_module",
]
