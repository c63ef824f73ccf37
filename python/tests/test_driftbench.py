"""driftbench from Python: tasks, runs of numpy networks against their Rust twins, errors, the
leaderboard. Run from anywhere: the project root is this checkout."""

import math
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest

import driftbench
from driftbench.networks import Gnn, Znn

ROOT = pathlib.Path(__file__).resolve().parents[2]
CLOVER = "jia2019-clover / vltco"
CIRCLE = "kong2019-circle / znn-eq22"

# Agreement with the Rust twins (stated in python/README.md): the same network, integrator and
# tolerances, so the numbers differ only by round-off and by the Jacobian the integrator gets
# (the twins give dF/dy along the QP data analytically, the numpy ones by differences).
DRIFT_FACTOR = 1.001  # drift norm within 0.1 %
ERROR_FACTOR = 1.05  # position error and distance to the optimum within 5 %


def within(a, b, factor):
    return max(a, b) <= factor * min(a, b)


def test_tasks_are_objects_with_the_experiment_files_fields():
    clover = driftbench.task(CLOVER, root=ROOT)
    assert clover.paper == "jia2019" and clover.robot == "jaco2-pen" and clover.dof == 6
    assert clover.path["name"] == "four-leaf-clover" and clover.duration == 5.0
    assert clover.scheme["kind"] == "jia2019" and clover.scheme["tau"] == 0.4
    assert clover.theta0 == clover.theta_ref and len(clover.theta0) == 6
    assert clover.integrator["method"] == "bdf" and clover.integrator["rtol"] == 1e-6
    assert "exact" in clover.solvers and "VLTCO" in clover.scheme_name
    ids = [t.id for t in driftbench.tasks(root=ROOT)]
    assert CLOVER in ids and CIRCLE in ids and len(ids) == len(set(ids))
    standard = driftbench.standard_tasks(root=ROOT)
    assert standard and all(t.paper == "cross" for t in standard)


def test_library_errors_are_python_exceptions_with_the_library_messages():
    with pytest.raises(driftbench.DriftbenchError, match='no task "nope"'):
        driftbench.task("nope", root=ROOT)
    clover = driftbench.task(CLOVER, root=ROOT)
    with pytest.raises(driftbench.DriftbenchError, match=r"rtol must be in \(0, 1\), got -1"):
        driftbench.simulate(clover, Gnn(), rtol=-1.0)
    with pytest.raises(driftbench.DriftbenchError, match='has no solver "FOO"'):
        driftbench.simulate(clover, "FOO")
    # The ZNN cannot be built for the clover's inequality-constrained QP: a setup error.
    with pytest.raises(driftbench.DriftbenchError, match="equality-only"):
        driftbench.simulate(clover, Znn())


def test_an_exception_in_the_network_is_raised_after_the_run():
    class Broken(Gnn):
        def rhs(self, t, y, qp):
            raise ZeroDivisionError("inside rhs")

    with pytest.raises(RuntimeError, match=r"rhs at t = ") as info:
        driftbench.simulate(driftbench.task(CLOVER, root=ROOT), Broken())
    assert isinstance(info.value.__cause__, ZeroDivisionError)


def rust_gnn_clover():
    """The Rust twin's line of `cargo run --example gnn_clover`: drift, max error, max |x - x*|."""
    if shutil.which("cargo") is None:
        pytest.skip("cargo is not installed: the Rust twin (examples/gnn_clover.rs) cannot run")
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "-p", "simulation", "--example", "gnn_clover"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    line = next(l for l in out.splitlines() if l.startswith("GNN (this example"))
    numbers = re.findall(r"\d\.\d+e[-+]?\d+", line)
    return [float(v) for v in numbers[:3]]


def test_numpy_gnn_on_the_clover_matches_its_rust_twin():
    run = driftbench.simulate(driftbench.task(CLOVER, root=ROOT), Gnn(gamma=1e4, rho=1e3))
    assert run["status"] == "ok" and run["solver_kind"] == "python"
    assert run["drift"].shape == (6,)
    assert math.isclose(np.linalg.norm(run["drift"]), run["drift_norm"], rel_tol=1e-9)
    assert run["trace"]["theta"].shape[1] == 6
    assert run["python_calls"] > 0
    drift, max_err, max_dx = rust_gnn_clover()
    assert within(run["drift_norm"], drift, DRIFT_FACTOR), (run["drift_norm"], drift)
    assert within(run["max_pos_err"], max_err, ERROR_FACTOR), (run["max_pos_err"], max_err)
    assert within(run["score_max_dx"], max_dx, ERROR_FACTOR), (run["score_max_dx"], max_dx)


def test_numpy_znn_on_the_circle_matches_the_suites_znn():
    circle = driftbench.task(CIRCLE, root=ROOT)
    twin_label = next(s for s in circle.solvers if s.startswith("znn"))
    twin = driftbench.simulate(circle, twin_label)
    run = driftbench.simulate(circle, Znn(gamma=1.0))
    assert run["status"] == "ok" and twin["status"] == "ok"
    assert within(run["drift_norm"], twin["drift_norm"], DRIFT_FACTOR)
    assert within(run["max_pos_err"], twin["max_pos_err"], ERROR_FACTOR)
    assert within(run["score_rms_dx"], twin["score_rms_dx"], ERROR_FACTOR)
    assert within(run["net_error_final"], twin["net_error_final"], 10.0)
    assert run["trace"]["theta"].shape[1] == 5


def test_a_numpy_network_on_the_leaderboard_beside_the_built_in_ones(tmp_path):
    standard = driftbench.standard_tasks(root=ROOT)
    board = driftbench.leaderboard({"GNN (numpy)": Gnn()}, root=ROOT, out_dir=tmp_path)
    rows = board["leaderboard"]
    header = (ROOT / "results" / "leaderboard.csv").read_text().splitlines()[0]
    assert list(rows[0].keys()) == header.split(",")
    # Ranked in the standard set (and in the zeroing networks' set of 5 tasks, as every
    # solver that ran on all of them is).
    ours = [r for r in rows if r["solver"] == "GNN (numpy)" and r["task_set"] == "standard"]
    assert len(ours) == 1 and ours[0]["solver_kind"] == "python"
    assert ours[0]["tasks"] == len(standard)
    mates = [r["solver"] for r in rows if r["task_set"] == "standard"]
    assert "LVI-PDNN" in mates and len(mates) > 2
    assert sorted(r["rank"] for r in rows if r["task_set"] == "standard") == list(
        range(1, len(mates) + 1)
    )
    assert len(board["runs"]) == len(standard)
    assert all(r["solver_kind"] == "python" for r in board["runs"])
    written = (tmp_path / "leaderboard.csv").read_text().splitlines()
    assert written[0] == header and len(written) == len(rows) + 1

    # The runs.csv schema: as many drift_k columns as the rows' arms have joints.
    def columns(path):
        header = path.read_text().splitlines()[0].split(",")
        return [c for c in header if not re.fullmatch(r"drift_\d+", c)]

    assert columns(tmp_path / "runs.csv") == columns(ROOT / "results" / "runs.csv")
    with pytest.raises(driftbench.DriftbenchError, match="already on the leaderboard"):
        driftbench.leaderboard({"LVI-PDNN": Gnn()}, tasks=standard[:1], root=ROOT)
    clover = driftbench.task(CLOVER, root=ROOT)
    with pytest.raises(driftbench.DriftbenchError, match="not in the standard task set"):
        driftbench.leaderboard([Gnn()], tasks=[clover], root=ROOT)


def test_a_trajectory_scores_as_the_run_that_made_it(tmp_path):
    circle = driftbench.task(CIRCLE, root=ROOT)
    run = driftbench.simulate(circle, Znn())
    trace = run["trace"]
    n = circle.dof
    path = tmp_path / "znn.csv"
    columns = ["t"] + [f"theta_{i + 1}" for i in range(n)] + [f"thetadot_{i + 1}" for i in range(n)]
    table = np.column_stack([trace["t"], trace["theta"], trace["thetadot"]])
    np.savetxt(path, table, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")
    scored = driftbench.score(circle, str(path), out_dir=tmp_path / "out")
    assert scored["solver_kind"] == "trajectory" and scored["score_samples"] == len(trace["t"])
    np.testing.assert_array_equal(scored["drift"], run["drift"])
    assert within(scored["score_max_dx"], run["score_max_dx"], 1.0 + 1e-6)
    assert (tmp_path / "out" / "scores.csv").exists()
    assert list((tmp_path / "out" / "figures").glob("*.svg"))
    arrays = driftbench.score(circle, {"t": trace["t"], "theta": trace["theta"]})
    np.testing.assert_array_equal(arrays["drift"], run["drift"])
    with pytest.raises(driftbench.DriftbenchError, match="ends at t ="):
        driftbench.score(circle, {"t": trace["t"][:-1], "theta": trace["theta"][:-1]})


def test_cost_of_a_python_call_is_reported():
    run = driftbench.simulate(driftbench.task(CIRCLE, root=ROOT), Znn())
    per_call = run["python_seconds"] / run["python_calls"]
    print(f"\nPython call (ZNN rhs/jacobian, QP conversion included): {per_call * 1e6:.1f} us")
    assert 0 < per_call < 1e-2


OCTAVE = shutil.which("octave-cli") or shutil.which("octave")


@pytest.mark.skipif(
    OCTAVE is None,
    reason="Octave is not installed (Debian: apt-get install octave; .ci/run installs it)",
)
def test_an_octave_mat_file_scores_as_its_csv(tmp_path):
    # examples/octave/znn_circle.m writes the same trajectory as CSV and as a v7 MAT-file.
    for name in ("znn.csv", "znn.mat"):
        script = f"addpath('{ROOT / 'examples' / 'octave'}'); znn_circle('{tmp_path / name}')"
        subprocess.run(
            [OCTAVE, "--no-gui", "--quiet", "--no-init-file", "--eval", script],
            check=True,
            capture_output=True,
        )
    task = driftbench.task(CIRCLE, root=ROOT)
    from_csv = driftbench.score(task, str(tmp_path / "znn.csv"))
    from_mat = driftbench.score(task, str(tmp_path / "znn.mat"))
    np.testing.assert_array_equal(from_mat["drift"], from_csv["drift"])
    assert from_mat["score_max_dx"] == from_csv["score_max_dx"]
    assert from_mat["max_pos_err"] < 1e-9
