"""Results as pandas data frames and xarray datasets: the views ``to_pandas()`` and
``to_xarray()`` of every result class and of a batch, built here once from what each class
declares (``_base.py``):

* ``_axis``: the dimension a run's values run along — ``"point"`` (static sweep points),
  ``"time"`` (output times), ``"speed"`` (flight speeds) — and ``_coord``, the field holding its
  coordinate values (``t``, ``speed``; ``None``: the points are numbered 0, 1, …);
* ``_columns``: the fields with one value per point of the axis (a data frame's columns, an
  xarray variable over the axis);
* ``_grids``: the fields with a second dimension (``"node"``, ``"dof"``, ``"load"``): xarray
  variables over (axis, that dimension).

Units come from :data:`UNITS`, one entry per name: a name means one quantity in every class
(``tip_y`` is always m). They are the ``units`` attribute of every xarray variable and of each
data frame's columns (``frame.attrs["units"]``). A value the result does not have (``None``:
no divergence speed, the full model's ``tip_difference``) and the points a stopped run did not
reach (when runs are put side by side along ``model``) are NaN: pandas' and xarray's mark for
missing data; a complete run of a complete result has none of its own.

pandas and xarray are optional (``pip install "flexwing[pandas]"``, ``"flexwing[xarray]"``):
a missing one raises ImportError naming the extra.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Dict, List, Optional

import numpy as np

#: The unit of every quantity a result holds, by its name (SI; "1" for a pure number).
UNITS: Dict[str, str] = {
    # Coordinates.
    "t": "s",
    "time": "s",
    "speed": "m/s",
    "speeds": "m/s",
    "x": "m",
    "scale": "1",
    "scales": "1",
    # Tips, shapes, loads.
    "tip_x": "m",
    "tip_y": "m",
    "tip_twist": "rad",
    "tip_z": "m",
    "tip_rotation": "rad",
    "tip_difference": "m",
    "max_tip_difference": "m",
    "y": "m",
    "twist": "rad",
    "q": "rad",
    "dx": "m",
    "dy": "m",
    "lift": "N",
    "root_bending_moment": "N m",
    "root_torque": "N m",
    "hinge_moments": "N m",
    "dynamic_pressure": "Pa",
    "divergence_pressure": "Pa",
    # Energies.
    "kinetic": "J",
    "strain": "J",
    "total": "J",
    "work": "J",
    "dissipated": "J",
    "balance_error": "1",
    # Frequencies, eigenvalues, speeds of instability.
    "omega": "rad/s",
    "unloaded_omega": "rad/s",
    "frequency_hz": "Hz",
    "frequency": "rad/s",
    "gust_psd": "m2 s-2 / (rad/s)",
    "bending_energy_fraction": "1",
    "wet_frequency": "rad/s",
    "real": "1/s",
    "imag": "rad/s",
    "damping_ratio": "1",
    "flutter_speed": "m/s",
    "flutter_frequency": "rad/s",
    "divergence_speed": "m/s",
    "divergence_dynamic_pressure": "Pa",
    # Flight and the rest.
    "root_angle": "rad",
    "gravity": "m/s^2",
    "end_time": "s",
    "wall_time_s": "s",
    "rust_time_s": "s",
    "ratio_to_first": "1",
    "dofs": "1",
    "aero_states": "1",
    "n_elements": "1",
    "n_dofs": "1",
    "tolerance": "1",
    "mode": "1",
    "index": "1",
    # Gust families.
    "gust": "m",
    "gradient": "m",
    "design_velocity": "m/s",
    "steps": "1",
}
# A gust family's peaks are in their output's unit, their times in s.
for _name in ("tip_y", "tip_twist", "root_bending_moment", "root_torque", "lift"):
    UNITS.update({f"{_name}_max": UNITS[_name], f"{_name}_min": UNITS[_name]})
    UNITS.update({f"{_name}_max_time": "s", f"{_name}_min_time": "s"})


def _need(module: str, extra: str, what: str):
    try:
        return __import__(module)
    except ImportError as e:
        raise ImportError(
            f"{what} needs {module}, an optional dependency of flexwing: "
            f'pip install "flexwing[{extra}]" (or pip install {module})'
        ) from e


def pandas(what: str = "to_pandas()"):
    """The pandas module, or ImportError naming the extra."""
    return _need("pandas", "pandas", what)


def xarray(what: str = "to_xarray()"):
    """The xarray module, or ImportError naming the extra."""
    return _need("xarray", "xarray", what)


def _float(v: Any) -> float:
    """A scalar as a float, None as NaN (missing)."""
    return math.nan if v is None else float(v)


def _column(values: Any, n: int) -> np.ndarray:
    """A run's column as a float array of `n` values (None, or None entries, as NaN)."""
    if values is None:
        return np.full(n, math.nan)
    if isinstance(values, list):
        return np.array([_float(v) for v in values], dtype=float)
    return np.asarray(values)


def _length(run) -> int:
    if run._coord is not None:
        return len(getattr(run, run._coord))
    for name in run._columns:
        v = getattr(run, name)
        if v is not None:
            return len(v)
    return 0


def _axis_values(run) -> np.ndarray:
    n = _length(run)
    if run._coord is None:
        return np.arange(n)
    return np.asarray(getattr(run, run._coord), dtype=float)


#: The declared types of the fields that are scalars (the results' annotations are strings).
SCALAR_TYPES = {"int", "float", "str", "Optional[int]", "Optional[float]", "Optional[str]"}


def _scalars(obj) -> Dict[str, Any]:
    """The scalar fields of `obj` — those declared as a number or a text, possibly None — in
    the order declared, the axis' own columns left out."""
    out = {}
    skip = set(getattr(obj, "_columns", ())) | set(getattr(obj, "_grids", {})) | {"extra"}
    for f in dataclasses.fields(obj):
        if f.name in skip or str(f.type) not in SCALAR_TYPES:
            continue
        v = getattr(obj, f.name)
        out[f.name] = v.item() if isinstance(v, np.generic) else v
    return out


def _units_of(names) -> Dict[str, str]:
    return {n: UNITS[n] for n in names if n in UNITS}


# --- Runs ----------------------------------------------------------------------------------


def frame(obj):
    """``obj.to_pandas()`` of any result, run or batch item."""
    if hasattr(obj, "runs"):
        return runs_frame(obj)
    if getattr(obj, "_axis", None) or getattr(obj, "_delegate", None):
        return run_frame(obj)
    if hasattr(obj, "damping_ratio"):
        return stability_frame(obj)
    if hasattr(obj, "dx"):
        return modes_frame(obj)
    if hasattr(obj, "unwrap"):
        return batch_frame([obj])
    raise TypeError(f"{type(obj).__name__} has no data frame")


def dataset(obj):
    """``obj.to_xarray()`` of any result, run or batch item."""
    if hasattr(obj, "runs"):
        return runs_dataset(obj)
    if getattr(obj, "_axis", None) or getattr(obj, "_delegate", None):
        return run_dataset(obj)
    if hasattr(obj, "damping_ratio"):
        return stability_dataset(obj)
    if hasattr(obj, "dx"):
        return modes_dataset(obj)
    if hasattr(obj, "unwrap"):
        return batch_dataset([obj])
    raise TypeError(f"{type(obj).__name__} has no dataset")


def run_frame(run):
    """A run's data frame: one row per point of its axis, its `_columns` as columns."""
    pd = pandas()
    if getattr(run, "_delegate", None):
        return frame(getattr(run, run._delegate))
    n = _length(run)
    columns = {}
    for name in run._columns:
        if name == run._coord:
            continue
        values = getattr(run, name)
        if values is None:
            continue
        columns[name] = _column(values, n)
    for name, second in run._grids.items():
        labels = getattr(run, run._grid_labels.get(second, ""), None)
        values = getattr(run, name)
        if labels is None or values is None:
            continue
        for j, label in enumerate(labels):
            columns[f"{name}[{label}]"] = np.asarray(values)[:, j]
    index = pd.Index(_axis_values(run), name=run._axis)
    table = pd.DataFrame(columns, index=index)
    table.attrs["units"] = _units_of([run._axis, *columns])
    return table


def _variable(xr, dims, values, name):
    attrs = {"units": UNITS[name]} if name in UNITS else {}
    return xr.Variable(dims, values, attrs=attrs)


def run_dataset(run):
    """A run's dataset: its columns over its axis, its grids over (axis, second dimension), its
    scalars as attributes (numbers and texts; None left out)."""
    xr = xarray()
    if getattr(run, "_delegate", None):
        ds = dataset(getattr(run, run._delegate))
        ds.attrs.update(_attrs(_scalars(run)))
        return ds
    n = _length(run)
    data = {}
    for name in run._columns:
        if name == run._coord:
            continue
        values = getattr(run, name)
        if values is not None:
            data[name] = _variable(xr, (run._axis,), _column(values, n), name)
    for name, second in run._grids.items():
        values = getattr(run, name)
        if values is not None:
            data[name] = _variable(xr, (run._axis, second), np.asarray(values), name)
    coords = {run._axis: _variable(xr, (run._axis,), _axis_values(run), run._coord or run._axis)}
    for second, field_name in run._grid_labels.items():
        labels = getattr(run, field_name, None)
        if labels is not None:
            coords[second] = xr.Variable((second,), np.array(labels, dtype=str))
    return xr.Dataset(data, coords=coords, attrs=_attrs(_scalars(run)))


def _attrs(scalars: Dict[str, Any]) -> Dict[str, Any]:
    """Scalars as dataset attributes (netCDF takes numbers and texts, not None)."""
    return {k: (v.item() if isinstance(v, np.generic) else v) for k, v in scalars.items() if v is not None}


# --- Results with one run per model --------------------------------------------------------


def runs_frame(result):
    """One frame for every run: a (model, axis) row index."""
    pd = pandas()
    frames = [run_frame(r) for r in result.runs]
    labels = [r.label for r in result.runs]
    if not frames:
        return pd.DataFrame()
    table = pd.concat(frames, keys=labels, names=["model", *frames[0].index.names])
    units = {}
    for f in frames:
        units.update(f.attrs.get("units", {}))
    table.attrs["units"] = units
    table.attrs["status"] = result.status
    return table


def runs_dataset(result):
    """The runs side by side along ``model`` (outer join on the axis: points a stopped run did
    not reach are NaN); each run's scalars become variables over ``model``."""
    xr = xarray()
    runs = result.runs
    labels = [r.label for r in runs]
    datasets = []
    for r in runs:
        ds = run_dataset(r)
        ds.attrs = {}
        datasets.append(ds)
    if datasets:
        ds = xr.concat(datasets, dim="model", join="outer", data_vars="all", coords="minimal", compat="override")
    else:
        ds = xr.Dataset()
    ds = ds.assign_coords(model=("model", np.array(labels, dtype=str)))
    scalars = [_scalars(r) for r in runs]
    names: List[str] = []
    for s in scalars:
        names += [k for k in s if k not in names and k not in ("label",)]
    for name in names:
        values = [s.get(name) for s in scalars]
        if all(isinstance(v, str) or v is None for v in values):
            column = np.array(["" if v is None else v for v in values], dtype=str)
        elif all(isinstance(v, int) for v in values):
            column = np.array(values, dtype=np.int64)
        else:
            column = np.array([_float(v) for v in values], dtype=float)
        ds[name] = _variable(xr, ("model",), column, name)
    ds.attrs.update(_attrs({k: v for k, v in _scalars(result).items()}))
    ds.attrs["analysis"] = type(result)._kind or type(result).__name__
    return ds


# --- Modes and stability -------------------------------------------------------------------


def modes_frame(result):
    pd = pandas()
    table = pd.DataFrame(
        {
            "omega": result.omega,
            "frequency_hz": result.frequency_hz,
            "bending_energy_fraction": result.bending_energy_fraction,
        },
        index=pd.Index(result.mode, name="mode"),
    )
    table.attrs["units"] = _units_of(table.columns)
    return table


def modes_dataset(result):
    xr = xarray()
    data = {
        name: _variable(xr, ("mode",), getattr(result, name), name)
        for name in ("omega", "frequency_hz", "bending_energy_fraction")
    }
    for name in ("dx", "dy", "twist"):
        data[name] = _variable(xr, ("mode", "node"), getattr(result, name), name)
    coords = {
        "mode": ("mode", result.mode),
        "node": ("node", np.arange(len(result.x))),
        "x": _variable(xr, ("node",), result.x, "x"),
    }
    return xr.Dataset(data, coords=coords, attrs=_attrs(_scalars(result)) | {"analysis": "modes"})


def stability_frame(s):
    """The V-g/V-ω data as a long table: one row per (branch, speed)."""
    pd = pandas()
    b, n = s.real.shape if s.real.ndim == 2 else (0, 0)
    index = pd.MultiIndex.from_product([np.arange(b), np.asarray(s.speeds)], names=["branch", "speed"])
    table = pd.DataFrame(
        {
            "mode": np.repeat(s.mode, n),
            "wet_frequency": np.repeat(s.wet_frequency, n),
            "real": s.real.reshape(-1),
            "imag": s.imag.reshape(-1),
            "damping_ratio": s.damping_ratio.reshape(-1),
        },
        index=index,
    )
    table.attrs["units"] = _units_of(["speed", *table.columns])
    return table


def stability_dataset(s):
    xr = xarray()
    data = {
        name: _variable(xr, ("branch", "speed"), getattr(s, name), name)
        for name in ("real", "imag", "damping_ratio")
    }
    data["mode"] = _variable(xr, ("branch",), s.mode, "mode")
    data["wet_frequency"] = _variable(xr, ("branch",), s.wet_frequency, "wet_frequency")
    data["uncertain"] = xr.Variable(("branch",), np.asarray(s.uncertain, dtype=bool))
    coords = {
        "branch": ("branch", np.arange(len(s.mode))),
        "speed": _variable(xr, ("speed",), np.asarray(s.speeds, dtype=float), "speed"),
    }
    return xr.Dataset(data, coords=coords, attrs=_attrs(_scalars(s)))


# --- Batches -------------------------------------------------------------------------------


def summary(result) -> Dict[str, Any]:
    """The scalars of a result, flat: its own (``status``, …), and per run (prefixed with the
    run's label: ``full.status``, ``full.flutter_speed``) its scalars and the last value of each
    of its columns (``full.tip_y``: at the last point or output time reached)."""
    out: Dict[str, Any] = {}
    if result is None:
        return out
    if hasattr(result, "runs"):
        for k, v in _scalars(result).items():
            if k not in ("status", "rust_time_s"):  # the item's own status stands for it
                out[k] = v
        for r in result.runs:
            for k, v in _scalars(r).items():
                if k not in ("label", "message"):
                    out[f"{r.label}.{k}"] = v
            source = getattr(r, r._delegate) if getattr(r, "_delegate", None) else r
            if hasattr(source, "_columns"):
                n = _length(source)
                for name in source._columns:
                    values = getattr(source, name)
                    if values is not None and n:
                        out[f"{r.label}.{name}"] = _column(values, n)[-1]
    elif hasattr(result, "omega"):
        for m, f in zip(result.mode, result.frequency_hz):
            out[f"frequency_hz[{int(m)}]"] = float(f)
    return out


def batch_frame(items, index=None):
    pd = pandas()
    rows = []
    for item in items:
        row = {"index": item.index, "status": item.status, "message": item.message, "wall_time_s": item.wall_time_s}
        row.update(summary(item.result))
        rows.append(row)
    table = pd.DataFrame(rows)
    for name in table.columns:
        # None of a missing number is NaN; texts stay texts.
        if table[name].dtype == object and table[name].map(lambda v: v is None or isinstance(v, (int, float))).all():
            table[name] = table[name].astype(float)
    if index is None:
        table = table.set_index("index").rename_axis("case")
    else:
        if not isinstance(index, pd.Index):
            index = pd.Index(index) if not (len(index) and isinstance(index[0], tuple)) else pd.MultiIndex.from_tuples(index)
        if len(index) != len(table):
            raise ValueError(f"index: {len(index)} labels for {len(table)} items")
        table.index = index
    units = {}
    for name in table.columns:
        unit = UNITS.get(name.rsplit(".", 1)[-1].split("[")[0])
        if unit is not None:
            units[name] = unit
    table.attrs["units"] = units
    return table


def batch_dataset(items, index=None):
    xr = xarray()
    table = batch_frame(items, index)
    if all(n is None for n in table.index.names):
        table = table.rename_axis("case")
    ds = xr.Dataset.from_dataframe(table)
    for name, unit in table.attrs["units"].items():
        ds[name].attrs["units"] = unit
    return ds
