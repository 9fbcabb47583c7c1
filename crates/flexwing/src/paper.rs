//! The beams and the dynamic case (b) of the results section of Veronese, Ribeiro & Moreira
//! (COBEM 2021), ready to use: the one definition of the benchmarks and examples. The paper study
//! (`flexwing-paper`) builds the same cases from the example case files and checks them against
//! these; the library's validation tests define their own copies from the paper, on purpose, so
//! that a mistake here cannot hide behind them.
//!
//! ```
//! let model = flexwing::paper::table4_beam(20)?;
//! assert_eq!(model.n_dofs(), 20);
//! # Ok::<(), flexwing::InputError>(())
//! ```

use crate::analysis::dynamics::DynamicPlan;
use crate::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use crate::error::InputError;
use crate::model::{Force, FullModel, Load};
use crate::solve::TimeFunction;

/// Span of the Table 1 beam (m).
pub const TABLE1_LENGTH: f64 = 16.0;
/// Span of the Table 4 beam (m).
pub const TABLE4_LENGTH: f64 = 1.0;

/// Section of the Table 1 beam (coupled bending–torsion): `EI = 2e4` N·m², `GJ = 1e3` N·m²,
/// `m = 0.75` kg/m, `d0 = 0.267` m, and the polar inertia of model.md item 6, `I_cg = 0.1` kg·m
/// about the mass centre (Table 1's printed 0.75 does not give Table 2).
pub fn table1_section() -> SectionProperties {
    SectionProperties {
        ei: Profile::Uniform(2e4),
        mass_per_length: Profile::Uniform(0.75),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(1e3),
            polar_inertia: Profile::Uniform(0.1),
            inertia_axis: InertiaAxis::MassCentre,
            offset: Profile::Uniform(0.267),
        }),
    }
}

/// Section of the Table 4 beam (bending only): `EI = 50` N·m², `m = 0.2` kg/m.
pub fn table4_section() -> SectionProperties {
    SectionProperties {
        ei: Profile::Uniform(50.0),
        mass_per_length: Profile::Uniform(0.2),
        torsion: None,
    }
}

/// The Table 1 beam with `n` equal elements and the paper's tip-load calibration.
///
/// # Errors
/// `n = 0` or more than [`crate::beam::MAX_ELEMENTS`] (field `beam.elements`).
pub fn table1_beam(n: usize) -> Result<FullModel, InputError> {
    model(TABLE1_LENGTH, &table1_section(), n)
}

/// The Table 4 beam with `n` equal elements and the paper's tip-load calibration.
///
/// # Errors
/// `n = 0` or more than [`crate::beam::MAX_ELEMENTS`] (field `beam.elements`).
pub fn table4_beam(n: usize) -> Result<FullModel, InputError> {
    model(TABLE4_LENGTH, &table4_section(), n)
}

/// A dead vertical force `fy` (N) at the tip of the Table 4 beam.
pub fn table4_tip_force(fy: f64) -> Load {
    Load::PointForce {
        span: TABLE4_LENGTH,
        force: Force::Dead { fx: 0.0, fy },
    }
}

/// Case (b), section 5.2.5 (Figure 6, Table 8): the Table 4 beam with `n` elements, from rest,
/// under the dead tip force `10 sin(20 t)` N, 1 s, outputs every 5 ms, the full model with the
/// exact gyroscopic term and the default integrator (as `examples/paper_sine.toml` without its
/// reduced models).
///
/// # Errors
/// As [`table4_beam`].
pub fn sine_case(n: usize) -> Result<DynamicPlan, InputError> {
    let times = (0..=200).map(|k| k as f64 * 0.005).collect();
    let mut plan = DynamicPlan::new(table4_beam(n)?, vec![table4_tip_force(10.0)], 1.0, times);
    plan.time = vec![Some(TimeFunction::Sine {
        omega: 20.0,
        phase: 0.0,
    })];
    Ok(plan)
}

fn model(length: f64, section: &SectionProperties, n: usize) -> Result<FullModel, InputError> {
    let beam = Beam::new(
        length,
        section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )?;
    Ok(FullModel::new(beam))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beams_have_the_papers_dimensions() {
        let t1 = table1_beam(16).unwrap();
        assert_eq!(t1.n_dofs(), 32);
        assert!(t1.has_torsion());
        let t4 = table4_beam(10).unwrap();
        assert_eq!(t4.n_dofs(), 10);
        let total: f64 = t4.beam().masses().iter().sum();
        assert!((total - 0.2).abs() < 1e-12);
        assert!(table4_beam(0).is_err());
        let b = sine_case(20).unwrap();
        assert!(b.validate("loads", "dynamic").is_ok());
        assert_eq!(b.output_times.len(), 201);
        assert_eq!(b.output_times[200], 1.0);
    }
}
