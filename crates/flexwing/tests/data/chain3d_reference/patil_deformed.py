#!/usr/bin/env python3
"""Patil's HALE wing about deformed equilibria: flutter and divergence against tip deflection.

Problem (README.md sec. 2): clamped straight wing, L = 16 m, GJ = 1e4, EI_flap = 2e4, EI_lag = 4e6 N m^2,
m = 0.75 kg/m, polar inertia 0.1 kg m about the elastic axis = mass centre (mid-chord), no bending
rotary inertia, inextensible and unshearable; chord 1 m, a = 0, cla = 2 pi, rho = 0.0889 kg/m^3, no
structural damping, root angle of attack 0. Loads: (a) dead vertical tip force F (up), no gravity;
(b) gravity g = 9.81 m/s^2 downward times a factor gamma, no tip force. Both equilibria are planar
(bending in the vertical plane, no twist), the angle of attack is zero everywhere, so the steady
aerodynamic load at the equilibrium vanishes at every speed: the equilibrium does not depend on U.

Linearized dynamics about it (rod.py), strip theory on the deformed geometry (plunge along the
deformed section normal, pitch about the deformed axis), flutter by
  * Ritz (N = 12 polynomials per rotation component) + k-method with C(ik) of each model
    (Theodorsen, Peters 6, Jones, quasi-steady C = 1), every crossing of every branch;
  * p-k (Theodorsen) on the Ritz system at the first onset;
  * the exact point by Newton on the shooting determinant (no discretization), from the Ritz point;
divergence from the Ritz steady stiffness and from the shooting determinant at p = 0.
Also the in-vacuo frequencies about each equilibrium, and a convergence study in N.

Writes patil_deformed_*.csv. Run: python3 patil_deformed.py > patil_deformed_run.log  (~10 min)
"""
import math
import os
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402
from scipy import optimize  # noqa: E402

from flutter import (StripSystem, exact_flutter, first_onset, jones, k_crossings, lag_C, peters, pk_flutter,  # noqa: E402
                     ss_onsets, theodorsen, vacuum_shooting)
from rod import PlanarStatic, RitzRod, Shooting, planar_static_fields  # noqa: E402

sys.path.insert(0, os.path.join(HERE, "..", "aero_reference"))
from aero_common import quasi_steady  # noqa: E402

L = 16.0
C = (1e4, 4e6, 2e4)  # GJ, EI_lag, EI_flap on (t, n, c)
J = (0.1, 0.0, 0.0)  # polar, lag-rotary, flap-rotary (kg m) about the axis
J_AEROBEAMS = (0.1, 0.1 - 0.1 * 2e4 / 4e6, 0.1 * 2e4 / 4e6)  # AeroBeams' SMW: rho Iz, rho Iy split of 0.1
MU = 0.75
G = 9.81
B, A, RHO, CLA = 0.5, 0.0, 0.0889, 2 * math.pi
AERO = dict(b=B, a=A, rho=RHO, cla=CLA)
N_SCAN = 12
KGRID = np.geomspace(6.0, 0.02, 220)
NBR = 8

TIP_FORCES = [0.0, 3.0, 6.0, 9.0, 12.0, 15.0, 18.0, 21.0, 24.0, 27.0, 30.0, 33.0, 36.0, 39.0, 42.0]
GRAVITY = [0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0]


def fmt(x):
    return repr(float(x))


def models():
    p6, jo, qs = peters(6), jones(), quasi_steady()
    return [("theodorsen", theodorsen, None), ("peters6", lag_C(p6), p6), ("jones", lag_C(jo), jo),
            ("quasi_steady", lambda k: 1.0 + 0j, qs)]


def system(ps, N, Jsec=J):
    r = RitzRod(L, C, Jsec, MU, N, planar_static_fields(ps, C))
    return r, StripSystem(r.Ms, r.Ks, r.H, r.P, r.w, B, A, RHO, cla=CLA, project=True)


def divergence_shooting(sh, U0):
    f = lambda U: sh.det(0.0, 1.0, U).real  # noqa: E731  (p = 0, C(0) = 1: real)
    a, b = U0 * 0.999, U0 * 1.001
    return optimize.brentq(f, a, b, xtol=1e-13, rtol=4 * np.finfo(float).eps)


def main():
    t00 = time.time()
    flut_rows, cross_rows, vac_rows, conv_rows = [], [], [], []
    ML = models()
    cases = [("tip_force", F, PlanarStatic(L, C[2], F=F)) for F in TIP_FORCES]
    cases += [("gravity", g, PlanarStatic(L, C[2], q=-MU * G * g)) for g in GRAVITY]
    for case, load, ps in cases:
        t0 = time.time()
        tip_x, tip_y = ps.tip[2], ps.tip[3]
        print("=== %s %g: tip (x, y) = (%.12f, %.12f) m, root theta' = %.12e" % (case, load, tip_x, tip_y, ps.k0))
        r, S = system(ps, N_SCAN)
        sh = Shooting(ps, C, J, MU, aero=AERO)
        shv = Shooting(ps, C, J, MU)
        # in-vacuo frequencies
        om = r.vacuum_frequencies()[:6]
        omx = [vacuum_shooting(shv, w) for w in om[:5]]
        print("  vacuum (Ritz N=%d): %s" % (N_SCAN, " ".join("%.10f" % w for w in om)))
        print("  vacuum (shooting):  %s" % " ".join("%.10f" % w for w in omx))
        for i, w in enumerate(om):
            vac_rows.append((case, load, tip_x, tip_y, i, w, omx[i] if i < len(omx) else float("nan")))
        # divergence
        ud = S.divergence_speeds()
        if ud:
            udx = divergence_shooting(sh, ud[0])
            print("  divergence: Ritz %.12f  shooting %.12f" % (ud[0], udx))
            flut_rows.append((case, load, tip_x, tip_y, "steady", "divergence", udx, 0.0, 0.0, ud[0], 0.0, ""))
        # flutter, every model
        for name, Cf, lag in ML:
            cr = k_crossings(S, Cf, KGRID, NBR)
            for c in cr:
                if c.get("neutral"):
                    print("  %-12s branch %d neutral (omega %.6f): no aerodynamic coupling" % (name, c["branch"], c["omega"]))
                    continue
                cross_rows.append((case, load, tip_x, tip_y, name, c["branch"], "onset" if c["direction"] > 0 else "offset",
                                   c["U"], c["omega"], c["k"]))
            fo = first_onset(cr)
            note = ""
            if name == "quasi_steady":
                on, start, _ = ss_onsets(S, lag, np.arange(0.5, 45.01, 0.5), om[:NBR], 150.0)
                if start:
                    s0 = start[0]
                    note = "unstable from U -> 0+; Re p = %.4e at U = %g (omega %.4f)" % (s0["p"].real, s0["U"], s0["p"].imag)
                    print("  %-12s %s" % (name, note))
                    flut_rows.append((case, load, tip_x, tip_y, name, "unstable_from_start", 0.0, s0["p"].imag, 0.0, 0.0,
                                      s0["p"].imag, note))
                    continue
            if fo is None:
                print("  %-12s no onset below the scan's top speed" % name)
                continue
            Ux, omx_, hist = exact_flutter(sh, Cf, fo["U"], fo["omega"], B)
            extra = ""
            if name == "theodorsen":
                Up, p = pk_flutter(S, fo["U"], fo["omega"])
                extra = "  p-k %.12f (Re p %.1e)" % (Up, p.real)
                note = "p-k Ritz N=%d: %s" % (N_SCAN, fmt(Up))
            print("  %-12s onset branch %d: Ritz k-method U = %.12f om = %.12f | exact U = %.12f om = %.12f%s"
                  % (name, fo["branch"], fo["U"], fo["omega"], Ux, omx_, extra))
            flut_rows.append((case, load, tip_x, tip_y, name, "flutter", Ux, omx_, omx_ * B / Ux, fo["U"], fo["omega"], note))
        print("  (%.1f s)" % (time.time() - t0))

    # ---------------- convergence in N at three loads (Theodorsen onset, divergence, torsion-like vacuum freq)
    print("=== convergence in N (Ritz), Theodorsen k-method onset and divergence")
    for case, load, ps in [("tip_force", 0.0, PlanarStatic(L, C[2])), ("tip_force", 24.0, PlanarStatic(L, C[2], F=24.0)),
                           ("tip_force", 42.0, PlanarStatic(L, C[2], F=42.0)),
                           ("gravity", 1.0, PlanarStatic(L, C[2], q=-MU * G))]:
        sh = Shooting(ps, C, J, MU, aero=AERO)
        r, S = system(ps, 16)
        fo = first_onset(k_crossings(S, theodorsen, KGRID, NBR))
        ref = exact_flutter(sh, theodorsen, fo["U"], fo["omega"], B)
        refd = divergence_shooting(sh, S.divergence_speeds()[0])
        for N in (3, 4, 5, 6, 8, 10, 12, 16, 20):
            r, S = system(ps, N)
            fo = first_onset(k_crossings(S, theodorsen, KGRID, min(NBR, 3 * N)))
            ud = S.divergence_speeds()[0]
            om = r.vacuum_frequencies()[:4]
            print("  %s %g N=%2d: U_F %.13f om_F %.13f (dU %.2e) U_D %.13f (dU %.2e) vac %s"
                  % (case, load, N, fo["U"], fo["omega"], fo["U"] - ref[0], ud, ud - refd, " ".join("%.11f" % w for w in om)))
            conv_rows.append((case, load, N, fo["U"], fo["omega"], ud, om[2], om[3], ref[0], ref[1], refd))

    # ---------------- variant: AeroBeams' rotary inertias (secondary comparison only)
    print("=== variant: section inertia (0.1, %.4f, %.4f) (AeroBeams' SMW), Theodorsen" % J_AEROBEAMS[1:])
    var_rows = []
    for case, load, ps in [("tip_force", F, PlanarStatic(L, C[2], F=F)) for F in (0.0, 12.0, 24.0, 36.0)] + \
                          [("gravity", 1.0, PlanarStatic(L, C[2], q=-MU * G))]:
        r, S = system(ps, N_SCAN, J_AEROBEAMS)
        fo = first_onset(k_crossings(S, theodorsen, KGRID, NBR))
        sh = Shooting(ps, C, J_AEROBEAMS, MU, aero=AERO)
        Ux, omx_, _ = exact_flutter(sh, theodorsen, fo["U"], fo["omega"], B)
        om = r.vacuum_frequencies()[:5]
        print("  %s %g: tip y %.6f  U_F %.10f om_F %.10f  vacuum %s" % (case, load, ps.tip[3], Ux, omx_, " ".join("%.6f" % w for w in om)))
        var_rows.append((case, load, ps.tip[2], ps.tip[3], Ux, omx_) + tuple(om))

    def write(name, header, rows):
        with open(os.path.join(HERE, name), "w") as f:
            f.write(header + "\n")
            for row in rows:
                f.write(",".join(x if isinstance(x, str) else (str(x) if isinstance(x, (int, np.integer)) else fmt(x)) for x in row) + "\n")

    write("patil_deformed_flutter.csv",
          "case,load,tip_x_m,tip_y_m,model,quantity,U_m_s,omega_rad_s,k,U_ritz12_m_s,omega_ritz12_rad_s,note", flut_rows)
    write("patil_deformed_crossings.csv",
          "case,load,tip_x_m,tip_y_m,model,branch,kind,U_m_s,omega_rad_s,k", cross_rows)
    write("patil_deformed_vacuum.csv", "case,load,tip_x_m,tip_y_m,mode,omega_ritz12_rad_s,omega_shooting_rad_s", vac_rows)
    write("patil_deformed_convergence.csv",
          "case,load,N,U_F_m_s,omega_F_rad_s,U_D_m_s,omega3_vac_rad_s,omega4_vac_rad_s,U_F_exact,omega_F_exact,U_D_exact",
          conv_rows)
    write("patil_deformed_variant_rotary.csv",
          "case,load,tip_x_m,tip_y_m,U_F_m_s,omega_F_rad_s,om1,om2,om3,om4,om5", var_rows)
    print("total %.1f s" % (time.time() - t00))


if __name__ == "__main__":
    main()
