#!/usr/bin/env python3
"""Lateral-torsional buckling of a cantilever under a dead tip force in its stiff plane.

Cantilever along x, length L = 1, clamped at s = 0; section frame (t, n, c) = (x, y, z) at rest;
C = diag(GJ, EI_weak, EI_strong): bending in the x-y plane (about c = z) uses EI_strong, lateral
bending (about n) EI_weak. Dead tip force P y (fixed direction, applied on the axis = shear centre),
no distributed load, no gravity. Kirchhoff rod (inextensible, unshearable, no warping stiffness).

  * Prandtl (1899): straight pre-buckling geometry, GJ phi'' + P^2 (L - s)^2 / EI_weak phi = 0,
    phi(0) = 0, phi'(L) = 0  =>  J_{-1/4}(gamma / 2) = 0,  gamma = P L^2 / sqrt(EI_weak GJ)
    = 2 j_{-1/4,1} (mpmath, 30 digits). Reproduced by the Ritz rod about the straight state with the
    moment m0 = P (L - s) z (a check of the geometric stiffness of rod.py).
  * Non-linear pre-buckling path: the planar large-deflection equilibrium in the stiff plane
    (rod.PlanarStatic, exact), and the smallest P at which the linearization about it becomes
    singular: Ritz (smallest eigenvalue of K_T(P) through zero, N = 4..24) and the shooting
    determinant at p = 0 (no discretization).

Writes ltb_points.csv. Run: python3 ltb.py > ltb_run.log (~1 min)
"""
import math
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402
from scipy import linalg, optimize  # noqa: E402

from rod import PlanarStatic, RitzRod, Shooting, planar_static_fields  # noqa: E402

L = 1.0
EIW = 1.0
GJ = 1.0
RATIOS = [0.0, 0.01, 0.1, 0.25]  # EI_weak / EI_strong (0: EI_strong -> infinity)


def fmt(x):
    return repr(float(x))


def prandtl_gamma():
    mp.mp.dps = 30
    z = mp.findroot(lambda x: mp.besselj(mp.mpf(-1) / 4, x), 2.0)
    return 2 * z


def straight_fields(P):
    def fn(s):
        M = len(s)
        t = np.tile([1.0, 0, 0], (M, 1))
        n = np.tile([0, 1.0, 0], (M, 1))
        c = np.tile([0, 0, 1.0], (M, 1))
        m0 = np.stack([np.zeros(M), np.zeros(M), P * (L - s)], 1)
        N0 = np.tile([0, P, 0], (M, 1))
        return dict(t=t, n=n, c=c, m0=m0, N0=N0)

    return fn


def min_eig(r):
    """Smallest eigenvalue of K_T relative to the elastic stiffness (generalized, symmetric)."""
    return linalg.eigh(r.Ks, r.Ke, eigvals_only=True)[0]


def main():
    t0 = time.time()
    gam = prandtl_gamma()
    print("Prandtl: gamma = 2 j_{-1/4,1} = %s" % mp.nstr(gam, 25))
    rows = [("prandtl_closed_form", "0", 0, float(gam), float("nan"), float("nan"), "J_{-1/4}(gamma/2) = 0")]
    # Prandtl by the Ritz rod about the straight state (EI_strong irrelevant there)
    C = (GJ, EIW, 100.0)
    for N in (4, 6, 8, 12, 16):
        P = optimize.brentq(lambda P: min_eig(RitzRod(L, C, (0, 0, 0), 1.0, N, straight_fields(P))), 3.0, 5.0,
                            xtol=1e-14, rtol=4 * np.finfo(float).eps)
        print("  Ritz straight N=%2d: gamma = %.15f  (err %.2e)" % (N, P, P - float(gam)))
        rows.append(("ritz_straight", "0", N, P, float("nan"), float("nan"), "linearized about the straight state"))
    # non-linear pre-buckling path
    for ratio in RATIOS[1:]:
        EIS = EIW / ratio
        C = (GJ, EIW, EIS)
        print("=== EI_weak/EI_strong = %g (EI_strong = %g)" % (ratio, EIS))

        def fritz(P, N):
            ps = PlanarStatic(L, EIS, F=P)
            return min_eig(RitzRod(L, C, (0, 0, 0), 1.0, N, planar_static_fields(ps, C)))

        Pprev = None
        for N in (4, 6, 8, 12, 16, 24):
            P = optimize.brentq(lambda P: fritz(P, N), 3.0, 8.0, xtol=1e-14, rtol=4 * np.finfo(float).eps)
            print("  Ritz N=%2d: P_cr = %.15f" % (N, P))
            Pprev = P
            rows.append(("ritz_nonlinear_path", fmt(ratio), N, P, float("nan"), float("nan"), ""))

        def fshoot(P):
            ps = PlanarStatic(L, EIS, F=P)
            sh = Shooting(ps, C, (0, 0, 0), 1.0)
            return np.linalg.det(sh.tip_matrix(0.0).real)

        Ps = optimize.brentq(fshoot, Pprev * (1 - 1e-4), Pprev * (1 + 1e-4), xtol=1e-14, rtol=4 * np.finfo(float).eps)
        ps = PlanarStatic(L, EIS, F=Ps)
        tip_x, tip_y = ps.tip[2], ps.tip[3]
        approx = float(gam) / math.sqrt((1 - ratio) * (1 - GJ / EIS))
        print("  shooting: P_cr = %.15f  (gamma %.12f, +%.4f %% over Prandtl); tip at P_cr (%.12f, %.12f)"
              % (Ps, Ps / math.sqrt(EIW * GJ), 100 * (Ps / float(gam) - 1), tip_x, tip_y))
        print("  classical pre-buckling-deflection estimate gamma_P / sqrt((1 - EIw/EIs)(1 - GJ/EIs)) = %.6f (%.3f %% from exact)"
              % (approx, 100 * (approx / Ps - 1)))
        rows.append(("shooting_nonlinear_path", fmt(ratio), 0, Ps, tip_x, tip_y, "exact (no discretization)"))
        rows.append(("approx_sqrt_factor", fmt(ratio), 0, approx, float("nan"), float("nan"),
                     "gamma_Prandtl / sqrt((1 - EIw/EIs)(1 - GJ/EIs)); approximate only"))
        # stability flag check points: smallest eigenvalue just below and above
        for f in (0.99, 1.01):
            psf = PlanarStatic(L, EIS, F=f * Ps)
            lam = min_eig(RitzRod(L, C, (0, 0, 0), 1.0, 16, planar_static_fields(psf, C)))
            print("    P = %.4f P_cr: smallest eigenvalue of K_T (relative to K_elastic) = %+.6e" % (f, lam))
    with open(os.path.join(HERE, "ltb_points.csv"), "w") as fo:
        fo.write("method,EI_weak_over_EI_strong,N,P_cr_over_sqrt_EIw_GJ_over_L2,tip_x_at_Pcr,tip_y_at_Pcr,note\n")
        for r in rows:
            fo.write(",".join(x if isinstance(x, str) else (str(x) if isinstance(x, int) else fmt(x)) for x in r) + "\n")
    print("total %.1f s" % (time.time() - t0))


if __name__ == "__main__":
    main()
