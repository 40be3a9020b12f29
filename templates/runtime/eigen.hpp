// The numeric runtime of the cpp target: manipulability, its gradient, Cholesky solves, on Eigen 3.4, any scalar.
//
// Every generated cpp header carries the part of this file below the runtime mark, unchanged, inside its own
// namespace (symjac::<robot>::runtime), so that two generated headers can be included together and each still
// needs only Eigen. Every routine is a template on the scalar type and the fixed sizes; a decision on the shape
// (square, wide or tall) is made at compile time. Tested on its own: tests/test_codegen_runtime.py compiles it.
// A header carries only the sections it uses; the acceleration and dynamics sections are empty: the header has
// no self-test.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace symjac_runtime_test {

// ---- runtime: everything below is copied into every generated module of the target ----
namespace runtime {

// ---- runtime section: determinant ----

// The determinant of a square matrix (Eigen's: LU with partial pivoting for sizes above 4, cofactors below).
template <class Scalar, int N>
Scalar determinant(const Eigen::Matrix<Scalar, N, N>& J)
{
    return J.determinant();
}

// ---- runtime section: manipulability ----

// The manipulability w: |det J| for a square J, else sqrt(det G), G = J J^T (wide) or J^T J (tall); 0 if det G <= 0.
template <class Scalar, int Rows, int Cols>
Scalar manipulability(const Eigen::Matrix<Scalar, Rows, Cols>& J)
{
    using std::abs;
    using std::sqrt;
    if constexpr (Rows == Cols) {
        return abs(J.determinant());
    } else {
        Scalar d;
        if constexpr (Rows < Cols) {
            d = (J * J.transpose()).determinant();
        } else {
            d = (J.transpose() * J).determinant();
        }
        return d > Scalar(0) ? Scalar(sqrt(d)) : Scalar(0);
    }
}

// ---- runtime section: manipulability_gradient ----

// dw/dq_m = w trace(J^+ dJ/dq_m), H[m] = dJ/dq_m, J^+ through one solve with the Gram matrix G: J^+ = (G^-1 J)^T
// for a wide J (G = J J^T), G^-1 J^T for a tall one (G = J^T J); zero where w = 0 (a kink, not a gradient).
template <class Scalar, int Rows, int Cols, std::size_t Slices>
Eigen::Matrix<Scalar, Cols, 1> manipulability_gradient(const Eigen::Matrix<Scalar, Rows, Cols>& J,
                                                       const std::array<Eigen::Matrix<Scalar, Rows, Cols>, Slices>& H)
{
    static_assert(Slices == static_cast<std::size_t>(Cols), "one slice of H per column of J");
    using std::sqrt;
    Eigen::Matrix<Scalar, Cols, 1> gradient = Eigen::Matrix<Scalar, Cols, 1>::Zero();
    if constexpr (Rows <= Cols) {
        const Eigen::Matrix<Scalar, Rows, Rows> G = J * J.transpose();
        const Scalar d = G.determinant();
        if (!(d > Scalar(0))) {
            return gradient;
        }
        const Scalar w = sqrt(d);
        const Eigen::Matrix<Scalar, Rows, Cols> X = G.partialPivLu().solve(J);  // J^+ = X^T
        for (int m = 0; m < Cols; m++) {
            gradient(m) = w * X.cwiseProduct(H[m]).sum();
        }
    } else {
        const Eigen::Matrix<Scalar, Cols, Cols> G = J.transpose() * J;
        const Scalar d = G.determinant();
        if (!(d > Scalar(0))) {
            return gradient;
        }
        const Scalar w = sqrt(d);
        const Eigen::Matrix<Scalar, Cols, Rows> X = G.partialPivLu().solve(J.transpose());  // J^+ = X
        for (int m = 0; m < Cols; m++) {
            gradient(m) = w * X.transpose().cwiseProduct(H[m]).sum();
        }
    }
    return gradient;
}

// ---- runtime section: cholesky_solve ----

// x with M x = b for a symmetric positive definite M (a mass matrix): M = L L^T (Eigen's LLT), then two triangular
// solves; ok is false when M is not positive definite (x is then meaningless).
template <class Scalar, int N>
Eigen::Matrix<Scalar, N, 1> cholesky_solve(const Eigen::Matrix<Scalar, N, N>& M, const Eigen::Matrix<Scalar, N, 1>& b,
                                           bool* ok = nullptr)
{
    const Eigen::LLT<Eigen::Matrix<Scalar, N, N>> factor(M);
    if (ok != nullptr) {
        *ok = factor.info() == Eigen::Success;
    }
    return factor.solve(b);
}

// ---- runtime section: forward_dynamics; needs: cholesky_solve ----

// qddot = M^-1 (tau - b) by a Cholesky solve: M the mass matrix, b = C qdot + g the bias forces.
template <class Scalar, int N>
Eigen::Matrix<Scalar, N, 1> forward_dynamics(const Eigen::Matrix<Scalar, N, N>& M, const Eigen::Matrix<Scalar, N, 1>& b,
                                             const Eigen::Matrix<Scalar, N, 1>& tau)
{
    return cholesky_solve<Scalar, N>(M, Eigen::Matrix<Scalar, N, 1>(tau - b));
}

// ---- runtime section: dynamics ----

// ---- runtime section: identification ----

// ---- runtime section: acceleration ----

// ---- runtime section: core ----

// q[i] = the position of joint_names[i] in names and positions (other names are ignored, the first of a repeated
// name counts): 0 when every joint has a value, else 1 + the index of the first without one; -1 if the sizes differ.
template <class Scalar, std::size_t N, int Rows>
int coordinates_from(const std::array<const char*, N>& joint_names, const std::vector<std::string>& names,
                     const std::vector<Scalar>& positions, Eigen::Matrix<Scalar, Rows, 1>& q)
{
    static_assert(static_cast<std::size_t>(Rows) == N, "q has one entry per joint name");
    if (names.size() != positions.size()) {
        return -1;
    }
    for (std::size_t i = 0; i < N; ++i) {
        std::size_t k = 0;
        while (k < names.size() && std::strcmp(names[k].c_str(), joint_names[i]) != 0) {
            ++k;
        }
        if (k == names.size()) {
            return static_cast<int>(i) + 1;
        }
        q(static_cast<Eigen::Index>(i)) = positions[k];
    }
    return 0;
}

// q[i] = values[joint_names[i]]: 0 when every joint has a value, else 1 + the index of the first without one; -1
// if values names a joint not in joint_names.
template <class Scalar, std::size_t N, int Rows>
int coordinates_from(const std::array<const char*, N>& joint_names, const std::map<std::string, Scalar>& values,
                     Eigen::Matrix<Scalar, Rows, 1>& q)
{
    static_assert(static_cast<std::size_t>(Rows) == N, "q has one entry per joint name");
    for (const auto& entry : values) {
        std::size_t i = 0;
        while (i < N && std::strcmp(entry.first.c_str(), joint_names[i]) != 0) {
            ++i;
        }
        if (i == N) {
            return -1;
        }
    }
    for (std::size_t i = 0; i < N; ++i) {
        std::size_t found = N;
        for (const auto& entry : values) {
            if (std::strcmp(entry.first.c_str(), joint_names[i]) == 0) {
                q(static_cast<Eigen::Index>(i)) = entry.second;
                found = i;
            }
        }
        if (found == N) {
            return static_cast<int>(i) + 1;
        }
    }
    return 0;
}

}  // namespace runtime
// ---- end of runtime ----
}  // namespace symjac_runtime_test
