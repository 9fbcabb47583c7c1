#!/usr/bin/env python3
"""Independent reference solutions of the planar inextensible elastica
(Euler-Bernoulli cantilever, large rotations) for the flexwing tests.

Requirements: Python >= 3.8 and mpmath (tested with mpmath 1.3.0).  Nothing else.
Run:          python3 elastica.py          (writes the CSV files next to this script)
              python3 elastica.py --quick  (skips the slow mpmath.odefun cross-check)

Model (see README.md): arc length s in [0, L], clamp at s = 0 with tangent +x,
    x' = cos(theta), y' = sin(theta), EI theta'(s) = M(s),
    M(s) = sum over loads F_i applied at X_i beyond s of (X_i - X(s)) x F_i  (z-component)
Differentiating, EI theta''(s) = -t(s) x N(s) = -(cos(theta) N_y - sin(theta) N_x),
where N(s) is the resultant of all loads applied on (s, L].  With
a(s) = -N_y(s)/EI and b(s) = N_x(s)/EI (both piecewise linear in s) every case is
    theta'' = a(s) cos(theta) + b(s) sin(theta),  theta(0) = 0,  theta'(L) = 0.

Method A (written to the CSVs): Taylor-series integration with exact recursive Taylor
coefficients (order 24, 40 fixed steps, dense output at the nodes s_k = k L/80).  The
coefficient recurrences run in fixed-point integer arithmetic with 124 fraction bits
(~37 digits, for speed); cos/sin and everything else use mpmath at 30 digits.  Shooting
on kappa0 = theta'(0) by Newton's method with the variational equation
z'' = (-a sin(theta) + b cos(theta)) z, continued in the load from the linear solution.
Breakpoints (s = L/2 in case 3) are step boundaries.  The follower case is solved as an
initial-value problem from the tip (no shooting).
Checks: (A') the same with 80 steps and order 34; (B) elliptic-integral closed form
(Bisshopp-Drucker) for the dead tip load and tanh-sinh quadrature of the first integral
for the follower load; (C) mpmath.odefun (a different Taylor integrator, 20 digits)
re-integrating every shape solution; (D) moment balance at the clamp and EI theta'(s_k)
= M(s_k) from the definition of M at every shape node; (E) small-load linear limit;
(F) scan of the shooting residual for other roots; a convergence table.
"""
import sys
import os
import time
import mpmath as mp
from operator import mul

mp.mp.dps = 30
HERE = os.path.dirname(os.path.abspath(__file__))

L = mp.mpf(1)
EI = mp.mpf(50)
NNODE = 80                      # shape nodes s_k = k L / 80, k = 0..80
MID = L / 2

# integration settings: (steps over [0, L], Taylor order)
CFG_A = (40, 24)                # production
CFG_B = (80, 34)                # refinement check

MAXDIFF = {}                    # name -> max |difference| recorded by the checks


def note(name, value):
    value = abs(value)
    MAXDIFF[name] = max(MAXDIFF.get(name, mp.mpf(0)), value)


# ---------------------------------------------------------------------------
# Taylor-series integrator
# ---------------------------------------------------------------------------
FB = 124                        # fixed-point fraction bits (2^-124 ~ 5e-38)
ONE = 1 << FB


def tofix(v):
    return int(mp.nint(mp.ldexp(mp.mpf(v), FB)))


def tompf(V):
    return mp.mpf((V, -FB))


def horner(coef, t):
    """fixed-point Horner: sum coef[k] t^k"""
    r = 0
    for cf in reversed(coef):
        r = ((r * t) >> FB) + cf
    return r


def dhorner(coef, t):
    r = 0
    for k in range(len(coef) - 1, 0, -1):
        r = ((r * t) >> FB) + k * coef[k]
    return r


def taylor_step(th0, th1, z0, z1, A0, A1, B0, B1, P, var):
    """Exact Taylor coefficients (fixed point, local variable tau = s - s0) of
        theta'' = (A0 + A1 tau) cos(theta) + (B0 + B1 tau) sin(theta),
    of cos(theta), sin(theta), and of the variational equation
        z'' = q z,  q = -(A0 + A1 tau) sin(theta) + (B0 + B1 tau) cos(theta).
    Recurrences: (k+1) c_{k+1} = -sum_j j th_j sn_{k+1-j},
                 (k+1) sn_{k+1} = sum_j j th_j c_{k+1-j}."""
    t0 = tompf(th0)
    th = [th0, th1] + [0] * (P - 1)
    jth = [0, th1] + [0] * (P - 1)            # j * th_j
    c = [tofix(mp.cos(t0))] + [0] * P
    sn = [tofix(mp.sin(t0))] + [0] * P
    if var:
        z = [z0, z1] + [0] * (P - 1)
        q = [0] * (P + 1)
    for k in range(P - 1):
        r = A0 * c[k] + B0 * sn[k]
        if k:
            r += A1 * c[k - 1] + B1 * sn[k - 1]
        th[k + 2] = (r >> FB) // ((k + 1) * (k + 2))
        jth[k + 2] = (k + 2) * th[k + 2]
        if var:
            qk = -A0 * sn[k] + B0 * c[k]
            if k:
                qk += -A1 * sn[k - 1] + B1 * c[k - 1]
            q[k] = qk >> FB
            acc = sum(map(mul, q[:k + 1], reversed(z[:k + 1])))
            z[k + 2] = (acc >> FB) // ((k + 1) * (k + 2))
        jj = jth[1:k + 2]
        sc = sum(map(mul, jj, reversed(sn[:k + 1])))
        ss = sum(map(mul, jj, reversed(c[:k + 1])))
        c[k + 1] = -((sc >> FB) // (k + 1))
        sn[k + 1] = (ss >> FB) // (k + 1)
    return th, c, sn, (z if var else None)


def integrate(kappa0, segs, cfg, var=True, nodes=False, theta0=0):
    """Integrate theta'' = a(s) cos(theta) + b(s) sin(theta) from s = 0 to L with
    theta(0) = theta0, theta'(0) = kappa0, x(0) = y(0) = 0.
    segs: list of (s_start, s_end, a0, a1, b0, b1) with a(s) = a0 + a1 s, b(s) = b0 + b1 s
    (global s).  Segment ends must be multiples of L/NNODE.
    Returns a dict with the end values (mpf), optionally the node values
    [(s, x, y, theta, theta', int_0^s x)] at s_k = k L/NNODE (dense output of the
    Taylor polynomials),
    and the values at s = L/2."""
    nsteps, P = cfg
    h = L / nsteps
    hf = tofix(h)
    th, dth = tofix(theta0), tofix(kappa0)
    x = y = W = 0                   # W = int_0^s x ds (used for the moment check)
    z, dz = 0, ONE
    out_nodes = [(mp.mpf(0), mp.mpf(0), mp.mpf(0), tompf(th), tompf(dth), mp.mpf(0))] if nodes else None
    mid = None
    ds_node = L / NNODE
    for (sa, sb, a0, a1, b0, b1) in segs:
        n = int(mp.nint((sb - sa) / h))
        assert abs(n * h - (sb - sa)) < mp.mpf(10) ** (-25)
        A1, B1 = tofix(a1), tofix(b1)
        for i in range(n):
            s0 = sa + i * h
            A0 = tofix(a0 + a1 * s0)
            B0 = tofix(b0 + b1 * s0)
            tc, cc, sc, zc = taylor_step(th, dth, z, dz, A0, A1, B0, B1, P, var)
            xc = [x] + [cc[k] // (k + 1) for k in range(P)]
            yc = [y] + [sc[k] // (k + 1) for k in range(P)]
            Wc = [W] + [xc[k] // (k + 1) for k in range(P)]
            if nodes:
                # nodes strictly inside (s0, s0 + h]
                kfirst = int(mp.floor(s0 / ds_node + mp.mpf('1e-20'))) + 1
                klast = int(mp.floor((s0 + h) / ds_node + mp.mpf('1e-20')))
                for kk in range(kfirst, klast + 1):
                    tau = tofix(kk * ds_node - s0)
                    out_nodes.append((kk * ds_node, tompf(horner(xc, tau)),
                                      tompf(horner(yc, tau)), tompf(horner(tc, tau)),
                                      tompf(dhorner(tc, tau)), tompf(horner(Wc, tau))))
            th, dth = horner(tc, hf), dhorner(tc, hf)
            x, y, W = horner(xc, hf), horner(yc, hf), horner(Wc, hf)
            if var:
                z, dz = horner(zc, hf), dhorner(zc, hf)
            if abs(s0 + h - MID) < mp.mpf(10) ** (-25):
                mid = (tompf(x), tompf(y), tompf(th))
    return dict(theta=tompf(th), dtheta=tompf(dth), x=tompf(x), y=tompf(y), W=tompf(W),
                z=tompf(z), dz=tompf(dz), nodes=out_nodes, mid=mid)


def shoot(segs, kappa_guess, cfg, maxit=40):
    """Newton on kappa0 = theta'(0) so that theta'(L) = 0 (derivative from the
    variational equation).  Stops once the Newton step is < 1e-15: by quadratic
    convergence the returned kappa0 is then correct to ~1e-28."""
    k = mp.mpf(kappa_guess)
    for it in range(maxit):
        r = integrate(k, segs, cfg, var=True)
        dk = -r['dtheta'] / r['dz']
        lim = 1 + abs(k)            # damp very large steps (poor initial guesses only)
        if abs(dk) > lim:
            dk = lim * mp.sign(dk)
        k += dk
        if abs(dk) < mp.mpf(10) ** (-15):
            return k
    raise RuntimeError('shooting did not converge')


# ---------------------------------------------------------------------------
# The load cases as a(s), b(s) segments
# ---------------------------------------------------------------------------
def segs_dead_tip(P):
    # N = (0, P) everywhere: a = -P/EI, b = 0
    return [(mp.mpf(0), L, -P / EI, 0, 0, 0)]


def segs_two_loads(F1, F2):
    # N_y = F1 + F2 on (0, L/2), F1 on (L/2, L)
    return [(mp.mpf(0), MID, -(F1 + F2) / EI, 0, 0, 0),
            (MID, L, -F1 / EI, 0, 0, 0)]


def segs_distributed(w0):
    # f = (0, -w0): N(s) = (0, -w0 (L - s)), a = w0 (L - s)/EI = w0 L/EI - (w0/EI) s
    return [(mp.mpf(0), L, w0 * L / EI, -w0 / EI, 0, 0)]


def solve_follower(P, cfg, nodes=False):
    """Follower normal tip force.  psi(r) = theta(L) - theta(L - r), r = L - s:
         psi'' = (P/EI) cos(psi), psi(0) = 0, psi'(0) = 0   (an IVP from the tip).
    U(r) = int_0^r cos psi, V(r) = int_0^r sin psi give
         x(L) - x(s) = cos(thL) U + sin(thL) V,  y(L) - y(s) = sin(thL) U - cos(thL) V."""
    r = integrate(0, [(mp.mpf(0), L, P / EI, 0, 0, 0)], cfg, var=False, nodes=nodes)
    thL = r['theta']
    cL, sL = mp.cos(thL), mp.sin(thL)
    U, V = r['x'], r['y']
    xt = cL * U + sL * V
    yt = sL * U - cL * V
    # theta'(s) = dpsi/dr, so theta'(0) = psi'(r = L)
    res = dict(thL=thL, x=xt, y=yt, kappa0=r['dtheta'])
    if nodes:
        nd = []
        for (rr, u, v, psi, dpsi, _) in reversed(r['nodes']):
            nd.append((L - rr, xt - (cL * u + sL * v), yt - (sL * u - cL * v), thL - psi, dpsi))
        res['nodes'] = nd
    return res


# ---------------------------------------------------------------------------
# Method B: closed forms / quadrature
# ---------------------------------------------------------------------------
def dead_tip_elliptic(alpha):
    """Bisshopp-Drucker elliptic-integral solution, vertical dead tip load.
    1 + sin(theta) = 2 m sin^2(phi), m = (1 + sin thL)/2, sin(phi0) = 1/sqrt(2m):
        sqrt(alpha) = K(m) - F(phi0|m)
        x_tip/L = sqrt(2 sin(thL)/alpha)
        y_tip/L = 1 - 2 (E(m) - E(phi0|m))/sqrt(alpha)."""
    sa = mp.sqrt(alpha)

    def g(m):
        phi0 = mp.asin(1 / mp.sqrt(2 * m))
        return mp.ellipk(m) - mp.ellipf(phi0, m) - sa
    # bracket: g(1/2) = -sqrt(alpha) < 0, g -> +inf as m -> 1
    lo, hi = mp.mpf(1) / 2, mp.mpf(1) / 2 + (1 - mp.mpf(1) / 2) / 2
    while g(hi) < 0:
        hi = (hi + 1) / 2
    m = mp.findroot(g, (lo, hi), solver='anderson', tol=mp.mpf(10) ** (-28))
    phi0 = mp.asin(1 / mp.sqrt(2 * m))
    thL = mp.asin(2 * m - 1)
    xt = mp.sqrt(2 * mp.sin(thL) / alpha) * L
    yt = (1 - 2 * (mp.ellipe(m) - mp.ellipe(phi0, m)) / sa) * L
    return thL, xt, yt


def follower_quadrature(alpha):
    """First integral psi'^2 = 2 alpha sin(psi) (s in units of L), psi = thL - theta.
    1 = int_0^thL dpsi / sqrt(2 alpha sin psi); x_tip = int cos(thL - psi) ds etc.
    Substitution psi = u^2 removes the endpoint singularity."""
    def length(thL):
        return mp.quad(lambda u: 2 * u / mp.sqrt(2 * alpha * mp.sin(u * u)),
                       [0, mp.sqrt(thL)])
    # length(T) increases from 0 (T = 0) to (Gamma(1/4)^2/sqrt(2 pi))/sqrt(2 alpha) (T = pi),
    # which exceeds 1 for alpha < 13.7; safeguarded Newton-bisection on (0, pi),
    # d length/dT = 1/sqrt(2 alpha sin T).
    lo, hi = mp.mpf(0), mp.pi
    assert length(hi) > 1
    T = min(mp.mpf(alpha) / 2, mp.pi / 2)
    for it in range(200):
        f = length(T) - 1
        if f > 0:
            hi = T
        else:
            lo = T
        Tn = T - f * mp.sqrt(2 * alpha * mp.sin(T))
        if not (lo < Tn < hi):
            Tn = (lo + hi) / 2
        if abs(Tn - T) < mp.mpf(10) ** (-26):
            T = Tn
            break
        T = Tn
    else:
        raise RuntimeError('follower quadrature: no convergence')
    w = lambda u: 2 * u / mp.sqrt(2 * alpha * mp.sin(u * u))
    xt = mp.quad(lambda u: mp.cos(T - u * u) * w(u), [0, mp.sqrt(T)]) * L
    yt = mp.quad(lambda u: mp.sin(T - u * u) * w(u), [0, mp.sqrt(T)]) * L
    return T, xt, yt


# ---------------------------------------------------------------------------
# Method C: mpmath.odefun re-integration of a given solution (20 digits)
# ---------------------------------------------------------------------------
def odefun_check(kappa0, segs, theta0=0, dps=20):
    """Integrate with mpmath.odefun segment by segment; returns node values
    [(s, x, y, theta)] and theta'(L)."""
    with mp.workdps(dps):
        u = [mp.mpf(theta0), mp.mpf(kappa0), mp.mpf(0), mp.mpf(0)]
        out = [(mp.mpf(0), u[2], u[3], u[0])]
        ds_node = L / NNODE
        for (sa, sb, a0, a1, b0, b1) in segs:
            def F(s, v, a0=a0, a1=a1, b0=b0, b1=b1):
                c, sn = mp.cos(v[0]), mp.sin(v[0])
                return [v[1], (a0 + a1 * s) * c + (b0 + b1 * s) * sn, c, sn]
            sol = mp.odefun(F, sa, u)
            k0 = int(mp.nint(sa / ds_node))
            k1 = int(mp.nint(sb / ds_node))
            for kk in range(k0 + 1, k1 + 1):
                v = sol(kk * ds_node)
                out.append((kk * ds_node, v[2], v[3], v[0]))
            u = sol(sb)
        return out, u[1]


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------
def _fmt(v):
    v = mp.mpf(v)
    if abs(v) < mp.mpf(10) ** (-25):   # exact zeros (clamp node) carry ~1e-31 round-off
        return '0'
    s = mp.nstr(v, 16, strip_zeros=False)
    return s


def write_csv(name, header, rows):
    with open(os.path.join(HERE, name), 'w') as f:
        f.write(','.join(header) + '\n')
        for r in rows:
            f.write(','.join(c if isinstance(c, str) else _fmt(c) for c in r) + '\n')


def plain(v):
    """exact decimal for load grid values"""
    v = mp.mpf(v)
    if v == mp.nint(v):
        return str(int(mp.nint(v)))
    return mp.nstr(v, 10)


def compare_nodes(name, n1, n2):
    for a, b in zip(n1, n2):
        assert abs(a[0] - b[0]) < mp.mpf(10) ** (-15)
        for i in (1, 2, 3):
            note(name, a[i] - b[i])


def moment_check(name, nodes, Mfun):
    """EI theta'(s_k) (from the integrated ODE) against the bending moment M(s_k) computed
    directly from its definition with the computed node positions."""
    for nd in nodes:
        note(name, EI * nd[4] - Mfun(nd))


def root_scan(segs, lo=-30, hi=30, n=240, cfg=(40, 20)):
    """Sign changes of theta'(L) over kappa0 in [lo, hi]: number of shooting roots
    (branches) visible at this resolution; returns the list of roots."""
    roots, prev = [], None
    for i in range(n + 1):
        k = lo + (hi - lo) * mp.mpf(i) / n
        f = integrate(k, segs, cfg, var=False)['dtheta']
        if prev is not None and mp.sign(f) != mp.sign(prev[1]):
            roots.append(shoot(segs, (k + prev[0]) / 2, CFG_A))
        prev = (k, f)
    return roots


def dead_tip_fold():
    """Dead vertical tip load: from the first integral theta'^2 = 2 alpha (c - sin theta),
    c = sin(theta_tip) >= 0, every solution oscillates in [-pi - asin c, asin c].  All
    solutions other than the tabulated one (0 <= theta <= theta_tip) reach -pi - asin c,
    which takes the length l2(c)/sqrt(alpha),
        l2(c) = int_{-pi-p}^{0} dtheta / sqrt(2 (c - sin theta)),  p = asin c.
    They exist iff sqrt(alpha) >= min_c l2(c).  Returns (c*, min l2, alpha_fold)."""
    def l2(c):
        p = mp.asin(c)
        # theta = -pi - p + u^2;  c - sin(theta) = 2 sin(u^2/2) cos(p - u^2/2)
        f = lambda u: 2 * u / mp.sqrt(4 * mp.sin(u * u / 2) * mp.cos(p - u * u / 2))
        return mp.quad(f, [0, mp.sqrt(mp.pi / 2 - p), mp.sqrt(mp.pi + p)])
    c0 = min((l2(mp.mpf(i) / 50), mp.mpf(i) / 50) for i in range(5, 45))[1]
    c = mp.findroot(lambda c_: mp.diff(l2, c_), c0)
    return c, l2(c), l2(c) ** 2


def convergence_table(say):
    """Error of the tip deflection vs (steps, order) for the hardest dead-load case."""
    segs = segs_dead_tip(10 * EI / L ** 2)
    thE, xE, yE = dead_tip_elliptic(mp.mpf(10))
    say('  convergence of case 1, alpha = 10 (|tip_y - elliptic|):')
    for cfg in [(10, 8), (20, 8), (40, 8), (20, 16), (40, 16), CFG_A, CFG_B]:
        k = shoot(segs, mp.mpf('4.45'), cfg)
        r = integrate(k, segs, cfg, var=False)
        say('    steps %3d, order %2d: %.2e' % (cfg[0], cfg[1], float(abs(r['y'] - yE))))


# ---------------------------------------------------------------------------
def main():
    quick = '--quick' in sys.argv
    scan_list = []
    t_start = time.time()
    log = []

    def say(*a):
        s = ' '.join(str(x) for x in a)
        print(s, flush=True)
        log.append(s)

    say('elastica.py: L =', L, 'm, EI =', EI, 'N m^2, mp.dps =', mp.mp.dps,
        ', cfg A (steps, order) =', CFG_A, ', cfg B =', CFG_B)
    alphas = [mp.mpf(i) / 4 for i in range(41)]
    shape_alphas = [mp.mpf(1), mp.mpf(3), mp.mpf(10)]

    # ---------------- case 1: dead vertical tip force ----------------
    rows, shapes = [], []
    kg = mp.mpf(0)
    prev = []
    for al in alphas:
        P = al * EI / L ** 2
        if al == 0:
            rows.append([plain(al), plain(P), L, 0, 0])
            continue
        # continuation: linear extrapolation of kappa0 in alpha
        if len(prev) >= 2:
            kg = 2 * prev[-1] - prev[-2]
        else:
            kg = P * L / EI
        segs = segs_dead_tip(P)
        k = shoot(segs, kg, CFG_A)
        prev.append(k)
        isshape = al in shape_alphas
        r = integrate(k, segs, CFG_A, var=False, nodes=isshape)
        kB = shoot(segs, k, CFG_B)
        rB = integrate(kB, segs, CFG_B, var=False, nodes=isshape)
        note('case1 A vs B (tip x,y,angle)', r['x'] - rB['x'])
        note('case1 A vs B (tip x,y,angle)', r['y'] - rB['y'])
        note('case1 A vs B (tip x,y,angle)', r['theta'] - rB['theta'])
        thE, xE, yE = dead_tip_elliptic(al)
        note('case1 A vs elliptic closed form (tip x,y,angle)', r['x'] - xE)
        note('case1 A vs elliptic closed form (tip x,y,angle)', r['y'] - yE)
        note('case1 A vs elliptic closed form (tip x,y,angle)', r['theta'] - thE)
        note('case1 moment balance |EI k0 - P x_tip| / (P L)', (EI * k - P * r['x']) / (P * L))
        rows.append([plain(al), plain(P), r['x'], r['y'], r['theta']])
        if isshape:
            scan_list.append(('case1 alpha=%s' % plain(al), segs, k))
            moment_check('case1 shapes |EI theta\' - M(s)| [N m]', r['nodes'],
                         lambda nd: P * (r['x'] - nd[1]))
            compare_nodes('case1 shapes A vs B', r['nodes'], rB['nodes'])
            if not quick:
                nC, dthC = odefun_check(k, segs)
                compare_nodes('case1 shapes A vs mpmath.odefun', r['nodes'], nC)
                note("case1 mpmath.odefun residual theta'(L) [1/m]", dthC)
            for kk, (s, x, y, th) in enumerate(nd_[:4] for nd_ in r["nodes"]):
                shapes.append([plain(al), str(kk), s, x, y, th])
    write_csv('dead_tip.csv', ['alpha', 'P_N', 'tip_x_m', 'tip_y_m', 'tip_angle_rad'], rows)
    write_csv('dead_tip_shapes.csv', ['alpha', 'k', 's_m', 'x_m', 'y_m', 'theta_rad'], shapes)
    say('\nBisshopp & Drucker (1945) check, vertical tip deflection / L:')
    bd = {1: '0.3017', 3: '0.6033', 10: '0.8106'}
    for a_, ref in bd.items():
        row = [r_ for r_ in rows if r_[0] == str(a_)][0]
        say('  alpha = %2d: computed %s, B&D table %s, |diff| = %.1e' %
            (a_, mp.nstr(row[3], 12), ref, float(abs(row[3] - mp.mpf(ref)))))
        assert abs(row[3] - mp.mpf(ref)) <= mp.mpf('0.00005') + mp.mpf(10) ** -12
    say('  case 1 done, %.1f s' % (time.time() - t_start))

    # ---------------- case 2: follower (normal) tip force ----------------
    rows, shapes = [], []
    for al in alphas:
        P = al * EI / L ** 2
        if al == 0:
            rows.append([plain(al), plain(P), L, 0, 0])
            continue
        isshape = al in shape_alphas
        r = solve_follower(P, CFG_A, nodes=isshape)
        rB = solve_follower(P, CFG_B, nodes=isshape)
        for key in ('x', 'y', 'thL'):
            note('case2 A vs B (tip x,y,angle)', r[key] - rB[key])
        T, xq, yq = follower_quadrature(al)
        note('case2 A vs first-integral quadrature (tip x,y,angle)', r['x'] - xq)
        note('case2 A vs first-integral quadrature (tip x,y,angle)', r['y'] - yq)
        note('case2 A vs first-integral quadrature (tip x,y,angle)', r['thL'] - T)
        # root curvature from the first integral: theta'(0) = sqrt(2 P sin(thL)/EI)
        note('case2 kappa0 vs sqrt(2 P sin(thL)/EI)', r['kappa0'] - mp.sqrt(2 * P * mp.sin(r['thL']) / EI))
        # moment balance at the clamp: EI theta'(0) = P (x_L cos thL + y_L sin thL)
        note('case2 moment balance / (P L)', (EI * r['kappa0'] - P * (r['x'] * mp.cos(r['thL']) + r['y'] * mp.sin(r['thL']))) / (P * L))
        rows.append([plain(al), plain(P), r['x'], r['y'], r['thL']])
        if isshape:
            compare_nodes('case2 shapes A vs B', r['nodes'], rB['nodes'])
            cT, sT = mp.cos(r['thL']), mp.sin(r['thL'])
            moment_check('case2 shapes |EI theta\' - M(s)| [N m]', r['nodes'],
                         lambda nd: P * ((r['x'] - nd[1]) * cT + (r['y'] - nd[2]) * sT))
            if not quick:
                # forward re-integration from the clamp as an equivalent dead load
                # N = P(-sin thL, cos thL): a = -P cos(thL)/EI, b = -P sin(thL)/EI
                thL = r['thL']
                segs = [(mp.mpf(0), L, -P * mp.cos(thL) / EI, 0, -P * mp.sin(thL) / EI, 0)]
                nC, dthC = odefun_check(r['kappa0'], segs)
                compare_nodes('case2 shapes A vs mpmath.odefun (forward)', r['nodes'], nC)
                note("case2 mpmath.odefun residual theta'(L) [1/m]", dthC)
            for kk, (s, x, y, th) in enumerate(nd_[:4] for nd_ in r["nodes"]):
                shapes.append([plain(al), str(kk), s, x, y, th])
    write_csv('follower_tip.csv', ['alpha', 'P_N', 'tip_x_m', 'tip_y_m', 'tip_angle_rad'], rows)
    write_csv('follower_tip_shapes.csv', ['alpha', 'k', 's_m', 'x_m', 'y_m', 'theta_rad'], shapes)
    say('  follower tip angle at alpha = 10: %s rad; first tabulated alpha with tip angle > pi/2: %s'
        % (mp.nstr(rows[-1][4], 12), [r_[0] for r_ in rows if r_[4] > mp.pi / 2][0]))
    say('  (tip angle -> pi as alpha -> Gamma(1/4)^4/(4 pi) = %s; the tip-IVP solution is unique)'
        % mp.nstr(mp.gamma(mp.mpf(1) / 4) ** 4 / (4 * mp.pi), 10))
    say('  case 2 done, %.1f s' % (time.time() - t_start))

    # ---------------- case 3: tip F1 (+y) and F2 = -150 N at mid-span ----------------
    F2 = mp.mpf(-150)
    rows, shapes = [], []
    prev = []
    shape_F1 = [mp.mpf(0), mp.mpf(50), mp.mpf(100), mp.mpf(150)]
    for i in range(16):
        F1 = mp.mpf(10 * i)
        segs = segs_two_loads(F1, F2)
        if len(prev) >= 2:
            kg = 2 * prev[-1] - prev[-2]
        else:
            kg = (F1 * L + F2 * MID) / EI
        k = shoot(segs, kg, CFG_A)
        prev.append(k)
        isshape = F1 in shape_F1
        r = integrate(k, segs, CFG_A, var=False, nodes=isshape)
        kB = shoot(segs, k, CFG_B)
        rB = integrate(kB, segs, CFG_B, var=False, nodes=isshape)
        for a_, b_ in ((r['x'], rB['x']), (r['y'], rB['y']), (r['mid'][0], rB['mid'][0]),
                       (r['mid'][1], rB['mid'][1]), (r['theta'], rB['theta'])):
            note('case3 A vs B (tip, mid)', a_ - b_)
        note('case3 moment balance |EI k0 - F1 x_tip - F2 x_mid| [N m]',
             EI * k - F1 * r['x'] - F2 * r['mid'][0])
        rows.append([plain(F1), r['x'], r['y'], r['mid'][0], r['mid'][1]])
        if isshape:
            scan_list.append(('case3 F1=%s N' % plain(F1), segs, k))
            moment_check('case3 shapes |EI theta\' - M(s)| [N m]', r['nodes'],
                         lambda nd: F1 * (r['x'] - nd[1])
                         + (F2 * (r['mid'][0] - nd[1]) if nd[0] < MID else 0))
            compare_nodes('case3 shapes A vs B', r['nodes'], rB['nodes'])
            if not quick:
                nC, dthC = odefun_check(k, segs)
                compare_nodes('case3 shapes A vs mpmath.odefun', r['nodes'], nC)
                note("case3 mpmath.odefun residual theta'(L) [1/m]", dthC)
            for kk, (s, x, y, th) in enumerate(nd_[:4] for nd_ in r["nodes"]):
                shapes.append([plain(F1), str(kk), s, x, y, th])
    write_csv('paper_two_loads.csv', ['F1_N', 'tip_x_m', 'tip_y_m', 'mid_x_m', 'mid_y_m'], rows)
    write_csv('paper_two_loads_shapes.csv', ['F1_N', 'k', 's_m', 'x_m', 'y_m', 'theta_rad'], shapes)
    say('  case 3 done, %.1f s' % (time.time() - t_start))

    # ---------------- case 4: uniformly distributed dead load (0, -w0) ----------------
    rows, shapes = [], []
    betas = [mp.mpf('0.5'), mp.mpf(1), mp.mpf(2), mp.mpf(5), mp.mpf(10)]
    # small-load limit: tip_y -> -w0 L^4/(8 EI)
    for beta in (mp.mpf('1e-4'), mp.mpf('1e-3')):
        w0 = beta * EI / L ** 3
        segs = segs_distributed(w0)
        k = shoot(segs, -w0 * L ** 2 / (2 * EI), CFG_A)
        r = integrate(k, segs, CFG_A, var=False)
        lin = -w0 * L ** 4 / (8 * EI)
        say('  case4 small-load limit beta = %s: tip_y = %s, linear -w0 L^4/(8EI) = %s, rel. diff = %.3e'
            % (mp.nstr(beta, 3), mp.nstr(r['y'], 15), mp.nstr(lin, 15), float((r['y'] - lin) / lin)))
    kg = None
    prevb = []
    for beta in betas:
        w0 = beta * EI / L ** 3
        segs = segs_distributed(w0)
        kg = -w0 * L ** 2 / (2 * EI) if not prevb else prevb[-1][1] * beta / prevb[-1][0]
        k = shoot(segs, kg, CFG_A)
        prevb.append((beta, k))
        isshape = beta in (mp.mpf(1), mp.mpf(10))
        r = integrate(k, segs, CFG_A, var=False, nodes=isshape)
        kB = shoot(segs, k, CFG_B)
        rB = integrate(kB, segs, CFG_B, var=False, nodes=isshape)
        for a_, b_ in ((r['x'], rB['x']), (r['y'], rB['y']), (r['theta'], rB['theta'])):
            note('case4 A vs B (tip x,y,angle)', a_ - b_)
        # moment at the clamp: M(0) = int_0^L x(s) (-w0) ds = -w0 W(L)
        note('case4 moment balance |EI k0 + w0 int x ds| [N m]', EI * k + w0 * r['W'])
        rows.append([plain(beta), plain(w0), r['x'], r['y'], r['theta']])
        if isshape:
            scan_list.append(('case4 beta=%s' % plain(beta), segs, k))
            moment_check('case4 shapes |EI theta\' - M(s)| [N m]', r['nodes'],
                         lambda nd: -w0 * ((r['W'] - nd[5]) - nd[1] * (L - nd[0])))
            compare_nodes('case4 shapes A vs B', r['nodes'], rB['nodes'])
            if not quick:
                nC, dthC = odefun_check(k, segs)
                compare_nodes('case4 shapes A vs mpmath.odefun', r['nodes'], nC)
                note("case4 mpmath.odefun residual theta'(L) [1/m]", dthC)
            for kk, (s, x, y, th) in enumerate(nd_[:4] for nd_ in r["nodes"]):
                shapes.append([plain(beta), str(kk), s, x, y, th])
    write_csv('distributed.csv', ['beta', 'w0_N_per_m', 'tip_x_m', 'tip_y_m', 'tip_angle_rad'], rows)
    write_csv('distributed_shapes.csv', ['beta', 'k', 's_m', 'x_m', 'y_m', 'theta_rad'], shapes)
    say('  case 4 done, %.1f s' % (time.time() - t_start))

    say('\nUniqueness scan (sign changes of theta\'(L) for kappa0 in [-30, 30] 1/m, 240 intervals):')
    for name, segs, kref in scan_list:
        roots = root_scan(segs)
        say('  %-28s roots kappa0 = %s   (tabulated branch: %s)' % (
            name, [mp.nstr(x_, 12) for x_ in roots], mp.nstr(kref, 12)))
    cf, lmin, afold = dead_tip_fold()
    say('  case 1, other (looped) equilibria exist only for alpha >= min_c l2(c)^2 = %s'
        ' (c* = sin(theta_tip) = %s): none in the tabulated range alpha <= 10'
        % (mp.nstr(afold, 10), mp.nstr(cf, 8)))
    convergence_table(say)

    say('\nAccuracy evidence (max |difference|, metres / radians unless noted):')
    worst = mp.mpf(0)
    for name in sorted(MAXDIFF):
        say('  %-62s %.2e' % (name, float(MAXDIFF[name])))
        worst = max(worst, MAXDIFF[name])
    say('  worst of all checks: %.2e' % float(worst))
    assert worst < mp.mpf('1e-12'), 'accuracy check failed'
    say('total runtime %.1f s' % (time.time() - t_start))
    with open(os.path.join(HERE, 'elastica_run.log'), 'w') as f:
        f.write('\n'.join(log) + '\n')


if __name__ == '__main__':
    main()
