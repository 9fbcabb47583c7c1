//! The classical wings of aeroelastic validation, ready to use for examples and benchmarks. The
//! library's validation tests define their own copies, so that a mistake here cannot hide behind
//! them.
//!
//! ```
//! use flexwing::model::aero::Aerodynamics;
//! let wing = flexwing::wings::patil_wing(16, Aerodynamics::Peters { states: 6 })?;
//! assert_eq!(wing.n_aero_states(), 96);
//! # Ok::<(), flexwing::InputError>(())
//! ```

use crate::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use crate::error::InputError;
use crate::model::aero::{AeroSection, Aerodynamics, Aeroelastic};
use crate::model::FullModel;

fn wing(
    length: f64,
    n: usize,
    (ei, gj, m, inertia, d0): (f64, f64, f64, f64, f64),
    inertia_axis: InertiaAxis,
    (chord, x_ea, density): (f64, f64, f64),
    aerodynamics: Aerodynamics,
) -> Result<Aeroelastic, InputError> {
    let section = SectionProperties {
        ei: Profile::Uniform(ei),
        mass_per_length: Profile::Uniform(m),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(gj),
            polar_inertia: Profile::Uniform(inertia),
            inertia_axis,
            offset: Profile::Uniform(d0),
        }),
    };
    let full = FullModel::new(Beam::new(
        length,
        &section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )?);
    let aero = AeroSection::new(Profile::Uniform(chord), Profile::Uniform(x_ea));
    Aeroelastic::new(&full, &aero, density, aerodynamics, "aero")
}

/// Patil's HALE wing (Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001): semi-span 16 m, chord
/// 1 m, elastic axis and mass centre at mid-chord, `m = 0.75 kg/m`, `I = 0.1 kg·m`,
/// `GJ = 1e4 N·m²`, flap `EI = 2e4 N·m²`, `ρ = 0.0889 kg/m³` (20 km), `c_lα = 2π`; `n` equal
/// elements. Published linear flutter 32.21 m/s at 22.61 rad/s, divergence 37.29 m/s.
pub fn patil_wing(n: usize, aerodynamics: Aerodynamics) -> Result<Aeroelastic, InputError> {
    wing(
        16.0,
        n,
        (2e4, 1e4, 0.75, 0.1, 0.0),
        InertiaAxis::MassCentre,
        (1.0, 0.5, 0.0889),
        aerodynamics,
    )
}

/// The Goland wing (Goland, J. Appl. Mech. 12, 1945): `L = 6.096 m`, `c = 1.8288 m`, elastic
/// axis at 33 % chord, mass centre at 43 % (`d0 = −0.18288 m`), `EI = 9.77e6 N·m²`,
/// `GJ = 0.99e6 N·m²`, `m = 35.71 kg/m`, `I = 8.64 kg·m` about the elastic axis, sea level
/// `ρ = 1.225 kg/m³`, `c_lα = 2π`. Classical strip-theory flutter about 137 m/s near 70 rad/s.
/// (With `I` about the elastic axis the in-vacuo torsion frequency is the classical 15.2 Hz and
/// the p-k flutter point 137.2 m/s at 70.1 rad/s; read about the mass centre, as some sources
/// print it, it gives 14.2 Hz and 128 m/s.)
pub fn goland_wing(n: usize, aerodynamics: Aerodynamics) -> Result<Aeroelastic, InputError> {
    let c = 1.8288;
    wing(
        6.096,
        n,
        (9.77e6, 0.99e6, 35.71, 8.64, (0.33 - 0.43) * c),
        InertiaAxis::ElasticAxis,
        (c, 0.33, 1.225),
        aerodynamics,
    )
}
