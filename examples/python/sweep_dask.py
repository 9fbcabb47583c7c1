"""A parameter sweep of static cases over a Dask cluster.

The Table 4 cantilever of the paper (L = 1 m, EI = 50 N m², 20 elements) under a dead tip
force, swept over the force F (N) and the bending stiffness EI (N m²): one static case per
(F, EI) pair, built from Python values with the case file's keys. The cases are cut into chunks
and each chunk is one Dask task running ``flexwing.solve_many``: one task per case would pay
Dask's per-task overhead (about a millisecond) on cases that take a fraction of that at 20
elements (docs/python.md gives the measured costs). Each case comes back with its
status, result and error as data: a case that fails does not stop the sweep.

    python examples/python/sweep_dask.py                       # 200 cases on 2 local workers
    python examples/python/sweep_dask.py --cases 10000 --workers 8 --chunk 200
    python examples/python/sweep_dask.py --scheduler tcp://head-node:8786   # a running cluster

On a real cluster the same code runs unchanged: give ``--scheduler`` the address of a running
``dask scheduler`` (workers started with ``dask worker tcp://head-node:8786`` on machines that
have ``pip install flexwing`` done), or build the cluster in Python with dask-jobqueue::

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(cores=8, processes=8, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=10)
    client = Client(cluster)

Nothing is written to disk; the summary is printed. Units: N, N m², m.
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


def run_sweep(client, cases: Sequence[flexwing.Case], chunk: int = 50, analysis: str = "static"):
    """Solve ``cases`` on the workers of ``client`` in chunks of ``chunk`` cases; returns one
    ``flexwing.BatchItem`` per case, in input order (``index`` is the position in ``cases``)."""
    chunks = [list(cases[i : i + chunk]) for i in range(0, len(cases), chunk)]
    futures = client.map(flexwing.solve_many, chunks, analysis=analysis, pure=False)
    items = []
    for start, batch in zip(range(0, len(cases), chunk), client.gather(futures)):
        for item in batch:
            item.index += start  # solve_many numbers the cases of its own chunk
            items.append(item)
    return items


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=200, help="number of cases (default 200)")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    parser.add_argument("--chunk", type=int, default=50, help="cases per task (default 50)")
    parser.add_argument("--elements", type=int, default=20, help="elements of the beam (default 20)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler instead of a LocalCluster")
    parser.add_argument("--compare", action="store_true", help="also solve serially and compare")
    args = parser.parse_args()

    from dask.distributed import Client, LocalCluster

    stiffnesses = [40.0, 50.0, 60.0, 80.0]
    forces = np.linspace(10.0, 200.0, max(1, -(-args.cases // len(stiffnesses))))
    cases = sweep_cases(forces, stiffnesses, args.elements)[: args.cases]

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
        items = run_sweep(client, cases, chunk=args.chunk)
        wall = time.perf_counter() - start
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    statuses = {s: sum(i.status == s for i in items) for s in ("complete", "stopped", "error")}
    where = f"{args.workers} local workers" if cluster is not None else args.scheduler
    print(f"{len(items)} cases on {where} in {wall:.3f} s: {statuses}")
    solved = sum(i.wall_time_s for i in items)
    print(f"solver time summed over the cases: {solved:.3f} s ({1e3 * solved / len(items):.3f} ms a case)")
    for item in items[:: max(1, len(items) // 5)]:
        case = cases[item.index]
        f, ei = case.to_dict()["loads"][0]["fy"], case.to_dict()["beam"]["section"]["EI"]
        if item.complete:
            tip = item.result.full
            print(f"  F = {f:6.1f} N, EI = {ei:4.1f} N m^2: tip at ({tip.tip_x[-1]:.5f}, {tip.tip_y[-1]:.5f}) m")
        else:
            print(f"  F = {f:6.1f} N, EI = {ei:4.1f} N m^2: {item.status}: {item.message}")
    if args.compare:
        serial = flexwing.solve_many(cases, "static")
        same = all(
            s.status == d.status
            and (s.result is None or np.array_equal(s.result.full.y, d.result.full.y))
            for s, d in zip(serial, items)
        )
        print(f"equal to the serial sweep: {'yes' if same else 'NO'}")
        if not same:
            raise SystemExit(1)


if __name__ == "__main__":
    main()
