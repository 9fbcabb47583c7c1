#!/usr/bin/env python3
"""Independent reference natural frequencies of a uniform Rayleigh-beam cantilever
(Euler-Bernoulli bending + rotary inertia of the section, no shear deformation).
Python 3 standard library only (decimal, fractions); nothing from the Rust code.

Model and derivation of the boundary conditions (Hamilton's principle)
----------------------------------------------------------------------
Clamped at x = 0, free at x = L; EI, m, J = rho*I = m r^2 uniform.
    T = 1/2 int_0^L (m w_t^2 + J w_xt^2) dx,     V = 1/2 int_0^L EI w_xx^2 dx.
delta int (T - V) dt = 0.  Integrating by parts once in t (end variations vanish):
    delta int T dt = -int int (m w_tt dw + J w_xtt dw_x) dx dt
                   = -int int (m w_tt - J w_xxtt) dw dx dt - int [J w_xtt dw]_0^L dt
    delta int V dt =  int int EI w_xx dw_xx dx dt
                   =  int int EI w_xxxx dw dx dt + int [EI w_xx dw_x - EI w_xxx dw]_0^L dt
so, for arbitrary dw in (0, L) and at the free end (dw(0) = dw_x(0) = 0 at the clamp):
    field:    EI w_xxxx - J w_xxtt + m w_tt = 0
    x = L:    dw_x:  EI w_xx = 0                       (bending moment)
              dw  :  EI w_xxx - J w_xtt = 0            (shear force incl. rotary inertia)
With w = W(x) cos(om t) (w_tt = -om^2 w):
    EI W'''' + J om^2 W'' - m om^2 W = 0,   W(0) = W'(0) = 0,
    EI W''(L) = 0,   EI W'''(L) + J om^2 W'(L) = 0.

Dimensionless form: xi = x/L, Om = om L^2 sqrt(m/EI), gam = J/(m L^2) = (r/L)^2:
    W'''' + gam Om^2 W'' - Om^2 W = 0,   W''(1) = 0,  W'''(1) + gam Om^2 W'(1) = 0.

Method A: exact characteristic equation, roots by scan + Illinois in Decimal
----------------------------------------------------------------------------
Characteristic exponents s^2 = (-gam Om^2 +- sqrt(gam^2 Om^4 + 4 Om^2))/2 give
W = C1 cosh(a xi) + C2 sinh(a xi) + C3 cos(b xi) + C4 sin(b xi) with
    a^2 b^2 = Om^2,   b^2 - a^2 = gam Om^2   (a, b > 0 for every Om > 0: a Rayleigh
    beam has no cut-off frequency, unlike a Timoshenko beam).
b is used as the independent variable: Om = b^2 / sqrt(1 + gam b^2), a = Om / b
(b increases monotonically with Om, so this is a one-to-one reparametrisation).
The clamp gives W = A (cosh a xi - cos b xi) + B (sinh a xi - (a/b) sin b xi); the
two free-end rows (W'', W''' + (b^2 - a^2) W') give, after using cosh^2 - sinh^2 = 1
and cos^2 + sin^2 = 1 analytically and dividing by a (a > 0),
    D(b) = 2 a^2 b^2 + (a^4 + b^4) cosh a cos b - a b (b^2 - a^2) sinh a sin b.
The solver uses g = D / ((a^4 + b^4) cosh a):
    g(b) = 2 a^2 b^2 / ((a^4+b^4) cosh a) + cos b - a b (b^2-a^2)/(a^4+b^4) tanh a sin b.
The divisor is strictly positive, so g is smooth (no poles: a sign change of g is
always a root, never a pole, and no overflow); all terms are O(1), so there is no
cancellation.  gam = 0 gives a = b and g = cos b + 1/cosh b (Euler-Bernoulli).
Roots: sign-change scan of g on a uniform b-grid of step pi/40 (adjacent roots are
>= 2.79 apart in b here and the first root is at b > 1.87, i.e. >= 23 grid cells;
asserted > 10 cells), then Illinois regula falsi at 50 digits (Decimal; cos/sin by Taylor
series with guard digits, cosh/tanh from Decimal.exp) to |db| < 1e-40 b.

Method B (independent): Rayleigh-Ritz from the energy functional alone
--------------------------------------------------------------------------
W = sum_{i<N} q_i xi^(i+2) (satisfies only the clamp conditions; the free-end
conditions, including the rotary-inertia term of the shear condition, are natural
conditions of the functional, so method B checks the derivation above).  Exact
rational matrices:  K_ij = (i+1)(i+2)(j+1)(j+2)/(i+j+1)   (int W''^2),
M_ij = 1/(i+j+5) + gam (i+2)(j+2)/(i+j+3)                 (int W^2 + gam W'^2),
K q = Om^2 M q.  The monomial basis is badly conditioned (Hilbert-like), so the
algebra is done in Decimal at 60 + 2N digits: Cholesky M = L L^T,
C = L^-1 K L^-T, Householder tridiagonalisation, Sturm-sequence bisection for the
k-th eigenvalue.  By the min-max principle the k-th Ritz value is an upper bound
of the k-th exact eigenvalue and decreases with N; the Sturm count gives the
eigenvalues by index, so comparing A and B mode by mode proves that the scan of
method A skipped no root and found no spurious one.

Checks (asserted)
-----------------
* A vs B, mode by mode for modes 1..11 (the 11th only as a root-count check):
  relative difference < TOL_AB = 1e-20.  Reason: A is exact up to its root
  tolerance (~1e-40); B (N=40) converges super-exponentially in N, its error is far
  below the N=32 -> 40 change (<= 4e-17 for mode 10), and the observed |A-B| is
  <= 7e-28 for modes 1..10; 1e-20 keeps a margin of 1e7 above that and is still 1e15
  below the effect of a boundary-condition mistake: the script also solves the
  equation with the rotary term dropped from the shear condition (EI W'''(L) = 0)
  and asserts that B rejects it (it is off by 2-5e-2).
* every B value >= the A value (min-max upper bound) and B non-increasing in N.
* gam = 0: A reproduces the Euler-Bernoulli roots of cos x cosh x = -1 (independent
  float bisection in [(k-1)pi, k pi], as in tests/suite/common/mod.rs) to 1e-14 relative
  and the classical 10-decimal values 1.8751040687, 4.6940911330, 7.8547574382,
  10.9955407349 to 6e-11 (their rounding); B(gam = 0) agrees with A to 1e-20.
* gam -> 0: om < om_EB, and (om_EB - om)/om_EB is O(gam): the deviations for
  gam = 1e-6, 1e-8, 1e-10 shrink by 100 per step (to 1e-2 resp. 1e-4).  The mode-1
  coefficient 2.3239 equals (1/2) int W'^2 / int W^2 of the EB mode (Rayleigh
  quotient perturbation), as it must.

Output
------
table4_r005.csv (r = 0.05 m, J = 5e-4 kg m) and table4_r002.csv (r = 0.02 m,
J = 8e-5 kg m), both L = 1 m, EI = 50 N m^2, m = 0.2 kg/m; 10 modes.
Columns follow tests/data/continuous_beam/*.csv:
    mode,omega_rad_s,omega_hz,method_a,method_b
(16 significant digits; omega_rad_s = method A; method_b = Ritz N=40, identical to
16 digits; omega_hz = omega_rad_s/(2 pi)).  Note reference_frequencies() looks in
tests/data/continuous_beam, so from a test use "../rayleigh_beam/table4_r005.csv".
There is NO '#' comment line by default, because the Rust helper
tests/suite/common/mod.rs::reference_frequencies() uses csv::Reader::from_path (default
builder: no comment character, has_headers = true, flexible = false), which would
take a '#' line as the header row and fail.  `--comment-header` prepends a one-line
'# ...' provenance header for readers configured with comment(Some(b'#')).

Run:  python3 reference.py [--comment-header]      (about 2 s)
"""
import math
import os
import sys
import time
from decimal import Decimal as D, getcontext, localcontext
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
DIGITS = 50                      # working precision of method A
getcontext().prec = DIGITS
NMODES = 10
CASES = [  # file, L [m], EI [N m^2], m [kg/m], r [m]  (J = m r^2)
    ("table4_r005.csv", "1", "50", "0.2", "0.05"),
    ("table4_r002.csv", "1", "50", "0.2", "0.02"),
]
RITZ_N = (24, 32, 40)
TOL_AB = D("1e-20")


# ---------------------------------------------------------------- Decimal helpers
def cos_sin(x):
    """cos x, sin x by Taylor series; guard digits cover the e^|x| growth of terms."""
    with localcontext() as ctx:
        ctx.prec += 10 + int(abs(x) / 2)
        x2, eps = x * x, D(10) ** -(ctx.prec + 2)
        c, s, tc, ts, n = D(1), x, D(1), x, 0
        while abs(tc) > eps or abs(ts) > eps:
            n += 2
            tc = -tc * x2 / (n * (n - 1))
            ts = -ts * x2 / (n * (n + 1))
            c, s = c + tc, s + ts
    return +c, +s


def pi_dec():
    """pi = 16 atan(1/5) - 4 atan(1/239) (Machin)."""
    def atan_inv(k):
        with localcontext() as ctx:
            ctx.prec += 5
            t = s = D(1) / k
            n, k2 = 1, k * k
            while abs(t) > D(10) ** -(ctx.prec + 1):
                t = -t / k2
                n += 2
                s += t / n
        return s
    return +(16 * atan_inv(5) - 4 * atan_inv(239))


# ---------------------------------------------------------------- method A
def g(b, gam, rotary_shear=True):
    """Scaled characteristic function (see docstring) at b = b L, gam = (r/L)^2.
    rotary_shear=False drops J om^2 W' from the shear condition (deliberately wrong
    BC, EI W'''(L) = 0, used only to show that method B detects such a mistake):
    then D = (a^4 + b^4) + 2 a^2 b^2 cosh a cos b + a b (b^2 - a^2) sinh a sin b."""
    Om = b * b / (1 + gam * b * b).sqrt()
    a = Om / b
    a2, b2 = a * a, b * b
    s4 = a2 * a2 + b2 * b2
    e = a.exp()
    ch, th = (e + 1 / e) / 2, (e - 1 / e) / (e + 1 / e)
    c, s = cos_sin(b)
    if rotary_shear:
        return 2 * a2 * b2 / (s4 * ch) + c - a * b * (b2 - a2) / s4 * th * s
    return s4 / (2 * a2 * b2 * ch) + c + (b2 - a2) / (2 * a * b) * th * s


def roots_A(gam, n, rotary_shear=True):
    """First n roots b_k of g, returned as Om_k; scan step pi/40, Illinois polish."""
    f = lambda b: g(b, gam, rotary_shear)
    h = pi_dec() / 40
    out, b0, f0 = [], h / 4, f(h / 4)
    while len(out) < n:
        b1 = b0 + h
        f1 = f(b1)
        if f1 == 0:
            out.append(b1)
        elif f0 * f1 < 0:                      # exactly one root expected: illinois
            lo, hi, flo, fhi, side = b0, b1, f0, f1, 0
            while hi - lo > D(10) ** (10 - DIGITS) * hi:
                c = (lo * fhi - hi * flo) / (fhi - flo)
                fc = f(c)
                if fc == 0:
                    lo = hi = c
                    break
                if (fc > 0) == (fhi > 0):
                    hi, fhi = c, fc
                    if side == -1:
                        flo /= 2
                    side = -1
                else:
                    lo, flo = c, fc
                    if side == 1:
                        fhi /= 2
                    side = 1
            out.append((lo + hi) / 2)
        b0, f0 = b1, f1
    return [b * b / (1 + gam * b * b).sqrt() for b in out]


# ---------------------------------------------------------------- method B
def ritz_B(gam, N, n):
    """Lowest n Ritz values Om_k (N monomials xi^(i+2)), Decimal at 60 + 2N digits."""
    gq = Fraction(str(gam))
    with localcontext() as ctx:
        ctx.prec = 60 + 2 * N
        dec = lambda q: D(q.numerator) / D(q.denominator)
        K = [[dec(Fraction((i + 1) * (i + 2) * (j + 1) * (j + 2), i + j + 1))
              for j in range(N)] for i in range(N)]
        M = [[dec(Fraction(1, i + j + 5) + gq * Fraction((i + 2) * (j + 2), i + j + 3))
              for j in range(N)] for i in range(N)]
        # Cholesky M = L L^T
        L = [[D(0)] * N for _ in range(N)]
        for i in range(N):
            for j in range(i + 1):
                s = M[i][j] - sum(L[i][k] * L[j][k] for k in range(j))
                L[i][j] = s.sqrt() if i == j else s / L[j][j]

        def fwd(v):  # solve L y = v
            y = []
            for i in range(N):
                y.append((v[i] - sum(L[i][k] * y[k] for k in range(i))) / L[i][i])
            return y
        X = [fwd([K[i][j] for i in range(N)]) for j in range(N)]   # X[j] = L^-1 K[:,j]
        Y = [fwd([X[j][i] for j in range(N)]) for i in range(N)]   # rows of C (C sym.)
        A = [[(Y[i][j] + Y[j][i]) / 2 for j in range(N)] for i in range(N)]
        # Householder tridiagonalisation
        for k in range(N - 2):
            x = [A[i][k] for i in range(k + 1, N)]
            nx = sum(t * t for t in x).sqrt()
            if nx == 0:
                continue
            alpha = -nx if x[0] > 0 else nx
            v = x[:]
            v[0] -= alpha
            beta = 2 / sum(t * t for t in v)
            m = len(v)
            p = [beta * sum(A[k + 1 + i][k + 1 + j] * v[j] for j in range(m)) for i in range(m)]
            Kc = beta * sum(v[i] * p[i] for i in range(m)) / 2
            q = [p[i] - Kc * v[i] for i in range(m)]
            for i in range(m):
                for j in range(m):
                    A[k + 1 + i][k + 1 + j] -= v[i] * q[j] + q[i] * v[j]
            for i in range(k + 1, N):
                A[i][k] = A[k][i] = D(0)
            A[k + 1][k] = A[k][k + 1] = alpha
        d = [A[i][i] for i in range(N)]
        e2 = [A[i + 1][i] ** 2 for i in range(N - 1)]

        def count(lam):  # Sturm count: number of eigenvalues < lam
            c, q = 0, d[0] - lam
            for i in range(N):
                if i:
                    q = d[i] - lam - e2[i - 1] / q
                if q == 0:
                    q = D(10) ** -(ctx.prec - 5)
                c += q < 0
            return c
        off = [D(0)] + [t.sqrt() for t in e2] + [D(0)]
        top = max(abs(d[i]) + off[i] + off[i + 1] for i in range(N))   # Gershgorin
        lams = []
        for k in range(n):      # k-th eigenvalue: count(lo) <= k < count(hi)
            lo, hi = (lams[-1] if lams else D(0)), top
            while hi - lo > D(10) ** -(DIGITS + 5) * hi:
                mid = (lo + hi) / 2
                if count(mid) > k:
                    hi = mid
                else:
                    lo = mid
            lams.append((lo + hi) / 2)
        return [+l.sqrt() for l in lams]


# ---------------------------------------------------------------- checks / driver
EB_DECIMALS = ["1.8751040687", "4.6940911330", "7.8547574382", "10.9955407349"]  # classical


def eb_float_roots(n):
    """Independent EB roots: bisection of cos x + 1/cosh x in [(k-1)pi, k pi]."""
    out = []
    for k in range(1, n + 1):
        a, b = (k - 1) * math.pi, k * math.pi
        f = lambda x: math.cos(x) + 1 / math.cosh(x)
        for _ in range(200):
            mid = (a + b) / 2
            a, b = (a, mid) if f(a) * f(mid) <= 0 else (mid, b)
        out.append((a + b) / 2)
    return out


def rel(x, y):
    return abs(x - y) / abs(y)


def sci(x):
    return "%.1e" % float(x)


def fmt(x, digits=16):
    with localcontext() as ctx:
        ctx.prec = digits
        return format(+x, "f")


def limit_checks():
    print("J -> 0 (Euler-Bernoulli) checks")
    OmA = roots_A(D(0), NMODES)
    bA = [o.sqrt() for o in OmA]
    eb = eb_float_roots(NMODES)
    OmB = ritz_B(D(0), RITZ_N[-1], NMODES)
    print("  k    beta_k L (A, gam=0)              EB float bisection   10-decimal     |A-float| |A-10dec| |B-A|/A (Om)")
    for k in range(NMODES):
        d1 = abs(float(bA[k]) - eb[k])
        d2 = abs(bA[k] - D(EB_DECIMALS[k])) if k < len(EB_DECIMALS) else D(0)
        d3 = rel(OmB[k], OmA[k])
        print("  %2d  %s  %.15f  %-13s  %.1e   %.1e   %s" % (k + 1, fmt(bA[k], 25), eb[k],
                                                       EB_DECIMALS[k] if k < len(EB_DECIMALS) else "-", d1, d2, sci(d3)))
        assert d1 < 1e-14 * eb[k] and d2 < D("6e-11") and d3 < TOL_AB
    print("  gam -> 0: (Om_EB - Om)/(gam Om_EB) for gam = 1e-6, 1e-8, 1e-10")
    dev = {}
    for gam in ("1e-6", "1e-8", "1e-10"):
        Om = roots_A(D(gam), NMODES)
        dev[gam] = [(OmA[k] - Om[k]) / OmA[k] for k in range(NMODES)]
        assert all(x > 0 for x in dev[gam])
        print("    gam=%-6s " % gam + " ".join("%.6g" % float(x / D(gam)) for x in dev[gam]))
    for k in range(NMODES):
        assert abs(dev["1e-6"][k] / dev["1e-8"][k] / 100 - 1) < D("1e-2")
        assert abs(dev["1e-8"][k] / dev["1e-10"][k] / 100 - 1) < D("1e-4")
    return OmA


def run_case(fname, L, EI, m, r, OmEB, comment):
    L, EI, m, r = D(L), D(EI), D(m), D(r)
    J = m * r * r
    gam = J / (m * L * L)
    scale = (EI / (m * L ** 4)).sqrt()          # om = Om * scale
    print("=" * 100)
    print("%s: L=%s m, EI=%s N m^2, m=%s kg/m, r=%s m, J=%s kg m, gam=(r/L)^2=%s"
          % (fname, L, EI, m, r, J, gam))
    t = time.perf_counter()
    OmA = roots_A(gam, NMODES + 1)             # one extra for the count check
    tA = time.perf_counter() - t
    bs = [((gam * o * o + (gam * gam * o ** 4 + 4 * o * o).sqrt()) / 2).sqrt() for o in OmA]
    gap = min(y - x for x, y in zip([D(0)] + bs, bs))
    assert gap > 10 * pi_dec() / 40, "roots too close for the scan grid"
    OmB = {}
    for N in RITZ_N:
        t = time.perf_counter()
        OmB[N] = ritz_B(gam, N, NMODES + 1)
        print("  Ritz N=%d: %.1f s" % (N, time.perf_counter() - t))
    print("  method A (scan+Illinois) %.1f s; min. gap between roots b_k L: %.3f (grid step %.4f)"
          % (tA, gap, pi_dec() / 40))
    Nf, Np = RITZ_N[-1], RITZ_N[-2]
    print("  mode          omega A [rad/s]                 omega B (N=%d)            |B-A|/A  B(N=%d)-B(N=%d)  "
          "omega EB [rad/s]     (om_EB-om)/om_EB" % (Nf, Np, Nf))
    for k in range(NMODES + 1):
        dAB = rel(OmB[Nf][k], OmA[k])
        conv = rel(OmB[Np][k], OmB[Nf][k])
        eb = "%-20s %.6f" % (fmt(OmEB[k] * scale), (OmEB[k] - OmA[k]) / OmEB[k]) if k < NMODES else ""
        print("  %4d  %-30s %-30s %-8s %-8s  %s" % (k + 1, fmt(OmA[k] * scale, 26),
              fmt(OmB[Nf][k] * scale, 26), sci(dAB), sci(conv), eb))
        assert dAB < TOL_AB, "A and B disagree at mode %d (skipped/spurious root?)" % (k + 1)
        assert k == NMODES or OmA[k] < OmEB[k]
        slack = 1 - D("1e-38")   # root / bisection tolerances of A and B
        for N1, N2 in zip(RITZ_N, RITZ_N[1:]):        # min-max: upper bounds, monotone
            assert OmB[N1][k] >= OmB[N2][k] * slack and OmB[N2][k] >= OmA[k] * slack
    # the deliberately wrong shear condition EI W'''(L) = 0 must be rejected by B
    OmW = roots_A(gam, NMODES, rotary_shear=False)
    dW = max(rel(OmW[k], OmB[Nf][k]) for k in range(NMODES))
    print("  wrong shear BC EI W'''(L)=0 (rotary term dropped): max |A_wrong-B|/B = %s" % sci(dW))
    assert dW > D(10) ** 6 * TOL_AB
    path = os.path.join(HERE, fname)
    tpi = 2 * pi_dec()
    with open(path, "w") as f:
        if comment:
            f.write("# %s: uniform Rayleigh-beam cantilever L=%s m EI=%s N m^2 m=%s kg/m J=%s kg m "
                    "(r=%s m); method A exact characteristic equation + Illinois (Decimal %d digits, "
                    "|db|<1e-40 b), checked vs Rayleigh-Ritz N=%d (rel diff < %s)\n"
                    % (os.path.basename(__file__), L, EI, m, J, r, DIGITS, Nf, TOL_AB))
        f.write("mode,omega_rad_s,omega_hz,method_a,method_b\n")
        for k in range(NMODES):
            om, omb = OmA[k] * scale, OmB[Nf][k] * scale
            f.write("%d,%s,%s,%s,%s\n" % (k + 1, fmt(om), fmt(om / tpi), fmt(om), fmt(omb)))
    print("  wrote", path)


def main():
    t0 = time.perf_counter()
    comment = "--comment-header" in sys.argv[1:]
    OmEB = limit_checks()
    for case in CASES:
        run_case(*case, OmEB, comment)
    print("total run time %.1f s" % (time.perf_counter() - t0))


if __name__ == "__main__":
    main()
