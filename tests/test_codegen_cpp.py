"""The cpp target: a header-only C++17 file on Eigen, compiled here with ``-Wall -Wextra -Werror``.

A small C-ABI shim per robot (written below, not generated) instantiates the templates for double and float and is
called through ctypes: every catalog robot and URDF arm agrees with the python target at 20 random configurations,
with default and other parameters. ``Eigen::AutoDiffScalar`` differentiates the generated functions themselves: the
derivative of the tool position is the Jacobian's linear rows, and the derivative of the Jacobian is the Hessian.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from compiled import SEVERAL, agrees_with_python_target, numbers_only_robot, python_module, two_joint_robot
from marks import marked

from symjac import JacobianRequest, load_robot
from symjac.codegen import CodegenError, ModuleRequest, describe, generate, render_files
from symjac.model.io import catalog

pytestmark = pytest.mark.external  # a C++ compiler and Eigen

GOLDEN = Path(__file__).resolve().parent / "golden"
ROBOTS = [*sorted(catalog()), "gripper.urdf", "panda.urdf", "ur5.urdf"]
EIGEN = Path("/usr/include/eigen3")
FLAGS = ["-std=c++17", "-Wall", "-Wextra", "-Werror", "-O1", f"-I{EIGEN}"]

if shutil.which("g++") is None or not (EIGEN / "Eigen" / "Dense").is_file():  # pragma: no cover - .ci/run installs
    pytest.skip("g++ or Eigen's headers (Debian libeigen3-dev) are missing", allow_module_level=True)

SHIM = """
#include "{robot}.hpp"

using namespace symjac::{robot};
constexpr int N = n_coordinates;
using Vector = Eigen::Matrix<double, N, 1>;

static Params<double> parameters(const double *p)
{{
    Params<double> values;
    if (p != nullptr) {{
{assignments}
    }}
    return values;
}}

static Vector vector(const double *q) {{ return Eigen::Map<const Vector>(q); }}

template <class M>
static void store(const M &m, double *out)
{{
    for (int i = 0; i < m.rows(); i++) {{
        for (int j = 0; j < m.cols(); j++) {{
            out[i * m.cols() + j] = m(i, j);
        }}
    }}
}}

extern "C" {{
void forward_kinematics_(const double *q, const double *p, double *out)
{{
    store(forward_kinematics(vector(q), parameters(p)), out);
}}
void jacobian_(const double *q, const double *p, double *out) {{ store(jacobian(vector(q), parameters(p)), out); }}
void joint_torques_(const double *q, const double *p, const double *F, double *out)
{{
    store(joint_torques(vector(q), Eigen::Matrix<double, 6, 1>(Eigen::Map<const Eigen::Matrix<double, 6, 1>>(F)),
                        parameters(p)), out);
}}
void hessian_(const double *q, const double *p, double *out)
{{
    const auto H = hessian(vector(q), parameters(p));
    for (int m = 0; m < N; m++) {{
        for (int i = 0; i < 6; i++) {{
            for (int j = 0; j < N; j++) {{
                out[(i * N + j) * N + m] = H[m](i, j);
            }}
        }}
    }}
}}
void bias_acceleration_(const double *q, const double *p, const double *qdot, double *out)
{{
    store(bias_acceleration(vector(q), vector(qdot), parameters(p)), out);
}}
void manipulability_gradient_(const double *q, const double *p, double *out)
{{
    store(manipulability_gradient(vector(q), parameters(p)), out);
}}
double manipulability_(const double *q, const double *p) {{ return manipulability(vector(q), parameters(p)); }}
{determinant}
float jacobian_float_(const float *q, float *out)
{{
    using Single = Eigen::Matrix<float, N, 1>;
    const Eigen::Matrix<float, 6, N> J = jacobian(Single(Eigen::Map<const Single>(q)));
    for (int i = 0; i < 6; i++) {{
        for (int j = 0; j < N; j++) {{
            out[i * N + j] = J(i, j);
        }}
    }}
    return J(0, 0);
}}
}}
"""

DETERMINANT = """double jacobian_determinant_(const double *q, const double *p)
{
    return jacobian_determinant(vector(q), parameters(p));
}"""


class Shim:
    """The generated header behind a C-ABI shim, compiled into a shared library and called through ctypes."""

    def __init__(self, folder: Path, robot, files: dict[str, str]):
        for name, text in files.items():
            (folder / name).write_text(text)
        assignments = "\n".join(f"        values.{p.name} = p[{k}];" for k, p in enumerate(robot.geometric_parameters))
        square = robot.n_coordinates == 6
        (folder / "shim.cpp").write_text(SHIM.format(robot=robot.name, assignments=assignments,
                                                     determinant=DETERMINANT if square else ""))
        subprocess.run(["g++", *FLAGS, "-fPIC", "-shared", "shim.cpp", "-o", "libshim.so"], cwd=folder, check=True,
                       capture_output=True, text=True)
        self.library = ctypes.CDLL(str(folder / "libshim.so"))

    @staticmethod
    def _pointer(array: np.ndarray | None, ctype=ctypes.c_double):
        return None if array is None else array.ctypes.data_as(ctypes.POINTER(ctype))

    def call(self, name: str, size: int, *inputs: np.ndarray | None) -> np.ndarray:
        arrays = [None if a is None else np.ascontiguousarray(a, dtype=float) for a in inputs]
        out = np.zeros(size)
        getattr(self.library, f"{name}_")(*(self._pointer(a) for a in arrays), self._pointer(out))
        return out

    def scalar(self, name: str, q: np.ndarray, params: np.ndarray | None) -> float:
        function = getattr(self.library, f"{name}_")
        function.restype = ctypes.c_double
        arrays = [None if a is None else np.ascontiguousarray(a, dtype=float) for a in (q, params)]
        return float(function(*(self._pointer(a) for a in arrays)))

    def jacobian_float(self, q: np.ndarray, n: int) -> np.ndarray:
        out = np.zeros(6 * n, dtype=np.float32)
        self.library.jacobian_float_(self._pointer(q.astype(np.float32), ctypes.c_float),
                                     self._pointer(out, ctypes.c_float))
        return out


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_every_function_agrees_with_the_python_target(tmp_path, name):
    robot = load_robot(name)
    shim = Shim(tmp_path, robot, render_files(describe(ModuleRequest(robot, "cpp", acceleration=True))))
    agrees_with_python_target(shim, robot)
    q = np.linspace(-1.1, 1.2, robot.n_coordinates)
    np.testing.assert_allclose(shim.jacobian_float(q, robot.n_coordinates),
                               shim.call("jacobian", 6 * robot.n_coordinates, q, None), atol=2e-5)


AUTODIFF = """
#include <cstdio>

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

#include "{robot}.hpp"

using namespace symjac::{robot};
constexpr int N = n_coordinates;
using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

int main()
{{
    double position = 0, hessian_error = 0;
    for (int sample = 0; sample < 5; sample++) {{
        Eigen::Matrix<double, N, 1> q;
        Eigen::Matrix<AD, N, 1> seeded;
        for (int k = 0; k < N; k++) {{
            q(k) = 1.3 * std::sin(0.9 * (sample + 1) * (k + 1));
            seeded(k) = AD(q(k), N, k);
        }}
        const auto T = forward_kinematics(seeded);
        const auto J = jacobian(q);
        const auto Jseeded = jacobian(seeded);
        const auto H = hessian(q);
        for (int m = 0; m < N; m++) {{
            for (int i = 0; i < 3; i++) {{
                position = std::max(position, std::abs(T(i, 3).derivatives()(m) - J(i, m)));
            }}
            for (int i = 0; i < 6; i++) {{
                for (int j = 0; j < N; j++) {{
                    hessian_error = std::max(hessian_error, std::abs(Jseeded(i, j).derivatives()(m) - H[m](i, j)));
                }}
            }}
        }}
    }}
    std::printf("%.3e %.3e\\n", position, hessian_error);
    return 0;
}}
"""


@pytest.mark.parametrize("name", ["planar3r", "stanford", "palletizer",
                                  pytest.param("puma560", marks=pytest.mark.slow)])
def test_autodiff_of_the_generated_functions_gives_the_jacobian_and_the_hessian(tmp_path, name):
    robot = load_robot(name)
    point = "tool" if robot.tool is not None else "wrist"  # where forward_kinematics ends
    request = ModuleRequest(robot, "cpp", jacobians=[JacobianRequest(0, point)], acceleration=True)
    files = render_files(describe(request))
    for file_name, text in files.items():
        (tmp_path / file_name).write_text(text)
    (tmp_path / "autodiff.cpp").write_text(AUTODIFF.format(robot=robot.name))
    subprocess.run(["g++", *FLAGS, "autodiff.cpp", "-o", "autodiff"], cwd=tmp_path, check=True, capture_output=True)
    position, hessian = map(float, subprocess.run([str(tmp_path / "autodiff")], check=True, capture_output=True,
                                                  text=True).stdout.split())
    assert position < 1e-12 and hessian < 1e-12


def test_golden_file_and_determinism():
    files = render_files(describe(ModuleRequest(load_robot("planar2r"), "cpp", acceleration=True)))
    assert files == render_files(describe(ModuleRequest(load_robot("planar2r"), "cpp", acceleration=True)))
    path = GOLDEN / "planar2r_cpp.hpp.golden"
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        path.write_text(files["planar2r.hpp"])
    assert path.read_text() == files["planar2r.hpp"], "review and regenerate with SYMJAC_UPDATE_GOLDEN=1"


@pytest.mark.parametrize(("word", "message"), [("namespace", "is a C\\+\\+ keyword"),
                                               ("nullptr", "is a C\\+\\+ keyword"),
                                               ("Scalar", "would shadow the C\\+\\+ builtin"),
                                               ("Params", "would shadow the C\\+\\+ builtin"),
                                               ("M_PI", "would shadow the C\\+\\+ builtin")])
def test_cpp_reserved_names_are_refused_in_one_line(word, message):
    with pytest.raises(CodegenError, match=f"parameter name '{word}' {message}"):
        generate(two_joint_robot(parameter=word), "cpp")
    with pytest.raises(CodegenError, match=f"robot name '{word}' {message}"):
        generate(two_joint_robot(name=word), "cpp")


SEVERAL_DRIVER = """
#include <cstdio>

#include "fixed.hpp"

int main()
{
    Eigen::Matrix<double, 3, 1> q;
    q << 0.3, -0.7, 0.2;
    const auto a = symjac::fixed::jacobian_2_wrist(q);
    const auto b = symjac::fixed::jacobian_0_p1_r015(q);
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 3; j++) {
            std::printf("%.17g ", a(i, j));
        }
    }
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            std::printf("%.17g ", b(i, j));
        }
    }
    std::printf("%.17g %.17g\\n", symjac::fixed::reach(q), symjac::fixed::jacobian_determinant_0_p1_r015(q));
    return 0;
}
"""


def test_several_jacobians_rows_a_point_a_scalar_and_no_parameters(tmp_path):
    robot = numbers_only_robot()
    for name, text in render_files(describe(ModuleRequest(robot, "cpp", **SEVERAL))).items():
        (tmp_path / name).write_text(text)
    (tmp_path / "several.cpp").write_text(SEVERAL_DRIVER)
    subprocess.run(["g++", *FLAGS, "several.cpp", "-o", "several"], cwd=tmp_path, check=True, capture_output=True)
    values = [float(v) for v in subprocess.run([str(tmp_path / "several")], check=True, capture_output=True,
                                               text=True).stdout.split()]
    reference = python_module(robot, **SEVERAL)
    q = [0.3, -0.7, 0.2]
    expected = [*np.ravel(reference["jacobian_2_wrist"](q)), *np.ravel(reference["jacobian_0_p1_r015"](q)),
                reference["reach"](q), reference["jacobian_determinant_0_p1_r015"](q)]
    np.testing.assert_allclose(values, expected, atol=1e-12)
