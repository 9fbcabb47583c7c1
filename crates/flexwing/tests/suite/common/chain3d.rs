//! Shared helpers of the 3-D chain's integration tests (`tests/suite/chain3d_*.rs`), built from the
//! public API only.
#![allow(dead_code)]

use flexwing::model::chain3d::{
    Beam3d, Chain3d, Geometry3d, JointCalibration, SectionInertia, SectionStiffness,
};

/// A straight uniform cantilever of length `l` in `n` elements with the compliance calibration,
/// elements as bars.
pub fn uniform_chain(
    n: usize,
    l: f64,
    (gj, ei_flap, ei_lag): (f64, f64, f64),
    (m, polar): (f64, f64),
) -> Chain3d {
    Chain3d::new(
        Beam3d::new(
            &Geometry3d::straight(l, n),
            &SectionStiffness::uncoupled(gj, ei_flap, ei_lag),
            &SectionInertia::uniform(m, polar),
            JointCalibration::Compliance,
        )
        .expect("valid beam"),
    )
}

/// Observed orders `log2(e_k / e_{k+1})` of errors at doubling `n`.
pub fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

pub fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
