//! Calibration of the joint springs from the continuous beam (paper eqs. 6–7, model.md).

use super::profile::{integrate, Profile};

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
    /// Bending spring stiffnesses for the node stations `nodes` (`x_0 = 0 … x_n = L`).
    pub(crate) fn bending(self, ei: &Profile, nodes: &[f64]) -> Vec<f64> {
        match self {
            Calibration::TipLoad => tip_load(ei, nodes),
            Calibration::Uniform => nodes
                .windows(2)
                .map(|w| 1.0 / integrate(&[ei], w[0], w[1], |x| 1.0 / ei.at(x)))
                .collect(),
        }
    }
}

/// Tip-load-matched springs. The deflection of the cantilever under a unit tip force satisfies
/// `w'' = (L − x)/EI(x)`, integrated element by element:
/// `w'(b) = w'(a) + ∫_a^b (L − s)/EI ds`, `w(b) = w(a) + (b − a) w'(a) + ∫_a^b (b − s)(L − s)/EI ds`.
fn tip_load(ei: &Profile, nodes: &[f64]) -> Vec<f64> {
    let length = nodes[nodes.len() - 1];
    let (mut slope, mut w) = (0.0, 0.0);
    let mut chord_prev = 0.0;
    nodes
        .windows(2)
        .map(|seg| {
            let (a, b) = (seg[0], seg[1]);
            let w_b =
                w + (b - a) * slope + integrate(&[ei], a, b, |s| (b - s) * (length - s) / ei.at(s));
            slope += integrate(&[ei], a, b, |s| (length - s) / ei.at(s));
            let chord = (w_b - w) / (b - a);
            let q = chord - chord_prev;
            chord_prev = chord;
            w = w_b;
            (length - a) / q
        })
        .collect()
}

/// Torsion springs: spring `i` joins the midpoints of elements `i − 1` and `i` (the clamp for
/// `i = 1`), and its stiffness is that of the continuous shaft between them,
/// `K_ψ,i = 1 / ∫_{c_{i−1}}^{c_i} dx/GJ` (`GJ/ℓ`, and `2GJ/ℓ` at the root, for a uniform beam).
pub(crate) fn torsion(gj: &Profile, nodes: &[f64]) -> Vec<f64> {
    let mut c_prev = 0.0;
    nodes
        .windows(2)
        .map(|seg| {
            let c = 0.5 * (seg[0] + seg[1]);
            let k = 1.0 / integrate(&[gj], c_prev, c, |x| 1.0 / gj.at(x));
            c_prev = c;
            k
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

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
