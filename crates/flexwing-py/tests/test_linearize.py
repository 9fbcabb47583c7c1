"""The linear state-space models (`flexwing linearize`, `Case.linearize`) on Patil's wing
(examples/patil_linearize.toml):

* the CLI's `.mat` read back by `scipy.io.loadmat` and its `.npz` by `numpy.load` hold the
  matrices, names and units of its JSON document (exactly: all three carry the same doubles);
* `Case.linearize()` gives the CLI's numbers (same plan and run; 1e-12 relative as
  test_aero_against_cli.py);
* `to_control()` and `to_scipy()` against python-control and SciPy (independent
  implementations): poles, names, and the frequency response helper against
  `control.frequency_response`;
* the poles are those of the basis change (velocities against momenta: similar matrices);
* bad input: unknown names, a speed past divergence, a bad basis.

The physics (poles = flutter eigenvalues, frequency response = non-linear harmonic response,
static gain = non-linear statics) is validated in the Rust suites (aero_linearize.rs,
linearize_cmd.rs)."""

from __future__ import annotations

import numpy as np
import pytest

import flexwing

from conftest import example, run_cli

CASE = example("patil_linearize.toml")
RTOL = 1e-12


def pole_distance(a, b) -> float:
    """The largest distance from a pole of either set to the nearest of the other (sorting
    complex numbers pairs conjugates and near-equal real parts differently on round-off)."""
    d = np.abs(np.asarray(a)[:, None] - np.asarray(b)[None, :])
    return max(d.min(axis=1).max(), d.min(axis=0).max())


@pytest.fixture(scope="module")
def result():
    return flexwing.Case.load(str(CASE)).linearize()


def test_mat_and_npz_hold_the_json(cli, tmp_path):
    scipy_io = pytest.importorskip("scipy.io")
    doc = run_cli(cli, "linearize", CASE, tmp_path / "out")
    assert doc["status"] == "complete"
    for m in doc["models"]:
        label = m["summary"]["model"]
        ss = m["state_space"]
        mat = scipy_io.loadmat(tmp_path / "out" / f"linear_{label}.mat")
        npz = np.load(tmp_path / "out" / f"linear_{label}.npz")
        assert "allow_pickle" not in str(npz)  # plain arrays, no pickles needed
        for key in "ABCD":
            expected = np.array(ss[key.lower()], dtype=float)
            np.testing.assert_array_equal(mat[key], expected)
            np.testing.assert_array_equal(npz[key], expected)
        for what in ("state", "input", "output"):
            signals = ss[what + "s"]
            for part in ("name", "unit"):
                expected = [s[part] for s in signals]
                # loadmat: a cell column of 1-element string arrays.
                assert [c[0][0] for c in mat[f"{what}_{part}s"]] == expected
                assert list(npz[f"{what}_{part}s"]) == expected
        poles = np.array([complex(re, im) for re, im in m["poles"]])
        np.testing.assert_array_equal(mat["poles"].ravel(), poles)
        np.testing.assert_array_equal(npz["poles"], poles)
        assert float(mat["speed"][0, 0]) == doc["speed_m_s"] == 20.0


def test_python_matches_the_cli(cli, tmp_path, result):
    doc = run_cli(cli, "linearize", CASE, tmp_path / "out")
    assert [r.label for r in result.runs] == [m["summary"]["model"] for m in doc["models"]]
    assert result.speed == 20.0 and result.status == "complete"
    for run, m in zip(result.runs, doc["models"]):
        ss = m["state_space"]
        for key in "ABCD":
            np.testing.assert_allclose(getattr(run, key), np.array(ss[key.lower()]), rtol=RTOL, atol=1e-14)
        assert run.state_names == [s["name"] for s in ss["states"]]
        assert run.input_units == [s["unit"] for s in ss["inputs"]]
        assert run.output_names == ["tip_y", "tip_twist", "lift", "root_shear", "tip_acceleration"]
        assert run.output_units == ["m", "rad", "N", "N", "m/s²"]
        assert run.extra == {}


def test_to_control_and_to_scipy(result):
    control = pytest.importorskip("control")
    signal = pytest.importorskip("scipy.signal")
    run = result.run("reduced-r4")
    sys = run.to_control()
    assert sys.input_labels == run.input_names
    assert sys.output_labels == run.output_names
    assert sys.state_labels == run.state_names
    # python-control's poles (LAPACK) against flexwing's (nalgebra's Schur form): the lag
    # states' poles are well separated, 1e-8 relative to the largest modulus is round-off.
    assert len(run.poles) == len(sys.poles()) == run.A.shape[0]
    assert pole_distance(run.poles, sys.poles()) <= 1e-8 * np.abs(run.poles).max()
    omega = np.array([0.5, 2.0, 10.0, 30.0])
    g = run.frequency_response(omega)
    resp = control.frequency_response(sys, omega)
    # python-control's (outputs, inputs, ω) against ours (ω, outputs, inputs); both solve the
    # same linear systems, 1e-9 relative to each entry's magnitude is round-off.
    theirs = np.moveaxis(np.asarray(resp.complex), -1, 0)
    np.testing.assert_allclose(g, theirs, rtol=1e-9, atol=1e-12 * np.abs(theirs).max())
    # SciPy's system holds the matrices (its freqresp goes through a transfer function of
    # degree 200, which overflows: python-control's above is the frequency check).
    lti = run.to_scipy()
    assert isinstance(lti, signal.StateSpace)
    np.testing.assert_array_equal(lti.A, run.A)
    np.testing.assert_array_equal(lti.D, run.D)
    np.testing.assert_allclose(
        run.frequency_response(omega, "gust", "tip_y")[:, 0, 0], g[:, 0, run.input_names.index("gust")]
    )
    # The static gain is the zero-frequency response.
    np.testing.assert_allclose(run.static_gain(), run.frequency_response([0.0])[0].real)


def test_momenta_and_velocities_have_the_same_poles(result):
    case = flexwing.Case.load(str(CASE))
    momenta = case.linearize(states="momenta")
    for a, b in zip(result.runs, momenta.runs):
        assert b.basis == "momenta" and a.basis == "velocities"
        # Similar matrices (T⁻¹ A T): the same eigenvalues to round-off of the largest.
        scale = np.abs(a.poles).max()
        assert pole_distance(a.poles, b.poles) <= 1e-8 * scale


def test_overrides_and_bad_input():
    case = flexwing.Case.load(str(CASE))
    r = case.linearize(speed=25.0, inputs=["gust[3]"], outputs=["lift"])
    assert r.speed == 25.0
    assert r.full.input_names == ["gust[3]"] and r.full.B.shape[1] == 1
    assert r.full.output_names == ["lift"] and r.full.C.shape[0] == 1
    with pytest.raises(flexwing.FlexwingError, match=r"linearize\.inputs\[1\]: unknown input 'wind'|linearize\.inputs\[1\]: unknown input \"wind\""):
        case.linearize(inputs=["gust", "wind"])
    with pytest.raises(flexwing.FlexwingError, match=r"linearize\.outputs\[0\]"):
        case.linearize(outputs=["y[99]"])
    with pytest.raises(flexwing.InputError, match="states"):
        case.linearize(states="positions")
    with pytest.raises(flexwing.ArgumentTypeError, match="inputs"):
        case.linearize(inputs=[1, 2])
    # Past the divergence speed (37.15 m/s): no stable equilibrium.
    with pytest.raises(flexwing.SolverError, match="no stable static equilibrium") as e:
        case.linearize(speed=40.0)
    assert e.value.result.runs[0].A is None
    stopped = case.linearize(speed=40.0, check=False)
    assert stopped.status != "complete"
    with pytest.raises(ValueError, match="no linear model"):
        stopped.full.to_control()
    with pytest.raises(KeyError, match="unknown name 'wind'"):
        r.full.frequency_response([1.0], inputs="wind")


def test_run_and_solve_many_take_linearize(result):
    """`Case.run("linearize")` and `solve_many(…, "linearize")` give `Case.linearize()`'s
    models (regression test of the one run path)."""
    case = flexwing.Case.load(str(CASE))
    by_run = case.run("linearize")
    np.testing.assert_array_equal(by_run.full.A, result.full.A)
    batch = flexwing.solve_many([case], "linearize")
    np.testing.assert_array_equal(batch[0].result.full.B, result.full.B)


def chain3d_text(tip_force: float = 24.0) -> str:
    """Patil's wing on the 3-D chain (examples/patil_3d_flutter.toml) at n = 8, bent by its tip
    force, linearized at 20 m/s (below its flutter speed)."""
    text = example("patil_3d_flutter.toml").read_text()
    text = text.replace("elements = 32", "elements = 8").replace("fy = 24.0", f"fy = {tip_force!r}")
    text = text[: text.index("[aero.sweep]")] + text[text.index("[flutter]") :]
    return text + (
        "\n[aero.flight]\nspeed = 20.0\n\n[linearize]\ninputs = [\"gust\", \"force[8]\"]\n"
        "outputs = [\"tip_y\", \"tip_z\", \"tip_twist\"]\n"
    )


def test_chain3d_linear_model_against_python_control_and_the_nonlinear_statics():
    """The 3-D chain's linear model: its poles against python-control's (LAPACK) and its
    static gain from the tip force against central differences of the non-linear 3-D static
    aeroelastic equilibria (`Case.statics()`, Newton on the full chain: another path than the
    Jacobian)."""
    control = pytest.importorskip("control")
    run = flexwing.Case.from_toml(chain3d_text()).linearize().runs[0]
    assert run.output_names == ["tip_y", "tip_z", "tip_twist"]
    assert run.A.shape[0] == len(run.state_names) == len(run.poles)
    sys = run.to_control()
    # Same tolerance as the planar model's check above (round-off of the largest modulus).
    assert pole_distance(run.poles, sys.poles()) <= 1e-8 * np.abs(run.poles).max()
    assert max(p.real for p in run.poles) < 0.0  # below the flutter speed: stable
    omega = np.array([0.5, 3.0, 20.0])
    theirs = np.moveaxis(np.asarray(control.frequency_response(sys, omega).complex), -1, 0)
    g = run.frequency_response(omega)
    np.testing.assert_allclose(g, theirs, rtol=1e-9, atol=1e-12 * np.abs(theirs).max())
    gain = run.static_gain()[:, run.input_names.index("force[8]")]
    # N: the central difference's error is O(h²): measured 1.6e-5 of tip_y's gain at h = 1 N,
    # 4.0e-6 at 0.5 N (second order).
    h = 0.5

    def tip(force):
        eq = flexwing.Case.from_toml(chain3d_text(force)).statics().equilibria[-1]
        return np.array([eq["tip"][1], eq["tip"][2], eq["tip_twist"]])

    fd = (tip(24.0 + h) - tip(24.0 - h)) / (2 * h)
    # tip_z's and tip_twist's gains are zero to round-off in both (below 1e-24: no drag in
    # strip theory, the force on the elastic axis of a wing with its mass centre there and no
    # root angle): the atol is round-off of 1 m/N.
    np.testing.assert_allclose(gain, fd, rtol=5e-5, atol=1e-12)
