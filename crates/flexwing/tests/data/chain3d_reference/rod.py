"""Geometrically exact rod (Kirchhoff: inextensible, unshearable), statics and linearized dynamics.

Independent of flexwing's Rust code (no source of the 3-D chain was read; none existed when this was
written) and of its discretization (no rigid elements, no joints): the continuum equations of the
special Cosserat rod (Antman, *Nonlinear Problems of Elasticity*, ch. 8; Simo & Vu-Quoc 1986,
Kirchhoff limit) are solved by

  * shooting on the exact ODEs in s (scipy DOP853 at rtol 1e-13) for every static state, and
  * two discretizations of the linearization about a static state:
      - a Ritz method: polynomial rotation fields (integrated Legendre polynomials, N per
        component), every integral by a 257-point Chebyshev rule (exact to round-off), giving
        symmetric mass and stiffness matrices -> RitzRod (spectral convergence in N);
      - shooting on the strong form of the same linearized equations (no spatial discretization:
        a 6 x 6 boundary determinant, zero at an eigenvalue) -> det_tip().

Notation. Arc length s in [0, L]. Section frame R(s) = [t n c] (columns, global components):
t along the axis, n the section normal (flap direction, "up"), c chordwise toward the leading
edge (t x n = c). Material curvature kappa = axial(R^T R') = (twist, lag, flap) components on
(t, n, c); section stiffness C = diag(GJ, EI_lag, EI_flap) so the internal moment is
m = R C (kappa - kappa_ref) (global). Internal force N(s): the force the part (s, L] exerts on [0, s].
Equilibrium  N' + f = mu r_tt,   m' + r' x N + l = d/dt(R J R^T omega),   r' = t = R e1.
Section inertia J = diag(I_polar, I_lag_rot, I_flap_rot) on (t, n, c), about the axis (mass centre on
the axis: d0 = 0 for every case here).

Linearization about a static state (R0, N0, m0) with a *spatial* small rotation theta(s) and a
displacement u(s) (R = (I + hat(theta)) R0, r = r0 + u), derived in README.md sec. 1.3:
    u'  = theta x t0                                (inextensibility)
    m1  = Cs theta' + theta x m0,  Cs = R0 C R0^T   (moment perturbation)
    N1' = mu u_tt - f1
    m1' = Js theta_tt - (theta x t0) x N0 - t0 x N1 - l1,   Js = R0 J R0^T
    root: u = theta = 0;  tip (dead loads): N1 = 0, m1 = 0.
Weak form (symmetric at equilibrium, README sec. 1.3):
    K(eta, theta) = int eta'.Cs theta' + 1/2 (eta'.(theta x m0) + theta'.(eta x m0))
                        + (t0.N0) eta.theta - 1/2 ((eta.t0)(theta.N0) + (eta.N0)(theta.t0)) ds
    M(eta, theta) = int mu v.u + eta.Js theta ds,  v, u = int_0^s (eta, theta) x t0
"""

import math
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from numpy.polynomial import chebyshev as npc
from numpy.polynomial import legendre as npl
from scipy import linalg, optimize
from scipy.integrate import solve_ivp

PI = math.pi
RTOL = 1e-13
ATOL = 1e-14


def hat(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


# ------------------------------------------------------------------------------------------------
# Planar static state: bending about the global z axis (= the section's c axis) under dead loads
# along y: a tip force F (up) and a distributed force q per unit length (up; gravity: q = -mu g).
#   N0(s) = (0, F + q (L - s), 0),  m0 = EI_c theta0' z,  EI_c theta0'' = -N0_y cos(theta0),
#   theta0(0) = 0, theta0'(L) = 0 (no tip moment).  Exact planar solution of the 3-D rod (no twist,
#   no lag) for any section: the loads are in the plane of a principal axis.
# ------------------------------------------------------------------------------------------------
class PlanarStatic:
    def __init__(self, L, EI_c, F=0.0, q=0.0, rtol=RTOL):
        self.L, self.EI, self.F, self.q, self.rtol = L, EI_c, F, q, rtol
        self.k0 = self._solve()
        sol = solve_ivp(self._rhs, (0.0, L), [0.0, self.k0, 0.0, 0.0], method="DOP853", rtol=rtol,
                        atol=ATOL, dense_output=True)
        self.sol = sol
        self.tip = sol.y[:, -1]  # theta, theta', x, y at s = L

    def Ny(self, s):
        return self.F + self.q * (self.L - s)

    def _rhs(self, s, y):
        th, k = y[0], y[1]
        return [k, -self.Ny(s) * math.cos(th) / self.EI, math.cos(th), math.sin(th)]

    def _rhs_sens(self, s, y):
        th, k, dth, dk = y
        Ny = self.Ny(s)
        return [k, -Ny * math.cos(th) / self.EI, dk, Ny * math.sin(th) / self.EI * dth]

    def _solve(self):
        L, EI = self.L, self.EI
        k0 = (self.F * L + 0.5 * self.q * L * L) / EI  # linear theory
        for it in range(60):
            sol = solve_ivp(self._rhs_sens, (0.0, L), [0.0, k0, 0.0, 1.0], method="DOP853", rtol=self.rtol,
                            atol=ATOL)
            r, dr = sol.y[1, -1], sol.y[3, -1]
            dk = -r / dr
            k0 += dk
            if abs(dk) <= 1e-15 * max(1.0, abs(k0)):
                return k0
        raise RuntimeError("planar static shooting did not converge")

    def fields(self, s):
        """theta0, theta0', x0, y0 at the points s (array)."""
        s = np.atleast_1d(np.asarray(s, float))
        out = self.sol.sol(s)
        return out


# ------------------------------------------------------------------------------------------------
# General 3-D static solver: shooting on m(0) for dead loads (N(s) known in closed form).
#   r' = R (e1 + Gamma),  R' = R hat(kappa),  kappa = kappa_ref + C^-1 R^T m,  m' = -r' x N(s)
#   Gamma = 0 (Kirchhoff) or Cf^-1 R^T N (Simo-Reissner: extension and shear, Cf = diag(EA, GA2, GA3)).
# ------------------------------------------------------------------------------------------------
class Static3D:
    def __init__(self, L, C, kappa_ref=(0.0, 0.0, 0.0), Cf=None, R_root=None):
        self.L = L
        self.Cinv = 1.0 / np.asarray(C, float)
        self.kref = np.asarray(kappa_ref, float)
        self.Cfinv = None if Cf is None else 1.0 / np.asarray(Cf, float)
        self.R_root = np.eye(3) if R_root is None else np.asarray(R_root, float)

    def N(self, s, F_tip, f_dist):
        return np.asarray(F_tip, float) + np.asarray(f_dist, float) * (self.L - s)

    def rhs(self, s, y, F_tip, f_dist):
        R = y[3:12].reshape(3, 3)
        m = y[12:15]
        Ns = self.N(s, F_tip, f_dist)
        kap = self.kref + self.Cinv * (R.T @ m)
        gam = np.array([1.0, 0.0, 0.0])
        if self.Cfinv is not None:
            gam = gam + self.Cfinv * (R.T @ Ns)
        rp = R @ gam
        Rp = R @ hat(kap)
        mp = -np.cross(rp, Ns)
        return np.concatenate([rp, Rp.reshape(-1), mp])

    def integrate(self, m0, F_tip, f_dist, dense=False, rtol=RTOL):
        y0 = np.concatenate([np.zeros(3), self.R_root.reshape(-1), m0])
        return solve_ivp(self.rhs, (0.0, self.L), y0, method="DOP853", rtol=rtol, atol=ATOL,
                         args=(F_tip, f_dist), dense_output=dense)

    def residual(self, m0, F_tip, f_dist, M_tip, rtol=RTOL):
        sol = self.integrate(m0, F_tip, f_dist, rtol=rtol)
        return sol.y[12:15, -1] - np.asarray(M_tip, float), sol

    def solve(self, F_tip, f_dist=(0, 0, 0), M_tip=(0, 0, 0), m0=None, steps=10, tol=1e-12, rtol=RTOL):
        """Load stepping (linear in the load factor) and Newton with a central-difference Jacobian."""
        F_tip, f_dist, M_tip = (np.asarray(v, float) for v in (F_tip, f_dist, M_tip))
        tol = max(tol, 10 * rtol)  # the residual cannot fall below the integration error
        m = np.zeros(3) if m0 is None else np.asarray(m0, float).copy()
        scale = max(1.0, np.linalg.norm(F_tip) * self.L + np.linalg.norm(f_dist) * self.L ** 2 + np.linalg.norm(M_tip))
        for j in range(1, steps + 1):
            lam = j / steps
            Fj, fj, Mj = lam * F_tip, lam * f_dist, lam * M_tip
            for it in range(50):
                r, _ = self.residual(m, Fj, fj, Mj, rtol)
                if np.linalg.norm(r) < tol * scale:
                    break
                Jm = np.zeros((3, 3))
                h = 1e-6 * scale
                for k in range(3):
                    e = np.zeros(3)
                    e[k] = h
                    Jm[:, k] = (self.residual(m + e, Fj, fj, Mj, rtol)[0] - self.residual(m - e, Fj, fj, Mj, rtol)[0]) / (2 * h)
                m = m - np.linalg.solve(Jm, r)
            else:
                raise RuntimeError("3-D static shooting did not converge at load factor %g" % lam)
        r, sol = self.residual(m, F_tip, f_dist, M_tip, rtol)
        self.m_root = m
        return m, sol


# ------------------------------------------------------------------------------------------------
# Chebyshev machinery on [0, L]: nodes, Clenshaw-Curtis weights, cumulative integration matrix
# ------------------------------------------------------------------------------------------------
def cheb_rule(M, L):
    j = np.arange(M)
    x = -np.cos(PI * j / (M - 1))  # -1 .. 1
    s = 0.5 * L * (x + 1.0)
    V = npc.chebvander(x, M - 1)  # M x M
    Vi = np.linalg.inv(V)
    # weights: integrate each Chebyshev polynomial over [-1, 1]
    tk = np.array([(2.0 / (1 - k * k)) if k % 2 == 0 else 0.0 for k in range(M)])
    w = 0.5 * L * (tk @ Vi)
    # cumulative integral from -1: chebint of the identity coefficient columns
    Icoef = npc.chebint(np.eye(M), lbnd=-1, axis=0)  # (M+1) x M
    Vx = npc.chebvander(x, M)
    Q = 0.5 * L * (Vx @ Icoef @ Vi)
    return s, w, Q


# ------------------------------------------------------------------------------------------------
# Ritz discretization of the linearized rod about a static state given at the quadrature points
# ------------------------------------------------------------------------------------------------
class RitzRod:
    """Rotation perturbation theta(s) = sum_k a_k phi_k(s) per global component, phi_k(s) =
    int_{-1}^{xi} P_{k-1} (integrated Legendre, phi_k(0) = 0), k = 1..N. Coordinates ordered
    (x components 1..N, y components, z components). Integrals on a Chebyshev rule of Mq points.
    static: dict of arrays at the rule's nodes: t (M,3), n (M,3), c (M,3), m0 (M,3), N0 (M,3)."""

    def __init__(self, L, C, J, mu, N, static_fn, Mq=257):
        self.L, self.N = L, N
        s, w, Q = cheb_rule(Mq, L)
        self.s, self.w = s, w
        st = static_fn(s)
        t, nn, cc, m0, N0 = st["t"], st["n"], st["c"], st["m0"], st["N0"]
        self.t, self.n, self.c = t, nn, cc
        xi = 2 * s / L - 1
        Pl = npl.legvander(xi, N)  # P_0 .. P_N
        phi = np.zeros((Mq, N))
        dphi = np.zeros((Mq, N))
        phi[:, 0] = xi + 1
        dphi[:, 0] = 2 / L * Pl[:, 0]
        for k in range(2, N + 1):
            phi[:, k - 1] = (Pl[:, k] - Pl[:, k - 2]) / (2 * k - 1)
            dphi[:, k - 1] = 2 / L * Pl[:, k - 1]
        nd = 3 * N
        Th = np.zeros((Mq, 3, nd))
        dTh = np.zeros((Mq, 3, nd))
        for a in range(3):
            Th[:, a, a * N:(a + 1) * N] = phi
            dTh[:, a, a * N:(a + 1) * N] = dphi
        # u = int theta x t0 = int -hat(t0) theta
        tx = -np.array([hat(tt) for tt in t])  # (M,3,3)
        integrand = np.einsum("qij,qjk->qik", tx, Th)
        U = np.einsum("pq,qik->pik", Q, integrand)
        Rq = np.stack([t, nn, cc], axis=2)  # columns t n c
        C = np.asarray(C, float)
        J = np.asarray(J, float)
        Cs = np.einsum("qij,j,qkj->qik", Rq, C, Rq)
        Js = np.einsum("qij,j,qkj->qik", Rq, J, Rq)
        mh = np.array([hat(v) for v in m0])
        tN = np.einsum("qi,qi->q", t, N0)
        B = tN[:, None, None] * np.eye(3)[None] - 0.5 * (np.einsum("qi,qj->qij", t, N0) + np.einsum("qi,qj->qij", N0, t))
        K = np.einsum("q,qia,qij,qjb->ab", w, dTh, Cs, dTh)
        KA = 0.5 * (-np.einsum("q,qia,qij,qjb->ab", w, dTh, mh, Th) + np.einsum("q,qia,qij,qjb->ab", w, Th, mh, dTh))
        KB = np.einsum("q,qia,qij,qjb->ab", w, Th, B, Th)
        self.Ke = K
        self.Kg = KA + KB
        self.Ks = K + KA + KB
        self.Ms = mu * np.einsum("q,qia,qib->ab", w, U, U) + np.einsum("q,qia,qij,qjb->ab", w, Th, Js, Th)
        self.asym = np.max(np.abs(self.Ks - self.Ks.T)) / np.max(np.abs(self.Ks))
        self.Ks = 0.5 * (self.Ks + self.Ks.T)
        self.Ms = 0.5 * (self.Ms + self.Ms.T)
        # strip rows: plunge down h = -n.u, pitch nose-up alpha = -t.theta
        self.H = -np.einsum("qi,qik->qk", nn, U)
        self.P = -np.einsum("qi,qik->qk", t, Th)
        self.U = U
        self.Th = Th

    def tip_displacement(self, a):
        """u(L) for coefficients a."""
        return self.U[-1] @ a

    def tip_rotation(self, a):
        return self.Th[-1] @ a

    def load_vector_tip(self, F=(0, 0, 0), Mo=(0, 0, 0)):
        """Generalized force of a dead tip force F and a tip moment Mo (global)."""
        return self.U[-1].T @ np.asarray(F, float) + self.Th[-1].T @ np.asarray(Mo, float)

    def vacuum_frequencies(self):
        ev = linalg.eigh(self.Ks, self.Ms, eigvals_only=True)
        return np.sign(ev) * np.sqrt(np.abs(ev))


def planar_static_fields(ps, C):
    """Static-field function for RitzRod from a PlanarStatic (section frame rotated about z)."""

    def fn(s):
        th, k, x, y = ps.fields(s)
        M = len(s)
        t = np.stack([np.cos(th), np.sin(th), np.zeros(M)], 1)
        n = np.stack([-np.sin(th), np.cos(th), np.zeros(M)], 1)
        c = np.tile([0.0, 0.0, 1.0], (M, 1))
        m0 = np.stack([np.zeros(M), np.zeros(M), C[2] * k], 1)
        N0 = np.stack([np.zeros(M), ps.Ny(s), np.zeros(M)], 1)
        return dict(t=t, n=n, c=c, m0=m0, N0=N0)

    return fn


# ------------------------------------------------------------------------------------------------
# Strong-form shooting of the linearized rod about a planar static state, with strip aerodynamics
# ------------------------------------------------------------------------------------------------
class Shooting:
    """det_tip(p, Cval, U): the 6 x 6 tip matrix [N1(L); m1(L)] of the six solutions that start with
    u = theta = 0 and (N1, m1)(0) = unit vectors, for motion e^{pt}; zero determinant <=> eigenvalue.
    Aerodynamics (Theodorsen's loads, h = -n0.u down, alpha = -t0.theta nose-up, per unit span):
        w  = U alpha + p h + b(1/2 - a) p alpha
        Lc = cla rho U b Cval w
        L  = Lc + pi rho b^2 (p^2 h + U p alpha - b a p^2 alpha)                 along n0
        Mo = b(1/2 + a) Lc + pi rho b^2 (b a p^2 h - U b(1/2 - a) p alpha - b^2 (1/8 + a^2) p^2 alpha)
        f1 = L n0,  l1 = -Mo t0 (nose-up moment about -t0)."""

    def __init__(self, ps, C, J, mu, aero=None, rtol=1e-12):
        self.ps, self.C, self.J, self.mu = ps, np.asarray(C, float), np.asarray(J, float), mu
        self.aero = aero  # dict(b, a, rho, cla) or None
        self.rtol = rtol

    def _rhs(self, s, y, p, Cval, U):
        th0, k0 = y[0].real, y[1].real
        Y = y[2:].reshape(12, 6)
        u, th, Nn, mm = Y[0:3], Y[3:6], Y[6:9], Y[9:12]
        ct, st = math.cos(th0), math.sin(th0)
        t0 = np.array([ct, st, 0.0])
        n0 = np.array([-st, ct, 0.0])
        R0 = np.array([[ct, -st, 0.0], [st, ct, 0.0], [0.0, 0.0, 1.0]])
        Csinv = R0 @ np.diag(1.0 / self.C) @ R0.T
        Js = R0 @ np.diag(self.J) @ R0.T
        m0 = np.array([0.0, 0.0, self.C[2] * k0])
        Ny = self.ps.Ny(s)
        N0 = np.array([0.0, Ny, 0.0])
        du = np.cross(th, t0, axis=0)
        dth = Csinv @ (mm - np.cross(th, m0, axis=0))
        f1 = np.zeros_like(u)
        l1 = np.zeros_like(u)
        if self.aero is not None and (U != 0 or p != 0):
            A = self.aero
            b, a, rho, cla = A["b"], A["a"], A["rho"], A["cla"]
            h = -(n0 @ u)
            al = -(t0 @ th)
            w = U * al + p * h + b * (0.5 - a) * p * al
            Lc = cla * rho * U * b * Cval * w
            pr = PI * rho * b * b
            Lf = Lc + pr * (p * p * h + U * p * al - b * a * p * p * al)
            Mo = b * (0.5 + a) * Lc + pr * (b * a * p * p * h - U * b * (0.5 - a) * p * al - b * b * (0.125 + a * a) * p * p * al)
            f1 = np.outer(n0, Lf)
            l1 = -np.outer(t0, Mo)
        dN = p * p * self.mu * u - f1
        dm = p * p * (Js @ th) - np.cross(du, N0[:, None], axis=0) - np.cross(t0[:, None], Nn, axis=0) - l1
        dY = np.concatenate([du, dth, dN, dm])
        return np.concatenate([[k0, -Ny * ct / self.C[2]], dY.reshape(-1)])

    def tip_matrix(self, p, Cval=1.0, U=0.0):
        Y0 = np.zeros((12, 6), complex)
        Y0[6:12, :] = np.eye(6)
        y0 = np.concatenate([[0.0, self.ps.k0], Y0.reshape(-1)]).astype(complex)
        sol = solve_ivp(self._rhs, (0.0, self.ps.L), y0, method="DOP853", rtol=self.rtol, atol=1e-14,
                        args=(complex(p), complex(Cval), float(U)))
        Y = sol.y[2:, -1].reshape(12, 6)
        return Y[6:12, :]

    def det(self, p, Cval=1.0, U=0.0):
        D = self.tip_matrix(p, Cval, U)
        # scale: force rows by L (-> moments), so that all entries have one unit
        D = D.copy()
        D[0:3] *= self.ps.L
        return np.linalg.det(D)
