"""What every result class shares: the base classes, the builder the Rust side calls, and the
conversion to dicts.

A result is a plain dataclass of NumPy arrays, numbers, strings and dicts, built from the dict
the Rust side makes of the library's outcome (``flexwing._native``, ``convert/``): it pickles
(to travel back from worker processes), prints and converts to dicts (``to_dict()``). A field
the Rust side adds before the class declares it lands in ``extra`` (the test suite checks that
nothing does).

A result class says how it is built from its dict with two class attributes: ``_nested`` maps a
field to the class its dict (or each dict of its list, for a list) becomes, and ``_kind`` (on
the top-level results) is the name of the analysis the Rust side builds it for (the library's
``Plan::name``). Every view of a result — ``to_dict`` here, ``to_pandas``/``to_xarray``
(``_frames.py``), ``plot`` (``_plot.py``), the notebook's HTML (``_html.py``) — works from the
dataclass fields and a run's declared ``_axis``, ``_coord``, ``_columns`` and ``_grids``, so a new
result class gets them by declaring its fields.
"""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar, Dict, List, Optional

_FIELDS: Dict[type, frozenset] = {}
_KINDS: Dict[str, type] = {}


def _from_raw(cls, raw: Dict[str, Any]):
    """An instance of the dataclass ``cls`` from the dict ``raw``, its ``_nested`` fields built
    too; keys that ``cls`` does not declare go to its ``extra`` dict."""
    names = _FIELDS.get(cls)
    if names is None:
        names = _FIELDS[cls] = frozenset(f.name for f in dataclasses.fields(cls))
    known = {k: v for k, v in raw.items() if k in names}
    for name, inner in getattr(cls, "_nested", {}).items():
        value = known.get(name)
        if isinstance(value, list):
            known[name] = [_from_raw(inner, v) for v in value]
        elif isinstance(value, dict):
            known[name] = _from_raw(inner, value)
    if "extra" in names:
        known["extra"] = {k: v for k, v in raw.items() if k not in names}
    return cls(**known)


def _build(kind: str, raw: Dict[str, Any]):
    """Build the result of the analysis ``kind`` from the bindings' dict (called by
    ``flexwing._native``)."""
    if not _KINDS:
        from . import _aero_results, _chain3d_results, _linear, _results  # noqa: F401 (they register their kinds)
    return _from_raw(_KINDS[kind], raw)


def _to_dict(value: Any) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        out = {}
        for f in dataclasses.fields(value):
            v = getattr(value, f.name)
            if f.name == "extra":
                out.update({k: _to_dict(x) for k, x in v.items()})
            else:
                out[f.name] = _to_dict(v)
        return out
    if isinstance(value, list):
        return [_to_dict(v) for v in value]
    if isinstance(value, dict):
        return {k: _to_dict(v) for k, v in value.items()}
    return value


def _summary(obj, fields: List[str]) -> str:
    parts = ", ".join(f"{f}={getattr(obj, f)!r}" for f in fields)
    return f"{type(obj).__name__}({parts})"


class _Result:
    """The base of every result class: ``to_dict()``, ``to_pandas()``, ``to_xarray()``,
    ``plot()`` and the notebook's HTML, each built once from the dataclass fields and what the
    class declares (``_frames.py``, ``_plot.py``, ``_html.py``)."""

    _nested: ClassVar[Dict[str, type]] = {}
    _kind: ClassVar[Optional[str]] = None
    # What a run's views are made of (``_frames.py``): the dimension its values run along, the
    # field of its coordinate, its columns over that axis, its fields with a second dimension;
    # or the field whose views are the run's (``_delegate``).
    _axis: ClassVar[Optional[str]] = None
    _coord: ClassVar[Optional[str]] = None
    _columns: ClassVar[tuple] = ()
    _grids: ClassVar[Dict[str, str]] = {}
    # The field naming the entries of a grid's second dimension (``{"output": "outputs"}``):
    # its coordinate in xarray, and one data frame column ``name[label]`` per entry.
    _grid_labels: ClassVar[Dict[str, str]] = {}
    _delegate: ClassVar[Optional[str]] = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.__dict__.get("_kind"):
            _KINDS[cls._kind] = cls

    def to_dict(self) -> Dict[str, Any]:
        """The result as nested dicts, lists, NumPy arrays and numbers (the arrays are the
        result's own, not copies)."""
        return _to_dict(self)

    def to_pandas(self):
        """The result as a ``pandas.DataFrame``: one row per point, output time or speed (and
        per model, with a ``(model, …)`` row index), one column per quantity; the units in
        ``frame.attrs["units"]``. Needs pandas (``pip install "flexwing[pandas]"``)."""
        from . import _frames

        return _frames.frame(self)

    def to_xarray(self):
        """The result as an ``xarray.Dataset`` with named dimensions (``model``, ``point``,
        ``time``, ``speed``, ``branch``, ``mode``, ``node``, ``dof``, ``load``) and units as
        attributes; NetCDF and Zarr through xarray (``ds.to_netcdf(path)``). Needs xarray
        (``pip install "flexwing[xarray]"``)."""
        from . import _frames

        return _frames.dataset(self)

    def plot(self, ax=None, **kwargs):
        """A quick look with matplotlib: the figure (see ``flexwing._plot``). Needs matplotlib
        (``pip install "flexwing[plot]"``)."""
        from . import _plot

        return _plot.plot(self, ax, **kwargs)

    def _repr_html_(self) -> str:
        from . import _html

        return _html.html_of(self)


class _Run(_Result):
    """The run of one model: its ``label``, ``kind`` and ``status``."""

    @property
    def complete(self) -> bool:
        """Whether the run reached its end and every check passed (``status == "complete"``)."""
        return self.status == "complete"


class _Runs(_Result):
    """A result with one run per model (``runs``) and a ``status``."""

    @property
    def complete(self) -> bool:
        """Whether every model completed."""
        return self.status == "complete"

    def run(self, label: str):
        """The run of the model ``label`` (``"full"``, ``"reduced-r2"``, …)."""
        for r in self.runs:
            if r.label == label:
                return r
        raise KeyError(f"no model {label!r}; the runs are {[r.label for r in self.runs]}")

    @property
    def full(self):
        """The full model's run, if it was run."""
        return next((r for r in self.runs if r.kind == "full"), None)

    def __repr__(self) -> str:
        return f"{type(self).__name__}(status={self.status!r}, runs={self.runs!r})"
