"""Result files from Python, written by the same Rust writers as the CLI's (the crate
``flexwing-io``): ``save_npz`` (the node histories, the layout of ``flexwing dynamic``'s
``dynamic_nodes.npz``), ``load_npz`` to read one back, and ``write_vtk`` (VTK XML for ParaView,
the files of the CLI's ``--vtk``). docs/python.md, "Files"."""

from __future__ import annotations

import os
from typing import Dict, List, Optional

import numpy as np

from . import _native

#: The fields of the planar chain's node histories, with their units.
PLANAR_FIELDS = (("x", "m"), ("y", "m"), ("twist", "rad"))


def _stations(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The undeformed nodes' spanwise positions from one deformed shape: the arc length along
    the chain, exact for rigid elements (to round-off, about n ulp)."""
    return np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])


def _vtk(folder, stem, times, x, y, twist, stations, modes=False) -> str:
    f64 = lambda a: np.ascontiguousarray(a, dtype=np.float64)
    return _native.write_planar_vtk(
        os.fspath(folder), stem, f64(times), f64(x), f64(y), f64(twist), f64(stations), modes)


def _spatial_vtk(folder, stem, times, position, rotation, reference, modes=False) -> str:
    """The 3-D chain's frames (``flexwing_io``'s writer, as the CLI's ``--vtk``)."""
    f64 = lambda a: np.ascontiguousarray(a, dtype=np.float64)
    return _native.write_spatial_vtk(
        os.fspath(folder), stem, f64(times), f64(position), f64(rotation), f64(reference), modes)


class _NodeFiles:
    """``save_npz`` and ``write_vtk`` for the results with node snapshots (``DynamicResult``,
    ``AeroDynamicResult``)."""

    def write_vtk(self, folder, stations: Optional[np.ndarray] = None) -> List[str]:
        """Write every run's snapshots to ``folder`` for ParaView, as ``flexwing dynamic
        --vtk`` does: ``dynamic_LABEL_0000.vtu``, … (the nodes as points at the deformed
        positions, the elements as lines, point data ``displacement`` (m, from the undeformed
        nodes) and ``twist`` (rad)) and ``dynamic_LABEL.pvd`` with the snapshot times. Returns
        the ``.pvd`` paths. ``stations``: the undeformed nodes (m); by default the arc length
        along the first snapshot (the elements are rigid)."""
        paths = []
        for r in self.runs:
            s = r.snapshots
            if len(s["t"]) == 0:
                continue
            st = _stations(s["x"][0], s["y"][0]) if stations is None else stations
            paths.append(_vtk(folder, f"dynamic_{r.label}", s["t"], s["x"], s["y"], s["twist"], st))
        return paths

    def save_npz(self, path) -> None:
        """Write every run's node snapshots to ``path`` (``.npz``, written atomically): the
        arrays ``models``, ``fields``, ``units`` and per model ``LABEL/t`` ``(S,)``,
        ``LABEL/index`` ``(S,)`` (indices among the output times) and ``LABEL/nodes``
        ``(S, n + 1, 3)`` (``x``, ``y`` in m, ``twist`` in rad), as ``flexwing dynamic
        --format npz`` writes them. ``numpy.load`` or :func:`load_npz` reads it."""
        histories = []
        for r in self.runs:
            s = r.snapshots
            nodes = np.stack([s[name] for name, _ in PLANAR_FIELDS], axis=-1)
            histories.append(
                (r.label, np.ascontiguousarray(s["t"], dtype=np.float64),
                 np.ascontiguousarray(s["index"], dtype=np.int64),
                 np.ascontiguousarray(nodes, dtype=np.float64)))
        _native.write_node_npz(os.fspath(path), list(PLANAR_FIELDS), histories)


def load_npz(path) -> Dict[str, Dict[str, np.ndarray]]:
    """Read node histories written by ``save_npz`` or ``flexwing dynamic --format npz``: per
    model label a dict of ``t``, ``index`` and one ``(S, n + 1)`` array per field (``x``, ``y``,
    ``twist``), as ``DynamicRun.snapshots``."""
    with np.load(os.fspath(path), allow_pickle=False) as d:
        fields = [str(f) for f in d["fields"]]
        out = {}
        for label in (str(m) for m in d["models"]):
            nodes = d[f"{label}/nodes"]
            run = {"index": d[f"{label}/index"], "t": d[f"{label}/t"]}
            for k, name in enumerate(fields):
                run[name] = nodes[:, :, k]
            out[label] = run
        return out


def _step_times(scale: np.ndarray) -> np.ndarray:
    """The load steps' times in a collection: the scales if they increase, else 1, 2, …"""
    scale = np.asarray(scale, dtype=np.float64)
    if np.all(np.diff(scale) > 0):
        return scale
    return np.arange(1, len(scale) + 1, dtype=np.float64)


class _StaticFiles:
    """``write_vtk`` of ``StaticResult``."""

    def write_vtk(self, folder, stations: Optional[np.ndarray] = None) -> List[str]:
        """Write every run's equilibria to ``folder`` for ParaView, as ``flexwing static
        --vtk`` does: ``static_LABEL_0000.vtu``, … one per load step (points, lines,
        ``displacement``, ``twist`` as ``DynamicResult.write_vtk``) and ``static_LABEL.pvd``
        whose times are the load scales (or 1, 2, … when they do not increase). Returns the
        ``.pvd`` paths."""
        paths = []
        for r in self.runs:
            if len(r.scale) == 0:
                continue
            st = _stations(r.x[0], r.y[0]) if stations is None else stations
            paths.append(_vtk(folder, f"static_{r.label}", _step_times(r.scale), r.x, r.y, r.twist, st))
        return paths


class _ModeFiles:
    """``write_vtk`` of ``ModesResult``."""

    def write_vtk(self, folder) -> str:
        """Write the mode shapes to ``folder`` for ParaView, as ``flexwing modes --vtk`` does:
        ``modes_0000.vtu``, … (the undeformed nodes as points, the elements as lines, point
        data ``displacement`` = the mass-normalized shape ``(dx, dy, 0)`` (m per unit modal
        amplitude; ParaView's Warp By Vector draws it) and ``twist``) and ``modes.pvd`` whose
        times are the mode numbers. Returns the ``.pvd`` path."""
        return _vtk(folder, "modes", self.mode.astype(np.float64),
                    self.dx, self.dy, self.twist, self.x, modes=True)
