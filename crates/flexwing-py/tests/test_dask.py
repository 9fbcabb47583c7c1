"""The Dask sweep: a static sweep mapped over a 2-worker `LocalCluster` (separate worker
processes, so cases go out and results and errors come back pickled) gives the serial results
exactly — the same binary runs the same deterministic solver on the same input, so equality is
bit for bit, not to a tolerance. A bad case in the sweep comes back as data (status "error" with
its exception), without stopping the others. The sweep is the one of examples/python/sweep_dask.py
(same functions), at a small size."""

from __future__ import annotations

import pathlib
import sys

import numpy as np
import pytest

import flexwing

from conftest import ROOT

# Not importorskip: a missing dask (requirements-test.txt) must fail the suite, not skip the test.
from dask import distributed  # noqa: E402

sys.path.insert(0, str(ROOT / "examples" / "python"))
import sweep_dask  # noqa: E402  (the example's functions: cases, chunks, the mapped task)


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


def compare(serial, distributed_items):
    assert len(serial) == len(distributed_items)
    for s, d in zip(serial, distributed_items):
        assert (s.index, s.status, s.message) == (d.index, d.status, d.message)
        assert type(s.error) is type(d.error)
        if s.result is None:
            assert d.result is None
            continue
        for a, b in zip(s.result.runs, d.result.runs):
            assert a.label == b.label and a.status == b.status
            for name in ["scale", "tip_x", "tip_y", "tip_twist", "x", "y", "q"]:
                np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
            for name, v in a.stats.items():
                np.testing.assert_array_equal(v, b.stats[name], err_msg=name)


def test_a_sweep_on_two_workers_equals_the_serial_sweep(client):
    cases = sweep_dask.sweep_cases(forces=np.linspace(20.0, 200.0, 6), stiffnesses=[40.0, 60.0])
    # One case that cannot run: its error must come back as data.
    cases.append(cases[0].replace({"beam.section.EI": -1.0}))
    serial = flexwing.solve_many(cases, "static")
    items = sweep_dask.run_sweep(client, cases, chunk=3)
    assert len(client.scheduler_info()["workers"]) == 2
    compare(serial, items)
    assert [i.status for i in items] == ["complete"] * 12 + ["error"]
    assert isinstance(items[-1].error, flexwing.CaseFileError)
    assert items[-1].error.field == "beam.section.EI"
    # The sweep found something: the tip rises with the force, falls with the stiffness.
    tips = np.array([i.result.full.tip_y[-1] for i in items[:-1]]).reshape(6, 2)
    assert (np.diff(tips[:, 0]) > 0).all() and (tips[:, 0] > tips[:, 1]).all()


def test_results_reduced_on_the_workers_equal_the_serial_ones(client):
    cases = sweep_dask.sweep_cases(forces=[50.0, 150.0], stiffnesses=[45.0, 55.0, 65.0])
    serial = [sweep_dask.tip(i) for i in flexwing.solve_many(cases, "static")]
    assert sweep_dask.run_sweep(client, cases, chunk=4, keep=sweep_dask.tip) == serial


def test_the_indices_follow_the_input_order_across_chunks(client):
    cases = sweep_dask.sweep_cases(forces=[10.0, 20.0, 30.0, 40.0, 50.0], stiffnesses=[50.0])
    items = sweep_dask.run_sweep(client, cases, chunk=2)
    assert [i.index for i in items] == list(range(5))
    tips = [i.result.full.tip_y[-1] for i in items]
    assert tips == sorted(tips)


def test_the_sweep_is_a_data_frame_indexed_by_the_swept_parameters(client):
    forces, stiffnesses = [50.0, 100.0, 150.0], [40.0, 60.0]
    frame = sweep_dask.sweep(client, forces, stiffnesses, chunk=2)
    assert list(frame.index.names) == ["F", "EI"] and list(frame.index) == [(f, e) for f in forces for e in stiffnesses]
    assert list(frame.columns) == ["status", "message", "tip_x", "tip_y"]
    serial = flexwing.solve_many(sweep_dask.sweep_cases(forces, stiffnesses), "static")
    for (f, ei), item in zip(frame.index, serial):
        assert frame.loc[(f, ei), "tip_y"] == item.result.full.tip_y[-1]  # bit for bit
    # The same table from whole results, through Batch.to_pandas.
    whole = sweep_dask.sweep(client, forces, stiffnesses, chunk=2, full_results=True)
    assert whole.index.equals(frame.index)
    assert whole["full.tip_y"].tolist() == frame["tip_y"].tolist()
    assert whole.attrs["units"]["full.tip_y"] == "m"


def test_the_example_script_runs(tmp_path):
    """examples/python/sweep_dask.py end to end at a small size (its own LocalCluster)."""
    import subprocess

    done = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "python" / "sweep_dask.py"), "--cases", "8", "--workers", "2", "--compare"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert "8 cases" in done.stdout and "equal to the serial sweep: yes" in done.stdout
    assert list(pathlib.Path(tmp_path).iterdir()) == [], "the example writes nothing"
