#!/usr/bin/env python3
"""Refine the chain flutter points of chain_<case>_points.csv in 30-digit arithmetic, and measure how
sensitive they are to round-off in the matrices.

For each (model, n) the double-precision k-method point (rows '<model>_k' / 'theodorsen') is the
start of a 2-D Newton iteration (mpmath.findroot, MDNewton) on
    f(k, X) = det(X I - B(k)) / X0^N = 0,   B(k) = Ks^{-1/2} A(k) Ks^{-1/2},  X = 1/omega^2,
with A(k) the k-method matrix (aero_common.StripSystem.Ak) built in mpmath from the double-precision
chain matrices, C(k) from mpmath (Theodorsen: Hankel functions; Jones: its rational form; Peters: the
definition 1 - 1/2 b^T (ik A + I)^-1 c ik). The root is the exact flutter point of the double-rounded
matrices. Then the same matrices are perturbed by relative random noise 1e-15 (fixed seed) and the
point is refined again: |dU/U| / 1e-15 is the condition number of the flutter speed, which bounds
how closely any double-precision implementation can agree with another.

Writes chain_<case>_mp.csv. Run: python3 chain_mp_refine.py [patil|goland]  (after chain_reference.py)
"""
import csv
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from aero_common import JONES_A, JONES_B, peters_C_mp, theodorsen_mp  # noqa: E402
from beam_reference import CASES  # noqa: E402
from chain_reference import chain  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
mp.mp.dps = 30


def Cfun_mp(model):
    if model == "theodorsen":
        return theodorsen_mp
    if model == "jones":
        A1, A2 = JONES_A
        b1, b2 = JONES_B
        return lambda k: 1 - A1 - A2 + A1 * b1 / (1j * k + b1) + A2 * b2 / (1j * k + b2)
    if model.startswith("peters"):
        N = int(model[6:])
        return lambda k: peters_C_mp(N, 1j * k, dps=mp.mp.dps + 10)
    raise ValueError(model)


def refine(s, model, k0, om0, noise=0.0, seed=1):
    rng = np.random.default_rng(seed)

    def pert(Mx):
        Mx = np.array(Mx, float)
        if noise:
            Mx = Mx * (1 + noise * rng.standard_normal(Mx.shape))
        return mp.matrix(Mx.tolist())

    M, Ct, Ks, G, E1, E2 = (pert(x) for x in (s.M, s.Ct, s.Ks, s.G, s.E1, s.E2))
    N = s.N
    b, rho, cla = mp.mpf(s.b), mp.mpf(s.rho), mp.mpf(s.cla)
    Ksih = mp.diag([1 / mp.sqrt(Ks[i, i]) for i in range(N)])  # Ks is diagonal for the chain
    for i in range(N):
        for j in range(N):
            assert i == j or Ks[i, j] == 0
    Cf = Cfun_mp(model)
    X0 = mp.mpf(1) / mp.mpf(om0) ** 2

    def f(k, X):
        Ck = Cf(k)
        A = M - 1j * (b / k) * Ct + cla * rho * b * Ck * G * ((b * b / (k * k)) * E1 + 1j * (b / k) * E2)
        B = Ksih * A * Ksih
        D = mp.eye(N) * X - B
        d = mp.det(D / X0)
        return [mp.re(d), mp.im(d)]

    # Newton in (k, X) with a forward-difference Jacobian (step 1e-12 relative: Jacobian error ~1e-12,
    # so each step gains ~12 digits from a start that is good to ~1e-9)
    k, X = mp.mpf(k0), X0
    for it in range(10):
        F = f(k, X)
        hk, hX = k * mp.mpf(10) ** -12, X * mp.mpf(10) ** -12
        Fk = f(k + hk, X)
        FX = f(k, X + hX)
        J = mp.matrix([[(Fk[0] - F[0]) / hk, (FX[0] - F[0]) / hX], [(Fk[1] - F[1]) / hk, (FX[1] - F[1]) / hX]])
        d = mp.lu_solve(J, mp.matrix([-F[0], -F[1]]))
        k, X = k + d[0], X + d[1]
        if abs(d[0]) < mp.mpf(10) ** -24 * k and abs(d[1]) < mp.mpf(10) ** -24 * X:
            break
    else:
        raise RuntimeError("Newton did not converge for %s n = %d" % (model, N // 2))
    om = 1 / mp.sqrt(X)
    return om * b / k, om, k


def main(name):
    cs = CASES[name]
    t0 = time.time()
    rows = []
    with open(os.path.join(HERE, "chain_%s_points.csv" % name)) as fh:
        for r in csv.DictReader(fh):
            if r["quantity"] != "flutter" or int(r["n"]) > 32:
                continue
            if r["model"] == "theodorsen" or r["model"].endswith("_k"):
                rows.append(r)
    out = []
    chains = {}
    for r in rows:
        n = int(r["n"])
        model = r["model"][:-2] if r["model"].endswith("_k") else r["model"]
        s = chains.setdefault(n, chain(cs, n))
        U, om, k = refine(s, model, float(r["k"]), float(r["omega_rad_s"]))
        Ud = float(r["U_m_s"])
        line = [model, n, U, om, k, (Ud - float(U)) / float(U)]
        if model in ("theodorsen", "peters6") and n == 32:
            Up, _, _ = refine(s, model, float(k), float(om), noise=1e-15)
            line.append(float(abs(Up - U) / U) / 1e-15)
        else:
            line.append(float("nan"))
        out.append(line)
        print("%-10s n=%-3d U = %s omega = %s  double k-method rel. error %.1e  cond %s  (%.0f s)" % (
            model, n, mp.nstr(U, 20), mp.nstr(om, 20), line[5], line[6], time.time() - t0))
    with open(os.path.join(HERE, "chain_%s_mp.csv" % name), "w") as fh:
        fh.write("model,n,U_m_s,omega_rad_s,k,rel_err_double_k_method,cond_U_wrt_matrix_roundoff\n")
        for line in out:
            fh.write("%s,%d,%s,%s,%s,%.3e,%s\n" % (line[0], line[1], mp.nstr(line[2], 20), mp.nstr(line[3], 20),
                                                  mp.nstr(line[4], 20), line[5],
                                                  "" if line[6] != line[6] else "%.3e" % line[6]))
    print("%s done in %.1f s" % (name, time.time() - t0))


if __name__ == "__main__":
    for nm in (sys.argv[1:] or ["patil", "goland"]):
        main(nm)
