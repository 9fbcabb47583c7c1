"""Flutter solvers on the Ritz system of rod.py (k-method with any C(ik), p-k, state space), and the
exact (discretization-free) flutter point by Newton on the shooting determinant.

The strip-theory matrices come from ../aero_reference/aero_common.py (StripSystem, project=True: exact
for a uniform chord, elastic axis and speed), the existing independent planar reference's code; the
structural matrices and the strip rows H (plunge down) and P (pitch nose-up) are the deformed wing's
(rod.RitzRod).
"""

import math
import os
import sys

import numpy as np
from scipy import linalg, optimize

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "aero_reference"))
from aero_common import StripSystem, jones, peters, theodorsen  # noqa: E402,F401

NEUTRAL_G = 1e-9  # a branch whose |g| stays below this everywhere carries no aerodynamic load


def lag_C(lag):
    return lambda k: lag.C(1j * k)


def _track(prev, cur):
    cost = np.abs(prev[:, None] - cur[None, :])
    r, c = optimize.linear_sum_assignment(cost)
    out = np.empty_like(prev)
    out[r] = cur[c]
    return out


def k_branches(S, kgrid, Cfun):
    kgrid = np.sort(np.asarray(kgrid))[::-1]
    Z0 = S.k_eigs(kgrid[0], Cfun)
    Zs = [Z0[np.argsort(-Z0.real)]]
    for k in kgrid[1:]:
        Zs.append(_track(Zs[-1], S.k_eigs(k, Cfun)))
    return kgrid, np.array(Zs)


def k_crossings(S, Cfun, kgrid, nbr, Umax=80.0, xtol=1e-15):
    """Zeros of g = Im Z / Re Z on the nbr lowest-frequency branches (k-method), refined by Brent on k.
    Neutral branches (|g| < NEUTRAL_G everywhere: no aerodynamic coupling, e.g. lag at zero load)
    are skipped. direction +1: unstable for speeds just above (g goes - to + as U grows)."""
    kgrid, Zs = k_branches(S, kgrid, Cfun)
    out = []
    for j in range(nbr):
        Zj = Zs[:, j]
        g = Zj.imag / Zj.real
        if np.max(np.abs(g)) < NEUTRAL_G:
            out.append(dict(branch=j, neutral=True, omega=1 / math.sqrt(Zj[0].real)))
            continue
        for i in range(len(kgrid) - 1):
            if Zj[i].real <= 0 or Zj[i + 1].real <= 0:
                continue
            if g[i] * g[i + 1] < 0:
                k1, k2, Z1, Z2 = kgrid[i], kgrid[i + 1], Zj[i], Zj[i + 1]

                def pick(k):
                    t = (k - k1) / (k2 - k1)
                    ev = S.k_eigs(k, Cfun)
                    return ev[np.argmin(np.abs(ev - (Z1 + t * (Z2 - Z1))))]

                kc = optimize.brentq(lambda k: (lambda Z: Z.imag / Z.real)(pick(k)), k2, k1, xtol=xtol,
                                     rtol=4 * np.finfo(float).eps, maxiter=200)
                Z = pick(kc)
                om = 1 / math.sqrt(Z.real)
                U = om * S.b / kc
                if U <= Umax:
                    out.append(dict(branch=j, neutral=False, k=kc, U=U, omega=om,
                                    direction=1 if g[i + 1] > g[i] else -1))
    return out


def first_onset(cr):
    on = [c for c in cr if not c.get("neutral") and c["direction"] > 0]
    return min(on, key=lambda c: c["U"]) if on else None


def pk_root(S, U, p0, Cfun=theodorsen, tol=1e-12, maxit=100):
    """p-k: for speed U, the root p of det(p^2 M + p (U Ct - c G E2) + Ks - U c G E1) = 0,
    c = cla rho U b C(k), k = Im(p) b / U, iterated on k from p0 (companion pencil, no inverse of M)."""
    n = S.N
    I = np.eye(n)
    Z = np.zeros((n, n))
    B = np.block([[I, Z], [Z, S.M]])
    p = p0
    for it in range(maxit):
        k = max(abs(p.imag) * S.b / U, 1e-10)
        c = S.cla * S.rho * U * S.b * Cfun(k)
        Kp = S.Ks - U * c * S.G @ S.E1
        Cp = U * S.Ct - c * S.G @ S.E2
        A = np.block([[Z, I], [-Kp, -Cp]])
        ev = linalg.eigvals(A, B)
        ev = ev[np.isfinite(ev)]
        pn = ev[np.argmin(np.abs(ev - p))]
        if abs(pn - p) < tol * abs(pn):
            return pn
        p = pn
    raise RuntimeError("p-k did not converge at U = %g" % U)


def pk_flutter(S, U_guess, om_guess, dU=0.05):
    """p-k (Theodorsen): Brent on Re p(U) of the branch through (U_guess, i om_guess)."""
    p_ref = pk_root(S, U_guess, 1j * om_guess)

    def f(U):
        return pk_root(S, U, p_ref).real

    Uc = optimize.brentq(f, U_guess * (1 - dU), U_guess * (1 + dU), xtol=1e-12, rtol=4 * np.finfo(float).eps)
    return Uc, pk_root(S, Uc, p_ref)


def ss_branches(S, lag, Ugrid, om_start, om_max):
    """State-space eigenvalues along Ugrid, branches started at the structural roots nearest i*om_start
    (list) at the first speed and followed by one-to-one nearest matching among eigenvalues with
    Im p > 0 and Im p < om_max."""
    from aero_common import follow

    ev = S.ss_eigs(Ugrid[0], lag)
    cur = [ev[np.argmin(np.abs(ev - 1j * w))] for w in om_start]
    hist = [cur]
    for U in Ugrid[1:]:
        ev = S.ss_eigs(U, lag)
        ev = ev[(ev.imag > -1e-9) & (ev.imag < om_max)]
        cur = follow(cur, ev)
        hist.append(cur)
    return np.array(hist)


def ss_onsets(S, lag, Ugrid, om_start, om_max, tol_re=1e-9):
    """Every upward crossing of Re p = 0 on the followed branches, refined by Brent with nearest
    tracking. Branches with |Re p| < tol_re |p| everywhere are neutral (skipped). Returns
    (onsets, unstable_at_first_speed) lists."""
    from aero_common import ss_flutter_branch

    H = ss_branches(S, lag, Ugrid, om_start, om_max)
    on, from_start = [], []
    for j in range(H.shape[1]):
        re = H[:, j].real
        if np.max(np.abs(re) / np.abs(H[:, j])) < tol_re:
            continue
        if re[0] > tol_re * abs(H[0, j]):
            from_start.append(dict(branch=j, U=Ugrid[0], p=H[0, j]))
        for i in range(len(Ugrid) - 1):
            if re[i] < 0 <= re[i + 1]:
                Uc, p = ss_flutter_branch(S, lag, Ugrid[i], Ugrid[i + 1], H[i, j], xtol=1e-12)
                on.append(dict(branch=j, U=Uc, omega=p.imag, p=p))
    on.sort(key=lambda d: d["U"])
    return on, from_start, H


def exact_flutter(sh, Cfun, U0, om0, b, tol=1e-12, maxit=30):
    """Newton on det(i om; C(om b / U), U) = 0 in the two real unknowns (U, om); forward-difference
    Jacobian (step 1e-7 relative). Returns U, om, |det| history."""
    x = np.array([U0, om0], float)

    def F(x):
        U, om = x
        d = sh.det(1j * om, Cfun(om * b / U), U)
        return d

    d0 = F(x)
    scale = abs(d0)
    hist = []
    for it in range(maxit):
        d = F(x)
        hist.append(abs(d) / scale)
        J = np.zeros((2, 2))
        for m in range(2):
            h = 1e-7 * x[m]
            e = np.zeros(2)
            e[m] = h
            dd = (F(x + e) - d) / h
            J[:, m] = [dd.real, dd.imag]
        dx = np.linalg.solve(J, -np.array([d.real, d.imag]))
        x = x + dx
        if np.max(np.abs(dx) / x) < tol:
            break
    return x[0], x[1], hist


def vacuum_shooting(sh, om_guess, rel=1e-3):
    """In-vacuo natural frequency near om_guess from the real determinant det(i om) (no aero)."""
    f = lambda w: sh.det(1j * w).real  # noqa: E731  (p^2 = -om^2: the system is real)
    a, b = om_guess * (1 - rel), om_guess * (1 + rel)
    fa, fb = f(a), f(b)
    while fa * fb > 0:
        rel *= 2
        a, b = om_guess * (1 - rel), om_guess * (1 + rel)
        fa, fb = f(a), f(b)
    return optimize.brentq(f, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps)
