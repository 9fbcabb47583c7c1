"""Everything that travels to a worker process pickles and comes back equal: cases (as their
TOML text, with the file name), results (plain objects of NumPy arrays), the model-level
objects (rebuilt from their inputs), batch items and their errors."""

from __future__ import annotations

import pickle

import numpy as np

import flexwing

from conftest import example


def roundtrip(x):
    return pickle.loads(pickle.dumps(x))


def same_dict(a, b):
    assert type(a) is type(b)
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            same_dict(a[k], b[k])
    elif isinstance(a, list):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            same_dict(x, y)
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b)
    else:
        assert a == b


def test_cases_pickle_with_their_file(sine_case):
    again = roundtrip(sine_case)
    assert again == sine_case
    assert again.file == sine_case.file
    assert again.to_dict() == sine_case.to_dict()


def test_results_pickle(sine_case, static_case):
    for result in [sine_case.modes(), static_case.statics(), sine_case.dynamics()]:
        again = roundtrip(result)
        assert type(again) is type(result)
        same_dict(again.to_dict(), result.to_dict())


def test_model_level_objects_pickle():
    beam = flexwing.Beam(length=2.0, stations=[0.0, 0.5, 1.0, 1.5, 2.0], EI=[60.0, 40.0], x=[0.0, 2.0], mass_per_length=0.3)
    full = flexwing.FullModel(beam)
    reduced = full.reduced([1, 3])
    for obj in [beam, full, reduced]:
        again = roundtrip(obj)
        assert type(again) is type(obj)
    assert np.array_equal(roundtrip(beam).bending_stiffness, beam.bending_stiffness)
    assert np.array_equal(roundtrip(full).stiffness_matrix(), full.stiffness_matrix())
    r2 = roundtrip(reduced)
    assert r2.modes == [1, 3] and np.array_equal(r2.basis, reduced.basis)


def test_batch_items_pickle_with_their_errors(sine_case):
    items = flexwing.solve_many([sine_case, {"beam": 1}], "modes")
    again = roundtrip(items)
    assert [i.status for i in again] == ["complete", "error"]
    assert isinstance(again[1].error, flexwing.CaseFileError)
    assert str(again[1].error) == str(items[1].error)
    assert np.array_equal(again[0].result.omega, items[0].result.omega)
