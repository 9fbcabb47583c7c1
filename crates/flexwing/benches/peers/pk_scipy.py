#!/usr/bin/env python3
"""A NumPy/SciPy p-k flutter solver for Patil's wing: the peer of flexwing's p-k check (issue 11).

The problem: Patil, Hodges & Cesnik's HALE wing (J. Aircraft 38(1), 2001; semi-span 16 m, chord
1 m, elastic axis and mass centre at mid-chord, m = 0.75 kg/m, I = 0.1 kg m, GJ = 1e4, EI = 2e4
N m^2, rho = 0.0889 kg/m^3, c_la = 2 pi), linear about the undeformed state, strip theory with
Theodorsen's C(k) (scipy.special.hankel2), discretized as flexwing's chain of n rigid elements
(tip-load calibrated bending springs, one strip per element). The matrices are built by the
independent chain reference of crates/flexwing/tests/data/aero_reference/ (chain_reference.chain,
aero_common.StripSystem: written from docs/model.md and Theodorsen, not from flexwing's Rust code),
so this script solves exactly the discretized problem of `flexwing flutter` at the same n.

The solver (written here, what a user would write): the 2N x 2N first-order p-k matrix of
    det[p^2 M + p (U Ct - c G E2) + Ks - U c G E1] = 0,   c = c_la rho U b C(k),  k = Im(p) b / U,
full complex eigenvalues (scipy.linalg.eigvals) at every fixed-point iteration, the branch followed
by the nearest eigenvalue; the `modes` lowest wet modes at U = 0 continued through a sweep of speeds
(as examples/patil_flutter.toml: 2 to 40 m/s every 2 m/s, 4 branches), then Brent (scipy.optimize.
brentq) on Re p(U) of the first branch to cross, to `--tol` relative in U. Timed from the matrices
(time.process_time and time.perf_counter, median of `--repeats` runs; the matrix build is timed
apart). The flutter point is checked against chain_patil_points.csv (k-method with Theodorsen, the
same discretization) and chain_patil_mp.csv (30 digits).

Run (from the repository root; README.md):
    /tmp/peers-venv/bin/python crates/flexwing/benches/peers/pk_scipy.py [--n 32] [--repeats 7]
"""
import argparse
import csv
import math
import os
import statistics
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # 128 x 128 matrices: threads only add overhead
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import scipy  # noqa: E402
from scipy import linalg, optimize, special  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.normpath(os.path.join(HERE, "..", "..", "tests", "data", "aero_reference"))
sys.path.insert(0, REF)
from beam_reference import CASES, section  # noqa: E402
from chain_reference import chain  # noqa: E402


def theodorsen(k):
    h1 = special.hankel2(1, k)
    h0 = special.hankel2(0, k)
    return h1 / (h1 + 1j * h0)


class PK:
    """p-k on M eta'' + U Ct eta' + Ks eta = c_la rho U b G C(k) [U E1 eta + E2 eta']."""

    def __init__(self, s, tol=1e-8, maxit=100):
        self.N = N = s.N
        self.b = s.b
        self.q = s.cla * s.rho * s.b
        Minv = np.linalg.inv(s.M)
        self.MK = Minv @ s.Ks
        self.MC = Minv @ s.Ct
        self.MGE1 = Minv @ (s.G @ s.E1)
        self.MGE2 = Minv @ (s.G @ s.E2)
        self.A = np.zeros((2 * N, 2 * N), complex)
        self.tol, self.maxit = tol, maxit
        self.eigs = 0  # eigen-solves, for the record
        # wet modes at U = 0 (apparent mass included)
        w2 = linalg.eigh(s.Ks, s.M, eigvals_only=True)
        self.omega0 = np.sqrt(w2)

    def root(self, U, p0):
        """The p-k root of the branch nearest p0 (Im p0 > 0) at speed U."""
        N, A = self.N, self.A
        p = p0
        for _ in range(self.maxit):
            c = self.q * U * theodorsen(max(abs(p.imag) * self.b / U, 1e-8))
            A[:N, :N] = 0.0
            A[:N, N:] = np.eye(N)
            A[N:, :N] = U * c * self.MGE1 - self.MK
            A[N:, N:] = c * self.MGE2 - U * self.MC
            ev = linalg.eigvals(A, check_finite=False, overwrite_a=True)
            self.eigs += 1
            pn = ev[np.argmin(np.abs(ev - p))]
            if abs(pn - p) <= self.tol * abs(pn):
                return pn
            p = pn
        raise RuntimeError("p-k did not converge at U = %g near p = %s" % (U, p0))


def flutter(pk, speeds, modes, tol):
    """First upward crossing of Re p = 0 along `modes` branches through `speeds`, refined by Brent."""
    ps = [1j * w for w in pk.omega0[:modes]]
    prev_U, prev_ps, older = 0.0, ps, None
    for U in speeds:
        # start each branch from the linear extrapolation of its last two points (fewer iterations)
        guesses = prev_ps if older is None else [2 * p - q for p, q in zip(prev_ps, older)]
        cur = [pk.root(U, g) for g in guesses]
        crossed = [j for j in range(modes) if prev_ps[j].real < 0.0 <= cur[j].real]
        if crossed:
            j = min(crossed, key=lambda j: prev_ps[j].real / (prev_ps[j].real - cur[j].real))
            lo, hi, p_lo, p_hi = prev_U, U, prev_ps[j], cur[j]
            last = {"p": p_lo}

            def f(u):
                guess = p_lo + (p_hi - p_lo) * (u - lo) / (hi - lo)
                last["p"] = pk.root(u, guess)
                return last["p"].real

            Uf = optimize.brentq(f, lo, hi, xtol=1e-12, rtol=tol)
            pf = pk.root(Uf, last["p"])
            return Uf, pf.imag, j
        prev_U, prev_ps, older = U, cur, prev_ps
    return None


def read_refs(n):
    out = {}
    with open(os.path.join(REF, "chain_patil_points.csv")) as fh:
        for r in csv.DictReader(fh):
            if r["quantity"] == "flutter" and r["model"] == "theodorsen" and int(r["n"]) == n:
                out["k-method"] = (float(r["U_m_s"]), float(r["omega_rad_s"]))
    with open(os.path.join(REF, "chain_patil_mp.csv")) as fh:
        for r in csv.DictReader(fh):
            if r["model"] == "theodorsen" and int(r["n"]) == n:
                out["30 digits"] = (float(r["U_m_s"]), float(r["omega_rad_s"]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=32, help="elements of the chain")
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--modes", type=int, default=4, help="branches: the lowest wet modes")
    ap.add_argument("--tol", type=float, default=1e-6, help="relative tolerance of the flutter speed")
    # 1e-8: the eigenvalues of the first bending branch (2.2 rad/s) jitter by ~5e-9 relative between
    # iterations (measured; LAPACK's accuracy on this matrix, whose eigenvalues span 2 to ~1e4 rad/s),
    # so 1e-10 never converges there; 1e-8 on p moves the flutter speed by far less than 1e-6.
    ap.add_argument("--pk-tol", type=float, default=1e-8, help="relative tolerance of the p-k fixed point")
    args = ap.parse_args()
    speeds = np.arange(2.0, 40.0 + 1e-9, 2.0)
    cs = CASES["patil"]
    b, a, d0 = section(cs)
    print("pk_scipy.py: Patil's wing, flexwing's chain n = %d (%d dofs), Theodorsen p-k, %d branches, "
          "speeds 2..40 m/s by 2, Brent to %.0e relative" % (args.n, 2 * args.n, args.modes, args.tol))
    print("python %s, numpy %s, scipy %s, OPENBLAS_NUM_THREADS=%s; %s"
          % (sys.version.split()[0], np.__version__, scipy.__version__, os.environ["OPENBLAS_NUM_THREADS"],
             "load average %.2f %.2f %.2f" % os.getloadavg()))

    cpu_b, wall_b, cpu, wall, res = [], [], [], [], None
    for _ in range(args.repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        s = chain(cs, args.n)
        pk = PK(s, tol=args.pk_tol)
        c1, w1 = time.process_time(), time.perf_counter()
        r = flutter(pk, speeds, args.modes, args.tol)
        c2, w2 = time.process_time(), time.perf_counter()
        cpu_b.append(c1 - c0)
        wall_b.append(w1 - w0)
        cpu.append(c2 - c1)
        wall.append(w2 - w1)
        if res is not None and r[:2] != res[:2]:
            raise SystemExit("repeats disagree: %r vs %r" % (r, res))
        res, eigs = r, pk.eigs
    if res is None:
        raise SystemExit("no flutter below 40 m/s")
    Uf, wf, j = res

    def ms(v):
        return "median %.1f ms (min %.1f, max %.1f)" % (1e3 * statistics.median(v), 1e3 * min(v), 1e3 * max(v))

    print("flutter (p-k, Theodorsen): U = %.10f m/s, omega = %.10f rad/s, k = %.8f, branch %d (wet mode %d at "
          "%.4f rad/s)" % (Uf, wf, wf * b / Uf, j, j + 1, pk.omega0[j]))
    print("eigen-solves of the %d x %d complex p-k matrix per run: %d" % (2 * s.N, 2 * s.N, eigs))
    print("matrices (chain + strips + M^-1 products), %d runs: CPU %s; wall %s" % (args.repeats, ms(cpu_b), ms(wall_b)))
    print("flutter solve (wet modes, sweep, Brent), %d runs:    CPU %s; wall %s" % (args.repeats, ms(cpu), ms(wall)))
    refs = read_refs(args.n)
    worst = 0.0
    for name, (U, w) in refs.items():
        eu, ew = Uf / U - 1, wf / w - 1
        worst = max(worst, abs(eu), abs(ew))
        print("check against %-9s (same chain, k-method): U = %.10f, omega = %.10f; relative difference %+.2e, %+.2e"
              % (name, U, w, eu, ew))
    if not refs:
        print("no reference at n = %d in chain_patil_points.csv" % args.n)
    elif worst > 2 * args.tol:
        raise SystemExit("FAILED: the flutter point differs from the reference by %.2e (> 2 x tol)" % worst)
    else:
        print("agreement within %.1e (bound 2 x tol = %.0e: Brent's bracket plus the p-k tolerance)" % (worst, 2 * args.tol))


if __name__ == "__main__":
    main()
