//! Calibration of the joint springs from the continuous beam (paper eqs. 6–7, model.md), by exact
//! integrals over the linear pieces of the stiffness tables (derivation in the comments of
//! [`tip_load`] and [`moments`]; docs/model-choices.md, "Stiffness calibration"):
//! O(n + table stations).

use super::profile::{for_each_piece, Piece, Profile};

/// Rule that turns `EI(x)` into the bending spring stiffnesses `K_θ,i`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Calibration {
    /// The paper's rule: the springs reproduce the exact linear nodal deflections of the
    /// Euler–Bernoulli cantilever under a tip force, `K_θ,i = M_i / q_i` with `M_i = L − x_{i−1}`.
    #[default]
    TipLoad,
    /// `K_θ,i = 1 / ∫ dx/EI` over element `i` (`EI/ℓ` for a uniform beam, as Rempel et al. 2020).
    Uniform,
}

impl Calibration {
    /// The case file's name: `tip-load` or `uniform`.
    pub fn name(self) -> &'static str {
        match self {
            Calibration::TipLoad => "tip-load",
            Calibration::Uniform => "uniform",
        }
    }

    /// Bending spring stiffnesses for the node stations `nodes` (`x_0 = 0 … x_n = L`).
    pub(crate) fn bending(self, ei: &Profile, nodes: &[f64]) -> Vec<f64> {
        match self {
            Calibration::TipLoad => tip_load(ei, nodes),
            Calibration::Uniform => flexibilities(ei, nodes)
                .into_iter()
                .map(|f| 1.0 / f)
                .collect(),
        }
    }
}

/// `M_jk(r) = ∫_0^1 τ^j (1 − τ)^k / (1 + r τ) dτ` for `(j, k)` = (0, 0), (1, 0), (2, 0), (0, 1),
/// (1, 1), in that order, for `r > −1`: the moments of `1/EI` on a piece where `EI` is linear,
/// `EI = EI_b (1 + r τ)` with `τ` measured from the piece's far end `b` in units of its length.
///
/// For `|r| ≤ 1/2` the geometric series `Σ_m (−r)^m B(j + m + 1, k + 1)` (Beta function), summed
/// until its terms no longer change the sum: exact for `r = 0` with one term and free of
/// cancellation for a tiny slope. Otherwise the closed forms `J_0 = ln(1 + r)/r`,
/// `J_1 = (1 − J_0)/r`, `J_2 = (1/2 − J_1)/r` (`J_j = M_j0`) and `M_01 = J_0 − J_1`,
/// `M_11 = J_1 − J_2`, which lose at most a few digits' worth of factors (≤ 20 ε) for `|r| ≥ 1/2`
/// and a logarithmic factor `ln(EI_b/EI_a)` as `r → −1`.
fn moments(r: f64) -> [f64; 5] {
    if r.abs() <= 0.5 {
        let mut out = [0.0; 5];
        let mut power = 1.0; // (−r)^m
                             // |r|^m < 2⁻⁵³ by m = 53: the last terms are below the sums' rounding.
        for m in 0..SERIES_TERMS {
            // B(j + m + 1, 1) = 1/(j + m + 1); B(j + m + 1, 2) = 1/((j + m + 1)(j + m + 2)).
            let (i1, i2, i3) = (INV[m + 1], INV[m + 2], INV[m + 3]);
            let terms = [i1, i2, i3, i1 * i2, i2 * i3];
            let before = out;
            for (o, t) in out.iter_mut().zip(terms) {
                *o += power * t;
            }
            if out == before {
                break;
            }
            power *= -r;
        }
        out
    } else {
        let j0 = r.ln_1p() / r;
        let j1 = (1.0 - j0) / r;
        let j2 = (0.5 - j1) / r;
        [j0, j1, j2, j0 - j1, j1 - j2]
    }
}

/// Terms of the series of [`moments`] at most (`2⁻⁵⁴` at `|r| = 1/2`).
const SERIES_TERMS: usize = 56;

/// `INV[k] = 1/k` (`INV[0]` unused).
const INV: [f64; SERIES_TERMS + 3] = {
    let mut t = [0.0; SERIES_TERMS + 3];
    let mut k = 1;
    while k < t.len() {
        t[k] = 1.0 / k as f64;
        k += 1;
    }
    t
};

/// The piece's length `h`, `h / EI(b)` and the moments of `1/EI` on it ([`moments`]).
fn piece_moments(p: &Piece<1>) -> (f64, f64, [f64; 5]) {
    let (ea, eb) = (p.at_a[0], p.at_b[0]);
    let h = p.b - p.a;
    (h, h / eb, moments((ea - eb) / eb))
}

/// `∫ dx/EI` over each interval `[bounds[i], bounds[i + 1]]`, exactly, in O(intervals + stations).
pub(crate) fn flexibilities(ei: &Profile, bounds: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; bounds.len() - 1];
    for_each_piece(bounds, [ei], |i, p| {
        let (_, h_over_e, m) = piece_moments(&p);
        out[i] += h_over_e * m[0];
    });
    out
}

/// Tip-load-matched springs, `K_θ,i = (L − x_i) / q_i`, with `q_i` the jump of the chord slope of
/// the cantilever's deflection `w` under a unit tip force at node `x_i`
/// (`w'' = κ = (L − x)/EI(x)`). Writing each chord slope as `w'` at its start plus a weighted
/// integral of `κ` over the element gives the jump as the integral of `κ` against the hat
/// function of node `i`,
///
/// ```text
/// q_i = E_{i−1} + D_i,   D_i = ∫_{x_i}^{x_{i+1}} (x_{i+1} − s) κ ds / ℓ_i,
///                        E_i = ∫_{x_i}^{x_{i+1}} (s − x_i) κ ds / ℓ_i,     E_{−1} = 0,
/// ```
///
/// a sum of positive terms: no difference of deflections, so no cancellation (the difference of
/// nodal deflections loses `log₁₀ n²` digits). On a piece `[p, p']` of element `i` with
/// `τ = (p' − s)/h`, `A = x_{i+1} − p'`, `A' = p − x_i`, `B = L − p'`:
///
/// ```text
/// ∫ (x_{i+1} − s)(L − s)/EI ds = h/EI(p') (A B M_00 + (A + B) h M_10 + h² M_20)
/// ∫ (s − x_i)(L − s)/EI ds     = h/EI(p') (A' B M_00 + A' h M_10 + B h M_01 + h² M_11)
/// ```
///
/// with the moments `M_jk` of [`moments`]; every term is non-negative.
fn tip_load(ei: &Profile, nodes: &[f64]) -> Vec<f64> {
    let n = nodes.len() - 1;
    let length = nodes[n];
    let (mut d, mut e) = (vec![0.0; n], vec![0.0; n]);
    for_each_piece(nodes, [ei], |i, p| {
        let (h, h_over_e, m) = piece_moments(&p);
        let (a, a_in, b) = (nodes[i + 1] - p.b, p.a - nodes[i], length - p.b);
        d[i] += h_over_e * (a * b * m[0] + (a + b) * h * m[1] + h * h * m[2]);
        e[i] += h_over_e * (a_in * b * m[0] + a_in * h * m[1] + b * h * m[3] + h * h * m[4]);
    });
    (0..n)
        .map(|i| {
            let ell = nodes[i + 1] - nodes[i];
            let before = if i > 0 {
                e[i - 1] / (nodes[i] - nodes[i - 1])
            } else {
                0.0
            };
            (length - nodes[i]) / (before + d[i] / ell)
        })
        .collect()
}

/// Torsion springs: spring `i` joins the midpoints of elements `i − 1` and `i` (the clamp for
/// `i = 1`), and its stiffness is that of the continuous shaft between them,
/// `K_ψ,i = 1 / ∫_{c_{i−1}}^{c_i} dx/GJ` (`GJ/ℓ`, and `2GJ/ℓ` at the root, for a uniform beam).
pub(crate) fn torsion(gj: &Profile, nodes: &[f64]) -> Vec<f64> {
    let mut bounds = Vec::with_capacity(nodes.len());
    bounds.push(0.0);
    bounds.extend(nodes.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    flexibilities(gj, &bounds)
        .into_iter()
        .map(|f| 1.0 / f)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::profile::integrate;

    /// The calibration this module replaced (kept as the test's independent reference): nodal
    /// deflections by adaptive Gauss–Legendre quadrature at 1e-14 relative, element by element,
    /// and the springs from differences of chord slopes.
    fn tip_load_by_quadrature(ei: &Profile, nodes: &[f64]) -> Vec<f64> {
        let length = nodes[nodes.len() - 1];
        let (mut slope, mut w) = (0.0, 0.0);
        let mut chord_prev = 0.0;
        nodes
            .windows(2)
            .map(|seg| {
                let (a, b) = (seg[0], seg[1]);
                let w_b = w
                    + (b - a) * slope
                    + integrate(&[ei], a, b, |s| (b - s) * (length - s) / ei.at(s));
                slope += integrate(&[ei], a, b, |s| (length - s) / ei.at(s));
                let chord = (w_b - w) / (b - a);
                let q = chord - chord_prev;
                chord_prev = chord;
                w = w_b;
                (length - a) / q
            })
            .collect()
    }

    /// Uneven stations: `n` elements whose lengths vary by a factor of 3.
    fn uneven_nodes(l: f64, n: usize) -> Vec<f64> {
        let w: Vec<f64> = (0..n).map(|i| 2.0 + (1.7 * i as f64).sin()).collect();
        let total: f64 = w.iter().sum();
        let mut x = vec![0.0];
        for wi in &w {
            x.push(x[x.len() - 1] + l * wi / total);
        }
        x[n] = l;
        x
    }

    /// A table of `points` stations over `[0, l]`: a taper from `root` to `tip` with a ±5 % ripple.
    fn rippled(l: f64, points: usize, root: f64, tip: f64) -> Profile {
        let x: Vec<f64> = (0..points)
            .map(|k| l * k as f64 / (points - 1) as f64)
            .collect();
        let value = x
            .iter()
            .map(|s| (root + (tip - root) * s / l) * (1.0 + 0.05 * (7.0 * s / l).sin()))
            .collect();
        Profile::Table { x, value }
    }

    fn max_rel(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x / y - 1.0).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn moments_match_quadrature_on_both_sides_of_the_switch() {
        // Against adaptive Gauss–Legendre (1e-14 relative) for slopes from EI falling a
        // thousandfold over the piece to rising a thousandfold, including both sides of the
        // series/closed-form switch at |r| = 1/2 and tiny slopes.
        let one = Profile::Uniform(1.0);
        for r in [
            -0.999, -0.9, -0.5000001, -0.5, -0.3, -1e-9, 0.0, 1e-12, 0.2, 0.5, 0.5000001, 3.0, 1e3,
        ] {
            let got = moments(r);
            let f = [
                |t: f64| 1.0 + 0.0 * t,
                |t: f64| t,
                |t: f64| t * t,
                |t: f64| 1.0 - t,
                |t: f64| t * (1.0 - t),
            ];
            for (k, g) in f.iter().enumerate() {
                let want = integrate(&[&one], 0.0, 1.0, |t| g(t) / (1.0 + r * t));
                // Measured ≤ 8e-16, and 1.7e-15 just past the switch (r = −0.5000001), where
                // the closed forms lose most; bound 1e-14.
                assert!(
                    (got[k] / want - 1.0).abs() < 1e-14,
                    "r = {r}, moment {k}: {} vs {want}",
                    got[k]
                );
            }
        }
    }

    #[test]
    fn tip_load_rule_for_linear_ei_matches_closed_form() {
        // EI = e0 (1 − c x): w'(x) = [x/c − (L − 1/c) ln(1 − cx)/c] / e0 and
        // w(x) = [x²/(2c) + (L − 1/c)(cx + (1 − cx) ln(1 − cx))/c²] / e0; the springs from the
        // jumps of the chord slopes. EI falls 4-fold and 1000-fold over the span.
        let (l, e0) = (10.0, 4e4);
        for ratio in [0.25, 1e-3] {
            let c = (1.0 - ratio) / l;
            let w = |x: f64| {
                let u = (-c * x).ln_1p();
                (x * x / (2.0 * c) + (l - 1.0 / c) * (c * x + (1.0 - c * x) * u) / (c * c)) / e0
            };
            let ei = Profile::Table {
                x: vec![0.0, l],
                value: vec![e0, e0 * ratio],
            };
            for n in [1, 3, 10, 37] {
                let nodes = uneven_nodes(l, n);
                let k = tip_load(&ei, &nodes);
                let mut chord_prev = 0.0;
                let mut expected = Vec::new();
                for i in 0..n {
                    let chord = (w(nodes[i + 1]) - w(nodes[i])) / (nodes[i + 1] - nodes[i]);
                    expected.push((l - nodes[i]) / (chord - chord_prev));
                    chord_prev = chord;
                }
                // The closed form's own round-off (differences of deflections, ~ε n²) is the
                // limit: measured ≤ 1.1e-11 at n = 37; bound 1e-10.
                let e = max_rel(&k, &expected);
                assert!(e < 1e-10, "ratio {ratio}, n = {n}: {e:.2e}");
            }
        }
    }

    #[test]
    fn tip_load_rule_equals_the_quadrature_it_replaced() {
        // Regression against the former adaptive quadrature: a two-point taper and a 300-point
        // rippled table, even and uneven stations. Same result to the quadrature's tolerance
        // and the round-off of its chord differences (measured ≤ 1.2e-12 at n = 40; bound 1e-10).
        let l = 10.0;
        for ei in [
            Profile::Table {
                x: vec![0.0, l],
                value: vec![4e4, 1e4],
            },
            rippled(l, 300, 4e4, 1e4),
        ] {
            for nodes in [uniform_nodes(l, 7), uneven_nodes(l, 40)] {
                let e = max_rel(&tip_load(&ei, &nodes), &tip_load_by_quadrature(&ei, &nodes));
                assert!(e < 1e-10, "{e:.2e}");
            }
        }
    }

    #[test]
    fn tip_load_rule_keeps_its_digits_at_large_n() {
        // Uniform EI at n = 10 000 on stations that are exact binary fractions (ℓ = 2⁻¹⁰): the
        // springs are EI/ℓ inside and 6 EI L/(ℓ (3L − ℓ)) at the root, exactly. The hat-function
        // form sums positive terms (measured error 0 at the root, 2.2e-16 inside: bound 1e-14);
        // the former chord differences lost 1.9e-8 already at n = 1000.
        let (ei, n, h) = (50.0, 10_000, 1.0 / 1024.0);
        let nodes: Vec<f64> = (0..=n).map(|i| i as f64 * h).collect();
        let l = nodes[n];
        let k = tip_load(&Profile::Uniform(ei), &nodes);
        let root = (k[0] / (6.0 * ei * l / (h * (3.0 * l - h))) - 1.0).abs();
        let inside = max_rel(&k[1..], &vec![ei / h; n - 1]);
        assert!(root < 1e-14 && inside < 1e-14, "{root:.2e}, {inside:.2e}");
    }

    #[test]
    fn torsion_rule_equals_the_quadrature_it_replaced() {
        let l = 10.0;
        for gj in [
            Profile::Table {
                x: vec![0.0, l],
                value: vec![2e3, 5e2],
            },
            rippled(l, 300, 2e3, 5e2),
        ] {
            for nodes in [uniform_nodes(l, 7), uneven_nodes(l, 40)] {
                let mut c_prev = 0.0;
                let old: Vec<f64> = nodes
                    .windows(2)
                    .map(|seg| {
                        let c = 0.5 * (seg[0] + seg[1]);
                        let k = 1.0 / integrate(&[&gj], c_prev, c, |x| 1.0 / gj.at(x));
                        c_prev = c;
                        k
                    })
                    .collect();
                // The quadrature's tolerance: measured ≤ 2.3e-16; bound 1e-13.
                let e = max_rel(&torsion(&gj, &nodes), &old);
                assert!(e < 1e-13, "{e:.2e}");
            }
        }
    }

    fn uniform_nodes(l: f64, n: usize) -> Vec<f64> {
        (0..=n).map(|i| l * i as f64 / n as f64).collect()
    }

    #[test]
    fn tip_load_rule_for_uniform_beam_matches_closed_form() {
        // Uniform EI: w(x) = x²(3L − x)/(6EI); root spring 6 EI L / (ℓ (3L − ℓ)) ≈ 2EI/ℓ.
        let (l, ei, n) = (2.0, 7.0, 8);
        let nodes = uniform_nodes(l, n);
        let k = tip_load(&Profile::Uniform(ei), &nodes);
        let h = l / n as f64;
        let w = |x: f64| x * x * (3.0 * l - x) / (6.0 * ei);
        let mut chord_prev = 0.0;
        for i in 0..n {
            let chord = (w(nodes[i + 1]) - w(nodes[i])) / h;
            let expected = (l - nodes[i]) / (chord - chord_prev);
            chord_prev = chord;
            assert!((k[i] - expected).abs() < 1e-12 * expected, "{i}");
        }
        assert!((k[0] - 6.0 * ei * l / (h * (3.0 * l - h))).abs() < 1e-12 * k[0]);
    }

    #[test]
    fn torsion_rule_for_uniform_beam() {
        let (l, gj, n) = (3.0, 5.0, 6);
        let k = torsion(&Profile::Uniform(gj), &uniform_nodes(l, n));
        let h = l / n as f64;
        assert!((k[0] - 2.0 * gj / h).abs() < 1e-12 * k[0]);
        for ki in &k[1..] {
            assert!((ki - gj / h).abs() < 1e-12 * ki);
        }
    }

    #[test]
    fn uniform_rule_is_ei_over_length() {
        let k = Calibration::Uniform.bending(&Profile::Uniform(4.0), &uniform_nodes(1.0, 4));
        for ki in k {
            assert!((ki - 16.0).abs() < 1e-12);
        }
    }
}
