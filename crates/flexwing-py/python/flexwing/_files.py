"""Result files from Python, written by the same Rust writers as the CLI's (the crate
``flexwing-io``): ``save_npz`` (the node histories, the layout of ``flexwing dynamic``'s
``dynamic_nodes.npz``) and ``load_npz`` to read one back. docs/python.md, "Files"."""

from __future__ import annotations

import os
from typing import Dict

import numpy as np

from . import _native

#: The fields of the planar chain's node histories, with their units.
PLANAR_FIELDS = (("x", "m"), ("y", "m"), ("twist", "rad"))


class _NodeFiles:
    """``save_npz`` for the results with node snapshots (``DynamicResult``,
    ``AeroDynamicResult``)."""

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
