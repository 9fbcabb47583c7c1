//! Trailing-edge flap of a thin airfoil: Theodorsen's coefficients `T1 … T14` and the loads per
//! unit span of a flap deflection (docs/aeroelastic-model.md §3b).
//!
//! Source: T. Theodorsen, *General theory of aerodynamic instability and the mechanism of
//! flutter*, NACA TR 496 (1935), the functions `T1 … T14` of the hinge position and the lift,
//! moment and hinge-moment expressions; the same in R. L. Bisplinghoff, H. Ashley, R. L.
//! Halfman, *Aeroelasticity* (1955) §5-6. Steady limits checked against H. Glauert, *The
//! elements of aerofoil and airscrew theory* (1926), §7.4 (tests below).
//!
//! Coordinates are Theodorsen's: distances in half-chords `b` from mid-chord, positive aft; the
//! elastic axis at `a`, the hinge at `c` (`c = 2 x_h − 1` for the hinge at chord fraction `x_h`
//! from the leading edge). The deflection `δ` (Theodorsen's `β`) is positive **trailing edge
//! down**; the hinge moment is positive in the sense of `δ` (it does work `H δ̇`). With `h` the
//! downward plunge and `α` the nose-up pitch, Theodorsen's loads (lift up, nose-up moment about the
//! elastic axis, hinge moment) are
//!
//! ```text
//! L  = πρb²(ḧ + Uα̇ − baα̈) − ρb²(U T4 δ̇ + b T1 δ̈) + 2πρUb C(k) Q
//! M  = πρb²(ba ḧ − Ub(½−a)α̇ − b²(⅛+a²)α̈)
//!      − ρb²[(T4+T10)U²δ + (T1 − T8 − (c−a)T4 + ½T11)Ub δ̇ − (T7 + (c−a)T1)b²δ̈]
//!      + 2πρUb²(a+½) C(k) Q
//! H  = −ρb²[−T1 b ḧ + (−2T9 − T1 + T4(a−½))Ub α̇ + 2T13 b²α̈
//!           + U²(T5 − T4T10)δ/π − Ub T4T11 δ̇/(2π) − T3 b²δ̈/π] − ρUb² T12 C(k) Q
//! Q  = Uα + ḣ + b(½−a)α̇ + U T10 δ/π + b T11 δ̇/(2π)
//! ```

/// Theodorsen's flap coefficients `T1 … T14` for the hinge at `c` and the elastic axis at `a`
/// (half-chords from mid-chord, positive aft), NACA TR 496 (1935).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlapCoefficients {
    /// Hinge position `c` (half-chords aft of mid-chord), in `(−1, 1)`.
    pub c: f64,
    /// Elastic-axis position `a` (half-chords aft of mid-chord).
    pub a: f64,
    /// `T[k]` is Theodorsen's `T_k` for `k = 1 … 14` (`T[0]` unused, 0).
    pub t: [f64; 15],
}

impl FlapCoefficients {
    /// The coefficients for hinge `c` and elastic axis `a`.
    pub fn new(c: f64, a: f64) -> Self {
        let s = (1.0 - c * c).max(0.0).sqrt();
        let f = c.clamp(-1.0, 1.0).acos();
        let mut t = [0.0; 15];
        t[1] = -s * (2.0 + c * c) / 3.0 + c * f;
        t[2] = c * s * s - s * (1.0 + c * c) * f + c * f * f;
        t[3] = -(0.125 + c * c) * f * f + 0.25 * c * s * f * (7.0 + 2.0 * c * c)
            - 0.125 * s * s * (5.0 * c * c + 4.0);
        t[4] = -f + c * s;
        t[5] = -s * s - f * f + 2.0 * c * s * f;
        t[6] = t[2];
        t[7] = -(0.125 + c * c) * f + 0.125 * c * s * (7.0 + 2.0 * c * c);
        t[8] = -s * (2.0 * c * c + 1.0) / 3.0 + c * f;
        t[9] = 0.5 * (s * s * s / 3.0 + a * t[4]);
        t[10] = s + f;
        t[11] = f * (1.0 - 2.0 * c) + s * (2.0 - c);
        t[12] = s * (2.0 + c) - f * (2.0 * c + 1.0);
        t[13] = 0.5 * (-t[7] - (c - a) * t[1]);
        t[14] = 1.0 / 16.0 + 0.5 * a * c;
        Self { c, a, t }
    }

    /// The hinge at chord fraction `x_h` from the leading edge (`c = 2 x_h − 1`) and the elastic
    /// axis at chord fraction `x_ea` (`a = 2 x_ea − 1`).
    pub fn at_chord_fractions(hinge: f64, elastic_axis: f64) -> Self {
        Self::new(2.0 * hinge - 1.0, 2.0 * elastic_axis - 1.0)
    }

    /// Steady lift coefficient per radian of deflection, `∂c_l/∂δ = 2 T10` (for `c_lα = 2π`).
    pub fn lift_per_deflection(&self) -> f64 {
        2.0 * self.t[10]
    }

    /// Steady moment coefficient about the quarter chord per radian of deflection (nose-up,
    /// on `q c²`): `−(T4 + T10)/2`.
    pub fn quarter_chord_moment_per_deflection(&self) -> f64 {
        -0.5 * (self.t[4] + self.t[10])
    }

    /// Steady hinge-moment coefficient (on `q c²`, positive trailing edge down) per radian of
    /// deflection at zero angle of attack: `−[(T5 − T4 T10) + T10 T12]/(2π)`.
    pub fn hinge_per_deflection(&self) -> f64 {
        let t = &self.t;
        -((t[5] - t[4] * t[10]) + t[10] * t[12]) / (2.0 * std::f64::consts::PI)
    }

    /// Steady hinge-moment coefficient (on `q c²`) per radian of angle of attack: `−T12/2`.
    pub fn hinge_per_angle(&self) -> f64 {
        -0.5 * self.t[12]
    }

    /// `T1 − T8 − (c − a) T4 + ½ T11`: the coefficient of `ρb³U δ̇` in the moment.
    pub(crate) fn moment_rate(&self) -> f64 {
        let t = &self.t;
        t[1] - t[8] - (self.c - self.a) * t[4] + 0.5 * t[11]
    }

    /// `T7 + (c − a) T1`: the coefficient of `ρb⁴ δ̈` in the moment.
    pub(crate) fn moment_acceleration(&self) -> f64 {
        self.t[7] + (self.c - self.a) * self.t[1]
    }
}

/// The flap of one strip: which surface, the fraction of the strip's width it covers, and its
/// coefficients at the strip's hinge and elastic axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StripFlap {
    /// Index of the surface.
    pub(crate) surface: usize,
    /// Fraction of the strip's width covered, in `(0, 1]`.
    pub(crate) coverage: f64,
    /// Theodorsen's coefficients of the strip's section.
    pub(crate) coefficients: FlapCoefficients,
}

/// What a strip's flap adds at one instant, independent of the structure's state: the
/// equivalent upwash at the three-quarter chord (lagged with the rest, circulatory), the
/// non-circulatory normal force and moment, each already scaled by the coverage.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct FlapAir {
    /// Equivalent upwash `φ (V T10 δ/π + b T11 δ̇/(2π))` (m/s).
    pub(crate) upwash: f64,
    /// The same over the covered part, `φ = 1` (m/s).
    pub(crate) covered_upwash: f64,
    /// Non-circulatory force per unit span along the section normal (N/m).
    pub(crate) normal: f64,
    /// Nose-up moment per unit span about the elastic axis, not carried by the lift at the
    /// quarter chord (N).
    pub(crate) moment: f64,
}

/// The flap's contribution for deflection, rate and acceleration `(δ, δ̇, δ̈)` at air speed
/// `speed`, density `rho`, half-chord `b`; `unsteady` keeps the rate and acceleration terms.
pub(crate) fn flap_air(
    f: &StripFlap,
    b: f64,
    rho: f64,
    speed: f64,
    [d, dd, ddd]: [f64; 3],
    unsteady: bool,
) -> FlapAir {
    let t = &f.coefficients.t;
    let pi = std::f64::consts::PI;
    let (dd, ddd) = if unsteady { (dd, ddd) } else { (0.0, 0.0) };
    let covered = speed * t[10] * d / pi + b * t[11] * dd / (2.0 * pi);
    let normal = -rho * b * b * (speed * t[4] * dd + b * t[1] * ddd);
    let moment = -rho
        * b
        * b
        * ((t[4] + t[10]) * speed * speed * d + f.coefficients.moment_rate() * speed * b * dd
            - f.coefficients.moment_acceleration() * b * b * ddd);
    FlapAir {
        upwash: f.coverage * covered,
        covered_upwash: covered,
        normal: f.coverage * normal,
        moment: f.coverage * moment,
    }
}

/// Hinge moment per unit span of the covered part of a strip (N·m/m) at rest relative to the
/// structure's rates (the steady and the flap-rate terms): `−ρb²[U²(T5 − T4T10)δ/π −
/// Ub T4T11 δ̇/(2π) − T3 b²δ̈/π] − (T12 b/(2π)) L_c`, with `L_c` the circulatory lift per unit span
/// of the covered part (`2πρUb C Q` in Theodorsen's terms).
pub(crate) fn hinge_moment(
    f: &StripFlap,
    b: f64,
    rho: f64,
    speed: f64,
    [d, dd, ddd]: [f64; 3],
    unsteady: bool,
    circulatory_lift: f64,
) -> f64 {
    let t = &f.coefficients.t;
    let pi = std::f64::consts::PI;
    let (dd, ddd) = if unsteady { (dd, ddd) } else { (0.0, 0.0) };
    -rho * b
        * b
        * (speed * speed * (t[5] - t[4] * t[10]) * d / pi
            - speed * b * t[4] * t[11] * dd / (2.0 * pi)
            - t[3] * b * b * ddd / pi)
        - t[12] * b * circulatory_lift / (2.0 * pi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Glauert's thin-airfoil closed forms (1926, §7.4) with `θ_h` the hinge's angle,
    /// `x_h/c = (1 − cos θ_h)/2` from the leading edge: `∂c_l/∂δ = 2(π − θ_h + sin θ_h)`,
    /// `∂c_m,c/4/∂δ = −½ sin θ_h (1 − cos θ_h)`. Independent of Theodorsen's functions; they agree
    /// to round-off (the two are the same integrals, written differently).
    #[test]
    fn steady_coefficients_are_glauerts() {
        for xh in [0.05_f64, 0.3, 0.5, 0.7, 0.75, 0.8, 0.9, 0.99] {
            let theta = (1.0 - 2.0 * xh).acos();
            let f = FlapCoefficients::at_chord_fractions(xh, 0.4);
            let cl = 2.0 * (PI - theta + theta.sin());
            let cm = -0.5 * theta.sin() * (1.0 - theta.cos());
            // Round-off of a few O(1) terms.
            assert!((f.lift_per_deflection() - cl).abs() < 1e-14, "{xh}");
            assert!(
                (f.quarter_chord_moment_per_deflection() - cm).abs() < 1e-14,
                "{xh}"
            );
        }
        // Limits: a hinge at the leading edge turns the whole plate (c_lδ = c_lα = 2π, no
        // moment about the quarter chord); a hinge at the trailing edge does nothing.
        let le = FlapCoefficients::new(-1.0, 0.0);
        assert!((le.lift_per_deflection() - 2.0 * PI).abs() < 1e-14);
        assert!(le.quarter_chord_moment_per_deflection().abs() < 1e-14);
        let te = FlapCoefficients::new(1.0, 0.0);
        assert!(te.t.iter().skip(1).take(13).all(|v| v.abs() < 1e-14));
    }

    /// The apparent-mass terms are those of one kinetic energy: the moment's `δ̈` coefficient
    /// `T7 + (c − a)T1` is the hinge moment's `α̈` coefficient `−2 T13` (Theodorsen's
    /// definition of `T13`), and for a hinge at the leading edge the flap is a pitch about it:
    /// the lift's `δ̇`, `δ̈` coefficients are those of `α̇`, `α̈` about `a = −1`
    /// (`−T4 = π`, `−T1 = π`).
    #[test]
    fn apparent_mass_symmetry_and_limits() {
        let f = FlapCoefficients::new(0.4, -0.3);
        assert!((f.moment_acceleration() + 2.0 * f.t[13]).abs() < 1e-15);
        let le = FlapCoefficients::new(-1.0, -1.0);
        assert!((le.t[4] + PI).abs() < 1e-14 && (le.t[1] + PI).abs() < 1e-14);
        // ... and its hinge moment about the leading edge is the pitching moment there:
        // `M_nc` at `a = −1`: `−πρb⁴(⅛ + 1) α̈`, i.e. `ρb⁴ T3/π = −9πρb⁴/8` for `δ̈`.
        assert!((le.t[3] / (PI * PI) + 1.125).abs() < 1e-14, "{}", le.t[3]);
    }
}
