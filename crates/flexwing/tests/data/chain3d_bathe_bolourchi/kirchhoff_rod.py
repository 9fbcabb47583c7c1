#!/usr/bin/env python3
"""Independent reference for tests/chain3d_bathe_bolourchi.rs: the 45-degree bend of Bathe &
Bolourchi (1979) as a continuous Kirchhoff rod (inextensible, unshearable), solved by shooting.

Pure Python (no flexwing code, no third-party package). The rod is clamped at the origin with
the section frame (t, n, c) = (x, z, x cross z = -y); its stress-free curvature is 1/R about n
(the arc of radius R = 100 in the x-y plane, bending toward +y). Under a dead tip force F the
internal moment is m(s) = (X(L) - X(s)) x F, and

    X' = R e1,   R' = R hat(kappa),   kappa = kappa0 + C^-1 R^T m(s),   C = diag(GJ, EI, EI).

The unknown tip X(L) is found by Newton on X(L) - X(L; guess) = 0 (finite-difference Jacobian),
each integration by classical RK4 with N steps; N is doubled until the tips agree to 1e-9 and
the last two are Richardson-extrapolated (order 4). Loads are followed 300 -> 450 -> 600.

Usage: python3 kirchhoff_rod.py  (prints CSV: gj_over_ei,P,x,y,z)
"""
import math

E = 1.0e7
EI = E / 12.0
RADIUS = 100.0
LENGTH = RADIUS * math.pi / 4.0


def hat_times(r, k):
    """R hat(k) for a 3x3 R (list of rows) and vector k."""
    out = [[0.0] * 3 for _ in range(3)]
    h = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]]
    for i in range(3):
        for j in range(3):
            out[i][j] = sum(r[i][a] * h[a][j] for a in range(3))
    return out


def rhs(state, tip, force, gj):
    x, r = state
    arm = [tip[i] - x[i] for i in range(3)]
    m = [arm[1] * force[2] - arm[2] * force[1],
         arm[2] * force[0] - arm[0] * force[2],
         arm[0] * force[1] - arm[1] * force[0]]
    mb = [sum(r[a][i] * m[a] for a in range(3)) for i in range(3)]  # R^T m
    kappa = [mb[0] / gj, 1.0 / RADIUS + mb[1] / EI, mb[2] / EI]
    dx = [r[0][0], r[1][0], r[2][0]]
    return dx, hat_times(r, kappa)


def axpy(state, d, h):
    x, r = state
    dx, dr = d
    return ([x[i] + h * dx[i] for i in range(3)],
            [[r[i][j] + h * dr[i][j] for j in range(3)] for i in range(3)])


def shoot(tip, force, gj, steps):
    h = LENGTH / steps
    state = ([0.0, 0.0, 0.0], [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    for _ in range(steps):
        k1 = rhs(state, tip, force, gj)
        k2 = rhs(axpy(state, k1, h / 2), tip, force, gj)
        k3 = rhs(axpy(state, k2, h / 2), tip, force, gj)
        k4 = rhs(axpy(state, k3, h), tip, force, gj)
        x, r = state
        x = [x[i] + h / 6 * (k1[0][i] + 2 * k2[0][i] + 2 * k3[0][i] + k4[0][i]) for i in range(3)]
        r = [[r[i][j] + h / 6 * (k1[1][i][j] + 2 * k2[1][i][j] + 2 * k3[1][i][j] + k4[1][i][j])
              for j in range(3)] for i in range(3)]
        state = (x, r)
    return state[0]


def solve3(a, b):
    """Solve the 3x3 system a x = b (Cramer)."""
    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    d = det(a)
    out = []
    for k in range(3):
        m = [row[:] for row in a]
        for i in range(3):
            m[i][k] = b[i]
        out.append(det(m) / d)
    return out


def tip_for(p, gj, steps, guess):
    force = [0.0, 0.0, p]
    tip = guess[:]
    for _ in range(30):
        res = [a - b for a, b in zip(shoot(tip, force, gj, steps), tip)]
        if max(abs(v) for v in res) < 1e-11:
            return tip
        jac = [[0.0] * 3 for _ in range(3)]
        eps = 1e-6
        for k in range(3):
            t2 = tip[:]
            t2[k] += eps
            r2 = [a - b for a, b in zip(shoot(t2, force, gj, steps), t2)]
            for i in range(3):
                jac[i][k] = (r2[i] - res[i]) / eps
        dx = solve3(jac, [-v for v in res])
        tip = [tip[i] + dx[i] for i in range(3)]
    raise RuntimeError("Newton did not converge")


def main():
    print("gj_over_ei,P,x,y,z")
    for label, gj in (("0.8436", 0.5 * E * 0.1406), ("1", EI)):
        guess = [RADIUS * math.sin(math.pi / 4), RADIUS * (1 - math.cos(math.pi / 4)), 0.0]
        for p in (300.0, 450.0, 600.0):
            prev = None
            steps = 250
            while True:
                t = tip_for(p, gj, steps, guess)
                if prev is not None and max(abs(a - b) for a, b in zip(t, prev)) < 1e-9:
                    break
                prev, steps = t, 2 * steps
            best = [a + (a - b) / 15.0 for a, b in zip(t, prev)]
            guess = best
            print(f"{label},{p:g},{best[0]:.10f},{best[1]:.10f},{best[2]:.10f}", flush=True)


if __name__ == "__main__":
    main()
