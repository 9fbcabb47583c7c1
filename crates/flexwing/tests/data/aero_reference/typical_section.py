#!/usr/bin/env python3
"""Typical section (pitch-plunge airfoil) reference: divergence, flutter, V-g.

Case (Hodges & Pierce, 2nd ed., ch. 5, the worked example used throughout sec. 5.2-5.6):
  a = -1/5, e = -1/10 (mass centre b/10 ahead of mid-chord), x_theta = e - a = 1/10 (mass centre
  b/10 AFT of the elastic axis), r^2 = 6/25 (radius of gyration about the EA, in semichords),
  sigma = omega_h/omega_theta = 2/5, mu = m/(pi rho b^2) = 20, cla = 2 pi.
Nondimensional units: b = 1, omega_theta = 1, rho = 1 (so m = 20 pi); every speed below is
U/(b omega_theta), every frequency omega/omega_theta, every eigenvalue p/omega_theta.
flexwing terms: x_ea = 0.4, x_cg = 0.45 (chord fractions from the LE), d0 = -b/10 (mass centre aft),
I_ea = m r^2 b^2, I_cg = I_ea - m d0^2, k_h = m sigma^2, k_theta = I_ea.
Coordinates: eta = (y, psi): y plunge UP (flexwing's flap direction) and psi pitch nose-up.

Writes typical_section_flutter.csv, typical_section_vg.csv, ck_table.csv.
Run: python3 typical_section.py   (about a minute)
"""
import math
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small dense matrices: threads only add overhead

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from aero_common import (follow, PI, StripSystem, fmt, jones, kmethod_crossings, peters, peters_C_mp,  # noqa: E402
                         peters_matrices, peters_mu, quasi_steady, ss_flutter, theodorsen, theodorsen_mp)

HERE = os.path.dirname(os.path.abspath(__file__))

a, e, r2, sigma, mu = -0.2, -0.1, 6.0 / 25.0, 0.4, 20.0
b, rho, wth = 1.0, 1.0, 1.0
x_theta = e - a
m = mu * PI * rho * b * b
d0 = -x_theta * b
I_ea = m * r2 * b * b
k_h = m * (sigma * wth) ** 2
k_th = I_ea * wth ** 2

Ms = np.array([[m, m * d0], [m * d0, I_ea]])
Ks = np.diag([k_h, k_th])
H = np.array([[-1.0, 0.0]])  # plunge down = -y
P = np.array([[0.0, 1.0]])
sysm = StripSystem(Ms, Ks, H, P, [1.0], b, a, rho, name="typical")

rows = []  # model, method, U, omega, k, note


def add(model, method, U, om, note=""):
    k = om * b / U if U > 0 and om > 0 else 0.0
    rows.append((model, method, U, om, k, note))
    print("%-12s %-28s U = %.12f  omega = %.12f  k = %.10f  %s" % (model, method, U, om, k, note))


t0 = time.time()
# ------------------------------------------------------------------ divergence
UD_closed = math.sqrt(mu * r2 / (1 + 2 * a)) * b * wth
add("steady", "divergence_closed_form", UD_closed, 0.0, "sqrt(mu r^2/(1+2a))")
UD_num = sysm.divergence_speeds()[0]
add("steady", "divergence_eig", UD_num, 0.0, "det(K - U^2 Ka) = 0")

# ------------------------------------------------------------------ Theodorsen: k-method
kgrid = np.geomspace(3.0, 0.02, 600)
cr, _, _ = kmethod_crossings(sysm, kgrid)
flut = [c for c in cr if c["direction"] > 0]
print("k-method crossings:", [(c["branch"], c["U"], c["omega"], c["direction"]) for c in cr])
kf = flut[0]
add("theodorsen", "k_method_brent", kf["U"], kf["omega"], "branch %d" % kf["branch"])

# ------------------------------------------------------------------ Theodorsen: determinant, 30 digits
mp.mp.dps = 30
Mmp = mp.matrix(sysm.M.tolist())
Ctmp = mp.matrix(sysm.Ct.tolist())
Kmp = mp.matrix(Ks.tolist())
Gmp = mp.matrix(sysm.G.tolist())
E1mp = mp.matrix(sysm.E1.tolist())
E2mp = mp.matrix(sysm.E2.tolist())
bm, rhom, clam = mp.mpf(b), mp.mpf(rho), 2 * mp.pi


def det_mp(k, X):
    Ck = theodorsen_mp(k)
    A = Mmp - 1j * (bm / k) * Ctmp + clam * rhom * bm * Ck * Gmp * ((bm * bm / (k * k)) * E1mp + 1j * (bm / k) * E2mp)
    D = Kmp * X - A
    return mp.det(D)


def fdet(k, X):
    d = det_mp(k, X)
    return [mp.re(d), mp.im(d)]


sol = mp.findroot(fdet, (mp.mpf(kf["k"]), mp.mpf(1.0 / kf["omega"] ** 2)), tol=mp.mpf(10) ** -50)
k_mp, X_mp = sol[0], sol[1]
om_mp = 1 / mp.sqrt(X_mp)
U_mp = om_mp * bm / k_mp
print("determinant (mpmath 30 digits): U = %s omega = %s k = %s |det| = %s" % (
    mp.nstr(U_mp, 20), mp.nstr(om_mp, 20), mp.nstr(k_mp, 20), mp.nstr(abs(det_mp(k_mp, X_mp)), 3)))
add("theodorsen", "determinant_mpmath", float(U_mp), float(om_mp), "30-digit Newton on det, (k, 1/omega^2)")

# ------------------------------------------------------------------ Theodorsen: textbook 2x2 determinant
# Written out entry by entry from the scalar equations (Hodges & Pierce ch. 5, h down, theta nose up),
# independently of aero_common.StripSystem, as a check of its matrices and signs:
#   m (h'' + b x_th th'') + k_h h = -L,   I_ea th'' + m b x_th h'' + k_th th = M_ea
def det_textbook(k, om):
    U = om * b / k
    C = theodorsen_mp(k)
    i = 1j
    mb = mp.mpf(m)
    pr = mp.pi * rho * b * b
    # L = Lh h + Lt th ; M = Mh h + Mt th  (harmonic amplitudes)
    Lh = pr * (-om ** 2) + 2 * mp.pi * rho * U * b * C * (i * om)
    Lt = pr * (U * i * om + b * a * om ** 2) + 2 * mp.pi * rho * U * b * C * (U + b * (0.5 - a) * i * om)
    Mh = pr * (-b * a * om ** 2) + 2 * mp.pi * rho * U * b * b * (a + 0.5) * C * (i * om)
    Mt = (pr * (-U * b * (0.5 - a) * i * om + b * b * (mp.mpf(1) / 8 + a * a) * om ** 2)
          + 2 * mp.pi * rho * U * b * b * (a + 0.5) * C * (U + b * (0.5 - a) * i * om))
    a11 = -om ** 2 * mb + k_h + Lh
    a12 = -om ** 2 * mb * b * x_theta + Lt
    a21 = -om ** 2 * mb * b * x_theta - Mh
    a22 = -om ** 2 * I_ea + k_th - Mt
    return a11 * a22 - a12 * a21


sol2 = mp.findroot(lambda k, om: [mp.re(det_textbook(k, om)), mp.im(det_textbook(k, om))],
                   (mp.mpf(kf["k"]), mp.mpf(kf["omega"])), tol=mp.mpf(10) ** -50)
U_tb = sol2[1] * b / sol2[0]
print("textbook determinant (mpmath): U = %s omega = %s; differs from the matrix form by %.1e" % (
    mp.nstr(U_tb, 20), mp.nstr(sol2[1], 20), float(abs(U_tb - U_mp))))
add("theodorsen", "determinant_textbook_mpmath", float(U_tb), float(sol2[1]), "2x2 written from the scalar equations")

# ------------------------------------------------------------------ Theodorsen: p-k
def pk_re(U, p_guess):
    return sysm.pk_root(U, p_guess)


# track both branches with p-k from low speed; keep them for V-g
lam0 = np.sort(np.sqrt(np.real(np.linalg.eigvals(np.linalg.solve(sysm.M, Ks)))))
Us = np.round(np.arange(0.05, 3.0001, 0.05), 10)
pk_branch = {0: [], 1: []}
guess = [1j * lam0[0], 1j * lam0[1]]
Ufine = np.arange(0.01, 3.0001, 0.01)
pk_track = []
for U in Ufine:
    ps = [sysm.pk_root(U, g) for g in guess]
    guess = ps
    pk_track.append((U, ps))
# flutter from p-k: bracket and Brent on Re p of the unstable branch
from scipy import optimize  # noqa: E402

for j in (0, 1):
    for i in range(len(pk_track) - 1):
        (U1, p1), (U2, p2) = pk_track[i], pk_track[i + 1]
        if p1[j].real < 0 <= p2[j].real:
            state = {"p": p1[j]}

            def fpk(U, j=j):
                p = sysm.pk_root(U, state["p"])
                return p.real

            Uc = optimize.brentq(fpk, U1, U2, xtol=1e-14, rtol=1e-15)
            pc = sysm.pk_root(Uc, p1[j])
            add("theodorsen", "p_k_brent", Uc, pc.imag, "branch %d (0 = plunge-like, 1 = pitch-like)" % j)
            break

# ------------------------------------------------------------------ finite-state and QS
models = [quasi_steady(), jones()] + [peters(N) for N in (2, 4, 6, 8, 10)]
for lag in models:
    res = ss_flutter(sysm, lag, np.arange(0.02, 4.0, 0.01), om_min=1e-3, xtol=1e-14)
    if res is None:
        add(lag.name, "state_space_eig", float("nan"), float("nan"), "no flutter below 4")
        continue
    add(lag.name, "state_space_eig", res["U"], res["omega"], "")
    # same aerodynamic model in the frequency domain (k-method with the model's C(ik))
    if lag.name.startswith("peters"):
        N = int(lag.name[6:])

        def Cf(k, N=N):
            return complex(peters_C_mp(N, 1j * mp.mpf(k)))
    else:
        def Cf(k, lag=lag):
            return lag.C(1j * k)
    cr, _, _ = kmethod_crossings(sysm, np.geomspace(3.0, 0.02, 300), Cfun=Cf)
    fl = [c for c in cr if c["direction"] > 0]
    if fl:
        add(lag.name, "k_method_brent", fl[0]["U"], fl[0]["omega"], "frequency domain, model C(ik)")

# descriptor (lambda, with w') form of Peters N = 6 as a check of the mu = lambda - A^-1 c w substitution
def peters_descriptor_eigs(U, N):
    from scipy import linalg

    A, bv, cv = peters_matrices(N)[:3]
    Nn = sysm.N
    c = sysm.cla * sysm.rho * U * sysm.b
    n = 2 * Nn + N
    E = np.zeros((n, n))
    F = np.zeros((n, n))
    E[:Nn, :Nn] = np.eye(Nn)
    F[:Nn, Nn:2 * Nn] = np.eye(Nn)
    # M v' + U Ct v + K eta = c G (U E1 eta + E2 v - 1/2 b^T lam)
    E[Nn:2 * Nn, Nn:2 * Nn] = sysm.M
    F[Nn:2 * Nn, :Nn] = -Ks + c * U * sysm.G @ sysm.E1
    F[Nn:2 * Nn, Nn:2 * Nn] = -U * sysm.Ct + c * sysm.G @ sysm.E2
    F[Nn:2 * Nn, 2 * Nn:] = -c * 0.5 * sysm.G @ bv.reshape(1, -1)
    # A lam' - c_p (U E1 v + E2 v') = -(U/b) lam
    E[2 * Nn:, 2 * Nn:] = A
    E[2 * Nn:, Nn:2 * Nn] = -np.outer(cv, sysm.E2[0])
    F[2 * Nn:, Nn:2 * Nn] = np.outer(cv, U * sysm.E1[0])
    F[2 * Nn:, 2 * Nn:] = -(U / sysm.b) * np.eye(N)
    return linalg.eigvals(F, E)


def eig_dist(ev1, ev2):
    r_, c_ = optimize.linear_sum_assignment(np.abs(ev1[:, None] - ev2[None, :]))
    return np.max(np.abs(ev1[r_] - ev2[c_]) / np.abs(ev2[c_]))


for Nd in (2, 6, 8, 10):
    evd = peters_descriptor_eigs(2.0, Nd)
    evm = sysm.ss_eigs(2.0, peters(Nd))
    evu = sysm.ss_eigs(2.0, peters_mu(Nd))
    print("Peters N=%d at U=2, max |dp|/|p| between realizations: descriptor (lambda, w') vs modal %.2e, "
          "mu-substituted vs modal %.2e" % (Nd, eig_dist(evd, evm), eig_dist(evu, evm)))

# ------------------------------------------------------------------ V-g table
vg = []
for U, ps in pk_track:
    if abs(U / 0.05 - round(U / 0.05)) < 1e-9:
        for j, p in enumerate(ps):
            vg.append(("theodorsen_pk", round(U, 10), j, p.real, p.imag))
for lag in models:
    ev0 = sysm.ss_eigs(0.01, lag)
    cur = [ev0[np.argmin(np.abs(ev0 - 1j * lam0[j]))] for j in (0, 1)]
    for U in np.arange(0.01, 3.0001, 0.005):
        ev = sysm.ss_eigs(U, lag)
        cur = follow(cur, ev)
        if abs(U / 0.05 - round(U / 0.05)) < 1e-9:
            for j, p in enumerate(cur):
                vg.append((lag.name, round(U, 10), j, p.real, p.imag))

with open(os.path.join(HERE, "typical_section_vg.csv"), "w") as f:
    f.write("model,U_over_b_omega_theta,branch,re_p_over_omega_theta,im_p_over_omega_theta\n")
    for r in vg:
        f.write("%s,%s,%d,%s,%s\n" % (r[0], fmt(r[1]), r[2], fmt(r[3]), fmt(r[4])))

with open(os.path.join(HERE, "typical_section_flutter.csv"), "w") as f:
    f.write("model,method,U_over_b_omega_theta,omega_over_omega_theta,k,note\n")
    for r in rows:
        f.write("%s,%s,%s,%s,%s,%s\n" % (r[0], r[1], fmt(r[2]), fmt(r[3]), fmt(r[4]), r[5].replace(",", ";")))

# ------------------------------------------------------------------ C(k) table
with open(os.path.join(HERE, "ck_table.csv"), "w") as f:
    f.write("model,k,re_C,im_C,abs_err_vs_theodorsen\n")
    mp.mp.dps = 40
    for k in [0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 5.0]:
        T = theodorsen_mp(mp.mpf(k))
        f.write("theodorsen,%s,%s,%s,0\n" % (fmt(k), mp.nstr(mp.re(T), 17), mp.nstr(mp.im(T), 17)))
        J = jones().C(1j * k)
        f.write("jones,%s,%s,%s,%s\n" % (fmt(k), fmt(J.real), fmt(J.imag), fmt(abs(J - complex(T)))))
        for N in (2, 4, 6, 8, 10, 12, 14):
            Cp = peters_C_mp(N, 1j * mp.mpf(k))
            f.write("peters%d,%s,%s,%s,%s\n" % (N, fmt(k), mp.nstr(mp.re(Cp), 17), mp.nstr(mp.im(Cp), 17),
                                                 mp.nstr(abs(Cp - T), 6)))
# ------------------------------------------------------------------ Peters' lag in modal form
with open(os.path.join(HERE, "peters_modal.csv"), "w") as f:
    f.write("N,D,kind,pole_re,pole_im,residue_re,residue_im\n")
    for N in (2, 4, 6, 8, 10):
        lg = peters(N)
        for s_, r_ in zip(lg.poles, lg.residues):
            kind = "real" if isinstance(s_, float) else "pair"
            s_, r_ = complex(s_), complex(r_)
            f.write("%d,%s,%s,%s,%s,%s,%s\n" % (N, fmt(lg.D), kind, fmt(s_.real), fmt(s_.imag), fmt(r_.real), fmt(r_.imag)))
print("done in %.1f s" % (time.time() - t0))
