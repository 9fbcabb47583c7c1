"""The result objects: every field the bindings produce is declared on its class (nothing left
in `extra`), `to_dict()` gives back the fields, arrays have the documented shapes and dtype."""

from __future__ import annotations

import dataclasses

import numpy as np

import flexwing

from conftest import example


def declared(obj):
    assert obj.extra == {}, f"{type(obj).__name__} has undeclared fields {sorted(obj.extra)}"


def test_every_field_is_declared(sine_case, static_case):
    modes = sine_case.modes()
    declared(modes)
    statics = static_case.statics()
    declared(statics)
    for r in statics.runs:
        declared(r)
    dynamics = sine_case.dynamics()
    declared(dynamics)
    for r in dynamics.runs:
        declared(r)
    for item in flexwing.solve_many([sine_case], "modes"):
        declared(item)


def test_shapes(static_case, sine_case):
    s = static_case.statics()
    full = s.full
    p, n = 16, 20
    assert full.scale.shape == (p,) and full.scales.shape == (p, 2)
    assert full.x.shape == full.y.shape == full.twist.shape == (p, n + 1)
    assert full.q.shape == (p, n)
    assert full.tip_difference is None
    assert s.run("reduced-r2").tip_difference.shape == (p,)
    assert all(v.shape == (p,) for v in full.stats.values())
    np.testing.assert_array_equal(full.tip_y, full.y[:, -1])
    d = sine_case.dynamics().run("full")
    assert d.t.shape == d.tip_y.shape == d.total.shape == (201,)
    assert d.t.dtype == np.float64
    np.testing.assert_allclose(d.total, d.kinetic + d.strain, rtol=1e-15)
    # [output] node_times: every output time up to 201.
    assert d.snapshots["x"].shape == (201, n + 1)
    m = sine_case.modes()
    assert m.dx.shape == (10, n + 1) and m.mode.dtype.kind == "i"


def test_to_dict_has_every_field(sine_case):
    result = sine_case.dynamics()
    d = result.to_dict()
    assert set(d) == {f.name for f in dataclasses.fields(result)} - {"extra"}
    run = d["runs"][0]
    assert set(run) == {f.name for f in dataclasses.fields(flexwing.DynamicRun)} - {"extra"}
    assert run["tip_y"] is result.runs[0].tip_y


def test_snapshots_at_chosen_output_times(sine_case):
    """Snapshots follow [output] node_times (test_files.py). The full model's final tip equals the last node of
    the shape a FullModel computes from the same joint rotations (a static point's q)."""
    s = flexwing.Case.load(example("paper_tip_force.toml")).statics()
    full = s.full
    model = flexwing.Case.load(example("paper_tip_force.toml")).model()
    shape = model.shape(full.q[-1])
    np.testing.assert_array_equal(shape["y"], full.y[-1])


def test_progress_callbacks(sine_case, static_case):
    """The analysis callback gets (fraction of the whole analysis, model label): fractions in
    [0, 1], non-decreasing, ending at 1, at most ~once per percent of each model (the binding
    throttles), and every model's label; solve_many's gets (done, total) once per case."""
    calls = []
    result = sine_case.dynamics(progress=lambda done, label: calls.append((done, label)))
    fractions = [d for d, _ in calls]
    assert all(0.0 <= d <= 1.0 for d in fractions)
    assert fractions == sorted(fractions) and fractions[-1] == 1.0
    assert {label for _, label in calls} == {r.label for r in result.runs}
    assert len(calls) <= len(result.runs) * 103  # start, <= 100 steps of 1 %, finish
    done = []
    flexwing.solve_many([static_case] * 3, "static", progress=lambda d, t: done.append((d, t)))
    assert done == [(1, 3), (2, 3), (3, 3)]
