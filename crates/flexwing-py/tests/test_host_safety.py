"""The package never crashes its host (issue 23): one test per finding of the issue, each of
which failed before its fix. Every risky call runs in a child process, so that a crash — a
segfault, an abort, a panic escaping as `PanicException` (which `except Exception` does not
catch) — fails the test instead of ending the run; the child prints OK when every assertion in
it held. The classes of defect are named in the test names: panics and unchecked counts,
unbounded recursion in conversions, batches that lose cases, signals, exceptions outside the
documented tree, silently wrong results, pickling.

The signal tests send SIGINT to the child while it runs a long call and assert that the call
stops at its next check (a bound of 2–3 s where the uninterrupted call takes 1–7 s on this
machine) with a KeyboardInterrupt carrying the partial result."""

from __future__ import annotations

import os
import pathlib
import re
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from conftest import EXAMPLES, ROOT

PREAMBLE = textwrap.dedent(
    f"""
    import copy, math, os, pickle, signal, sys, threading, time
    import numpy as np
    import flexwing
    EXAMPLES = {str(EXAMPLES)!r}
    LOAD = {{"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}}
    BEAM = flexwing.Beam(length=1.0, elements=4, EI=50.0, mass_per_length=0.2)
    FULL = flexwing.FullModel(BEAM)
    def raises(cls, f, field=None):
        try:
            f()
        except cls as e:
            if field is not None:
                assert getattr(e, "field", None) == field, (field, e)
            return e
        except BaseException as e:
            raise AssertionError(f"expected {{cls.__name__}}, got {{type(e).__name__}}: {{e}}")
        raise AssertionError(f"expected {{cls.__name__}}, nothing raised")
    """
)


def child(code: str, timeout: float = 120, signal_after: float | None = None) -> str:
    """Run `code` (after PREAMBLE) in a fresh interpreter; with `signal_after`, send it SIGINT
    that many seconds after it prints READY. Returns its stdout; fails unless it exited 0 and
    printed OK."""
    script = PREAMBLE + textwrap.dedent(code) + "\nprint('OK', flush=True)\n"
    p = subprocess.Popen(
        [sys.executable, "-c", script],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    if signal_after is not None:
        line = p.stdout.readline()
        assert line.strip() == "READY", line + p.stderr.read()
        time.sleep(signal_after)
        p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=timeout)
    assert "PanicException" not in err, err[-3000:]
    assert p.returncode == 0, f"exit status {p.returncode}\n{out}\n{err[-3000:]}"
    assert "OK" in out.split(), out + err[-2000:]
    return out


# --- Panics and unchecked counts -------------------------------------------------------------


def test_huge_mode_counts_are_refused_before_anything_is_allocated():
    # 2**62: capacity overflow (PanicException); 2**33: a 64 GB allocation (abort); 10**8: 790 MB
    # before the error — here the child may map at most 1 GiB in all.
    child(
        """
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))
        for r in (2**62, 2**33, 10**8, 2**64, -1):
            raises(flexwing.InputError, lambda: FULL.reduced(r), "modes")
        raises(flexwing.InputError, lambda: FULL.reduced([1, 10**8]), "modes[1]")
        raises(flexwing.InputError, lambda: flexwing.solve_many([], threads=2**40), "threads")
        """
    )


def test_ctrl_c_in_the_first_call_of_a_fresh_process_is_a_keyboard_interrupt():
    # NumPy's C API was loaded by the first array made, after the run: a pending Ctrl-C made
    # that import fail as a panic ("Failed to access NumPy array API capsule").
    out = child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "long_chain.toml"))
        print("READY", flush=True)
        start = time.perf_counter()
        e = raises(KeyboardInterrupt, case.dynamics)
        print("after", time.perf_counter() - start)
        """,
        signal_after=0.3,
    )
    assert float(re.search(r"after (\S+)", out).group(1)) < 3.0, out


def test_every_entry_point_of_the_extension_catches_panics():
    """The last line of defence, checked on the source: every method and function the extension
    exports that can fail (returns `PyResult`) runs its body under `errors::guard` or
    `errors::detached`, which turn a panic into `InternalError`; the others are short getters
    (a field read, a copy into a new array)."""
    src = ROOT / "crates" / "flexwing-py" / "src"
    unguarded, long_getters = [], []
    for path in sorted(src.rglob("*.rs")):
        for name, returns, body in exported_functions(path.read_text()):
            if "PyResult" in returns or "Reduce" in returns:
                if "errors::guard(" not in body and "errors::detached(" not in body:
                    unguarded.append(f"{path.name}:{name}")
            elif body.count("\n") > 10:
                long_getters.append(f"{path.name}:{name}")
    assert not unguarded, unguarded
    assert not long_getters, long_getters


def exported_functions(text: str):
    """(name, return type, body) of every `fn` in the `#[pymethods]` blocks of `text` and of
    every `#[pyfunction]`."""

    def closing(s, i, open_, close):
        depth = 1
        while depth:
            depth += (s[i] == open_) - (s[i] == close)
            i += 1
        return i

    def fns(block, first_only=False):
        out = []
        for m in re.finditer(r"\bfn\s+(\w+)\s*(<[^>]*>)?\s*\(", block):
            k = closing(block, m.end(), "(", ")")
            brace = block.index("{", k)
            end = closing(block, brace + 1, "{", "}")
            out.append((m.group(1), block[k:brace], block[brace:end]))
            if first_only:
                break
        return out

    found = []
    for m in re.finditer(r"#\[pymethods\]\s*impl\s+\w+\s*\{", text):
        found += fns(text[m.end() : closing(text, m.end(), "{", "}") - 1])
    for m in re.finditer(r"#\[pyfunction\]", text):
        found += fns(text[m.end() :], first_only=True)
    return found


# --- Unbounded recursion in conversions ------------------------------------------------------


def test_values_that_contain_themselves_or_nest_deep_are_errors_naming_the_path():
    child(
        """
        b = {"length": 1.0, "elements": 2}
        b["section"] = b
        e = raises(flexwing.CaseFileError, lambda: flexwing.Case({"beam": b}))
        assert e.key.startswith("beam.section.section") and "nested more than" in e.reason, e
        raises(flexwing.InputError, lambda: flexwing.Beam.from_dict(b))
        deep = []
        for _ in range(10_000):
            deep = [deep]
        beam = BEAM.to_dict()
        e = raises(flexwing.CaseFileError, lambda: flexwing.Case({"beam": beam, "loads": deep}))
        assert e.key.startswith("loads[0][0]"), e
        raises(flexwing.InputError, lambda: FULL.equations(deep), None)
        loads = [dict(LOAD)]
        loads.append(loads)
        raises(flexwing.InputError, lambda: FULL.stepper(loads))
        case = flexwing.Case({"beam": beam, "loads": [LOAD]})
        cyclic = {"x": 1.0}
        cyclic["t"] = cyclic
        raises(flexwing.CaseFileError, lambda: case.replace({"loads[0].time": cyclic}))
        damping = {"type": "rayleigh"}
        damping["alpha"] = [damping]
        raises(flexwing.InputError, lambda: FULL.equations(damping=damping))
        """
    )


# --- Batches ---------------------------------------------------------------------------------


def test_a_malformed_case_is_an_error_item_and_the_good_cases_are_kept():
    child(
        """
        good = flexwing.Case.load(os.path.join(EXAMPLES, "paper_static.toml"))
        bad = {"length": 1.0, "elements": 2}
        bad["section"] = bad
        for threads in (1, 2):
            items = flexwing.solve_many([good, {"beam": bad}, good, {"beam": 1}, 7], threads=threads)
            assert [i.status for i in items] == ["complete", "error", "complete", "error", "error"]
            assert [i.index for i in items] == [0, 1, 2, 3, 4]
            assert isinstance(items[1].error, flexwing.CaseFileError)
            assert isinstance(items[4].error, flexwing.ArgumentTypeError)
        """
    )


def test_a_raising_callback_stops_the_batch_with_the_items_so_far():
    child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "paper_static.toml"))
        class Stop(Exception):
            pass
        def cb(done, total):
            if done == 2:
                raise Stop("enough")
        e = raises(Stop, lambda: flexwing.solve_many([case] * 6, progress=cb))
        assert [i.index for i in e.result] == [0, 1], e.result
        assert all(i.status == "complete" for i in e.result)
        # With threads, the cases running when the callback raised end too (complete or
        # interrupted) and none starts after.
        e = raises(Stop, lambda: flexwing.solve_many([case] * 40, threads=2, progress=cb))
        assert 2 <= len(e.result) < 40, len(e.result)
        """
    )


def test_batch_progress_counts_in_order_on_the_calling_thread_with_a_deep_python_stack():
    # The callbacks ran on the workers' 2 MiB Rust threads, where ordinary deep Python code
    # overflowed the stack; `done` could reach the callback out of order.
    child(
        """
        sys.setrecursionlimit(100_000)
        case = flexwing.Case.load(os.path.join(EXAMPLES, "paper_static.toml"))
        def deep(n):
            return 0 if n == 0 else 1 + deep(n - 1)
        seen, threads = [], set()
        def cb(done, total):
            seen.append((done, total, deep(20_000)))
            threads.add(threading.get_ident())
        cases = [case.replace({"loads[1].fy": -f}) for f in range(10, 170, 10)]
        items = flexwing.solve_many(cases, threads=2, progress=cb)
        assert [s[0] for s in seen] == list(range(1, 17)), seen
        assert threads == {threading.get_ident()}
        assert all(i.complete for i in items)
        """
    )


def test_batch_items_are_numbered_from_start_and_solve_takes_an_index():
    child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "paper_static.toml"))
        assert [i.index for i in flexwing.solve_many([case, case], start=10)] == [10, 11]
        assert flexwing.solve(case).index is None
        assert flexwing.solve(case, "static", 7).index == 7
        """
    )


def test_a_progress_callback_that_reenters_is_bounded():
    child(
        """
        sys.setrecursionlimit(10**6)
        case = flexwing.Case.load(os.path.join(EXAMPLES, "table4.toml"))
        calls = [0]
        def cb(done, label):
            calls[0] += 1
            case.modes(progress=cb)
        e = raises(flexwing.ReentrancyError, lambda: case.modes(progress=cb), "progress")
        assert calls[0] == 16, calls
        """
    )


# --- Signals ---------------------------------------------------------------------------------


def test_ctrl_c_stops_an_analysis_with_its_partial_result():
    out = child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "long_chain.toml"))
        case.modes()
        print("READY", flush=True)
        start = time.perf_counter()
        e = raises(KeyboardInterrupt, case.dynamics)
        print("after", time.perf_counter() - start)
        run = e.result.full
        assert e.result.status == "interrupted" and run.status == "interrupted", e.result
        assert 0 < len(run.t) and run.t[-1] < case.to_dict()["dynamic"]["end_time"]
        assert run.stop["reason"] == "interrupted" and run.stop["time"] >= run.t[-1], run.stop
        """,
        signal_after=0.5,
    )
    assert float(re.search(r"after (\S+)", out).group(1)) < 2.0, out


def test_ctrl_c_stops_a_stepper_step_and_leaves_its_state():
    out = child(
        """
        beam = flexwing.Beam(length=1.0, elements=400, EI=50.0, mass_per_length=0.2)
        s = flexwing.FullModel(beam).stepper([LOAD], scales=[0.0])
        y0 = s.y
        print("READY", flush=True)
        start = time.perf_counter()
        raises(KeyboardInterrupt, lambda: s.step(30.0, [1.0]))
        print("after", time.perf_counter() - start)
        assert s.t == 0.0 and np.array_equal(s.y, y0) and list(s.scales) == [0.0]
        assert s.stats["calls"] == 1 and s.stats["steps"] > 0
        """,
        signal_after=0.3,
    )
    assert float(re.search(r"after (\S+)", out).group(1)) < 2.0, out


def test_ctrl_c_stops_a_batch_with_the_items_so_far():
    out = child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "long_chain.toml"))
        print("READY", flush=True)
        start = time.perf_counter()
        e = raises(KeyboardInterrupt, lambda: flexwing.solve_many([case] * 4, "dynamic", threads=2))
        print("after", time.perf_counter() - start)
        assert [i.status for i in e.result] == ["interrupted", "interrupted"], e.result
        assert all(len(i.result.full.t) > 0 for i in e.result)
        """,
        signal_after=0.5,
    )
    assert float(re.search(r"after (\S+)", out).group(1)) < 3.0, out


# --- Exceptions outside the documented tree --------------------------------------------------


def test_every_exception_is_documented_and_names_its_argument():
    child(
        """
        e = raises(flexwing.ArgumentTypeError, lambda: FULL.equations(damping={1: 2}), "damping")
        case = flexwing.Case.load(os.path.join(EXAMPLES, "long_chain.toml"))
        start = time.perf_counter()
        raises(flexwing.ArgumentTypeError, lambda: case.dynamics(progress=1), "progress")
        raises(flexwing.ArgumentTypeError, lambda: flexwing.solve_many([case], progress=1), "progress")
        assert time.perf_counter() - start < 0.5  # refused before the 7 s run
        small = flexwing.Case.load(os.path.join(EXAMPLES, "table4.toml"))
        assert small.run("modes", check=False).omega.size > 0
        assert small.modes(check=True).omega.size > 0
        """
    )


def test_the_callers_own_exceptions_propagate_as_themselves():
    child(
        """
        class Raises:
            def __init__(self, cls):
                self.cls = cls
            def __float__(self):
                raise self.cls("from __float__")
            def __index__(self):
                raise self.cls("from __index__")
            def __array__(self, *args, **kwargs):
                raise self.cls("from __array__")
        eom = FULL.equations()
        for cls in (KeyboardInterrupt, MemoryError, RecursionError):
            raises(cls, lambda: eom.rhs(Raises(cls), np.zeros(8)))
            raises(cls, lambda: eom.rhs(0.0, Raises(cls)))
            raises(cls, lambda: FULL.modes(Raises(cls)))
            raises(cls, lambda: FULL.mass_matrix(Raises(cls)))
            raises(cls, lambda: flexwing.Beam(length=Raises(cls), elements=4, EI=50.0, mass_per_length=0.2))
            raises(cls, lambda: FULL.equations(damping={"type": "rayleigh", "alpha": Raises(cls)}))
        # A TypeError or ValueError of the conversion is the argument's error.
        class Bad:
            def __float__(self):
                raise ValueError("no")
        raises(flexwing.ArgumentTypeError, lambda: eom.rhs(Bad(), np.zeros(8)), "t")
        """
    )


def test_the_stepper_can_be_read_from_another_thread_during_a_step():
    child(
        """
        beam = flexwing.Beam(length=1.0, elements=200, EI=50.0, mass_per_length=0.2)
        s = flexwing.FullModel(beam).stepper([LOAD], scales=[0.0])
        errors, seen = [], set()
        th = threading.Thread(target=lambda: s.step(4.0, [1.0]))
        th.start()
        while th.is_alive():
            try:
                seen.add(s.t)
                s.y, s.x, s.q, s.scales, s.stats, s.tip, s.shape()
            except Exception as e:
                errors.append(e)
        th.join()
        assert not errors, errors[:3]
        assert seen <= {0.0, 4.0} and s.t == 4.0 and list(s.scales) == [1.0]
        """
    )


# --- Silently wrong --------------------------------------------------------------------------


def test_a_failed_step_restores_the_load_factors_too():
    child(
        """
        s = FULL.stepper([LOAD], max_steps=3)
        raises(flexwing.SolverError, lambda: s.step(0.5, [5.0]))
        assert s.t == 0.0 and list(s.scales) == [1.0], (s.t, s.scales)
        # A retry ramps 1 -> 5 as the first try: the same failure at the same time.
        ref = FULL.stepper([LOAD], max_steps=3)
        a = raises(flexwing.SolverError, lambda: s.step(0.5, [5.0]))
        b = raises(flexwing.SolverError, lambda: ref.step(0.5, [5.0]))
        assert a.stop == b.stop, (a.stop, b.stop)
        """
    )


def test_a_step_below_the_times_resolution_is_an_error():
    child(
        """
        s = FULL.stepper(t0=1e20)
        raises(flexwing.InputError, lambda: s.step(1e-3), "dt")
        assert s.t == 1e20
        s = FULL.stepper(t0=1e9)  # time resolution 1.2e-7 s there
        raises(flexwing.InputError, lambda: s.step(1e-10), "dt")
        assert s.t == 1e9
        s = FULL.stepper(t0=1e3)
        assert s.step(1e-3) == 1e3 + 1e-3
        """
    )


def test_masked_arrays_are_refused():
    child(
        """
        q = np.ma.masked_array(np.ones(4), mask=[1, 0, 0, 0])
        raises(flexwing.ArgumentTypeError, lambda: FULL.shape(q), "q")
        raises(flexwing.ArgumentTypeError, lambda: FULL.equations().rhs(0.0, np.ma.masked_array(np.zeros(8))), "y")
        beam = BEAM.to_dict()
        raises(flexwing.CaseFileError, lambda: flexwing.Case(beam=beam, loads=[dict(LOAD, fy=np.ma.array(1.0))]))
        """
    )


def test_a_case_holding_nan_is_refused_at_construction():
    child(
        """
        beam = BEAM.to_dict()
        beam["section"]["EI"] = math.nan
        e = raises(flexwing.CaseFileError, lambda: flexwing.Case(beam=beam))
        assert e.key == "beam.section.EI" and "finite" in e.reason, e
        text = flexwing.Case(beam=BEAM.to_dict(), loads=[LOAD]).to_toml().replace("fy = 10.0", "fy = inf")
        e = raises(flexwing.CaseFileError, lambda: flexwing.Case.from_toml(text, file="x.toml"))
        assert e.key == "loads[0].fy" and e.file == "x.toml", e
        case = flexwing.Case(beam=BEAM.to_dict(), loads=[LOAD])
        raises(flexwing.CaseFileError, lambda: case.replace({"loads[0].fy": float("-inf")}))
        """
    )


def test_non_finite_model_level_outputs_are_errors():
    child(
        """
        eom = FULL.equations([LOAD])
        for f in (eom.rhs, eom.jacobian):
            raises(flexwing.InputError, lambda: f(0.0, np.full(8, 1e160)), "y")
        raises(flexwing.InputError, lambda: eom.energies(np.full(8, 1e160)), "y")
        raises(flexwing.InputError, lambda: eom.velocities(np.full(8, 1e308)), "y")
        raises(flexwing.InputError, lambda: eom.state(np.zeros(4), np.full(4, 1e308)), "xdot")
        """
    )


# --- Pickling --------------------------------------------------------------------------------


def test_model_level_objects_built_by_a_case_round_trip():
    child(
        """
        case = flexwing.Case.load(os.path.join(EXAMPLES, "paper_sine.toml"))
        full = case.model()
        for obj in (full, full.reduced(2), full.beam):
            for again in (pickle.loads(pickle.dumps(obj)), copy.deepcopy(obj)):
                assert type(again) is type(obj)
        again = pickle.loads(pickle.dumps(full.reduced(2)))
        assert np.array_equal(again.basis, full.reduced(2).basis)
        assert np.array_equal(pickle.loads(pickle.dumps(full)).stiffness_matrix(), full.stiffness_matrix())
        assert full.beam.to_dict() == case.to_dict()["beam"]
        """
    )
