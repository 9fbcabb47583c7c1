//! Static aeroelastic equilibria of the full model and of reduced models at one flight
//! condition or along a sweep in speed, each point continued from the previous one with load
//! stepping in dynamic pressure, and the divergence speed
//! ([`crate::solve::aeroelastic::static_sweep`], docs/aeroelastic-model.md §5). The aerodynamics
//! are steady here whatever the plan's model: a static equilibrium has no motion to lag.

use std::time::Instant;

use super::{build, models, Aero, Built, Fields, SpeedSweep};
use crate::analysis::{ModelKind, Progress, Status, Stop};
use crate::error::{Error, InputError};
use crate::model::aero::{Aeroelastic, FlightCondition, PlanarStructure};
use crate::model::{FullModel, Load, Shape};
use crate::solve::aeroelastic::{static_sweep_polled, AeroStaticOptions, Divergence};
use crate::solve::{StaticOptions, StaticStats};

/// Relative tolerance of the divergence dynamic pressure when a sweep brackets it.
pub const DIVERGENCE_TOLERANCE: f64 = 1e-8;

/// A static aeroelastic analysis. Build it with [`AeroStaticPlan::new`], set the fields, check it
/// with [`AeroStaticPlan::validate`].
#[derive(Debug, Clone)]
pub struct AeroStaticPlan {
    /// The full model (in vacuo).
    pub model: FullModel,
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// The flight: its speed is the one point solved without a sweep; root angle and gravity
    /// hold at every point.
    pub flight: FlightCondition,
    /// A sweep in speed, in place of the flight's speed.
    pub sweep: Option<SpeedSweep>,
    /// Other loads, at their full value at every point.
    pub loads: Vec<Load>,
    /// Solve the full model. Default `true`.
    pub full: bool,
    /// Reduced models on the first `r` wet modes, one per entry.
    pub reduced: Vec<usize>,
    /// Reduced models on listed wet modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// Newton's options.
    pub options: StaticOptions,
    /// Relative tolerance of the divergence dynamic pressure, in `(0, 1)`.
    pub divergence_tolerance: f64,
}

impl AeroStaticPlan {
    /// The full model in the flight `flight`, no sweep, no other loads, default options.
    pub fn new(model: FullModel, aero: Aero, flight: FlightCondition) -> Self {
        Self {
            model,
            aero,
            flight,
            sweep: None,
            loads: Vec::new(),
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            options: StaticOptions::default(),
            divergence_tolerance: DIVERGENCE_TOLERANCE,
        }
    }

    /// The speeds solved: the sweep's, or the flight's speed.
    pub fn speeds(&self) -> Vec<f64> {
        self.sweep
            .as_ref()
            .map_or_else(|| vec![self.flight.speed], |s| s.speeds.clone())
    }

    /// Check the plan under the caller's names.
    ///
    /// # Errors
    /// Invalid section data, air or aerodynamic model, flight, speeds, loads, options, reduced
    /// models on modes the model does not have, nothing to solve.
    pub fn validate(&self, fields: &Fields) -> Result<(), InputError> {
        let wing = self.aero.wing(&self.model, fields.aero)?;
        check_flight(&self.flight, self.sweep.as_ref(), fields)?;
        self.model.apply(&self.loads, fields.loads)?;
        self.options.validate(fields.statics)?;
        check_divergence_tolerance(self.divergence_tolerance, fields)?;
        let n = wing.structure().n_dofs();
        models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            n,
            fields.analysis,
        )?;
        Ok(())
    }

    /// The models solved, in order: full (if asked), `reduced`, `reduced_modes`.
    ///
    /// # Errors
    /// As [`AeroStaticPlan::validate`] for the models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            self.model.n_dofs(),
            "",
        )
    }
}

/// The flight of a static aeroelastic plan: `flight` at its speed, or at each speed of `sweep`
/// (the planar [`AeroStaticPlan`] and the 3-D chain's).
pub(crate) fn check_flight(
    flight: &FlightCondition,
    sweep: Option<&SpeedSweep>,
    fields: &Fields,
) -> Result<(), InputError> {
    let name = fields.flight();
    match sweep {
        None => flight.validate(&name),
        Some(sweep) => {
            sweep.validate(&format!("{}.sweep.speeds", fields.aero), false)?;
            FlightCondition {
                speed: sweep.speeds[0],
                ..*flight
            }
            .validate(&name)
        }
    }
}

/// `{analysis}.divergence_tolerance` in `(0, 1)`.
pub(crate) fn check_divergence_tolerance(
    tolerance: f64,
    fields: &Fields,
) -> Result<(), InputError> {
    if tolerance > 0.0 && tolerance < 1.0 {
        Ok(())
    } else {
        Err(InputError::new(
            fields.analysis("divergence_tolerance"),
            format!("must be in (0, 1), got {}", crate::text::short(tolerance)),
        ))
    }
}

/// One static aeroelastic equilibrium, as nodal quantities of the full model.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroPoint {
    /// Free-stream speed (m/s).
    pub speed: f64,
    /// Dynamic pressure `½ρU²` (Pa).
    pub dynamic_pressure: f64,
    /// The deformed shape.
    pub shape: Shape,
    /// Joint rotations of the full model (rad).
    pub q: Vec<f64>,
    /// Total aerodynamic force along the ground's vertical (N).
    pub lift: f64,
    /// Root bending moment, the clamp spring's moment `K_θ,1 q_1` (N·m).
    pub root_bending_moment: f64,
    /// Hinge moment of each control surface (N·m, positive trailing edge down), in the order of
    /// the surfaces of [`Aero::section`].
    pub hinge_moments: Vec<f64>,
    /// Divergence pressure of the frozen state (Pa), `None` if no real mode diverges.
    pub divergence_pressure: Option<f64>,
    /// Solver counters of this point.
    pub stats: StaticStats,
    /// Distance of the tip from the full model's at the same speed (m); reduced models only.
    pub tip_difference: Option<f64>,
}

impl AeroPoint {
    /// Tip position and twist `(x, y, twist)`.
    pub fn tip(&self) -> (f64, f64, f64) {
        self.shape.tip()
    }
}

/// The equilibria of one model.
#[derive(Debug, Clone)]
pub struct AeroStaticRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// Wall time of the sweep (s).
    pub wall_time_s: f64,
    /// The equilibria found, in speed order from the first.
    pub points: Vec<AeroPoint>,
    /// The divergence speed, where the sweep finds it (see
    /// [`crate::solve::aeroelastic::AeroStaticSolution::divergence`]).
    pub divergence: Option<Divergence>,
    /// Whether every speed was reached, or where and why the sweep stopped
    /// ([`Stop::SpeedPoint`]).
    pub status: Status,
}

/// What a static aeroelastic analysis found.
#[derive(Debug, Clone)]
pub struct AeroStaticOutcome {
    /// One run per model, in the order of [`AeroStaticPlan::models`].
    pub runs: Vec<AeroStaticRun>,
}

impl AeroStaticOutcome {
    /// Whether every model reached every speed.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
    }

    /// Wall time of `run` over the first model's.
    pub fn ratio_to_first(&self, run: &AeroStaticRun) -> Option<f64> {
        let first = self.runs.first()?;
        (first.wall_time_s > 0.0).then(|| run.wall_time_s / first.wall_time_s)
    }
}

/// Run the static aeroelastic analysis of `plan`.
///
/// # Errors
/// An invalid plan (fields named relative to the plan, [`Fields::RELATIVE`]), or the wet modes
/// of a reduced model not found. A sweep that stops is in its run's [`Status`].
///
/// ```
/// use flexwing::analysis::aero::{statics, Aero};
/// use flexwing::analysis::NoProgress;
/// use flexwing::beam::Profile;
/// use flexwing::model::aero::{AeroSection, Aerodynamics, FlightCondition};
/// let wing = flexwing::wings::patil_wing(16, Aerodynamics::Steady)?;
/// let aero = Aero {
///     section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
///     density: 0.0889,
///     aerodynamics: Aerodynamics::Steady,
/// };
/// let flight = FlightCondition { speed: 20.0, root_angle: 0.02, gravity: None };
/// let plan = statics::AeroStaticPlan::new(wing.full().clone(), aero, flight);
/// let outcome = statics::run(&plan, &mut NoProgress)?;
/// let (_, tip_y, _) = outcome.runs[0].points[0].tip();
/// assert!(tip_y > 0.0 && outcome.runs[0].points[0].lift > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(plan: &AeroStaticPlan, progress: &mut dyn Progress) -> Result<AeroStaticOutcome, Error> {
    let fields = Fields::RELATIVE;
    plan.validate(&fields)?;
    let full = plan.aero.wing(&plan.model, fields.aero)?;
    let kinds = plan.models()?;
    let sweep = AeroStaticOptions {
        speeds: plan.speeds(),
        root_angle: plan.flight.root_angle,
        gravity: plan.flight.gravity,
        loads: plan.loads.clone(),
        options: plan.options.clone(),
        divergence_tolerance: plan.divergence_tolerance,
    };
    let mut runs = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        let built = build(&full, kind)?;
        progress.start(k, kinds.len(), &kind.label());
        let run = match &built {
            Built::Full => sweep_model(kind, &full, &sweep, progress),
            Built::Reduced(rom) => sweep_model(kind, rom.as_ref(), &sweep, progress),
        }?;
        progress.finish();
        runs.push(run);
    }
    compare_tips(&mut runs);
    Ok(AeroStaticOutcome { runs })
}

/// The sweep of one model, timed.
pub(crate) fn sweep_model<M: PlanarStructure>(
    kind: &ModelKind,
    aero: &Aeroelastic<M>,
    sweep: &AeroStaticOptions,
    progress: &mut dyn Progress,
) -> Result<AeroStaticRun, InputError> {
    let start = Instant::now();
    let outcome = static_sweep_polled(aero, sweep, "", &mut |f| {
        progress.advance(f);
        !progress.cancelled()
    })?;
    let wall_time_s = start.elapsed().as_secs_f64();
    let full = aero.full();
    let points: Vec<AeroPoint> = outcome
        .points
        .into_iter()
        .map(|p| AeroPoint {
            speed: p.speed,
            dynamic_pressure: p.dynamic_pressure,
            shape: full.shape(&p.q),
            q: p.q,
            lift: p.lift,
            root_bending_moment: p.root_bending_moment,
            hinge_moments: p.hinge_moments,
            divergence_pressure: p.divergence_pressure,
            stats: p.stats,
            tip_difference: None,
        })
        .collect();
    let status = match outcome.stopped {
        None if outcome.interrupted => Status::Stopped(Stop::SweepInterrupted {
            done: points.len(),
            points: sweep.speeds.len(),
        }),
        None => Status::Complete,
        Some((point, error)) => Status::Stopped(Stop::SpeedPoint {
            point,
            points: sweep.speeds.len(),
            speed: sweep.speeds[point],
            error,
        }),
    };
    Ok(AeroStaticRun {
        kind: kind.clone(),
        dofs: aero.structure().n_dofs(),
        wall_time_s,
        points,
        divergence: outcome.divergence,
        status,
    })
}

/// Each reduced model's tip distance from the full model's, speed by speed.
fn compare_tips(runs: &mut [AeroStaticRun]) {
    let Some(full) = runs.iter().position(|r| r.kind == ModelKind::Full) else {
        return;
    };
    let tips: Vec<(f64, f64, f64)> = runs[full].points.iter().map(AeroPoint::tip).collect();
    for run in runs.iter_mut().filter(|r| r.kind.modes().is_some()) {
        for (p, reference) in run.points.iter_mut().zip(&tips) {
            let (x, y, _) = p.tip();
            p.tip_difference = Some((x - reference.0).hypot(y - reference.1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::patil;
    use super::*;
    use crate::analysis::NoProgress;
    use crate::model::aero::Aerodynamics;

    fn plan() -> AeroStaticPlan {
        let (model, aero) = patil(8, Aerodynamics::Steady);
        let flight = FlightCondition {
            speed: 20.0,
            root_angle: 0.03,
            gravity: Some(9.80665),
        };
        AeroStaticPlan::new(model, aero, flight)
    }

    /// The plan's runs are those of the library's sweep (the same solver, model by model): a
    /// regression test of the wrapper, and the reduced model on every wet mode is the full
    /// model (docs/aeroelastic-model.md §5, tested to round-off in the library).
    #[test]
    fn runs_are_the_solvers_sweeps_and_all_modes_reproduce_the_full_model() {
        let mut p = plan();
        p.sweep = Some(SpeedSweep {
            speeds: vec![0.0, 10.0, 20.0, 30.0],
        });
        p.reduced = vec![16];
        let out = run(&p, &mut NoProgress).unwrap();
        assert!(out.is_complete());
        let direct = crate::solve::aeroelastic::static_sweep(
            &p.aero.wing(&p.model, "aero").unwrap(),
            &AeroStaticOptions {
                speeds: p.speeds(),
                root_angle: 0.03,
                gravity: Some(9.80665),
                loads: vec![],
                options: StaticOptions::default(),
                divergence_tolerance: DIVERGENCE_TOLERANCE,
            },
            "s",
            &mut |_| {},
        )
        .unwrap();
        for (a, b) in out.runs[0].points.iter().zip(&direct.points) {
            assert_eq!(a.q, b.q);
            assert_eq!(a.lift, b.lift);
        }
        // Gravity pulls the wing down at rest; the lift lifts it at speed.
        assert!(out.runs[0].points[0].tip().1 < 0.0);
        assert!(out.runs[0].points[3].tip().1 > 0.0);
        // All 16 wet modes: the full model to round-off (measured 4e-15 m).
        let d = out.runs[1].points.iter().map(|p| p.tip_difference.unwrap());
        assert!(d.fold(0.0, f64::max) < 1e-10);
    }

    #[test]
    fn errors_name_the_callers_fields() {
        let fields = Fields {
            loads: "loads",
            aero: "aero",
            statics: "static",
            analysis: "static",
        };
        type Change = Box<dyn Fn(&mut AeroStaticPlan)>;
        let cases: Vec<(Change, &str)> = vec![
            (
                Box::new(|p| p.aero.density = 0.0),
                "aero.density: must be a finite positive",
            ),
            (
                Box::new(|p| p.aero.aerodynamics = Aerodynamics::Peters { states: 0 }),
                "aero.aerodynamics.states:",
            ),
            (
                Box::new(|p| p.flight.speed = -1.0),
                "aero.flight.speed: must be a finite non-negative",
            ),
            (
                Box::new(|p| p.flight.root_angle = 2.0),
                "aero.flight.root_angle:",
            ),
            (
                Box::new(|p| {
                    p.sweep = Some(SpeedSweep {
                        speeds: vec![1.0, 0.5],
                    })
                }),
                "aero.sweep.speeds[1]: 0.5 is not above",
            ),
            (
                Box::new(|p| p.loads.push(Load::Gravity { g: f64::NAN })),
                "loads[0].g:",
            ),
            (
                Box::new(|p| p.options.tolerance = -1.0),
                "static.tolerance:",
            ),
            (Box::new(|p| p.reduced = vec![17]), "static.reduced[0]:"),
            (Box::new(|p| p.full = false), "static.full: nothing to run"),
        ];
        for (change, expected) in cases {
            let mut p = plan();
            change(&mut p);
            let msg = p.validate(&fields).unwrap_err().to_string();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }
}
