#!/usr/bin/env python3
"""flexwing beside Exudyn on the paper's Table 4 chain: the static tip force 150 N and case (b).

Exudyn's C++ ObjectKinematicTree solves the identical chain: the element lengths, masses and the
joint stiffnesses of flexwing's tip-load calibration come from flexwing itself (the example
`peer_chain chain N`), each element is a RevoluteZ link with its point mass at its midpoint and no
rotary inertia (docs/model.md, "Energies"), and each bending spring is the link's joint P-control
with stiffness K_i about 0. The tip force acts on a MarkerKinematicTreeRigid at the end of the last
link (a dead force: LoadForceVector in global coordinates); case (b)'s 10 sin(20 t) is a symbolic
user function, evaluated in C++ (no Python call per step).

Both codes run in this process's session, on the same machine, one after the other; CPU time around
the solve only (model set-up, calibration and imports excluded): time.process_time() around
mbs.SolveStatic / mbs.SolveDynamic for Exudyn (one thread), the thread's CPU time around
solve_static / the Radau integration for flexwing (measured by the example). Every answer is checked
against the other code before its time is shown: a peer whose answer differs is not a speed
comparison.

Run from the repository root (see README.md next to this file):

    python3 -m venv /tmp/peers-venv
    /tmp/peers-venv/bin/pip install -r crates/flexwing/benches/peers/requirements.txt
    /tmp/peers-venv/bin/python crates/flexwing/benches/peers/exudyn_chain.py

Not part of `cargo test` or CI.
"""

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

# One thread everywhere (BLAS under numpy, Exudyn's own pool is set in the settings below).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

sys.exudynFast = True  # Exudyn's module without range checks: its fastest build
import numpy as np  # noqa: E402
import exudyn as exu  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    LoadForceVector,
    MarkerKinematicTreeRigid,
    NodeGenericODE2,
    ObjectKinematicTree,
    SensorKinematicTree,
    VObjectKinematicTree,
)
from exudyn.utilities import CreateSymbolicUserFunction  # noqa: E402

ROOT = Path(__file__).resolve().parents[4]
OUTPUT_PERIOD = 0.005  # s, the tip is compared every 5 ms (case (b)'s output times)


# ---------------------------------------------------------------------------------------------
# flexwing side: the example `peer_chain`
# ---------------------------------------------------------------------------------------------


def flexwing_binary(args):
    if args.flexwing:
        return Path(args.flexwing)
    subprocess.run(
        ["cargo", "build", "--release", "-q", "-p", "flexwing", "--example", "peer_chain"],
        cwd=ROOT,
        check=True,
    )
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "examples" / "peer_chain"


def flexwing(binary, *words):
    out = subprocess.run(
        [str(binary), *map(str, words)], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)


# ---------------------------------------------------------------------------------------------
# Exudyn side
# ---------------------------------------------------------------------------------------------


def exudyn_chain(chain, tip_force, sine_omega=None):
    """The chain as an Exudyn KinematicTree with a dead tip force [0, tip_force, 0] N, times
    sin(sine_omega t) if given. Returns (mbs, sensor)."""
    n = chain["n"]
    lengths, masses, stiffness = chain["lengths"], chain["masses"], chain["stiffness"]
    assert all(j == 0.0 for j in chain["inertias"]), "bending-only chain: no rotary inertia"
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    node = mbs.AddNode(
        NodeGenericODE2(
            referenceCoordinates=[0.0] * n,
            initialCoordinates=[0.0] * n,
            initialCoordinates_t=[0.0] * n,
            numberOfODE2Coordinates=n,
        )
    )
    offsets, rotations, coms, inertias = (
        exu.Vector3DList(),
        exu.Matrix3DList(),
        exu.Vector3DList(),
        exu.Matrix3DList(),
    )
    for i in range(n):
        # joint i sits at the end of link i-1 (node i-1 of docs/model.md); the clamp is joint 0
        offsets.Append([0.0, 0.0, 0.0] if i == 0 else [lengths[i - 1], 0.0, 0.0])
        rotations.Append(np.eye(3))
        coms.Append([0.5 * lengths[i], 0.0, 0.0])  # point mass at the element's midpoint
        inertias.Append(np.zeros((3, 3)))
    tree = mbs.AddObject(
        ObjectKinematicTree(
            nodeNumber=node,
            jointTypes=[exu.JointType.RevoluteZ] * n,
            linkParents=list(range(-1, n - 1)),
            jointTransformations=rotations,
            jointOffsets=offsets,
            linkInertiasCOM=inertias,
            linkCOMs=coms,
            linkMasses=masses,
            # bending springs: torque -K_i q_i (P "control" about the offset 0)
            jointPControlVector=stiffness,
            jointDControlVector=[0.0] * n,
            jointPositionOffsetVector=[0.0] * n,
            jointVelocityOffsetVector=[0.0] * n,
            visualization=VObjectKinematicTree(show=False),
        )
    )
    tip = [lengths[-1], 0.0, 0.0]
    marker = mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=n - 1, localPosition=tip))
    load = mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0.0, tip_force, 0.0]))
    if sine_omega is not None:
        esym = exu.symbolic

        def force(mbs, t, load_vector):
            return load_vector * esym.sin(sine_omega * t)

        symbolic = CreateSymbolicUserFunction(mbs, force, "loadVectorUserFunction", load)
        mbs.SetLoadParameter(load, "loadVectorUserFunction", symbolic)
    sensor = mbs.AddSensor(
        SensorKinematicTree(
            objectNumber=tree,
            linkNumber=n - 1,
            localPosition=tip,
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    mbs.Assemble()
    return mbs, sensor


def exudyn_settings():
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.solution.sensors.writePeriod = OUTPUT_PERIOD
    s.parallel.numberOfThreads = 1
    s.timeIntegration.verboseMode = 0
    s.staticSolver.verboseMode = 0
    return s


def exudyn_static(chain, force, samples):
    """Exudyn's static solve (Newton, one load step: its adaptive stepping refines if Newton fails
    from rest). Returns tip, CPU times (s), Newton iterations."""
    mbs, sensor = exudyn_chain(chain, force)
    s = exudyn_settings()
    s.staticSolver.numberOfLoadSteps = 1
    times, tips = [], []
    for _ in range(samples):
        t0 = time.process_time()
        ok = mbs.SolveStatic(s)
        t1 = time.process_time()
        if not ok:
            raise RuntimeError(f"Exudyn static solve failed at n = {chain['n']}")
        times.append(t1 - t0)
        tips.append(np.array(mbs.GetSensorValues(sensor))[:2])
    assert max(np.hypot(*(t - tips[0])) for t in tips) < 1e-12, "repeats differ"
    return tips[0], times, mbs.sys["staticSolver"].it.newtonStepsCount


def exudyn_dynamic(chain, step, spectral_radius, samples, modified_newton=True):
    """Case (b) with Exudyn's generalized-α at a fixed step. Returns the tip every 5 ms (array
    of [x, y]), CPU times (s), Newton iterations and Jacobians of the last run."""
    mbs, sensor = exudyn_chain(chain, 10.0, sine_omega=20.0)
    s = exudyn_settings()
    s.timeIntegration.endTime = 1.0
    s.timeIntegration.numberOfSteps = int(round(1.0 / step))
    s.timeIntegration.generalizedAlpha.spectralRadius = spectral_radius
    s.timeIntegration.newton.useModifiedNewton = modified_newton
    times, histories = [], []
    for _ in range(samples):
        t0 = time.process_time()
        ok = mbs.SolveDynamic(s, solverType=exu.DynamicSolverType.GeneralizedAlpha)
        t1 = time.process_time()
        if not ok:
            raise RuntimeError(f"Exudyn dynamic solve failed at n = {chain['n']}")
        times.append(t1 - t0)
        data = mbs.GetSensorStoredData(sensor)
        histories.append(np.array(data[:, 1:3]))
    t_grid = np.array(mbs.GetSensorStoredData(sensor)[:, 0])
    assert np.allclose(t_grid, OUTPUT_PERIOD * np.arange(len(t_grid)), atol=1e-9), "output grid"
    assert all(np.array_equal(h, histories[0]) for h in histories), "repeats differ"
    it = mbs.sys["dynamicSolver"].it
    return histories[0], times, it.newtonStepsCount, it.newtonJacobiCount


# ---------------------------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------------------------


def fmt_time(s):
    if s is None:
        return "–"
    if s < 1e-3:
        return f"{s * 1e6:.3g} µs"
    if s < 1.0:
        return f"{s * 1e3:.3g} ms"
    return f"{s:.3g} s"


def slope(prev, n, t):
    if prev is None or t is None or prev[1] is None:
        return "–"
    return f"{np.log(t / prev[1]) / np.log(n / prev[0]):.2f}"


def ratio(a, b):
    return "–" if a is None else f"{a / b:.0f}"


def predict(prev, n):
    """CPU time at n extrapolated from the last measured size with the last measured slope (at
    least 1; 2 before two sizes are measured)."""
    if prev is None:
        return None
    n0, t0, k = prev
    return t0 * (n / n0) ** max(1.0, k)


def max_distance(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.hypot(a[:, 0] - b[:, 0], a[:, 1] - b[:, 1])))


def parse_sizes(text):
    return [int(v) for v in text.split(",") if v]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--static-n", default="20,80,320,1000", help="sizes of the static case")
    p.add_argument("--dynamic-n", default="20,40,80,160,320,1000", help="sizes of case (b)")
    p.add_argument("--samples", type=int, default=3, help="repeats of each timing (median)")
    p.add_argument("--step", type=float, default=None,
                   help="Exudyn's fixed step for case (b) (default: chosen by the step study)")
    p.add_argument("--spectral-radius", type=float, default=0.9,
                   help="generalized-α ρ∞ for Exudyn (Exudyn's default 0.9)")
    p.add_argument("--accuracy", type=float, default=1e-4,
                   help="tip accuracy (m) the step study aims at, against the tight flexwing run")
    p.add_argument("--cap", type=float, default=200.0,
                   help="skip an Exudyn run predicted (from the previous size) to take longer (s of CPU)")
    p.add_argument("--rtol", type=float, default=1e-3, help="flexwing's Radau rtol (default: the library's)")
    p.add_argument("--atol", type=float, default=1e-5, help="flexwing's Radau atol, rad (default: the library's)")
    p.add_argument("--flexwing", help="path of a built peer_chain example (default: cargo build it)")
    p.add_argument("--json", help="also write every figure to this JSON file")
    args = p.parse_args()

    binary = flexwing_binary(args)
    record = {"machine": {}, "static": [], "step_study": [], "dynamic": [], "dynamic_same_method": []}
    load = os.getloadavg()
    record["machine"] = {
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpus": os.cpu_count(),
        "load_average_start": load,
        "python": platform.python_version(),
        "exudyn": exu.__version__,
        "numpy": np.__version__,
    }
    print(f"# flexwing beside Exudyn {exu.__version__} (KinematicTree, C++), Table 4 chain\n")
    print(f"machine: {platform.platform()}, {os.cpu_count()} CPUs, load average at start "
          f"{load[0]:.1f} {load[1]:.1f} {load[2]:.1f}; CPU time around the solve only; "
          f"median of {args.samples} samples (flexwing: each the mean over ≥ 0.2 s of repeats)\n")

    # ---- statics ------------------------------------------------------------------------------
    print("## Static tip force 150 N (dead), from rest\n")
    print("| n | flexwing tip (x, y) m | Exudyn − flexwing tip (m) | flexwing Newton its | Exudyn Newton its | flexwing CPU | slope | Exudyn CPU | slope | Exudyn / flexwing |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    prev_f = prev_e = None
    for n in parse_sizes(args.static_n):
        chain = flexwing(binary, "chain", n)
        fw = flexwing(binary, "static", n, 150.0, args.samples)
        fw_tip = np.array(fw["tip"])
        predicted = predict(prev_e, n)
        if predicted is not None and predicted > args.cap:
            ex_tip, ex_times, ex_its = None, None, None
        else:
            ex_tip, ex_times, ex_its = exudyn_static(chain, 150.0, args.samples)
        ex_t = statistics.median(ex_times) if ex_times else None
        diff = None if ex_tip is None else float(np.hypot(*(ex_tip - fw_tip)))
        if diff is not None and diff > 1e-8:
            raise SystemExit(f"static n = {n}: the codes disagree by {diff:.2e} m: not a speed comparison")
        print(f"| {n} | ({fw_tip[0]:.9f}, {fw_tip[1]:.9f}) | {'–' if diff is None else f'{diff:.1e}'} | "
              f"{fw['iterations']} | {ex_its if ex_its is not None else '–'} | {fmt_time(fw['cpu_median_s'])} | "
              f"{slope(prev_f, n, fw['cpu_median_s'])} | {fmt_time(ex_t)} | {slope(prev_e, n, ex_t)} | "
              f"{ratio(ex_t, fw['cpu_median_s'])} |", flush=True)
        record["static"].append({"n": n, "flexwing": fw, "exudyn": {
            "tip": None if ex_tip is None else ex_tip.tolist(), "cpu_s": ex_times,
            "newton_iterations": ex_its, "skipped_predicted_s": predicted if ex_tip is None else None}})
        prev_f = (n, fw["cpu_median_s"])
        if ex_t is not None:
            prev_e = (n, ex_t, 2.0 if prev_e is None else np.log(ex_t / prev_e[1]) / np.log(n / prev_e[0]))

    # ---- step study -----------------------------------------------------------------------------
    sizes = parse_sizes(args.dynamic_n)
    references = {}

    def reference(n):
        # tight flexwing run: Radau at rtol 1e-8, atol 1e-10 rad (untimed)
        if n not in references:
            references[n] = np.array(flexwing(binary, "dynamic", n, 1e-8, 1e-10, 0)["tips"])
        return references[n]

    step = args.step
    n0 = sizes[0]
    if step is None:
        print(f"\n## Exudyn's step for case (b): tip error against flexwing at rtol 1e-8 (n = {n0})\n")
        print("| h (s) | ρ∞ | tip error (m) | Newton its | Jacobians | Exudyn CPU |")
        print("|---|---|---|---|---|---|")
        chain = flexwing(binary, "chain", n0)
        # steps that divide the 5 ms output period, from large to small
        for h in (OUTPUT_PERIOD / k for k in (5, 10, 15, 20, 30, 40, 80)):
            hist, times, its, jacs = exudyn_dynamic(chain, h, args.spectral_radius, 1)
            err = max_distance(hist, reference(n0))
            print(f"| {h:.4g} | {args.spectral_radius} | {err:.1e} | {its} | {jacs} | {fmt_time(times[0])} |", flush=True)
            record["step_study"].append({"n": n0, "step": h, "error_m": err, "cpu_s": times[0]})
            if err <= args.accuracy:
                step = h
                break
        if step is None:
            raise SystemExit("no step in the study reached the accuracy")
        print(f"\nchosen: h = {step:.4g} s, the largest step of the study within {args.accuracy:g} m")

    # ---- case (b) -------------------------------------------------------------------------------
    print(f"\n## Case (b): tip force 10 sin(20 t) N, 1 s, from rest; tip every 5 ms\n")
    print(f"flexwing: Radau IIA (5), rtol {args.rtol:g}, atol {args.atol:g} rad. Exudyn: generalized-α, "
          f"ρ∞ = {args.spectral_radius}, fixed h = {step:.4g} s, modified Newton. Errors: largest tip distance "
          f"over the 201 outputs from flexwing at rtol 1e-8, atol 1e-10 (same n).\n")
    print("| n | flexwing error (m) | Exudyn error (m) | flexwing steps | flexwing CPU | slope | Exudyn CPU | slope | Exudyn / flexwing |")
    print("|---|---|---|---|---|---|---|---|---|")
    prev_f = prev_e = None
    exudyn_runs = {}
    for n in sizes:
        chain = flexwing(binary, "chain", n)
        fw = flexwing(binary, "dynamic", n, args.rtol, args.atol, args.samples)
        ref = reference(n)
        fw_err = max_distance(fw["tips"], ref)
        predicted = predict(prev_e, n)
        if predicted is not None and predicted > args.cap:
            ex_err, ex_t, ex_times = None, None, None
        else:
            # long runs once: three samples of a 100 s run would take the afternoon
            reps = args.samples if (predicted is None or predicted < 10.0) else 1
            hist, ex_times, _, _ = exudyn_dynamic(chain, step, args.spectral_radius, reps)
            ex_err = max_distance(hist, ref)
            ex_t = statistics.median(ex_times)
        if ex_err is not None and ex_err > 2 * args.accuracy:
            raise SystemExit(f"case (b) n = {n}: Exudyn's tip is {ex_err:.2e} m off: not a speed comparison")
        fw_t = fw["cpu_median_s"]
        skipped = f"skipped (predicted {predicted:.0f} s > cap {args.cap:g} s)" if ex_t is None and predicted else None
        print(f"| {n} | {fw_err:.1e} | {'–' if ex_err is None else f'{ex_err:.1e}'} | {fw['steps']} ({fw['rejected']}) | "
              f"{fmt_time(fw_t)} | {slope(prev_f, n, fw_t)} | {skipped or fmt_time(ex_t)} | {slope(prev_e, n, ex_t)} | "
              f"{ratio(ex_t, fw_t)} |", flush=True)
        record["dynamic"].append({"n": n, "flexwing": {k: v for k, v in fw.items() if k not in ("tips", "t")},
                                  "flexwing_error_m": fw_err, "exudyn": {
                                      "step": step, "spectral_radius": args.spectral_radius, "cpu_s": ex_times,
                                      "error_m": ex_err, "skipped_predicted_s": predicted if ex_t is None else None}})
        if ex_t is not None:
            prev_e = (n, ex_t, 2.0 if prev_e is None else np.log(ex_t / prev_e[1]) / np.log(n / prev_e[0]))
            exudyn_runs[n] = (ex_err, ex_t)
        prev_f = (n, fw_t)

    # ---- case (b), the same method in both codes ----------------------------------------------
    print(f"\n## Case (b), the same method and step in both codes\n")
    print(f"Both generalized-α at h = {step:.4g} s, ρ∞ = {args.spectral_radius} (flexwing: first-order form, "
          f"Newton systems by the chain sweeps from 40 coordinates; Exudyn: its run of the table above). "
          f"Errors as above.\n")
    print("| n | flexwing error (m) | Exudyn error (m) | flexwing steps | flexwing CPU | slope | Exudyn CPU | Exudyn / flexwing |")
    print("|---|---|---|---|---|---|---|---|")
    prev_a = None
    for n in sizes:
        fa = flexwing(binary, "alpha", n, step, args.spectral_radius, args.samples)
        fa_err = max_distance(fa["tips"], reference(n))
        fa_t = fa["cpu_median_s"]
        ex_err, ex_t = exudyn_runs.get(n, (None, None))
        print(f"| {n} | {fa_err:.1e} | {'–' if ex_err is None else f'{ex_err:.1e}'} | {fa['steps']} ({fa['rejected']}) | "
              f"{fmt_time(fa_t)} | {slope(prev_a, n, fa_t)} | {fmt_time(ex_t) if ex_t else '–'} | {ratio(ex_t, fa_t)} |", flush=True)
        record["dynamic_same_method"].append({"n": n, "flexwing": {k: v for k, v in fa.items() if k not in ("tips", "t")},
                                              "flexwing_error_m": fa_err, "exudyn_error_m": ex_err, "exudyn_cpu_s": ex_t})
        prev_a = (n, fa_t)

    load = os.getloadavg()
    record["machine"]["load_average_end"] = load
    print(f"\nload average at the end {load[0]:.1f} {load[1]:.1f} {load[2]:.1f}")
    if args.json:
        Path(args.json).write_text(json.dumps(record, indent=1))
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
