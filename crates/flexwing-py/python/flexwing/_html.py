"""The compact HTML a notebook shows for a result (``_repr_html_``), built once from the
dataclass fields: a result with runs is a table of its runs (model, status, size, range of its
axis, the numbers that sum it up); any other result a table of its fields (numbers and texts
as they are, arrays as their dtype and shape); a batch a count of its statuses and its first
items. No dependency beyond the standard library."""

from __future__ import annotations

import dataclasses
import html
from typing import Any, List

import numpy as np

from ._frames import UNITS

#: The scalars a run's row shows, where the run has them.
HEADLINE = [
    "flutter_speed",
    "flutter_frequency",
    "divergence_speed",
    "max_tip_difference",
    "wall_time_s",
]

STYLE = "border-collapse:collapse;font-size:90%;text-align:left"


def _e(v: Any) -> str:
    return html.escape(str(v))


def _value(name: str, v: Any) -> str:
    if isinstance(v, np.ndarray):
        return f"<i>{_e(v.dtype)} {_e(v.shape)}</i>"
    if isinstance(v, (float, np.floating)):
        unit = UNITS.get(name)
        text = f"{float(v):.6g}"
        return _e(f"{text} {unit}" if unit and unit != "1" else text)
    if isinstance(v, dict):
        return f"<i>dict of {len(v)}</i>"
    if isinstance(v, list):
        return f"<i>list of {len(v)}</i>"
    if v is None:
        return "–"
    if dataclasses.is_dataclass(v):
        return f"<i>{_e(type(v).__name__)}</i>"
    text = str(v)
    return _e(text if len(text) <= 80 else text[:79] + "…")


def _table(head: List[str], rows: List[List[str]]) -> str:
    th = "".join(f"<th>{_e(h)}</th>" for h in head)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
    return f'<table style="{STYLE}"><tr>{th}</tr>{body}</table>'


def _title(obj, extra: str = "") -> str:
    status = getattr(obj, "status", None)
    if isinstance(status, dict):
        # The 3-D chain's results keep the library's status data: its word.
        status = status.get("status")
    parts = [f"<b>{_e(type(obj).__name__)}</b>"]
    if status is not None:
        colour = {"complete": "green", "suspect": "darkorange"}.get(status, "firebrick")
        parts.append(f'<span style="color:{colour}">{_e(status)}</span>')
    if extra:
        parts.append(extra)
    return "<div>" + " · ".join(parts) + "</div>"


def _extent(run) -> str:
    axis = getattr(run, "_axis", None)
    if axis is None and getattr(run, "_delegate", None):
        s = getattr(run, run._delegate)
        return f"{len(s.mode)} branches × {len(s.speeds)} speeds"
    if axis is None:
        return ""
    values = getattr(run, run._coord) if run._coord else getattr(run, run._columns[0])
    n = len(values)
    words = {"time": "output times", "point": "points", "speed": "speeds"}[axis]
    if n and run._coord:
        unit = UNITS.get(run._coord, "")
        return f"{n} {words}, {values[0]:.4g} … {values[-1]:.4g} {unit}"
    return f"{n} {words}"


def html_of(obj) -> str:
    if hasattr(obj, "runs"):
        head = ["model", "status", "dofs", "extent"]
        shown = [h for h in HEADLINE if any(getattr(r, h, None) is not None for r in obj.runs)]
        head += shown + ["message"]
        rows = []
        for r in obj.runs:
            row = [_e(r.label), _e(r.status), _e(r.dofs), _e(_extent(r))]
            row += [_value(h, getattr(r, h, None)) for h in shown]
            row.append(_value("message", r.message))
            rows.append(row)
        rust = getattr(obj, "rust_time_s", None)
        extra = f"{len(obj.runs)} models" + (f" · {rust:.3g} s in Rust" if rust is not None else "")
        return _title(obj, extra) + _table(head, rows)
    rows = []
    for f in dataclasses.fields(obj):
        if f.name == "extra":
            continue
        rows.append([_e(f.name), _value(f.name, getattr(obj, f.name))])
    return _title(obj) + _table(["field", "value"], rows)


def batch_html(items, shown: int = 10) -> str:
    counts = {}
    for i in items:
        counts[i.status] = counts.get(i.status, 0) + 1
    summary = ", ".join(f"{n} {_e(s)}" for s, n in counts.items())
    rows = [
        [_e(i.index), _e(i.status), _e(type(i.result).__name__ if i.result is not None else "–"),
         _value("wall_time_s", i.wall_time_s), _value("message", i.message)]
        for i in items[:shown]
    ]
    more = f"<div>… {len(items) - shown} more</div>" if len(items) > shown else ""
    head = f"<div><b>Batch</b> of {len(items)} cases: {summary or 'empty'}</div>"
    return head + _table(["index", "status", "result", "wall time", "message"], rows) + more
