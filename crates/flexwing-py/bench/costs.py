"""What calling flexwing through Python costs (docs/python.md, "Costs"). Not run by the tests: a
benchmark that prints its figures (medians of repeated runs; the machine may be shared, so
compare medians, not single runs).

    python crates/flexwing-py/bench/costs.py              # all three parts
    python crates/flexwing-py/bench/costs.py case-b stepper
    python crates/flexwing-py/bench/costs.py sweep --cases 2000

1. case-b: the paper's case (b) (examples/paper_sine.toml: five models, 1 s), the Python wall
   time of ``case.dynamics()`` against the Rust side of the same call (``rust_time_s``, timed
   in Rust around the plan and the run, the interpreter released), and the CLI binary
   (``flexwing dynamic … --json``, process start and JSON output included) for reference.
2. stepper: the cost of one ``Stepper.step`` call beyond the integrator's time (``stats
   ["rust_time_s"]``), on the smallest model (a reduced model on 1 mode, a short interval), and
   of one ``Equations.rhs`` call at n = 20 (wall time of the whole call: the Rust work is a
   fraction of a microsecond).
3. sweep: static cases of examples/python/sweep_dask.py (Table 4 beam, 20 elements, dead tip
   force, full model) by ``solve_many`` serially, and on 1 and 2 Dask worker processes
   (LocalCluster, chunks of 100 cases), bringing back whole results or only the tips (reduced
   on the workers), cluster start-up excluded and reported apart.
4. sweep-dynamic: 16 dynamic cases (case (b), full model, force amplitude swept), serially and
   on 1 and 2 workers, one case a task.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import flexwing

ROOT = pathlib.Path(__file__).resolve().parents[3]


def median(xs):
    return statistics.median(xs)


def case_b(repeats: int) -> None:
    case = flexwing.Case.load(ROOT / "examples" / "paper_sine.toml")
    case.dynamics()  # warm-up
    python, rust, models = [], [], []
    for _ in range(repeats):
        start = time.perf_counter()
        result = case.dynamics()
        python.append(time.perf_counter() - start)
        rust.append(result.rust_time_s)
        models.append(sum(r.wall_time_s for r in result.runs))
    overhead = [p - r for p, r in zip(python, rust)]
    print(f"case (b), {repeats} runs, medians:")
    print(f"  Python case.dynamics()          {1e3 * median(python):9.2f} ms")
    print(f"  Rust side of the call           {1e3 * median(rust):9.2f} ms  (plan, modes, 5 model runs)")
    print(f"  of which the 5 integrations     {1e3 * median(models):9.2f} ms")
    print(f"  binding overhead                {1e3 * median(overhead):9.3f} ms  "
          f"({100 * median(overhead) / median(rust):.2f} %; min {1e3 * min(overhead):.3f} ms)")
    cli = os.environ.get("FLEXWING_CLI", str(ROOT / "target" / "release" / "flexwing"))
    if pathlib.Path(cli).exists():
        times = []
        with tempfile.TemporaryDirectory() as out:
            for _ in range(repeats):
                start = time.perf_counter()
                subprocess.run(
                    [cli, "dynamic", str(ROOT / "examples" / "paper_sine.toml"), "--json", "--out", out],
                    check=True, capture_output=True,
                )
                times.append(time.perf_counter() - start)
        print(f"  CLI flexwing dynamic --json     {1e3 * median(times):9.2f} ms  (process, CSV and JSON output included)")


def stepper(calls: int) -> None:
    beam = flexwing.Beam(length=1.0, elements=20, EI=50.0, mass_per_length=0.2)
    load = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 1.0}
    model = flexwing.FullModel(beam)
    for label, target in [("reduced r = 1", model.reduced(1)), ("full n = 20", model)]:
        s = target.stepper([load], scales=[0.0])
        walls = []
        rust_before = 0.0
        for k in range(calls):
            start = time.perf_counter()
            s.step(1e-4, [np.sin(k * 1e-2)])
            walls.append(time.perf_counter() - start)
            rust_now = s.stats["rust_time_s"]
            walls[-1] = (walls[-1], rust_now - rust_before)
            rust_before = rust_now
        wall = [w for w, _ in walls]
        over = [w - r for w, r in walls]
        print(f"Stepper.step, {label}, {calls} calls of 0.1 ms, medians: call {1e6 * median(wall):.2f} us, "
              f"integrator {1e6 * median([r for _, r in walls]):.2f} us, overhead {1e6 * median(over):.2f} us")
    eom = model.equations([load])
    y = np.zeros(2 * eom.n_dofs)
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        eom.rhs(0.0, y)
        times.append(time.perf_counter() - start)
    print(f"Equations.rhs at n = 20, {calls} calls: median {1e6 * median(times):.2f} us a call (whole call)")


def sweep(n_cases: int, repeats: int, chunk: int) -> None:
    sys.path.insert(0, str(ROOT / "examples" / "python"))
    import sweep_dask
    from dask.distributed import Client, LocalCluster

    forces = np.linspace(10.0, 200.0, n_cases // 4)
    cases = sweep_dask.sweep_cases(forces, [40.0, 50.0, 60.0, 80.0])
    flexwing.solve_many(cases[:50], "static")  # warm-up
    serial = []
    for _ in range(repeats):
        start = time.perf_counter()
        items = flexwing.solve_many(cases, "static")
        serial.append(time.perf_counter() - start)
    per_case = median(serial) / len(cases)
    rust = sum(i.wall_time_s for i in items) / len(cases)
    print(f"sweep of {len(cases)} static cases (n = 20, full model), medians of {repeats}:")
    print(f"  serial solve_many                  {median(serial):8.3f} s  ({1e6 * per_case:.1f} us a case, "
          f"{1e6 * rust:.1f} us in Rust)")
    rows = {}
    for workers in (1, 2):
        start = time.perf_counter()
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        setup = time.perf_counter() - start
        sweep_dask.run_sweep(client, cases[:200], chunk=chunk)  # warm-up: import flexwing on the workers
        for keep, what in [(None, "whole results"), (sweep_dask.tip, "tips only")]:
            times = []
            for _ in range(repeats):
                start = time.perf_counter()
                out = sweep_dask.run_sweep(client, cases, chunk=chunk, keep=keep)
                times.append(time.perf_counter() - start)
            if keep is None:
                assert [sweep_dask.tip(i) for i in out] == [sweep_dask.tip(i) for i in items]
            else:
                assert out == [sweep_dask.tip(i) for i in items]
            rows[f"{workers} {what}"] = median(times)
            print(f"  Dask, {workers} worker(s), {what:13s} {median(times):8.3f} s  "
                  f"({1e6 * median(times) / len(cases):.1f} us a case; cluster start-up {setup:.2f} s)")
        client.close()
        cluster.close()
    print(json.dumps({"cases": len(cases), "serial_s": median(serial), "dask_s": rows}))


def sweep_dynamic(n_cases: int, repeats: int) -> None:
    """Heavier cases: case (b) (full model only, 1 s) with the force amplitude swept, one case a
    task: here the per-task overhead is negligible and the workers' cores are the limit."""
    sys.path.insert(0, str(ROOT / "examples" / "python"))
    import sweep_dask
    from dask.distributed import Client, LocalCluster

    base = flexwing.Case.load(ROOT / "examples" / "paper_sine.toml").replace({"dynamic.reduced": []})
    cases = [base.replace({"loads[0].fy": float(f)}) for f in np.linspace(5.0, 15.0, n_cases)]
    serial = []
    for _ in range(repeats):
        start = time.perf_counter()
        items = flexwing.solve_many(cases, "dynamic")
        serial.append(time.perf_counter() - start)
    print(f"sweep of {n_cases} dynamic cases (case (b), full model), medians of {repeats}:")
    print(f"  serial solve_many                  {median(serial):8.3f} s  ({1e3 * median(serial) / n_cases:.1f} ms a case)")
    last = lambda i: (i.index, i.status, float(i.result.runs[0].tip_y[-1]))  # noqa: E731
    for workers in (1, 2):
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        sweep_dask.run_sweep(client, cases[:2], chunk=1, analysis="dynamic")  # warm-up
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            out = sweep_dask.run_sweep(client, cases, chunk=1, analysis="dynamic", keep=last)
            times.append(time.perf_counter() - start)
        assert out == [last(i) for i in items]
        client.close()
        cluster.close()
        print(f"  Dask, {workers} worker(s), one case a task {median(times):8.3f} s  "
              f"(speed-up {median(serial) / median(times):.2f})")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("parts", nargs="*", default=["case-b", "stepper", "sweep", "sweep-dynamic"])
    p.add_argument("--repeats", type=int, default=11)
    p.add_argument("--calls", type=int, default=2000)
    p.add_argument("--cases", type=int, default=2000)
    p.add_argument("--chunk", type=int, default=100)
    a = p.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} (shared: medians)")
    if "case-b" in a.parts:
        case_b(a.repeats)
    if "stepper" in a.parts:
        stepper(a.calls)
    if "sweep" in a.parts:
        sweep(a.cases, max(3, a.repeats // 3), a.chunk)
    if "sweep-dynamic" in a.parts:
        sweep_dynamic(16, 3)


if __name__ == "__main__":
    main()
