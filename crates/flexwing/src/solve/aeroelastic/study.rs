//! Flutter and divergence against a load level: how the flutter speed falls as the wing bends
//! (issue 20; docs/chain3d-model.md, "Strip aerodynamics"). At every level of the swept load — a
//! dead vertical tip force, a gravity factor, a root angle — the flutter analysis about the
//! equilibria of that level (`flutter.rs`: the equilibrium is solved at every speed, or once when
//! it does not move with the speed), the static sweep over the same speeds with its divergence
//! (`statics.rs`), and the tip deflection at rest and at the flutter speed.
//!
//! The study is a plain function returning data; the front ends draw its tables and plots.

use super::flutter::{flutter_polled, FlutterOptions, FlutterSolution};
use super::statics::{static_sweep, AeroStaticOptions, Divergence};
use crate::error::{InputError, SolveError};
use crate::model::aero::{AeroStructure, Aeroelastic, FlightCondition};
use crate::model::{Force, Load};

/// The load swept by a [`deflection_study`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StudyParameter {
    /// A dead vertical force at the tip (N, up positive), added to the plan's loads.
    TipForce,
    /// Gravity `level · g` (m/s², along the ground's vertical), replacing the plan's gravity.
    GravityFactor {
        /// The gravitational acceleration of level 1 (m/s²), e.g. 9.81.
        g: f64,
    },
    /// The root angle of attack (rad), replacing the plan's.
    RootAngle,
}

/// A flutter study against a load level, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct DeflectionStudyOptions {
    /// The flutter analysis run at every level (speeds, branches, method, other loads,
    /// damping, tolerance); the swept load replaces or adds to its loads, gravity or root angle.
    pub flutter: FlutterOptions,
    /// The load swept.
    pub parameter: StudyParameter,
    /// Its levels (N, a factor of `g`, or rad), in the order run.
    pub levels: Vec<f64>,
    /// Also the static sweep's divergence speed (a static equilibrium at each of
    /// `divergence_points` of the flutter speeds, with its frozen-state divergence pressure; the
    /// divergence is bracketed between two of them, or between the last equilibrium and the
    /// speed where none is stable, and refined to `divergence_tolerance`: its accuracy does not
    /// depend on their spacing). Without it the statics are solved at rest and at the flutter
    /// speed only.
    pub divergence: bool,
    /// How many of the flutter speeds the static sweep visits (at least 1: evenly picked, the
    /// last included; all of them if there are fewer). Default 5.
    pub divergence_points: usize,
    /// Relative tolerance of the divergence speed (on the dynamic pressure), in `(0, 1)`.
    pub divergence_tolerance: f64,
}

impl DeflectionStudyOptions {
    /// The study of `parameter` at `levels` with the flutter analysis `flutter`, with the
    /// divergence to the flutter analysis' tolerance.
    pub fn new(flutter: FlutterOptions, parameter: StudyParameter, levels: Vec<f64>) -> Self {
        let divergence_tolerance = flutter.tolerance;
        Self {
            flutter,
            parameter,
            levels,
            divergence: true,
            divergence_points: 5,
            divergence_tolerance,
        }
    }

    /// The flutter speeds the static sweep visits: `divergence_points` of them, evenly picked
    /// with the last.
    fn divergence_speeds(&self) -> Vec<f64> {
        let speeds = &self.flutter.speeds;
        let m = self.divergence_points.min(speeds.len());
        (1..=m)
            .map(|k| speeds[(k * speeds.len()).div_ceil(m) - 1])
            .collect()
    }

    /// The flutter analysis of level `level` of a wing of span `length`.
    fn plan_at(&self, level: f64, length: f64) -> FlutterOptions {
        let mut plan = self.flutter.clone();
        match self.parameter {
            StudyParameter::TipForce => plan.loads.push(Load::PointForce {
                span: length,
                force: Force::Dead { fx: 0.0, fy: level },
            }),
            StudyParameter::GravityFactor { g } => plan.gravity = Some(level * g),
            StudyParameter::RootAngle => plan.root_angle = level,
        }
        plan
    }

    /// Check the study against a model of `n_dofs` coordinates and span `length`; `field`
    /// prefixes the fields.
    ///
    /// # Errors
    /// No levels, a level that is not finite or gives an invalid flight condition, a gravity of
    /// level 1 that is not finite and positive, no divergence points, a divergence tolerance
    /// outside `(0, 1)`, an invalid flutter plan.
    pub fn validate(&self, field: &str, n_dofs: usize, length: f64) -> Result<(), InputError> {
        if self.levels.is_empty() {
            return Err(InputError::new(
                format!("{field}.levels"),
                "needs at least one level",
            ));
        }
        if let StudyParameter::GravityFactor { g } = self.parameter {
            if !(g.is_finite() && g > 0.0) {
                return Err(InputError::new(
                    format!("{field}.parameter.g"),
                    format!(
                        "must be a finite positive acceleration (m/s²), got {}",
                        crate::text::short(g)
                    ),
                ));
            }
        }
        for (i, &level) in self.levels.iter().enumerate() {
            let name = format!("{field}.levels[{i}]");
            if !level.is_finite() {
                return Err(InputError::new(
                    name,
                    format!("must be finite, got {}", crate::text::short(level)),
                ));
            }
            crate::magnitude::check(&name, "", level)?;
            let plan = self.plan_at(level, length);
            FlightCondition {
                speed: 0.0,
                root_angle: plan.root_angle,
                gravity: plan.gravity,
            }
            .validate(&name)?;
        }
        if self.divergence_points == 0 {
            return Err(InputError::new(
                format!("{field}.divergence_points"),
                "must be at least 1",
            ));
        }
        if !(self.divergence_tolerance > 0.0 && self.divergence_tolerance < 1.0) {
            return Err(InputError::new(
                format!("{field}.divergence_tolerance"),
                format!(
                    "must be in (0, 1), got {}",
                    crate::text::short(self.divergence_tolerance)
                ),
            ));
        }
        self.flutter.validate(&format!("{field}.flutter"), n_dofs)
    }
}

/// The study at one level.
#[derive(Debug, Clone, PartialEq)]
pub struct DeflectionPoint {
    /// The level of the swept load.
    pub level: f64,
    /// Tip displacement of the elastic axis at rest (`U = 0`), `(dx, dy, dz)` (m): the
    /// deflection under the level's loads and gravity (zero for a root angle alone).
    pub tip: [f64; 3],
    /// Tip twist at rest (rad, nose-up).
    pub tip_twist: f64,
    /// Tip displacement at the flutter speed (m), `None` without a flutter point or an
    /// equilibrium there: with a root angle the wing bends under its own lift.
    pub tip_at_flutter: Option<[f64; 3]>,
    /// The flutter analysis (V-g data, crossings, flutter point, why it stopped).
    pub flutter: FlutterSolution,
    /// The divergence speed of the static sweep, if asked for and found.
    pub divergence: Option<Divergence>,
    /// Where and why the static sweep stopped, if it did (past the divergence speed it does).
    pub statics_stopped: Option<(f64, SolveError)>,
}

/// What a [`deflection_study`] produced.
#[derive(Debug, Clone, PartialEq)]
pub struct DeflectionStudySolution {
    /// One point per level reached, in the order of the levels.
    pub points: Vec<DeflectionPoint>,
    /// The caller's poll stopped the study before the level after the last point.
    pub interrupted: bool,
}

/// Flutter and divergence of `aero` at every level of `study.parameter`: "how does the flutter
/// speed fall as the wing bends?". `keep_going` hears the fraction done (levels, and speeds
/// within a level's flutter analysis) and stops the study when it returns `false`, keeping the
/// levels done (a level's analysis cut short keeps its data, with its stop).
///
/// # Errors
/// An invalid study (`field` prefixes the fields). Failures of an analysis are in its point
/// (the flutter analysis' `stopped`, the static sweep's `statics_stopped`).
pub fn deflection_study<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    study: &DeflectionStudyOptions,
    field: &str,
    keep_going: &mut dyn FnMut(f64) -> bool,
) -> Result<DeflectionStudySolution, InputError> {
    let length = aero.chain().length();
    study.validate(field, aero.structure().n_dofs(), length)?;
    let count = study.levels.len() as f64;
    let mut points = Vec::with_capacity(study.levels.len());
    let mut interrupted = false;
    for (i, &level) in study.levels.iter().enumerate() {
        let done = i as f64 / count;
        if !keep_going(done) {
            interrupted = true;
            break;
        }
        let plan = study.plan_at(level, length);
        let name = format!("{field}.levels[{i}]");
        let mut cancelled = false;
        let flutter = flutter_polled(aero, &plan, &name, &mut |f| {
            let go = keep_going(done + f / count);
            cancelled |= !go;
            go
        })?;
        // The statics: at rest, at the flutter speed, and over the speeds for the divergence.
        let u_flutter = flutter.flutter.map(|c| c.speed);
        let mut speeds = vec![0.0];
        if study.divergence {
            speeds.extend(study.divergence_speeds());
        }
        speeds.extend(u_flutter);
        speeds.sort_by(f64::total_cmp);
        speeds.dedup();
        let statics = static_sweep(
            aero,
            &AeroStaticOptions {
                speeds: speeds.clone(),
                root_angle: plan.root_angle,
                gravity: plan.gravity,
                loads: plan.loads.clone(),
                options: plan.static_options.clone(),
                divergence_tolerance: study.divergence_tolerance,
            },
            &name,
            &mut |_| {},
        )?;
        let rest = statics.points.first();
        let point = DeflectionPoint {
            level,
            tip: rest.map_or([f64::NAN; 3], |p| p.tip),
            tip_twist: rest.map_or(f64::NAN, |p| p.tip_twist),
            tip_at_flutter: u_flutter
                .and_then(|u| statics.points.iter().find(|p| p.speed == u).map(|p| p.tip)),
            flutter,
            divergence: if study.divergence {
                statics.divergence
            } else {
                None
            },
            statics_stopped: statics.stopped.map(|(k, e)| (speeds[k], e)),
        };
        points.push(point);
        if cancelled {
            interrupted = true;
            break;
        }
    }
    if !interrupted {
        keep_going(1.0);
    }
    Ok(DeflectionStudySolution {
        points,
        interrupted,
    })
}
