"""Trailing-edge control surfaces from Python (docs/aeroelastic-model.md §3b): the effectiveness
of a full-span aileron on a uniform clamped wing against the closed form of the torsion ODE,
computed here, at second order in the element count; the hinge moments as arrays; bad surfaces
named by their case-file key.

Closed form (steady strip theory): GJ ψ'' + q c e c_lα ψ = −q (c e c_lδ + c² c_mδ) δ,
ψ(0) = ψ'(L) = 0, gives the lift relative to the rigid wing
η = 1 + (e c_lδ + c c_mδ)/(e c_lδ) (tan λL/(λL) − 1), λ² = q c e c_lα/GJ, with Glauert's
c_lδ = 2(π − θ + sin θ), c_mδ = −½ sin θ (1 − cos θ) (about the quarter chord), cos θ = 1 − 2 x_h."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import flexwing
from flexwing import CaseFileError

from conftest import aileron_case, run_cli

L, C, GJ, RHO, X_EA, X_H, DELTA = 16.0, 1.0, 1.0e4, 0.0889, 0.35, 0.8, 1e-4


def wing(n, surfaces, speeds):
    return {
        "beam": {
            "length": L,
            "elements": n,
            "section": {
                "EI": 2.0e4,
                "GJ": GJ,
                "mass_per_length": 0.75,
                "polar_inertia": 0.1,
                "polar_inertia_about": "mass-centre",
            },
        },
        "aero": {
            "chord": C,
            "elastic_axis": X_EA,
            "density": RHO,
            "aerodynamics": {"model": "steady"},
            "surfaces": surfaces,
            "sweep": {"speeds": speeds},
        },
    }


def glauert():
    theta = np.arccos(1.0 - 2.0 * X_H)
    return 2.0 * (np.pi - theta + np.sin(theta)), -0.5 * np.sin(theta) * (1.0 - np.cos(theta))


def test_full_span_aileron_effectiveness_converges_to_the_torsion_ode():
    """Errors of η at U = 15, 20 m/s: measured 2.5e-2 → 1.5e-3 from n = 8 to 32 in the library
    test (aero_surfaces.rs); here n = 16 and 32: the ratio of the errors must show second order
    (between 1.8 and 2.2) and n = 32 lie within 2e-3."""
    cld, cmd = glauert()
    e, cla = (X_EA - 0.25) * C, 2.0 * np.pi
    speeds = [15.0, 20.0]
    aileron = [{"name": "aileron", "from": 0.0, "to": L, "hinge": X_H, "deflection": DELTA}]
    errors = []
    for n in (16, 32):
        run = flexwing.Case(wing(n, aileron, speeds)).statics().full
        assert run.hinge_moments.shape == (len(speeds), 1)
        err = 0.0
        for k, u in enumerate(speeds):
            q = 0.5 * RHO * u * u
            x = np.sqrt(q * C * e * cla / GJ) * L
            eta = 1.0 + (e * cld + C * cmd) / (e * cld) * (np.tan(x) / x - 1.0)
            err = max(err, abs(run.lift[k] / (q * C * cld * DELTA * L) - eta))
        errors.append(err)
    order = np.log2(errors[0] / errors[1])
    assert 1.8 < order < 2.2, (errors, order)
    assert errors[1] < 2e-3, errors


def test_hinge_moments_follow_the_surfaces():
    """Two surfaces, the inboard one undeflected: hinge moments `(points, 2)` in the order of
    `aerodynamics["surfaces"]`. With the elastic axis at 35 % the aileron's moment twists the
    wing nose-down (e c_lδ + c c_mδ < 0), root to tip: the aileron's hinge moment is negative (its
    lift pushes the trailing edge up) and grows less than q (4× from 10 to 20 m/s) as the twist
    unloads it; the flap's, from that nose-down angle of attack alone (c_hα < 0), is positive."""
    surfaces = [
        {"name": "flap", "from": 0.0, "to": 8.0, "hinge": 0.75},
        {"name": "aileron", "from": 12.0, "to": 16.0, "hinge": X_H, "deflection": 0.01},
    ]
    result = flexwing.Case(wing(16, surfaces, [10.0, 20.0])).statics()
    names = [s["name"] for s in result.aerodynamics["surfaces"]]
    assert names == ["flap", "aileron"]
    h = result.full.hinge_moments
    assert h.shape == (2, 2)
    assert h[0, 1] < 0 and 4.0 * h[0, 1] < h[1, 1] < h[0, 1]
    assert np.all(h[:, 0] > 0)
    assert not result.full.extra


@pytest.mark.parametrize(
    "key, value, field",
    [
        ("hinge", 1.0, "aero.surfaces[0].hinge"),
        ("to", 17.0, "aero.surfaces[0].to"),
        ("from", -1.0, "aero.surfaces[0].from"),
    ],
)
def test_bad_surfaces_name_the_key(key, value, field):
    surface = {"name": "aileron", "from": 12.0, "to": 16.0, "hinge": X_H}
    surface[key] = value
    with pytest.raises(CaseFileError) as info:
        flexwing.Case(wing(8, [surface], [10.0])).statics()
    assert info.value.field == field
    assert "\n" not in str(info.value)


# Deflection histories in a dynamic run (`deflection_change`, `deflection_function`).
# The stiffened Patil wing (EI ten times: its bending mode well damped by the air at 10 m/s).
STIFF = {"EI": 2.0e5}


def test_a_slow_ramp_of_the_aileron_ends_at_the_static_equilibrium(cli, tmp_path):
    """δ ramped from 0 to 0.02 rad over 1 s, then held to 8 s: the last sample is `flexwing
    static`'s equilibrium with `deflection = 0.02` (the CLI, steady aerodynamics), the aileron's
    hinge moment (`hinge_moments`, against the static run's) included. What is left
    of the transient after 7 s of hold is below 1e-3 of each output's change (measured 2.7e-4 on
    the tip: the wing's slowest poles decay at 0.43/s) and it shrinks: at 8 s it is below half
    of what it is at 4 s."""
    speed, delta = 10.0, 0.02
    static = aileron_case(speed, delta, dynamic=False, **STIFF)
    static["aero"]["sweep"] = {"speeds": [speed]}
    path = tmp_path / "static.toml"
    path.write_text(flexwing.Case(static).to_toml())
    static_model = run_cli(cli, "static", path, tmp_path / "out")["models"][0]
    point = static_model["points"][0]
    point["hinge_moment_n_m"] = next(
        h["hinge_moment_n_m"] for h in static_model["hinge_moments"] if h["surface"] == "aileron"
    )
    d = aileron_case(speed, 0.0, **STIFF)
    d["aero"]["surfaces"][1]["deflection_change"] = delta
    d["aero"]["surfaces"][1]["deflection_function"] = {"type": "ramp", "start": 0.0, "end": 1.0}
    d["dynamic"].update({"end_time": 8.0, "output_step": 0.1, "rtol": 1e-8, "reduced": []})
    run = flexwing.Case(d).dynamics().runs[0]
    assert run.status == "complete"
    assert run.hinge_moments.shape == (len(run.t), 2)
    keys = [("tip_y", "tip_y_m"), ("tip_twist", "tip_twist_rad"), ("lift", "lift_n")]
    for key, cli_key in keys + [(HINGE, "hinge_moment_n_m")]:
        y = output(run, key)
        change = abs(point[cli_key] - y[0])
        late, mid = abs(y[-1] - point[cli_key]), abs(y[len(y) // 2] - point[cli_key])
        assert late < 1e-3 * change and late < 0.5 * mid, (key, late, mid, change)
    assert run.lift[-1] > run.lift[0]  # TE down raises the lift


HINGE = "hinge_moment[aileron]"


def output(run, key):
    """The history of the output `key` (a linear model's output name) of a dynamic run."""
    if key == HINGE:
        return np.asarray(run.hinge_moments)[:, 1]  # the surfaces: flap, aileron
    return np.asarray(getattr(run, key))


def harmonic_error(amplitude, omega, keys=("tip_y", "tip_twist", "lift", HINGE)):
    """The steady-state response to δ = amplitude · sin(ωt) from the equilibrium against the
    linear model's `G_δ + iω G_δ̇ − ω² G_δ̈`: per output, the distance of the two phasors
    relative to the linear one's size. The start's transient (linear in the amplitude, and slow
    to die: the slowest poles decay at 0.43/s) is the linear model's own free response,
    computed by `scipy.signal.lsim` of `A, C`, and taken away before the phasor is fitted
    (least squares on sin, cos and a constant over t ≥ 1 s): what is left is the non-linear
    model's departure from the linear one. The non-linear run starts with its lag states steady
    for the flight at t = 0, δ̇(0) = Aω included (docs/aeroelastic-model.md): so does the
    linear one, `a(0) = −A_aa⁻¹ B_a u(0)` over the lag-state rows (without it the start differs
    by 1.5 % of the lift, linear in A). The free response is exact (lsim without inputs): a
    forced lsim would add its linear interpolation of the inputs, (ωh)²/12 = 1.3e-4 at ω = 8,
    h = 5 ms."""
    signal = pytest.importorskip("scipy.signal")
    d = aileron_case(10.0, 0.0, **STIFF)
    d["aero"]["surfaces"][1]["deflection_change"] = amplitude
    d["aero"]["surfaces"][1]["deflection_function"] = {"type": "sine", "omega": omega}
    d["dynamic"].update(
        {"end_time": 4.0, "output_step": 0.005, "rtol": 1e-9, "atol": 1e-11, "reduced": []}
    )
    case = flexwing.Case(d)
    run = case.dynamics().runs[0]
    assert run.status == "complete"
    names = ["delta[aileron]", "delta_rate[aileron]", "delta_acceleration[aileron]"]
    # The linear model is about the equilibrium at `deflection`: the history is its input.
    held = copy.deepcopy(d)
    for key in ("deflection_change", "deflection_function"):
        del held["aero"]["surfaces"][1][key]
    lin = flexwing.Case(held).linearize(inputs=names, outputs=list(keys)).runs[0]
    g = lin.frequency_response([omega], names, list(keys))[0]  # (outputs, inputs)
    t = np.asarray(run.t)
    lag = [i for i, n in enumerate(lin.state_names) if n.startswith("lag")]
    a, b = np.asarray(lin.A), np.asarray(lin.B)
    phasor = amplitude * np.array([1.0, 1j * omega, -(omega**2)])  # δ, δ̇, δ̈ = Im(û e^{iωt})
    x0 = np.zeros(a.shape[0])
    x0[lag] = -np.linalg.solve(a[np.ix_(lag, lag)], b[lag] @ phasor.imag)
    # The linear solution is the forced one, Im(X e^{iωt}) with X = (iω − A)⁻¹ B û, plus the
    # free response from x0 − Im X: lsim with no input (exact, no interpolation of inputs).
    forced = np.linalg.solve(1j * omega * np.eye(a.shape[0]) - a, b @ phasor)
    free = signal.StateSpace(a, np.zeros((a.shape[0], 1)), np.asarray(lin.C), np.zeros((len(keys), 1)))
    _, transients, _ = signal.lsim(free, np.zeros(len(t)), t, X0=x0 - forced.imag)
    window = t >= 1.0
    basis = np.column_stack(
        [np.sin(omega * t[window]), np.cos(omega * t[window]), np.ones(window.sum())]
    )
    errors = {}
    for j, key in enumerate(keys):
        linear = amplitude * (g[j, 0] + 1j * omega * g[j, 1] - omega**2 * g[j, 2])
        # δ = A sin ωt = Im(A e^{iωt}): y = Im(G A e^{iωt}) = Re(GA) sin ωt + Im(GA) cos ωt.
        y = output(run, key) - transients[:, j]
        c, *_ = np.linalg.lstsq(basis, y[window], rcond=None)
        errors[key] = abs(complex(c[0], c[1]) - linear) / abs(linear)
    return errors


@pytest.mark.parametrize("omega", [2.0, 8.0])
def test_a_harmonic_deflection_follows_the_linear_frequency_response(omega):
    """Amplitude and phase of the non-linear response to a harmonic aileron against the linear
    model's frequency response at the same speed. The difference is the linearization error
    (second order in δ: the lift's tilt by the deflection's own angle, the wing's geometric
    non-linearity): below 2e-4 of the phasor at δ = 0.01 rad (measured ≤ 5e-5 in the time
    domain; the aileron's hinge moment, the dynamic run's `hinge_moments` against the linear
    model's `hinge_moment[aileron]`: 1.5e-6 at ω = 2 and 4.3e-7 at ω = 8, four times less at
    half the amplitude), and at least 1.5 times smaller at half the amplitude (2 for an error of second
    order; 1.5 leaves room for the integration's own error, rtol 1e-9, which does not shrink
    with the amplitude)."""
    big = harmonic_error(0.01, omega)
    small = harmonic_error(0.005, omega)
    for key in big:
        assert big[key] < 2e-4, (key, big[key])
        assert small[key] < big[key] / 1.5, (key, small[key], big[key])


@pytest.mark.parametrize(
    "keys, field",
    [
        ({"deflection_change": 0.01}, "aero.surfaces[1].deflection_function"),
        ({"deflection_function": {"type": "ramp", "start": 0.0, "end": 1.0}}, "aero.surfaces[1].deflection_change"),
        (
            {"deflection_change": 2.0, "deflection_function": {"type": "ramp", "start": 0.0, "end": 0.5}},
            "aero.surfaces[1].deflection_change",
        ),
        (
            {"deflection_change": 0.01, "deflection_function": {"type": "ramp", "start": 0.5, "end": 0.1}},
            "aero.surfaces[1].deflection_function.end",
        ),
    ],
)
def test_bad_deflection_histories_name_the_key(keys, field):
    """Both keys or neither; |δ(t)| < π/2 over the run; a valid time function."""
    d = aileron_case(10.0, 0.0)
    d["aero"]["surfaces"][1].update(keys)
    with pytest.raises(CaseFileError) as info:
        flexwing.Case(d).dynamics()
    assert info.value.field == field, str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("run", ["statics", "flutter", "linearize"])
def test_runs_about_an_equilibrium_refuse_a_deflection_history(run):
    """A deflection's time history is a dynamic run's: the static, flutter and linear runs hold
    the surface at its `deflection` and refuse the history with an error naming the key (not
    ignore it); the dynamic run of the same case takes it."""
    d = aileron_case(10.0, 0.0)
    d["aero"]["surfaces"][1]["deflection_change"] = 0.01
    d["aero"]["surfaces"][1]["deflection_function"] = {"type": "ramp", "start": 0.0, "end": 0.5}
    d["aero"]["sweep"] = {"speeds": [10.0]}
    case = flexwing.Case(d)
    with pytest.raises(CaseFileError) as info:
        getattr(case, run)()
    assert info.value.field == "aero.surfaces[1].deflection_change", str(info.value)
    assert "holds the surface" in str(info.value) and "\n" not in str(info.value)
    d["dynamic"]["end_time"] = 0.05
    assert flexwing.Case(d).dynamics().runs[0].status == "complete"
