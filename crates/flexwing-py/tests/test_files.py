"""Result files read by independent readers: the `.npz` node histories of `flexwing dynamic
--format npz` and of `DynamicResult.save_npz`, read with NumPy and compared with the CLI's CSV
of the same run (parsed here with the csv module) and with the run's arrays."""

from __future__ import annotations

import csv
import pathlib
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


# --- VTK ------------------------------------------------------------------------------------

import xml.etree.ElementTree as ET

import meshio


def pvd(path):
    """(timestep, file) of a .pvd collection, parsed with the standard library's XML reader."""
    root = ET.parse(path).getroot()
    assert root.get("type") == "Collection"
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def check_frame(mesh, x, y, twist, reference_x, tol=0.0):
    """A .vtu read by meshio: the nodes at (x, y, 0), lines between consecutive nodes, and the
    point data `displacement` = (x, y, 0) − (station, 0, 0) and `twist`."""
    n = len(x)
    np.testing.assert_array_equal(mesh.points, np.column_stack([x, y, np.zeros(n)]))
    assert [c.type for c in mesh.cells] == ["line"]
    np.testing.assert_array_equal(mesh.cells[0].data, np.column_stack([np.arange(n - 1), np.arange(1, n)]))
    d = mesh.point_data["displacement"]
    np.testing.assert_allclose(d, np.column_stack([x - reference_x, y, np.zeros(n)]), rtol=0, atol=tol)
    np.testing.assert_array_equal(mesh.point_data["twist"], twist)


def test_dynamic_vtk_files_hold_the_run(cli, tmp_path):
    """`flexwing dynamic --vtk`: per model a .pvd whose times are the snapshot times, one .vtu
    per time with the nodes of the run (from the CLI's CSV) and the displacement from the
    case's undeformed stations (20 equal elements of 1 m: i / 20, exact in binary only to
    round-off, hence the 1e-15 m); Python's write_vtk of the same case writes the same frames
    (its stations from the arc length: 1e-14 m, the round-off of 20 hypot sums)."""
    run(cli, CASE, tmp_path / "cli", "--vtk")
    ref = csv_nodes(tmp_path / "cli" / "dynamic_nodes.csv")
    stations = np.arange(21) / 20.0
    for label, (t, x, y, twist) in ref.items():
        entries = pvd(tmp_path / "cli" / "vtk" / f"dynamic_{label}.pvd")
        np.testing.assert_array_equal([e[0] for e in entries], t)
        for k in (0, 100, 200):
            mesh = meshio.read(tmp_path / "cli" / "vtk" / entries[k][1])
            check_frame(mesh, x[k], y[k], twist[k], stations, tol=1e-15)
    result = flexwing.Case.load(CASE).dynamics()
    paths = result.write_vtk(tmp_path / "py")
    assert [pathlib.Path(p).name for p in paths] == [f"dynamic_{r.label}.pvd" for r in result.runs]
    for r in result.runs:
        s = r.snapshots
        entries = pvd(tmp_path / "py" / f"dynamic_{r.label}.pvd")
        assert entries == pvd(tmp_path / "cli" / "vtk" / f"dynamic_{r.label}.pvd")
        k = len(entries) - 1
        check_frame(meshio.read(tmp_path / "py" / entries[k][1]), s["x"][k], s["y"][k],
                    s["twist"][k], stations, tol=1e-14)


def test_static_and_modes_vtk_files(cli, tmp_path):
    """`flexwing static --vtk`: one frame per load step, timed by the sweep's increasing
    scales; `flexwing modes --vtk`: one frame per mode at the undeformed nodes, the shape as
    `displacement`; both against the Python results' arrays, and Python's write_vtk."""
    case = example("paper_static.toml")
    out = tmp_path / "static"
    subprocess.run([str(cli), "static", str(case), "--out", str(out), "--vtk"], check=True,
                   capture_output=True)
    result = flexwing.Case.load(case).statics()
    for r in result.runs:
        entries = pvd(out / "vtk" / f"static_{r.label}.pvd")
        np.testing.assert_array_equal([e[0] for e in entries], r.scale)
        stations = np.linspace(0.0, 1.0, r.x.shape[1])
        for k, (_, name) in enumerate(entries):
            check_frame(meshio.read(out / "vtk" / name), r.x[k], r.y[k], r.twist[k], stations,
                        tol=1e-15)
    py = result.write_vtk(tmp_path / "py-static")
    assert len(py) == len(result.runs)
    out = tmp_path / "modes"
    subprocess.run([str(cli), "modes", str(CASE), "--out", str(out), "--vtk"], check=True,
                   capture_output=True)
    m = flexwing.Case.load(CASE).modes()
    entries = pvd(out / "vtk" / "modes.pvd")
    assert [e[0] for e in entries] == list(m.mode.astype(float))
    for k, (_, name) in enumerate(entries):
        mesh = meshio.read(out / "vtk" / name)
        n = len(m.x)
        np.testing.assert_array_equal(mesh.points, np.column_stack([m.x, np.zeros(n), np.zeros(n)]))
        np.testing.assert_array_equal(mesh.point_data["displacement"],
                                      np.column_stack([m.dx[k], m.dy[k], np.zeros(n)]))
        np.testing.assert_array_equal(mesh.point_data["twist"], m.twist[k])
    assert pvd(m.write_vtk(tmp_path / "py-modes")) == entries
