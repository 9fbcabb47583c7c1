//! The typical section (the 2-DOF pitch–plunge airfoil, unit span) in its own coordinates, as an
//! independent reference: its flutter determinant with a lift-deficiency function `C(k)`, the root
//! of the determinant by Newton on `(U, ω)`, and the divergence speed in closed form
//! (Hodges & Pierce, *Introduction to Structural Dynamics and Aeroelasticity*, §5.3–5.4;
//! Bisplinghoff, Ashley & Halfman, *Aeroelasticity*, §9-6). Written from the textbook loads, not
//! from flexwing's strip model.
//!
//! Used by `crates/flexwing/tests/suite/aero_typical_section.rs` and, included by path, by the CLI's
//! check of `examples/section_flutter.toml` (`crates/flexwing-cli/tests/suite/section_example.rs`).
#![allow(dead_code)]

use nalgebra::Complex;

/// A typical section: semi-chord `b` (m), elastic axis at `a b` aft of mid-chord, air density
/// `rho`, mass `m` (kg), static moment `s_alpha = m x_α b` (mass centre aft of the elastic axis
/// positive), moment of inertia about the elastic axis `i_alpha`, plunge and pitch stiffnesses
/// `k_h` (N/m), `k_alpha` (N·m/rad).
#[derive(Debug, Clone, Copy)]
pub struct TypicalSection {
    pub b: f64,
    pub a: f64,
    pub rho: f64,
    pub m: f64,
    pub s_alpha: f64,
    pub i_alpha: f64,
    pub k_h: f64,
    pub k_alpha: f64,
}

/// R. T. Jones' two-term approximation of `C(k)`, from the indicial function
/// `φ(s) = 1 − 0.165 e^{−0.0455 s} − 0.335 e^{−0.3 s}` (Bisplinghoff, Ashley & Halfman §5-6):
/// `C(k) = 1 − 0.165 k/(k − 0.0455 i) − 0.335 k/(k − 0.3 i)`.
pub fn jones(k: f64) -> Complex<f64> {
    let term = |a: f64, beta: f64| Complex::new(a * k, 0.0) / Complex::new(k, -beta);
    Complex::new(1.0, 0.0) - term(0.165, 0.0455) - term(0.335, 0.3)
}

impl TypicalSection {
    /// The flutter determinant at speed `u` and real frequency `w` with `c = C(ωb/U)` (h down,
    /// α nose-up; Theodorsen's circulatory and non-circulatory loads).
    pub fn determinant(&self, u: f64, w: f64, c: Complex<f64>) -> Complex<f64> {
        let pi = std::f64::consts::PI;
        let (b, a, rho) = (self.b, self.a, self.rho);
        let iw = Complex::new(0.0, w);
        let w2 = w * w;
        let q = 2.0 * pi * rho * u * b * c; // 2πρUbC
        let nc = pi * rho * b * b;
        // Upwash at ¾ chord per unit h̄, ᾱ: iω h̄ + (U + b(½−a) iω) ᾱ.
        let (wh, wa) = (iw, Complex::new(u, 0.0) + iw * (b * (0.5 - a)));
        // Lift (up) and nose-up moment per unit h̄, ᾱ.
        let l_h = -nc * w2 + q * wh;
        let l_a = nc * (iw * u + b * a * w2) + q * wa;
        let m_h = -nc * b * a * w2 + q * b * (a + 0.5) * wh;
        let m_a = nc * (-iw * (u * b * (0.5 - a)) + b * b * (0.125 + a * a) * w2)
            + q * b * (a + 0.5) * wa;
        // m ḧ + S_α α̈ + k_h h = −L,   S_α ḧ + I_α α̈ + k_α α = M.
        let a11 = -w2 * self.m + self.k_h + l_h;
        let a12 = -w2 * self.s_alpha + l_a;
        let a21 = -w2 * self.s_alpha - m_h;
        let a22 = -w2 * self.i_alpha + self.k_alpha - m_a;
        a11 * a22 - a12 * a21
    }

    /// The flutter point `(U, ω)`: the root of the determinant with `C(k)` = `c(k)`, by Newton
    /// on `(U, ω)` with central-difference derivatives from the guess `(u, w)`, to 1e-13.
    pub fn flutter(&self, mut u: f64, mut w: f64, c: &dyn Fn(f64) -> Complex<f64>) -> (f64, f64) {
        let det = |u: f64, w: f64| self.determinant(u, w, c(w * self.b / u));
        for _ in 0..50 {
            let d = det(u, w);
            let (hu, hw) = (1e-6 * u, 1e-6 * w);
            let du = (det(u + hu, w) - det(u - hu, w)) / (2.0 * hu);
            let dw = (det(u, w + hw) - det(u, w - hw)) / (2.0 * hw);
            // [Re du Re dw; Im du Im dw] [δu; δw] = −[Re d; Im d]
            let j = du.re * dw.im - dw.re * du.im;
            let du_step = -(d.re * dw.im - dw.re * d.im) / j;
            let dw_step = -(du.re * d.im - d.re * du.im) / j;
            u += du_step;
            w += dw_step;
            if du_step.abs() < 1e-13 * u && dw_step.abs() < 1e-13 * w {
                break;
            }
        }
        (u, w)
    }

    /// The divergence speed (m/s) with the lift slope 2π: the pitch stiffness equals the
    /// aerodynamic moment's, `k_α = q 2b · 2π · b(½ + a)`, so `U_D = √(k_α / (π ρ b² (1 + 2a)))`.
    pub fn divergence_speed(&self) -> f64 {
        let pi = std::f64::consts::PI;
        (self.k_alpha / (pi * self.rho * self.b * self.b * (1.0 + 2.0 * self.a))).sqrt()
    }
}
