"""NumPy input of every layout and dtype gives the same numbers as a plain float64 array (the
input is converted and copied before any arithmetic: no strided view reaches nalgebra, whose
arithmetic on such views writes out of bounds, nalgebra issue #1616); bad dtypes, shapes and
values are refused with the argument named. Output arrays are new, C-ordered float64 arrays
owned by Python."""

from __future__ import annotations

import numpy as np
import pytest

import flexwing

LOAD = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}


@pytest.fixture(scope="module")
def equations():
    beam = flexwing.Beam(length=1.0, elements=6, EI=50.0, mass_per_length=0.2, GJ=5.0, polar_inertia=0.01, polar_inertia_about="mass-centre", d0=0.02)
    return flexwing.FullModel(beam).equations([LOAD])


@pytest.fixture(scope="module")
def state(equations):
    rng = np.random.default_rng(7)  # explicit seed
    return rng.normal(scale=0.1, size=2 * equations.n_dofs)


def layouts(y):
    """The same values as: a list, C- and F-ordered arrays, a strided view, a reversed view, a
    slice of a 2-D F-ordered array, float32 (rounded), int (rounded), big-endian float64."""
    n = y.size
    wide = np.zeros((n, 3), order="F")
    wide[:, 1] = y
    padded = np.zeros(2 * n)
    padded[::2] = y
    return {
        "list": (y.tolist(), y),
        "C": (np.ascontiguousarray(y), y),
        "F": (np.asfortranarray(y), y),
        "strided": (padded[::2], y),
        "reversed": (y[::-1].copy()[::-1], y),
        "column of F 2-D": (wide[:, 1], y),
        "float32": (y.astype(np.float32), y.astype(np.float32).astype(np.float64)),
        "int": (np.round(y * 100).astype(np.int64), np.round(y * 100)),
        "big-endian": (y.astype(">f8"), y),
        "read-only": (np.frombuffer(y.tobytes()), y),
    }


def test_every_layout_and_dtype_gives_the_float64_result(equations, state):
    for name, (given, as_float64) in layouts(state).items():
        expected = equations.rhs(0.0, np.array(as_float64, dtype=np.float64))
        got = equations.rhs(0.0, given)
        np.testing.assert_array_equal(got, expected, err_msg=name)
        np.testing.assert_array_equal(equations.jacobian(0.0, given), equations.jacobian(0.0, as_float64), err_msg=name)


def test_inputs_are_not_modified_and_outputs_are_fresh(equations, state):
    given = state.copy()
    out1 = equations.rhs(0.0, given)
    out2 = equations.rhs(0.0, given)
    assert np.array_equal(given, state)
    assert out1 is not out2 and not np.shares_memory(out1, out2)
    out1[:] = 0.0
    assert not np.array_equal(out2, out1)
    jac = equations.jacobian(0.0, given)
    assert jac.flags.c_contiguous and jac.flags.owndata is not None and jac.dtype == np.float64


def test_matrices_are_row_major_as_numpy_expects(equations):
    """M(q) of the full model is symmetric, K diagonal with the spring stiffnesses in order: a
    transposed copy would show as an asymmetric or reordered matrix here."""
    beam = flexwing.Beam(length=1.0, elements=5, EI=[80.0, 40.0], x=[0.0, 1.0], mass_per_length=0.2)
    full = flexwing.FullModel(beam)
    q = np.linspace(0.1, 0.5, 5)
    m = full.mass_matrix(q)
    np.testing.assert_allclose(m, m.T, rtol=1e-13, atol=1e-16)
    np.testing.assert_array_equal(np.diag(full.stiffness_matrix()), beam.bending_stiffness)
    assert beam.bending_stiffness[0] > beam.bending_stiffness[-1]  # EI falls along the span


@pytest.mark.parametrize(
    "bad, cls, field",
    [
        # Each entry builds the bad state for a model of n_dofs coordinates (state: 2 n_dofs).
        (lambda n: np.zeros(5), flexwing.InputError, "y"),
        (lambda n: np.zeros((2, n)), flexwing.InputError, "y"),
        (lambda n: np.zeros(2 * n, dtype=np.complex128), flexwing.ArgumentTypeError, "y"),
        (lambda n: np.zeros(2 * n, dtype=bool), flexwing.ArgumentTypeError, "y"),
        (lambda n: np.array(["a"] * (2 * n)), flexwing.ArgumentTypeError, "y"),
        (lambda n: np.array([object()] * (2 * n)), flexwing.ArgumentTypeError, "y"),
        (lambda n: np.r_[np.zeros(11), np.nan, np.zeros(2 * n - 12)], flexwing.InputError, "y[11]"),
        (lambda n: np.r_[np.zeros(3), -np.inf, np.zeros(2 * n - 4)], flexwing.InputError, "y[3]"),
        (lambda n: None, flexwing.ArgumentTypeError, "y"),
    ],
    ids=["short", "2-D", "complex", "bool", "str", "object", "NaN", "-inf", "None"],
)
def test_bad_arrays_are_refused_naming_the_argument(equations, bad, cls, field):
    with pytest.raises(cls) as info:
        equations.rhs(0.0, bad(equations.n_dofs))
    assert info.value.field == field


def test_beam_tables_accept_any_layout():
    x = np.linspace(0.0, 1.0, 5)
    ei = 50.0 + 10.0 * x
    reference = flexwing.Beam(length=1.0, elements=8, EI=ei, x=x, mass_per_length=0.2)
    for given_x, given_ei in [
        (x.tolist(), ei.tolist()),
        (x.astype(np.float32), ei.astype(np.float32)),
        (np.asfortranarray(x), ei[::-1][::-1]),
        (np.vstack([x, x]).T[:, 0], np.vstack([ei, ei]).T[:, 1]),
    ]:
        beam = flexwing.Beam(length=1.0, elements=8, EI=given_ei, x=given_x, mass_per_length=0.2)
        np.testing.assert_allclose(beam.bending_stiffness, reference.bending_stiffness, rtol=1e-6)
