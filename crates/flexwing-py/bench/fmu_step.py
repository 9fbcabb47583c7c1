"""The co-simulation FMU's cost per communication step through FMPy (docs/performance.md, "The
aeroelastic stepper"): the FMU of examples/patil_gust.toml (the reduced model r = 6, then the
full model), FMPy's FMU2Slave: a first step of 10 ms, then 200 calls of `setReal` (the gust) and
`doStep` of 0.1 ms, three repeats, then 200 `getReal` of every output. Printed per call (µs):
setReal + doStep / getReal. Beside it the same calls of the Python stepper (`aero_stepper.py`'s
loop) in the same run, so the two are measured under the same load. Needs FMPy and the FMU
library (`cargo build --release -p flexwing-fmu`); run from the repository root:
`python crates/flexwing-py/bench/fmu_step.py [target/release/libflexwing_fmu.so]`."""
import os, sys, tempfile, time
import fmpy
from fmpy.fmi2 import FMU2Slave
import flexwing

library = sys.argv[1] if len(sys.argv) > 1 else "target/release/libflexwing_fmu.so"
case = flexwing.Case.load("examples/patil_gust.toml")
calls, h = 200, 1e-4
with tempfile.TemporaryDirectory() as tmp:
    for model, label in [(1, "reduced r = 6"), (0, "full n = 32")]:
        path = os.path.join(tmp, f"wing{model}.fmu")
        case.fmu(path, library=library, model=model)
        md = fmpy.read_model_description(path)
        vr = {v.name: v.valueReference for v in md.modelVariables}
        outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
        unzipped = fmpy.extract(path)
        fmu_rows, stepper_rows = [], []
        for rep in range(3):
            s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                          modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bench")
            s.instantiate()
            s.setupExperiment(startTime=0.0)
            s.enterInitializationMode()
            s.exitInitializationMode()
            s.doStep(currentCommunicationPoint=0.0, communicationStepSize=0.01)
            t = 0.01
            t0 = time.perf_counter()
            for k in range(calls):
                s.setReal([vr["gust"]], [0.1])
                s.doStep(currentCommunicationPoint=t, communicationStepSize=h)
                t += h
            step = (time.perf_counter() - t0) / calls
            t0 = time.perf_counter()
            for k in range(calls):
                s.getReal(outputs)
            read = (time.perf_counter() - t0) / calls
            s.terminate()
            s.freeInstance()
            fmu_rows.append("%.1f / %.1f" % (step * 1e6, read * 1e6))
            st = case.stepper(model=model)
            st.step(0.01)
            t0 = time.perf_counter()
            for k in range(calls):
                st.step(h, {"gust": 0.1})
            stepper_rows.append("%.1f" % ((time.perf_counter() - t0) / calls * 1e6))
        print(f"{label}: FMU setReal+doStep / getReal {fmu_rows}; stepper.step {stepper_rows}")
