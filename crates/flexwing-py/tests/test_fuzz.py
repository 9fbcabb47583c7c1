"""A fuzz test of the package as a hostile user would drive it (issue 23): hypothesis generates
case dicts (random beams, loads and analyses, then hostile mutations of any key: NaN, inf, huge
and negative numbers, wrong types, NumPy scalars and arrays, masked arrays, unknown keys, values
that contain themselves, lists nested thousands deep), model-level calls over NumPy arrays of
every dtype, shape and layout, and stepper runs with hostile arguments.

Every example runs in a worker process (`WORKER`, fed over a pipe), so that a crash of the
interpreter fails the example instead of the run: the worker is started again and hypothesis
shrinks the input that killed it. For each example the worker checks, and the test asserts:

* no signal (the worker is alive and answers) and no `PanicException`;
* only documented exceptions: a `FlexwingError` other than `InternalError` (a caught panic is
  a bug too);
* no non-finite number in a complete result (every float of `to_dict()`), and no non-finite
  output of a model-level call that returned;
* pickling round-trips: cases, results, model-level objects; a stepper whose step failed is
  left as it was.

Bounded: a fixed seed (`derandomize`), no example database, `MAX_EXAMPLES` examples per
strategy, dynamic runs of at most 0.05 s of simulated time, a 2 s budget per analysis (a
progress callback that raises: itself a check of the stopping path). About 10–20 s in all on
the 2-core CI machine."""

from __future__ import annotations

import math
import os
import pickle
import select
import struct
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import flexwing

from conftest import example

MAX_EXAMPLES = {"cases": 300, "arrays": 300, "stepper": 150}
SETTINGS = dict(
    derandomize=True,  # the fixed seed: the same examples on every run
    database=None,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
#: How long the parent waits for one example (a dynamic run is cut at 2 s by its budget).
EXAMPLE_TIMEOUT = 60.0

WORKER = textwrap.dedent(
    r'''
    import math, pickle, struct, sys, time
    import numpy as np
    import flexwing

    DOCUMENTED = (flexwing.FlexwingError,)

    class Budget(Exception):
        """Raised by the progress callback past the time budget of one analysis."""

    def budget(seconds):
        end = time.perf_counter() + seconds
        def cb(*args):
            if time.perf_counter() > end:
                raise Budget()
        return cb

    def materialize(v, parent=None):
        """Hostile values the pipe cannot carry: "__SELF__" is the enclosing dict or list,
        "__DEEP__" a list nested 5000 deep."""
        if isinstance(v, str) and v == "__SELF__":
            return parent if parent is not None else v
        if isinstance(v, str) and v == "__DEEP__":
            deep = []
            for _ in range(5000):
                deep = [deep]
            return deep
        if isinstance(v, dict):
            out = {}
            for k, x in v.items():
                out[k] = materialize(x, out)
            return out
        if isinstance(v, list):
            out = []
            for x in v:
                out.append(materialize(x, out))
            return out
        return v

    def non_finite(v, path="", depth=0):
        """The path of the first non-finite float in v (a result's to_dict()), or None."""
        if depth > 40:
            return None
        if isinstance(v, float):
            return None if math.isfinite(v) else path
        if isinstance(v, np.ndarray):
            if v.dtype.kind == "f" and not np.isfinite(v).all():
                return path
            return None
        if isinstance(v, dict):
            for k, x in v.items():
                p = non_finite(x, f"{path}.{k}", depth + 1)
                if p:
                    return p
        if isinstance(v, (list, tuple)):
            for i, x in enumerate(v):
                p = non_finite(x, f"{path}[{i}]", depth + 1)
                if p:
                    return p
        return None

    def same(a, b, depth=0):
        if depth > 40:
            return True
        if isinstance(a, np.ndarray):
            return isinstance(b, np.ndarray) and a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")
        if isinstance(a, dict):
            return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k], depth + 1) for k in a)
        if isinstance(a, list):
            return isinstance(b, list) and len(a) == len(b) and all(same(x, y, depth + 1) for x, y in zip(a, b))
        if isinstance(a, float) and isinstance(b, float) and math.isnan(a):
            return math.isnan(b)
        if isinstance(a, BaseException):
            return type(a) is type(b) and str(a) == str(b)
        return a == b

    def check_exception(e, problems, what):
        if type(e).__name__ == "PanicException":
            problems.append(f"{what}: PanicException: {e}")
        elif isinstance(e, flexwing.InternalError):
            problems.append(f"{what}: InternalError (a caught panic): {e}")
        elif isinstance(e, Budget):
            pass
        elif not isinstance(e, DOCUMENTED):
            problems.append(f"{what}: undocumented {type(e).__module__}.{type(e).__name__}: {e}")
        else:
            part = getattr(e, "result", None)
            if part is not None:
                check_result(part, problems, what + " (partial result)", complete_only=True)
            try:
                again = pickle.loads(pickle.dumps(e))
                if type(again) is not type(e) or str(again) != str(e):
                    problems.append(f"{what}: the exception does not round-trip")
            except Exception as p:
                problems.append(f"{what}: the exception does not pickle: {p!r}")

    def check_result(result, problems, what, complete_only=False):
        d = result.to_dict()
        if getattr(result, "status", "complete") == "complete":
            p = non_finite(d)
            if p:
                problems.append(f"{what}: a non-finite number at {p} in a complete result")
        try:
            again = pickle.loads(pickle.dumps(result))
            if not same(again.to_dict(), d):
                problems.append(f"{what}: the result does not round-trip through pickle")
        except Exception as p:
            problems.append(f"{what}: the result does not pickle: {p!r}")

    def case_example(payload, problems):
        data = materialize(payload["case"])
        analysis = payload["analysis"]
        try:
            case = flexwing.Case(data)
        except BaseException as e:
            check_exception(e, problems, "Case(...)")
            items = flexwing.solve_many([data], analysis)
            if items[0].status != "error":
                problems.append("solve_many took a case that Case refused")
            return "refused"
        again = pickle.loads(pickle.dumps(case))
        if again != case:
            problems.append("the case does not round-trip through pickle")
        try:
            model = case.model()
            for obj in (model, model.beam):
                pickle.loads(pickle.dumps(obj))
        except BaseException as e:
            check_exception(e, problems, "case.model()")
        try:
            result = case.run(analysis, check=False, progress=budget(2.0))
            check_result(result, problems, f"case.run({analysis!r})")
            outcome = result.status
        except BaseException as e:
            check_exception(e, problems, f"case.run({analysis!r})")
            outcome = type(e).__name__
        return outcome

    FULL = None

    def model_of(spec):
        beam = flexwing.Beam(**spec)
        full = flexwing.FullModel(beam)
        return full, full.reduced(min(2, full.n_dofs))

    def finite_output(out, problems, what):
        arrays = out.values() if isinstance(out, dict) else (out if isinstance(out, tuple) else [out])
        for a in arrays:
            a = np.asarray(a, dtype=float)
            if not np.isfinite(a).all():
                problems.append(f"{what} returned a non-finite value")

    def array_example(payload, problems):
        full, reduced = model_of(payload["beam"])
        model = full if payload["which"] == "full" else reduced
        x = materialize(payload["x"])
        method = payload["method"]
        eom = model.equations([{"type": "point-force", "span": payload["beam"]["length"], "direction": "dead", "fy": 1.0}])
        calls = {
            "mass_matrix": lambda: model.mass_matrix(x),
            "shape": lambda: model.shape(x),
            "rhs": lambda: eom.rhs(payload["t"], x),
            "jacobian": lambda: eom.jacobian(payload["t"], x),
            "energies": lambda: eom.energies(x),
            "velocities": lambda: eom.velocities(x),
            "state": lambda: eom.state(x, x),
            "scales": lambda: setattr(eom, "scales", x),
            "full_coordinates": lambda: eom.full_coordinates(x),
            "reduce_coordinates": lambda: reduced.reduce_coordinates(x),
            "reduced": lambda: full.reduced(x),
            "modes": lambda: full.modes(x),
        }
        try:
            out = calls[method]()
            if out is not None and method not in ("reduced", "modes"):
                finite_output(out, problems, method)
            for obj in (full, reduced, full.beam):
                pickle.loads(pickle.dumps(obj))
            return "returned"
        except BaseException as e:
            check_exception(e, problems, method)
            return type(e).__name__

    def stepper_example(payload, problems):
        full, reduced = model_of(payload["beam"])
        model = full if payload["which"] == "full" else reduced
        kwargs = materialize(payload["kwargs"])
        kwargs["max_steps"] = 3000  # bounds every step's cost (a hostile dt otherwise runs long)
        loads = [{"type": "point-force", "span": payload["beam"]["length"], "direction": "dead", "fy": 1.0}]
        try:
            s = model.stepper(loads, **kwargs)
        except BaseException as e:
            check_exception(e, problems, "stepper(...)")
            return "refused"
        outcomes = []
        for dt, scales in payload["steps"]:
            dt, scales = materialize(dt), materialize(scales)
            before = (s.t, s.y.copy(), s.scales.copy())
            try:
                t = s.step(dt) if scales is None else s.step(dt, scales)
                if not (math.isfinite(t) and np.isfinite(s.y).all()):
                    problems.append("a step returned a non-finite state")
                outcomes.append("ok")
            except BaseException as e:
                check_exception(e, problems, "step")
                after = (s.t, s.y, s.scales)
                if not (before[0] == after[0] and np.array_equal(before[1], after[1]) and np.array_equal(before[2], after[2])):
                    problems.append(f"a failed step ({type(e).__name__}) changed the stepper")
                outcomes.append(type(e).__name__)
        try:
            finite_output(s.shape(), problems, "stepper.shape()")
            s.energies(), s.tip, s.stats
        except BaseException as e:
            check_exception(e, problems, "stepper state")
        return ",".join(outcomes)

    def abort(payload, problems):
        """Kill the worker as a crash would (the test that a crash is seen)."""
        import os
        os.abort()

    HANDLERS = {"case": case_example, "array": array_example, "stepper": stepper_example, "abort": abort}

    def read():
        head = sys.stdin.buffer.read(8)
        if len(head) < 8:
            return None
        (n,) = struct.unpack("<Q", head)
        return pickle.loads(sys.stdin.buffer.read(n))

    def write(obj):
        data = pickle.dumps(obj)
        sys.stdout.buffer.write(struct.pack("<Q", len(data)) + data)
        sys.stdout.buffer.flush()

    while True:
        message = read()
        if message is None:
            break
        kind, payload = message
        problems = []
        try:
            outcome = HANDLERS[kind](payload, problems)
        except BaseException as e:
            problems.append(f"the worker's own call failed: {type(e).__name__}: {e}")
            outcome = "crash"
        write((outcome, problems))
    '''
)


class Worker:
    """A worker process running examples; started again after it dies."""

    def __init__(self):
        self.p = None

    def start(self):
        self.p = subprocess.Popen(
            [sys.executable, "-c", WORKER],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )

    def run(self, kind, payload):
        if self.p is None or self.p.poll() is not None:
            self.start()
        data = pickle.dumps((kind, payload))
        try:
            self.p.stdin.write(struct.pack("<Q", len(data)) + data)
            self.p.stdin.flush()
            head = self._read(8)
            (n,) = struct.unpack("<Q", head)
            return pickle.loads(self._read(n))
        except (BrokenPipeError, EOFError, TimeoutError) as e:
            self.p.kill()
            _, err = self.p.communicate()
            status = self.p.returncode
            self.p = None
            raise AssertionError(
                f"the worker died ({type(e).__name__}, exit status {status}) on {kind}: "
                f"{payload!r}\n{err.decode(errors='replace')[-3000:]}"
            ) from None

    def _read(self, n):
        out = b""
        fd = self.p.stdout.fileno()
        while len(out) < n:
            ready, _, _ = select.select([fd], [], [], EXAMPLE_TIMEOUT)
            if not ready:
                raise TimeoutError
            chunk = os.read(fd, n - len(out))
            if not chunk:
                raise EOFError
            out += chunk
        return out

    def close(self):
        if self.p is not None and self.p.poll() is None:
            self.p.stdin.close()
            self.p.wait(timeout=30)


@pytest.fixture(scope="module")
def worker():
    w = Worker()
    yield w
    w.close()


OUTCOMES = {}


def outcome(kind, result):
    OUTCOMES.setdefault(kind, {}).setdefault(result, 0)
    OUTCOMES[kind][result] += 1


# --- Strategies --------------------------------------------------------------------------------

COMMON_HOSTILE = st.sampled_from(
    [
        None, True, False, "x", "", math.nan, math.inf, -math.inf, -1, 0, 1, -1.0, 0.0, 1e-300,
        1e300, 2**70, -(2**70), 1.5, [], [1.0], [[1.0]], [None], {}, {"x": 1.0}, {"type": "bogus"},
        np.float32(1.5), np.float64(math.nan), np.int64(3), np.bool_(True), np.array([1.0, 2.0]),
        np.array(1.0), np.ma.masked_array([1.0], mask=[True]), np.array(["a"]), 1j, b"bytes",
        (1.0, 2.0),
    ]
)
#: The enclosing dict or list itself, a list nested 5000 deep (built in the worker).
RECURSIVE = st.sampled_from(["__SELF__", "__DEEP__"])
#: One hostile value in five is a recursive one (the values that crashed the interpreter).
HOSTILE = st.one_of(COMMON_HOSTILE, COMMON_HOSTILE, COMMON_HOSTILE, COMMON_HOSTILE, RECURSIVE)


def count_recursive(kind, value):
    """Count the recursive hostile values an example holds (the outcome test checks the fuzz
    met them)."""
    def has(v, s):
        if isinstance(v, str):
            return v == s
        if isinstance(v, dict):
            return any(has(x, s) for x in v.values())
        if isinstance(v, (list, tuple)):
            return any(has(x, s) for x in v)
        return False

    for marker in ("__SELF__", "__DEEP__"):
        if has(value, marker):
            outcome(kind + " recursive", marker)


positive = st.floats(0.01, 100.0)


@st.composite
def properties(draw, length):
    """A section property: a number, or a two-point table over the span."""
    if draw(st.booleans()):
        return draw(positive)
    return {"x": [0.0, length], "value": [draw(positive), draw(positive)]}


@st.composite
def loads(draw, length, torsion):
    kind = draw(st.sampled_from(["point-force", "moment", "distributed", "gravity"] + (["torque"] if torsion else [])))
    load = {"type": kind}
    if kind in ("point-force", "moment", "torque"):
        load["span"] = draw(st.floats(0.0, length))
    if kind in ("point-force", "distributed"):
        load["direction"] = draw(st.sampled_from(["dead", "follower"]))
        keys = ("fx", "fy") if load["direction"] == "dead" else ("tangential", "normal")
        load[draw(st.sampled_from(keys))] = draw(st.floats(-50.0, 50.0))
    if kind in ("moment", "torque"):
        load["value"] = draw(st.floats(-20.0, 20.0))
    if kind == "gravity":
        load["g"] = draw(st.floats(0.0, 20.0))
    if draw(st.booleans()):
        load["time"] = draw(
            st.sampled_from([{"type": "sine", "omega": 20.0}, {"type": "ramp", "end": 0.01}, {"type": "step", "time": 0.005}])
        )
    return load


@st.composite
def generated_case(draw):
    length = draw(st.floats(0.2, 5.0))
    torsion = draw(st.booleans())
    section = {"EI": draw(properties(length)), "mass_per_length": draw(properties(length))}
    if torsion:
        section.update(
            GJ=draw(properties(length)),
            polar_inertia=draw(st.floats(1e-3, 1.0)),
            polar_inertia_about="mass-centre",
            d0=draw(st.floats(-0.05, 0.05)),
        )
    beam = {"length": length, "elements": draw(st.integers(1, 10)), "section": section}
    beam["calibration"] = draw(st.sampled_from(["tip-load", "uniform"]))
    case = {"beam": beam, "loads": draw(st.lists(loads(length, torsion), max_size=3))}
    n_dofs = beam["elements"] * (2 if torsion else 1)
    case["static"] = {"full": True, "reduced": draw(st.lists(st.integers(1, n_dofs), max_size=2))}
    case["dynamic"] = {
        "end_time": draw(st.floats(0.001, 0.05)),
        "integrator": draw(st.sampled_from(["auto", "radau", "bdf", "dopri5", "midpoint", "generalized-alpha"])),
        "reduced": draw(st.lists(st.integers(1, n_dofs), max_size=2)),
        "simplified": draw(st.booleans()),
    }
    case["modes"] = {"count": draw(st.integers(1, n_dofs))}
    return case


def example_dicts():
    """The example case files as dicts (the aeroelastic ones too), their dynamic runs cut to
    0.05 s."""
    out = []
    for name in ["table1.toml", "paper_static.toml", "paper_sine.toml", "tip_follower.toml",
                 "gravity_wing.toml", "section_flutter.toml", "gust_wing.toml"]:
        d = flexwing.Case.load(example(name)).to_dict()
        if "dynamic" in d:
            d["dynamic"]["end_time"] = min(d["dynamic"]["end_time"], 0.05)
            d["dynamic"].pop("output_times", None)
            for load in d.get("loads", []):
                if load.get("time", {}).get("type") == "table":
                    load.pop("time")
        out.append(d)
    return out


EXAMPLE_DICTS = example_dicts()


def paths(value, prefix=()):
    """Every key path into dicts and lists of `value`."""
    out = [prefix]
    if isinstance(value, dict):
        for k, v in value.items():
            out += paths(v, prefix + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            out += paths(v, prefix + (i,))
    return out


@st.composite
def mutated(draw, base):
    """`base` with a few hostile changes: a value replaced, a key added or removed."""
    import copy

    case = copy.deepcopy(base)
    for _ in range(draw(st.integers(0, 3))):
        where = draw(st.sampled_from(paths(case)[1:] or [()]))
        if not where:
            break
        parent = case
        for step in where[:-1]:
            parent = parent[step]
        action = draw(st.sampled_from(["replace", "replace", "replace", "add", "remove"]))
        if action == "replace":
            parent[where[-1]] = draw(HOSTILE)
        elif action == "add" and isinstance(parent, dict):
            parent[draw(st.sampled_from(["bogus", "elements", "stations", "GJ", "time", "damping", "sweep", "initial"]))] = draw(HOSTILE)
        elif isinstance(parent, dict):
            parent.pop(where[-1], None)
    return case


cases = st.one_of(generated_case(), st.sampled_from(EXAMPLE_DICTS)).flatmap(mutated)


@settings(max_examples=MAX_EXAMPLES["cases"], **SETTINGS)
@given(case=cases, analysis=st.sampled_from(["modes", "static", "dynamic", "flutter"]))
def test_fuzz_case_dicts(worker, case, analysis):
    result, problems = worker.run("case", {"case": case, "analysis": analysis})
    outcome("cases", result)
    count_recursive("cases", case)
    assert not problems, problems


beams = st.fixed_dictionaries(
    {"length": st.floats(0.2, 5.0), "elements": st.integers(1, 8), "EI": positive, "mass_per_length": positive}
)

array_values = st.one_of(
    st.floats(-3.0, 3.0),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([1e160, -1e300, 1e-320]),
)


@st.composite
def hostile_arrays(draw, n):
    """An array-like for an argument of `n` values: mostly of the right size, of any dtype and
    layout (strided, Fortran-ordered, 0-d, 2-d), or a hostile value."""
    kind = draw(st.sampled_from(["good", "good", "dtype", "shape", "strided", "fortran", "hostile", "list"]))
    if kind == "hostile":
        return draw(HOSTILE)
    if kind == "list":
        return draw(st.lists(array_values, min_size=n, max_size=n))
    if kind == "shape":
        shape = draw(hnp.array_shapes(min_dims=0, max_dims=3, max_side=n + 2))
        return draw(hnp.arrays(np.float64, shape, elements=array_values))
    dtype = np.float64
    if kind == "dtype":
        dtype = draw(st.sampled_from([np.float32, np.int32, np.int64, np.uint8, np.bool_, np.complex128, np.float16]))
    base = draw(hnp.arrays(np.float64, (2 * n,) if kind == "strided" else (n,), elements=array_values))
    if kind == "strided":
        return base[::2]
    if kind == "fortran":
        return np.asfortranarray(base.reshape(n, 1))[:, 0]
    with np.errstate(all="ignore"):
        return base.astype(dtype)


@st.composite
def array_calls(draw):
    beam = draw(beams)
    which = draw(st.sampled_from(["full", "reduced"]))
    n = beam["elements"] if which == "full" else min(2, beam["elements"])
    method = draw(
        st.sampled_from(
            ["mass_matrix", "shape", "rhs", "jacobian", "energies", "velocities", "state", "scales",
             "full_coordinates", "reduce_coordinates", "reduced", "modes"]
        )
    )
    size = {"rhs": 2 * n, "jacobian": 2 * n, "energies": 2 * n, "velocities": 2 * n, "scales": 1,
            "reduce_coordinates": beam["elements"]}.get(method, n)
    x = draw(st.one_of(hostile_arrays(size), st.integers(-5, 2**64), HOSTILE)) if method in ("reduced", "modes") else draw(hostile_arrays(size))
    return {"beam": beam, "which": which, "method": method, "x": x, "t": draw(st.one_of(st.floats(0.0, 1.0), HOSTILE))}


@settings(max_examples=MAX_EXAMPLES["arrays"], **SETTINGS)
@given(payload=array_calls())
def test_fuzz_model_level_arrays(worker, payload):
    result, problems = worker.run("array", payload)
    outcome("arrays", result)
    assert not problems, problems


def mostly(good):
    """`good`, or one time in four a hostile value."""
    return st.one_of(good, good, good, HOSTILE)


@st.composite
def stepper_calls(draw):
    beam = draw(beams)
    which = draw(st.sampled_from(["full", "reduced"]))
    n = beam["elements"] if which == "full" else min(2, beam["elements"])
    options = st.fixed_dictionaries(
        {},
        optional={
            "integrator": mostly(st.sampled_from(["auto", "radau", "bdf", "dopri5", "midpoint", "generalized-alpha"])),
            "rtol": mostly(st.sampled_from([1e-6, 1e-3, 0.5])),
            "atol": mostly(st.just(1e-6)),
            "hold": mostly(st.sampled_from(["linear", "zero"])),
            "t0": mostly(st.sampled_from([0.0, 1e6, 1e20])),
            "x0": mostly(hostile_arrays(n)),
            "scales": mostly(hostile_arrays(1)),
            "damping": mostly(st.just({"type": "rayleigh", "alpha": 0.1})),
            "gyroscopic": mostly(st.sampled_from(["exact", "neglected"])),
        },
    )
    dt = st.one_of(st.floats(1e-5, 0.02), st.sampled_from([0.0, -1.0, 1e-300, math.nan, 1e300]), HOSTILE)
    scales = st.one_of(st.none(), hostile_arrays(1), st.lists(st.floats(-100.0, 100.0), min_size=1, max_size=1))
    return {
        "beam": beam,
        "which": which,
        "kwargs": draw(options),
        "steps": draw(st.lists(st.tuples(dt, scales), min_size=1, max_size=4)),
    }


@settings(max_examples=MAX_EXAMPLES["stepper"], **SETTINGS)
@given(payload=stepper_calls())
def test_fuzz_stepper_calls(worker, payload):
    result, problems = worker.run("stepper", payload)
    outcome("stepper", result)
    count_recursive("stepper", payload)
    assert not problems, problems


def test_a_crash_of_the_worker_fails_the_example():
    w = Worker()
    with pytest.raises(AssertionError, match="the worker died"):
        w.run("abort", {})
    assert w.run("array", {"beam": {"length": 1.0, "elements": 2, "EI": 1.0, "mass_per_length": 1.0},
                           "which": "full", "method": "shape", "x": [0.0, 0.0], "t": 0.0}) == ("returned", [])
    w.close()


def test_the_fuzz_reached_every_kind_of_outcome():
    """The fuzz is not vacuous: analyses completed, were refused and stopped; model-level calls
    returned and raised; steps advanced and failed (the counts of this run; runs after the
    three fuzz tests in the file's order)."""
    if not {"cases", "arrays", "stepper"} <= set(OUTCOMES):
        pytest.skip("the fuzz tests did not all run in this session")
    c, a, s = OUTCOMES["cases"], OUTCOMES["arrays"], OUTCOMES["stepper"]
    recursive = OUTCOMES.get("cases recursive", {})
    assert recursive.get("__SELF__", 0) >= 5 and recursive.get("__DEEP__", 0) >= 5, recursive
    assert c.get("complete", 0) >= 10 and c.get("refused", 0) >= 10, c
    assert a.get("returned", 0) >= 20 and sum(v for k, v in a.items() if k != "returned") >= 20, a
    steps = [o for k, v in s.items() for o in k.split(",") * v]
    assert steps.count("ok") >= 20 and len(steps) - steps.count("ok") >= 20, s

