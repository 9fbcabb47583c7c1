"""Result files read by independent readers: the `.npz` node histories of `flexwing dynamic
--format npz` and of `DynamicResult.save_npz`, read with NumPy and compared with the CLI's CSV
of the same run (parsed here with the csv module) and with the run's arrays."""

from __future__ import annotations

import csv
import json
import subprocess

import numpy as np

import flexwing
from conftest import example

CASE = example("paper_sine.toml")


def run(cli, case, out, *options):
    done = subprocess.run(
        [str(cli), "dynamic", str(case), "--json", "--out", str(out), *options],
        capture_output=True, text=True, check=False,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def csv_nodes(path):
    """dynamic_nodes.csv as {model: (t, x, y, twist)} with arrays (S, nodes)."""
    rows = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.setdefault(r["model"], []).append(r)
    out = {}
    for label, rs in rows.items():
        nodes = max(int(r["node"]) for r in rs) + 1
        a = lambda k: np.array([float(r[k]) for r in rs]).reshape(-1, nodes)
        out[label] = (a("t_s")[:, 0], a("x_m"), a("y_m"), a("twist_rad"))
    return out


def test_cli_npz_holds_the_csv_values(cli, tmp_path):
    """The same case written as CSV and as .npz: every model, time and node equal (the CSV's
    numbers are shortest round-trip decimals, so equal to the last bit), with the documented
    names, units, shapes and the indices of the output times."""
    run(cli, CASE, tmp_path / "csv")
    doc = run(cli, CASE, tmp_path / "npz", "--format", "npz")
    assert doc["node_output"] == {"format": "npz", "times": 201, "of": 201, "every": 1}
    ref = csv_nodes(tmp_path / "csv" / "dynamic_nodes.csv")
    with np.load(tmp_path / "npz" / "dynamic_nodes.npz", allow_pickle=False) as d:
        assert list(d["models"]) == list(ref)
        assert list(d["fields"]) == ["x", "y", "twist"]
        assert list(d["units"]) == ["m", "m", "rad"]
        for label, (t, x, y, twist) in ref.items():
            nodes = d[f"{label}/nodes"]
            assert nodes.shape == (201, 21, 3) and nodes.dtype == np.float64
            np.testing.assert_array_equal(d[f"{label}/t"], t)
            np.testing.assert_array_equal(d[f"{label}/index"], np.arange(201))
            np.testing.assert_array_equal(nodes[:, :, 0], x)
            np.testing.assert_array_equal(nodes[:, :, 1], y)
            np.testing.assert_array_equal(nodes[:, :, 2], twist)
    assert not (tmp_path / "npz" / "dynamic_nodes.csv").exists()


def test_save_npz_writes_what_the_cli_writes(cli, tmp_path):
    """Python's save_npz of the same case: the same arrays as the CLI's file (regression across
    the front ends, same writer), and load_npz gives back the run's snapshots."""
    run(cli, CASE, tmp_path / "cli", "--format", "npz")
    result = flexwing.Case.load(CASE).dynamics()
    path = tmp_path / "py.npz"
    result.save_npz(path)
    with np.load(path) as mine, np.load(tmp_path / "cli" / "dynamic_nodes.npz") as theirs:
        assert sorted(mine.keys()) == sorted(theirs.keys())
        for k in theirs.keys():
            np.testing.assert_array_equal(mine[k], theirs[k], err_msg=k)
    back = flexwing.load_npz(path)
    for r in result.runs:
        for k in ("t", "index", "x", "y", "twist"):
            np.testing.assert_array_equal(back[r.label][k], r.snapshots[k], err_msg=k)
    # Nothing but the file: the temporary was renamed.
    assert sorted(p.name for p in tmp_path.iterdir() if p.is_file()) == ["py.npz"]


def test_node_times_thin_the_snapshots_of_both_front_ends(cli, tmp_path):
    """[output] node_times = 50 on 201 output times keeps every ⌈201/50⌉ = 5th from the first
    (41 of them) in Python's snapshots and in the CLI's file, and says so in the JSON."""
    case = flexwing.Case.load(CASE).replace({"output": {"node_times": 50, "format": "npz"}})
    toml = tmp_path / "case.toml"
    toml.write_text(case.to_toml())
    doc = run(cli, toml, tmp_path / "out")
    assert doc["node_output"] == {"format": "npz", "times": 41, "of": 201, "every": 5}
    full = case.dynamics().full
    np.testing.assert_array_equal(full.snapshots["index"], np.arange(0, 201, 5))
    np.testing.assert_array_equal(full.snapshots["t"], full.t[::5])
    back = flexwing.load_npz(tmp_path / "out" / "dynamic_nodes.npz")
    np.testing.assert_array_equal(back["full"]["index"], np.arange(0, 201, 5))
    # The last node of each snapshot is the tip of the tip history at that time.
    np.testing.assert_array_equal(back["full"]["y"][:, -1], full.tip_y[::5])
    every = case.replace({"output": {"node_times": "all"}}).dynamics().full
    assert every.snapshots["x"].shape == (201, 21)
