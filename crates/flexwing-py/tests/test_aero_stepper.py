"""`Case.stepper`: the aeroelastic response stepped per call (the core of the FMU)
against `flexwing dynamic` on the same case, and its errors. The library's own test
(analysis/aero/stepper_tests.rs) checks the inputs against the response to the same inputs as
time functions; this one checks the Python path and the case's own gust end to end."""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexwing

from conftest import aileron_case, example, run_cli


@pytest.fixture(scope="module")
def gust_case(tmp_path_factory):
    """Patil's wing in its 1−cos gust (examples/patil_gust.toml), 0.6 s, the full model only."""
    case = flexwing.Case.load(example("patil_gust.toml")).replace(
        {"dynamic.end_time": 0.6, "dynamic.reduced": []}
    )
    path = tmp_path_factory.mktemp("case") / "gust.toml"
    path.write_text(case.to_toml())
    return case, path


def test_stepping_the_case_matches_flexwing_dynamic(cli, gust_case, tmp_path):
    case, path = gust_case
    expected = run_cli(cli, "dynamic", path, tmp_path)["models"][0]["samples"]
    stepper = case.stepper()
    assert stepper.input_names == ["root_angle", "speed", "gust"]
    assert stepper.inputs == {"root_angle": 0.0349, "speed": 25.0, "gust": 0.0}
    assert stepper.units["root_bending_moment"] == "N·m" and stepper.units["gust"] == "m/s"
    got = []
    for k, sample in enumerate(expected):
        assert math.isclose(stepper.t, sample["t_s"], abs_tol=1e-12)
        got.append(stepper.outputs)
        if k + 1 < len(expected):
            stepper.step(expected[k + 1]["t_s"] - sample["t_s"])
    # Both runs integrate the same equations at rtol 1e-6, atol 1e-8 rad; the stepper restarts
    # the integrator at each of its 60 intervals. The bounds are 100 times the tolerance on the
    # scale of each output: 1e-4 m and rad (the tip moves ~0.1 m), 1e-4 relative for the
    # moment and the lift.
    for key, cli_key, scale in [
        ("tip_y", "tip_y_m", 1.0),
        ("tip_twist", "tip_twist_rad", 1.0),
        ("root_bending_moment", "root_bending_moment_n_m", max(abs(s["root_bending_moment_n_m"]) for s in expected)),
        ("lift", "lift_n", max(abs(s["lift_n"]) for s in expected)),
    ]:
        a = np.array([g[key] for g in got])
        b = np.array([s[cli_key] for s in expected])
        assert np.max(np.abs(a - b)) < 1e-4 * scale, (key, np.max(np.abs(a - b)))
    tip = np.array([g["tip_y"] for g in got])
    assert tip.max() - tip.min() > 0.01  # the gust moved the wing
    assert stepper.status["status"] == "complete"
    assert stepper.energy_audit["max_error"] < stepper.energy_audit["limit"]
    assert stepper.stats["calls"] == len(expected) - 1


def test_inputs_move_the_wing_and_errors_name_what_is_wrong(gust_case):
    case, _ = gust_case
    stepper = case.stepper(inputs=["gust", "force[16]"], outputs=["tip_y", "lift"], hold="zero")
    before = stepper.outputs
    stepper.step(0.01, {"gust": 1.0, "force[16]": 10.0})
    after = stepper.outputs
    assert after["lift"] > before["lift"] and after["tip_y"] > before["tip_y"]
    assert stepper.inputs == {"gust": 1.0, "force[16]": 10.0}
    t = stepper.t
    cases = [
        (lambda: stepper.step(0.01, {"gusts": 1.0}), "unknown input \"gusts\""),
        (lambda: stepper.step(-0.01), "dt: must be a finite positive interval"),
        (lambda: stepper.step(0.01, {"gust": float("nan")}), "gust: must be finite"),
        (lambda: case.stepper(inputs=["gust[3]"]), "inputs[0]: gust[3] is an input of the linear model only"),
        (lambda: case.stepper(outputs=["root_shear"]), "outputs[0]: root_shear is an output of the linear model only"),
        (lambda: case.stepper(inputs=["force[17]"]), "inputs[0]: node 17 is out of range"),
        (lambda: case.stepper(hold="first"), "hold: unknown value"),
        (lambda: case.stepper(model=3), "model: is 3 but the plan has 1 model(s)"),
        (lambda: flexwing.Case.load(example("paper_sine.toml")).stepper(), "aero: missing"),
    ]
    for call, message in cases:
        with pytest.raises(flexwing.InputError) as e:
            call()
        assert message in str(e.value), str(e.value)
    # A failed call leaves the stepper as it was.
    assert stepper.t == t and stepper.inputs == {"gust": 1.0, "force[16]": 10.0}


def test_a_stepped_deflection_settles_at_the_static_equilibrium_of_flexwing_static(cli, tmp_path):
    """`delta[aileron]` as a stepper input: from the undeflected equilibrium, the aileron
    ramped to 0.02 rad over 0.1 s (linear hold) and held; after 20 s the outputs are those of
    `flexwing static` with `deflection = 0.02` (the CLI, steady aerodynamics: the steady state
    of every model). The wing's slowest pole at 10 m/s (an overdamped bending mode, from the
    linear model) sets what is left of the transient: the bound is 10 e^{Re(p) T} of each
    output's change plus 100 times the integration tolerance."""
    speed, delta, end = 10.0, 0.02, 20.0
    static = aileron_case(speed, delta, dynamic=False)
    static["aero"]["sweep"] = {"speeds": [speed]}
    path = tmp_path / "static.toml"
    path.write_text(flexwing.Case(static).to_toml())
    point = run_cli(cli, "static", path, tmp_path / "out")
    case = flexwing.Case(aileron_case(speed, 0.0))
    outputs = ["tip_y", "tip_twist", "lift", "hinge_moment[aileron]"]
    stepper = case.stepper(inputs=["delta[aileron]"], outputs=outputs)
    assert stepper.input_names == ["delta[aileron]"]
    assert stepper.units["delta[aileron]"] == "rad"
    assert stepper.units["hinge_moment[aileron]"] == "N·m"
    assert stepper.inputs == {"delta[aileron]": 0.0}
    before = stepper.outputs
    stepper.step(0.1, {"delta[aileron]": delta})
    while stepper.t < end - 1e-9:
        stepper.step(0.25)
    after = stepper.outputs
    assert stepper.status["status"] == "complete"
    slowest = max(p.real for p in case.linearize(inputs=["root_angle"]).runs[0].poles)
    assert slowest < 0.0
    decay = 10.0 * math.exp(slowest * end)
    p = point["models"][0]["points"][0]
    hinge = next(h for h in point["models"][0]["hinge_moments"] if h["surface"] == "aileron")
    expected = {
        "tip_y": p["tip_y_m"],
        "tip_twist": p["tip_twist_rad"],
        "lift": p["lift_n"],
        "hinge_moment[aileron]": hinge["hinge_moment_n_m"],
    }
    # TE down raises the lift (one sign of the convention).
    assert after["lift"] > before["lift"] + 0.5 * abs(expected["lift"])
    for key in outputs:
        change = abs(expected[key] - before[key])
        bound = decay * change + 1e-6 * max(abs(expected[key]), change)
        assert abs(after[key] - expected[key]) < bound, (key, after[key], expected[key], bound)
