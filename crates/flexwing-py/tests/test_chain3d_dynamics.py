"""Dynamics of the 3-D chain (``beam.model = "chain3d"``) from Python: ``Case.dynamics()``
against the CLI's JSON of the same case (the same plan through ``flexwing::analysis``: equal to
round-off, 1e-12 relative as test_chain3d.py), the views (``to_pandas``, ``to_xarray``,
``plot``), and the VTK files of ``write_vtk`` and ``flexwing dynamic --vtk`` read back by meshio,
their section axes checked against SciPy's rotation of the reported rotation vectors (an
independent Rodrigues formula). The physics of the runs (planar limit, modal superposition,
energy balance) is checked by the CLI suite (``chain3d_dynamic_cmd``)."""

from __future__ import annotations

import pathlib
import subprocess
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import flexwing

from conftest import example, run_cli

RTOL = 1e-12
ATOL = 1e-14
CASE = example("swept_3d_wing.toml")


def close(a, b, atol=ATOL):
    np.testing.assert_allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=RTOL, atol=atol)


@pytest.fixture(scope="module")
def result() -> flexwing.Chain3dDynamicResult:
    return flexwing.Case.load(CASE).dynamics()


def test_dynamics_match_the_cli(cli, tmp_path, result):
    expected = run_cli(cli, "dynamic", CASE, tmp_path)
    assert isinstance(result, flexwing.Chain3dDynamicResult)
    assert result.status == expected["status"] == "complete"
    assert (result.n_elements, result.n_dofs) == (expected["n_elements"], expected["n_dofs"]) == (24, 72)
    assert result.extra == {}
    (run,) = result.runs
    e = expected["runs"][0]
    assert isinstance(run, flexwing.Chain3dDynamicRun) and run.extra == {}
    assert (run.label, run.integrator, run.gyroscopic) == (e["label"], e["integrator"], e["gyroscopic"])
    assert run.complete and run.stop is None
    for name in ("t", "tip_x", "tip_y", "tip_z", "tip_rotation", "kinetic", "strain", "total", "work", "balance_error"):
        close(getattr(run, name), e[name], atol=1e-12 if name == "balance_error" else ATOL)
    assert run.tip_rotation.shape == (51, 3)
    assert run.position.shape == (51, 25, 3) and run.rotation.shape == (51, 24, 3)
    close(run.position, [s["shape"]["position"] for s in e["snapshots"]])
    close(run.rotation, [s["shape"]["rotation"] for s in e["snapshots"]])
    # The tip of each snapshot is the tip history's.
    close(run.position[:, -1, 1], run.tip_y)
    assert run.energy_audit["max_error"] == pytest.approx(e["energy_audit"]["max_error"], rel=1e-9)
    assert run.stats == e["stats"]


def test_views(result):
    frame = result.to_pandas()
    assert list(frame.index.names) == ["model", "time"]
    assert {"tip_x", "tip_y", "tip_z", "total", "balance_error"} <= set(frame.columns)
    assert frame.attrs["units"]["tip_z"] == "m"
    np.testing.assert_array_equal(frame.loc["full"]["tip_z"].to_numpy(), result.full.tip_z)
    ds = result.to_xarray()
    assert ds["tip_rotation"].dims == ("model", "time", "component")
    assert ds["tip_rotation"].attrs["units"] == "rad"
    np.testing.assert_array_equal(ds["tip_y"].sel(model="full").to_numpy(), result.full.tip_y)
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    fig = result.plot()
    assert [a.get_ylabel() for a in fig.axes] == ["tip_y (m)", "tip_z (m)"]


def pvd(path):
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def test_vtk_frames_hold_the_run_and_the_section_axes(cli, tmp_path, result):
    """The CLI's and Python's files agree; each frame's points are the snapshot's nodes, its
    ``rotation`` the elements' rotation vectors (node k: element k − 1, the root: element 0) and
    ``t``, ``n``, ``c`` the columns of SciPy's matrix of that vector (to 1e-15: the round-off of
    two Rodrigues formulas on angles of order 1)."""
    subprocess.run([str(cli), "dynamic", str(CASE), "--out", str(tmp_path / "cli"), "--vtk"],
                   check=True, capture_output=True)
    run = result.full
    (path,) = result.write_vtk(tmp_path / "py")
    assert pathlib.Path(path).name == "dynamic_full.pvd"
    entries = pvd(path)
    assert entries == pvd(tmp_path / "cli" / "vtk" / "dynamic_full.pvd")
    np.testing.assert_array_equal([e[0] for e in entries], run.snapshot_t)
    reference = np.asarray(result.reference)
    for k in (0, 25, 50):
        for folder in (tmp_path / "py", tmp_path / "cli" / "vtk"):
            mesh = meshio.read(folder / entries[k][1])
            np.testing.assert_array_equal(mesh.points, run.position[k])
            assert [c.type for c in mesh.cells] == ["line"]
            np.testing.assert_array_equal(mesh.point_data["displacement"], run.position[k] - reference)
            per_node = run.rotation[k][np.maximum(np.arange(25) - 1, 0)]
            np.testing.assert_array_equal(mesh.point_data["rotation"], per_node)
            matrices = Rotation.from_rotvec(per_node).as_matrix()
            for j, axis in enumerate("tnc"):
                np.testing.assert_allclose(mesh.point_data[axis], matrices[:, :, j], rtol=0, atol=1e-15)


def test_modes_vtk(tmp_path):
    modes = flexwing.Case.load(CASE).modes()
    path = modes.write_vtk(tmp_path)
    entries = pvd(path)
    assert [e[0] for e in entries] == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    mesh = meshio.read(tmp_path / entries[1][1])
    np.testing.assert_array_equal(mesh.points, modes.position)
    np.testing.assert_array_equal(mesh.point_data["displacement"], modes.displacement[1])


def test_static_vtk(cli, tmp_path):
    """Python's static frames are the CLI's: the same collection, the same numbers."""
    subprocess.run([str(cli), "static", str(CASE), "--out", str(tmp_path / "cli"), "--vtk"],
                   check=True, capture_output=True)
    statics = flexwing.Case.load(CASE).statics()
    path = statics.write_vtk(tmp_path / "py")
    entries = pvd(path)
    assert entries == pvd(tmp_path / "cli" / "vtk" / "static_full.pvd")
    np.testing.assert_array_equal([e[0] for e in entries], statics.scale)
    for name in (entries[0][1], entries[-1][1]):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / "vtk" / name).read_text()
    mesh = meshio.read(tmp_path / "py" / entries[-1][1])
    np.testing.assert_array_equal(mesh.points, statics.position[-1])


def test_bad_3d_dynamic_input_names_the_key():
    text = CASE.read_text()
    with pytest.raises(flexwing.InputError, match=r"dynamic\.rtol"):
        flexwing.Case.from_toml(text.replace("rtol = 1e-5", "rtol = 2.0")).dynamics()
