//! The inextensible elastica of a cantilever, computed in the tests (independent of the code
//! under test): clamp at the origin, tangent along `+x`, arc length `s ∈ [0, L]`, tangent angle
//! `θ(s)`, `x' = cos θ`, `y' = sin θ`, `EI θ'(s) = M(s)` and so
//! `EI θ'' = −t × N = −(cos θ N_y − sin θ N_x)` with `N(s)` the resultant of the loads on `(s, L]`
//! (the equations of `tests/data/elastica/README.md`). Integrated with classical fourth-order
//! Runge–Kutta on a fine fixed grid; each function states its shooting problem.

/// `(θ, θ', x, y)` at one arc length.
pub type State = [f64; 4];

/// Integrate `θ'' = f(θ)` with `x' = cos θ`, `y' = sin θ` from `state` over an arc `length`
/// (negative to integrate backwards) in `steps` RK4 steps.
pub fn integrate(mut state: State, length: f64, steps: usize, f: impl Fn(f64) -> f64) -> State {
    let h = length / steps as f64;
    let rate = |u: &State| [u[1], f(u[0]), u[0].cos(), u[0].sin()];
    let add = |u: &State, k: &[f64; 4], c: f64| -> State {
        [
            u[0] + c * k[0],
            u[1] + c * k[1],
            u[2] + c * k[2],
            u[3] + c * k[3],
        ]
    };
    for _ in 0..steps {
        let k1 = rate(&state);
        let k2 = rate(&add(&state, &k1, 0.5 * h));
        let k3 = rate(&add(&state, &k2, 0.5 * h));
        let k4 = rate(&add(&state, &k3, h));
        for i in 0..4 {
            state[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    state
}

/// Steps per unit of `√α · s`: RK4's global error is then ~ (1/800)⁴ ≈ 2e-12 of the solution
/// (the solution varies on the scale `1/√α`). Checked against the checked-in elliptic-integral
/// reference in `statics_path.rs` (1e-10 agreement at α = 1, 3, 10).
fn steps_for(alpha: f64) -> usize {
    (800.0 * alpha.sqrt().max(1.0)).ceil() as usize
}

/// Tip `(x, y, θ)` of the cantilever of length 1 under a dead tip force `(0, P)`, `α = P L²/EI > 0`,
/// on the primary branch (the one connected to the unloaded beam: `θ` rises monotonically from 0
/// to `θ_L < π/2`).
///
/// `θ'' = −α cos θ`, `θ(0) = 0`, `θ'(1) = 0`. The first integral `θ'² = 2α(c − sin θ)` with
/// `c = sin θ_L` gives `θ'(0) = √(2αc)`; on the primary branch `θ'` stays positive until the arc
/// reaches `θ_L`, and the arc length of that rise grows monotonically with `c` from 0 (c → 0) to
/// infinity (c → 1, the separatrix). So bisection on `c` with the test "does `θ'` change sign
/// before `s = 1`?" converges to the primary branch and to no other (the looped equilibria, which
/// exist for α ≥ 10.33, turn back at `θ = asin c` before `s = 1`).
pub fn dead_tip_primary(alpha: f64) -> [f64; 3] {
    assert!(alpha > 0.0);
    let steps = steps_for(alpha);
    let h = 1.0 / steps as f64;
    let f = move |th: f64| -alpha * th.cos();
    // Integrate step by step so that the first sign change of θ' is seen.
    let rises_past_the_tip = |c: f64| -> bool {
        let mut u: State = [0.0, (2.0 * alpha * c).sqrt(), 0.0, 0.0];
        for _ in 0..steps {
            u = integrate(u, h, 1, f);
            if u[1] < 0.0 {
                return false;
            }
        }
        true
    };
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if rises_past_the_tip(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let c = 0.5 * (lo + hi);
    let u = integrate([0.0, (2.0 * alpha * c).sqrt(), 0.0, 0.0], 1.0, steps, f);
    // θ'(1) = 0 at the root: the residual measures the shooting accuracy.
    assert!(u[1].abs() < 1e-7 * alpha, "θ'(1) = {}", u[1]);
    [u[2], u[3], u[0]]
}

/// Cantilever of length 1 under a dead compressive tip force `(−P, 0)`, `k² = P/EI`, and a tip
/// moment: the solution with root curvature `θ'(0) = kappa0`, `θ'' = −k² sin θ` (a pendulum),
/// integrated from the clamp. Returns `(EI θ'(1) / EI = M/EI, x_tip, y_tip, θ_tip)`: every `kappa0`
/// gives one equilibrium, for the tip moment `M = EI θ'(1)`, and the curve `kappa0 ↦ (M, tip)` is
/// the whole connected equilibrium path of the moment-loaded buckled beam.
pub fn compressed_with_tip_moment(k2: f64, kappa0: f64) -> [f64; 4] {
    let steps = steps_for(k2.max(kappa0 * kappa0));
    let u = integrate([0.0, kappa0, 0.0, 0.0], 1.0, steps, move |th| {
        -k2 * th.sin()
    });
    [u[1], u[2], u[3], u[0]]
}

/// Two normal follower forces on a cantilever of length 1 and stiffness `ei`: `f_tip` at the tip
/// and `f_mid` at `s = 1/2`, each along the normal `n(θ) = (−sin θ, cos θ)` of the beam's tangent
/// at its point. Shoots from the tip inwards on the unknown tip angle `θ_L` (`θ'(1) = 0`; the
/// resultant `N` is known once `θ_L` and, past mid-span, `θ(1/2)` are), to `θ(0) = 0`, by the
/// secant method from `guess`. Returns the tip `(x, y, θ_L)`.
pub fn two_followers(ei: f64, f_tip: f64, f_mid: f64, guess: f64) -> [f64; 3] {
    let normal = |phi: f64| [-phi.sin(), phi.cos()];
    let steps = 4000;
    // Integrate from the tip (x = y = 0 there) back to the clamp; returns the clamp state.
    let shoot = |theta_l: f64| -> State {
        let n1 = normal(theta_l);
        let outer = [f_tip * n1[0], f_tip * n1[1]];
        let rhs = |n: [f64; 2]| move |th: f64| -(th.cos() * n[1] - th.sin() * n[0]) / ei;
        let u = integrate([theta_l, 0.0, 0.0, 0.0], -0.5, steps / 2, rhs(outer));
        let n2 = normal(u[0]);
        let inner = [outer[0] + f_mid * n2[0], outer[1] + f_mid * n2[1]];
        integrate(u, -0.5, steps / 2, rhs(inner))
    };
    let (mut a, mut b) = (guess, guess + 1e-3);
    let (mut fa, mut fb) = (shoot(a)[0], shoot(b)[0]);
    for _ in 0..100 {
        if fb.abs() < 1e-14 || fa == fb {
            break;
        }
        let c = b - fb * (b - a) / (fb - fa);
        (a, fa) = (b, fb);
        b = c;
        fb = shoot(b)[0];
    }
    assert!(fb.abs() < 1e-11, "shooting did not converge: θ(0) = {fb}");
    let clamp = shoot(b);
    // Positions relative to the clamp: the tip is at −(clamp position relative to the tip).
    [-clamp[2], -clamp[3], b]
}
