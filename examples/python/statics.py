"""Non-linear statics from Python: the paper's Figure 4 sweep (examples/paper_static.toml), the
full model against reduced models on 2, 3 and 4 modes, and the same case changed in Python.

    python examples/python/statics.py
"""

from __future__ import annotations

import pathlib

import flexwing

HERE = pathlib.Path(__file__).resolve().parent
case = flexwing.Case.load(HERE.parent / "paper_static.toml")
result = case.statics()  # raises SolverError (with the partial result) if a model stops
full = result.full
print(case.title)
print("  F1 (N)   full tip y (m)   " + "   ".join(f"{r.label:>12}" for r in result.runs[1:]))
for i in range(0, len(full.scale), 5):
    others = "   ".join(f"{r.tip_y[i]:12.5f}" for r in result.runs[1:])
    print(f"  {full.scale[i]:6.1f}   {full.tip_y[i]:14.5f}   {others}")
for r in result.runs[1:]:
    print(f"  {r.label}: largest tip distance from the full model {r.tip_difference.max():.2e} m")

# A changed copy: a stiffer beam, full model only, no sweep of F1 (F1 = 150 N).
stiffer = case.replace({"beam.section.EI": 80.0, "static.reduced": [], "static.sweep": None})
point = stiffer.statics().full
print(f"EI = 80 N m^2, F1 = 1 N, F2 = -150 N: tip at ({point.tip_x[0]:.5f}, {point.tip_y[0]:.5f}) m")

# A case from plain Python values, with the case file's keys.
tip = flexwing.Case(
    beam={"length": 1.0, "elements": 20, "section": {"EI": 50.0, "mass_per_length": 0.2}},
    loads=[{"type": "point-force", "span": 1.0, "direction": "follower", "normal": 100.0}],
)
print("follower tip force 100 N (normal to the tip element): tip y = %.5f m" % tip.statics().full.tip_y[0])
