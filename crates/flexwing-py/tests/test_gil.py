"""Long computations release the interpreter: while two threads each run a dynamic analysis,
a third thread keeps executing Python bytecode, and the two analyses run at the same time.

Concurrency is asserted by the overlap of intervals and by bytecode running inside them, not by
timing ratios (the machine is shared: a speed-up may not show). Had a call kept the interpreter
locked, no bytecode of another thread could run between its start and its end (a native call
cannot be preempted by the interpreter's switch interval), so the ticks counted inside each call
would be zero."""

from __future__ import annotations

import threading
import time

import flexwing


def test_two_solves_run_concurrently_and_python_runs_meanwhile(sine_case):
    # The paper's case (b) with its five models: long enough (tens of ms) to see ticks inside.
    intervals = {}
    results = {}
    barrier = threading.Barrier(3)

    def solve(name):
        barrier.wait()
        start = time.perf_counter()
        results[name] = sine_case.dynamics()
        intervals[name] = (start, time.perf_counter())

    threads = [threading.Thread(target=solve, args=(n,)) for n in ("a", "b")]
    for t in threads:
        t.start()
    ticks = []
    barrier.wait()
    while any(t.is_alive() for t in threads):
        ticks.append(time.perf_counter())
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = intervals["a"], intervals["b"]
    assert max(a0, b0) < min(a1, b1), f"the solves did not overlap: {intervals}"
    for name, (s, e) in intervals.items():
        inside = sum(s < t < e for t in ticks)
        assert inside >= 10, f"{name}: only {inside} ticks of the main thread inside the call"
    # Same numbers from both threads (no shared state).
    assert (results["a"].run("full").tip_y == results["b"].run("full").tip_y).all()


def test_solve_many_threads_give_the_serial_results(static_case):
    cases = [static_case.replace({"loads[1].fy": -f}) for f in (50.0, 100.0, 150.0, 200.0)]
    serial = flexwing.solve_many(cases, "static")
    threaded = flexwing.solve_many(cases, "static", threads=2)
    for s, t in zip(serial, threaded):
        assert s.status == t.status == "complete"
        assert (s.result.full.tip_y == t.result.full.tip_y).all()


def test_the_stepper_releases_the_interpreter():
    # One call long enough (≈0.1 s at n = 200 over 4 s of motion) that the main thread, woken when
    # the call releases the interpreter, is surely scheduled inside it; a 1 ms call (n = 40 over
    # 0.05 s) could end before the OS ran the main thread at all, so it saw 0 ticks on a busy CI.
    beam = flexwing.Beam(length=1.0, elements=200, EI=50.0, mass_per_length=0.2)
    stepper = flexwing.FullModel(beam).stepper(
        [{"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}], scales=[0.0]
    )
    ticks = []
    done = threading.Event()
    span = []

    def run():
        start = time.perf_counter()
        stepper.step(4.0, [1.0])
        span.append((start, time.perf_counter()))
        done.set()

    t = threading.Thread(target=run)
    t.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
    t.join()
    s, e = span[0]
    inside = sum(s < x < e for x in ticks)
    assert inside >= 10, f"only {inside} ticks of the main thread inside a {e - s:.3f} s call"
