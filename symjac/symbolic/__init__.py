"""Algebra that knows no robot.

Homogeneous transforms, angle bases, trigonometric polynomials, the
normal-form simplifier, graph walks over shared expressions and the size budget of a result.
"""

__all__: list[str] = []
