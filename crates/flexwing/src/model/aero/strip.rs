//! One strip: section kinematics, upwash and loads per unit span (docs/aeroelastic-model.md
//! §2–3), generic over the scalar so that their exact derivatives come from dual numbers.
//!
//! Frames: `e = (cos θ, sin θ, 0)`, `n = (−sin θ, cos θ, 0)`, chord direction toward the leading
//! edge `t = cos ψ ẑ + sin ψ n`, section normal `ν = cos ψ n − sin ψ ẑ`.

use num_dual::DualNum;

/// Aerodynamic data of one strip (the element's midpoint, over its width).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StripData {
    /// Half-chord `b` (m).
    pub(crate) b: f64,
    /// Theodorsen's `a = 2 x_ea − 1`.
    pub(crate) a: f64,
    /// Lift slope `c_lα` (1/rad).
    pub(crate) lift_slope: f64,
    /// Zero-lift angle `α0` (rad).
    pub(crate) alpha0: f64,
    /// Moment coefficient about the aerodynamic centre `c_m0`.
    pub(crate) cm0: f64,
    /// Drag coefficient `c_d0`.
    pub(crate) cd0: f64,
    /// Strip width `ℓ` (m).
    pub(crate) width: f64,
    /// Span station of the strip's midpoint (m).
    pub(crate) station: f64,
}

impl StripData {
    /// Aerodynamic centre, `ζ_ac = b(½ + a)` toward the leading edge (m).
    pub(crate) fn zeta_ac(&self) -> f64 {
        self.b * (0.5 + self.a)
    }
    /// Three-quarter chord, `ζ_34 = −b(½ − a)` (m).
    pub(crate) fn zeta_34(&self) -> f64 {
        -self.b * (0.5 - self.a)
    }
}

/// The air at a strip at one instant: free stream plus gust `V∞ + V_g` (wing frame, m/s), its
/// speed `V = |V∞ + V_g|` and dynamic pressure `q = ½ρV²`; the gust's rate `∂V_g/∂t` (m/s², its
/// apparent mass: uniform penetration) and the gust velocity through Küssner's function (m/s,
/// Küssner's penetration, whose gust is then not in `wind`), docs/aeroelastic-model.md §3a.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Air {
    pub(crate) wind: [f64; 3],
    pub(crate) speed: f64,
    pub(crate) pressure: f64,
    pub(crate) gust_rate: [f64; 3],
    pub(crate) gust_lagged: [f64; 3],
}

/// The motion of a strip's section: the trigonometry of its element, the velocity of its
/// elastic-axis point `ċ` (in plane) and its absolute rates.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Motion<D> {
    pub(crate) cos_theta: D,
    pub(crate) sin_theta: D,
    pub(crate) cos_psi: D,
    pub(crate) sin_psi: D,
    pub(crate) cdot: [D; 2],
    pub(crate) psi_dot: D,
}

/// Upwash at the three-quarter chord `w` and chordwise relative speed `W_T`. `steady` drops the
/// section's own velocity (the steady model: geometry only).
pub(crate) fn flow<D: DualNum<Primitive = f64> + Copy>(
    s: &StripData,
    m: &Motion<D>,
    air: &Air,
    steady: bool,
) -> (D, D) {
    let (c, si, cp, sp) = (m.cos_theta, m.sin_theta, m.cos_psi, m.sin_psi);
    let [wx, wy, wz] = air.wind;
    // wind·t and wind·ν with t = (−sψ sθ, sψ cθ, cψ), ν = (−cψ sθ, cψ cθ, −sψ).
    let wind_n = c * wy - si * wx; // wind·n
    let wind_t = sp * wind_n + cp * wz;
    let wind_nu = cp * wind_n - sp * wz;
    if steady {
        return (wind_nu, -wind_t);
    }
    let cdot_n = c * m.cdot[1] - si * m.cdot[0];
    let w = wind_nu - cp * cdot_n + m.psi_dot * (s.b * (0.5 - s.a));
    let wt = -wind_t + sp * cdot_n;
    (w, wt)
}

/// Loads per unit span on the strip: the force (global components, the `ẑ` one reacted by the
/// clamp) and the nose-up moment about the elastic axis, for the upwash `w`, chordwise speed
/// `wt`, lagged upwash `w_eff`, and, if `unsteady`, the non-circulatory velocity term
/// `πρb²Vψ̇ ν` at the three-quarter chord.
pub(crate) fn loads<D: DualNum<Primitive = f64> + Copy>(
    s: &StripData,
    m: &Motion<D>,
    air: &Air,
    density: f64,
    flow: (D, D, D),
    unsteady: bool,
) -> ([D; 3], D) {
    let (c, si, cp, sp) = (m.cos_theta, m.sin_theta, m.cos_psi, m.sin_psi);
    let t = [-(sp * si), sp * c, cp];
    let nu = [-(cp * si), cp * c, -sp];
    section_loads(s, (t, nu, m.psi_dot), air, density, flow, unsteady)
}

/// [`loads`] for a section given by its chord direction toward the leading edge `t`, its
/// normal `ν` (global components, orthonormal, both ⟂ the span) and its nose-up pitch rate
/// `ψ̇`: the planar chain's and the 3-D chain's strips (`spatial.rs`) share it.
pub(crate) fn section_loads<D: DualNum<Primitive = f64> + Copy>(
    s: &StripData,
    (t, nu, psi_dot): ([D; 3], [D; 3], D),
    air: &Air,
    density: f64,
    (w, wt, w_eff): (D, D, D),
    unsteady: bool,
) -> ([D; 3], D) {
    let zero = D::from(0.0);
    let mut force = [zero; 3];
    let mut moment = zero;
    let chord = 2.0 * s.b;
    if air.pressure > 0.0 {
        let speed2 = wt * wt + w * w;
        // Lift ⟂ relative wind, drag along it; at a vanishing relative speed (the section moving
        // with the air) their directions fall back to those at rest.
        let (lift_dir, drag_dir) = if speed2.re() > 1e-24 * air.speed * air.speed {
            let r = speed2.sqrt().recip();
            let l: [D; 3] = std::array::from_fn(|k| (wt * nu[k] + w * t[k]) * r);
            let d: [D; 3] = std::array::from_fn(|k| (w * nu[k] - wt * t[k]) * r);
            (l, d)
        } else {
            (nu, [-t[0], -t[1], -t[2]])
        };
        // Küssner's gust: its lagged upwash adds to the circulation's.
        let g = &air.gust_lagged;
        let w_eff = w_eff + (nu[0] * g[0] + nu[1] * g[1] + nu[2] * g[2]);
        let alpha = w_eff.atan2(wt);
        let cl = (alpha - s.alpha0) * s.lift_slope;
        let qc = air.pressure * chord;
        for k in 0..3 {
            force[k] = (cl * lift_dir[k] + drag_dir[k] * s.cd0) * qc;
        }
        let f_nu = force[0] * nu[0] + force[1] * nu[1] + force[2] * nu[2];
        moment = f_nu * s.zeta_ac() + D::from(qc * chord * s.cm0);
    }
    if unsteady && air.speed > 0.0 {
        // Non-circulatory velocity term: πρb²Vψ̇ along ν at ζ_34 (moment ζ_34 · πρb²Vψ̇).
        let fv = psi_dot * (std::f64::consts::PI * density * s.b * s.b * air.speed);
        for k in 0..3 {
            force[k] += fv * nu[k];
        }
        moment += fv * s.zeta_34();
    }
    if unsteady && air.gust_rate != [0.0; 3] {
        // The gust's apparent mass: πρb² (∂V_g/∂t·ν) along ν at mid-chord (ζ_m = a b), the
        // section's own ḧ term for a section moving with −V_g.
        let g = &air.gust_rate;
        let fa = (nu[0] * g[0] + nu[1] * g[1] + nu[2] * g[2])
            * (std::f64::consts::PI * density * s.b * s.b);
        for k in 0..3 {
            force[k] += fa * nu[k];
        }
        moment += fa * (s.a * s.b);
    }
    (force, moment)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sign conventions of docs/aeroelastic-model.md §1–3 on one element, computed by hand.
    ///
    /// Section: c = 1 m (b = 0.5), elastic axis at 40 % chord (a = −0.2), c_lα = 2π, α0 = 0,
    /// c_m0 = −0.02, c_d0 = 0.01; air ρ = 1.2, U = 10 m/s along −z (q = 60 Pa). Element bent up
    /// θ = 0.2 rad, twisted nose-up ψ = 0.05 rad, plunging down along −n at 1 m/s, pitching nose-up
    /// at 2 rad/s.
    #[test]
    fn one_element_by_hand() {
        let s = StripData {
            b: 0.5,
            a: -0.2,
            lift_slope: 2.0 * std::f64::consts::PI,
            alpha0: 0.0,
            cm0: -0.02,
            cd0: 0.01,
            width: 1.0,
            station: 0.5,
        };
        let (rho, u) = (1.2, 10.0);
        let air = Air {
            wind: [0.0, 0.0, -u],
            speed: u,
            pressure: 0.5 * rho * u * u,
            ..Air::default()
        };
        let (th, ps): (f64, f64) = (0.2, 0.05);
        let n = [-th.sin(), th.cos()];
        let m = Motion {
            cos_theta: th.cos(),
            sin_theta: th.sin(),
            cos_psi: ps.cos(),
            sin_psi: ps.sin(),
            cdot: [-n[0], -n[1]], // 1 m/s along −n: the section plunges down
            psi_dot: 2.0,
        };
        // By hand: the wind −U ẑ has ν-component U sin ψ (positive: air comes from below the
        // chord) and −wind·t = U cos ψ. Plunging down at 1 m/s adds cos ψ · 1 to the upwash, and
        // the nose-up pitch rate moves the ¾-chord (0.35 m aft of the elastic axis) down at
        // 0.35 · 2 = 0.7 m/s, adding 0.7. The plunge has a chord component −sin ψ · 1.
        let w = u * ps.sin() + ps.cos() * 1.0 + 0.35 * 2.0;
        let wt = u * ps.cos() - ps.sin() * 1.0;
        let (fw, fwt) = flow(&s, &m, &air, false);
        assert!((fw - w).abs() < 1e-14 && (fwt - wt).abs() < 1e-14);
        // Steady: geometry only.
        let (sw, swt) = flow(&s, &m, &air, true);
        assert!((sw - u * ps.sin()).abs() < 1e-14 && (swt - u * ps.cos()).abs() < 1e-14);
        // Loads without lag (w_eff = w): lift ⟂ relative wind, up; drag along the wind (aft).
        let alpha = w.atan2(wt);
        let (lift, drag) = (60.0 * 2.0 * std::f64::consts::PI * alpha, 60.0 * 0.01);
        // Relative wind in the section frame: −W_T along t, w along ν, so the lift direction is
        // (W_T ν + w t)/|W|, rotated by α from ν toward the leading edge.
        let (ca, sa) = (alpha.cos(), alpha.sin());
        let t = [-ps.sin() * th.sin(), ps.sin() * th.cos(), ps.cos()];
        let nu = [-ps.cos() * th.sin(), ps.cos() * th.cos(), -ps.sin()];
        let want: Vec<f64> = (0..3)
            .map(|k| lift * (ca * nu[k] + sa * t[k]) + drag * (sa * nu[k] - ca * t[k]))
            .collect();
        // Non-circulatory: πρb²Uψ̇ = π · 1.2 · 0.25 · 10 · 2 = 6π N/m along ν at the ¾-chord.
        let fv = 6.0 * std::f64::consts::PI;
        let (force, moment) = loads(&s, &m, &air, rho, (w, wt, w), true);
        for k in 0..3 {
            assert!((force[k] - want[k] - fv * nu[k]).abs() < 1e-12, "{k}");
        }
        // Moment about the elastic axis, nose-up: the normal force at the quarter chord
        // (0.15 m ahead) nose-up, c_m0 q c² = −1.2 N, the apparent-mass force 0.35 m aft nose-down.
        let normal = lift * ca + drag * sa;
        let m_want = 0.15 * normal - 0.02 * 60.0 - 0.35 * fv;
        assert!((moment - m_want).abs() < 1e-12, "{moment} vs {m_want}");
        // The qualitative signs the conventions promise.
        assert!(force[1] > 0.0, "lift is up");
        assert!(
            w > u * ps.sin(),
            "plunging down and pitching up raise the angle of attack"
        );
        // At rest with nose-up twist and no pitch rate the lift is ⟂ the free stream: no z part
        // beyond the drag.
        let rest = Motion {
            cdot: [0.0, 0.0],
            psi_dot: 0.0,
            ..m
        };
        let (w0, wt0) = flow(&s, &rest, &air, false);
        let (f0, _) = loads(&s, &rest, &air, rho, (w0, wt0, w0), true);
        assert!((f0[2] + drag).abs() < 1e-12, "{}", f0[2]);
    }
}
