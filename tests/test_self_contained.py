"""The repository refers to nothing outside its own tree: the course notes are named by title and section only."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent

# A path that climbs out of its folder, an absolute path into the machine symjac was written on, or the folder the
# course notes were kept in. Relative links inside the repository (``symjac/teaching/errata/formulas.toml``) pass.
OUTSIDE = re.compile(
    r"\.\./"
    r"|(?<![\w.])/work/"  # outside-the-repository: allowed (the pattern itself)
    r"|\bseeds/"
    r"|\b00[023]_[0-9a-f]{6,}"
)


def _tracked_text_files() -> list[Path]:
    try:
        listed = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout (an installed copy has no tracked files to check)")
    files = [REPO / name for name in listed.decode().split("\0") if name]
    return [path for path in files if path.is_file() and b"\0" not in path.read_bytes()[:4096]]


def test_no_tracked_file_refers_to_a_path_outside_the_repository():
    offending = []
    for path in _tracked_text_files():
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), start=1):
            if OUTSIDE.search(line) and "outside-the-repository: allowed" not in line:
                offending.append(f"{path.relative_to(REPO)}:{number}: {line.strip()[:100]}")
    assert not offending, "paths outside the repository:\n" + "\n".join(offending)


# Each kind the pattern must catch, assembled from pieces so that this file itself names no outside path.
UP, WORK, NOTES = "..", "work", "seeds"
EXAMPLES = [
    f"see {UP}/elsewhere/notes.txt",
    f"/{WORK}/main/x",
    f"notes in {NOTES}/",
    "000" + "_7a9327692e00",
]


@pytest.mark.parametrize("text", EXAMPLES)
def test_the_pattern_catches_each_kind_of_outside_path(text):
    assert OUTSIDE.search(text)
