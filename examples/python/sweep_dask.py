"""A parameter sweep of static cases over a Dask cluster.

The Table 4 cantilever of the paper (L = 1 m, EI = 50 N m², 20 elements) under a dead tip
force, swept over the force F (N) and the bending stiffness EI (N m²): one static case per
(F, EI) pair, built from Python values with the case file's keys. The cases are cut into chunks
and each chunk is one Dask task running ``flexwing.solve_many``: one task per case would pay
Dask's per-task overhead (about a millisecond) on cases that take a fraction of that at 20
elements (docs/python.md gives the measured costs). Each worker also reduces its results to
the numbers the study needs (here the tip, ``tip``) before sending them back: a whole result
holds a dozen NumPy arrays, and pickling them costs more than solving these small cases. Each case comes back with its
status, result and error as data: a case that fails does not stop the sweep. The sweep comes
back as a pandas DataFrame indexed by the swept parameters (F, EI): ``sweep()``.

    python examples/python/sweep_dask.py                       # 200 cases on 2 local workers
                                                               # (rounded up to a multiple of 4)
    python examples/python/sweep_dask.py --cases 10000 --workers 8 --chunk 200
    python examples/python/sweep_dask.py --scheduler tcp://head-node:8786   # a running cluster

On a real cluster the same code runs unchanged: give ``--scheduler`` the address of a running
``dask scheduler`` (workers started with ``dask worker tcp://head-node:8786`` on machines that
have ``pip install flexwing`` done), or build the cluster in Python with dask-jobqueue::

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=8, processes=8, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=10)
    client = Client(cluster)

Nothing is written to disk; the summary is printed. Units: N, N m², m. Needs pandas and dask
(``pip install "flexwing[pandas]" "dask[distributed]"``).
"""

from __future__ import annotations

import argparse
import time
from typing import List, Sequence

import numpy as np

import flexwing

#: The base case, as the dict of a case file (docs/case-file.md): the paper's Table 4 beam with
#: a dead tip force, full model only.
BASE = {
    "title": "Table 4 beam under a dead tip force (sweep)",
    "beam": {
        "length": 1.0,  # m
        "elements": 20,
        "calibration": "tip-load",
        "section": {"EI": 50.0, "mass_per_length": 0.2},  # N m², kg/m
    },
    "loads": [{"name": "F", "type": "point-force", "span": 1.0, "direction": "dead", "fy": 1.0}],
    "static": {"full": True},
}


def sweep_cases(
    forces: Sequence[float], stiffnesses: Sequence[float], elements: int = 20
) -> List[flexwing.Case]:
    """One case per (force F in N, stiffness EI in N m²), forces outermost, on a beam of
    ``elements`` elements."""
    base = flexwing.Case(BASE).replace({"beam.elements": elements})
    return [
        base.replace({"loads[0].fy": float(f), "beam.section.EI": float(ei)})
        for f in forces
        for ei in stiffnesses
    ]


def solve_chunk(cases, start: int, analysis: str = "static", keep=None):
    """The task a worker runs: ``flexwing.solve_many`` on one chunk of cases, numbered from
    ``start``; with ``keep``, each ``BatchItem`` is reduced on the worker to what ``keep``
    returns (a few numbers travel back instead of every array of the result)."""
    items = flexwing.solve_many(cases, analysis, start=start)  # indices in the whole sweep
    return items if keep is None else [keep(item) for item in items]


def tip(item: flexwing.BatchItem):
    """A ``keep`` function: one row of the sweep's table — the case's index, status, message
    and final tip position ``tip_x``, ``tip_y`` (m; None where the case has no result)."""
    row = {"index": item.index, "status": item.status, "message": item.message, "tip_x": None, "tip_y": None}
    if item.result is not None and len(item.result.full.tip_y):
        full = item.result.full
        row.update(tip_x=float(full.tip_x[-1]), tip_y=float(full.tip_y[-1]))
    return row


def run_sweep(client, cases: Sequence[flexwing.Case], chunk: int = 50, analysis: str = "static", keep=None):
    """Solve ``cases`` on the workers of ``client`` in chunks of ``chunk`` cases; returns one
    ``flexwing.BatchItem`` per case (or what ``keep`` makes of it), in input order."""
    starts = range(0, len(cases), chunk)
    futures = [
        client.submit(solve_chunk, list(cases[s : s + chunk]), s, analysis, keep, pure=False)
        for s in starts
    ]
    return [item for batch in client.gather(futures) for item in batch]


def sweep_index(forces: Sequence[float], stiffnesses: Sequence[float]):
    """The swept parameters of ``sweep_cases``, in its order: a pandas MultiIndex (F in N, EI
    in N m²)."""
    import pandas as pd

    return pd.MultiIndex.from_product([list(forces), list(stiffnesses)], names=["F", "EI"])


def sweep(client, forces, stiffnesses, chunk: int = 50, elements: int = 20, full_results: bool = False):
    """The whole study: the cases of every (F, EI), solved on ``client``'s workers, as a pandas
    DataFrame indexed by (F, EI). Reduced on the workers to the rows of ``tip`` (columns
    ``status``, ``message``, ``tip_x``, ``tip_y``), or with ``full_results`` the whole results
    brought back and tabulated by ``flexwing.Batch.to_pandas`` (``full.tip_y``, … for every
    model)."""
    import pandas as pd

    cases = sweep_cases(forces, stiffnesses, elements)
    index = sweep_index(forces, stiffnesses)
    if full_results:
        return flexwing.Batch(run_sweep(client, cases, chunk=chunk)).to_pandas(index=index)
    rows = run_sweep(client, cases, chunk=chunk, keep=tip)
    return pd.DataFrame(rows, index=index).drop(columns="index")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=200, help="number of cases, rounded up to a multiple of 4 (default 200)")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    parser.add_argument("--chunk", type=int, default=50, help="cases per task (default 50)")
    parser.add_argument("--elements", type=int, default=20, help="elements of the beam (default 20)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler instead of a LocalCluster")
    parser.add_argument("--compare", action="store_true", help="also solve serially and compare")
    parser.add_argument("--full-results", action="store_true", help="bring back whole results, not just the tips")
    args = parser.parse_args()

    from dask.distributed import Client, LocalCluster

    stiffnesses = [40.0, 50.0, 60.0, 80.0]
    forces = np.linspace(10.0, 200.0, max(1, -(-args.cases // len(stiffnesses))))

    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(
            n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None
        )
        client = Client(cluster)
    try:
        start = time.perf_counter()
        frame = sweep(client, forces, stiffnesses, args.chunk, args.elements, args.full_results)
        wall = time.perf_counter() - start
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    tip_y = "full.tip_y" if args.full_results else "tip_y"
    statuses = frame["status"].value_counts().to_dict()
    where = f"{args.workers} local workers" if cluster is not None else args.scheduler
    print(f"{len(frame)} cases on {where} in {wall:.3f} s: {statuses}")
    print(frame[["status", tip_y]].iloc[:: max(1, len(frame) // 5)].to_string())
    if args.compare:
        cases = sweep_cases(forces, stiffnesses, args.elements)
        serial = flexwing.solve_many(cases, "static").to_pandas(index=sweep_index(forces, stiffnesses))
        same = serial["full.tip_y"].equals(frame[tip_y].rename("full.tip_y"))  # bit for bit
        print(f"equal to the serial sweep: {'yes' if same else 'NO'}")
        if not same:
            raise SystemExit(1)


if __name__ == "__main__":
    main()
