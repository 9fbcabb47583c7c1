"""Shared machinery of the independent aeroelastic references (strip theory, linear).

Written from the literature, not from flexwing's Rust sources:
  * Theodorsen, NACA TR 496 (1935): C(k) = H1(2)(k) / (H1(2)(k) + i H0(2)(k)), loads below.
  * R. T. Jones, NACA TR 681 (1940): Wagner phi(s) ~ 1 - 0.165 e^{-0.0455 s} - 0.335 e^{-0.3 s}.
  * Peters, Karunamoorthy & Cao, J. Aircraft 32(2), 1995; Hodges & Pierce (2nd ed., 2011) sec. 5.5:
    A lam' + (U/b) lam = c w',  lam0 = 1/2 b^T lam,  A = D + d b^T + c d^T + 1/2 c b^T.

Conventions (flexwing, aeroelastic.md sec. 1): structural coordinates are whatever the caller uses;
the caller supplies, for every strip s (span station with integration weight W_s),
  H[s, :]  plunge *down* (Theodorsen's h = -y) per unit generalized coordinate,
  P[s, :]  pitch, nose-up (= flexwing's twist psi) per unit generalized coordinate.
Section (uniform over the span): semichord b, Theodorsen a (EA at b*a aft of mid-chord), lift slope
cla, air density rho.  Loads per unit span (Theodorsen; h down, alpha nose up):
  w      = U alpha + hdot + b (1/2 - a) alphadot                       (3/4-chord downwash)
  L      = cla rho U b  C[w]  +  pi rho b^2 (hddot + U alphadot - b a alphaddot)      (up)
  M_ea   = b (1/2 + a) cla rho U b C[w]
           + pi rho b^2 (b a hddot - U b (1/2 - a) alphadot - b^2 (1/8 + a^2) alphaddot)  (nose up)
Generalized force Q = sum_s W_s (-H_s^T L_s + P_s^T M_s).

Resulting linear equations:  M eta'' + U Ct eta' + K eta = cla rho U b G C[ U E1 eta + E2 eta' ]
  M  = Ms + pi rho b^2 [H^T W H - b a (H^T W P + P^T W H) + b^2 (1/8 + a^2) P^T W P]
  Ct = pi rho b^2 [H^T W P + b (1/2 - a) P^T W P]
  R  = (-H + b (1/2 + a) P)^T W          (N x S)
  per strip:    G = R,  E1 = P,  E2 = H + b (1/2 - a) P
  projected:    G = I,  E1 = R P, E2 = R (H + b(1/2 - a) P)   (exact when b, a, U are uniform,
                because C[.] is the same linear time-invariant operator at every strip)
C[.] is Theodorsen's C(k) in the frequency domain, or a rational (finite-state) approximation
  C(pbar) = D + Ca (pbar I - Aa)^{-1} Ba,  pbar = p b / U,
realized per strip as  x' = (U/b)(Aa x + Ba w),  w_eff = Ca x + D w.
"""

import math

import numpy as np
from scipy import linalg, optimize, special

PI = math.pi


# ----------------------------------------------------------------------------------------------
# Aerodynamic operators
# ----------------------------------------------------------------------------------------------
def theodorsen(k):
    """Theodorsen's function C(k) = F + iG for real k > 0 (e^{i omega t} convention)."""
    h1 = special.hankel2(1, k)
    h0 = special.hankel2(0, k)
    return h1 / (h1 + 1j * h0)


def theodorsen_mp(k):
    import mpmath as mp

    h1 = mp.hankel2(1, k)
    h0 = mp.hankel2(0, k)
    return h1 / (h1 + 1j * h0)


class Lag:
    """Rational approximation C(pbar) = D + Ca (pbar I - Aa)^{-1} Ba of the circulatory lag."""

    def __init__(self, name, Aa, Ba, Ca, D):
        self.name = name
        self.Aa = np.atleast_2d(np.asarray(Aa, float)) if np.size(Aa) else np.zeros((0, 0))
        self.Ba = np.asarray(Ba, float).reshape(-1)
        self.Ca = np.asarray(Ca, float).reshape(-1)
        self.D = float(D)
        self.n = self.Ba.size

    def C(self, pbar):
        if self.n == 0:
            return self.D + 0j
        return self.D + self.Ca @ np.linalg.solve(pbar * np.eye(self.n) - self.Aa, self.Ba.astype(complex))


def quasi_steady():
    return Lag("quasi_steady", np.zeros((0, 0)), [], [], 1.0)


JONES_A = (0.165, 0.335)
JONES_B = (0.0455, 0.3)


def jones():
    """R. T. Jones: C(pbar) = 1 - A1 - A2 + sum A_k b_k / (pbar + b_k).
    States z_k: z_k' = -b_k (U/b) z_k + w, w_eff = (1-A1-A2) w + (U/b) sum A_k b_k z_k
    (aeroelastic.md form); here x_k = (U/b) z_k is used, same transfer function."""
    A1, A2 = JONES_A
    b1, b2 = JONES_B
    return Lag("jones", np.diag([-b1, -b2]), [1.0, 1.0], [A1 * b1, A2 * b2], 1.0 - A1 - A2)


def peters_matrices(N):
    """A, b, c, d of Peters' finite-state inflow with N states (H&P eq. 5.xx, AeroFlex Peter.m).
    Integer factorials are exact (Python ints)."""
    D = np.zeros((N, N))
    for i in range(1, N + 1):  # 1-based as in the paper
        for j in range(1, N + 1):
            if i == j + 1:
                D[i - 1, j - 1] = 1.0 / (2 * i)
            elif i == j - 1:
                D[i - 1, j - 1] = -1.0 / (2 * i)
    bv = np.zeros(N)
    for n in range(1, N):
        bv[n - 1] = (-1) ** (n - 1) * math.factorial(N + n - 1) / math.factorial(N - n - 1) / math.factorial(n) ** 2
    bv[N - 1] = (-1) ** (N + 1)
    cv = np.array([2.0 / n for n in range(1, N + 1)])
    dv = np.zeros(N)
    dv[0] = 0.5
    A = D + np.outer(dv, bv) + np.outer(cv, dv) + 0.5 * np.outer(cv, bv)
    return A, bv, cv, dv


def peters_matrices_mp(N, dps=60):
    """Peters' A, b, c in mpmath (exact rationals to dps digits)."""
    import mpmath as mp

    with mp.workdps(dps):
        A = mp.zeros(N, N)
        for i in range(1, N + 1):
            for j in range(1, N + 1):
                if i == j + 1:
                    A[i - 1, j - 1] += mp.mpf(1) / (2 * i)
                elif i == j - 1:
                    A[i - 1, j - 1] -= mp.mpf(1) / (2 * i)
        bv = [mp.mpf(0)] * N
        for n in range(1, N):
            bv[n - 1] = mp.mpf((-1) ** (n - 1) * math.factorial(N + n - 1)) / (math.factorial(N - n - 1) * math.factorial(n) ** 2)
        bv[N - 1] = mp.mpf((-1) ** (N + 1))
        cv = [mp.mpf(2) / n for n in range(1, N + 1)]
        for i in range(N):
            for j in range(N):
                A[i, j] += (bv[j] / 2 if i == 0 else 0) + (cv[i] / 2 if j == 0 else 0) + cv[i] * bv[j] / 2
        return A, mp.matrix(bv), mp.matrix(cv)


def peters_mu(N):
    """Peters in the substituted form of aeroelastic.md (mu = lam - A^-1 c w):
        mu' = (U/b)(-A^-1 mu - A^-2 c w),  w_eff = (1 - 1/2 b^T A^-1 c) w - 1/2 b^T mu.
    Transfer function C(pbar) = 1 - 1/2 b^T (pbar A + I)^{-1} c pbar
                              = (1 - 1/2 b^T A^-1 c) + 1/2 b^T (pbar I + A^-1)^{-1} A^-2 c.
    The matrices are formed in 60-digit arithmetic and rounded once. Even so this realization is
    badly conditioned (A^-1 is far from normal, b has entries ~1e5 of alternating sign at N = 10):
    C(ik) evaluated from it in double precision is off by ~1e-9 at N = 10, and eigenvalues of a
    chain with N = 10 states per element are off by ~1e-4 rad/s (see README)."""
    import mpmath as mp

    with mp.workdps(60):
        A, bv, cv = peters_matrices_mp(N)
        Ai = A ** -1
        Bm = Ai * (Ai * cv)
        D = 1 - (bv.T * (Ai * cv))[0] / 2
        Aa = np.array([[float(-Ai[i, j]) for j in range(N)] for i in range(N)])
        Ba = np.array([float(Bm[i]) for i in range(N)])
        Ca = np.array([float(bv[i]) / 2 for i in range(N)])
        lag = Lag("peters%d_mu" % N, Aa, Ba, Ca, float(D))
    lag.raw = peters_matrices(N)[:3]
    return lag


def peters(N):
    """Peters' lag in real modal (partial-fraction) form, computed in 60-digit arithmetic:
        C(pbar) = D + sum_j r_j / (pbar - s_j),   s_j = eigenvalues of -A^-1 (real or conjugate pairs),
    one state per real pole (x' = (U/b)(s x + w), contribution r x) and two per conjugate pair
    (x' = (U/b)([[sr, -si], [si, sr]] x + [1, 0] w), contribution 2 Re(r) x1 - 2 Im(r) x2).
    Same transfer function as peters_mu (a constant similarity transform of it), but C(ik) is exact
    to 1e-16 in double precision and the state-matrix eigenvalues are well conditioned."""
    import mpmath as mp

    with mp.workdps(60):
        A, bv, cv = peters_matrices_mp(N)
        Ai = A ** -1
        Aa = -Ai
        Ba = Ai * (Ai * cv)
        Ca = bv / 2
        D = 1 - (bv.T * (Ai * cv))[0] / 2
        E, V = mp.eig(Aa)
        Vi = V ** -1
        beta = Vi * Ba
        gam = Ca.T * V
        tiny = mp.mpf(10) ** -30
        blocks, used = [], set()
        for j in range(N):
            if j in used:
                continue
            if abs(mp.im(E[j])) < tiny:
                blocks.append(("r", float(mp.re(E[j])), float(mp.re(gam[j] * beta[j]))))
                used.add(j)
                continue
            k = [i for i in range(N) if i not in used and i != j and abs(E[i] - mp.conj(E[j])) < mp.mpf(10) ** -20]
            assert len(k) == 1, "unpaired complex pole"
            used.update({j, k[0]})
            jj = j if mp.im(E[j]) > 0 else k[0]
            blocks.append(("c", complex(E[jj]), complex(gam[jj] * beta[jj])))
        D = float(D)
    n = sum(1 if bl[0] == "r" else 2 for bl in blocks)
    Am = np.zeros((n, n))
    Bm = np.zeros(n)
    Cm = np.zeros(n)
    i = 0
    for bl in blocks:
        if bl[0] == "r":
            Am[i, i], Bm[i], Cm[i] = bl[1], 1.0, bl[2]
            i += 1
        else:
            sr, si, r = bl[1].real, bl[1].imag, bl[2]
            Am[i:i + 2, i:i + 2] = [[sr, -si], [si, sr]]
            Bm[i] = 1.0
            Cm[i], Cm[i + 1] = 2 * r.real, -2 * r.imag
            i += 2
    lag = Lag("peters%d" % N, Am, Bm, Cm, D)
    lag.poles = [bl[1] for bl in blocks]
    lag.residues = [bl[2] for bl in blocks]
    lag.raw = peters_matrices(N)[:3]
    return lag


def peters_C_mp(N, pbar, dps=40):
    """Peters' C(pbar) from its definition, in mpmath."""
    import mpmath as mp

    with mp.workdps(dps):
        A, bv, cv = peters_matrices_mp(N, dps)
        lam = mp.lu_solve(pbar * A + mp.eye(N), cv * pbar)
        return 1 - (bv.T * lam)[0] / 2


def peters_C_direct(N, pbar):
    """Peters' C(pbar) straight from its definition (no inverse-of-A rearrangement)."""
    A, bv, cv, _ = peters_matrices(N)
    lam = np.linalg.solve(pbar * A + np.eye(N), cv * pbar)
    return 1.0 - 0.5 * bv @ lam


# ----------------------------------------------------------------------------------------------
# Linear strip-theory aeroelastic system
# ----------------------------------------------------------------------------------------------
class StripSystem:
    def __init__(self, Ms, Ks, H, P, W, b, a, rho, cla=2 * PI, project=False, name=""):
        self.name = name
        self.Ms = np.asarray(Ms, float)
        self.Ks = np.asarray(Ks, float)
        H = np.atleast_2d(np.asarray(H, float))
        P = np.atleast_2d(np.asarray(P, float))
        Wd = np.diag(np.asarray(W, float).reshape(-1))
        self.b, self.a, self.rho, self.cla = b, a, rho, cla
        self.N = self.Ms.shape[0]
        pr = PI * rho * b * b
        self.Mnc = pr * (H.T @ Wd @ H - b * a * (H.T @ Wd @ P + P.T @ Wd @ H) + b * b * (0.125 + a * a) * P.T @ Wd @ P)
        self.M = self.Ms + self.Mnc
        self.Ct = pr * (H.T @ Wd @ P + b * (0.5 - a) * P.T @ Wd @ P)
        R = (-H + b * (0.5 + a) * P).T @ Wd
        E2 = H + b * (0.5 - a) * P
        if project:
            self.G = np.eye(self.N)
            self.E1 = R @ P
            self.E2 = R @ E2
        else:
            self.G = R
            self.E1 = P.copy()
            self.E2 = E2
        self.S = self.G.shape[1]
        self.Minv = np.linalg.inv(self.M)

    # ---- steady aero / divergence ----
    def steady_aero_stiffness(self):
        """Q = U^2 * Ka eta for steady flow (C(0) = 1, no rates)."""
        return self.cla * self.rho * self.b * self.G @ self.E1

    def divergence_speeds(self):
        """All real positive U with det(Ks - U^2 Ka) = 0, ascending."""
        Ka = self.steady_aero_stiffness()
        # Ka x = mu Ks x, mu = 1/U^2
        mu = linalg.eigvals(Ka, self.Ks)
        out = []
        for m in mu:
            if abs(m.imag) < 1e-9 * max(1e-300, abs(m)) and m.real > 0:
                out.append(1.0 / math.sqrt(m.real))
        return sorted(out)

    # ---- frequency domain ----
    def Ak(self, k, Ck=None):
        """A(k) with Ks eta = omega^2 A(k) eta for harmonic motion at reduced frequency k."""
        if Ck is None:
            Ck = theodorsen(k)
        b = self.b
        return (self.M - 1j * (b / k) * self.Ct
                + self.cla * self.rho * b * Ck * self.G @ ((b * b / (k * k)) * self.E1 + 1j * (b / k) * self.E2))

    def k_eigs(self, k, Cfun=theodorsen):
        """k-method eigenvalues Z = (1 + i g)/omega^2 of A(k) x = Z Ks x."""
        return linalg.eigvals(self.Ak(k, Cfun(k)), self.Ks)

    # ---- p-k (Theodorsen C at k = Im(p) b / U, p elsewhere) ----
    def pk_matrix(self, U, Ck):
        """First-order matrix whose eigenvalues are p of det(p^2 M + p(U Ct - c E2) + Ks - U c E1) = 0,
        c = cla rho U b Ck G."""
        N = self.N
        c = self.cla * self.rho * U * self.b * Ck
        Kp = self.Ks - U * c * self.G @ self.E1
        Cp = U * self.Ct - c * self.G @ self.E2
        A = np.zeros((2 * N, 2 * N), complex)
        A[:N, N:] = np.eye(N)
        A[N:, :N] = -self.Minv @ Kp
        A[N:, N:] = -self.Minv @ Cp
        return A

    def pk_root(self, U, p0, Cfun=theodorsen, tol=1e-13, maxit=200):
        """Iterate p-k for the branch nearest p0 (Im p0 > 0)."""
        p = p0
        for it in range(maxit):
            k = abs(p.imag) * self.b / U
            ev = np.linalg.eigvals(self.pk_matrix(U, Cfun(max(k, 1e-8))))
            ev = ev[ev.imag > 0] if np.any(ev.imag > 0) else ev
            pn = ev[np.argmin(np.abs(ev - p))]
            if abs(pn - p) < tol * max(1.0, abs(pn)):
                return pn
            p = pn
        return p

    # ---- state space with a rational lag per strip ----
    def state_matrix(self, U, lag):
        N, S, na = self.N, self.S, lag.n
        b = self.b
        c = self.cla * self.rho * U * b
        Kp = self.Ks - U * c * lag.D * self.G @ self.E1
        Cp = U * self.Ct - c * lag.D * self.G @ self.E2
        n = 2 * N + S * na
        A = np.zeros((n, n))
        A[:N, N:2 * N] = np.eye(N)
        A[N:2 * N, :N] = -self.Minv @ Kp
        A[N:2 * N, N:2 * N] = -self.Minv @ Cp
        if na:
            Cx = np.kron(np.eye(S), lag.Ca.reshape(1, -1))  # S x S*na
            A[N:2 * N, 2 * N:] = self.Minv @ (c * self.G @ Cx)
            Bx = np.kron(np.eye(S), lag.Ba.reshape(-1, 1))  # S*na x S
            A[2 * N:, :N] = (U / b) * Bx @ (U * self.E1)
            A[2 * N:, N:2 * N] = (U / b) * Bx @ self.E2
            A[2 * N:, 2 * N:] = (U / b) * np.kron(np.eye(S), lag.Aa)
        return A

    def ss_eigs(self, U, lag):
        return np.linalg.eigvals(self.state_matrix(U, lag))


# ----------------------------------------------------------------------------------------------
# Flutter solvers
# ----------------------------------------------------------------------------------------------
def _track(prev, cur):
    """Hungarian matching of eigenvalue lists (prev -> cur)."""
    cost = np.abs(prev[:, None] - cur[None, :])
    r, c = optimize.linear_sum_assignment(cost)
    out = np.empty_like(prev)
    out[r] = cur[c]
    return out


def kmethod_crossings(sysm, kgrid, Cfun=theodorsen, branches=None, xtol=1e-15):
    """k-method: track Z_j(k) over a descending k grid; return every zero of g_j = Im Z/Re Z,
    refined by Brent on k, as dicts (branch, k, U, omega, direction: +1 if g goes - to + as U grows).
    branches: indices (in the order of the first grid point, sorted by omega descending Z) to track."""
    kgrid = np.sort(np.asarray(kgrid))[::-1]  # high k (low U) first
    Z0 = sysm.k_eigs(kgrid[0], Cfun)
    order = np.argsort(-Z0.real)  # largest Re Z = lowest omega first
    Zs = [Z0[order]]
    for k in kgrid[1:]:
        Zs.append(_track(Zs[-1], sysm.k_eigs(k, Cfun)))
    Zs = np.array(Zs)  # (nk, N)
    nb = Zs.shape[1] if branches is None else branches
    out = []
    for j in range(nb):
        g = Zs[:, j].imag / Zs[:, j].real
        for i in range(len(kgrid) - 1):
            if Zs[i, j].real <= 0 or Zs[i + 1, j].real <= 0:
                continue
            if g[i] == 0 or g[i] * g[i + 1] < 0:
                k1, k2 = kgrid[i], kgrid[i + 1]
                Z1, Z2 = Zs[i, j], Zs[i + 1, j]

                def pick(k):
                    t = (k - k1) / (k2 - k1)
                    Zg = Z1 + t * (Z2 - Z1)
                    ev = sysm.k_eigs(k, Cfun)
                    return ev[np.argmin(np.abs(ev - Zg))]

                def f(k):
                    Z = pick(k)
                    return Z.imag / Z.real

                kc = optimize.brentq(f, k2, k1, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
                Z = pick(kc)
                om = 1.0 / math.sqrt(Z.real)
                U = om * sysm.b / kc
                # as U grows k falls: direction from g at the low-k side
                direction = 1 if g[i + 1] > g[i] else -1
                out.append(dict(branch=j, k=kc, U=U, omega=om, direction=direction, g_resid=Z.imag / Z.real))
    out.sort(key=lambda d: d["U"])
    return out, kgrid, Zs


def ss_flutter(sysm, lag, Ugrid, om_min, xtol=1e-12):
    """Lowest U where an oscillatory eigenvalue (Im > om_min) of the state matrix crosses Re = 0
    upward. Returns dict(U, omega, p) or None. Brent on f(U) = max Re over Im > om_min."""

    def f(U):
        ev = sysm.ss_eigs(U, lag)
        ev = ev[ev.imag > om_min]
        i = np.argmax(ev.real)
        return ev[i].real, ev[i]

    prev = None
    for i, U in enumerate(Ugrid):
        val, p = f(U)
        if i == 0 and val >= 0:
            # unstable already at the first speed of the grid: report it, do not look further
            return dict(U=0.0, omega=p.imag, p=p, from_start=True, U_first=U)
        if prev is not None and prev[1] < 0 <= val:
            Uc = optimize.brentq(lambda u: f(u)[0], prev[0], U, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
            _, p = f(Uc)
            return dict(U=Uc, omega=p.imag, p=p)
        prev = (U, val)
    return None


def ss_flutter_branch(sysm, lag, U_lo, U_hi, p_guess, xtol=1e-12):
    """Refine a flutter crossing on the branch nearest p_guess between U_lo and U_hi."""
    state = {"p": p_guess}

    def f(U):
        ev = sysm.ss_eigs(U, lag)
        p = ev[np.argmin(np.abs(ev - state["p"]))]
        return p.real, p

    Uc = optimize.brentq(lambda u: f(u)[0], U_lo, U_hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
    return Uc, f(Uc)[1]


def fmt(x):
    return repr(float(x))


def kmethod_local(sysm, k_lo, k_hi, om_guess, Cfun=theodorsen, npts=41, xtol=1e-15):
    """k-method on one branch: the eigenvalue Z nearest 1/om_guess^2 at k_hi, tracked on a grid
    from k_hi down to k_lo (nearest neighbour), first zero of g = Im Z / Re Z refined by Brent."""
    ks = np.linspace(k_hi, k_lo, npts)
    Zs = []
    Zc = 1.0 / om_guess ** 2 + 0j
    for k in ks:
        ev = sysm.k_eigs(k, Cfun)
        Zc = ev[np.argmin(np.abs(ev - Zc))]
        Zs.append(Zc)
    g = [Z.imag / Z.real for Z in Zs]
    for i in range(npts - 1):
        if g[i] * g[i + 1] <= 0:
            k1, k2, Z1, Z2 = ks[i], ks[i + 1], Zs[i], Zs[i + 1]

            def pick(k):
                t = (k - k1) / (k2 - k1)
                Zg = Z1 + t * (Z2 - Z1)
                ev = sysm.k_eigs(k, Cfun)
                return ev[np.argmin(np.abs(ev - Zg))]

            kc = optimize.brentq(lambda k: (lambda Z: Z.imag / Z.real)(pick(k)), k2, k1, xtol=xtol,
                                 rtol=4 * np.finfo(float).eps, maxiter=200)
            Z = pick(kc)
            om = 1.0 / math.sqrt(Z.real)
            return dict(k=kc, U=om * sysm.b / kc, omega=om, direction=1 if g[i + 1] > g[i] else -1)
    return None


def follow(cur, ev):
    """Continue branches cur (list of eigenvalues) to the eigenvalues ev of the next speed:
    one-to-one (Hungarian) nearest matching among the eigenvalues with Im >= 0, so two branches can
    never land on the same eigenvalue (e.g. when a pair turns real near divergence)."""
    cand = ev[ev.imag >= -1e-12 * max(1.0, np.max(np.abs(ev)))]
    cost = np.abs(np.asarray(cur)[:, None] - cand[None, :])
    r, c = optimize.linear_sum_assignment(cost)
    out = list(cur)
    for i, j in zip(r, c):
        out[i] = cand[j]
    return out
