"""driftbench from Python: tasks, runs of numpy networks against their Rust twins, errors, the
leaderboard, the package outside the checkout. Run from anywhere: the tests name this checkout
as root= where they compare with it."""

import ast
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import textwrap
import time

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
    assert clover.scheme["kind"] == "vltco" and clover.scheme["tau"] == 0.4
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
    # The ZNN does not handle the clover's inequality-constrained QP (its handles(dims)).
    with pytest.raises(driftbench.NotApplicable, match=rf'task "{CLOVER}": .*handles\(dims\) returned False'):
        driftbench.simulate(clover, Znn())


def test_an_exception_in_the_network_is_raised_after_the_run():
    class Broken(Gnn):
        def rhs(self, t, y, qp):
            raise ZeroDivisionError("inside rhs")

    with pytest.raises(RuntimeError, match=rf'task "{CLOVER}": GNN \(numpy\)\.rhs at t = ') as info:
        driftbench.simulate(driftbench.task(CLOVER, root=ROOT), Broken())
    assert isinstance(info.value.__cause__, ZeroDivisionError)


def test_ctrl_c_stops_a_run_of_a_python_network():
    """SIGINT during a long run of a slow network: KeyboardInterrupt within seconds, as any
    Python loop would stop, not after the run."""
    import signal
    import time

    script = textwrap.dedent(
        f"""
        import sys, time
        import driftbench
        from driftbench.networks import Gnn

        class Slow(Gnn):
            def rhs(self, t, y, qp):
                time.sleep(0.002)
                return super().rhs(t, y, qp)

        print("started", flush=True)
        try:
            driftbench.simulate(driftbench.task({CLOVER!r}, root={str(ROOT)!r}), Slow())
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            sys.exit(3)
        print("finished", flush=True)
        """
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert proc.stdout.readline().strip() == "started"
    time.sleep(1.0)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    try:
        out, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the run went on for 60 s after Ctrl-C")
    assert proc.returncode == 3, (out, err)
    assert "interrupted" in out
    assert time.monotonic() - sent < 30


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
    # The Python call counts stay on the runs' rows.
    assert all(r["python_calls"] > 0 and r["python_seconds"] > 0 for r in board["runs"])
    assert board["not_applicable"] == []
    with pytest.raises(driftbench.DriftbenchError, match="already on the leaderboard"):
        driftbench.leaderboard({"LVI-PDNN": Gnn()}, tasks=standard[:1], root=ROOT)
    clover = driftbench.task(CLOVER, root=ROOT)
    valid = re.escape(standard[0].id)
    with pytest.raises(driftbench.DriftbenchError, match=rf'no standard task "{CLOVER}".*valid ids: .*{valid}'):
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


def test_tasks_expose_the_qp_dimensions_and_the_meaning_of_x():
    clover = driftbench.task(CLOVER, root=ROOT)
    # jia2019's VLTCO: x = [thetadot; p], p = |thetadot|_inf; G holds |thetadot_i| <= p.
    assert (clover.nx, clover.n_aux, clover.n_eq, clover.n_in) == (7, 1, 3, 12)
    assert clover.level == "velocity" and clover.nx == clover.dof + 1
    assert (clover.dims.nx, clover.dims.n_eq, clover.dims.n_in) == (7, 3, 12)
    circle = driftbench.task(CIRCLE, root=ROOT)
    assert (circle.nx, circle.n_aux, circle.n_in) == (circle.dof, 0, 0)
    zhong = [t for t in driftbench.tasks(root=ROOT) if t.paper == "zhong2021"]
    assert zhong and all(t.nx == t.dof + 1 for t in zhong)
    zhang = [t for t in driftbench.tasks(root=ROOT) if t.paper == "zhang2018"]
    assert zhang and all(t.level == "acceleration" for t in zhang)
    for text in (driftbench.Task.__doc__, (ROOT / "python" / "README.md").read_text()):
        assert "auxiliary" in text and "dof + 1" in text


def test_a_network_that_handles_some_tasks_is_ranked_on_those(tmp_path):
    standard = driftbench.standard_tasks(root=ROOT)
    equality = [t for t in standard if t.n_in == 0]
    inequality = [t for t in standard if t.n_in > 0]
    assert equality and inequality
    chosen = [equality[0].id, inequality[0].id]  # ids, not Task objects

    class Declines(Gnn):
        """Says N/A by raising NotApplicable while it is built, on the inequality tasks."""

        def state_dim(self, dims):
            if dims.n_in:
                raise driftbench.NotApplicable("no inequality rows, please")
            return dims.nx

    board = driftbench.leaderboard(
        {"ZNN (numpy)": Znn(), "GNN declining": Declines()}, tasks=chosen, root=ROOT
    )
    for name in ("ZNN (numpy)", "GNN declining"):
        runs = [r for r in board["runs"] if r["solver"] == name]
        assert [f"{r['experiment']} / {r['variant_id']}" for r in runs] == [equality[0].id]
        skipped = [n for n in board["not_applicable"] if n["solver"] == name]
        assert [n["task"] for n in skipped] == [inequality[0].id]
        ranked = [r for r in board["leaderboard"] if r["solver"] == name]
        assert len(ranked) == 1 and ranked[0]["task_set"] != "standard"
        assert ranked[0]["tasks"] == 1 and ranked[0]["standard_runs"] == 1
    reasons = {n["solver"]: n["reason"] for n in board["not_applicable"]}
    assert "handles(dims) returned False" in reasons["ZNN (numpy)"]
    assert "no inequality rows, please" in reasons["GNN declining"]



class Raises(Gnn):
    def rhs(self, t, y, qp):
        raise ZeroDivisionError("inside rhs")


class ReturnsNan(Gnn):
    def rhs(self, t, y, qp):
        return np.full(len(y), np.nan)


class Hangs(Gnn):
    """A call into the network that never returns."""

    def rhs(self, t, y, qp):
        while True:
            pass


class Crawls(Gnn):
    """Every call returns, but the run would take hours."""

    def rhs(self, t, y, qp):
        time.sleep(0.05)
        return super().rhs(t, y, qp)


def test_an_entry_that_raises_returns_nan_or_hangs_is_a_failed_run_and_the_rest_rank(tmp_path):
    """The issue's case: one entry must not abort the leaderboard. Each failing entry has a
    failed run per task with its reason (in the rows, runs.csv and board["failed"]); the
    working entry is ranked above them; the hanging ones cost the budget, not the test."""
    # Two tasks the numpy GNN runs in well under the budget (about 0.05 s each).
    chosen = [t.id for t in driftbench.standard_tasks(root=ROOT) if t.id.endswith("/ znn-scheme")][:2]
    assert len(chosen) == 2
    budget = 1.0
    entries = {
        "GNN (numpy)": Gnn(),
        "raises": Raises(name="raises"),
        "returns NaN": ReturnsNan(name="returns NaN"),
        "hangs": Hangs(name="hangs"),
        "crawls": Crawls(name="crawls"),
    }
    started = time.monotonic()
    board = driftbench.leaderboard(
        entries, tasks=chosen, root=ROOT, out_dir=tmp_path, wall_budget=budget
    )
    elapsed = time.monotonic() - started
    # Two tasks of at most the budget (and a call's overrun) for each of the two slow entries.
    assert elapsed < 4 * len(chosen) * budget + 10, elapsed
    runs = {(r["solver"], f"{r['experiment']} / {r['variant_id']}"): r for r in board["runs"]}
    assert len(runs) == len(entries) * len(chosen)
    expected = {
        "raises": ("network", "ZeroDivisionError: inside rhs"),
        "returns NaN": ("network", "non-finite entry (NaN at index 0)"),
        "hangs": ("wall-time", "wall-time budget of 1 s used up inside hangs.rhs at t = "),
        "crawls": ("wall-time", "wall-time budget of 1 s used up"),
    }
    for task in chosen:
        assert runs[("GNN (numpy)", task)]["status"] == "ok"
        for name, (kind, reason) in expected.items():
            row = runs[(name, task)]
            assert row["status"] == "failed" and row["failure_kind"] == kind, row
            assert reason in row["failure"], row["failure"]
            assert row["drift_norm"] is None
    failed = {(f["solver"], f["task"]): f["reason"] for f in board["failed"]}
    assert failed == {(n, t): runs[(n, t)]["failure"] for n in expected for t in chosen}
    written = (tmp_path / "runs.csv").read_text()
    assert "ZeroDivisionError: inside rhs" in written and "wall_budget" in written
    # Every entry is ranked in the set of the chosen tasks; the working one first.
    ranked = {r["solver"]: r for r in board["leaderboard"] if r["solver"] in entries}
    assert set(ranked) == set(entries)
    assert len({r["task_set"] for r in ranked.values()}) == 1
    for name in expected:
        assert ranked[name]["success_pct"] == 0
        assert ranked["GNN (numpy)"]["rank"] < ranked[name]["rank"]
    with pytest.raises(ValueError, match="wall_budget must be positive and finite"):
        driftbench.leaderboard([Gnn()], tasks=chosen, root=ROOT, wall_budget=0.0)


def test_simulate_with_a_wall_budget_stops_a_hanging_network():
    circle = driftbench.task(CIRCLE, root=ROOT)
    started = time.monotonic()
    run = driftbench.simulate(circle, Hangs(name="hangs"), wall_budget=0.5)
    assert time.monotonic() - started < 10
    assert run["status"] == "failed" and run["failure_kind"] == "wall-time"
    assert "inside hangs.rhs at t = " in run["failure"]
    # Nothing of the budget is left to go off in the code after the run.
    total = 0
    for i in range(3_000_000):
        total += i
    assert total > 0
    # What the network raised is still raised by simulate, the budget or not.
    with pytest.raises(RuntimeError, match=rf'task "{CIRCLE}": raises\.rhs at t = ') as info:
        driftbench.simulate(circle, Raises(name="raises"), wall_budget=5.0)
    assert isinstance(info.value.__cause__, ZeroDivisionError)


def test_the_leaderboard_example_runs_outside_a_checkout(tmp_path):
    """python/examples/leaderboard.py copied out of the checkout (as a user who has the
    package, not the repository, runs it): it ranks against the packaged data and writes its
    tables into --out."""
    here = tmp_path / "elsewhere"
    here.mkdir()
    script = here / "leaderboard.py"
    shutil.copy(ROOT / "python" / "examples" / "leaderboard.py", script)
    out = outside_run(tmp_path, [str(script), "--out", "board"], cwd=here)
    table = (here / "board" / "leaderboard.csv").read_text()
    assert "GNN (numpy)" in table and "LVI-PDNN" in table
    assert (here / "board" / "runs.csv").exists()
    assert "board" in out


def test_tasks_are_given_by_id_and_unknown_ids_are_listed():
    standard = driftbench.standard_tasks(root=ROOT)
    with pytest.raises(driftbench.DriftbenchError, match=r'no standard task "nope / x".*valid ids: ') as info:
        driftbench.leaderboard([Gnn()], tasks=["nope / x"], root=ROOT)
    assert all(t.id in str(info.value) for t in standard)
    with pytest.raises(TypeError, match="not one id"):
        driftbench.leaderboard([Gnn()], tasks=standard[0].id, root=ROOT)
    with pytest.raises(TypeError, match="Task objects or ids"):
        driftbench.leaderboard([Gnn()], tasks=[3], root=ROOT)
    with pytest.raises(driftbench.DriftbenchError, match=re.escape(CIRCLE)):
        driftbench.task("kong2019-circle / nope", root=ROOT)


def test_a_missing_needs_qp_dot_is_diagnosed_with_a_hint():
    class NoQpDot(Znn):
        needs_qp_dot = False

    circle = driftbench.task(CIRCLE, root=ROOT)
    with pytest.raises(TypeError, match=r"\.rhs takes \(t, y, qp, qp_dot\).*set needs_qp_dot = True"):
        driftbench.simulate(circle, NoQpDot())

    class Extra(Gnn):
        needs_qp_dot = True

    with pytest.raises(TypeError, match=r"\.rhs takes \(t, y, qp\) but the network sets needs_qp_dot"):
        driftbench.simulate(circle, Extra())


def test_bad_input_from_python_raises_errors_naming_the_field():
    circle = driftbench.task(CIRCLE, root=ROOT)

    class Complex(Gnn):
        def rhs(self, t, y, qp):
            return y * 1j

    with pytest.raises(RuntimeError, match="rhs at t = 0") as info:
        driftbench.simulate(circle, Complex())
    assert isinstance(info.value.__cause__, TypeError)
    assert "real numbers" in str(info.value.__cause__)

    class Flat(Gnn):
        def jacobian(self, t, y, qp):
            return np.zeros(len(y))

    with pytest.raises(RuntimeError, match="jacobian at t = ") as info:
        driftbench.simulate(circle, Flat())
    assert "2-D array" in str(info.value.__cause__)

    class Nan(Gnn):
        def rhs(self, t, y, qp):
            return np.full(len(y), np.nan)

    with pytest.raises(RuntimeError, match="rhs at t = 0") as info:
        driftbench.simulate(circle, Nan())
    assert "non-finite entry (NaN at index 0)" in str(info.value.__cause__)
    run = driftbench.simulate(circle, Znn())
    t, theta = run["trace"]["t"], run["trace"]["theta"]
    for typo in ("thetadott", "thetadto"):
        with pytest.raises(ValueError, match=rf"'{typo}'"):
            driftbench.score(circle, {"t": t, "theta": theta, typo: theta})
    with pytest.raises(ValueError, match=r'trajectory\["theta"\].*2-D array'):
        driftbench.score(circle, {"t": t, "theta": theta[:, 0]})
    with pytest.raises(TypeError, match=r'trajectory\["theta"\].* must be real numbers'):
        driftbench.score(circle, {"t": t, "theta": theta + 0j})
    with pytest.raises(ValueError, match='needs "theta"'):
        driftbench.score(circle, {"t": t})
    with pytest.raises(TypeError, match="a file .* or a dict of arrays"):
        driftbench.score(circle, 3.0)
    with pytest.raises(ValueError, match=r'theta"\] has 7 rows, trajectory\["t"\] '):
        driftbench.score(circle, {"t": t, "theta": theta[:7]})
    for bad, error in ((-1, ValueError), (10**12, ValueError), ("7", TypeError)):
        with pytest.raises(error, match=r"state_dim"):
            driftbench.simulate(circle, type("Sized", (Gnn,), {"state_dim": bad})())
    with pytest.raises(ValueError, match=r"scoring must be .* got -3"):
        driftbench.simulate(circle, Znn(), scoring=-3)
    with pytest.raises(TypeError, match=r"scoring must be .* got float"):
        driftbench.simulate(circle, Znn(), scoring=2.5)
    with pytest.raises(ValueError, match="tasks= is empty"):
        driftbench.leaderboard([Gnn()], tasks=[], root=ROOT)
    with pytest.raises(TypeError, match="rtoll"):
        driftbench.simulate(circle, Znn(), rtoll=1e-6)


def test_errors_about_the_root_name_root_not_a_command_line_flag(tmp_path):
    with pytest.raises(driftbench.DriftbenchError, match=r"root=.*no experiments/ folder") as info:
        driftbench.tasks(root=tmp_path)
    assert "--root" not in str(info.value)
    (tmp_path / "experiments").mkdir()
    with pytest.raises(driftbench.DriftbenchError, match=r"root=.*holds no experiment file") as info:
        driftbench.standard_tasks(root=tmp_path)
    assert "--" not in str(info.value)


def project_copy(tmp_path):
    """A project beside the checkout: its experiment files and the top level of its results/
    (the tables and results/manifest.toml, which seals them), and report/manifest.toml."""
    proj = tmp_path / "project"
    shutil.copytree(ROOT / "experiments", proj / "experiments")
    (proj / "results").mkdir(parents=True)
    for f in (ROOT / "results").iterdir():
        if f.is_file() and not f.name.startswith("."):
            shutil.copy(f, proj / "results" / f.name)
    (proj / "report").mkdir()
    shutil.copy(ROOT / "report" / "manifest.toml", proj / "report" / "manifest.toml")
    return proj


def test_out_dir_may_not_be_a_directory_driftbench_seals(tmp_path):
    """The audit's case: leaderboard(out_dir="results") cut runs.csv to the network's rows;
    score(out_dir="results") would pass a trajectory for a run. Both are refused before
    anything runs, and nothing there changes."""
    proj = project_copy(tmp_path)
    runs = (proj / "results" / "runs.csv").read_bytes()
    circle = driftbench.task(CIRCLE, root=proj)
    run = driftbench.simulate(circle, Znn())
    trajectory = tmp_path / "znn.csv"
    n = circle.dof
    columns = ["t"] + [f"theta_{i + 1}" for i in range(n)]
    table = np.column_stack([run["trace"]["t"], run["trace"]["theta"]])
    np.savetxt(trajectory, table, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")
    for out in (proj / "results", proj / "results" / "traces" / "x", proj / "report"):
        with pytest.raises(driftbench.DriftbenchError, match=r"out_dir=.*sealed by driftbench's"):
            driftbench.leaderboard([Gnn()], tasks=[CIRCLE], root=proj, out_dir=out)
        with pytest.raises(driftbench.DriftbenchError, match="sealed by this program's manifest"):
            driftbench.score(circle, str(trajectory), out_dir=out)
    assert (proj / "results" / "runs.csv").read_bytes() == runs
    assert not (proj / "results" / "traces").exists()
    assert sorted(p.name for p in (proj / "report").iterdir()) == ["manifest.toml"]


def test_a_scripts_table_is_sealed_into_results(tmp_path):
    """The audit's case: python/examples/leaderboard.py wrote results/leaderboard-python.csv
    past the manifest, so the next `reproduce report` refused. into_results writes it as
    reproduce does: checked, under the lock, recorded in results/manifest.toml."""
    import hashlib

    proj = project_copy(tmp_path)
    committed = (ROOT / "results" / "leaderboard-python.csv").read_text().splitlines()
    table = tmp_path / "leaderboard-python.csv"
    table.write_text("\n".join(committed[:2]) + "\n")
    out = driftbench.into_results(table, root=proj)
    assert out == proj / "results" / "leaderboard-python.csv"
    assert out.read_bytes() == table.read_bytes()
    manifest = (proj / "results" / "manifest.toml").read_text()
    entry = manifest.split('[files."leaderboard-python.csv"]')[1].split("[files.")[0]
    assert f'sha256 = "{hashlib.sha256(table.read_bytes()).hexdigest()}"' in entry
    # Only the scripts' tables, each in its schema; never past an edit of results/.
    other = tmp_path / "runs.csv"
    other.write_text("x\n")
    with pytest.raises(driftbench.DriftbenchError, match="leaderboard-python.csv, python-call-cost.csv"):
        driftbench.into_results(other, root=proj)
    cost = tmp_path / "python-call-cost.csv"
    cost.write_text("network,task\nx,y\n")
    with pytest.raises(driftbench.DriftbenchError, match="not a table of its schema"):
        driftbench.into_results(cost, root=proj)
    # A name with markup or a line break is refused where it enters (the audit's case: it
    # reached report/leaderboard.md unescaped), without quoting it.
    import csv
    import io

    header, row = next(csv.reader([committed[0]])), next(csv.reader([committed[1]]))
    standard = driftbench.standard_tasks(root=ROOT)
    for name in ["<img src=x onerror=alert(1)>", "[x](javascript:alert(1))", "a\n## b"]:
        evil = dict(zip(header, row), solver=name)
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=header, lineterminator="\n")
        w.writeheader()
        w.writerow(evil)
        table.write_text(buf.getvalue())
        with pytest.raises(driftbench.DriftbenchError, match="line 2, column `solver`: holds HTML") as e:
            driftbench.into_results(table, root=proj)
        assert name not in str(e.value)
        with pytest.raises(driftbench.DriftbenchError, match="leaderboard's entry name"):
            driftbench.leaderboard({name: Gnn()}, tasks=[standard[0]], root=ROOT)
    table.write_text("\n".join(committed[:2]) + "\n")
    with (proj / "results" / "runs.csv").open("a") as f:
        f.write("\n")
    with pytest.raises(driftbench.DriftbenchError, match="runs.csv"):
        driftbench.into_results(table, root=proj)


OUTSIDE = textwrap.dedent(
    """
    import json, driftbench
    from driftbench.networks import Gnn
    standard = driftbench.standard_tasks()
    board = driftbench.leaderboard([Gnn()], tasks=[standard[0].id])
    print(json.dumps({
        "tasks": len(driftbench.tasks()),
        "standard": [t.id for t in standard],
        "root": str(driftbench.data_root()),
        "ranked": any(r["solver"] == "GNN (numpy)" for r in board["leaderboard"]),
    }))
    """
)


def outside(tmp_path, code):
    """Runs `code` with the installed package from a directory outside the checkout, with a
    fresh cache (where the package unpacks its data)."""
    cwd = tmp_path / "elsewhere"
    cwd.mkdir(exist_ok=True)
    return outside_run(tmp_path, ["-c", code], cwd)


def outside_run(tmp_path, args, cwd):
    """Runs `python args...` in `cwd` (outside the checkout) with a fresh cache; its stdout."""
    assert not any((d / "experiments").is_dir() for d in [cwd, *cwd.parents])
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"))
    out = subprocess.run(
        [sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_the_installed_package_works_outside_the_checkout(tmp_path):
    import json

    # The acceptance command, as a user types it.
    count = outside(tmp_path, "import driftbench; print(len(driftbench.tasks()))")
    assert int(count) == len(driftbench.tasks(root=ROOT))
    got = json.loads(outside(tmp_path, OUTSIDE))
    assert got["tasks"] == len(driftbench.tasks(root=ROOT))
    assert got["standard"] == [t.id for t in driftbench.standard_tasks(root=ROOT)]
    assert got["ranked"]
    # The package's data is the repository's own files, byte for byte (the wheel embeds them
    # at build time), and an edit in the unpacked copy does not survive the next process.
    data = pathlib.Path(got["root"])
    assert data.is_relative_to(tmp_path / "cache")
    files = sorted(
        p.relative_to(data) for p in data.rglob("*") if p.is_file() and p.name != ".driftbench-private"
    )
    assert pathlib.Path("experiments/cross.toml") in files
    assert pathlib.Path("results/runs.csv") in files
    assert any(p.parts[0] == "papers" for p in files)
    for rel in files:
        assert (data / rel).read_bytes() == (ROOT / rel).read_bytes(), rel
    (data / "results" / "runs.csv").write_text("edited")
    outside(tmp_path, "import driftbench; driftbench.standard_tasks()")
    assert (data / "results" / "runs.csv").read_bytes() == (ROOT / "results" / "runs.csv").read_bytes()
    # A file the package did not write is named, not deleted (nor read as an experiment).
    (data / "experiments" / "stray.toml").write_text("not an experiment file")
    err = outside_fails(tmp_path, "import driftbench; driftbench.tasks()")
    assert "stray.toml: driftbench did not write it" in err, err
    assert (data / "experiments" / "stray.toml").exists()


def outside_fails(tmp_path, code):
    """`outside`, for code that must fail: its standard error."""
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"))
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert out.returncode != 0, out.stdout
    return out.stderr


def test_the_data_cache_is_private_and_never_followed_through_a_link(tmp_path):
    """The audit's case: with $XDG_CACHE_HOME/driftbench/data-<digest> linked elsewhere,
    driftbench.tasks() deleted the files there and wrote its data into it. The cache is
    created owner-only; a link, a directory the package did not create and one other users may
    write are refused, and nothing there is written or deleted."""
    code = "import driftbench; print(driftbench.data_root())"
    data = pathlib.Path(outside(tmp_path, code).strip())
    assert data.stat().st_mode & 0o777 == 0o700
    assert data.parent.stat().st_mode & 0o777 == 0o700
    elsewhere = tmp_path / "elsewhere-data"
    elsewhere.mkdir()
    (elsewhere / "precious.txt").write_text("keep")
    shutil.rmtree(data)
    data.symlink_to(elsewhere)
    err = outside_fails(tmp_path, "import driftbench; driftbench.tasks()")
    assert "is a symbolic link" in err, err
    assert sorted(p.name for p in elsewhere.iterdir()) == ["precious.txt"]
    # A directory in its place that the package did not create (a poisoned cache).
    data.unlink()
    data.mkdir(mode=0o700)
    (data / "planted.toml").write_text("x")
    err = outside_fails(tmp_path, "import driftbench; driftbench.tasks()")
    assert "was not created by driftbench" in err, err
    assert (data / "planted.toml").read_text() == "x"
    shutil.rmtree(data)
    data.parent.chmod(0o777)
    err = outside_fails(tmp_path, "import driftbench; driftbench.tasks()")
    assert "other users may write it" in err, err


def test_the_type_stubs_cover_the_module():
    package = pathlib.Path(driftbench.__file__).parent
    assert (package / "py.typed").exists()
    stub = ast.parse((package / "_driftbench.pyi").read_text())
    stubbed = {n.name for n in stub.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    public = {n for n in dir(driftbench._driftbench) if not n.startswith("_")}
    assert public == stubbed
    task_props = {
        n.name for c in stub.body if isinstance(c, ast.ClassDef) and c.name == "Task" for n in c.body
        if isinstance(n, ast.FunctionDef)
    }
    assert task_props == {n for n in dir(driftbench.Task) if not n.startswith("_")}


ARM4 = """name = "{name}"
source = "a test arm: a yaw joint, then three pitch links"
convention = "standard"
tool = [0.0, 0.0, 0.0]
{extra}
[[joint]]
a = 0.0
alpha = 1.5707963267948966
d = 0.3

[[joint]]
a = 0.3
alpha = 0.0
d = 0.0

[[joint]]
a = 0.3
alpha = 0.0
d = 0.0

[[joint]]
a = 0.3
alpha = 0.0
d = 0.0
"""

ARM4_EXPERIMENT = """paper = "kong2019"
title = "a robot file of one's own"

[[experiment]]
id = "kong2019-py-arm4"
paper_output = "none"
robot = "py-arm4"
tool = [0.0, 0.0, 0.05]
path = { name = "circle", duration = 1.0 }
theta0 = [0.2, 1.2, -0.8, -0.8]
exact_integrator = { method = "bdf", rtol = 1e-8, atol = 1e-10 }

[[experiment.variant]]
id = "znn"
label = "ZNN (eq. 22)"
scheme = { kind = "znn-rmp", mu = 1.0, k_p = 1.0 }
solvers = [{ kind = "znn", gamma = 1.0 }]
"""


def test_a_robot_file_written_at_run_time_runs_a_task_without_a_rebuild(tmp_path):
    # A 4-joint robot file of one's own, outside any checkout, registered by its path.
    (tmp_path / "py-arm4.toml").write_text(ARM4.format(name="py-arm4", extra=""))
    assert driftbench.add_robots(tmp_path / "py-arm4.toml") == ["py-arm4"]
    assert driftbench.add_robots(str(tmp_path / "py-arm4.toml")) == ["py-arm4"]  # once only
    project = tmp_path / "project"
    (project / "experiments").mkdir(parents=True)
    (project / "experiments" / "arm4.toml").write_text(ARM4_EXPERIMENT)
    task = driftbench.task("kong2019-py-arm4 / znn", root=project)
    assert task.robot == "py-arm4" and task.dof == 4 and task.nx == 4
    run = driftbench.simulate(task, Znn(gamma=1.0))
    assert run["status"] == "ok", run.get("failure")
    assert len(run["drift"]) == 4 and run["max_pos_err"] < 1e-4
    twin = driftbench.simulate(task, "znn")
    assert twin["status"] == "ok" and within(run["drift_norm"], twin["drift_norm"], DRIFT_FACTOR)


def test_a_paper_folder_of_robot_files_registers_and_a_bad_file_names_its_field(tmp_path):
    robots = tmp_path / "mypaper" / "robots"
    robots.mkdir(parents=True)
    (robots / "py-arm4b.toml").write_text(ARM4.format(name="py-arm4b", extra=""))
    assert driftbench.add_robots(tmp_path / "mypaper") == ["py-arm4b"]
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "py-arm4c.toml").write_text(ARM4.format(name="py-arm4c", extra='stated_pose = [0.0]'))
    with pytest.raises(driftbench.DriftbenchError, match=r"py-arm4c\.toml.*stated_pose"):
        driftbench.add_robots(bad)
    with pytest.raises(driftbench.DriftbenchError, match="no robot file here"):
        driftbench.add_robots(tmp_path / "project-that-is-not-there")
