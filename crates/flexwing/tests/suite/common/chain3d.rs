//! Shared helpers of the 3-D chain's integration tests (`tests/suite/chain3d_*.rs`), built from the
//! public API only.
#![allow(dead_code)]

use flexwing::beam::{Discretization, InertiaAxis, Profile};
use flexwing::model::chain3d::{
    Beam3d, Chain3d, ElementInertia, Geometry3d, JointCalibration, SectionInertia,
    SectionStiffness, StiffnessCoupling,
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

/// Patil's HALE wing on the 3-D chain (Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001; the
/// problem of `tests/data/chain3d_reference/README.md` §2.1): straight, 16 m, `GJ = 1e4`,
/// `EI_flap = 2e4`, `EI_lag = 4e6 N·m²`, `m = 0.75 kg/m`, `I = 0.1 kg·m` about the mass centre on
/// the elastic axis (`d0 = 0`), chord 1 m, elastic axis at mid-chord, `c_lα = 2π`,
/// `ρ = 0.0889 kg/m³`; `n` equal elements with the given element inertia and calibration.
pub fn patil_wing_3d(
    n: usize,
    aerodynamics: flexwing::model::aero::Aerodynamics,
    element_inertia: flexwing::model::chain3d::ElementInertia,
    calibration: JointCalibration,
) -> flexwing::model::aero::Aeroelastic<Chain3d> {
    use flexwing::beam::Profile;
    use flexwing::model::aero::{AeroSection, Aeroelastic};
    let chain = Chain3d::new(
        Beam3d::new(
            &Geometry3d::straight(16.0, n),
            &SectionStiffness::uncoupled(1e4, 2e4, 4e6),
            &SectionInertia {
                element_inertia,
                ..SectionInertia::uniform(0.75, 0.1)
            },
            calibration,
        )
        .expect("valid beam"),
    );
    let aero = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
    Aeroelastic::spatial(&chain, &aero, 0.0889, aerodynamics, "aero").expect("valid wing")
}

/// Richardson's extrapolation of a second-order sequence from its values at `n` and `2n`.
pub fn richardson(coarse: f64, fine: f64) -> f64 {
    fine + (fine - coarse) / 3.0
}

/// A row of `tests/data/chain3d_reference/patil_deformed_flutter.csv` (README §2): `case`
/// (`tip_force`, `gravity`), `load` (N or the factor of g), `model` (`theodorsen`, `peters6`,
/// `jones`, `quasi_steady`, `steady`), `quantity` (`flutter`, `divergence`,
/// `unstable_from_start`): `(tip_y, U, ω)` of the continuum rod, exact to ~1e-11.
pub fn patil_deformed(case: &str, load: f64, model: &str, quantity: &str) -> (f64, f64, f64) {
    patil_deformed_rows()
        .into_iter()
        .find(|r| {
            r[0] == case
                && crate::common::aero_reference::parse(&r[1]) == load
                && r[4] == model
                && r[5] == quantity
        })
        .map(|r| {
            let p = crate::common::aero_reference::parse;
            (p(&r[3]), p(&r[6]), p(&r[7]))
        })
        .unwrap_or_else(|| {
            panic!("patil_deformed_flutter.csv: no {case} {load} {model} {quantity}")
        })
}

/// The rows of `patil_deformed_flutter.csv`, split on commas (header dropped).
pub fn patil_deformed_rows() -> Vec<Vec<String>> {
    reference_rows("patil_deformed_flutter.csv")
}

/// The rows of `tests/data/chain3d_reference/{file}` (header dropped), split on commas (no
/// field holds a comma, README).
pub fn reference_rows(file: &str) -> Vec<Vec<String>> {
    let path: std::path::PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "tests/data/chain3d_reference",
        file,
    ]
    .iter()
    .collect();
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// A swept, dihedral, pretwisted, bend–twist coupled cantilever with offsets in both directions:
/// flap, lag and twist coupled through the geometry, the section and the inertia (the
/// `chain3d_dynamics`, `chain3d_newton_systems` and `chain3d_reduced` tests' general case).
pub fn coupled_chain(n: usize) -> Chain3d {
    let l = 1.0;
    let geometry = Geometry3d::Span {
        length: l,
        discretization: Discretization::Uniform(n),
        sweep: Profile::Uniform(0.2),
        dihedral: Profile::Table {
            x: vec![0.0, l],
            value: vec![0.0, 0.15],
        },
        pretwist: Profile::Table {
            x: vec![0.0, l],
            value: vec![0.1, -0.2],
        },
    };
    let stiffness = SectionStiffness {
        gj: Profile::Uniform(8.0),
        ei_flap: Profile::Uniform(10.0),
        ei_lag: Profile::Uniform(60.0),
        coupling: Some(StiffnessCoupling {
            twist_flap: Profile::Uniform(2.0),
            twist_lag: Profile::Uniform(0.0),
            lag_flap: Profile::Uniform(-1.0),
        }),
    };
    let inertia = SectionInertia {
        mass_per_length: Profile::Uniform(0.5),
        polar_inertia: Profile::Uniform(0.004),
        polar_inertia_about: InertiaAxis::MassCentre,
        d0: Profile::Uniform(0.04),
        d0_normal: Profile::Uniform(-0.01),
        rotary_inertia_flap: Profile::Uniform(0.0),
        rotary_inertia_lag: Profile::Uniform(0.002),
        element_inertia: ElementInertia::Bar,
    };
    Chain3d::new(
        Beam3d::new(
            &geometry,
            &stiffness,
            &inertia,
            JointCalibration::Compliance,
        )
        .unwrap(),
    )
}
