"""Flutter from Python: Patil's HALE wing (examples/patil_flutter.toml: Peters' inflow with 6
states, full model against reduced models on 4 and 8 wet modes, p-k check with Theodorsen's
C(k)); its V-g data; then a sweep of the flutter and divergence speeds over the elastic-axis
position, as a batch (``solve_many``: the unit of work of a Dask sweep, see sweep_dask.py).
Plots V-g and V-ω if matplotlib is installed.

    python examples/python/flutter.py
"""

from __future__ import annotations

import math
import pathlib


import flexwing

HERE = pathlib.Path(__file__).resolve().parent
case = flexwing.Case.load(HERE.parent / "patil_flutter.toml")
result = case.flutter()  # raises SolverError if an eigen-analysis stops before the last speed
print(case.title)
print(f"{'model':12s} {'dofs':>4s} {'divergence':>11s} {'flutter':>10s} {'ω_f':>8s} {'p-k flutter':>11s} {'time':>9s}")
for run in result.runs:
    pk = run.pk.flutter_speed if run.pk is not None else float("nan")
    print(
        f"{run.label:12s} {run.dofs:4d} {run.divergence_speed:9.4f}   {run.flutter_speed:8.4f}   "
        f"{run.flutter_frequency:6.3f}   {pk:9.4f}   {1e3 * run.wall_time_s:6.1f} ms"
    )
# References (crates/flexwing/tests/data/aero_reference/, computed by independent scripts, quoted in
# examples/patil_flutter.toml): this chain at n = 32, and the continuous wing (divergence in closed
# form π² GJ / (4 L² e c c_lα), docs/aeroelastic-model.md §5).
print("references (n = 32): flutter 32.1148 m/s at 22.5188 rad/s (Peters 6), p-k 32.5080 m/s, divergence 37.1501 m/s")
print("continuous wing: divergence 37.1539 m/s (closed form), p-k flutter 32.5127 m/s")

# V-g data of the full model: the branch that flutters, around its flutter speed.
full = result.full
s = full.eigenvalues
k = s.flutter_branch
print(f"V-g: branch of wet mode {s.mode[k]} ({s.wet_frequency[k]:.3f} rad/s at U = 0)")
for u, zeta, omega in zip(s.speeds, s.damping_ratio[k], s.imag[k]):
    if 26.0 <= u <= 38.0:
        print(f"  U = {u:5.1f} m/s  ζ = {zeta:+.5f}  ω = {omega:7.3f} rad/s")

# A sweep of the elastic-axis position x_ea (fraction of the chord from the leading edge), the
# mass centre staying at mid-chord (d0 = −(0.5 − x_ea) c: behind the axis), on 16 elements and
# Wagner's function (cheaper), one case per position, run as a batch.
base = case.replace(
    {
        "beam.elements": 16,
        "aero.aerodynamics": {"model": "wagner"},
        "aero.sweep": {"from": 4.0, "to": 80.0, "steps": 20},
        "flutter.reduced": [],
        "flutter.pk": False,
    }
)
positions = [0.30, 0.35, 0.40, 0.45, 0.50]
cases = [base.replace({"aero.elastic_axis": x, "beam.section.d0": -(0.5 - x) * 1.0}) for x in positions]
items = flexwing.solve_many(cases, "flutter", threads=2)
GJ, L, C, RHO = 1.0e4, 16.0, 1.0, 0.0889
print("elastic axis sweep (16 elements, Wagner):")
print(f"{'x_ea':>5s} {'status':>9s} {'flutter':>9s} {'ω_f':>7s} {'divergence':>11s} {'closed form':>11s}")
for x, item in zip(positions, items):
    if item.status != "complete":
        print(f"{x:5.2f} {item.status:>9s} {item.message}")
        continue
    run = item.result.full
    e = (x - 0.25) * C  # aerodynamic centre ahead of the elastic axis
    u_d = math.sqrt(2.0 / RHO * math.pi**2 * GJ / (4.0 * L**2 * e * C * 2.0 * math.pi))
    print(
        f"{x:5.2f} {item.status:>9s} {run.flutter_speed:9.4f} {run.flutter_frequency:7.3f} "
        f"{run.divergence_speed:11.4f} {u_d:11.4f}"
    )

try:
    import matplotlib.pyplot as plt
except ImportError:
    pass
else:
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True)
    for b in range(len(s.mode)):
        ax1.plot(s.speeds, s.damping_ratio[b], label=f"mode {s.mode[b]}")
        ax2.plot(s.speeds, s.imag[b])
    ax1.axhline(0.0, color="k", lw=0.5)
    ax1.set_ylabel("damping ratio ζ")
    ax2.set_ylabel("ω (rad/s)")
    ax2.set_xlabel("U (m/s)")
    ax1.legend()
    plt.show()
