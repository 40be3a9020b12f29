/* The numeric runtime of the c99 target: linear algebra and the self-test driver, C99 with the standard library.
 *
 * Every generated c99 source carries the part of this file below the runtime mark, unchanged (so that it compiles
 * with the C standard library alone); before it, the source defines the type `real` and SJ_DIM, the largest side of
 * any matrix, and includes <tgmath.h> (sqrt and fabs of the type real). Matrices are row-major arrays. Every
 * function is static inline, and a module carries only the sections it uses (the core: the self-test's driver
 * helpers and its pose and Jacobian checks; another section when a routine or check of the module needs it).
 * Tested on its own: tests/test_codegen_runtime.py compiles it with a small driver and compares with numpy.linalg.
 */
#include <stddef.h>
#include <string.h>
#include <tgmath.h>

/* ---- runtime: everything below is copied into every generated module of the target ---- */

/* A function of one configuration writing its output: (q, params, out), or with an input between (F, qdot). */
typedef void (*sj_map)(const real *q, const real *params, real *out);
typedef void (*sj_map_with)(const real *q, const real *params, const real *input, real *out);

/* ---- runtime section: lu_determinant ---- */

/* Determinant of the n x n row-major matrix a (overwritten): Gaussian elimination with partial pivoting. */
static inline real sj_lu_determinant(real *a, int n)
{
    real result = 1;
    for (int k = 0; k < n; k++) {
        int pivot = k;
        for (int r = k + 1; r < n; r++) {
            if (fabs(a[r * n + k]) > fabs(a[pivot * n + k])) {
                pivot = r;
            }
        }
        if (a[pivot * n + k] == 0) {
            return 0;
        }
        if (pivot != k) {
            for (int c = 0; c < n; c++) {
                const real swap = a[k * n + c];
                a[k * n + c] = a[pivot * n + c];
                a[pivot * n + c] = swap;
            }
            result = -result;
        }
        result *= a[k * n + k];
        for (int r = k + 1; r < n; r++) {
            const real factor = a[r * n + k] / a[k * n + k];
            for (int c = k + 1; c < n; c++) {
                a[r * n + c] -= factor * a[k * n + c];
            }
        }
    }
    return result;
}

/* ---- runtime section: determinant; needs: lu_determinant ---- */

/* det J of a square rows x cols Jacobian J (overwritten; cols == rows): the routine of the determinant kind. */
static inline real sj_determinant(real *J, int rows, int cols)
{
    (void)cols;
    return sj_lu_determinant(J, rows);
}

/* ---- runtime section: gram ---- */

/* The Gram matrix of the shorter side of the rows x cols matrix J: J J^T (wide) or J^T J (tall); its side. */
static inline int sj_gram(const real *J, int rows, int cols, real *g)
{
    const int wide = rows <= cols;
    const int small = wide ? rows : cols, large = wide ? cols : rows;
    for (int r = 0; r < small; r++) {
        for (int c = 0; c < small; c++) {
            real sum = 0;
            for (int k = 0; k < large; k++) {
                sum += wide ? J[r * cols + k] * J[c * cols + k] : J[k * cols + r] * J[k * cols + c];
            }
            g[r * small + c] = sum;
        }
    }
    return small;
}

/* ---- runtime section: manipulability; needs: lu_determinant, gram ---- */

/* w = |det J| for a square J, else sqrt(det(G)) with G the Gram matrix of the shorter side. */
static inline real sj_manipulability(const real *J, int rows, int cols)
{
    real g[SJ_DIM * SJ_DIM];
    if (rows == cols) {
        for (int k = 0; k < rows * cols; k++) {
            g[k] = J[k];
        }
        return fabs(sj_lu_determinant(g, rows));
    }
    const real d = sj_lu_determinant(g, sj_gram(J, rows, cols, g));
    return d > 0 ? sqrt(d) : 0;
}

/* ---- runtime section: solve ---- */

/* Gauss-Jordan with partial pivoting on [g | x], g n x n and x n x m (both overwritten): x becomes g^-1 x. */
static inline void sj_solve(real *g, real *x, int n, int m)
{
    for (int k = 0; k < n; k++) {
        int pivot = k;
        for (int r = k + 1; r < n; r++) {
            if (fabs(g[r * n + k]) > fabs(g[pivot * n + k])) {
                pivot = r;
            }
        }
        for (int c = 0; c < n; c++) {
            const real swap = g[k * n + c];
            g[k * n + c] = g[pivot * n + c];
            g[pivot * n + c] = swap;
        }
        for (int c = 0; c < m; c++) {
            const real swap = x[k * m + c];
            x[k * m + c] = x[pivot * m + c];
            x[pivot * m + c] = swap;
        }
        const real diagonal = g[k * n + k];
        for (int c = 0; c < n; c++) {
            g[k * n + c] /= diagonal;
        }
        for (int c = 0; c < m; c++) {
            x[k * m + c] /= diagonal;
        }
        for (int r = 0; r < n; r++) {
            if (r == k) {
                continue;
            }
            const real factor = g[r * n + k];
            for (int c = 0; c < n; c++) {
                g[r * n + c] -= factor * g[k * n + c];
            }
            for (int c = 0; c < m; c++) {
                x[r * m + c] -= factor * x[k * m + c];
            }
        }
    }
}

/* ---- runtime section: manipulability_gradient; needs: gram, lu_determinant, solve ---- */

/* dw/dq_m = w trace(J^+ H_m), H_m[i][j] = H[(i * cols + j) * cols + m]; J^+ through one solve with the Gram matrix
 * G: J^+ = (G^-1 J)^T for a wide J, G^-1 J^T for a tall one. Zero where w = 0 (a kink, not a gradient). */
static inline void sj_manipulability_gradient(const real *J, const real *H, int rows, int cols, real *gradient)
{
    real g[SJ_DIM * SJ_DIM], a[SJ_DIM * SJ_DIM], x[SJ_DIM * SJ_DIM];
    const int wide = rows <= cols;
    const int small = sj_gram(J, rows, cols, g), large = wide ? cols : rows;
    for (int k = 0; k < small * small; k++) {
        a[k] = g[k];
    }
    const real d = sj_lu_determinant(a, small);
    const real w = d > 0 ? sqrt(d) : 0;
    for (int m = 0; m < cols; m++) {
        gradient[m] = 0;
    }
    if (w == 0) {
        return;
    }
    for (int i = 0; i < small; i++) {
        for (int j = 0; j < large; j++) {
            x[i * large + j] = wide ? J[i * cols + j] : J[j * cols + i];
        }
    }
    sj_solve(g, x, small, large);
    for (int m = 0; m < cols; m++) {
        real trace = 0;
        for (int i = 0; i < rows; i++) {
            for (int j = 0; j < cols; j++) {
                const real pseudo = wide ? x[i * large + j] : x[j * large + i]; /* J^+[j][i] */
                trace += pseudo * H[(i * cols + j) * cols + m];
            }
        }
        gradient[m] = w * trace;
    }
}

/* ---- runtime section: cholesky_solve ---- */

/* x with M x = b for a symmetric positive definite n x n M (a mass matrix): M = L L^T, L y = b, L^T x = y.
 * L[i][i] = sqrt(M[i][i] - sum_k<i L[i][k]^2), L[r][i] = (M[r][i] - sum_k<i L[r][k] L[i][k]) / L[i][i].
 * Returns 1, or 0 (x untouched) when a pivot is not positive: M is not positive definite. */
static inline int sj_cholesky_solve(const real *M, const real *b, int n, real *x)
{
    real L[SJ_DIM * SJ_DIM], y[SJ_DIM];
    for (int i = 0; i < n; i++) {
        real pivot = M[i * n + i];
        for (int k = 0; k < i; k++) {
            pivot -= L[i * n + k] * L[i * n + k];
        }
        if (!(pivot > 0)) {
            return 0;
        }
        L[i * n + i] = sqrt(pivot);
        for (int r = i + 1; r < n; r++) {
            real sum = M[r * n + i];
            for (int k = 0; k < i; k++) {
                sum -= L[r * n + k] * L[i * n + k];
            }
            L[r * n + i] = sum / L[i * n + i];
        }
    }
    for (int i = 0; i < n; i++) {
        real sum = b[i];
        for (int k = 0; k < i; k++) {
            sum -= L[i * n + k] * y[k];
        }
        y[i] = sum / L[i * n + i];
    }
    for (int i = n - 1; i >= 0; i--) {
        real sum = y[i];
        for (int k = i + 1; k < n; k++) {
            sum -= L[k * n + i] * x[k];
        }
        x[i] = sum / L[i * n + i];
    }
    return 1;
}

/* ---- runtime section: core ---- */

/* |a - b| within tolerance relative to 1 + |b|: 0 when it is, else 1 (a count of failures). */
static inline int sj_differs(real a, real b, real tolerance)
{
    return !(fabs(a - b) <= tolerance * (1 + fabs(b)));
}

/* Self-test configuration `sample`: q[k] = 1.4 sin(0.7 (sample + 1)(k + 1) + 0.3 k), spread and reproducible. */
static inline void sj_sample(int sample, int n, real *q)
{
    for (int k = 0; k < n; k++) {
        q[k] = (real)1.4 * sin((real)0.7 * (real)((sample + 1) * (k + 1)) + (real)0.3 * (real)k);
    }
}

/* Every check takes (n, size, rows, its functions, q, h, tolerance) and returns its count of failures. */

/* The forward kinematics is a rigid transform: R^T R = I and the last row is (0, 0, 0, 1). */
static inline int sj_check_pose(int n, int size, const int *rows, sj_map forward_kinematics, const real *q, real h,
                                real tolerance)
{
    real T[16];
    int failures = 0;
    (void)n;
    (void)size;
    (void)rows;
    (void)h;
    forward_kinematics(q, NULL, T);
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) {
            real dot = 0;
            for (int k = 0; k < 3; k++) {
                dot += T[k * 4 + r] * T[k * 4 + c];
            }
            failures += sj_differs(dot, r == c ? 1 : 0, tolerance);
        }
    }
    for (int c = 0; c < 4; c++) {
        failures += sj_differs(T[12 + c], c == 3 ? 1 : 0, tolerance);
    }
    return failures;
}

/* A Jacobian (rows `rows` of [v; omega], size of them, n columns) against central differences of its kinematics
 * (point position, ^0_nR and ^0_kR: 21 values; omega from dR R^T), turned into frame {k}; its torques against
 * J^T F. */
static inline int sj_check_jacobian(int n, int size, const int *rows, sj_map jacobian, sj_map_with torques,
                                    sj_map kinematics, const real *q, real h, real tolerance)
{
    real J[6 * SJ_DIM], at[21], plus[21], minus[21], step[SJ_DIM], F[6], tau[SJ_DIM];
    int failures = 0;
    jacobian(q, NULL, J);
    kinematics(q, NULL, at);
    for (int m = 0; m < n; m++) {
        real twist[6];
        for (int k = 0; k < n; k++) {
            step[k] = q[k];
        }
        step[m] = q[m] + h;
        kinematics(step, NULL, plus);
        step[m] = q[m] - h;
        kinematics(step, NULL, minus);
        for (int i = 0; i < 3; i++) {
            /* v in {0}, then omega in {0} from W = dR R^T: omega = (W[2][1], W[0][2], W[1][0]) */
            const int a = (i + 2) % 3, b = (i + 1) % 3;
            real w = 0;
            for (int c = 0; c < 3; c++) {
                w += (plus[3 + a * 3 + c] - minus[3 + a * 3 + c]) / (2 * h) * at[3 + b * 3 + c];
            }
            twist[i] = (plus[i] - minus[i]) / (2 * h);
            twist[3 + i] = w;
        }
        for (int k = 0; k < size; k++) {
            /* the row in frame {k}: (R_0k^T v)[i] or (R_0k^T omega)[i] */
            const int base = rows[k] < 3 ? 0 : 3, i = rows[k] % 3;
            real expected = 0;
            for (int r = 0; r < 3; r++) {
                expected += at[12 + r * 3 + i] * twist[base + r];
            }
            failures += sj_differs(J[k * n + m], expected, tolerance);
        }
    }
    for (int k = 0; k < size; k++) {
        F[k] = (real)0.3 + (real)0.2 * (real)k;
    }
    torques(q, NULL, F, tau);
    for (int m = 0; m < n; m++) {
        real expected = 0;
        for (int k = 0; k < size; k++) {
            expected += J[k * n + m] * F[k];
        }
        failures += sj_differs(tau[m], expected, tolerance);
    }
    return failures;
}

/* ---- runtime section: acceleration ---- */

/* A scalar function of one configuration (the manipulability the acceleration check differentiates). */
typedef real (*sj_scalar)(const real *q, const real *params);

/* The Hessian, the manipulability gradient and the bias acceleration Jdot qdot of a Jacobian (size x n) against
 * central differences of the Jacobian and of w^2 = det(J J^T) (2 w dw/dq_m: the square root in w would amplify the
 * rounding of det near a singularity). */
static inline int sj_check_acceleration(int n, int size, const int *rows, sj_map jacobian, sj_map hessian,
                                        sj_map_with bias, sj_scalar manipulability, sj_map manipulability_gradient,
                                        const real *q, real h, real tolerance)
{
    real H[6 * SJ_DIM * SJ_DIM], Jplus[6 * SJ_DIM], Jminus[6 * SJ_DIM], qdot[SJ_DIM], out[6], step[SJ_DIM];
    real gradient[SJ_DIM];
    int failures = 0;
    (void)rows;
    hessian(q, NULL, H);
    manipulability_gradient(q, NULL, gradient);
    const real w = manipulability(q, NULL);
    for (int m = 0; m < n; m++) {
        for (int k = 0; k < n; k++) {
            step[k] = q[k];
        }
        step[m] = q[m] + h;
        jacobian(step, NULL, Jplus);
        const real above = manipulability(step, NULL);
        step[m] = q[m] - h;
        jacobian(step, NULL, Jminus);
        const real below = manipulability(step, NULL);
        for (int i = 0; i < size * n; i++) {
            failures += sj_differs(H[i * n + m], (Jplus[i] - Jminus[i]) / (2 * h), tolerance);
        }
        failures += sj_differs(2 * w * gradient[m], (above * above - below * below) / (2 * h), tolerance);
    }
    for (int k = 0; k < n; k++) {
        qdot[k] = (real)0.7 - (real)0.3 * (real)k;
    }
    bias(q, NULL, qdot, out);
    for (int k = 0; k < n; k++) {
        step[k] = q[k] + h * qdot[k];
    }
    jacobian(step, NULL, Jplus);
    for (int k = 0; k < n; k++) {
        step[k] = q[k] - h * qdot[k];
    }
    jacobian(step, NULL, Jminus);
    for (int i = 0; i < size; i++) {
        real expected = 0;
        for (int k = 0; k < n; k++) {
            expected += (Jplus[i * n + k] - Jminus[i * n + k]) / (2 * h) * qdot[k];
        }
        failures += sj_differs(out[i], expected, tolerance);
    }
    return failures;
}

/* ---- runtime section: forward_dynamics; needs: cholesky_solve ---- */

/* qddot = M^-1 (tau - b) by a Cholesky solve: M the n x n mass matrix, b = C qdot + g the bias forces; NaN when M is
 * not positive definite. */
static inline void sj_forward_dynamics(const real *M, const real *b, int n, int columns, const real *tau, real *qddot)
{
    real rest[SJ_DIM];
    (void)columns;
    for (int i = 0; i < n; i++) {
        rest[i] = tau[i] - b[i];
    }
    if (!sj_cholesky_solve(M, rest, n, qddot)) {
        for (int i = 0; i < n; i++) {
            qddot[i] = (real)NAN;
        }
    }
}

/* ---- runtime section: dynamics; needs: cholesky_solve ---- */

/* A function of one configuration and two inputs (inverse dynamics: qdot, qddot; forward dynamics: qdot, tau). */
typedef void (*sj_map_with2)(const real *q, const real *params, const real *a, const real *b, real *out);

/* The dynamics against each other and central differences of M and V: M symmetric positive definite; Mdot - 2C
 * skew (Mdot = (M(q + h qdot) - M(q - h qdot)) / 2h); g = tau(q, 0, 0); column j of M = tau(q, 0, e_j) - g;
 * tau(q, qdot, qddot) = M qddot + C qdot + g; b = C qdot + g; forward dynamics of that tau gives qddot back;
 * g_j = (V(q + h e_j) - V(q - h e_j)) / 2h, V the potential energy. */
static inline int sj_check_dynamics(int n, int size, const int *rows, sj_map_with2 inverse_dynamics,
                                    sj_map mass_matrix, sj_map_with coriolis_matrix, sj_map_with bias_forces,
                                    sj_map gravity_torques, sj_map_with2 forward_dynamics,
                                    real (*potential_energy)(const real *q, const real *params), const real *q,
                                    real h, real tolerance)
{
    real M[SJ_DIM * SJ_DIM], C[SJ_DIM * SJ_DIM], above[SJ_DIM * SJ_DIM], below[SJ_DIM * SJ_DIM];
    real g[SJ_DIM], qdot[SJ_DIM], qddot[SJ_DIM], zero[SJ_DIM], unit[SJ_DIM], tau[SJ_DIM], out[SJ_DIM];
    real step[SJ_DIM], solution[SJ_DIM];
    int failures = 0;
    (void)size;
    (void)rows;
    for (int k = 0; k < n; k++) {
        qdot[k] = (real)0.7 - (real)0.3 * (real)k;
        qddot[k] = (real)0.5 - (real)0.25 * (real)k + (real)0.3 * qdot[k];
        zero[k] = 0;
    }
    mass_matrix(q, NULL, M);
    coriolis_matrix(q, NULL, qdot, C);
    gravity_torques(q, NULL, g);
    failures += !sj_cholesky_solve(M, qdot, n, solution);
    for (int k = 0; k < n; k++) {
        step[k] = q[k] + h * qdot[k];
    }
    mass_matrix(step, NULL, above);
    for (int k = 0; k < n; k++) {
        step[k] = q[k] - h * qdot[k];
    }
    mass_matrix(step, NULL, below);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            const real skew = (above[i * n + j] - below[i * n + j]) / (2 * h) - 2 * C[i * n + j];
            const real mirror = (above[j * n + i] - below[j * n + i]) / (2 * h) - 2 * C[j * n + i];
            failures += sj_differs(M[i * n + j], M[j * n + i], tolerance);
            failures += sj_differs(skew, -mirror, tolerance);
        }
    }
    inverse_dynamics(q, NULL, zero, zero, out);
    for (int i = 0; i < n; i++) {
        failures += sj_differs(g[i], out[i], tolerance);
    }
    for (int j = 0; j < n; j++) {
        for (int k = 0; k < n; k++) {
            unit[k] = k == j ? 1 : 0;
        }
        inverse_dynamics(q, NULL, zero, unit, out);
        for (int i = 0; i < n; i++) {
            failures += sj_differs(M[i * n + j], out[i] - g[i], tolerance);
        }
        for (int k = 0; k < n; k++) {
            step[k] = q[k] + (k == j ? h : 0);
        }
        const real V_above = potential_energy(step, NULL);
        step[j] = q[j] - h;
        failures += sj_differs(g[j], (V_above - potential_energy(step, NULL)) / (2 * h), tolerance);
    }
    inverse_dynamics(q, NULL, qdot, qddot, tau);
    bias_forces(q, NULL, qdot, out);
    for (int i = 0; i < n; i++) {
        real Cqdot = 0, Mqddot = 0;
        for (int k = 0; k < n; k++) {
            Cqdot += C[i * n + k] * qdot[k];
            Mqddot += M[i * n + k] * qddot[k];
        }
        failures += sj_differs(out[i], Cqdot + g[i], tolerance);
        failures += sj_differs(tau[i], Mqddot + Cqdot + g[i], tolerance);
    }
    forward_dynamics(q, NULL, qdot, tau, out);
    for (int i = 0; i < n; i++) {
        failures += sj_differs(out[i], qddot[i], tolerance);
    }
    return failures;
}

/* ---- runtime section: identification; needs: dynamics ---- */

/* A regressor times the robot's own parameters against inverse dynamics: Y(q, qdot, qddot) pi = tau(q, qdot,
 * qddot). rows[0] is the regressor's column count p (size is 1); pi comes from values(q). */
static inline int sj_check_identification(int n, int size, const int *rows, sj_map_with2 inverse_dynamics,
                                          sj_map_with2 regressor, sj_map values, const real *q, real h,
                                          real tolerance)
{
    const int p = rows[0];
    real Y[SJ_DIM * p], parameters[p];
    real qdot[SJ_DIM], qddot[SJ_DIM], tau[SJ_DIM];
    int failures = 0;
    (void)size;
    (void)h;
    for (int k = 0; k < n; k++) {
        qdot[k] = (real)0.7 - (real)0.3 * (real)k;
        qddot[k] = (real)0.5 - (real)0.25 * (real)k + (real)0.3 * qdot[k];
    }
    inverse_dynamics(q, NULL, qdot, qddot, tau);
    regressor(q, NULL, qdot, qddot, Y);
    values(q, NULL, parameters);
    for (int i = 0; i < n; i++) {
        real value = 0;
        for (int j = 0; j < p; j++) {
            value += Y[i * p + j] * parameters[j];
        }
        failures += sj_differs(value, tau[i], tolerance);
    }
    return failures;
}

/* ---- runtime section: ik_numeric ---- */

/* splitmix64 (Steele, Lea and Flood 2014): the numeric solver's seeds, the same sequence on every platform. */
static inline unsigned long long sj_splitmix64(unsigned long long *state)
{
    unsigned long long z = (*state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/* The rotation vector (axis times angle) of the row-major rotation r, robust near 0 and pi. */
static inline void sj_rotation_vector(const real *r, real *w)
{
    const real pi = (real)3.14159265358979323846;
    real cosine = (r[0] + r[4] + r[8] - 1) / 2;
    cosine = cosine > 1 ? 1 : (cosine < -1 ? -1 : cosine);
    const real angle = acos(cosine);
    w[0] = r[7] - r[5];
    w[1] = r[2] - r[6];
    w[2] = r[3] - r[1];
    if (angle < (real)1e-6) {
        for (int k = 0; k < 3; k++) {
            w[k] /= 2;
        }
    } else if (pi - angle > (real)1e-4) {
        const real scale = angle / (2 * sin(angle));
        for (int k = 0; k < 3; k++) {
            w[k] *= scale;
        }
    } else { /* near pi: the axis from the symmetric part (r + I) / 2, its largest diagonal entry's row */
        int m = 0;
        for (int k = 1; k < 3; k++) {
            m = r[4 * k] > r[4 * m] ? k : m;
        }
        real axis[3];
        real norm = 0;
        real dot = 0;
        for (int k = 0; k < 3; k++) {
            axis[k] = (r[3 * m + k] + (k == m ? 1 : 0)) / 2;
            norm += axis[k] * axis[k];
            dot += axis[k] * w[k];
        }
        norm = (dot < 0 ? -angle : angle) / sqrt(norm);
        for (int k = 0; k < 3; k++) {
            w[k] = axis[k] * norm;
        }
    }
}

/* e = [p* - p; log(R* R^T)] of the pose T (row-major 4 x 4) against the target; returns e^T e. */
static inline real sj_ik_error(const real *target, const real *T, real *e)
{
    real r[9];
    for (int i = 0; i < 3; i++) {
        e[i] = target[4 * i + 3] - T[4 * i + 3];
        for (int j = 0; j < 3; j++) {
            r[3 * i + j] = 0;
            for (int k = 0; k < 3; k++) {
                r[3 * i + j] += target[4 * i + k] * T[4 * j + k];
            }
        }
    }
    sj_rotation_vector(r, e + 3);
    real cost = 0;
    for (int i = 0; i < 6; i++) {
        cost += e[i] * e[i];
    }
    return cost;
}

/* The angle x wrapped to (-pi, pi] (unchanged when it is in already). */
static inline real sj_ik_wrap_angle(real x)
{
    const real pi = (real)3.14159265358979323846;
    return (x > pi || x <= -pi) ? pi - fmod(fmod(pi - x, 2 * pi) + 2 * pi, 2 * pi) : x;
}

/* Joint kinds: 0 prismatic, 1 revolute with limits, 2 revolute without (wrapped to (-pi, pi]). Clip q to [lower,
 * upper] (no clipping when lower is NULL) and wrap the joints of kind 2. */
static inline void sj_ik_project(int n, const real *lower, const real *upper, const int *kind, real *q)
{
    for (int k = 0; k < n; k++) {
        if (kind[k] == 2) {
            q[k] = sj_ik_wrap_angle(q[k]);
        } else if (lower != NULL) {
            q[k] = q[k] < lower[k] ? lower[k] : (q[k] > upper[k] ? upper[k] : q[k]);
        }
    }
}

/* Shift each angle by 2 pi k (the same pose) into its limits where a shift fits, else clip it: 1 when all fitted. */
static inline int sj_ik_into_limits(int n, const real *lower, const real *upper, const int *kind, real *q)
{
    const real pi = (real)3.14159265358979323846;
    int inside = 1;
    for (int k = 0; k < n; k++) {
        const real value = kind[k] ? sj_ik_wrap_angle(q[k]) : q[k];
        int fits = 0;
        for (int shift = 0; shift < (kind[k] ? 5 : 1) && !fits; shift++) {
            const real x = value + (real)((shift + 1) / 2 * (shift % 2 ? 1 : -1)) * 2 * pi;
            if (lower[k] <= x && x <= upper[k]) {
                q[k] = x;
                fits = 1;
            }
        }
        if (!fits) {
            q[k] = value < lower[k] ? lower[k] : (value > upper[k] ? upper[k] : value);
            inside = 0;
        }
    }
    return inside;
}

/* Solve a x = b in place (a n x n symmetric positive definite, row-major; its strict lower triangle becomes the unit
 * lower L of a = L D L^T) by LDL^T: b becomes x. No square root and one division per row (a Cholesky factor's
 * square roots and divisions lie on the dependency chain). */
static inline void sj_ik_cholesky(real *a, real *b, int n)
{
    real inverse[SJ_DIM]; /* 1 / D */
    real t[SJ_DIM];       /* row i of L D */
    for (int i = 0; i < n; i++) {
        real d = a[i * n + i];
        for (int j = 0; j < i; j++) {
            real s = a[i * n + j];
            for (int k = 0; k < j; k++) {
                s -= t[k] * a[j * n + k];
            }
            t[j] = s;
        }
        for (int j = 0; j < i; j++) {
            const real l = t[j] * inverse[j];
            d -= t[j] * l;
            a[i * n + j] = l;
        }
        inverse[i] = 1 / d;
    }
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < i; k++) {
            b[i] -= a[i * n + k] * b[k];
        }
    }
    for (int i = n - 1; i >= 0; i--) {
        b[i] *= inverse[i];
        for (int k = i + 1; k < n; k++) {
            b[i] -= a[k * n + i] * b[k];
        }
    }
}

/* J^T r, J 6 x n row-major. */
static inline void sj_ik_transpose_times(int n, const real *J, const real *r, real *out)
{
    for (int i = 0; i < n; i++) {
        out[i] = 0;
        for (int k = 0; k < 6; k++) {
            out[i] += J[k * n + i] * r[k];
        }
    }
}

/* x = (J^T J + lambda I)^-1 b over the joints not held (x = 0 for those: their rows and columns are the
 * identity's), from the normal matrix J^T J (n x n, row-major). */
static inline void sj_ik_solve(int n, const real *normal, const real *b, real lambda, const int *held, real *x)
{
    real a[SJ_DIM * SJ_DIM];
    for (int i = 0; i < n; i++) {
        x[i] = held[i] ? 0 : b[i];
        for (int j = 0; j < n; j++) {
            a[i * n + j] = (held[i] || held[j]) ? (i == j ? 1 : 0) : normal[i * n + j] + (i == j ? lambda : 0);
        }
    }
    sj_ik_cholesky(a, x, n);
}

/* One damped least-squares step (J^T J + lambda I) dq = J^T e (the gradient), the joints at a limit that it would
 * push past held still (held[i] = 1) and the step solved again (no limits when lower is NULL). */
static inline void sj_ik_step(int n, const real *normal, const real *gradient, real lambda, const real *q,
                              const real *lower, const real *upper, real *step, int *held)
{
    for (int i = 0; i < n; i++) {
        held[i] = 0;
    }
    for (int round = 0; round < n; round++) {
        sj_ik_solve(n, normal, gradient, lambda, held, step);
        int more = 0;
        for (int i = 0; i < n; i++) {
            if (lower != NULL && !held[i]
                && ((q[i] <= lower[i] && step[i] < 0) || (q[i] >= upper[i] && step[i] > 0))) {
                held[i] = more = 1;
            }
        }
        if (!more) {
            return;
        }
    }
}

/* Transtrum and Sethna's geodesic acceleration of the step v, once E < 1e-6: f_vv = (2 / h) ((f(q + h v) - f(q)) / h
 * - J v) with h = 0.1 (from the error e = f* - f), (J^T J + lambda I) a = -J^T f_vv, and v += a / 2 when
 * 2 |a| <= 0.75 |v|: it follows the curved valleys of the cost near a singular solution. */
static inline void sj_ik_accelerate(int n, sj_map forward_kinematics, const real *params, const real *target,
                                    const real *J, const real *normal, const real *e, real lambda, const int *held,
                                    const real *x, real *step)
{
    real probe[SJ_DIM], acceleration[SJ_DIM], b[SJ_DIM], T[16], e_probe[6], curvature[6];
    for (int k = 0; k < n; k++) {
        probe[k] = x[k] + (real)0.1 * step[k];
    }
    forward_kinematics(probe, params, T);
    sj_ik_error(target, T, e_probe);
    for (int r = 0; r < 6; r++) {
        real moved = 0;
        for (int k = 0; k < n; k++) {
            moved += J[r * n + k] * step[k];
        }
        curvature[r] = 20 * ((e_probe[r] - e[r]) / (real)0.1 + moved); /* -f_vv */
    }
    sj_ik_transpose_times(n, J, curvature, b);
    sj_ik_solve(n, normal, b, lambda, held, acceleration);
    real a2 = 0;
    real v2 = 0;
    for (int k = 0; k < n; k++) {
        a2 += acceleration[k] * acceleration[k];
        v2 += step[k] * step[k];
    }
    if (4 * a2 <= (real)0.5625 * v2) {
        for (int k = 0; k < n; k++) {
            step[k] += acceleration[k] / 2;
        }
    }
}

/* Both error norms within the tolerance: 1e-10 (1e-4 in single precision). */
static inline int sj_ik_converged(const real *e)
{
    const real tolerance = sizeof(real) < sizeof(double) ? (real)1e-4 : (real)1e-10;
    return e[0] * e[0] + e[1] * e[1] + e[2] * e[2] <= tolerance * tolerance
           && e[3] * e[3] + e[4] * e[4] + e[5] * e[5] <= tolerance * tolerance;
}

/* One start of Levenberg-Marquardt with Sugihara's damping lambda = mu (E / 2 + 1e-3), E = e^T e, e = [p* - p(q);
 * log(R* R(q)^T)], and geodesic acceleration once E < 1e-6: mu halves after an accepted step and grows 4 times
 * after a rejected one; the start ends after 100 steps or `patience` steps without the cost falling by 10 % (while
 * E > 1e-10; 4 for a start, 100 for the closest configuration's last descent). Limits when lower is not NULL.
 * x is overwritten by the configuration reached and e by its error; *steps counts the steps; returns the cost E. */
static inline real sj_ik_descend(int n, sj_map forward_kinematics, sj_map jacobian, const real *params,
                                 const real *lower, const real *upper, const int *kind, const real *target, real *x,
                                 real *e, int *steps, int patience)
{
    real trial[SJ_DIM], step[SJ_DIM], T[16], e_trial[6], J[6 * SJ_DIM], normal[SJ_DIM * SJ_DIM], gradient[SJ_DIM];
    int held[SJ_DIM];
    int moved = 1; /* J, J^T J and J^T e are those of x unless it moved */
    sj_ik_project(n, lower, upper, kind, x);
    forward_kinematics(x, params, T);
    real cost = sj_ik_error(target, T, e);
    real reference = cost;
    real mu = 1;
    int stalled = 0;
    for (int it = 0; it < 100 && !sj_ik_converged(e); it++) {
        ++*steps;
        if (moved) {
            jacobian(x, params, J);
            for (int i = 0; i < n; i++) {
                for (int j = 0; j <= i; j++) {
                    real dot = 0;
                    for (int k = 0; k < 6; k++) {
                        dot += J[k * n + i] * J[k * n + j];
                    }
                    normal[i * n + j] = normal[j * n + i] = dot;
                }
            }
            sj_ik_transpose_times(n, J, e, gradient);
        }
        const real lambda = mu * (cost / 2 + (real)1e-3);
        sj_ik_step(n, normal, gradient, lambda, x, lower, upper, step, held);
        if (cost < (real)1e-6) {
            sj_ik_accelerate(n, forward_kinematics, params, target, J, normal, e, lambda, held, x, step);
        }
        for (int k = 0; k < n; k++) {
            trial[k] = x[k] + step[k];
        }
        sj_ik_project(n, lower, upper, kind, trial);
        forward_kinematics(trial, params, T);
        const real c = sj_ik_error(target, T, e_trial);
        moved = c < cost;
        if (moved) {
            memcpy(x, trial, sizeof(real) * (size_t)n);
            memcpy(e, e_trial, sizeof e_trial);
            cost = c;
            mu = mu / 2 > (real)1e-6 ? mu / 2 : (real)1e-6;
        } else {
            mu *= 4;
        }
        if (cost < (real)0.9 * reference || cost < (real)1e-10) {
            reference = cost;
            stalled = 0;
        } else if (++stalled >= patience) {
            break;
        }
    }
    return cost;
}

/* Numeric inverse kinematics, as symjac's solve_numeric: each start descends without limits first; a solution it
 * reaches is shifted by 2 pi into the limits, and when a joint does not fit, a redundant arm (n > 6) goes on from the
 * clipped configuration with the limits respected (a joint at a limit that a step would push past is held still;
 * an arm with n <= 6 has isolated solutions: it restarts). Starts from `start` (when not NULL), then from seeds
 * drawn uniformly in [low, high] by splitmix64 from `seed`, at most 64 starts. When none converges, the closest
 * configuration reached (the least cost E, clipped into the limits) descends once more within the limits (no
 * early stop). Writes
 * q (the solution, or that closest configuration), the steps taken in all and the position (m) and orientation
 * (rad) error norms of q (each when not NULL); returns 1 when q reaches the pose, else 0. */
static inline int sj_ik_numeric(int n, sj_map forward_kinematics, sj_map jacobian, const real *params,
                                const real *lower, const real *upper, const int *kind, const real *low,
                                const real *high, const real *target, const real *start, unsigned long long seed,
                                real *q, int *iterations, real *position_error, real *orientation_error)
{
    unsigned long long state = seed;
    real best[SJ_DIM], T[16];
    real best_e[6] = {0, 0, 0, 0, 0, 0};
    real best_cost = (real)HUGE_VAL;
    int steps = 0;
    int found = 0;
    for (int attempt = 0; attempt < 64 && !found; attempt++) {
        real x[SJ_DIM], e[6];
        for (int k = 0; k < n; k++) {
            const real u = (real)((double)(sj_splitmix64(&state) >> 11) * (1.0 / 9007199254740992.0));
            x[k] = (attempt == 0 && start != NULL) ? start[k] : low[k] + u * (high[k] - low[k]);
        }
        real cost = sj_ik_descend(n, forward_kinematics, jacobian, params, NULL, NULL, kind, target, x, e, &steps,
                                  4);
        found = sj_ik_converged(e);
        const int inside = sj_ik_into_limits(n, lower, upper, kind, x); /* else clipped into them */
        if (found && !inside && n > 6) {
            cost = sj_ik_descend(n, forward_kinematics, jacobian, params, lower, upper, kind, target, x, e, &steps,
                                 4);
            found = sj_ik_converged(e);
        } else if (!inside) { /* not converged, or isolated solutions (n <= 6) outside the limits: restart */
            found = 0;
            forward_kinematics(x, params, T);
            cost = sj_ik_error(target, T, e);
        }
        if (found || cost < best_cost || attempt == 0) {
            best_cost = cost;
            memcpy(best, x, sizeof(real) * (size_t)n);
            memcpy(best_e, e, sizeof e);
        }
    }
    if (!found) { /* the closest configuration reached: one more descent from it, within the limits */
        real x[SJ_DIM], e[6];
        memcpy(x, best, sizeof(real) * (size_t)n);
        const real cost = sj_ik_descend(n, forward_kinematics, jacobian, params, lower, upper, kind, target, x, e,
                                        &steps, 100);
        found = sj_ik_converged(e);
        if (found || cost < best_cost) {
            memcpy(best, x, sizeof(real) * (size_t)n);
            memcpy(best_e, e, sizeof e);
        }
    }
    memcpy(q, best, sizeof(real) * (size_t)n);
    if (iterations != NULL) {
        *iterations = steps;
    }
    if (position_error != NULL) {
        *position_error = sqrt(best_e[0] * best_e[0] + best_e[1] * best_e[1] + best_e[2] * best_e[2]);
    }
    if (orientation_error != NULL) {
        *orientation_error = sqrt(best_e[3] * best_e[3] + best_e[4] * best_e[4] + best_e[5] * best_e[5]);
    }
    return found;
}

/* ---- runtime section: core ---- */

/* q[i] = the position of joint_names[i] in names and positions (count entries; other names are ignored, the first
 * of a repeated name counts): 0 when every joint has a value, else 1 + the index of the first without one; -1 for
 * a NULL array or a negative count. */
static inline int sj_coordinates_from(const char *const *joint_names, int n, const char *const *names,
                                      const real *positions, int count, real *q)
{
    if (names == NULL || positions == NULL || q == NULL || count < 0) {
        return -1;
    }
    for (int i = 0; i < n; i++) {
        int k = 0;
        while (k < count && (names[k] == NULL || strcmp(names[k], joint_names[i]) != 0)) {
            k++;
        }
        if (k == count) {
            return i + 1;
        }
        q[i] = positions[k];
    }
    return 0;
}
