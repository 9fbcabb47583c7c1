#!/usr/bin/env python3
"""Where Patil, Hodges & Cesnik (2001)'s published flutter curve lies against this reference.

The published curve (flutter speed and frequency against tip displacement, tip force, no gravity)
is the digitization stored in AeroBeams.jl's test data (test/referenceData/SMW/flutterSpeedVsTipDisp.txt,
flutterFreqVsTipDisp.txt; digitized by AeroBeams' authors from PHC 2001, read here, numbers copied
into patil_published_digitized.csv). It is a secondary, approximate check: digitization error (a few
0.1 m/s), and PHC used a finite-state inflow model and their own beam data (not stated in full).
Our curve (patil_deformed_flutter.csv, tip force rows) is interpolated (cubic, in tip deflection) at
the digitized abscissae. Run: python3 published_compare.py > published_compare_run.log (< 1 s)
"""
import csv
import os

import numpy as np
from scipy.interpolate import CubicSpline

HERE = os.path.dirname(os.path.abspath(__file__))
pub = list(csv.DictReader(open(os.path.join(HERE, "patil_published_digitized.csv"))))
rows = [r for r in csv.DictReader(open(os.path.join(HERE, "patil_deformed_flutter.csv"))) if r["case"] == "tip_force"]
for model in ("theodorsen", "peters6"):
    rr = [r for r in rows if r["model"] == model and r["quantity"] == "flutter"]
    d = np.array([float(r["tip_y_m"]) for r in rr])
    U = CubicSpline(d, [float(r["U_m_s"]) for r in rr])
    W = CubicSpline(d, [float(r["omega_rad_s"]) for r in rr])
    print("=== %s" % model)
    print("quantity  tip_m   published   this_ref   published-ref  (%)")
    for p in pub:
        x, y = float(p["tip_m"]), float(p["value"])
        if x > d[-1]:
            continue
        ref = U(x) if p["quantity"] == "flutter_speed_m_s" else W(x)
        print("%-9s %6.3f %10.3f %10.3f %+10.3f  %+6.1f" % (p["quantity"][:9], x, y, ref, y - ref, 100 * (y / ref - 1)))
