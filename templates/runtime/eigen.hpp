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

// ---- runtime section: ik_numeric ----

// splitmix64 (Steele, Lea and Flood 2014): the numeric solver's seeds, the same sequence on every platform.
inline unsigned long long splitmix64(unsigned long long& state)
{
    unsigned long long z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// The rotation vector (axis times angle) of the rotation r, robust near 0 and pi.
template <class Scalar>
Eigen::Matrix<Scalar, 3, 1> rotation_vector(const Eigen::Matrix<Scalar, 3, 3>& r)
{
    using std::acos;
    using std::sin;
    const Scalar pi = Scalar(3.14159265358979323846);
    const Scalar cosine = std::min(Scalar(1), std::max(Scalar(-1), (r.trace() - Scalar(1)) / Scalar(2)));
    const Scalar angle = acos(cosine);
    Eigen::Matrix<Scalar, 3, 1> w(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
    if (angle < Scalar(1e-6)) {
        return w / Scalar(2);
    }
    if (pi - angle > Scalar(1e-4)) {
        return w * (angle / (Scalar(2) * sin(angle)));
    }
    int m = 0;  // near pi: the axis from the symmetric part (r + I) / 2, its largest diagonal entry's row
    for (int k = 1; k < 3; k++) {
        m = r(k, k) > r(m, m) ? k : m;
    }
    Eigen::Matrix<Scalar, 3, 1> axis = (r.row(m).transpose() + Eigen::Matrix<Scalar, 3, 1>::Unit(m)) / Scalar(2);
    axis.normalize();
    return (axis.dot(w) < Scalar(0) ? -angle : angle) * axis;
}

// Solve a x = b (a symmetric positive definite) by LDL^T without pivoting, as the c99 runtime's sj_ik_cholesky: no
// square root and one division per row (faster than a Cholesky factor at these sizes); b becomes x.
template <class Scalar, int N>
void ldl_solve(Eigen::Matrix<Scalar, N, N>& a, Eigen::Matrix<Scalar, N, 1>& b)
{
    Scalar inverse[N];  // 1 / D
    Scalar t[N];        // row i of L D
    for (int i = 0; i < N; i++) {
        Scalar d = a(i, i);
        for (int j = 0; j < i; j++) {
            Scalar s = a(i, j);
            for (int k = 0; k < j; k++) {
                s -= t[k] * a(j, k);
            }
            t[j] = s;
        }
        for (int j = 0; j < i; j++) {
            const Scalar l = t[j] * inverse[j];
            d -= t[j] * l;
            a(i, j) = l;
        }
        inverse[i] = Scalar(1) / d;
    }
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < i; k++) {
            b[i] -= a(i, k) * b[k];
        }
    }
    for (int i = N - 1; i >= 0; i--) {
        b[i] *= inverse[i];
        for (int k = i + 1; k < N; k++) {
            b[i] -= a(k, i) * b[k];
        }
    }
}

// A per-joint table of N entries (N an int, as Eigen's sizes are).
template <class T, int N>
using Table = std::array<T, static_cast<std::size_t>(N)>;

// Numeric inverse kinematics, as the c99 runtime's sj_ik_numeric (the same seeds, steps and budget): each start
// descends by Levenberg-Marquardt with Sugihara's damping lambda = mu (E / 2 + 1e-3), E = e^T e, e = [p* - p(q);
// log(R* R(q)^T)] (with geodesic acceleration once E < 1e-6), without limits first (100 steps, or 4 without the
// cost falling 10 % while E > 1e-10); a solution is shifted by 2 pi into the limits, and when a joint does not
// fit, a redundant arm (N > 6) goes on from the clipped configuration with the limits respected (N <= 6: isolated
// solutions, it restarts) (a joint at a limit that a
// step would push past is held still). Kinds: 0 prismatic, 1 revolute with limits, 2 revolute without (wrapped
// to (-pi, pi]). At most 64 starts; converged when both error norms are at most 1e-10 (1e-4 in single precision).
// When none converges, the closest configuration reached (the least cost E, clipped into the limits) descends once
// more within the limits. Writes q (the solution, or that closest configuration), the steps taken and q's position
// (m) and orientation (rad) error norms (each pointer when not nullptr); returns 1 when q reaches the pose, else 0.
template <class Scalar, int N, class PoseOf, class VelocityOf>
int ik_numeric(const PoseOf& pose_of, const VelocityOf& velocity_of, const Table<double, N>& lower,
               const Table<double, N>& upper, const Table<int, N>& kind, const Table<double, N>& low,
               const Table<double, N>& high, const Eigen::Matrix<Scalar, 4, 4>& target,
               const Eigen::Matrix<Scalar, N, 1>* start, unsigned long long seed, Eigen::Matrix<Scalar, N, 1>& q,
               int* iterations, Scalar* position_error, Scalar* orientation_error)
{
    using std::fmod;
    using Vector = Eigen::Matrix<Scalar, N, 1>;
    using Error = Eigen::Matrix<Scalar, 6, 1>;
    const Scalar pi = Scalar(3.14159265358979323846);
    const Scalar tolerance = sizeof(Scalar) < sizeof(double) ? Scalar(1e-4) : Scalar(1e-10);
    auto wrapped = [&](Scalar x) {  // to (-pi, pi], unchanged when it is in already
        return (x > pi || x <= -pi) ? pi - fmod(fmod(pi - x, Scalar(2) * pi) + Scalar(2) * pi, Scalar(2) * pi) : x;
    };
    auto converged = [&](const Error& e) {
        return e.template head<3>().squaredNorm() <= tolerance * tolerance
               && e.template tail<3>().squaredNorm() <= tolerance * tolerance;
    };
    auto project = [&](Vector& x, bool limited) {
        for (int k = 0; k < N; k++) {
            if (kind[k] == 2) {
                x[k] = wrapped(x[k]);
            } else if (limited) {
                x[k] = std::min(Scalar(upper[k]), std::max(Scalar(lower[k]), x[k]));
            }
        }
    };
    auto into_limits = [&](Vector& x) {
        bool inside = true;
        for (int k = 0; k < N; k++) {
            const Scalar value = kind[k] ? wrapped(x[k]) : x[k];
            bool fits = false;
            for (int shift = 0; shift < (kind[k] ? 5 : 1) && !fits; shift++) {
                const Scalar y = value + Scalar((shift + 1) / 2 * (shift % 2 ? 1 : -1)) * Scalar(2) * pi;
                if (Scalar(lower[k]) <= y && y <= Scalar(upper[k])) {
                    x[k] = y;
                    fits = true;
                }
            }
            if (!fits) {
                x[k] = std::min(Scalar(upper[k]), std::max(Scalar(lower[k]), value));
                inside = false;
            }
        }
        return inside;
    };
    auto error = [&](const Vector& x, Error& e) {
        const Eigen::Matrix<Scalar, 4, 4> T = pose_of(x);
        e.template head<3>() = target.template block<3, 1>(0, 3) - T.template block<3, 1>(0, 3);
        e.template tail<3>() = rotation_vector<Scalar>(
            Eigen::Matrix<Scalar, 3, 3>(target.template block<3, 3>(0, 0) * T.template block<3, 3>(0, 0).transpose()));
        return e.squaredNorm();
    };
    int steps = 0;
    auto descend = [&](Vector& x, Error& e, bool limited, int patience) {
        project(x, limited);
        Scalar cost = error(x, e);
        Scalar reference = cost;
        Scalar mu = 1;
        int stalled = 0;
        Eigen::Matrix<Scalar, 6, N> J;
        Eigen::Matrix<Scalar, N, N> normal;
        bool moved = true;  // J and J^T J are those of x unless it moved
        for (int it = 0; it < 100 && !converged(e); it++) {
            steps++;
            if (moved) {
                J = velocity_of(x);
                normal = J.transpose() * J;
            }
            const Scalar lambda = mu * (cost / Scalar(2) + Scalar(1e-3));
            Table<bool, N> held{};
            auto solve = [&](const Error& r) {  // (J^T J + lambda I)^-1 J^T r over the joints not held
                Eigen::Matrix<Scalar, N, N> a = normal;
                Vector b = J.transpose() * r;
                for (int k = 0; k < N; k++) {
                    a(k, k) += lambda;
                    if (held[k]) {
                        a.row(k).setZero();
                        a.col(k).setZero();
                        a(k, k) = Scalar(1);
                        b[k] = Scalar(0);
                    }
                }
                ldl_solve<Scalar, N>(a, b);
                return b;
            };
            Vector step;
            for (int round = 0; round < N; round++) {
                step = solve(e);
                bool more = false;
                for (int k = 0; k < N && limited; k++) {
                    const bool outward = (x[k] <= Scalar(lower[k]) && step[k] < 0)
                                         || (x[k] >= Scalar(upper[k]) && step[k] > 0);
                    if (!held[k] && outward) {
                        held[k] = more = true;
                    }
                }
                if (!more) {
                    break;
                }
            }
            if (cost < Scalar(1e-6)) {  // geodesic acceleration: -f_vv from the error at q + 0.1 v
                Error e_probe;
                error(Vector(x + Scalar(0.1) * step), e_probe);
                const Vector acceleration = solve(Error(Scalar(20) * ((e_probe - e) / Scalar(0.1) + J * step)));
                if (Scalar(2) * acceleration.norm() <= Scalar(0.75) * step.norm()) {
                    step += acceleration / Scalar(2);
                }
            }
            Vector trial = x + step;
            project(trial, limited);
            Error e_trial;
            const Scalar c = error(trial, e_trial);
            moved = c < cost;
            if (moved) {
                x = trial;
                e = e_trial;
                cost = c;
                mu = std::max(mu / Scalar(2), Scalar(1e-6));
            } else {
                mu *= Scalar(4);
            }
            if (cost < Scalar(0.9) * reference || cost < Scalar(1e-10)) {
                reference = cost;
                stalled = 0;
            } else if (++stalled >= patience) {
                break;
            }
        }
        return cost;
    };
    unsigned long long state = seed;
    Vector best = Vector::Zero();
    Error best_e = Error::Zero();
    Scalar best_cost = std::numeric_limits<Scalar>::infinity();
    int found = 0;
    for (int attempt = 0; attempt < 64 && !found; attempt++) {
        Vector x;
        for (int k = 0; k < N; k++) {
            const double u = double(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
            x[k] = (attempt == 0 && start != nullptr) ? (*start)[k] : Scalar(low[k] + u * (high[k] - low[k]));
        }
        Error e;
        Scalar cost = descend(x, e, false, 4);
        found = converged(e);
        const bool inside = into_limits(x);  // else clipped into them
        if (found && !inside && N > 6) {
            cost = descend(x, e, true, 4);
            found = converged(e);
        } else if (!inside) {  // not converged, or isolated solutions (N <= 6) outside the limits: restart
            found = 0;
            cost = error(x, e);
        }
        if (found || cost < best_cost || attempt == 0) {
            best_cost = cost;
            best = x;
            best_e = e;
        }
    }
    if (!found) {  // the closest configuration reached: one more descent from it, within the limits
        Vector x = best;
        Error e;
        const Scalar cost = descend(x, e, true, 100);  // no early stop
        found = converged(e);
        if (found || cost < best_cost) {
            best = x;
            best_e = e;
        }
    }
    q = best;
    if (iterations != nullptr) {
        *iterations = steps;
    }
    if (position_error != nullptr) {
        *position_error = best_e.template head<3>().norm();
    }
    if (orientation_error != nullptr) {
        *orientation_error = best_e.template tail<3>().norm();
    }
    return found;
}

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
