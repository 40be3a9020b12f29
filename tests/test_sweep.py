"""Design sweeps: every metric against a brute-force NumPy computation, chunking and scheduling change nothing.

The brute force evaluates the Jacobian independently of the generated kernels (the 2R arm's closed form, or
SymPy's lambdify of symjac's symbolic Jacobian with the swept parameters as arguments), takes full SVDs of all
samples at once and averages.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp

pytest.importorskip("xarray")
pytest.importorskip("dask")

from symjac import ArgumentError, SymjacError, jacobian, load_robot
from symjac.sweeps import HISTOGRAM_EDGES, JointSampler, joint_ranges, sweep

ALL = ("gci", "gci_frobenius", "manipulability", "sigma_min", "near_singular", "workspace_volume")


def _brute_force(J: np.ndarray, tool: np.ndarray, near: float, voxel: float) -> dict[str, float]:
    sigma = np.linalg.svd(J, compute_uv=False)
    inverse = sigma[:, -1] / sigma[:, 0]
    w = np.prod(sigma, axis=1)
    square = J.shape[1] == J.shape[2]
    frobenius = J.shape[2] / (np.linalg.norm(J, axis=(1, 2)) * np.linalg.norm(np.linalg.inv(J), axis=(1, 2))) \
        if square else None
    return {"gci": inverse.mean(), "gci_frobenius": frobenius.mean() if square else np.nan,
            "manipulability_mean": w.mean(), "manipulability_min": w.min(), "manipulability_max": w.max(),
            "manipulability_std": w.std(), "sigma_min_mean": sigma[:, -1].mean(), "sigma_min_min": sigma[:, -1].min(),
            "near_singular": np.mean(inverse < near),
            "manipulability_histogram": np.histogram(w, HISTOGRAM_EDGES)[0],
            "sigma_min_histogram": np.histogram(sigma[:, -1], HISTOGRAM_EDGES)[0],
            "workspace_volume": len({tuple(c) for c in np.floor(tool / voxel).astype(int)}) * voxel**3}


def test_planar_2r_over_its_link_lengths_matches_the_closed_form():
    robot = load_robot("planar2r")
    lengths = {"L1": (0.3, 0.6, 3), "L2": [0.2, 0.45]}
    result = sweep(robot, lengths, samples=4096, metrics=ALL, rows=[0, 1], chunk=1000, voxel=0.02,
                   scheduler="synchronous")
    Q = JointSampler(joint_ranges(robot), 4096).chunk(0, 4096)
    s1, c1 = np.sin(Q[:, 0]), np.cos(Q[:, 0])
    s12, c12 = np.sin(Q[:, 0] + Q[:, 1]), np.cos(Q[:, 0] + Q[:, 1])
    for L1, L2 in itertools.product(np.linspace(0.3, 0.6, 3), [0.2, 0.45]):
        J = np.stack([np.stack([-L1 * s1 - L2 * s12, -L2 * s12], -1), np.stack([L1 * c1 + L2 * c12, L2 * c12], -1)],
                     axis=1)
        tool = np.stack([L1 * c1 + L2 * c12, L1 * s1 + L2 * s12, 0 * s1], -1)
        expected = _brute_force(J, tool, 0.01, 0.02)
        for name, value in expected.items():
            got = result[name].sel(L1=L1, L2=L2).values
            np.testing.assert_allclose(got, value, rtol=1e-12, atol=1e-14, err_msg=f"{name} {L1} {L2}")
    # a textbook fact the sweep must show: for the 2R arm, det J = L1 L2 s2, largest for equal links' product
    assert float(result["manipulability_mean"].sel(L1=0.6, L2=0.45)) > float(
        result["manipulability_mean"].sel(L1=0.3, L2=0.2))


def test_planar_3r_over_its_link_lengths_matches_the_closed_form():
    robot = load_robot("planar3r")
    result = sweep(robot, {"L2": (0.3, 0.5, 2), "L3": [0.1, 0.25]}, samples=2048, metrics=ALL, point="tool",
                   rows=[0, 1, 5], chunk=500, voxel=0.03, scheduler="synchronous")
    Q = JointSampler(joint_ranges(robot), 2048).chunk(0, 2048)
    angles = np.cumsum(Q, axis=1)  # theta1, theta1 + theta2, theta1 + theta2 + theta3
    for L2, L3 in itertools.product([0.3, 0.5], [0.1, 0.25]):
        lengths = np.array([0.5, L2, L3])  # L1 keeps its default
        x = np.cos(angles) * lengths
        y = np.sin(angles) * lengths
        # column j: minus y and x summed over the links from j on; the angular row is all ones
        beyond_x, beyond_y = np.cumsum(x[:, ::-1], axis=1)[:, ::-1], np.cumsum(y[:, ::-1], axis=1)[:, ::-1]
        J = np.stack([np.stack([-beyond_y[:, j], beyond_x[:, j], np.ones(len(Q))], axis=1) for j in range(3)], axis=2)
        tool = np.stack([x.sum(axis=1), y.sum(axis=1), 0 * x[:, 0]], axis=1)
        for name, value in _brute_force(J, tool, 0.01, 0.03).items():
            np.testing.assert_allclose(result[name].sel(L2=L2, L3=L3).values, value, rtol=1e-12, atol=1e-14,
                                       err_msg=f"{name} {L2} {L3}")


@pytest.mark.slow
def test_puma_over_a2_and_d4_matches_an_independent_jacobian():
    robot = load_robot("puma560")
    a2, d4 = (next(p.symbol for p in robot.parameters if p.name == name) for name in ("a2", "d4"))
    J_symbolic = jacobian(robot).xreplace({s: v for s, v in robot.defaults.items() if s not in (a2, d4)})
    function = sp.lambdify([list(robot.q), a2, d4], J_symbolic, modules="numpy")
    result = sweep(robot, {"a2": (0.35, 0.45, 2), "d4": [0.4, 0.45]}, samples=300, metrics=ALL, chunk=128,
                   voxel=0.05, scheduler="synchronous")
    Q = JointSampler(joint_ranges(robot), 300).chunk(0, 300)
    for value_a2, value_d4 in itertools.product([0.35, 0.45], [0.4, 0.45]):
        J = np.array([np.array(function(q, value_a2, value_d4), dtype=float) for q in Q])
        from symjac import forward_kinematics

        T = sp.lambdify([list(robot.q), a2, d4], forward_kinematics(robot, 0, robot.n_joints).xreplace(
            {s: v for s, v in robot.defaults.items() if s not in (a2, d4)}), modules="numpy")
        tool = np.array([np.array(T(q, value_a2, value_d4), dtype=float)[:3, 3] for q in Q])
        for name, value in _brute_force(J, tool, 0.01, 0.05).items():
            got = result[name].sel(a2=value_a2, d4=value_d4).values
            np.testing.assert_allclose(got, value, rtol=1e-9, atol=1e-12, err_msg=f"{name} {value_a2} {value_d4}")


def test_chunk_size_and_scheduler_change_nothing():
    robot = load_robot("planar3r")
    options = {"samples": 3000, "metrics": ALL, "rows": [0, 1, 5]}
    reference = sweep(robot, {"L2": (0.2, 0.4, 2)}, chunk=3000, scheduler="synchronous", **options)
    for chunk, scheduler in ((7, "synchronous"), (512, "threads"), (1000, "processes")):
        other = sweep(robot, {"L2": (0.2, 0.4, 2)}, chunk=chunk, scheduler=scheduler, **options)
        for name in reference.data_vars:
            np.testing.assert_allclose(other[name].values, reference[name].values, rtol=1e-12, atol=1e-15,
                                       err_msg=f"{name} with chunk {chunk} on {scheduler}")


@pytest.mark.external
def test_a_local_cluster_gives_the_same_result():
    distributed = pytest.importorskip("distributed")
    robot = load_robot("planar2r")
    options = {"samples": 2048, "metrics": ("gci", "manipulability"), "rows": [0, 1], "chunk": 256}
    alone = sweep(robot, {"L1": (0.3, 0.5, 3)}, scheduler="synchronous", **options)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with cluster, distributed.Client(cluster) as client:
        spread = sweep(robot, {"L1": (0.3, 0.5, 3)}, client=client, **options)
    for name in alone.data_vars:
        np.testing.assert_allclose(spread[name].values, alone[name].values, rtol=1e-12)


def test_a_grid_covers_cell_centres():
    sampler = JointSampler(np.array([[0.0, 1.0], [0.0, 2.0]]), 9, "grid")
    assert sampler.total == 9
    np.testing.assert_allclose(sampler.chunk(0, 9)[:3], [[1 / 6, 1 / 3], [1 / 6, 1.0], [1 / 6, 5 / 3]])


@pytest.mark.parametrize(("arguments", "message"), [
    ({"params": {"L3": (0.1, 0.2, 2)}}, r"planar2r has no parameter 'L3'"),
    ({"params": {"L1": (0.5, 0.1, 2)}}, r"L1: the range 0.5:0.1:2 is empty"),
    ({"params": {"L1": []}}, r"L1: give from 1 to 10000 values, got 0"),
    ({"params": {"L1": [0.3, 0.3]}}, r"L1: the values repeat"),
    ({"params": {"L1": (0.3, 0.6, 2.5)}}, r"the count of .* must be a whole number"),
    ({"params": {"L1": (True, 0.6, 2)}}, r"L1's low end must be a finite number"),
    ({"scheduler": "thread"}, r"unknown scheduler 'thread'"),
    ({"seed": -1}, r"seed must be a whole number >= 0"),
    ({"metrics": ["gci_frobenius"], "rows": [0, 1, 2]}, r"gci_frobenius needs a square Jacobian"),
    ({"samples": 10**15, "chunk": 1000}, r"tasks, more than 1000000"),
    ({"samples": 0}, r"samples must be a positive integer"),
    ({"metrics": ["dexterity"]}, r"unknown metric 'dexterity'"),
    ({"sampling": "random"}, r"unknown sampling 'random'"),
    ({"chunk": 0}, r"chunk must be a positive integer"),
])
def test_bad_input_is_refused_before_any_work(arguments, message):
    options = {"params": {"L1": (0.3, 0.5, 2)}, "samples": 64, **arguments}
    with pytest.raises(ArgumentError, match=message):
        sweep(load_robot("planar2r"), **options)


@pytest.mark.external
def test_a_scheduler_that_does_not_answer_is_one_clear_error_within_seconds():
    pytest.importorskip("distributed")
    import time

    start = time.perf_counter()
    with pytest.raises(SymjacError, match=r"no dask scheduler answers at tcp://127.0.0.1:9"):
        sweep(load_robot("planar2r"), {"L1": [0.5]}, samples=16, scheduler="tcp://127.0.0.1:9")
    assert time.perf_counter() - start < 15


# --- the command ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".nc", ".csv", ".json"])
def test_the_command_writes_the_result_in_the_format_of_the_suffix(cli, tmp_path, suffix):
    import json

    import xarray as xr

    out, picture = tmp_path / f"result{suffix}", tmp_path / "metrics.png"
    assert cli.run("sweep", "planar2r", "--param", "L1=0.3:0.5:3", "--param", "L2=0.2,0.4", "--samples", "2e3",
                   "--rows", "v_x,v_y", "--metric", "gci,manipulability", "--scheduler", "synchronous",
                   "-o", str(out), "--plot", str(picture)) == (0, "", "")
    expected = sweep(load_robot("planar2r"), {"L1": (0.3, 0.5, 3), "L2": [0.2, 0.4]}, samples=2000,
                     metrics=["gci", "manipulability"], rows=[0, 1], scheduler="synchronous")
    if suffix == ".nc":
        with xr.open_dataset(out, engine="scipy") as written:
            xr.testing.assert_allclose(written.load(), expected)
    elif suffix == ".json":
        written = xr.Dataset.from_dict(json.loads(out.read_text()))  # JSON has no infinity: the last bin's top
        xr.testing.assert_allclose(written.drop_vars("bin_high"), expected.drop_vars("bin_high"))
    else:
        lines = out.read_text().splitlines()
        assert lines[0].startswith("L1,L2,gci,manipulability_mean") and len(lines) == 1 + 6
    assert picture.read_bytes().startswith(b"\x89PNG")


@pytest.mark.parametrize(("arguments", "message"), [
    (["--param", "L3=0.1:0.2:2"], "planar2r has no parameter 'L3'"),
    (["--param", "L1=0.5:0.1:2"], "L1: the range 0.5:0.1:2 is empty"),
    (["--param", "L1=0.1:0.2:x"], "give NAME=LOW:HIGH:COUNT"),
    (["--param", "L1=0.1:0.2:2", "--samples", "0"], "--samples must be a whole number >= 1"),
    (["--param", "L1=0.1:0.2:2", "--metric", "dexterity"], "unknown metric 'dexterity'"),
    ([], "give at least one --param"),
    (["--param", "L1=0.1:0.2:2", "--param", "L1=0.3,0.4"], "--param names L1 twice"),
    (["--param", "L1=0.1:0.2:2", "--scheduler", "thread"], "unknown scheduler 'thread'"),
    (["--param", "L1=0.1:0.2:2", "--plot", "{out}.gif"], "use a .svg, .png or .pdf file"),
])
def test_bad_command_input_is_one_line_and_writes_nothing(cli, tmp_path, arguments, message):
    out = tmp_path / "result"
    error = cli.one_line_error("sweep", "planar2r", *[a.replace("{out}", str(out)) for a in arguments],
                               "-o", str(out) + ".nc")
    assert message in error
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_stops_the_sweep_says_how_far_it_got_and_writes_nothing(cli, tmp_path, monkeypatch):
    from symjac.sweeps import run

    calls = []

    def interrupted(*arguments):
        calls.append(arguments)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return run.Tally()

    monkeypatch.setattr(run, "_chunk_tally", interrupted)
    status, out, err = cli.run("sweep", "planar2r", "--param", "L1=0.3:0.5:3", "--samples", "4096", "--rows",
                               "v_x,v_y", "--scheduler", "synchronous", "-o", str(tmp_path / "r.nc"), "--plot",
                               str(tmp_path / "r.png"))
    assert (status, out) == (130, "")
    assert err.splitlines()[0].startswith("symjac: sweep stopped after 2 of ")
    assert err.splitlines()[-1] == "symjac: interrupted"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("name", "rows"), [("planar3r", [0, 1, 5]), ("planar3r", [0, 1]), ("stanford", None),
                                            ("scara", None)])  # square, wide, square, tall (6 rows, 4 joints)
def test_without_sigma_metrics_a_determinant_and_an_inverse_agree_with_the_singular_values(name, rows):
    robot = load_robot(name)
    parameter = robot.parameters[0].name
    value = float(robot.defaults[robot.parameters[0].symbol])
    options = {"samples": 1024, "rows": rows, "scheduler": "synchronous", "voxel": 0.05}
    cheap = ["manipulability", "workspace_volume"] + ["gci_frobenius"] * (len(rows or range(6)) == robot.n_joints)
    alone = sweep(robot, {parameter: [value]}, metrics=cheap, **options)
    full = sweep(robot, {parameter: [value]}, metrics=[*cheap, "gci"], **options)
    for variable in alone.data_vars:
        if variable != "manipulability_histogram":  # a w at a bin edge may fall either side
            np.testing.assert_allclose(alone[variable].values, full[variable].values, rtol=1e-9, atol=1e-12)
    assert abs(int(alone["manipulability_histogram"].sum()) - 1024) == 0
