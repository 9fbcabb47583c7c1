"""The cost of AeroStepper.step beyond the integration (docs/performance.md, "The aeroelastic
stepper"): 200 calls of 0.1 ms with a gust input on examples/patil_gust.toml, three repeats.
Printed per call: wall / rust_time_s (the library: forcing, integration) / the difference / the
outputs read / integrator steps (µs). Run from the repository root."""
import time, flexwing
case = flexwing.Case.load("examples/patil_gust.toml")
for model, label in [(1, "reduced r = 6"), (0, "full n = 32")]:
    res = []
    for rep in range(3):
        st = case.stepper(model=model)
        st.step(0.01)
        s0 = st.stats
        calls = 200
        t0 = time.perf_counter()
        for k in range(calls):
            st.step(1e-4, {"gust": 0.1})
        wall = (time.perf_counter() - t0) / calls
        s1 = st.stats
        rust = (s1["rust_time_s"] - s0["rust_time_s"]) / calls
        steps = (s1["steps"] - s0["steps"]) / calls
        t0 = time.perf_counter()
        for k in range(calls):
            o = st.outputs
        out = (time.perf_counter() - t0) / calls
        res.append((wall * 1e6, rust * 1e6, (wall - rust) * 1e6, out * 1e6, steps))
    print(label, ["%.1f/%.1f/%.1f/%.1f/%.1f" % r for r in res])
