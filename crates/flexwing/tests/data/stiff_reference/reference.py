"""Reference solutions of two stiff test problems, computed with SciPy independently of flexwing.

Run: python3 reference.py > reference.txt   (SciPy >= 1.10; prints one line per value)

Van der Pol in the singular-perturbation form of Hairer & Wanner II (§IV.1, eq. 1.5'):
    y1' = y2,  y2' = ((1 - y1^2) y2 - y1) / eps,  eps = 1e-6,  y(0) = (2, 0),  t in [0, 2].
Robertson's chemical kinetics (Hairer & Wanner II, §IV.1, eq. 1.3):
    y1' = -0.04 y1 + 1e4 y2 y3,  y2' = 0.04 y1 - 1e4 y2 y3 - 3e7 y2^2,  y3' = 3e7 y2^2,
    y(0) = (1, 0, 0), values at t = 40 and t = 1e4 (y2 printed as is; it is ~1e-5 .. 1e-8).

Each problem is solved with two different SciPy methods (Radau and the BDF of LSODA) at rtol 1e-12
and the difference between them is printed as the reference's own uncertainty.
"""
import numpy as np
from scipy.integrate import solve_ivp

EPS = 1e-6


def vdp(t, y):
    return [y[1], ((1 - y[0] ** 2) * y[1] - y[0]) / EPS]


def vdp_jac(t, y):
    return [[0.0, 1.0], [(-2 * y[0] * y[1] - 1) / EPS, (1 - y[0] ** 2) / EPS]]


def rober(t, y):
    return [
        -0.04 * y[0] + 1e4 * y[1] * y[2],
        0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2,
        3e7 * y[1] ** 2,
    ]


def rober_jac(t, y):
    return [
        [-0.04, 1e4 * y[2], 1e4 * y[1]],
        [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
        [0.0, 6e7 * y[1], 0.0],
    ]


def solve(f, jac, y0, t_end, t_eval, method, atol):
    r = solve_ivp(f, (0.0, t_end), y0, method=method, jac=jac, t_eval=t_eval,
                  rtol=1e-12, atol=atol)
    assert r.success, r.message
    return r.y


for name, f, jac, y0, t_eval, atol in [
    ("vdpol", vdp, vdp_jac, [2.0, 0.0], [1.0, 2.0], 1e-14),
    ("rober", rober, rober_jac, [1.0, 0.0, 0.0], [40.0, 1e4], 1e-20),
]:
    a = solve(f, jac, y0, t_eval[-1], t_eval, "Radau", atol)
    b = solve(f, jac, y0, t_eval[-1], t_eval, "LSODA", atol)
    for k, t in enumerate(t_eval):
        for i in range(len(y0)):
            print(f"{name} t={t:g} y{i + 1} = {a[i, k]:.16e}  (LSODA - Radau: {b[i, k] - a[i, k]:.1e})")
