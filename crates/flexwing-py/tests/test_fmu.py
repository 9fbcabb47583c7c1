"""The co-simulation FMU (FMI 2.0, `flexwing fmu` and `Case.fmu`) run by FMPy, an independent
FMI host from PyPI: its model description passes FMPy's validation, FMPy's simulation of it
matches `flexwing dynamic` on the same gust case (the gust in the case, and the gust fed as an
FMU input under either hold), and calls out of order or with unknown value references return
errors without harming the host process (run in a child process)."""

from __future__ import annotations

import os
import pathlib
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import flexwing

from conftest import ROOT, aileron_case, example, run_cli

fmpy = pytest.importorskip("fmpy")
import fmpy.validation  # noqa: E402


@pytest.fixture(scope="session")
def library() -> pathlib.Path:
    """The compiled FMU library: $FLEXWING_FMU_LIBRARY, else target/release/libflexwing_fmu.so
    (./test.sh builds it and sets the variable). Missing is a failure, not a skip."""
    path = pathlib.Path(
        os.environ.get("FLEXWING_FMU_LIBRARY", ROOT / "target" / "release" / "libflexwing_fmu.so")
    )
    if not path.exists():
        pytest.fail(
            f"the FMU library {path} is missing: build it with "
            "`cargo build --release -p flexwing-fmu` or set FLEXWING_FMU_LIBRARY"
        )
    return path


def gust_case() -> flexwing.Case:
    """Patil's wing in its 1−cos gust (examples/patil_gust.toml), 0.6 s, the reduced model on 6
    wet modes only (model 0)."""
    return flexwing.Case.load(example("patil_gust.toml")).replace(
        {"dynamic.end_time": 0.6, "dynamic.full": False, "dynamic.reduced": [6]}
    )


def calm_case() -> flexwing.Case:
    """The same wing and flight without the gust: the gust comes in through the FMU's input."""
    d = gust_case().to_dict()
    del d["aero"]["flight"]["gust"]
    return flexwing.Case(d)


@pytest.fixture(scope="module")
def reference(cli, tmp_path_factory):
    """`flexwing dynamic` on the gust case: its samples every 0.01 s."""
    tmp = tmp_path_factory.mktemp("reference")
    path = tmp / "gust.toml"
    path.write_text(gust_case().to_toml())
    samples = run_cli(cli, "dynamic", path, tmp / "out")["models"][0]["samples"]
    return {
        "time": np.array([s["t_s"] for s in samples]),
        "tip_y": np.array([s["tip_y_m"] for s in samples]),
        "tip_twist": np.array([s["tip_twist_rad"] for s in samples]),
        "root_bending_moment": np.array([s["root_bending_moment_n_m"] for s in samples]),
        "lift": np.array([s["lift_n"] for s in samples]),
    }


def test_the_cli_and_python_write_the_same_valid_fmu(cli, library, tmp_path):
    case = gust_case()
    path = tmp_path / "gust.toml"
    path.write_text(case.to_toml())
    from_cli = tmp_path / "cli.fmu"
    done = subprocess.run(
        [str(cli), "fmu", str(path), "-o", str(from_cli), "--library", str(library)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "inputs:  root_angle, speed, gust" in done.stdout
    summary = case.fmu(tmp_path / "py.fmu", library=library)
    assert summary["inputs"] == ["root_angle", "speed", "gust"]
    assert summary["outputs"] == [
        "tip_x", "tip_y", "tip_twist", "root_bending_moment", "root_torque", "lift",
    ]
    assert summary["model"] == "reduced-r6" and summary["platform"] == "linux64"
    assert fmpy.validation.validate_fmu(str(from_cli)) == []
    assert fmpy.validation.validate_fmu(str(tmp_path / "py.fmu")) == []
    md = fmpy.read_model_description(str(from_cli))
    assert md.guid == summary["guid"]
    assert md.coSimulation.modelIdentifier == "flexwing_fmu"
    units = {v.name: (v.causality, v.unit) for v in md.modelVariables}
    assert units["gust"] == ("input", "m/s")
    assert units["root_bending_moment"] == ("output", "N.m")
    assert units["hold"][0] == "parameter"
    start = {v.name: v.start for v in md.modelVariables}
    assert float(start["speed"]) == 25.0 and float(start["root_angle"]) == 0.0349
    with zipfile.ZipFile(from_cli) as z:
        names = set(z.namelist())
        assert "binaries/linux64/flexwing_fmu.so" in names
        # The case travels in the resources and is the case the FMU was made of.
        carried = flexwing.Case.from_toml(z.read("resources/case.toml").decode())
        assert carried.to_dict() == case.to_dict()


@pytest.fixture(scope="module")
def gust_fmu(library, tmp_path_factory):
    path = tmp_path_factory.mktemp("fmu") / "gust.fmu"
    gust_case().fmu(path, library=library)
    return path


def test_fmpy_simulation_of_the_case_gust_matches_flexwing_dynamic(gust_fmu, reference):
    result = fmpy.simulate_fmu(str(gust_fmu), stop_time=0.6, output_interval=0.01)
    np.testing.assert_allclose(result["time"], reference["time"], atol=1e-12)
    # The inputs keep their start values: the FMU integrates the case's own gust, the equations
    # of `flexwing dynamic`, restarting the integrator at each of its 60 communication points
    # (rtol 1e-6, atol 1e-8). The bound is 100 times the tolerance on the scale of each output,
    # as for the stepper (test_aero_stepper.py): 1e-4 m and rad, 1e-4 relative for the moment
    # and the lift.
    for key in ["tip_y", "tip_twist", "root_bending_moment", "lift"]:
        scale = 1.0 if key in ("tip_y", "tip_twist") else np.max(np.abs(reference[key]))
        error = np.max(np.abs(result[key] - reference[key]))
        assert error < 1e-4 * scale, (key, error)
    assert np.ptp(result["tip_y"]) > 0.01  # the gust moved the wing


H = 0.005  # s: the communication step of the input tests


@pytest.fixture(scope="module")
def fine_reference(cli, tmp_path_factory):
    """`flexwing dynamic` on the gust case, sampled every H."""
    tmp = tmp_path_factory.mktemp("fine")
    path = tmp / "gust.toml"
    path.write_text(gust_case().replace({"dynamic.output_step": H}).to_toml())
    samples = run_cli(cli, "dynamic", path, tmp / "out")["models"][0]["samples"]
    return {
        "time": np.array([s["t_s"] for s in samples]),
        "tip_y": np.array([s["tip_y_m"] for s in samples]),
        "root_bending_moment": np.array([s["root_bending_moment_n_m"] for s in samples]),
        "lift": np.array([s["lift_n"] for s in samples]),
    }


ZERO_HOLD_LOSES_THE_GUST_RATE = pytest.mark.xfail(
    strict=True,
    reason="since the gust's apparent mass (main d257455) the stepper's gust input carries its "
    "hold's rate: the zero hold's staircase has rate 0 inside each step and its jumps are not "
    "carried, so the FMU loses the apparent-mass force pi rho b^2 dv_g/dt (tip off by 7.6e-3 m, "
    "2.8e-3 m before); the linear hold carries it. Strict: the test says when this is fixed.",
)


@pytest.mark.parametrize("hold", [pytest.param("zero", marks=ZERO_HOLD_LOSES_THE_GUST_RATE), "linear"])
def test_a_gust_fed_through_the_input_is_the_case_gust_delayed_by_the_hold(
    library, fine_reference, tmp_path, hold
):
    ref = fine_reference
    path = tmp_path / "calm.fmu"
    summary = calm_case().fmu(path, library=library, hold=hold)
    assert summary["hold"] == hold
    # The case's gust: 1 m/s, 1−cos over 10 m at 25 m/s from t = 0.1 s (examples/patil_gust.toml).
    t = ref["time"]
    tau = np.clip((t - 0.1) * 25.0 / 10.0, 0.0, 1.0)
    gust = 0.5 * (1.0 - np.cos(2.0 * np.pi * tau))
    signal = np.array(list(zip(t, gust)), dtype=[("time", np.float64), ("gust", np.float64)])
    result = fmpy.simulate_fmu(
        str(path), stop_time=0.6, step_size=H, output_interval=H, input=signal
    )
    np.testing.assert_allclose(result["time"], t, atol=1e-12)
    # FMPy sets the input's value at each communication point t_k before the step from t_k.
    # The linear hold reaches it at t_k + H: the FMU sees the case's gust H late, linear between
    # samples; the zero hold keeps it over [t_k, t_k + H): to first order the gust H/2 late. So
    # the FMU's response is the reference's delayed by H (linear) or H/2 (zero, the mean of two
    # samples), up to second-order terms, bounded by H² max|y''| (second differences of the
    # reference), and the integration tolerance of the test above (1e-4 of the scale).
    for key in ["tip_y", "root_bending_moment"] + (["lift"] if hold == "linear" else []):
        y = ref[key]
        delayed = y[:-1] if hold == "linear" else 0.5 * (y[:-1] + y[1:])
        scale = 1.0 if key == "tip_y" else np.max(np.abs(y))
        bound = np.max(np.abs(np.diff(y, 2))) + 1e-4 * scale  # H² max|y''|
        error = np.max(np.abs(result[key][1:] - delayed))
        assert error < bound, (key, error, bound)
        # Without the delay the error is several times the bound: the comparison can fail.
        undelayed = np.max(np.abs(result[key] - y))
        assert undelayed > 3 * bound, (key, undelayed, bound)
    if hold == "zero":
        # The lift also follows the gust in force at once (its non-circulatory and quasi-steady
        # parts): between no delay and H late, within H max|lift'|.
        y = ref["lift"]
        bound = np.max(np.abs(np.diff(y))) + 1e-4 * np.max(np.abs(y))  # H max|lift'|
        assert np.max(np.abs(result["lift"] - y)) < bound


CHILD = r"""
import sys, fmpy
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi1 import FMICallException

path = sys.argv[1]
md = fmpy.read_model_description(path)
unzipped = fmpy.extract(path)
vr = {v.name: v.valueReference for v in md.modelVariables}

def slave():
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="probe")
    s.instantiate()
    return s

def refused(what, call):
    try:
        call()
    except FMICallException as e:
        print("REFUSED", what, e.status)
        return
    print("ACCEPTED", what)

s = slave()
refused("doStep before initialization", lambda: s.doStep(0.0, 0.01))
refused("getReal before initialization", lambda: s.getReal([vr["tip_y"]]))
refused("exitInitializationMode before enter", lambda: s.exitInitializationMode())
refused("terminate before initialization", lambda: s.terminate())
refused("setString unknown hold", lambda: s.setString([0], ["first"]))
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
refused("enterInitializationMode twice", lambda: s.enterInitializationMode())
s.exitInitializationMode()
refused("getReal unknown value reference", lambda: s.getReal([999]))
refused("setReal of an output", lambda: s.setReal([vr["tip_y"]], [1.0]))
refused("setReal negative speed", lambda: s.setReal([vr["speed"]], [-1.0]))
refused("setReal nan gust", lambda: s.setReal([vr["gust"]], [float("nan")]))
refused("getInteger", lambda: s.getInteger([0]))
refused("setBoolean", lambda: s.setBoolean([0], [True]))
refused("setString hold after initialization", lambda: s.setString([0], ["linear"]))
refused("doStep at the wrong time", lambda: s.doStep(1.0, 0.01))
refused("doStep with a negative step", lambda: s.doStep(0.0, -0.01))
refused("cancelStep", lambda: s.cancelStep())
refused("getFMUstate", lambda: s.getFMUstate())
s.doStep(0.0, 0.01)
y = s.getReal([vr["tip_y"]])[0]
print("STEPPED", y)
s.terminate()
refused("doStep after terminate", lambda: s.doStep(0.01, 0.01))
s.reset()
s.enterInitializationMode(); s.exitInitializationMode()
s.doStep(0.0, 0.01)
print("AFTER RESET", s.getReal([vr["tip_y"]])[0] == y)
s.terminate(); s.freeInstance()
try:
    bad = FMU2Slave(guid="{00000000-0000-0000-0000-000000000000}", unzipDirectory=unzipped,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bad")
    bad.instantiate()
    print("ACCEPTED wrong GUID")
except Exception as e:
    print("REFUSED wrong GUID", e)
print("DONE")
"""


def test_calls_out_of_order_are_errors_and_the_host_survives(gust_fmu):
    done = subprocess.run(
        [sys.executable, "-c", CHILD, str(gust_fmu)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    out = done.stdout
    assert done.returncode == 0, (done.returncode, out, done.stderr)
    assert "ACCEPTED" not in out, out
    assert out.count("REFUSED") == 19, out
    # Each refusal is fmi2Error (3) with a message naming the function and the reason.
    assert "[ERROR] fmi2DoStep: called in state instantiated" in out
    assert "[ERROR] fmi2GetReal: unknown value reference 999 (Real)" in out
    assert "[ERROR] fmi2SetReal: value reference 4 is the output tip_y" in out
    assert "[ERROR] fmi2DoStep: currentCommunicationPoint 1 is not the FMU's time" in out
    assert "[ERROR] fmi2Instantiate: fmuGUID" in out
    assert "[ERROR] fmi2SetReal: speed: must be non-negative" in out
    assert "[ERROR] fmi2DoStep: communicationStepSize: must be a finite positive" in out
    assert "[ERROR] fmi2SetString: hold: unknown value \"first\"" in out
    assert "AFTER RESET True" in out
    assert out.rstrip().endswith("DONE")
    assert "panicked" not in done.stderr


def test_a_control_surface_is_an_fmu_input_and_its_hinge_moment_an_output(library, tmp_path):
    """`delta[NAME]` and `hinge_moment[NAME]` come into the model description from the
    stepper's signal list, with their units; FMPy's run with the aileron ramped to 0.02 rad is
    the Python stepper's fed the same samples (a regression test of the FMI path: the same core,
    the same steps, so to 1e-9 of each output's scale). The physics of the stepped deflection is
    tested in test_aero_stepper.py (it settles at `flexwing static`'s equilibrium)."""
    d = aileron_case(10.0, 0.0)
    d["dynamic"] = {"end_time": 1.0, "output_step": 0.05}
    case = flexwing.Case(d)
    inputs, outputs = ["delta[aileron]"], ["tip_y", "lift", "hinge_moment[aileron]"]
    path = tmp_path / "aileron.fmu"
    summary = case.fmu(path, library=library, inputs=inputs, outputs=outputs, hold="linear")
    assert summary["inputs"] == inputs and summary["outputs"] == outputs
    assert fmpy.validation.validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    units = {v.name: (v.causality, v.unit) for v in md.modelVariables}
    assert units["delta[aileron]"] == ("input", "rad")
    assert units["hinge_moment[aileron]"] == ("output", "N.m")
    h = 0.05
    t = np.arange(0.0, 1.0 + h / 2, h)
    delta = 0.02 * np.clip(t / 0.1, 0.0, 1.0)
    signal = np.array(
        list(zip(t, delta)), dtype=[("time", np.float64), ("delta[aileron]", np.float64)]
    )
    result = fmpy.simulate_fmu(
        str(path), stop_time=1.0, step_size=h, output_interval=h, input=signal
    )
    stepper = case.stepper(inputs=inputs, outputs=outputs, hold="linear")
    expected = [stepper.outputs]
    for k in range(len(t) - 1):
        stepper.step(h, {"delta[aileron]": delta[k]})
        expected.append(stepper.outputs)
    for key in outputs:
        y = np.array([e[key] for e in expected])
        assert np.max(np.abs(result[key] - y)) <= 1e-9 * np.max(np.abs(y)), key
    assert result["lift"][-1] > 0.1 and result["hinge_moment[aileron]"][-1] < 0.0
