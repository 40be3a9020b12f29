"""Pictures of the arm: the numbers the figure's artists hold, golden images, animations and bad input.

The reference for every position and axis is tests/reference.py: its own NumPy product of the link transforms,
written from the conventions, not from symjac's chain; the ellipsoids are checked against a Jacobian from central
differences of that forward kinematics.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from marks import marked

pytest.importorskip("matplotlib")

from matplotlib.testing.compare import compare_images

from symjac import ArgumentError, arm_pose, catalog, draw, load_robot
from symjac.drawing.animation import figure_bytes, joint_path
from symjac.drawing.geometry import FORCE_AXIS_RATIO
from symjac.model.robot import JointType
from tests import reference

ROBOTS = [*sorted(catalog()), "gripper.urdf", "panda.urdf", "ur5.urdf"]
GOLDEN = Path(__file__).resolve().parent / "golden" / "drawings"


def _artist(axes, gid: str):
    found = [a for a in [*axes.lines, *axes.collections, *axes.texts] if a.get_gid() == gid]
    assert len(found) == 1, (gid, len(found))
    return found[0]


def _segment(axes, gid: str) -> np.ndarray:
    return np.array(_artist(axes, gid).get_data_3d()).T


def _tool_point(robot) -> np.ndarray | None:
    """The tool point in frame {n} coordinates (None: the wrist)."""
    if robot.tool is None:
        return None
    return np.array(robot.tool.matrix.subs(robot.defaults), dtype=float)[:3, 3]


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_the_artists_hold_the_forward_kinematics(name):
    robot = load_robot(name)
    rng = np.random.default_rng(11)
    for _ in range(3):
        q = reference.random_configuration(robot, rng)
        figure = draw(robot, q, frames=True)
        axes = figure.axes[0]
        expected = reference.frames(robot, q)  # world, {0}, ..., {n}, tool
        np.testing.assert_allclose(_segment(axes, "links"), [T[:3, 3] for T in expected], atol=1e-12)
        pose = arm_pose(robot, q)
        length = 0.12 * pose.reach
        shown = {"W": 0, "T": robot.n_joints + 2, **{str(k): k + 1 for k in range(robot.n_joints + 1)}}
        drawn = 0
        for label, index in shown.items():
            if not any(a.get_gid() == f"frame-{label}-x" for a in axes.lines):
                continue
            drawn += 1
            for column, letter in enumerate("xyz"):
                start, end = _segment(axes, f"frame-{label}-{letter}")
                np.testing.assert_allclose(start, expected[index][:3, 3], atol=1e-12)
                np.testing.assert_allclose((end - start) / length, expected[index][:3, column], atol=1e-12)
        assert drawn == robot.n_joints + 1 + (robot.base is not None) + (robot.tool is not None)
        for joint in range(1, robot.n_joints + 1):
            start, end = _segment(axes, f"joint-{joint}-axis")
            # the axis of joint i is z of frame {i-1} (standard DH) or {i}: it must be one of the two, through
            # that frame's origin
            centre, direction = (start + end) / 2, (end - start) / np.linalg.norm(end - start)
            candidates = [expected[joint], expected[joint + 1]] if robot.convention == "standard" \
                else [expected[joint + 1]]
            assert any(np.allclose(centre, T[:3, 3], atol=1e-12) and np.allclose(direction, T[:3, 2], atol=1e-12)
                       for T in candidates), (name, joint)


@pytest.mark.parametrize("name", marked(["planar3r", "puma560", "stanford", "panda", "ur5_poe", "palletizer",
                                          "ur5.urdf"]))
def test_the_ellipsoids_axes_are_the_singular_vectors_times_the_singular_values(name):
    robot = load_robot(name)
    rng = np.random.default_rng(5)
    for _ in range(3):
        q = reference.random_configuration(robot, rng)
        figure = draw(robot, q, ellipsoids=("velocity", "force"), ellipsoid_scale=1.0)
        axes = figure.axes[0]
        J_v = reference.finite_difference_jacobian(robot, q, "world", _tool_point(robot))[:3]
        semi = {kind: np.array([np.subtract(*_segment(axes, f"{kind}-ellipsoid-axis-{k}")[::-1]) / 2
                                for k in range(3)]) for kind in ("velocity", "force")}
        # sum_k a_k a_k^T = U S^2 U^T = J_v J_v^T (no sign or order ambiguity left)
        np.testing.assert_allclose(semi["velocity"].T @ semi["velocity"], J_v @ J_v.T, atol=1e-7)
        sigma = np.linalg.svd(J_v, compute_uv=False)
        np.testing.assert_allclose(sorted(np.linalg.norm(semi["velocity"], axis=1)),
                                   sorted(np.concatenate([sigma, np.zeros(3 - len(sigma))])), atol=1e-7)
        centre = (_segment(axes, "velocity-ellipsoid-axis-0")).mean(axis=0)
        np.testing.assert_allclose(centre, reference.frames(robot, q)[-1][:3, 3], atol=1e-12)
        if len(sigma) == 3 and np.min(sigma) * FORCE_AXIS_RATIO > 1.01 * np.max(sigma):  # not clipped: (J_v J_v^T)^-1
            np.testing.assert_allclose(semi["force"].T @ semi["force"], np.linalg.inv(J_v @ J_v.T), rtol=1e-5,
                                       atol=1e-6)


def test_a_singular_force_ellipsoid_is_clipped_and_says_so():
    robot = load_robot("planar2r")
    pose = arm_pose(robot, [0.4, 0.0])  # stretched: no force along the arm needs torque
    from symjac import ellipsoid

    shape = ellipsoid(pose, "force")
    lengths = np.linalg.norm(shape.axes, axis=1)
    assert sum(shape.clipped) == 2  # along the arm, and out of the plane (no joint moves the tool along z)
    sigma = np.linalg.svd(pose.jacobian[:3], compute_uv=False)
    np.testing.assert_allclose(sorted(lengths), [1 / sigma.max()] + [FORCE_AXIS_RATIO / sigma.max()] * 2)


@pytest.mark.parametrize("name", ["puma560", "ur5", "panda", "planar3r"])
def test_a_regular_force_ellipsoid_is_never_clipped(name):
    robot = load_robot(name)
    rng = np.random.default_rng(3)
    from symjac import ellipsoid

    for _ in range(50):
        pose = arm_pose(robot, reference.random_configuration(robot, rng))
        sigma = np.linalg.svd(pose.jacobian[:3], compute_uv=False)
        if len(sigma) == 3 and sigma.min() > 0.05 * sigma.max():
            assert not any(ellipsoid(pose, "force").clipped)


def test_joints_are_coloured_by_their_distance_to_the_limits():
    robot = load_robot("panda")
    low = np.array([float(j.limits[0].subs(robot.defaults)) for j in robot.joints])
    high = np.array([float(j.limits[1].subs(robot.defaults)) for j in robot.joints])
    q = (low + high) / 2
    q[3] = high[3]  # joint 4 at its upper limit
    q[5] = low[5] + 0.25 * (high[5] - low[5])  # joint 6 half-way to the middle
    pose = arm_pose(robot, q)
    np.testing.assert_allclose(pose.limit_margins[[0, 3, 5]], [1.0, 0.0, 0.5], atol=1e-12)
    figure = draw(robot, q, limits=True)
    colours = [_artist(figure.axes[0], f"joint-{k}").get_facecolor()[0] for k in (1, 4)]
    assert colours[0][1] > colours[0][0]  # green in the middle
    assert colours[1][0] > colours[1][1]  # red at the limit


def test_configurations_side_by_side_share_one_scale():
    robot = load_robot("puma560")
    figure = draw(robot, [[0, 0.3, -0.2, 0, 0.5, 0], [0.5, 0, 0, 0, 0, 0]], ellipsoids="velocity")
    assert len(figure.axes) == 2
    assert figure.axes[0].get_xlim() == figure.axes[1].get_xlim()
    for axes in figure.axes:  # equal scale: a cube
        spans = [np.diff(getattr(axes, f"get_{c}lim")())[0] for c in "xyz"]
        np.testing.assert_allclose(spans, spans[0])


def test_joint_path_passes_through_the_waypoints():
    path = joint_path([[0, 0], [1, 2], [1, 0]], steps=4)
    assert path.shape == (9, 2)
    np.testing.assert_allclose(path[[0, 4, 8]], [[0, 0], [1, 2], [1, 0]])


@pytest.mark.parametrize(("q", "message"), [
    ([1.0, 2.0], r"q must have 6 entries"),
    ([0, 0, float("nan"), 0, 0, 0], r"q must be finite"),
    ("0,0,0,0,0,0", r"q must be numbers"),
    ([[0] * 6, [0] * 5], r"q must be numbers|shape"),
])
def test_bad_configurations_are_refused(q, message):
    with pytest.raises(ArgumentError, match=message):
        draw(load_robot("puma560"), q)


def test_bad_options_are_refused():
    robot = load_robot("planar2r")
    with pytest.raises(ArgumentError, match="unknown ellipsoid"):
        draw(robot, ellipsoids="acceleration")
    with pytest.raises(ArgumentError, match="view"):
        draw(robot, view=(1.0, float("inf")))
    with pytest.raises(ArgumentError, match="ellipsoid_scale"):
        draw(robot, ellipsoids="velocity", ellipsoid_scale=-1.0)
    with pytest.raises(ArgumentError, match=r"cannot write a figure as \.jpg"):
        figure_bytes(draw(robot), ".jpg")


GOLDEN_CASES = {
    "puma560-ellipsoid": ("puma560", [[0.3, -0.6, 0.4, 0.2, 0.8, 0.0]], {"ellipsoids": ("velocity",)}),
    "stanford-side-by-side": ("stanford", [[0.2, -0.4, 0.3, 0.0, 0.5, 0.0], [1.0, 0.3, 0.6, 0.4, -0.5, 0.2]],
                              {"limits": True}),
    "ur5-report-arrow": ("ur5", [[0.3, -1.2, 0.0, -0.8, 1.2, 0.0]],  # as the report draws a singular configuration
                         {"arrow": (0.0, 0.6, 0.8), "title": "", "size": (3.9, 3.7)}),
    "panda-force-limits": ("panda", [[0.3, -0.5, 0.2, -2.0, 0.1, 1.5, 0.4]],
                           {"ellipsoids": ("force",), "limits": True, "frames": False, "view": (-100.0, 15.0)}),
}


@pytest.mark.parametrize("case", sorted(GOLDEN_CASES))
def test_the_drawing_matches_its_golden_image(case, tmp_path):
    name, q, options = GOLDEN_CASES[case]
    actual = tmp_path / f"{case}.png"
    actual.write_bytes(figure_bytes(draw(load_robot(name), q, **options), ".png"))
    expected = GOLDEN / f"{case}.png"
    if not expected.exists():  # pragma: no cover - a new case: write its golden image once, look at it, commit it
        GOLDEN.mkdir(parents=True, exist_ok=True)
        shutil.copy(actual, expected)
        pytest.fail(f"wrote the new golden image {expected}; check it by eye and commit it")
    assert compare_images(str(expected), str(actual), tol=3) is None


def test_figures_are_byte_stable():
    robot = load_robot("planar3r")
    for suffix in (".svg", ".png", ".pdf"):
        assert figure_bytes(draw(robot, [0.1, 0.2, 0.3]), suffix) == figure_bytes(draw(robot, [0.1, 0.2, 0.3]), suffix)


# --- the command ------------------------------------------------------------------------------------------------


def _drawn(cli, *argv: str) -> None:
    """Run ``symjac *argv``, which must write its file and print nothing."""
    assert cli.run(*argv) == (0, "", "")


@pytest.mark.parametrize("suffix", [".svg", ".png", ".pdf"])
def test_the_command_writes_the_format_of_the_suffix(cli, tmp_path, suffix):
    out = tmp_path / f"arm{suffix}"
    _drawn(cli, "draw", "puma560", "--q", "0,30deg,-pi/4,0,0.5,0", "--ellipsoid", "velocity", "--view", "30,20",
           "-o", str(out))
    data = out.read_bytes()
    assert data.startswith({".svg": b"<?xml", ".png": b"\x89PNG", ".pdf": b"%PDF"}[suffix])


def test_the_command_takes_degrees_and_radians_alike(cli, tmp_path):
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    _drawn(cli, "draw", "planar2r", "--q", "90deg,-45deg", "-o", str(a))
    _drawn(cli, "draw", "planar2r", "--q", "pi/2,-pi/4", "-o", str(b))
    assert a.read_bytes() == b.read_bytes()


def test_the_command_animates_a_path_as_gif(cli, tmp_path):
    from PIL import Image

    out = tmp_path / "arm.gif"
    _drawn(cli, "draw", "planar3r", "--q", "0,0,0", "--q", "1,0.5,-0.5", "--q", "0.5,1,1", "--path",
           "--path-steps", "4", "-o", str(out))
    with Image.open(out) as movie:
        assert movie.n_frames == 9


@pytest.mark.external
def test_the_command_animates_a_path_as_mp4(cli, tmp_path):
    if shutil.which("ffprobe") is None:
        pytest.skip("ffmpeg is not installed (.ci/run installs it: apt-get install ffmpeg)")
    out = tmp_path / "arm.mp4"
    _drawn(cli, "draw", "planar2r", "--q", "0,0", "--q", "1,1", "--path", "--path-steps", "6", "-o", str(out))
    frames = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                             "stream=nb_read_frames", "-of", "csv=p=0", str(out)], capture_output=True, text=True,
                            check=True).stdout.strip()
    assert int(frames) == 7


@pytest.mark.parametrize(("arguments", "message"), [
    (["--q", "0,1", "-o", "{out}.png"], "--q needs 6 comma-separated values for puma560, got 2"),
    (["--q", "0,x,0,0,0,0", "-o", "{out}.png"], "--q takes numbers and expressions with pi only"),
    (["-o", "{out}.jpg"], "unknown suffix .jpg"),
    ([], "draw writes a file: give -o FILE"),
    (["--q", "0,0,0,0,0,0", "-o", "{out}.gif"], "animates a path: give --path"),
    (["--path", "--q", "0,0,0,0,0,0", "-o", "{out}.gif"], "--path needs two or more --q"),
    (["--view", "north", "-o", "{out}.png"], "--view must be two numbers"),
])
def test_bad_command_input_is_one_line_and_writes_nothing(cli, tmp_path, arguments, message):
    out = tmp_path / "arm"
    error = cli.one_line_error("draw", "puma560", *[a.replace("{out}", str(out)) for a in arguments])
    assert message in error
    assert list(tmp_path.iterdir()) == []


def test_an_unknown_ellipsoid_is_a_usage_error(tmp_path, capsys):
    from symjac.cli.main import main

    with pytest.raises(SystemExit) as stopped:
        main(["draw", "puma560", "--ellipsoid", "wobble", "-o", str(tmp_path / "a.png")])
    assert stopped.value.code == 2
    assert "invalid choice: 'wobble'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_prismatic_coordinates_are_not_in_degrees(cli, tmp_path):
    error = cli.one_line_error("draw", "stanford", "--q", "0,0,10deg,0,0,0", "-o", str(tmp_path / "a.png"))
    assert "d3 is a length" in error
    assert load_robot("stanford").joints[2].type is JointType.PRISMATIC


@pytest.mark.external
def test_the_slider_notebook_shows_one_static_figure_when_run_headless(tmp_path, monkeypatch):
    jupytext = pytest.importorskip("jupytext")
    nbclient = pytest.importorskip("nbclient")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("SYMJAC_NOTEBOOK_OUTPUT", str(tmp_path))
    notebook = jupytext.read(Path(__file__).resolve().parent.parent / "notebooks" / "09_drawing_the_arm.py")
    notebook.cells = [cell for cell in notebook.cells if "answer_" not in cell.source]  # the exercises: elsewhere
    nbclient.NotebookClient(notebook, timeout=240, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    images = [output for cell in notebook.cells if cell.cell_type == "code" for output in cell.outputs
              if "image/png" in output.get("data", {})]
    assert len(images) == 2  # the PUMA's frames and the 2R ellipsoids, shown without pyplot
    state = notebook.metadata["widgets"]["application/vnd.jupyter.widget-state+json"]["state"]
    shown = [output for model in state.values() if model["model_name"] == "OutputModel"
             for output in model["state"].get("outputs", []) if "image/png" in output.get("data", {})]
    assert len(shown) == 1  # the sliders' figure, drawn once at their starting values
    assert (tmp_path / "panda_sliders.png").stat().st_size > 10_000
