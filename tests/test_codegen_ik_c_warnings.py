"""The c target's embedded C (its extension's source) of inverse-kinematics modules, compiled with every warning an
error: the closed form (PUMA 560), a coupled robot's (the palletizer), a 7-joint arm's with a joint given (iiwa7) and
the numeric stand-in of an arm without a closed form (Panda, whose extension carries the module's FK and Jacobian).

The target compiles its extension with the compiler's default dialect (``_compile`` in ``templates/c/module.py.j2``:
no ``-std``), with and without NumPy's headers and libmvec; each is checked here with ``-Wall -Wextra -Werror``, in
that dialect and in C99 (``-pedantic`` too without NumPy's headers, which are not pedantic C themselves), at ``-O2``
(some warnings need the optimiser). The extension itself must then load (``BACKEND == "c"``).
"""

from __future__ import annotations

import shutil
import subprocess
import sysconfig
import types
from pathlib import Path

import numpy as np
import pytest

from symjac.codegen import ModuleRequest, describe, render_files
from symjac.model.io import load_robot

FREE_JOINT = 3  # iiwa7: joint 3 given (a joint number, from 1)
CASES = {
    "puma560": {"inverse_kinematics": True},
    "palletizer": {"inverse_kinematics": True},
    "iiwa7": {"inverse_kinematics": True, "free_joint": FREE_JOINT},
    "panda": {"inverse_kinematics": True},  # no closed form: inverse_kinematics_numeric
}
WARNINGS = ["-Wall", "-Wextra", "-Werror"]


@pytest.fixture(scope="module")
def compiler(tmp_path_factory, monkeypatch_module):
    monkeypatch_module.setenv("SYMJAC_CACHE_DIR", str(tmp_path_factory.mktemp("c-cache")))
    found = shutil.which("cc") or shutil.which("gcc")
    if found is None or not (Path(sysconfig.get_paths()["include"]) / "Python.h").is_file():
        pytest.skip("no C compiler or no Python headers")
    return found


@pytest.fixture(scope="module")
def monkeypatch_module():
    with pytest.MonkeyPatch.context() as patch:
        yield patch


@pytest.mark.external  # a C compiler
@pytest.mark.parametrize("name", sorted(CASES))
def test_the_c_targets_extension_compiles_without_warnings(compiler, tmp_path, name):
    options = CASES[name]
    text = next(iter(render_files(describe(ModuleRequest(load_robot(name), "c", **options))).values()))
    module = types.ModuleType(f"{name}_c_ik")
    exec(compile(text, f"{name}.py", "exec"), module.__dict__)  # our own generated module
    assert module.BACKEND == "c", module.BUILD_ERROR
    assert ("inverse_kinematics_numeric" if name == "panda" else "inverse_kinematics") in module.__all__
    source = tmp_path / f"{name}.c"
    source.write_text(module._C_SOURCE, encoding="utf-8")
    assert name == "panda" or "inverse_kinematics" in module._C_SOURCE  # the closed form is compiled in
    include = f"-I{sysconfig.get_paths()['include']}"
    numpy = [f"-I{np.get_include()}", "-DSYMJAC_NUMPY", "-DSYMJAC_LIBMVEC"]
    for dialect in ([], ["-std=c99"], ["-std=c99", "-pedantic"]):
        for extra in ([], numpy) if "-pedantic" not in dialect else ([],):
            command = [compiler, *dialect, *WARNINGS, "-O2", "-fPIC", "-c", include, *extra, str(source), "-o",
                       str(tmp_path / f"{name}.o")]
            result = subprocess.run(command, capture_output=True, text=True, timeout=300, check=False)
            assert result.returncode == 0, f"{' '.join(command[1:-3])}:\n{result.stderr[-3000:]}"
