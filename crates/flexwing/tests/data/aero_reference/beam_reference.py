#!/usr/bin/env python3
"""Continuous-wing strip-theory references: Patil's HALE wing and the Goland wing.

Structure: uniform clamped-free Euler-Bernoulli flap bending w(x) (up) + St-Venant torsion psi(x)
(nose up), mass centre d0 ahead of the elastic axis (flexwing sign), linear, undeformed.
    T = 1/2 int [ m (w_t + d0 psi_t)^2 + I_cg psi_t^2 ] dx,   V = 1/2 int [ EI w_xx^2 + GJ psi_x^2 ] dx
Two independent discretizations:
  * Galerkin with Nb clamped-free bending eigenfunctions and Nt torsion eigenfunctions
    sin((2j-1) pi x / 2L) (the in-vacuo modes of the uncoupled beam), integrals by 600-point
    Gauss-Legendre quadrature;
  * finite elements: Hermite-cubic bending + linear torsion, consistent matrices and consistent
    (4-point Gauss) strip loads.
Aerodynamics: strip theory (aero_common.py), Theodorsen C(k) (k-method + p-k), quasi-steady C = 1,
R. T. Jones, Peters N = 2..10 (state space), all with the non-circulatory terms.
Divergence: closed form for the uniform wing, q_D = (pi/2L)^2 GJ / (c cla e), e = b (1/2 + a).

Writes beam_<case>_*.csv. Run: python3 beam_reference.py [patil|goland]   (a few minutes)
"""
import math
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense matrices: threads only add overhead

import mpmath as mp
import numpy as np
from scipy import optimize

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from aero_common import (follow, PI, StripSystem, fmt, jones, kmethod_crossings, kmethod_local, peters,  # noqa: E402
                         peters_C_mp, quasi_steady, ss_flutter, theodorsen)

HERE = os.path.dirname(os.path.abspath(__file__))

CASES = {
    # Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001, Table 1 (wing only, linear).
    "patil": dict(L=16.0, c=1.0, x_ea=0.5, x_cg=0.5, m=0.75, I_ea=0.1, EI=2e4, GJ=1e4, rho=0.0889,
                  published=dict(U_F=32.21, omega_F=22.61, U_D=37.29), Umax=45.0, dU=0.5, dUvg=0.25),
    # Goland (1945) as in Bisplinghoff, Ashley & Halfman sec. 9.3; I about the elastic axis
    # (1.943 slug ft^2/ft = 8.64 kg m), sea level.
    "goland": dict(L=6.096, c=1.8288, x_ea=0.33, x_cg=0.43, m=35.71, I_ea=8.64, EI=9.77e6, GJ=0.99e6,
                   rho=1.225, published=dict(U_F=137.2, omega_F=70.7, U_D=252.8), Umax=260.0, dU=2.0, dUvg=1.0),
}


def section(cs):
    b = cs["c"] / 2
    a = 2 * cs["x_ea"] - 1
    d0 = (cs["x_ea"] - cs["x_cg"]) * cs["c"]
    return b, a, d0


# ---------------------------------------------------------------- clamped-free bending modes
def beta_L(i):
    f = lambda x: math.cos(x) + 1.0 / math.cosh(x)  # noqa: E731  (1 + cos cosh = 0)
    c = (i - 0.5) * PI
    return optimize.brentq(f, c - 0.4 if i > 1 else 1.2, c + 0.4 if i > 1 else 2.2, xtol=1e-15)


def bend_mode(i, x, L):
    """phi = cosh bx - cos bx - s (sinh bx - sin bx), evaluated without cancellation; and phi''."""
    BL = beta_L(i)
    be = BL / L
    s = (math.sinh(BL) - math.sin(BL)) / (math.cosh(BL) + math.cos(BL))
    oms = (math.exp(-BL) + math.cos(BL) + math.sin(BL)) / (math.cosh(BL) + math.cos(BL))  # 1 - s
    bx = be * x
    ch_sh = 0.5 * oms * np.exp(bx) + 0.5 * (1 + s) * np.exp(-bx)  # cosh - s sinh
    phi = ch_sh - np.cos(bx) + s * np.sin(bx)
    phi2 = be * be * (ch_sh + np.cos(bx) - s * np.sin(bx))
    return phi, phi2


def galerkin(cs, Nb, Nt, nq=600):
    L = cs["L"]
    b, a, d0 = section(cs)
    xg, wg = np.polynomial.legendre.leggauss(nq)
    x = 0.5 * L * (xg + 1)
    W = 0.5 * L * wg
    Pw = np.zeros((nq, Nb))
    Pw2 = np.zeros((nq, Nb))
    for i in range(Nb):
        Pw[:, i], Pw2[:, i] = bend_mode(i + 1, x, L)
    Pt = np.zeros((nq, Nt))
    Pt1 = np.zeros((nq, Nt))
    for j in range(Nt):
        kk = (2 * j + 1) * PI / (2 * L)
        Pt[:, j] = np.sin(kk * x)
        Pt1[:, j] = kk * np.cos(kk * x)
    return assemble(cs, Pw, Pw2, Pt, Pt1, W)


def assemble(cs, Pw, Pw2, Pt, Pt1, W):
    b, a, d0 = section(cs)
    m, I_ea, EI, GJ = cs["m"], cs["I_ea"], cs["EI"], cs["GJ"]
    Wd = np.diag(W)
    Nb, Nt = Pw.shape[1], Pt.shape[1]
    N = Nb + Nt
    Ms = np.zeros((N, N))
    Ks = np.zeros((N, N))
    Ms[:Nb, :Nb] = m * Pw.T @ Wd @ Pw
    Ms[:Nb, Nb:] = m * d0 * Pw.T @ Wd @ Pt
    Ms[Nb:, :Nb] = Ms[:Nb, Nb:].T
    Ms[Nb:, Nb:] = I_ea * Pt.T @ Wd @ Pt
    Ks[:Nb, :Nb] = EI * Pw2.T @ Wd @ Pw2
    Ks[Nb:, Nb:] = GJ * Pt1.T @ Wd @ Pt1
    H = np.hstack([-Pw, np.zeros_like(Pt)])
    P = np.hstack([np.zeros_like(Pw), Pt])
    return StripSystem(Ms, Ks, H, P, W, b, a, cs["rho"], project=True)


def fe(cs, nel):
    """Hermite bending (w, w') + linear torsion psi per node; root node clamped."""
    L = cs["L"]
    h = L / nel
    xg, wg = np.polynomial.legendre.leggauss(4)
    xi = 0.5 * (xg + 1)
    wq = 0.5 * h * wg
    nq = 4 * nel
    nbd = 2 * nel  # bending dofs (w, w') at nodes 1..nel
    ntd = nel
    Pw = np.zeros((nq, nbd))
    Pw2 = np.zeros((nq, nbd))
    Pt = np.zeros((nq, ntd))
    Pt1 = np.zeros((nq, ntd))
    W = np.zeros(nq)
    N1 = 1 - 3 * xi ** 2 + 2 * xi ** 3
    N2 = h * (xi - 2 * xi ** 2 + xi ** 3)
    N3 = 3 * xi ** 2 - 2 * xi ** 3
    N4 = h * (-xi ** 2 + xi ** 3)
    D1 = (-6 + 12 * xi) / h ** 2
    D2 = (-4 + 6 * xi) / h
    D3 = (6 - 12 * xi) / h ** 2
    D4 = (-2 + 6 * xi) / h
    for e in range(nel):
        r = slice(4 * e, 4 * e + 4)
        W[r] = wq
        # element nodes e (left) and e+1 (right); node 0 is clamped
        if e > 0:
            Pw[r, 2 * (e - 1)] = N1
            Pw[r, 2 * (e - 1) + 1] = N2
            Pw2[r, 2 * (e - 1)] = D1
            Pw2[r, 2 * (e - 1) + 1] = D2
            Pt[r, e - 1] = 1 - xi
            Pt1[r, e - 1] = -1 / h
        Pw[r, 2 * e] = N3
        Pw[r, 2 * e + 1] = N4
        Pw2[r, 2 * e] = D3
        Pw2[r, 2 * e + 1] = D4
        Pt[r, e] = xi
        Pt1[r, e] = 1 / h
    return assemble(cs, Pw, Pw2, Pt, Pt1, W)


def divergence_closed(cs):
    b, a, d0 = section(cs)
    e = b * (0.5 + a)
    qD = (PI / (2 * cs["L"])) ** 2 * cs["GJ"] / (cs["c"] * 2 * PI * e)
    return math.sqrt(2 * qD / cs["rho"])


def peters_Cf(N):
    return lambda k: complex(peters_C_mp(N, 1j * mp.mpf(k)))


def main(name):
    cs = CASES[name]
    t0 = time.time()
    b, a, d0 = section(cs)
    print("=== %s: b = %g, a = %g, d0 = %g, I_cg = %.10g" % (name, b, a, d0, cs["I_ea"] - cs["m"] * d0 ** 2))
    rows = []  # (quantity, model, discretization, n, U, omega, k)

    def add(q, model, disc, n, U, om, note=""):
        k = om * b / U if om > 0 and U > 0 else 0.0
        rows.append((q, model, disc, n, U, om, k, note))
        print("%-11s %-12s %-10s n=%-4s U = %.12f  omega = %.12f  k = %.10f %s" % (q, model, disc, n, U, om, k, note))

    # ------------------------------------------------ divergence
    UD = divergence_closed(cs)
    add("divergence", "steady", "closed_form", 0, UD, 0.0)
    add("divergence", "steady", "galerkin", 1, galerkin(cs, 1, 1).divergence_speeds()[0], 0.0)
    for nel in (8, 16, 32, 64, 128):
        add("divergence", "steady", "fe", nel, fe(cs, nel).divergence_speeds()[0], 0.0)

    # ------------------------------------------------ in-vacuo frequencies (for orientation)
    s = galerkin(cs, 12, 12)
    from scipy import linalg
    om0 = np.sqrt(np.sort(linalg.eigvalsh(s.Ks, s.Ms)))[:6]
    print("in-vacuo frequencies (Galerkin 12+12):", om0)

    # ------------------------------------------------ Theodorsen flutter, Galerkin convergence
    kgrid = np.geomspace(4.0, 0.02, 500)
    last = None
    for N in (1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 20):
        sm = galerkin(cs, N, N)
        cr, _, _ = kmethod_crossings(sm, kgrid, branches=min(2 * N, 8))
        fl = [c for c in cr if c["direction"] > 0]
        if fl:
            add("flutter", "theodorsen", "galerkin", N, fl[0]["U"], fl[0]["omega"], "k-method, Nb = Nt = %d" % N)
            last = fl[0]
    ref = last
    # p-k check on the finest Galerkin model
    sm = galerkin(cs, 20, 20)
    state = {"p": 1j * ref["omega"]}

    def fpk(U):
        p = sm.pk_root(U, state["p"])
        return p.real

    Uc = optimize.brentq(fpk, ref["U"] * 0.99, ref["U"] * 1.01, xtol=1e-13, rtol=1e-15)
    pc = sm.pk_root(Uc, state["p"])
    add("flutter", "theodorsen", "galerkin_pk", 20, Uc, pc.imag, "p-k, Nb = Nt = 20")

    # ------------------------------------------------ Theodorsen flutter, FE convergence
    for nel in (8, 16, 32, 64, 128):
        sf = fe(cs, nel)
        r = kmethod_local(sf, ref["k"] * 0.8, ref["k"] * 1.25, ref["omega"])
        add("flutter", "theodorsen", "fe", nel, r["U"], r["omega"], "k-method")

    # ------------------------------------------------ finite-state / QS, Galerkin
    Ugrid = np.arange(cs["dU"], cs["Umax"], cs["dU"])
    om_min = 0.2 * om0[0]
    for N in (4, 6, 8, 10, 12):
        sm = galerkin(cs, N, N)
        for lag in [jones(), peters(6)] + ([quasi_steady()] + [peters(n) for n in (2, 4, 8, 10)] if N == 10 else []):
            res = ss_flutter(sm, lag, Ugrid, om_min, xtol=1e-11)
            if res is None:
                print("%s N=%d: no crossing in the grid" % (lag.name, N))
                continue
            if res.get("from_start"):
                add("flutter", lag.name, "galerkin_ss", N, 0.0, res["omega"],
                    "unstable from U -> 0+ (Re p = %.3e at U = %g)" % (res["p"].real, res["U_first"]))
                continue
            add("flutter", lag.name, "galerkin_ss", N, res["U"], res["omega"], "state space, Nb = Nt = %d" % N)
            if N == 10 and lag.name != "quasi_steady":
                Cf = peters_Cf(int(lag.name[6:])) if lag.name.startswith("peters") else (lambda k, lag=lag: lag.C(1j * k))
                kk = res["omega"] * b / res["U"]
                r = kmethod_local(sm, kk * 0.9, kk * 1.1, res["omega"], Cfun=Cf, npts=21)
                add("flutter", lag.name, "galerkin_k", N, r["U"], r["omega"], "k-method with the model's C(ik)")

    # quasi-steady: the lowest-U instabilities
    sm = galerkin(cs, 10, 10)
    print("quasi-steady C = 1 (with apparent mass): eigenvalues of the oscillatory branches, Galerkin 10+10")
    qs_rows = []
    for U in (0.01, 0.1, 0.5, 1, 2, 5, 10, 15, 20, 25, 30) if name == "patil" else (1, 5, 10, 20, 40, 60, 80, 100, 120):
        ev = sm.ss_eigs(U, quasi_steady())
        ev = ev[ev.imag > 0]
        ev = ev[np.argsort(ev.imag)][:4]
        qs_rows.append((U, ev))
        print("  U = %6.2f: " % U + "  ".join("%.6e%+.6fi" % (p.real, p.imag) for p in ev))

    # ------------------------------------------------ V-g: Theodorsen p-k and Peters 6 / Jones state space
    sm = galerkin(cs, 10, 10)
    nbr = 4
    om_vac = np.sqrt(np.sort(linalg.eigvals(sm.Ks, sm.M).real))[:nbr]
    vg = []
    Uvg = np.arange(cs["dUvg"], cs["Umax"] + 1e-9, cs["dUvg"])
    step_out = 1.0 if name == "patil" else 5.0
    guess = [1j * w for w in om_vac]
    for U in Uvg:
        guess = [sm.pk_root(U, g) for g in guess]
        if abs(U / step_out - round(U / step_out)) < 1e-9:
            for j, p in enumerate(guess):
                vg.append(("theodorsen_pk", U, j, p.real, p.imag))
    for lag in (peters(6), jones()):
        ev = sm.ss_eigs(Uvg[0], lag)
        cur = [ev[np.argmin(np.abs(ev - 1j * w))] for w in om_vac]
        for U in Uvg:
            ev = sm.ss_eigs(U, lag)
            cur = follow(cur, ev)
            if abs(U / step_out - round(U / step_out)) < 1e-9:
                for j, p in enumerate(cur):
                    vg.append((lag.name, U, j, p.real, p.imag))

    # ------------------------------------------------ write
    with open(os.path.join(HERE, "beam_%s_points.csv" % name), "w") as f:
        f.write("quantity,model,discretization,n,U_m_s,omega_rad_s,k,note\n")
        for r in rows:
            f.write("%s,%s,%s,%d,%s,%s,%s,%s\n" % (r[0], r[1], r[2], r[3], fmt(r[4]), fmt(r[5]), fmt(r[6]),
                                                    r[7].replace(",", ";")))
    with open(os.path.join(HERE, "beam_%s_vg.csv" % name), "w") as f:
        f.write("model,U_m_s,branch,re_p_1_s,im_p_rad_s\n")
        for r in vg:
            f.write("%s,%s,%d,%s,%s\n" % (r[0], fmt(round(r[1], 9)), r[2], fmt(r[3]), fmt(r[4])))
    with open(os.path.join(HERE, "beam_%s_quasi_steady.csv" % name), "w") as f:
        f.write("U_m_s,branch,re_p_1_s,im_p_rad_s\n")
        for U, ev in qs_rows:
            for j, p in enumerate(ev):
                f.write("%s,%d,%s,%s\n" % (fmt(U), j, fmt(p.real), fmt(p.imag)))
    pub = cs["published"]
    print("published: U_F = %g, omega_F = %g, U_D = %g" % (pub["U_F"], pub["omega_F"], pub["U_D"]))
    print("converged (Galerkin 20+20, Theodorsen): U_F = %.10f (%.3f %% from published), omega_F = %.10f (%.3f %%)" % (
        ref["U"], 100 * (pub["U_F"] / ref["U"] - 1), ref["omega"], 100 * (pub["omega_F"] / ref["omega"] - 1)))
    print("closed-form divergence: %.10f (published %.2f, %.3f %%)" % (UD, pub["U_D"], 100 * (pub["U_D"] / UD - 1)))
    print("%s done in %.1f s" % (name, time.time() - t0))


if __name__ == "__main__":
    for nm in (sys.argv[1:] or ["patil", "goland"]):
        main(nm)
