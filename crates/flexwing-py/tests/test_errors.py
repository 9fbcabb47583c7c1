"""Errors: one tree under FlexwingError, the data of each error as attributes, the right
built-in bases (ValueError, TypeError, RuntimeError), and no panic across the boundary: every
bad input below must raise a FlexwingError that is not an InternalError (a caught panic) — and
never pyo3's PanicException, which is a BaseException and would escape `except Exception`."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import flexwing
from flexwing import (
    ArgumentTypeError,
    CaseFileError,
    FlexwingError,
    InputError,
    InternalError,
    SolverError,
)

from conftest import example

BEAM = {"length": 1.0, "elements": 4, "section": {"EI": 50.0, "mass_per_length": 0.2}}
LOAD = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}


def test_the_tree():
    assert issubclass(InputError, FlexwingError) and issubclass(InputError, ValueError)
    assert issubclass(CaseFileError, InputError)
    assert issubclass(ArgumentTypeError, FlexwingError) and issubclass(ArgumentTypeError, TypeError)
    assert issubclass(SolverError, FlexwingError) and issubclass(SolverError, RuntimeError)
    assert issubclass(InternalError, FlexwingError)


def raised(call) -> BaseException:
    """The exception `call` raises (BaseException too: a PanicException must be caught here to
    fail the test, not the run)."""
    try:
        call()
    except BaseException as e:  # noqa: BLE001 - the point of the test
        return e
    pytest.fail("no exception")


def beam(**kw):
    args = {"length": 1.0, "elements": 4, "EI": 50.0, "mass_per_length": 0.2}
    args.update(kw)
    return flexwing.Beam(**args)


FULL = flexwing.FullModel(beam())
EQUATIONS = FULL.equations([LOAD])
STEPPER = FULL.stepper([LOAD])

# (what, call, exception class, field it must name)
BAD = [
    ("unknown keyword of Beam", lambda: flexwing.Beam(lenght=1.0), ArgumentTypeError, "lenght"),
    ("negative length", lambda: beam(length=-1.0), InputError, "length"),
    ("NaN length", lambda: beam(length=float("nan")), InputError, "length"),
    ("negative element count", lambda: beam(elements=-3), InputError, "elements"),
    ("zero elements", lambda: beam(elements=0), InputError, "elements"),
    ("float element count", lambda: beam(elements=2.5), ArgumentTypeError, "elements"),
    ("string EI", lambda: beam(EI="50"), ArgumentTypeError, "EI"),
    ("boolean EI", lambda: beam(EI=True), ArgumentTypeError, "EI"),
    ("negative EI", lambda: beam(EI=-1.0), InputError, "EI"),
    ("table EI without x", lambda: beam(EI=[1.0, 2.0]), InputError, "x"),
    ("NaN in EI table", lambda: beam(EI=[50.0, np.nan], x=[0.0, 1.0]), InputError, "EI[1]"),
    ("EI table of the wrong length", lambda: beam(EI=[50.0, 1.0, 2.0], x=[0.0, 1.0]), InputError, "EI"),
    ("complex EI table", lambda: beam(EI=np.array([1j, 2.0]), x=[0.0, 1.0]), ArgumentTypeError, "EI"),
    ("2-D EI table", lambda: beam(EI=np.ones((2, 2)), x=[0.0, 1.0]), InputError, "EI"),
    ("decreasing stations", lambda: beam(elements=None, stations=[0.0, 0.6, 0.5, 1.0]), InputError, "stations"),
    ("torsion data without GJ", lambda: beam(d0=0.1), InputError, "d0"),
    ("unknown calibration", lambda: beam(calibration="exact"), InputError, "calibration"),
    ("unknown element inertia", lambda: beam(element_inertia="rod"), InputError, "element_inertia"),
    ("negative rotary inertia", lambda: beam(rotary_inertia=-1e-3), InputError, "rotary_inertia"),
    ("NaN rotary inertia", lambda: beam(rotary_inertia=float("nan")), InputError, "rotary_inertia"),
    ("state of the wrong size", lambda: EQUATIONS.rhs(0.0, np.zeros(7)), InputError, "y"),
    ("state with NaN", lambda: EQUATIONS.rhs(0.0, np.full(8, np.nan)), InputError, "y[0]"),
    ("state with inf", lambda: EQUATIONS.energies(np.r_[np.zeros(7), np.inf]), InputError, "y[7]"),
    ("complex state", lambda: EQUATIONS.rhs(0.0, np.zeros(8, dtype=complex)), ArgumentTypeError, "y"),
    ("string state", lambda: EQUATIONS.rhs(0.0, ["a"] * 8), ArgumentTypeError, "y"),
    ("ragged state", lambda: EQUATIONS.rhs(0.0, [[0.0], [0.0, 1.0]]), ArgumentTypeError, "y"),
    ("scalar state", lambda: EQUATIONS.rhs(0.0, 1.0), InputError, "y"),
    ("2-D state", lambda: EQUATIONS.rhs(0.0, np.zeros((2, 4))), InputError, "y"),
    ("string time", lambda: EQUATIONS.rhs("0", np.zeros(8)), ArgumentTypeError, "t"),
    ("unknown keyword of rhs", lambda: EQUATIONS.rhs(0.0, np.zeros(8), yy=1), ArgumentTypeError, "yy"),
    ("scales of the wrong size", lambda: setattr(EQUATIONS, "scales", [1.0, 2.0]), InputError, "scales"),
    ("unknown load type", lambda: FULL.equations([{**LOAD, "type": "push"}]), InputError, "loads[0].type"),
    ("load key of another type", lambda: FULL.equations([{**LOAD, "value": 1.0}]), InputError, "loads[0].value"),
    ("node beyond the tip", lambda: FULL.equations([{**{k: v for k, v in LOAD.items() if k != "span"}, "node": 9}]), InputError, "loads[0].node"),
    ("load off the beam", lambda: FULL.equations([{**LOAD, "span": 2.0}]), InputError, "loads[0].span"),
    ("time history at the model level", lambda: FULL.equations([{**LOAD, "time": {"type": "sine", "omega": 1.0}}]), InputError, "loads[0].time"),
    ("unknown gyroscopic", lambda: FULL.equations([LOAD], gyroscopic="none"), InputError, "gyroscopic"),
    ("negative damping", lambda: FULL.equations([LOAD], damping={"type": "rayleigh", "alpha": -1.0}), InputError, "damping.alpha"),
    ("unknown keyword of equations", lambda: FULL.equations([LOAD], damp=1), ArgumentTypeError, "damp"),
    ("negative step", lambda: STEPPER.step(-0.1), InputError, "dt"),
    ("NaN step", lambda: STEPPER.step(float("nan")), InputError, "dt"),
    ("unknown integrator", lambda: FULL.stepper([LOAD], integrator="euler"), InputError, "integrator"),
    ("zero rtol", lambda: FULL.stepper([LOAD], rtol=0.0), InputError, "rtol"),
    ("negative max_steps", lambda: FULL.stepper([LOAD], max_steps=-1), InputError, "max_steps"),
    ("x0 of the wrong size", lambda: FULL.stepper([LOAD], x0=[0.0]), InputError, "x0"),
    ("reduced model on mode 0", lambda: FULL.reduced([0, 1]), InputError, "modes[0]"),
    ("reduced model on too many modes", lambda: FULL.reduced(5), InputError, "modes"),
    ("reduced model on a repeated mode", lambda: FULL.reduced([1, 1]), InputError, "modes[1]"),
    ("too many modes", lambda: FULL.modes(count=99), InputError, "count"),
    ("negative mode count", lambda: FULL.modes(count=-1), InputError, "count"),
    ("unknown key of a case", lambda: flexwing.Case(beam=BEAM, bogus=1), CaseFileError, None),
    ("misspelt key in a case", lambda: flexwing.Case(beam={**BEAM, "lenght": 1.0}), CaseFileError, "beam.lenght"),
    ("negative elements in a case", lambda: flexwing.Case(beam={**BEAM, "elements": -4}), CaseFileError, "beam.elements"),
    ("string value in a case", lambda: flexwing.Case(beam={**BEAM, "length": "1"}), CaseFileError, "beam.length"),
    ("case data not a dict", lambda: flexwing.Case([1, 2]), ArgumentTypeError, "data"),
    ("bad TOML", lambda: flexwing.Case.from_toml("[beam\nlength = 1"), CaseFileError, None),
    ("missing file", lambda: flexwing.Case.load("/nonexistent/case.toml"), CaseFileError, None),
    ("negative EI in a case", lambda: flexwing.Case(beam={**BEAM, "section": {"EI": -1.0, "mass_per_length": 0.2}}).modes(), CaseFileError, "beam.section.EI"),
    ("no loads for statics", lambda: flexwing.Case(beam=BEAM).statics(), CaseFileError, "loads"),
    ("no [dynamic] table", lambda: flexwing.Case(beam=BEAM, loads=[LOAD]).dynamics(), CaseFileError, "dynamic"),
    ("unknown keyword of statics", lambda: flexwing.Case(beam=BEAM, loads=[LOAD]).statics(chek=False), ArgumentTypeError, "chek"),
    ("unknown analysis", lambda: flexwing.solve_many([], "buckling"), InputError, "analysis"),
    ("zero threads", lambda: flexwing.solve_many([], "static", threads=0), InputError, "threads"),
    ("cases not iterable", lambda: flexwing.solve_many(3), ArgumentTypeError, "cases"),
    ("bad path in replace", lambda: flexwing.Case(beam=BEAM).replace({"beam..x": 1}), InputError, "beam..x"),
    ("index out of range in replace", lambda: flexwing.Case(beam=BEAM, loads=[LOAD]).replace({"loads[3].fy": 1}), InputError, "loads[3].fy"),
]


@pytest.mark.parametrize("what, call, cls, field", BAD, ids=[b[0] for b in BAD])
def test_bad_input_raises_a_flexwing_error_naming_the_field(what, call, cls, field):
    e = raised(call)
    assert isinstance(e, cls), f"{what}: {type(e).__name__}: {e}"
    assert not isinstance(e, InternalError), f"{what}: a panic was caught: {e}"
    if field is not None:
        assert e.field == field, f"{what}: {e}"
        assert str(e).startswith(field) or field in str(e), str(e)
    assert "\n" not in str(e), "one-line messages"


def test_case_file_errors_carry_file_line_column_and_key(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = \"50\"\nmass_per_length = 0.2\n")
    e = raised(lambda: flexwing.Case.load(path))
    assert isinstance(e, CaseFileError)
    assert (e.file, e.line, e.column, e.key) == (str(path), 6, 6, "beam.section.EI")
    assert e.field == e.key
    assert e.reason.startswith("must be a number"), e.reason


def test_solver_errors_say_where_they_stopped_and_keep_the_partial_result(sine_case):
    case = sine_case.replace({"dynamic.max_steps": 200})
    e = raised(case.dynamics)
    assert isinstance(e, SolverError)
    assert e.model == "full"
    assert e.stop["reason"] == "integration"
    assert e.stop["error"]["kind"] == "too-many-steps"
    assert 0.0 < e.stop["error"]["time"] < 1.0
    partial = e.result
    assert isinstance(partial, flexwing.DynamicResult)
    full = partial.run("full")
    assert full.status == "stopped" and full.stop == e.stop
    assert len(full.t) >= 1 and full.t[-1] <= e.stop["error"]["time"]
    # The other models ran (a stopped model does not stop the analysis).
    assert len(partial.runs) == 5
    # check=False returns the same result without raising.
    result = case.dynamics(check=False)
    assert result.status == "stopped" and np.array_equal(result.run("full").t, full.t)


def test_static_sweep_stops_at_the_limit_point_with_its_load_factor():
    """A follower tip force swept far past where load control holds: the sweep stops at a
    point, says which scale it reached, and keeps the equilibria before it."""
    case = flexwing.Case(
        beam={"length": 1.0, "elements": 10, "section": {"EI": 50.0, "mass_per_length": 0.2}},
        loads=[{"name": "F", "type": "point-force", "span": 1.0, "direction": "dead", "fx": -1.0}],
        **{"static": {"sweep": {"load": "F", "from": 0.0, "to": 400.0, "steps": 5}}},
    )
    result = case.statics(check=False)
    full = result.full
    if full.complete:
        pytest.skip("the sweep passed the buckling load (the library follows the other branch)")
    stop = full.stop
    assert stop["reason"] == "static-point"
    assert 0 < stop["point"] < 5 and len(full.scale) == stop["point"]
    assert "F scale" in stop["message"]
    with pytest.raises(SolverError) as info:
        case.statics()
    assert info.value.stop["point"] == stop["point"]


def test_exceptions_pickle_with_their_attributes():
    e = raised(lambda: flexwing.Case.from_toml("[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = -50.0\nmass_per_length = 0.2\n").modes())
    again = pickle.loads(pickle.dumps(e))
    assert type(again) is CaseFileError
    assert (again.key, again.reason, str(again)) == (e.key, e.reason, str(e))
    s = raised(lambda: flexwing.Case.load(example("paper_sine.toml")).replace({"dynamic.max_steps": 5}).dynamics())
    again = pickle.loads(pickle.dumps(s))
    assert again.stop == s.stop and again.model == "full"
    assert np.array_equal(again.result.run("full").t, s.result.run("full").t)


def test_a_progress_callback_that_raises_stops_the_calls_and_its_error_is_raised(sine_case):
    calls = []

    def progress(done, label):
        calls.append(done)
        raise KeyError("from the callback")

    e = raised(lambda: sine_case.modes(progress=progress))
    assert isinstance(e, KeyError) and len(calls) == 1
