"""Derived kinematics of a chain.

Transforms, Jacobians by every method, the acceleration level, statics,
numeric evaluation and conversion between conventions.
"""

__all__: list[str] = []
