"""The discrete gust family (`flexwing gust`, `Case.gust_family`) on Patil's wing
(examples/patil_gust_family.toml, cut to 3 gusts on 8 elements):

* validation: the family's peaks in a small gust against an independent solution, SciPy's
  `scipy.signal.lsim` of the linear state-space model (`Case.linearize`, inputs `gust` and
  `gust_rate`: the uniform gust's upwash and its apparent mass) driven by the same 1−cos gusts;
* `Case.gust_family()` gives the CLI's numbers (same plan and run: a regression test);
* the views: `to_pandas()`, `plot()`, the critical gust of each output;
* bad input: errors naming the case file's keys.
"""

from __future__ import annotations


import numpy as np
import pytest

import flexwing

from conftest import example, run_cli

OUTPUTS = ("tip_y", "tip_twist", "root_bending_moment", "root_torque", "lift")


def small(**changes):
    """The example on 8 elements with 3 gusts (30, 190, 350 ft), and `changes`."""
    case = flexwing.Case.load(str(example("patil_gust_family.toml")))
    return case.replace({"beam.elements": 8, "gust_family.steps": 3, **changes})


@pytest.fixture(scope="module")
def family():
    return small().gust_family()


def one_minus_cosine(t, u_ds, h, speed, start):
    """The gust velocity and its rate at times `t`: (U_ds/2)(1 − cos(π s/H)), s = U (t − start)
    within [0, 2H]."""
    s = speed * (t - start)
    inside = (s >= 0.0) & (s <= 2.0 * h)
    v = np.where(inside, 0.5 * u_ds * (1.0 - np.cos(np.pi * s / h)), 0.0)
    dv = np.where(inside, 0.5 * u_ds * np.pi * speed / h * np.sin(np.pi * s / h), 0.0)
    return v, dv


def test_small_gusts_match_scipy_lsim_of_the_linear_model():
    """U_ref = 0.01 m/s (U_ds ≤ 0.01 m/s): the tip moves at most 2.5e-2 m from its
    equilibrium, where the non-linear response is its linearization's to O(U_ds). The linear model about the same
    equilibrium (full model, Peters 6 states), integrated by SciPy's lsim on a 1e-3 s grid
    (first-order hold of the input: its error (π U Δt/H)²/8 ≤ 9e-6 relative for the 30 ft gust)
    and sampled at the output times, against the family's peaks and their times.

    Tolerance: 2e-3 of the largest change of each output over the family, for the peak values.
    Measured (2026-12-03): up to 1.1e-3 (tip, the 350 ft gust), 1.3e-3 (lift), and it is the
    model's non-linearity about the trimmed, bent wing: it halves with U_ref (tip, 350 ft:
    1.12e-3 at 0.01 m/s, 5.6e-4 at 0.005 m/s) and does not move with the integration
    tolerance (rtol 1e-6 → 1e-8: 1.1207e-3 → 1.1217e-3). The times agree within one output
    step (0.01 s) where the peak is sharp; a flat extreme (a change below 1e-3 of the largest) is not compared in time."""
    signal = pytest.importorskip("scipy.signal")
    case = small(**{"gust_family.reference_velocity": 0.01, "dynamic.reduced": []})
    fam = case.gust_family()
    assert fam.status == "complete"
    run = fam.runs[0]
    lin = case.linearize(inputs=["gust", "gust_rate"], outputs=list(OUTPUTS)).runs[0]
    lti = lin.to_scipy()
    speed = case.to_dict()["aero"]["flight"]["speed"]
    start = fam.start
    dt_out = case.to_dict()["dynamic"]["output_step"]
    t_out = np.arange(0.0, fam.end_time + 0.5 * dt_out, dt_out)
    fine = np.linspace(0.0, t_out[-1], 10 * (len(t_out) - 1) + 1)
    worst = {o: 0.0 for o in OUTPUTS}
    for g, (h, u_ds) in enumerate(zip(run.gradient, run.design_velocity)):
        v, dv = one_minus_cosine(fine, u_ds, h, speed, start)
        _, y, _ = signal.lsim(lti, np.column_stack([v, dv]), fine)
        y = y[::10]
        after = t_out >= start - 1e-12
        for j, o in enumerate(OUTPUTS):
            change = y[after, j] - y[0, j]
            scale = max(np.max(np.abs(getattr(run, f"{o}_max"))), np.max(np.abs(getattr(run, f"{o}_min"))))
            for which, k in (("max", np.argmax(change)), ("min", np.argmin(change))):
                expected = max(change[k], 0.0) if which == "max" else min(change[k], 0.0)
                got = getattr(run, f"{o}_{which}")[g]
                err = abs(got - expected) / scale
                worst[o] = max(worst[o], err)
                assert err < 2e-3, f"H = {h:.2f} m, {o} {which}: {got:.6e} against lsim {expected:.6e}"
                if abs(expected) > 1e-3 * scale:
                    t_lsim = t_out[after][k]
                    t_got = getattr(run, f"{o}_{which}_time")[g]
                    assert abs(t_got - t_lsim) <= dt_out + 1e-9, f"H = {h:.2f} m, {o} {which} time"
    print("largest peak error against lsim, relative to the output's largest change:", worst)


def test_python_matches_the_cli(cli, tmp_path, family):
    """The same plan and run: every peak and the critical gusts agree (1e-12 relative: the CLI
    writes JSON numbers with round-trip precision)."""
    path = tmp_path / "family.toml"
    path.write_text(small().to_toml())
    doc = run_cli(cli, "gust", path, tmp_path / "out")
    assert [m["model"] for m in doc["models"]] == [r.label for r in family.runs]
    units = {"tip_y": "m", "tip_twist": "rad", "root_bending_moment": "n_m", "root_torque": "n_m", "lift": "n"}
    for m, r in zip(doc["models"], family.runs):
        assert m["status"] == r.status
        for g, row in enumerate(m["members"]):
            assert row["gradient_m"] == pytest.approx(r.gradient[g], rel=1e-12)
            for o in OUTPUTS:
                for which in ("max", "min"):
                    assert row[f"{o}_{which}_{units[o]}"] == pytest.approx(getattr(r, f"{o}_{which}")[g], rel=1e-12, abs=1e-300)
                    assert row[f"{o}_{which}_time_s"] == pytest.approx(getattr(r, f"{o}_{which}_time")[g], rel=1e-12)
        for c in m["critical"]:
            assert c["gradient_m"] == pytest.approx(r.critical[c["output"]]["gradient"], rel=1e-12)
            assert c["peak"] == pytest.approx(r.critical[c["output"]]["peak"], rel=1e-12)


def test_views_and_critical_gusts(family):
    """U_ds follows CS 25.341(a) (U_ref (H/350 ft)^(1/6), exact in feet); the critical gust of
    each output is its member of largest peak magnitude; the data frame has one row per model
    and gust; the plot has one panel per output."""
    foot = 0.3048
    for r in family.runs:
        assert r.gradient / foot == pytest.approx([30.0, 190.0, 350.0], rel=1e-12)
        assert r.design_velocity == pytest.approx(family.reference_velocity * (r.gradient / (350 * foot)) ** (1 / 6), rel=1e-12)
        for o in OUTPUTS:
            mags = np.maximum(np.abs(getattr(r, f"{o}_max")), np.abs(getattr(r, f"{o}_min")))
            c = r.critical[o]
            assert c["gradient"] == r.gradient[int(np.argmax(mags))]
            assert abs(c["peak"]) == mags.max()
    assert family.outputs == list(OUTPUTS)
    pd = pytest.importorskip("pandas")
    frame = family.to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert frame.shape[0] == 2 * 3 and "root_torque_max" in frame.columns
    assert frame.attrs["units"]["root_torque_max"] == "N m"
    assert frame.attrs["units"]["lift_max_time"] == "s"
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    fig = family.plot()
    assert len(fig.axes) == 5
    assert family.runs[0].complete and family.complete


def test_run_and_errors_name_the_keys():
    """`Case.run("gust")` is `gust_family()`; bad values are one-line InputErrors naming the
    case file's key."""
    r = small(**{"gust_family.steps": 1, "gust_family.from": 9.144, "gust_family.to": 9.144, "dynamic.reduced": []}).run("gust")
    assert isinstance(r, flexwing.GustFamilyResult) and len(r.runs[0].gradient) == 1
    for changes, key in [
        ({"gust_family.from": 5.0}, "gust_family.lengths"),
        ({"gust_family.alleviation": 1.5}, "gust_family.alleviation"),
        ({"dynamic.end_time": 4.0}, "dynamic.end_time"),
    ]:
        with pytest.raises(flexwing.InputError) as e:
            small(**changes).gust_family()
        assert key in str(e.value), str(e.value)
