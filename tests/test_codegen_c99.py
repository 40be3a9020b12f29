"""The c99 target: a standalone header and source, compiled here with the strictest flags and called through ctypes.

Every catalog robot and URDF arm agrees with the python target at 20 random configurations, with the default and
with other parameters; the self-test in C passes in double and in single precision and fails on a wrong entry; the
files are byte-deterministic (golden files for planar2r) and the C language's reserved names are refused.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from compiled import SEVERAL, agrees_with_python_target, numbers_only_robot, python_module, two_joint_robot
from marks import marked

from symjac import load_robot
from symjac.cli.main import main
from symjac.codegen import CodegenError, ModuleRequest, describe, generate, render_files
from symjac.model.io import catalog

pytestmark = pytest.mark.external  # a C compiler

GOLDEN = Path(__file__).resolve().parent / "golden"
ROBOTS = [*sorted(catalog()), "gripper.urdf", "panda.urdf", "ur5.urdf"]
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2"]

if shutil.which("gcc") is None:  # pragma: no cover - .ci/run installs it
    pytest.skip("gcc is not installed", allow_module_level=True)


class Compiled:
    """A generated c99 pair compiled into a shared library, with NumPy in and out."""

    def __init__(self, folder: Path, files: dict[str, str], real: str = "double"):
        for name, text in files.items():
            (folder / name).write_text(text)
        source = next(name for name in files if name.endswith(".c"))
        prefix = source.removesuffix(".c")
        library = folder / f"lib{prefix}_{real}.so"
        define = [] if real == "double" else [f"-D{prefix.upper()}_REAL=float"]
        subprocess.run(["gcc", *FLAGS, *define, "-fPIC", "-shared", source, "-o", library.name, "-lm"], cwd=folder,
                       check=True, capture_output=True, text=True)
        self.library = ctypes.CDLL(str(library))
        self.prefix = prefix
        self.dtype = np.float64 if real == "double" else np.float32
        self.ctype = ctypes.c_double if real == "double" else ctypes.c_float

    def _pointer(self, array: np.ndarray | None):
        return None if array is None else array.ctypes.data_as(ctypes.POINTER(self.ctype))

    def call(self, name: str, size: int, *inputs: np.ndarray | None) -> np.ndarray:
        """``name(q, params, *more, out)``: ``out`` of ``size`` entries."""
        arrays = [None if a is None else np.ascontiguousarray(a, dtype=self.dtype) for a in inputs]
        out = np.zeros(size, dtype=self.dtype)
        getattr(self.library, f"{self.prefix}_{name}")(*(self._pointer(a) for a in arrays), self._pointer(out))
        return out

    def scalar(self, name: str, q: np.ndarray, params: np.ndarray | None) -> float:
        function = getattr(self.library, f"{self.prefix}_{name}")
        function.restype = self.ctype
        arrays = [np.ascontiguousarray(a, dtype=self.dtype) if a is not None else None for a in (q, params)]
        return float(function(*(self._pointer(a) for a in arrays)))

    def selftest(self) -> int:
        return int(getattr(self.library, f"{self.prefix}_selftest")())


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_every_function_agrees_with_the_python_target(tmp_path, name):
    robot = load_robot(name)
    compiled = Compiled(tmp_path, render_files(describe(ModuleRequest(robot, "c99", acceleration=True))))
    assert compiled.selftest() == 0
    agrees_with_python_target(compiled, robot)


@pytest.mark.parametrize("name", ["planar2r", "stanford", "palletizer", "puma560"])
def test_single_precision_builds_and_passes_its_selftest(tmp_path, name):
    robot = load_robot(name)
    files = render_files(describe(ModuleRequest(robot, "c99", acceleration=True)))
    single = Compiled(tmp_path, files, real="float")
    double = Compiled(tmp_path, files)
    assert single.selftest() == 0
    q = np.linspace(-1.2, 1.3, robot.n_coordinates)
    J = single.call("jacobian", 6 * robot.n_coordinates, q, None)
    assert J.dtype == np.float32
    np.testing.assert_allclose(J, double.call("jacobian", 6 * robot.n_coordinates, q, None), atol=1e-5)


def test_several_jacobians_rows_a_point_a_scalar_and_no_parameters(tmp_path):
    robot = numbers_only_robot()
    compiled = Compiled(tmp_path, render_files(describe(ModuleRequest(robot, "c99", **SEVERAL))))
    reference = python_module(robot, **SEVERAL)
    assert compiled.selftest() == 0
    q = np.array([0.3, -0.7, 0.2])
    for name, size in (("jacobian_2_wrist", 18), ("jacobian_0_p1_r015", 9)):
        np.testing.assert_allclose(compiled.call(name, size, q, None), np.ravel(reference[name](q)), atol=1e-12)
    np.testing.assert_allclose(compiled.scalar("reach", q, None), reference["reach"](q), atol=1e-12)
    np.testing.assert_allclose(compiled.scalar("jacobian_determinant_0_p1_r015", q, None),
                               reference["jacobian_determinant_0_p1_r015"](q), atol=1e-12)


def test_the_selftest_catches_a_wrong_entry(tmp_path):
    files = render_files(describe(ModuleRequest(load_robot("planar3r"), "c99")))
    assert Compiled(tmp_path, files).selftest() == 0
    source = files["planar3r.c"]
    assert "    J[1] = " in source
    broken = {**files, "planar3r.c": source.replace("    J[1] = ", "    J[1] = (real)1e-3 + ", 1)}
    (tmp_path / "bad").mkdir()
    assert Compiled(tmp_path / "bad", broken).selftest() > 0


@pytest.mark.parametrize("case", ["puma560", "puma560 acceleration", "several", "scara"])
def test_the_c_targets_extension_compiles_without_a_warning(tmp_path, case):
    """The c target's extension (the same function bodies, a batch loop, CPython glue) is warning-free C too."""
    robot = numbers_only_robot() if case == "several" else load_robot(case.split()[0])
    options = SEVERAL if case == "several" else {"acceleration": case.endswith("acceleration")}
    module = generate(robot, "c", **options)
    source = module[module.index('_C_SOURCE = r"""') + len('_C_SOURCE = r"""'):]
    (tmp_path / "extension.c").write_text(source[:source.index('"""')])
    includes = [f"-I{sysconfig.get_paths()['include']}", f"-I{np.get_include()}"]
    result = subprocess.run(["gcc", "-O2", "-Wall", "-Wextra", "-Werror", "-fPIC", *includes, "-DSYMJAC_NUMPY",
                             "-DSYMJAC_LIBMVEC", "-c", "extension.c"], cwd=tmp_path, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


@pytest.mark.parametrize("suffix", [".h", ".c"])
def test_golden_files_and_determinism(suffix):
    files = render_files(describe(ModuleRequest(load_robot("planar2r"), "c99", acceleration=True)))
    assert files == render_files(describe(ModuleRequest(load_robot("planar2r"), "c99", acceleration=True)))
    path = GOLDEN / f"planar2r_c99{suffix}.golden"
    text = files[f"planar2r{suffix}"]
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        path.write_text(text)
    assert path.read_text() == text, f"{path.name} differs; review and regenerate with SYMJAC_UPDATE_GOLDEN=1"


@pytest.mark.parametrize(("word", "message"), [("double", "is a C keyword"), ("restrict", "is a C keyword"),
                                               ("NULL", "would shadow the C builtin"),
                                               ("fabs", "would shadow the C builtin"),
                                               ("sj_body", "starts with 'sj_', which the generated C keeps")])
def test_c_reserved_names_are_refused_in_one_line(word, message):
    with pytest.raises(CodegenError, match=f"parameter name '{word}' {message}"):
        generate(two_joint_robot(parameter=word), "c99")
    with pytest.raises(CodegenError, match=f"robot name '{word}' {message}"):
        generate(two_joint_robot(name=word), "c99")


@pytest.mark.parametrize("command", ["symjac codegen */ int x; /* ??/", "x *\\/ int y; /*\nz ??= \\"])
def test_comment_text_cannot_end_a_comment(tmp_path, command):
    files = render_files(describe(ModuleRequest(load_robot("planar2r"), "c99", command=command)))
    for text in files.values():
        assert "int x" not in text.replace("* / int x", "") and "int y" not in text.replace("* // int y", "")
        assert "??" not in text
    Compiled(tmp_path, files)  # still compiles with -Werror (-Wcomment included)


def test_command_line_needs_a_folder_and_writes_both_files(tmp_path, capsys):
    assert main(["codegen", "planar2r", "--target", "c99"]) != 0
    error = capsys.readouterr().err.strip()
    assert "2 files" in error and "planar2r.h" in error and "-o DIR" in error and "\n" not in error
    (tmp_path / "file.h").write_text("")
    assert main(["codegen", "planar2r", "--target", "c99", "-o", str(tmp_path / "file.h")]) != 0
    assert "is not a folder" in capsys.readouterr().err
    folder = tmp_path / "new" / "c"
    assert main(["codegen", "planar2r", "--target", "c99", "--name", "arm", "-o", str(folder)]) == 0
    assert sorted(p.name for p in folder.iterdir()) == ["arm.c", "arm.h"]
    assert Compiled(folder, {name: (folder / name).read_text() for name in ("arm.h", "arm.c")}).selftest() == 0
