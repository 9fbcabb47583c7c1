#!/usr/bin/env python3
"""Independent Python reference for flexwing's dynamic case (b):
the Table 4 cantilever (L = 1 m, EI = 50 N m^2, m = 0.2 kg/m, bending only, n = 20 rigid
elements, tip-load stiffness calibration) from rest under a dead vertical tip force
F(t) = 10 sin(20 t) N, t = 0 ... 1 s, output every 0.005 s.

Written from docs/model.md (the specification) and docs/model-choices.md only; the Rust
sources were not read.  See README.md in this folder for the equations and the checks.

Run:  python3 reference.py            (writes case_b_tip.csv, prints all checks and timings)
      python3 reference.py --quick    (skips the SciPy timing sweep)
"""
import sys
import time
import platform

import numpy as np
import scipy
from scipy.integrate import solve_ivp

# ----------------------------------------------------------------------------- case data
L = 1.0          # m
EI = 50.0        # N m^2
MU = 0.2         # kg/m
N = 20           # rigid elements
F0 = 10.0        # N, dead force along global +y at the tip node P_n
OMEGA = 20.0     # rad/s
T_END = 1.0
DT_OUT = 0.005
T_EVAL = np.linspace(0.0, T_END, 201)   # 0, 0.005, ..., 1.0 exactly as 201 points

# --------------------------------------------------------------------------- discretisation
ell = np.full(N, L / N)                          # element lengths l_i
x_nodes = np.concatenate(([0.0], np.cumsum(ell)))  # x_0 = 0 ... x_n = L
m_el = MU * ell                                  # m_i = m l_i   (model.md "Energies")
# bending only: d0 = 0, no torsion -> g_i = c_i (element midpoint), and model.md's T has no
# rotary term for bending (J_i multiplies psi_dot only), so only point masses at midpoints.

TRI = np.tril(np.ones((N, N)))                   # theta = TRI q  (model.md "Frames")


def tip_load_springs():
    """model.md 'Stiffness calibration', tip-load matched, uniform EI.
    Unit tip force on the linear Euler-Bernoulli cantilever: w(x) = x^2 (3L - x) / (6 EI)."""
    w = x_nodes**2 * (3 * L - x_nodes) / (6 * EI)
    theta = np.diff(w) / ell                     # chord angle of each element
    qj = np.diff(np.concatenate(([0.0], theta))) # joint rotations, theta_0 = 0
    moment = L - x_nodes[:-1]                    # M_i = L - x_{i-1}
    return moment / qj


K_DIAG = tip_load_springs()

# a_ij = l_j for j < i, l_i / 2 for j = i, 0 for j > i  (lever arms of midpoint i on angle j)
A_LEVER = np.tril(np.tile(ell, (N, 1)), -1) + np.diag(ell / 2)
# A_jk = sum_{i >= max(j,k)} m_i a_ij a_ik
A_MAT = A_LEVER.T @ (m_el[:, None] * A_LEVER)


# ------------------------------------------------------------------------------ kinematics
def midpoints(q):
    th = TRI @ q
    e = np.stack([np.cos(th), np.sin(th)])        # (2, N)
    P = np.concatenate([np.zeros((2, 1)), np.cumsum(ell * e, axis=1)], axis=1)
    return P[:, :-1] + 0.5 * ell * e              # c_i = P_{i-1} + l_i/2 e(theta_i)


def tip(q):
    th = TRI @ q
    return np.array([np.sum(ell * np.cos(th)), np.sum(ell * np.sin(th))])


def midpoint_jacobians(q):
    """J_i = d c_i / d q, shape (N, 2, N), built directly from the geometry:
    d c_i / d theta_j = a_ij n(theta_j), then chain rule through theta = TRI q."""
    th = TRI @ q
    nvec = np.stack([-np.sin(th), np.cos(th)])    # (2, N)
    Jth = A_LEVER[:, None, :] * nvec[None, :, :]  # (N, 2, N): [i, xy, j]
    return Jth @ TRI


def mass_matrix_jacobian_form(q):
    """M = sum_i m_i J_i^T J_i  (model.md 'Equations of motion'), built from the Jacobians."""
    J = midpoint_jacobians(q)
    return np.einsum('i,iaj,iak->jk', m_el, J, J)


def mass_matrix(q):
    """Closed form of model.md: M_theta_jk = A_jk cos(theta_j - theta_k), M = T^T M_theta T.
    Works for complex q (used for the complex-step checks).  Batched over a trailing axis."""
    th = TRI @ q
    Mth = A_MAT * np.cos(th[:, None] - th[None, :])
    return TRI.T @ Mth @ TRI


def kinetic(q, qd):
    return 0.5 * qd @ mass_matrix(q) @ qd


def gyro(q, qd):
    """Exact gamma = dT/dq at fixed qdot, analytic (model.md closed form):
    dT/dtheta_k = -thd_k sum_j A_kj sin(theta_k - theta_j) thd_j;  gamma = T^T dT/dtheta.
    Works on batches: q, qd of shape (N,) or (N, B)."""
    th = TRI @ q
    thd = TRI @ qd
    if th.ndim == 1:
        S = A_MAT * np.sin(th[:, None] - th[None, :])
        dT = -thd * (S @ thd)
    else:
        S = A_MAT[:, :, None] * np.sin(th[:, None, :] - th[None, :, :])   # (N, N, B)
        dT = -thd * np.einsum('kjb,jb->kb', S, thd)
    return TRI.T @ dT


def gen_force(q, t):
    """Q = J_tip^T F with F = (0, F0 sin(omega t)) dead; d P_n / d theta_j = l_j n(theta_j)."""
    th = TRI @ q
    Fy = F0 * np.sin(OMEGA * t)
    Qth = ell[:, None] * np.cos(th) * Fy if th.ndim > 1 else ell * np.cos(th) * Fy
    return TRI.T @ Qth


# ---------------------------------------------------------------------- equations of motion
FORCE_ON = True


def rhs(t, y):
    """Hamiltonian form, model.md: qdot = M^-1 p, pdot = -K q + gamma(q, qdot) + Q(q, t).
    y may be (2N,) or (2N, B) (vectorized, also complex for the complex-step Jacobian)."""
    q, p = y[:N], y[N:]
    if y.ndim == 1:
        qd = np.linalg.solve(mass_matrix(q), p)
    else:
        th = TRI @ q                                             # (N, B)
        Mth = A_MAT[None] * np.cos(th.T[:, :, None] - th.T[:, None, :])   # (B, N, N)
        Mb = TRI.T[None] @ Mth @ TRI[None]
        qd = np.linalg.solve(Mb, p.T[:, :, None])[:, :, 0].T
    pd = -K_DIAG.reshape((N,) + (1,) * (y.ndim - 1)) * q + gyro(q, qd)
    if FORCE_ON:
        pd = pd + gen_force(q, t)
    return np.concatenate([qd, pd])


def rhs_vec(t, y):
    return rhs(t, y)


def jac_complex_step(t, y):
    """Exact Jacobian df/dy by the complex step (h = 1e-30, no subtractive cancellation,
    exact to rounding since rhs is real-analytic in y), all 2N columns in one batched call."""
    h = 1e-30
    Y = y[:, None] + 1j * h * np.eye(2 * N)
    return rhs(t, Y).imag / h


def hamiltonian(y):
    q, p = y[:N], y[N:]
    return 0.5 * p @ np.linalg.solve(mass_matrix(q), p) + 0.5 * q @ (K_DIAG * q)


def simulate(method, rtol, atol, jac=None, vectorized=False, t_eval=T_EVAL, y0=None,
             t_end=T_END):
    if y0 is None:
        y0 = np.zeros(2 * N)
    kw = {}
    if jac is not None:
        kw['jac'] = jac
    t0 = time.perf_counter()
    sol = solve_ivp(rhs_vec if vectorized else rhs, (0.0, t_end), y0, method=method,
                    t_eval=t_eval, rtol=rtol, atol=atol, vectorized=vectorized, **kw)
    wall = time.perf_counter() - t0
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol, wall


def tips_of(sol):
    return np.array([tip(sol.y[:N, k]) for k in range(sol.y.shape[1])])


# ------------------------------------------------------------------------------- self-checks
def self_checks(log):
    rng = np.random.default_rng(1)
    log("== self-checks of the model ==")
    # 1. calibration: linear tip-load deflections are exact nodal values
    log(f"K_theta: root {K_DIAG[0]:.12g} (2EI/l = {2*EI/ell[0]:.12g}), "
        f"joint 2 {K_DIAG[1]:.12g}, joint n {K_DIAG[-1]:.12g} (EI/l = {EI/ell[0]:.12g})")
    Flin = 1e-3
    qlin = Flin * (TRI.T @ ell) / K_DIAG          # small-load linear statics: K q = J_tip(0)^T F
    th = TRI @ qlin
    w_nodes = np.concatenate(([0.0], np.cumsum(ell * th)))
    w_exact = Flin * x_nodes**2 * (3 * L - x_nodes) / (6 * EI)
    log(f"calibration: max |linear nodal deflection - EB closed form| / tip = "
        f"{np.max(np.abs(w_nodes - w_exact)) / w_exact[-1]:.2e}")
    # 2. mass matrix: closed form vs sum m_i J_i^T J_i
    worst = 0.0
    for _ in range(5):
        q = rng.normal(scale=0.3, size=N)
        M1 = mass_matrix(q)
        M2 = mass_matrix_jacobian_form(q)
        worst = max(worst, np.max(np.abs(M1 - M2)) / np.max(np.abs(M1)))
    log(f"mass matrix: closed form vs sum m_i J_i^T J_i, max rel diff {worst:.2e}")
    # 3. Jacobians vs central finite differences of the midpoint positions
    q = rng.normal(scale=0.3, size=N)
    J = midpoint_jacobians(q)
    h = 1e-6
    Jfd = np.zeros_like(J)
    for k in range(N):
        dq = np.zeros(N); dq[k] = h
        Jfd[:, :, k] = ((midpoints(q + dq) - midpoints(q - dq)) / (2 * h)).T
    log(f"midpoint Jacobian vs central FD (h=1e-6): max abs diff {np.max(np.abs(J - Jfd)):.2e}")
    # 4. kinetic energy from positions: FD of c_i along a trajectory q + s qd
    qd = rng.normal(size=N)
    hh = 1e-5
    v = (midpoints(q + hh * qd) - midpoints(q - hh * qd)) / (2 * hh)
    T_pos = 0.5 * np.sum(m_el * np.sum(v**2, axis=0))
    log(f"T = 1/2 qd^T M qd vs 1/2 sum m_i |c_i'|^2 (FD velocities): rel diff "
        f"{abs(kinetic(q, qd) - T_pos) / T_pos:.2e}")
    # 5. gyroscopic term: analytic vs complex step of T(q, qd) at fixed qd
    hc = 1e-30
    g_cs = np.array([kinetic(q + 1j * hc * np.eye(N)[k], qd).imag / hc for k in range(N)])
    g_an = gyro(q, qd)
    log(f"gamma analytic vs complex step dT/dq: max rel diff "
        f"{np.max(np.abs(g_an - g_cs)) / np.max(np.abs(g_cs)):.2e}")
    # 6. gamma = -1/2 d(p^T M^-1 p)/dq at fixed p (the Hamiltonian identity in model.md)
    p = mass_matrix(q) @ qd
    g_h = np.array([-0.5 * (p @ np.linalg.solve(mass_matrix(q + 1j * hc * np.eye(N)[k]), p)).imag
                    / hc for k in range(N)])
    log(f"gamma vs -1/2 d(p^T M^-1 p)/dq|_p (complex step): max rel diff "
        f"{np.max(np.abs(g_an - g_h)) / np.max(np.abs(g_h)):.2e}")
    # 7. generalized force: Q vs complex step of the virtual work F . P_n(q)
    t = 0.0731
    Fy = F0 * np.sin(OMEGA * t)
    Q_cs = np.array([Fy * tip(q + 1j * hc * np.eye(N)[k])[1].imag / hc for k in range(N)])
    log(f"Q = J_tip^T F vs complex step of F . P_n: max rel diff "
        f"{np.max(np.abs(gen_force(q, t) - Q_cs)) / np.max(np.abs(Q_cs)):.2e}")
    # 8. vectorized rhs == scalar rhs; complex-step Jacobian vs central FD Jacobian
    y = np.concatenate([q, p])
    Y = np.stack([y, 2 * y], axis=1)
    dv = max(np.max(np.abs(rhs(t, Y)[:, 0] - rhs(t, y))) / np.max(np.abs(rhs(t, y))),
             np.max(np.abs(rhs(t, Y)[:, 1] - rhs(t, 2 * y))) / np.max(np.abs(rhs(t, 2 * y))))
    Jc = jac_complex_step(t, y)
    Jf = np.zeros_like(Jc)
    for k in range(2 * N):
        e = np.zeros(2 * N); e[k] = 1e-6
        Jf[:, k] = (rhs(t, y + e) - rhs(t, y - e)) / 2e-6
    log(f"vectorized rhs vs scalar rhs: max rel {dv:.2e}; complex-step Jacobian vs central FD: "
        f"max rel {np.max(np.abs(Jc - Jf)) / np.max(np.abs(Jc)):.2e}")
    # 9. small-amplitude frequencies (for information)
    M0 = mass_matrix(np.zeros(N))
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M0, np.diag(K_DIAG))).real)
    fr = np.sqrt(w2[:4])
    beta = np.array([1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349])
    fr_eb = beta**2 * np.sqrt(EI / (MU * L**4))
    log("linear frequencies (rad/s), n=20: " + ", ".join(f"{v:.4f}" for v in fr)
        + "  | continuous EB: " + ", ".join(f"{v:.4f}" for v in fr_eb))


def energy_check(log):
    global FORCE_ON
    log("== energy check: force off, initial velocity, C = 0 ==")
    FORCE_ON = False
    try:
        q0 = np.zeros(N)
        # smooth initial velocity: first linear mode, scaled to a 15 m/s tip velocity
        # (a velocity kink at one joint would excite the 6e5 rad/s top mode and make the
        # tight implicit run needlessly slow)
        M0 = mass_matrix(q0)
        w2, V = np.linalg.eig(np.linalg.solve(M0, np.diag(K_DIAG)))
        phi = V[:, np.argmin(w2.real)].real
        qd0 = phi * 15.0 / (np.sum(ell * (TRI @ phi)))
        y0 = np.concatenate([q0, mass_matrix(q0) @ qd0])
        H0 = hamiltonian(y0)
        res = {}
        for method, rtol, atol in (('Radau', 1e-10, 1e-12), ('Radau', 1e-8, 1e-10),
                                   ('DOP853', 1e-8, 1e-10)):
            sol, wall = simulate(method, rtol, atol, y0=y0,
                                 jac=jac_complex_step if method == 'Radau' else None)
            H = np.array([hamiltonian(sol.y[:, k]) for k in range(sol.y.shape[1])])
            drift = np.max(np.abs(H - H0)) / H0
            amp = np.max(np.abs(tips_of(sol)[:, 1]))
            res[method] = drift
            log(f"{method:7s} rtol {rtol:.0e} atol {atol:.0e}: H0 = {H0:.12g} J, max |H - H0| / H0 = "
                f"{drift:.2e} over 1 s (max |tip y| = {amp:.3f} m, {sol.t.size} outputs, "
                f"{wall:.2f} s)")
        return res
    finally:
        FORCE_ON = True


def main():
    quick = '--quick' in sys.argv
    lines = []

    def log(s=''):
        print(s, flush=True)
        lines.append(s)

    cpu = 'unknown'
    try:
        with open('/proc/cpuinfo') as f:
            for ln in f:
                if ln.startswith('model name'):
                    cpu = ln.split(':', 1)[1].strip()
                    break
    except OSError:
        pass
    import os
    log(f"python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}")
    log(f"machine: nproc = {os.cpu_count()}, CPU: {cpu}")
    self_checks(log)
    energy_check(log)

    log("== case (b): tight runs ==")
    sR, wR = simulate('Radau', 1e-10, 1e-12, jac=jac_complex_step)
    sD, wD = simulate('DOP853', 1e-10, 1e-12)
    tR, tD = tips_of(sR), tips_of(sD)
    diff = np.max(np.hypot(*(tR - tD).T))
    log(f"Radau  (complex-step Jacobian) rtol 1e-10 atol 1e-12: nfev {sR.nfev}, njev {sR.njev}, "
        f"{wR:.2f} s")
    log(f"DOP853                          rtol 1e-10 atol 1e-12: nfev {sD.nfev}, {wD:.2f} s")
    log(f"max tip distance Radau vs DOP853 over the 201 outputs: {diff:.3e} m")
    ref = tR      # the implicit tight run is written; DOP853 at the same tolerance is its check
    log(f"tip at t = 1 s: x = {ref[-1, 0]:.12f} m, y = {ref[-1, 1]:.12f} m; "
        f"max |tip y| = {np.max(np.abs(ref[:, 1])):.6f} m, min tip x = {np.min(ref[:, 0]):.6f} m")
    for name, tips in (('case_b_tip.csv', tR), ('case_b_tip_dop853.csv', tD)):
        with open(name, 'w') as f:
            f.write('t_s,tip_x_m,tip_y_m\n')
            for t, (x, y) in zip(T_EVAL, tips):
                f.write(f"{t:.17g},{x:.17g},{y:.17g}\n")
    log("wrote case_b_tip.csv (Radau rtol 1e-10 atol 1e-12) and case_b_tip_dop853.csv "
        "(DOP853, same tolerances), 201 rows each")

    if not quick:
        log("== SciPy Radau timings vs the reference (tip error = max distance over 201 outputs) ==")
        log("| Jacobian | rtol | atol | max tip error (m) | wall (s) | nfev | njev | nlu |")
        log("|---|---|---|---|---|---|---|---|")
        for jac_name, jac, vec in (('FD (default)', None, False),
                                   ('FD, vectorized rhs', None, True),
                                   ('complex-step (exact)', jac_complex_step, False)):
            for rtol in (1e-3, 1e-4, 1e-5, 1e-6):
                atol = rtol * 1e-2
                walls = []
                for _ in range(2 if rtol < 1e-5 else 3):
                    s, w = simulate('Radau', rtol, atol, jac=jac, vectorized=vec)
                    walls.append(w)
                err = np.max(np.hypot(*(tips_of(s) - ref).T))
                log(f"| {jac_name} | {rtol:.0e} | {atol:.0e} | {err:.2e} | {min(walls):.3f} | "
                    f"{s.nfev} | {s.njev} | {s.nlu} |")
        log("(wall = best of 3 runs (2 at rtol 1e-6), includes t_eval dense output)")

    with open('reference_run.log' if not quick else 'reference_run_quick.log', 'w') as f:
        f.write('\n'.join(lines) + '\n')


if __name__ == '__main__':
    main()
