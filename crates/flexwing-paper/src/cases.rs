//! The paper's cases, built from the example case files (`examples/*.toml`), the one definition
//! that `flexwing modes/static/dynamic`, this study and the CLI's tests share. Each function says
//! how the study's case differs from its file (the paper's number of elements or of modes, a
//! longer run).

use anyhow::{Context, Result};
use flexwing::analysis::dynamics::DynamicPlan;
use flexwing::analysis::statics::StaticPlan;
use flexwing::beam::Profile;
use flexwing::model::FullModel;
use flexwing_case::{Case, Property};

/// `examples/table1.toml`: the Table 1 beam, coupled bending and torsion, n = 16.
const TABLE1: &str = include_str!("../../../examples/table1.toml");
/// `examples/paper_tip_force.toml`: Table 3, a 150 N dead tip force on the Table 4 beam.
const TIP_FORCE: &str = include_str!("../../../examples/paper_tip_force.toml");
/// `examples/paper_static.toml`: Figure 4, the swept tip force F1 and −150 N at mid-span.
const TWO_FORCES: &str = include_str!("../../../examples/paper_static.toml");
/// `examples/paper_sine.toml`: case (b), the tip force 10 sin(20 t) N from rest.
const SINE: &str = include_str!("../../../examples/paper_sine.toml");
/// `examples/paper_free_vibration.toml`: case (a), released from the 150 N static deflection.
const FREE_VIBRATION: &str = include_str!("../../../examples/paper_free_vibration.toml");

/// Reduced models of the study's static and dynamic cases: the paper's 2 (and 3), and the
/// others for the accuracy against the number of modes.
pub const MODES: [usize; 5] = [1, 2, 3, 4, 6];

fn case(text: &str, file: &str) -> Result<Case> {
    Case::parse(text, Some(file)).with_context(|| format!("the study's case {file}"))
}

/// The Table 1 beam (`examples/table1.toml`) with `n` elements.
///
/// # Errors
/// A case file that no longer parses, or `n = 0`.
pub fn table1(n: usize) -> Result<FullModel> {
    let mut c = case(TABLE1, "examples/table1.toml")?;
    c.beam.elements = Some(n);
    Ok(c.model()?)
}

/// Table 3: `examples/paper_tip_force.toml` as it is.
///
/// # Errors
/// A case file that no longer parses or converts.
pub fn tip_force() -> Result<StaticPlan> {
    Ok(case(TIP_FORCE, "examples/paper_tip_force.toml")?.static_plan()?)
}

/// Table 5 and Figure 4: `examples/paper_static.toml` with the paper's `n = 10` elements and
/// reduced models on [`MODES`].
///
/// # Errors
/// A case file that no longer parses or converts.
pub fn two_forces() -> Result<StaticPlan> {
    let mut c = case(TWO_FORCES, "examples/paper_static.toml")?;
    c.beam.elements = Some(10);
    c.statics.reduced = MODES.to_vec();
    Ok(c.static_plan()?)
}

/// Case (b), Tables 6 and 8, Figure 6: `examples/paper_sine.toml` with reduced models on
/// [`MODES`].
///
/// # Errors
/// A case file that no longer parses or converts.
pub fn sine() -> Result<DynamicPlan> {
    let mut c = case(SINE, "examples/paper_sine.toml")?;
    if let Some(d) = c.dynamic.as_mut() {
        d.reduced = MODES.to_vec();
    }
    Ok(c.dynamic_plan()?)
}

/// Case (a), Table 7 and Figure 5: `examples/paper_free_vibration.toml` released from the
/// static deflection under a tip force of `force` (N; the file's is 150 N) and run to `end_time`
/// (s; the file's is 0.2 s).
///
/// # Errors
/// A case file that no longer parses or converts, or a force or time it rejects.
pub fn free_vibration(force: f64, end_time: f64) -> Result<DynamicPlan> {
    let mut c = case(FREE_VIBRATION, "examples/paper_free_vibration.toml")?;
    let load = c
        .loads
        .first_mut()
        .context("examples/paper_free_vibration.toml: no load")?;
    load.fy = Some(Property(Profile::Uniform(force)));
    if let Some(d) = c.dynamic.as_mut() {
        d.end_time = end_time;
    }
    Ok(c.dynamic_plan()?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexwing::analysis::dynamics::Initial;
    use flexwing::model::{Force, Load};
    use flexwing::solve::TimeFunction;

    /// The study's cases are the paper's (an independent definition from the paper's tables,
    /// not from the example files: a change to a file that changes the study fails here).
    #[test]
    fn the_cases_are_the_papers() {
        let t1 = table1(32).unwrap();
        assert_eq!(t1.n_dofs(), 64);
        assert_eq!(t1.beam().length(), 16.0);
        // d0 = 0.267 m, as the mass-weighted mean over each element (round-off only).
        assert!((t1.beam().offsets()[0] - 0.267).abs() < 1e-15);
        let tip = |span: f64, fy: f64| Load::PointForce {
            span,
            force: Force::Dead { fx: 0.0, fy },
        };
        let t3 = tip_force().unwrap();
        assert_eq!(t3.model.n_dofs(), 20);
        assert_eq!(t3.loads, [tip(1.0, 150.0)]);
        assert_eq!(t3.reduced, MODES);
        let t5 = two_forces().unwrap();
        assert_eq!(t5.model.n_dofs(), 10);
        assert_eq!(t5.loads, [tip(1.0, 1.0), tip(0.5, -150.0)]);
        let scales: Vec<f64> = (0..=15).map(|k| 10.0 * k as f64).collect();
        assert_eq!(t5.point_scales(), scales);
        let b = sine().unwrap();
        assert_eq!(b.model.n_dofs(), 20);
        assert_eq!(b.loads, [tip(1.0, 10.0)]);
        let sine = TimeFunction::Sine {
            omega: 20.0,
            phase: 0.0,
        };
        assert_eq!(b.time, [Some(sine)]);
        let times: Vec<f64> = (0..=200).map(|k| k as f64 * 0.005).collect();
        assert_eq!(b.output_times, times);
        // The library's preset of case (b), the benchmarks' and examples' definition, is the
        // same case.
        let preset = flexwing::paper::sine_case(20).unwrap();
        assert_eq!(preset.model.beam(), b.model.beam());
        assert_eq!(
            (&preset.loads, &preset.time, &preset.output_times),
            (&b.loads, &b.time, &b.output_times)
        );
        assert_eq!(
            (preset.end_time, preset.gyroscopic, preset.integrator),
            (b.end_time, b.gyroscopic, b.integrator)
        );
        assert_eq!(
            flexwing::paper::table4_beam(20).unwrap().beam(),
            t3.model.beam()
        );
        assert_eq!(flexwing::paper::table1_beam(32).unwrap().beam(), t1.beam());
        let a = free_vibration(10.0, 30.0).unwrap();
        assert_eq!(a.model.n_dofs(), 10);
        assert_eq!(a.loads, [tip(1.0, 10.0)]);
        assert_eq!(a.time, [None]);
        assert_eq!(a.initial, Initial::Static { loads: vec![0] });
        assert_eq!(a.output_times.len(), 6001);
        assert_eq!(a.output_times[6000], 30.0);
        for beam in [&t3.model, &t5.model, &b.model, &a.model] {
            let total: f64 = beam.beam().masses().iter().sum();
            assert!((total - 0.2).abs() < 1e-12);
        }
    }
}
