"""Worked answers to the notebooks" exercises, kept out of the notebooks so students write their own.

Each notebook"s exercise cells hold ``answer_N = ...  # your answer here``; ``SOLUTIONS[notebook][name]`` is the
line that replaces it (``tests/test_notebooks.py`` runs every notebook with these in place and checks that the
placeholders fail). Peek only after trying.
"""

SOLUTIONS: dict[str, dict[str, str]] = {
    "01_differential_motion_2r": {
        "answer_1": "answer_1 = -L2_s * sp.sin(theta1 + theta2)",
        "answer_2": "answer_2 = sp.Matrix([-L2_s, L1_s])",
        "answer_3": "answer_3 = {0, sp.pi}",
    },
    "02_stanford_arm": {
        "answer_1": "answer_1 = sp.Matrix([c1 * s2, s1 * s2, c2, 0, 0, 0])",
        "answer_2": "answer_2 = sp.Matrix([-p[1], p[0], 0])",
        "answer_3": "answer_3 = J_3[2, 2]",
    },
    "03_propagation_and_statics": {
        "answer_1": "answer_1 = L3 * f_y",
        "answer_2": 'answer_2 = sp.Matrix([0, 0, sp.Symbol("thetadot1", real=True)])',
        "answer_3": "answer_3 = True",
    },
    "04_singularities": {
        "answer_1": "answer_1 = L1_s * L2_s * sp.sin(planar.q[1])",
        "answer_2": "answer_2 = {0, sp.pi}",
        "answer_3": "answer_3 = False",
    },
    "05_representation_jacobians": {
        "answer_1": "answer_1 = sp.cos(theta_rpy)",
        "answer_2": "answer_2 = [0.0, 0.0, 0.3]",
        "answer_3": "answer_3 = sp.Matrix([[-sp.sin(alpha), sp.cos(alpha), 0]])",
    },
    "06_generated_code": {
        "answer_1": "answer_1 = plain.jacobian([0.0] * 6, d3=0.2)[0][0]",
        "answer_2": "answer_2 = batched.manipulability(batch[:50]).ravel()",
    },
    "07_acceleration_level": {
        "answer_1": ("answer_1 = -L1 * sp.cos(theta1) * thetadot1**2"
                     " - L2 * sp.cos(theta1 + theta2) * (thetadot1 + thetadot2) ** 2"),
        "answer_2": "answer_2 = sp.cos(theta2) / sp.sin(theta2)",
        "answer_3": "answer_3 = 0.9",
    },
    "08_product_of_exponentials": {
        "answer_1": ("answer_1 = sp.Matrix([-sp.sin(theta1), sp.cos(theta1), 0, -H1 * sp.cos(theta1), "
                     "-H1 * sp.sin(theta1), 0])"),
        "answer_2": "answer_2 = sp.Matrix([0, 0, 1, 0, 0, 0])",
        "answer_3": "answer_3 = 6",
    },
    "09_drawing_the_arm": {
        "answer_1": "answer_1 = 0.0  # stretched: the tool cannot move along the arm",
        "answer_2": "answer_2 = np.sqrt((0.57 + np.sqrt(0.57**2 - 4 * 0.04)) / 2)  # eigenvalues of J_v J_v^T",
        "answer_3": "answer_3 = 3  # {1} and {2}, {3}, and the wrist centre {4}, {5}, {6}",
    },
    "10_dynamics": {
        "answer_1": "answer_1 = m2 * lc2**2 + I2",
        "answer_2": "answer_2 = m2 * g_symbol * lc2 * sp.cos(theta1 + theta2)",
        "answer_3": "answer_3 = 0  # joint 1 turns about the vertical",
    },
    "11_identification": {
        "answer_1": "answer_1 = 36",
        "answer_2": "answer_2 = MX2 + L2 * M2",
    },
    "12_inverse_kinematics": {
        "answer_1": "answer_1 = np.arccos((0.3**2 + 0.6**2 - 0.5**2 - 0.4**2) / (2 * 0.5 * 0.4))",
        "answer_2": "answer_2 = 1.2 - 0.9  # the reach is L1 + L2",
        "answer_3": "answer_3 = 8  # two shoulders, two elbows, two wrists",
    },
}
