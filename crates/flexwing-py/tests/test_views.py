"""The views of a result in the tools users analyse with (issue 19, item 6): pandas data frames,
xarray datasets (and NetCDF through them), matplotlib plots, the notebook's HTML, a tqdm bar as
the progress callback, and the batch of a sweep as a table indexed by its parameters.

Each view is checked against the result it comes from — the same numbers, bit for bit (a view
copies, it does not compute), under the documented names, dimensions and units — not against
itself. pandas, xarray, matplotlib, tqdm and netCDF4 are installed by requirements-test.txt;
their absence is an ImportError naming the extra, tested by hiding them."""

from __future__ import annotations

import html.parser
import io
import math
import sys

import matplotlib

matplotlib.use("Agg")  # before pyplot: no display in tests

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import flexwing

from conftest import example


@pytest.fixture(scope="module")
def results():
    """One result of every kind, from the example case files."""
    load = lambda name: flexwing.Case.load(example(name))  # noqa: E731
    return {
        "modes": load("table1.toml").modes(),
        "static": load("paper_static.toml").statics(),
        "dynamic": load("paper_sine.toml").dynamics(),
        "stopped": load("paper_free_vibration.toml").dynamics(check=False),
        "aero-static": load("patil_flutter.toml").statics(check=False),
        "flutter": load("patil_flutter.toml").flutter(),
        "aero-dynamic": load("patil_gust.toml").dynamics(),
    }


# --- pandas ----------------------------------------------------------------------------------


def test_runs_become_rows_by_model_and_axis(results):
    for kind, axis, coord in [
        ("static", "point", None),
        ("dynamic", "time", "t"),
        ("aero-static", "speed", "speed"),
        ("aero-dynamic", "time", "t"),
    ]:
        result = results[kind]
        frame = result.to_pandas()
        assert list(frame.index.names) == ["model", axis], kind
        assert list(frame.index.unique("model")) == [r.label for r in result.runs]
        for run in result.runs:
            rows = frame.loc[run.label]
            expected = np.arange(len(rows)) if coord is None else getattr(run, coord)
            assert np.array_equal(rows.index.to_numpy(), expected), kind
            for name in run._columns:
                values = getattr(run, name)
                if name == coord or values is None:
                    continue
                got = rows[name].to_numpy()
                want = np.array([math.nan if v is None else v for v in values], dtype=float)
                assert np.array_equal(got, want, equal_nan=True), f"{kind} {run.label} {name}"
        assert frame.attrs["units"]["tip_y"] == "m" and frame.attrs["units"]["tip_twist"] == "rad"
    assert results["dynamic"].to_pandas().attrs["units"]["total"] == "J"
    assert results["aero-static"].to_pandas().attrs["units"]["dynamic_pressure"] == "Pa"


def test_a_run_is_its_own_table(results):
    run = results["dynamic"].run("reduced-r2")
    frame = run.to_pandas()
    assert frame.index.name == "time" and np.array_equal(frame.index.to_numpy(), run.t)
    assert np.array_equal(frame["tip_y"].to_numpy(), run.tip_y)
    assert list(frame.columns) == [c for c in run._columns if c != "t"]


def test_modes_and_the_vg_data_as_tables(results):
    m = results["modes"]
    frame = m.to_pandas()
    assert frame.index.name == "mode" and list(frame.index) == list(m.mode)
    assert np.array_equal(frame["frequency_hz"].to_numpy(), m.frequency_hz)
    assert frame.attrs["units"]["omega"] == "rad/s"
    f = results["flutter"]
    vg = f.to_pandas()
    assert list(vg.index.names) == ["model", "branch", "speed"]
    s = f.full.eigenvalues
    full = vg.loc["full"]
    for b in range(len(s.mode)):
        assert np.array_equal(full.loc[b]["damping_ratio"].to_numpy(), s.damping_ratio[b])
        assert np.array_equal(full.loc[b].index.to_numpy(), s.speeds)
        assert (full.loc[b]["mode"] == s.mode[b]).all()
    assert vg.attrs["units"]["imag"] == "rad/s" and vg.attrs["units"]["real"] == "1/s"


# --- xarray ----------------------------------------------------------------------------------


def test_datasets_have_named_dimensions_and_units(results):
    ds = results["static"].to_xarray()
    n = results["static"].full.x.shape[1]
    assert dict(ds.sizes) == {"model": 4, "point": 16, "node": n, "dof": n - 1, "load": 2}
    assert ds["x"].dims == ("model", "point", "node") and ds["x"].attrs["units"] == "m"
    assert ds["q"].dims == ("model", "point", "dof") and ds["q"].attrs["units"] == "rad"
    for run in results["static"].runs:
        assert np.array_equal(ds["y"].sel(model=run.label).to_numpy(), run.y)
        assert ds["status"].sel(model=run.label).item() == run.status
    ds = results["dynamic"].to_xarray()
    assert ds["tip_y"].dims == ("model", "time") and ds["time"].attrs["units"] == "s"
    assert np.array_equal(ds["time"].to_numpy(), results["dynamic"].full.t)
    assert ds.attrs["analysis"] == "dynamic" and ds.attrs["end_time"] == 1.0
    ds = results["flutter"].to_xarray()
    assert ds["damping_ratio"].dims == ("model", "branch", "speed")
    assert ds["flutter_speed"].sel(model="full").item() == results["flutter"].full.flutter_speed
    assert ds["speed"].attrs["units"] == "m/s" and ds["flutter_speed"].attrs["units"] == "m/s"
    m = results["modes"].to_xarray()
    assert m["dy"].dims == ("mode", "node") and np.array_equal(m["x"].to_numpy(), results["modes"].x)


def test_a_stopped_run_is_missing_past_its_stop_and_a_complete_one_is_whole(results):
    r = results["stopped"]
    full, simplified = r.run("full"), r.run("simplified")
    assert full.status == "complete" and simplified.status == "stopped"
    ds = r.to_xarray()
    assert not np.isnan(ds["tip_y"].sel(model="full").to_numpy()).any()
    tail = ds["tip_y"].sel(model="simplified").to_numpy()
    assert np.array_equal(tail[: len(simplified.t)], simplified.tip_y)
    assert np.isnan(tail[len(simplified.t) :]).all() and len(simplified.t) < len(full.t)


def test_a_netcdf_round_trip_keeps_values_dimensions_and_units(results, tmp_path):
    for kind in ("static", "dynamic", "flutter", "modes", "aero-static"):
        ds = results[kind].to_xarray()
        path = tmp_path / f"{kind}.nc"
        ds.to_netcdf(path)
        again = xr.load_dataset(path)
        xr.testing.assert_equal(again, ds)
        for name in ds.variables:
            assert again[name].attrs.get("units") == ds[name].attrs.get("units"), (kind, name)
        assert again.attrs == ds.attrs


# --- Batches ---------------------------------------------------------------------------------


def test_a_batch_is_a_table_indexed_by_the_swept_parameters():
    base = flexwing.Case.load(example("paper_static.toml"))
    forces, stiffnesses = [50.0, 100.0, 150.0], [40.0, 60.0]
    cases = [base.replace({"loads[1].fy": -f, "beam.section.EI": e}) for f in forces for e in stiffnesses]
    batch = flexwing.solve_many(cases + [{"beam": 1}])
    assert isinstance(batch, flexwing.Batch) and isinstance(batch, list)
    frame = batch.to_pandas()
    assert frame.index.name == "case" and list(frame.index) == list(range(7))
    assert list(frame["status"]) == ["complete"] * 6 + ["error"]
    for i, item in enumerate(batch[:6]):
        assert frame.loc[i, "full.tip_y"] == item.result.full.tip_y[-1]
        assert frame.loc[i, "reduced-r2.tip_x"] == item.result.run("reduced-r2").tip_x[-1]
    assert math.isnan(frame.loc[6, "full.tip_y"]) and "beam" in frame.loc[6, "message"]
    assert frame.attrs["units"]["full.tip_y"] == "m" and frame.attrs["units"]["wall_time_s"] == "s"
    index = pd.MultiIndex.from_product([forces, stiffnesses], names=["F", "EI"])
    grid = flexwing.Batch(batch[:6]).to_xarray(index=index)
    assert grid["full.tip_y"].dims == ("F", "EI") and grid["full.tip_y"].attrs["units"] == "m"
    assert grid["full.tip_y"].sel(F=100.0, EI=60.0).item() == batch[3].result.full.tip_y[-1]
    with pytest.raises(ValueError, match="index"):
        batch.to_pandas(index=index)  # 6 labels for 7 items


def test_a_flutter_sweep_tabulates_its_speeds():
    base = flexwing.Case.load(example("section_flutter.toml"))
    batch = flexwing.solve_many([base, base.replace({"aero.elastic_axis": 0.4})], "flutter")
    frame = batch.to_pandas()
    for i, item in enumerate(batch):
        assert frame.loc[i, "full.flutter_speed"] == item.result.full.flutter_speed
    items = flexwing.solve_many([base], "modes")
    modes = items.to_pandas()
    assert modes.loc[0, "frequency_hz[1]"] == items[0].result.frequency_hz[0]
    assert modes.attrs["units"]["frequency_hz[1]"] == "Hz"


# --- Plots, HTML, progress -------------------------------------------------------------------


def lines(fig):
    return [line for ax in fig.axes for line in ax.get_lines()]


def test_plots_draw_the_results_numbers(results, tmp_path):
    import matplotlib.figure

    for kind, result in results.items():
        fig = result.plot()
        assert isinstance(fig, matplotlib.figure.Figure), kind
        path = tmp_path / f"{kind}.png"
        fig.savefig(path)
        assert path.stat().st_size > 5000, kind  # a drawn figure, not an empty canvas
    drawn = {line.get_label(): line for line in results["dynamic"].plot().axes[0].get_lines()}
    for run in results["dynamic"].runs:
        assert np.array_equal(drawn[run.label].get_xdata(), run.t)
        assert np.array_equal(drawn[run.label].get_ydata(), run.tip_y)
    s = results["flutter"].full.eigenvalues
    vg = results["flutter"].plot().axes[0].get_lines()
    for b in range(len(s.mode)):
        assert np.array_equal(vg[b].get_ydata(), s.damping_ratio[b])
    # Into the caller's axes.
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    assert results["dynamic"].full.plot(ax=ax) is fig and len(ax.get_lines()) == 1
    plt.close("all")


def test_the_notebook_html_is_a_compact_table_of_the_runs(results):
    class Parser(html.parser.HTMLParser):
        def __init__(self):
            super().__init__()
            self.rows, self.text = 0, []

        def handle_starttag(self, tag, attrs):
            self.rows += tag == "tr"

        def handle_data(self, data):
            self.text.append(data)

    for kind, result in results.items():
        page = result._repr_html_()
        p = Parser()
        p.feed(page)
        text = " ".join(p.text)
        assert type(result).__name__ in text and len(page) < 20_000, kind
        if hasattr(result, "runs"):
            assert p.rows == len(result.runs) + 1, kind
            for run in result.runs:
                assert run.label in text and run.status in text
    assert "32.1147 m/s" in results["flutter"]._repr_html_()  # Patil's flutter speed, with its unit
    batch = flexwing.solve_many([flexwing.Case.load(example("table4.toml"))] * 12, "modes")
    page = batch._repr_html_()
    assert "12 complete" in page and "2 more" in page


def test_a_tqdm_bar_follows_an_analysis_and_a_batch():
    case = flexwing.Case.load(example("paper_sine.toml"))
    out = io.StringIO()
    with flexwing.tqdm_progress(file=out, desc="case (b)") as bar:
        case.dynamics(progress=bar)
    assert "case (b)" in out.getvalue() and "100" in out.getvalue()
    out = io.StringIO()
    cases = [flexwing.Case.load(example("table4.toml"))] * 3
    with flexwing.tqdm_progress(file=out) as bar:
        flexwing.solve_many(cases, "modes", progress=bar)
    assert "3/3" in out.getvalue()


@pytest.mark.parametrize(
    "module, extra, call",
    [
        ("pandas", "pandas", lambda r: r.to_pandas()),
        ("xarray", "xarray", lambda r: r.to_xarray()),
        ("matplotlib", "plot", lambda r: r.plot()),
        ("tqdm", "tqdm", lambda r: flexwing.tqdm_progress()),
    ],
)
def test_a_missing_optional_dependency_names_its_extra(results, monkeypatch, module, extra, call):
    for name in list(sys.modules):
        if name == module or name.startswith(module + "."):
            monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(ImportError, match=rf'pip install "flexwing\[{extra}\]"'):
        call(results["dynamic"])
