"""Bad input never takes the interpreter down. Every public callable of the package is called
with every argument replaced, one at a time, by each of a set of bad values (None, strings, NaN,
inf, negative and huge numbers, empty, 3-D, complex, boolean, object arrays, arbitrary objects);
this runs in a child process, so that a crash (a segfault, an abort, a panic that escaped as
`PanicException`, which `except Exception` does not catch) fails the test instead of the run.
Each call must return or raise an `Exception` (a `FlexwingError`, or Python's own `TypeError`
for a wrong number of arguments); no `InternalError` (a caught panic) is allowed either."""

from __future__ import annotations

import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent(
    r'''
    import itertools, math, sys
    import numpy as np
    import flexwing

    BAD = [None, "x", math.nan, math.inf, -1, -1.0, 0, 2**70, -2**70, True, 1j, [], [[1.0], [2.0, 3.0]],
           np.zeros(0), np.zeros((3, 3, 3)), np.array([1j]), np.array(["a"]), np.array([object()]),
           np.full(5, np.nan), np.ones(3, dtype=np.float32)[::2], {"type": "bogus"}, object()]
    LOAD = {"type": "point-force", "span": 1.0, "direction": "dead", "fy": 10.0}
    beam = flexwing.Beam(length=1.0, elements=4, EI=50.0, mass_per_length=0.2, GJ=5.0,
                         polar_inertia=0.01, polar_inertia_about="mass-centre", d0=0.02)
    full = flexwing.FullModel(beam)
    reduced = full.reduced(2)
    eom = full.equations([LOAD])
    # max_steps bounds a step of 2**70 s (a valid request the integrator gives up on).
    stepper = reduced.stepper([LOAD], max_steps=2000)
    case = flexwing.Case(beam=beam.to_dict(), loads=[LOAD], dynamic={"end_time": 0.01, "output_step": 0.005})
    n, m = full.n_dofs, reduced.n_dofs
    good = {
        "Beam": (flexwing.Beam, [], dict(length=1.0, elements=4, EI=50.0, mass_per_length=0.2)),
        "Beam.from_dict": (flexwing.Beam.from_dict, [beam.to_dict()], {}),
        "FullModel": (flexwing.FullModel, [beam], {}),
        "FullModel.mass_matrix": (full.mass_matrix, [np.zeros(n)], {}),
        "FullModel.shape": (full.shape, [np.zeros(n)], {}),
        "FullModel.modes": (full.modes, [3], {}),
        "FullModel.reduced": (full.reduced, [[1, 2]], {}),
        "FullModel.equations": (full.equations, [[LOAD]], dict(scales=[1.0], gyroscopic="exact", damping={"type": "none"})),
        "FullModel.stepper": (full.stepper, [[LOAD]], dict(x0=np.zeros(n), rtol=1e-6, integrator="radau", hold="zero")),
        "ReducedModel": (flexwing.ReducedModel, [full, 2], {}),
        "ReducedModel.full_coordinates": (reduced.full_coordinates, [np.zeros(m)], {}),
        "ReducedModel.reduce_coordinates": (reduced.reduce_coordinates, [np.zeros(n)], {}),
        "ReducedModel.mass_matrix": (reduced.mass_matrix, [np.zeros(m)], {}),
        "Equations.state": (eom.state, [np.zeros(n), np.zeros(n)], {}),
        "Equations.rhs": (eom.rhs, [0.0, np.zeros(2 * n)], {}),
        "Equations.jacobian": (eom.jacobian, [0.0, np.zeros(2 * n)], {}),
        "Equations.energies": (eom.energies, [np.zeros(2 * n)], {}),
        "Equations.velocities": (eom.velocities, [np.zeros(2 * n)], {}),
        "Stepper.step": (stepper.step, [1e-3], dict(scales=[0.5])),
        "Stepper.set_state": (stepper.set_state, [np.zeros(m), np.zeros(m)], dict(t=0.0)),
        "Case": (flexwing.Case, [case.to_dict()], {}),
        "Case.from_toml": (flexwing.Case.from_toml, [case.to_toml()], dict(file="a.toml")),
        "Case.replace": (case.replace, [{"beam.length": 2.0}], {}),
        "Case.run": (case.run, ["dynamic"], dict(check=False)),
        "solve_many": (flexwing.solve_many, [[case]], dict(threads=1)),
    }
    calls = 0
    for name, (f, args, kwargs) in good.items():
        f(*args, **kwargs)  # the good call works
        slots = [("arg", i) for i in range(len(args))] + [("kw", k) for k in kwargs]
        for (kind, where), bad in itertools.product(slots, BAD):
            a, k = list(args), dict(kwargs)
            if kind == "arg":
                a[where] = bad
            else:
                k[where] = bad
            try:
                f(*a, **k)
            except flexwing.InternalError as e:
                print(f"{name} {kind} {where} = {bad!r}: a caught panic: {e}")
                sys.exit(3)
            except Exception:
                pass
            calls += 1
    setattr_bad = 0
    for bad in BAD:
        try:
            eom.scales = bad
        except flexwing.FlexwingError:
            setattr_bad += 1
    print(f"{calls} bad calls, scales refused {setattr_bad} of {len(BAD)}")
    '''
)


def test_no_bad_input_crashes_the_interpreter(tmp_path):
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, cwd=tmp_path, timeout=600
    )
    assert done.returncode == 0, f"exit status {done.returncode}\n{done.stdout}\n{done.stderr[-3000:]}"
    assert "bad calls" in done.stdout
    calls = int(done.stdout.split()[0])
    assert calls > 500, done.stdout
