//! Shared helpers of the integration tests: beams of the validated cases and reference data.
#![allow(dead_code)]

use flexwing::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use flexwing::model::{AppliedLoads, Force, FullModel, Load};
use flexwing::solve::TimeFunction;
use std::path::PathBuf;

pub mod aero_reference;
pub mod chain3d;
pub mod elastica;
pub mod typical_section;

/// A two-point (linear root → tip) table over `[0, length]`.
pub fn linear(length: f64, root: f64, tip: f64) -> Profile {
    Profile::Table {
        x: vec![0.0, length],
        value: vec![root, tip],
    }
}

pub fn bending_only(ei: Profile, m: Profile) -> SectionProperties {
    SectionProperties {
        ei,
        mass_per_length: m,
        torsion: None,
    }
}

pub fn coupled(
    ei: Profile,
    m: Profile,
    gj: Profile,
    i_cg: Profile,
    d0: Profile,
) -> SectionProperties {
    SectionProperties {
        ei,
        mass_per_length: m,
        torsion: Some(TorsionProperties {
            gj,
            polar_inertia: i_cg,
            inertia_axis: InertiaAxis::MassCentre,
            offset: d0,
        }),
    }
}

/// The Table 4 beam (L = 1 m, EI = 50 N·m², m = 0.2 kg/m, bending only), tip-load calibration,
/// `n` elements: the tests' one definition, written from the paper and independent of
/// `flexwing::paper::table4_beam` on purpose (a mistake there cannot hide behind these tests).
pub fn table4(n: usize) -> FullModel {
    model(
        1.0,
        &bending_only(Profile::Uniform(50.0), Profile::Uniform(0.2)),
        n,
        Calibration::TipLoad,
    )
}

/// Case (b) of the paper (section 5.2.5): the Table 4 beam under a dead tip force
/// `10 sin(20 t)` N, from rest. The tests' one definition of it (independent of
/// `flexwing::paper::sine_case`, as [`table4`]).
pub struct SineCase {
    /// The Table 4 beam.
    pub full: FullModel,
    /// The tip force's amplitude, resolved on the beam.
    pub loads: AppliedLoads,
    /// Its time history.
    pub time: Vec<TimeFunction>,
}

/// Case (b) with `n` elements.
pub fn sine_case(n: usize) -> SineCase {
    let full = table4(n);
    let loads = full
        .apply(
            &[Load::PointForce {
                span: 1.0,
                force: Force::Dead { fx: 0.0, fy: 10.0 },
            }],
            "loads",
        )
        .expect("loads");
    let time = vec![TimeFunction::Sine {
        omega: 20.0,
        phase: 0.0,
    }];
    SineCase { full, loads, time }
}

pub fn model(length: f64, section: &SectionProperties, n: usize, cal: Calibration) -> FullModel {
    FullModel::new(
        Beam::new(length, section, &Discretization::Uniform(n), cal).expect("valid beam"),
    )
}

/// The Table 1 beam with the parameter set of model.md (item 6): L = 16 m, EI = 2e4 N·m²,
/// GJ = 1e3 N·m², m = 0.75 kg/m, I_cg = 0.1 kg·m about the mass centre, d0 = 0.267 m.
pub fn table1_section() -> SectionProperties {
    coupled(
        Profile::Uniform(2e4),
        Profile::Uniform(0.75),
        Profile::Uniform(1e3),
        Profile::Uniform(0.1),
        Profile::Uniform(0.267),
    )
}

/// `omega_rad_s` column of a reference CSV in `tests/data/continuous_beam/`.
pub fn reference_frequencies(file: &str) -> Vec<f64> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/continuous_beam")
        .join(file);
    let mut rdr = csv::Reader::from_path(&path).expect("reference file");
    let headers = rdr.headers().expect("header").clone();
    let col = headers
        .iter()
        .position(|h| h == "omega_rad_s")
        .expect("omega_rad_s column");
    rdr.records()
        .map(|r| r.expect("record")[col].parse::<f64>().expect("number"))
        .collect()
}

/// Roots of the Euler–Bernoulli cantilever frequency equation `1 + cos x cosh x = 0`, by bisection
/// in each bracket `[(k − 1)π, kπ]`, which holds exactly one root (independent of the code under
/// test).
pub fn euler_bernoulli_roots(count: usize) -> Vec<f64> {
    let f = |x: f64| 1.0 + x.cos() * x.cosh();
    (1..=count)
        .map(|k| {
            let pi = std::f64::consts::PI;
            let (mut a, mut b) = ((k as f64 - 1.0) * pi, k as f64 * pi);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if f(a) * f(m) <= 0.0 {
                    b = m;
                } else {
                    a = m;
                }
            }
            0.5 * (a + b)
        })
        .collect()
}

/// The structure of Patil's HALE wing (Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001):
/// semi-span 16 m, m = 0.75 kg/m, I = 0.1 kg·m, GJ = 1e4 N·m², flap EI = 2e4 N·m², mass centre
/// on the elastic axis; `n` equal elements, tip-load calibration.
pub fn patil_structure(n: usize) -> FullModel {
    let section = coupled(
        Profile::Uniform(2e4),
        Profile::Uniform(0.75),
        Profile::Uniform(1e4),
        Profile::Uniform(0.1),
        Profile::Uniform(0.0),
    );
    FullModel::new(
        Beam::new(
            16.0,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap(),
    )
}

/// Patil's HALE wing: [`patil_structure`] with chord 1 m, elastic axis at mid-chord,
/// ρ = 0.0889 kg/m³, c_lα = 2π.
pub fn patil_wing(
    n: usize,
    aerodynamics: flexwing::model::aero::Aerodynamics,
) -> flexwing::model::aero::Aeroelastic {
    use flexwing::model::aero::{AeroSection, Aeroelastic};
    let aero = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
    Aeroelastic::new(&patil_structure(n), &aero, 0.0889, aerodynamics, "aero").unwrap()
}

/// The structure of the Goland wing (Goland, J. Appl. Mech. 12, 1945): L = 6.096 m,
/// c = 1.8288 m, elastic axis at 33 % chord, mass centre at 43 %, EI = 9.77e6 N·m²,
/// GJ = 0.99e6 N·m², m = 35.71 kg/m, I = 8.64 kg·m about the elastic axis (the reading that gives
/// the classical torsion frequency 15.2 Hz); `n` equal elements.
pub fn goland_structure(n: usize) -> FullModel {
    let c = 1.8288;
    let section = SectionProperties {
        ei: Profile::Uniform(9.77e6),
        mass_per_length: Profile::Uniform(35.71),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(0.99e6),
            polar_inertia: Profile::Uniform(8.64),
            inertia_axis: InertiaAxis::ElasticAxis,
            offset: Profile::Uniform((0.33 - 0.43) * c),
        }),
    };
    FullModel::new(
        Beam::new(
            6.096,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap(),
    )
}

/// The Goland wing: [`goland_structure`] with sea level ρ = 1.225 kg/m³, c_lα = 2π.
pub fn goland_wing(
    n: usize,
    aerodynamics: flexwing::model::aero::Aerodynamics,
) -> flexwing::model::aero::Aeroelastic {
    use flexwing::model::aero::{AeroSection, Aeroelastic};
    let aero = AeroSection::new(Profile::Uniform(1.8288), Profile::Uniform(0.33));
    Aeroelastic::new(&goland_structure(n), &aero, 1.225, aerodynamics, "aero").unwrap()
}
