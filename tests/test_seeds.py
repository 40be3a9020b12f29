"""The closed forms printed in the course notes, asserted as exact symbolic identities.

Each expected matrix is typed from the notes in their own notation; `assert_identical` checks every entry with the
exact normal form of symjac.symbolic.simplify (not by comparing printed strings). Where the notes have a typo, the test
says which entry the derivation corrects and checks both the correction and that the printed value is really wrong.
"""

from __future__ import annotations

import sympy as sp

from symjac import AngleBasis, chain_of, forward_kinematics, is_identity, jacobian, load_robot

t1, t2, t3, t4, t5, t6 = sp.symbols("theta1:7", real=True)
d3 = sp.Symbol("d3", real=True)
L1, L2, L3, d2 = sp.symbols("L1 L2 L3 d2", real=True)
s1, s2, s3, s4, s5, s6 = (sp.sin(t) for t in (t1, t2, t3, t4, t5, t6))
c1, c2, c3, c4, c5, c6 = (sp.cos(t) for t in (t1, t2, t3, t4, t5, t6))
s12, c12 = sp.sin(t1 + t2), sp.cos(t1 + t2)
s123, c123 = sp.sin(t1 + t2 + t3), sp.cos(t1 + t2 + t3)
s23, c23 = sp.sin(t2 + t3), sp.cos(t2 + t3)
BASIS = AngleBasis.of([t1, t2, t3, t4, t5, t6])


def mismatches(actual: sp.MatrixBase, expected: sp.MatrixBase) -> list[tuple[int, int]]:
    """1-based (row, column) of the entries that are not identically equal."""
    assert actual.shape == expected.shape
    return [(r + 1, c + 1) for r in range(actual.rows) for c in range(actual.cols)
            if not is_identity(actual[r, c], expected[r, c], BASIS)]


def assert_identical(actual: sp.MatrixBase, expected: sp.MatrixBase) -> None:
    assert mismatches(actual, expected) == []


def test_planar_2r_in_frames_0_and_1():
    """The course chapter (4.102) and (4.104), with x = l1 c1 + l2 c12, y = l1 s1 + l2 s12 (4.100, 4.101)."""
    robot = load_robot("planar2r")
    x, y = L1 * c1 + L2 * c12, L1 * s1 + L2 * s12
    assert_identical(jacobian(robot, frame=0)[:2, :], sp.Matrix([[-y, -L2 * s12], [x, L2 * c12]]))
    assert_identical(jacobian(robot, frame=1)[:2, :], sp.Matrix([[-L2 * s2, -L2 * s2], [L1 + L2 * c2, L2 * c2]]))
    # and the compact layout reads exactly as in the notes
    assert jacobian(robot, frame=1)[1, 0] == L1 + L2 * c2


def test_planar_3r_at_wrist_and_end_effector():
    """The course chapter (4.117) at the wrist and (4.122) at the end-effector point E, L3 beyond the wrist."""
    robot = load_robot("planar3r")
    zero = [0, 0, 0]
    J_W = sp.Matrix([
        [-L1 * s1 - L2 * s12, -L2 * s12, 0],
        [L1 * c1 + L2 * c12, L2 * c12, 0],
        zero, zero, zero, [1, 1, 1],
    ])
    J_E = sp.Matrix([
        [-L1 * s1 - L2 * s12 - L3 * s123, -L2 * s12 - L3 * s123, -L3 * s123],
        [L1 * c1 + L2 * c12 + L3 * c123, L2 * c12 + L3 * c123, L3 * c123],
        zero, zero, zero, [1, 1, 1],
    ])
    assert_identical(jacobian(robot, point="flange"), J_W)
    assert_identical(jacobian(robot, point="tool"), J_E)
    assert_identical(jacobian(robot), J_E)  # the default: the end of the chain, planar3r's tool point
    # (4.121): the point-shift term -p_WE^ J_w
    assert_identical(J_E[:3, :] - J_W[:3, :], sp.Matrix([[-L3 * s123] * 3, [L3 * c123] * 3, zero]))


def test_stanford_link_transforms_with_the_corrected_sign_in_1_2T():
    """Course chapter (4.86)-(4.91). It prints row 3 of 1_2T as [-s2, c2, 0, 0]; Rx(-pi/2) Rz(theta2) gives -c2."""
    chain = chain_of(load_robot("stanford"))
    notes = {
        1: [[c1, -s1, 0, 0], [s1, c1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
        2: [[c2, -s2, 0, 0], [0, 0, 1, d2], [-s2, c2, 0, 0], [0, 0, 0, 1]],
        3: [[1, 0, 0, 0], [0, 0, -1, -d3], [0, 1, 0, 0], [0, 0, 0, 1]],
        4: [[c4, -s4, 0, 0], [s4, c4, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
        5: [[c5, -s5, 0, 0], [0, 0, 1, 0], [-s5, -c5, 0, 0], [0, 0, 0, 1]],
        6: [[c6, -s6, 0, 0], [0, 0, -1, 0], [s6, c6, 0, 0], [0, 0, 0, 1]],
    }
    corrections = {2: {(3, 2): -c2}}
    for i, printed in notes.items():
        derived = chain.simplified_transform(i - 1, i)
        expected = sp.Matrix(printed)
        for (r, c), value in corrections.get(i, {}).items():
            assert not is_identity(derived[r - 1, c - 1], expected[r - 1, c - 1], BASIS)
            expected[r - 1, c - 1] = value
        assert_identical(derived, expected)


def test_stanford_forward_kinematics():
    """The course chapter (4.92), (4.93), (4.152); and (4.15) for the position."""
    robot = load_robot("stanford")
    assert_identical(forward_kinematics(robot, 0, 2), sp.Matrix([
        [c1 * c2, -c1 * s2, -s1, -s1 * d2], [s1 * c2, -s1 * s2, c1, c1 * d2], [-s2, -c2, 0, 0], [0, 0, 0, 1]]))
    assert_identical(forward_kinematics(robot, 0, 3), sp.Matrix([
        [c1 * c2, -s1, c1 * s2, c1 * d3 * s2 - s1 * d2],
        [s1 * c2, c1, s1 * s2, s1 * d3 * s2 + c1 * d2],
        [-s2, 0, c2, d3 * c2], [0, 0, 0, 1]]))
    assert_identical(forward_kinematics(robot, 1, 3), sp.Matrix([
        [c2, 0, s2, d3 * s2], [0, 1, 0, d2], [-s2, 0, c2, d3 * c2], [0, 0, 0, 1]]))


def test_stanford_position_jacobian():
    """The course chapter (4.16): columns -y, x from (4.15), then c1c2d3 ... for theta2 and the prismatic d3."""
    robot = load_robot("stanford")
    x, y = c1 * s2 * d3 - s1 * d2, s1 * s2 * d3 + c1 * d2
    J_p = sp.Matrix([
        [-y, c1 * c2 * d3, c1 * s2, 0, 0, 0],
        [x, s1 * c2 * d3, s1 * s2, 0, 0, 0],
        [0, -s2 * d3, c2, 0, 0, 0],
    ])
    assert_identical(jacobian(robot)[:3, :], J_p)


def test_stanford_full_jacobian_and_the_entries_the_notes_get_wrong():
    """The course chapter section 4.11.1 prints the 6 x 6 Jacobian in {0}; three of its entries are typos.

    (4, 5): printed -s1 c2 s4 + c1 c4 (a copy of the entry below it); z5 = 0_4R [0, 1, 0]^T gives -c1 c2 s4 - s1 c4.
    (4, 6) and (5, 6): printed ... + c1 s2 s5 and ... + s1 s2 s5; z6 = -(column 2 of 0_5R) gives c1 s2 c5, s1 s2 c5.
    """
    printed = sp.Matrix([
        [-c1 * d2 - s1 * s2 * d3, c1 * c2 * d3, c1 * s2, 0, 0, 0],
        [-s1 * d2 + c1 * s2 * d3, s1 * c2 * d3, s1 * s2, 0, 0, 0],
        [0, -s2 * d3, c2, 0, 0, 0],
        [0, -s1, 0, c1 * s2, -s1 * c2 * s4 + c1 * c4, c1 * c2 * c4 * s5 - s1 * s4 * s5 + c1 * s2 * s5],
        [0, c1, 0, s1 * s2, -s1 * c2 * s4 + c1 * c4, s1 * c2 * c4 * s5 + c1 * s4 * s5 + s1 * s2 * s5],
        [1, 0, 0, c2, s2 * s4, -s2 * c4 * s5 + c5 * c2],
    ])
    derived = jacobian(load_robot("stanford"))
    assert mismatches(derived, printed) == [(4, 5), (4, 6), (5, 6)]
    corrected = printed.copy()
    corrected[3, 4] = -c1 * c2 * s4 - s1 * c4
    corrected[3, 5] = c1 * c2 * c4 * s5 - s1 * s4 * s5 + c1 * s2 * c5
    corrected[4, 5] = s1 * c2 * c4 * s5 + c1 * s4 * s5 + s1 * s2 * c5
    assert_identical(derived, corrected)


def test_stanford_cross_product_terms_in_frame_i():
    """The course chapter (4.156), (4.157), (4.159), (4.161): z_i x p_i3 computed in {i}, then rotated into {0}."""
    robot = load_robot("stanford")
    chain = chain_of(robot)
    p_13 = chain.transform(1, 3)[:3, 3]
    assert_identical(sp.Matrix([-p_13[1], p_13[0], 0]), sp.Matrix([-d2, d3 * s2, 0]))
    assert_identical(chain.rotation(0, 1) * sp.Matrix([-d2, d3 * s2, 0]),
                     sp.Matrix([-c1 * d2 - s1 * s2 * d3, -s1 * d2 + c1 * s2 * d3, 0]))
    p_23 = chain.transform(2, 3)[:3, 3]
    assert_identical(sp.Matrix([-p_23[1], p_23[0], 0]), sp.Matrix([d3, 0, 0]))
    assert_identical(chain.rotation(0, 2) * sp.Matrix([d3, 0, 0]), sp.Matrix([c1 * c2 * d3, s1 * c2 * d3, -s2 * d3]))


def test_articulated_3r_in_frame_4():
    """The lecture slides: 4J = [[0, L2 s3, 0], [0, L2 c3 + L3, L3], [-L1 - L2 c2 - L3 c23, 0, 0]] at the tool point."""
    robot = load_robot("articulated3r")
    J_4 = jacobian(robot, frame="tool", point="tool")
    expected = sp.Matrix([[0, L2 * s3, 0], [0, L2 * c3 + L3, L3], [-L1 - L2 * c2 - L3 * c23, 0, 0]])
    assert_identical(J_4[:3, :], expected)
    # the compact layout keeps the notes' mix of references: s3 beside c2 and c23
    assert J_4[:3, :] == expected
    # its determinant, -(L1 + L2 c2 + L3 c23) L2 s3 L3, is the lecture slides' shoulder/elbow singularity
    assert is_identity(J_4[:3, :].det(), -(L1 + L2 * c2 + L3 * c23) * L2 * s3 * L3, BASIS)


def test_2r_determinant_is_l1_l2_s2():
    """The lecture slides: det J = L1 L2 s2, independent of theta1."""
    assert is_identity(jacobian(load_robot("planar2r"))[:2, :].det(), L1 * L2 * s2, BASIS)
