#!/usr/bin/env python3
"""flexwing's lumped chain, linearized about the undeformed state, with strip aerodynamics per element:
a discrete reference for the Rust model at equal n (Patil and Goland wings).

Structure, built from docs/model.md only (not from the Rust sources):
  n rigid elements of length l = L/n; joint rotations q = (q_b[1..n], q_t[1..n]);
  absolute angles theta = T q_b, psi = T q_t (T lower-triangular ones).
  Midpoint c_i = P_{i-1} + (l/2) e(theta_i); linearized, its flap displacement is
      y_i = sum_{j<i} l theta_j + (l/2) theta_i = (A T q_b)_i,  A_ij = l (j < i), l/2 (j = i).
  Mass centre g_i = c_i + d0 (sin psi_i n_i + cos psi_i z), linearized flap displacement y_i + d0 psi_i.
  T = 1/2 sum m_i |g_i'|^2 + 1/2 sum J_i psi_i'^2, m_i = m l, J_i = I_cg l, I_cg = I_ea - m d0^2.
  Bending springs, tip-load calibration: w(x) = x^2 (3L - x)/(6 EI), chord angles
      th_i = (w(x_i) - w(x_{i-1}))/l, q_i = th_i - th_{i-1}, K_i = (L - x_{i-1})/q_i.
  Torsion springs: 2 GJ/l at the root joint, GJ/l elsewhere.
Aerodynamics (aero_common.py), one strip per element at the element midpoint c_i, width l:
  plunge down h_i = -y_i (row -(A T)_i on q_b), pitch alpha_i = psi_i (row T_i on q_t);
  the lift per span L_i (up) gives generalized forces l L_i d y_i/d q_b = l L_i (A T)_i on the bending
  joints (the midpoint's Jacobian, linearized: d c_i/d theta_j = A_ij y-hat) and the nose-up moment
  per span about the elastic axis M_i gives l M_i on every twist joint j <= i (row T_i);
  apparent mass = fluid kinetic energy of each strip (l times Theodorsen's per-span value);
  unsteady states per element (per strip), not projected.

Writes chain_<case>_points.csv, chain_<case>_n8_matrices.csv, chain_<case>_n8_eigs.csv.
Run: python3 chain_reference.py [patil|goland]   (a few minutes)
"""
import math
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense matrices: threads only add overhead

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from aero_common import (StripSystem, fmt, jones, kmethod_crossings, kmethod_local, peters,  # noqa: E402
                         peters_C_mp, peters_mu, quasi_steady, ss_flutter)
from beam_reference import CASES, section  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def chain(cs, n):
    L = cs["L"]
    b, a, d0 = section(cs)
    l = L / n
    m_i = cs["m"] * l
    I_cg = cs["I_ea"] - cs["m"] * d0 ** 2
    J_i = I_cg * l
    T = np.tril(np.ones((n, n)))
    A = np.tril(np.full((n, n), l), -1) + np.diag(np.full(n, l / 2))
    Y = A @ T  # midpoint flap displacement per q_b
    # mass: rows of the mass-centre displacement (y_i + d0 psi_i) and of psi_i
    G = np.hstack([Y, d0 * T])
    Ps = np.hstack([np.zeros((n, n)), T])
    Ms = m_i * G.T @ G + J_i * Ps.T @ Ps
    # springs
    x = np.linspace(0, L, n + 1)
    w = x ** 2 * (3 * L - x) / (6 * cs["EI"])
    th = np.diff(w) / l
    qb = np.diff(np.concatenate([[0.0], th]))
    Kb = (L - x[:-1]) / qb
    Kt = np.full(n, cs["GJ"] / l)
    Kt[0] = 2 * cs["GJ"] / l
    Ks = np.diag(np.concatenate([Kb, Kt]))
    H = np.hstack([-Y, np.zeros((n, n))])
    P = Ps
    s = StripSystem(Ms, Ks, H, P, np.full(n, l), b, a, cs["rho"], project=False)
    s.Kb = Kb
    return s


def main(name):
    cs = CASES[name]
    b, a, d0 = section(cs)
    t0 = time.time()
    rows = []

    def add(q, model, n, U, om, note=""):
        k = om * b / U if om > 0 and U > 0 else 0.0
        rows.append((q, model, n, U, om, k, note))
        print("%-10s %-12s n=%-4d U = %.12f omega = %.12f k = %.10f %s" % (q, model, n, U, om, k, note))

    # sanity: tip-load calibration of the springs (K_1 ~ 2EI/l, K_i = EI/l)
    s8 = chain(cs, 8)
    print("n = 8 bending springs / (EI/l):", s8.Kb / (cs["EI"] / (cs["L"] / 8)))

    ns = (8, 16, 32, 64, 128)
    ref = None
    for n in ns:
        s = chain(cs, n)
        add("divergence", "steady", n, s.divergence_speeds()[0], 0.0)
    kgrid = np.geomspace(4.0, 0.02, 400)
    for n in ns:
        s = chain(cs, n)
        if n <= 32:
            cr, _, _ = kmethod_crossings(s, kgrid, branches=8)
            fl = [c for c in cr if c["direction"] > 0][0]
        else:
            fl = kmethod_local(s, ref["k"] * 0.9, ref["k"] * 1.1, ref["omega"], npts=21)
        ref = fl
        add("flutter", "theodorsen", n, fl["U"], fl["omega"], "k-method")

    Ugrid = np.arange(0.5, cs["Umax"], 0.5 if name == "patil" else 2.0)
    for n in (8, 16, 32):
        s = chain(cs, n)
        from scipy import linalg
        om0 = math.sqrt(min(linalg.eigvals(s.Ks, s.M).real))
        lags = [quasi_steady(), jones()] + [peters(N) for N in (2, 4, 6, 8, 10)] + [peters_mu(N) for N in (6, 8, 10)]
        for lag in lags:
            res = ss_flutter(s, lag, Ugrid, 0.2 * om0, xtol=1e-11)
            if res is None:
                print("  %s n=%d: no upward crossing on the grid" % (lag.name, n))
                continue
            if res.get("from_start"):
                add("flutter", lag.name, n, 0.0, res["omega"],
                    "unstable from U -> 0+ (Re p = %.3e at U = %g)" % (res["p"].real, res["U_first"]))
                continue
            add("flutter", lag.name, n, res["U"], res["omega"],
                "state space" + (", Peters in the mu = lam - A^-1 c w realization (ill-conditioned)"
                                 if lag.name.endswith("_mu") else ""))
            if lag.name != "quasi_steady" and not lag.name.endswith("_mu"):
                Cf = ((lambda k, N=int(lag.name[6:]): complex(peters_C_mp(N, 1j * mp.mpf(k))))
                      if lag.name.startswith("peters") else (lambda k, lag=lag: lag.C(1j * k)))
                kk = res["omega"] * b / res["U"]
                r = kmethod_local(s, kk * 0.9, kk * 1.1, res["omega"], Cfun=Cf, npts=21)
                add("flutter", lag.name + "_k", n, r["U"], r["omega"], "k-method with the model's C(ik)")

    with open(os.path.join(HERE, "chain_%s_points.csv" % name), "w") as f:
        f.write("quantity,model,n,U_m_s,omega_rad_s,k,note\n")
        for r in rows:
            f.write("%s,%s,%d,%s,%s,%s,%s\n" % (r[0], r[1], r[2], fmt(r[3]), fmt(r[4]), fmt(r[5]), r[6].replace(",", ";")))

    # matrices and eigenvalues at n = 8 for element-level comparisons
    s = chain(cs, 8)
    with open(os.path.join(HERE, "chain_%s_n8_matrices.csv" % name), "w") as f:
        f.write("matrix,i,j,value\n")
        for nm, Mx in (("Ms", s.Ms), ("Ks", s.Ks), ("Mnc", s.Mnc), ("Ct", s.Ct), ("G", s.G), ("E1", s.E1), ("E2", s.E2)):
            for i in range(Mx.shape[0]):
                for j in range(Mx.shape[1]):
                    if Mx[i, j] != 0:
                        f.write("%s,%d,%d,%s\n" % (nm, i, j, fmt(Mx[i, j])))
    U_e = 20.0 if name == "patil" else 100.0
    with open(os.path.join(HERE, "chain_%s_n8_eigs.csv" % name), "w") as f:
        f.write("model,U_m_s,re_p_1_s,im_p_rad_s\n")
        for lag in (quasi_steady(), jones(), peters(6)):
            ev = s.ss_eigs(U_e, lag)
            ev = ev[np.lexsort((ev.real, np.round(ev.imag, 9)))]
            for p in ev:
                f.write("%s,%s,%s,%s\n" % (lag.name, fmt(U_e), fmt(p.real), fmt(p.imag)))
    print("%s done in %.1f s" % (name, time.time() - t0))


if __name__ == "__main__":
    for nm in (sys.argv[1:] or ["patil", "goland"]):
        main(nm)
