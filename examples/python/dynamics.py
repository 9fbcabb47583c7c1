"""Non-linear dynamics from Python: the paper's case (b) (examples/paper_sine.toml), a tip force
10 sin(20 t) N, full model against reduced models on 1 to 4 modes; plots the tip if matplotlib
is installed.

    python examples/python/dynamics.py
"""

from __future__ import annotations

import pathlib

import flexwing

HERE = pathlib.Path(__file__).resolve().parent
case = flexwing.Case.load(HERE.parent / "paper_sine.toml")
result = case.dynamics(progress=None)  # or progress=lambda done, label: print(done, label)
print(case.title)
for run in result.runs:
    diff = run.comparison["max_tip_difference"] if run.comparison else 0.0
    print(
        f"  {run.label:12s} {run.dofs:3d} dofs  {run.stats['steps']:5d} steps  "
        f"{1e3 * run.wall_time_s:8.2f} ms  max tip difference {diff:.2e} m  "
        f"largest tip y {run.tip_y.max():.4f} m"
    )

try:
    import matplotlib.pyplot as plt
except ImportError:
    pass
else:
    for label in ["full", "reduced-r2"]:
        run = result.run(label)
        plt.plot(run.t, run.tip_y, label=label)
    plt.xlabel("t (s)")
    plt.ylabel("tip y (m)")
    plt.legend()
    plt.show()
