"""What the Jacobian says about the arm.

Singular configurations, null and range spaces, joint rates, manipulability and representation Jacobians.
"""

__all__: list[str] = []
