#!/usr/bin/env python3
"""Max tip distance between flexwing's full model (dynamic_tip.csv, rows with model == 'full')
and this reference (case_b_tip.csv).  Usage: python3 compare_flexwing.py /tmp/fw_sine/dynamic_tip.csv"""
import sys
import csv
import numpy as np

path = sys.argv[1] if len(sys.argv) > 1 else '/tmp/fw_sine/dynamic_tip.csv'
with open(path) as f:
    rows = [r for r in csv.DictReader(f) if r['model'] == 'full']
fw = np.array([[float(r['t_s']), float(r['tip_x_m']), float(r['tip_y_m'])] for r in rows])
for name in sys.argv[2:] or ['case_b_tip.csv']:
    ref = np.loadtxt(name, delimiter=',', skiprows=1)
    assert fw.shape == ref.shape == (201, 3), (fw.shape, ref.shape)
    assert np.max(np.abs(fw[:, 0] - ref[:, 0])) < 1e-12
    d = np.hypot(fw[:, 1] - ref[:, 1], fw[:, 2] - ref[:, 2])
    k = int(np.argmax(d))
    print(f"{name}: flexwing full (rtol 1e-6) vs reference: max tip distance {d[k]:.3e} m at "
          f"t = {fw[k, 0]:.3f} s (max |dx| {np.max(np.abs(fw[:, 1] - ref[:, 1])):.3e}, "
          f"max |dy| {np.max(np.abs(fw[:, 2] - ref[:, 2])):.3e}); "
          f"at t = 1 s: {d[-1]:.3e} m")
