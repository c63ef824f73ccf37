"""A numpy network on the leaderboard beside the suite's own: the gradient network written in
numpy (``driftbench.networks.Gnn``) runs every task of the standard task set through
``driftbench.leaderboard``, which ranks it with the suite's networks exactly as
``results/leaderboard.csv`` ranks them, and the ranking is sealed into
``results/leaderboard-python.csv`` (the schema of ``results/leaderboard.csv``) by
``driftbench.into_results``, as ``reproduce`` writes there (under the results directory's lock,
recorded in ``results/manifest.toml``), so the next ``reproduce report`` shows it as the
Leaderboard section's Python entry.

Run from the repository root, with the package installed (``pip install -v ./python``)::

    python python/examples/leaderboard.py
"""

import pathlib
import shutil
import tempfile

import driftbench
from driftbench.networks import Gnn

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    with tempfile.TemporaryDirectory() as scratch:
        board = driftbench.leaderboard({"GNN (numpy)": Gnn()}, root=ROOT, out_dir=scratch)
        table = pathlib.Path(scratch) / "leaderboard-python.csv"
        shutil.copyfile(pathlib.Path(scratch) / "leaderboard.csv", table)
        out = driftbench.into_results(table, root=ROOT)
    for row in board["leaderboard"]:
        print(row["task_set"], row["rank"], row["solver"], row["success_pct"], row["dx_rel"])
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
