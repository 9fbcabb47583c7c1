//! Absolute angles and their sines and cosines for one configuration.

/// Trigonometry of one configuration `q`, computed once and shared by the mass matrix, the
/// gyroscopic term and the generalized forces. Build with [`Kinematics::new`], refresh with
/// [`Kinematics::update`] (no allocation).
#[derive(Debug, Clone, PartialEq)]
pub struct Kinematics {
    /// Absolute bending angles `θ_i` (rad).
    pub theta: Vec<f64>,
    /// `cos θ_i`.
    pub cos_theta: Vec<f64>,
    /// `sin θ_i`.
    pub sin_theta: Vec<f64>,
    /// Absolute twists `ψ_i` (rad); zeros in a bending-only model.
    pub psi: Vec<f64>,
    /// `cos ψ_i`.
    pub cos_psi: Vec<f64>,
    /// `sin ψ_i`.
    pub sin_psi: Vec<f64>,
}

impl Kinematics {
    /// Storage for a chain of `n` elements, at the undeformed state.
    pub fn new(n: usize) -> Self {
        Self {
            theta: vec![0.0; n],
            cos_theta: vec![1.0; n],
            sin_theta: vec![0.0; n],
            psi: vec![0.0; n],
            cos_psi: vec![1.0; n],
            sin_psi: vec![0.0; n],
        }
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.theta.len()
    }

    /// Recompute from joint rotations `q` (length `n` or `2n`).
    ///
    /// # Panics
    /// If `q` has neither `n` nor `2n` entries.
    pub fn update(&mut self, q: &[f64]) {
        let n = self.n_elements();
        assert!(
            q.len() == n || q.len() == 2 * n,
            "q has {} entries for {n} elements",
            q.len()
        );
        let mut th = 0.0;
        for i in 0..n {
            th += q[i];
            self.theta[i] = th;
            (self.sin_theta[i], self.cos_theta[i]) = th.sin_cos();
        }
        if q.len() == 2 * n {
            let mut ps = 0.0;
            for i in 0..n {
                ps += q[n + i];
                self.psi[i] = ps;
                (self.sin_psi[i], self.cos_psi[i]) = ps.sin_cos();
            }
        } else {
            self.psi.fill(0.0);
            self.sin_psi.fill(0.0);
            self.cos_psi.fill(1.0);
        }
    }
}

/// `(sin x, cos x)` in one evaluation, at most `2 ε max(|v|, ½)` from the library's values `v`
/// for `|x| < 1e5` (the planar chain's angles are a few radians), and `f64::sin_cos` beyond and for
/// NaN. Cody–Waite reduction by `π/2` in three parts, then fdlibm's minimax kernels on
/// `[−π/4, π/4]`: one reduction and about 30 flops instead of two library calls, which were a
/// quarter of a reduced model's right-hand side (docs/performance.md, issue 22).
// The constants as fdlibm publishes them (their decimal strings round to the intended doubles).
#[allow(clippy::excessive_precision)]
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    // π/2 in three parts, the first two with 33 significant bits, so that `k · part` is exact
    // for |k| < 2^20.
    const PIO2_1: f64 = 1.570_796_326_734_125_614_17;
    const PIO2_2: f64 = 6.077_100_506_303_965_976_6e-11;
    const PIO2_3: f64 = 2.022_266_248_795_950_732_4e-21;
    const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
    // fdlibm __kernel_sin / __kernel_cos.
    const S1: f64 = -1.666_666_666_666_663_243_48e-1;
    const S2: f64 = 8.333_333_333_322_489_461_24e-3;
    const S3: f64 = -1.984_126_982_985_794_931_34e-4;
    const S4: f64 = 2.755_731_370_707_006_767_89e-6;
    const S5: f64 = -2.505_076_025_340_686_341_95e-8;
    const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    const C1: f64 = 4.166_666_666_666_660_190_37e-2;
    const C2: f64 = -1.388_888_888_887_410_957_49e-3;
    const C3: f64 = 2.480_158_728_947_672_941_78e-5;
    const C4: f64 = -2.755_731_435_139_066_330_35e-7;
    const C5: f64 = 2.087_572_321_298_174_827_90e-9;
    const C6: f64 = -1.135_964_755_778_819_482_65e-11;
    if !(x.abs() < 1e5) {
        return x.sin_cos();
    }
    // Round to nearest by the 1.5 · 2^52 shift (no library call; exact for |x| < 1e5).
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let k = (x * TWO_OVER_PI + SHIFT) - SHIFT;
    let y = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
    let z = y * y;
    let s = y + y * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    // fdlibm's cos: `w + ((1 − w) − z/2) + z² c(z)` with `w = 1 − z/2`, the rounding of `w`
    // carried.
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c =
        w + (((1.0 - w) - hz) + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
    match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    /// Against the library's `sin` and `cos` (within 1 ulp on glibc): at most `2 ε max(|v|,
    /// ½)` apart (the kernels' documented error is under 1 ulp, the reduction adds about one
    /// rounding of `π/2`'s size; near the zeros of sin and cos the bound is absolute), on a dense grid over ±60 rad, at
    /// multiples of π/4 (the quadrant boundaries) and at tiny and huge arguments and NaN.
    #[test]
    fn sin_cos_is_within_two_ulp_of_the_library() {
        let ulp = |v: f64| f64::EPSILON * v.abs().max(0.5);
        let mut xs: Vec<f64> = (-600_000..=600_000)
            .map(|k| k as f64 * 1e-4 + 3e-9)
            .collect();
        xs.extend((-80..=80).map(|k| k as f64 * std::f64::consts::FRAC_PI_4));
        xs.extend([0.0, -0.0, 1e-300, -1e-20, 5e-9, 99_999.9, 1e6, -3e7]);
        for &x in &xs {
            let (s, c) = super::sin_cos(x);
            let (se, ce) = x.sin_cos();
            assert!((s - se).abs() <= 2.0 * ulp(se), "sin {x}: {s} {se}");
            assert!((c - ce).abs() <= 2.0 * ulp(ce), "cos {x}: {c} {ce}");
        }
        let (s, c) = super::sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
    }
}
