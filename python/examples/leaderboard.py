"""A numpy network on the leaderboard beside the suite's own: the gradient network written in
numpy (``driftbench.networks.Gnn``) runs every task of the standard task set through
``driftbench.leaderboard``, which ranks it with the suite's networks exactly as
``results/leaderboard.csv`` ranks them.

In a checkout (this file at ``python/examples/`` of it, or ``--root DIR``), the ranking is
sealed into ``results/leaderboard-python.csv`` (the schema of ``results/leaderboard.csv``) by
``driftbench.into_results``, as ``reproduce`` writes there (under the results directory's lock,
recorded in ``results/manifest.toml``), so the next ``reproduce report`` shows it as the
Leaderboard section's Python entry. Anywhere else (the package installed, this file copied out),
it ranks against the data the package carries and writes ``leaderboard.csv`` and ``runs.csv``
into ``--out`` (default ``leaderboard-python/``).

An entry that fails on a task (raises, returns NaN, or runs past ``--wall-budget`` seconds) has
a failed run there, listed with its reason; the others are still ranked::

    python python/examples/leaderboard.py                 # in a checkout
    python leaderboard.py --out my-board                  # anywhere, package installed
"""

import argparse
import pathlib
import shutil
import tempfile

import driftbench
from driftbench.networks import Gnn


def checkout_of(script):
    """The checkout holding ``script`` at ``python/examples/``, or None when it lies elsewhere."""
    here = script.resolve().parent
    if here.name != "examples" or here.parent.name != "python":
        return None
    root = here.parent.parent
    sealed = (root / "experiments").is_dir() and (root / "results" / "manifest.toml").is_file()
    return root if sealed else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", type=pathlib.Path, help="a checkout to rank in and seal into")
    parser.add_argument(
        "--out",
        type=pathlib.Path,
        default=pathlib.Path("leaderboard-python"),
        help="where to write the tables outside a checkout (default: %(default)s)",
    )
    parser.add_argument(
        "--wall-budget",
        type=float,
        default=None,
        help="seconds of wall time per run (default: driftbench.leaderboard's)",
    )
    args = parser.parse_args()
    root = args.root or checkout_of(pathlib.Path(__file__))
    budget = {} if args.wall_budget is None else {"wall_budget": args.wall_budget}
    entries = {"GNN (numpy)": Gnn()}
    if root is None:
        board = driftbench.leaderboard(entries, out_dir=args.out, **budget)
        out = args.out / "leaderboard.csv"
    else:
        with tempfile.TemporaryDirectory() as scratch:
            board = driftbench.leaderboard(entries, root=root, out_dir=scratch, **budget)
            table = pathlib.Path(scratch) / "leaderboard-python.csv"
            shutil.copyfile(pathlib.Path(scratch) / "leaderboard.csv", table)
            out = driftbench.into_results(table, root=root)
    for row in board["leaderboard"]:
        print(row["task_set"], row["rank"], row["solver"], row["success_pct"], row["dx_rel"])
    for failed in board["failed"]:
        print(f"failed: {failed['solver']} on {failed['task']}: {failed['reason']}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
