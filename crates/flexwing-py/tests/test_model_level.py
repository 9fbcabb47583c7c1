"""The model level against independent numbers: the Jacobian against central differences of the
right-hand side, the energies against their closed forms (½ qᵀ K q with K diagonal, ½ ẋᵀ M(q) ẋ
with M from `mass_matrix`), the reduced model's linearization against the full model's modes,
and the stepper against the CLI's run of the same case (its loads as a table time history: what
`hold="linear"` does between calls)."""

from __future__ import annotations

import numpy as np
import pytest

import flexwing

from conftest import ROOT, run_cli

LOAD = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}


def beam(torsion=True):
    extra = dict(GJ=5.0, polar_inertia=0.01, polar_inertia_about="mass-centre", d0=0.02) if torsion else {}
    return flexwing.Beam(length=1.0, elements=8, EI=[80.0, 30.0], x=[0.0, 1.0], mass_per_length=0.2, **extra)


@pytest.mark.parametrize("which", ["full", "reduced"])
def test_jacobian_against_central_differences(which):
    """Central differences: truncation O(h^2 |f'''|) plus round-off eps |f| / h, at h = 1e-6
    about 1e-12 of the largest entry here. Measured 4.9e-13 (full), 2.8e-12 (reduced) of the
    largest entry; bound 1e-9 (a wrong term of the Jacobian is O(1) relative)."""
    full = flexwing.FullModel(beam())
    model = full if which == "full" else full.reduced(5)
    eom = model.equations([LOAD], scales=[0.7], gyroscopic="exact")
    rng = np.random.default_rng(3)  # explicit seed
    y = eom.state(rng.normal(scale=0.1, size=model.n_dofs), rng.normal(scale=0.5, size=model.n_dofs))
    J = eom.jacobian(0.0, y)
    h = 1e-6
    fd = np.column_stack([(eom.rhs(0.0, y + h * e) - eom.rhs(0.0, y - h * e)) / (2 * h) for e in np.eye(y.size)])
    assert np.abs(J - fd).max() <= 1e-9 * np.abs(J).max()


def test_energies_are_the_closed_forms():
    """Strain: the springs are linear in the joint rotations, so ½ qᵀ K q with the diagonal K
    the model returns; kinetic: ½ ẋᵀ M(q) ẋ with M(q) from mass_matrix (independent of the
    momentum recursion the equations use). Agreement to round-off: 1e-12 relative."""
    full = flexwing.FullModel(beam())
    eom = full.equations([LOAD])
    rng = np.random.default_rng(5)
    q, qdot = rng.normal(scale=0.2, size=full.n_dofs), rng.normal(scale=1.0, size=full.n_dofs)
    y = eom.state(q, qdot)
    kinetic, strain = eom.energies(y)
    K, M = full.stiffness_matrix(), full.mass_matrix(q)
    assert np.count_nonzero(K - np.diag(np.diag(K))) == 0
    assert strain == pytest.approx(0.5 * q @ K @ q, rel=1e-12)
    assert kinetic == pytest.approx(0.5 * qdot @ M @ qdot, rel=1e-12)
    np.testing.assert_allclose(eom.velocities(y), qdot, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(y[full.n_dofs:], M @ qdot, rtol=1e-12, atol=1e-14)


def test_reduced_linearization_gives_the_full_models_modes():
    """About the undeformed state the reduced model on modes 1-4 is exact: its linearized
    frequencies are those modes' (eigenvalues of an 8×8 Jacobian against the full model's
    symmetric eigenproblem: measured 7e-16 relative; bound 1e-9)."""
    full = flexwing.FullModel(beam())
    reduced = full.reduced(4)
    A = reduced.equations([LOAD], scales=[0.0]).jacobian(0.0, np.zeros(8))
    omega = np.sort(np.abs(np.linalg.eigvals(A).imag))[::2]
    np.testing.assert_allclose(omega, full.modes(4).omega, rtol=1e-9)


def test_the_stepper_follows_the_cli_run_of_the_same_loads(cli, tmp_path):
    """A force factor set at each call (hold="linear": a ramp from the previous call's) is the
    case file's "table" time history through the same points; the CLI integrates it in one
    run, the stepper restarts at each of 40 calls. Both with Radau at rtol 1e-9, atol 1e-11, so
    each is within ~1e-8 m of the exact tip: measured difference 7.3e-10 m; bound 1e-7 m, 1e-6
    of the 0.13 m motion. With hold="zero" the force jumps at each call instead: measured
    difference 6.1e-3 m, which shows the check can fail."""
    times = np.linspace(0.0, 0.2, 41)
    factors = np.sin(20.0 * times) + 0.5 * times
    case = flexwing.Case(
        beam={"length": 1.0, "elements": 10, "section": {"EI": 50.0, "mass_per_length": 0.2}},
        loads=[{**LOAD, "time": {"type": "table", "t": times.tolist(), "value": factors.tolist()}}],
        dynamic={"end_time": 0.2, "output_step": 0.005, "integrator": "radau", "rtol": 1e-9, "atol": 1e-11},
    )
    path = tmp_path / "stepper.toml"
    path.write_text(case.to_toml())
    expected = run_cli(cli, "dynamic", path, tmp_path)["models"][0]
    np.testing.assert_allclose(expected["t_s"], times, atol=1e-15)

    def tips(hold):
        model = flexwing.FullModel(flexwing.Beam.from_dict(case.to_dict()["beam"]))
        stepper = model.stepper([LOAD], scales=[factors[0]], integrator="radau", rtol=1e-9, atol=1e-11, hold=hold)
        out = [stepper.tip[1]]
        for t, f in zip(times[1:], factors[1:]):
            assert stepper.step(0.005, [f]) == pytest.approx(t, abs=1e-12)
            out.append(stepper.tip[1])
        return np.array(out)

    linear = tips("linear")
    motion = np.ptp(expected["tip"]["y_m"])
    assert motion > 0.01
    assert np.abs(linear - expected["tip"]["y_m"]).max() < 1e-7
    zero = tips("zero")
    assert np.abs(zero - expected["tip"]["y_m"]).max() > 1e-4


def test_a_stepper_failure_says_when_and_keeps_the_state():
    model = flexwing.FullModel(beam(torsion=False))
    stepper = model.stepper([LOAD], scales=[0.0], max_steps=3)
    before = stepper.y.copy()
    with pytest.raises(flexwing.SolverError) as info:
        stepper.step(0.5, [1.0])
    assert 0.0 <= info.value.stop["error"]["time"] < 0.5
    assert stepper.t == 0.0 and np.array_equal(stepper.y, before)


def test_rotary_inertia_in_bending():
    """Elements as rigid bars (``element_inertia="bar"``) add ``m l^2/12`` per element to the mass
    matrix in absolute angles, ``T^T diag(J_b) T`` in joint coordinates (T lower-triangular ones):
    checked against that closed form (round-off bound 1e-12 relative). The section's rotary
    inertia ``rotary_inertia = m r^2`` (r = 0.05 m) makes the chain a Rayleigh beam: its first five
    frequencies at n = 256 against the reference of crates/flexwing/tests/data/rayleigh_beam
    (exact frequency equation). Measured (Rust, tests/suite/rotary_inertia.rs): at most 1.1e-5 relative,
    falling as 1/n^2; bound 2e-5."""
    n, m, length = 8, 0.2, 1.0
    point = flexwing.FullModel(flexwing.Beam(length=length, elements=n, EI=50.0, mass_per_length=m))
    bars_beam = flexwing.Beam(length=length, elements=n, EI=50.0, mass_per_length=m, element_inertia="bar")
    bars = flexwing.FullModel(bars_beam)
    ell = length / n
    assert np.allclose(bars_beam.bending_inertias, m * ell**3 / 12.0, rtol=1e-14, atol=0.0)
    q = np.linspace(-0.2, 0.3, n)
    T = np.tril(np.ones((n, n)))
    expected = point.mass_matrix(q) + T.T @ (m * ell * ell**2 / 12.0 * np.eye(n)) @ T
    assert np.abs(bars.mass_matrix(q) - expected).max() <= 1e-12 * np.abs(expected).max()

    reference = np.loadtxt(
        ROOT / "crates/flexwing/tests/data/rayleigh_beam/table4_r005.csv", delimiter=",", skiprows=1, usecols=1
    )
    rayleigh = flexwing.FullModel(
        flexwing.Beam(length=1.0, elements=256, EI=50.0, mass_per_length=m, rotary_inertia=m * 0.05**2)
    )
    omega = rayleigh.modes(5).omega
    assert np.abs(omega / reference[:5] - 1.0).max() < 2e-5
