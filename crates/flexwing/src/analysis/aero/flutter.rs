//! Flutter along a sweep in speed, for the full model and reduced models on its wet modes:
//! the static equilibrium and its divergence pressure at every speed
//! ([`crate::solve::aeroelastic::static_sweep`]), the tracked branches (V-g and V-ω data), the
//! onset and offset of every unstable branch refined to the plan's tolerance
//! ([`crate::solve::aeroelastic::flutter`]), and optionally the same with the p-k method and
//! Theodorsen's function, the frequency-domain check of the finite-state models
//! (docs/aeroelastic-model.md §5).
//!
//! A branch already unstable at the first speed of the sweep has no onset in it: the run lists it
//! in [`FlutterRun::unstable_at_start`] and gives no flutter speed ([`FlutterRun::flutter`] is
//! `None`), never a number that would read as one (the quasi-steady model on an elastic axis at
//! or aft of mid-chord).

use std::time::Instant;

use super::statics::{sweep_model, AeroPoint};
use super::{build, models, Aero, Built, Fields, SpeedSweep};
use crate::analysis::{ModelKind, Note, Progress, Status, Stop};
use crate::error::{Error, InputError};
use crate::model::aero::{Aeroelastic, FlightCondition, PlanarStructure};
use crate::model::{FullModel, Load};
use crate::solve::aeroelastic::{
    flutter_polled, AeroStaticOptions, Branch, Crossing, Divergence, FlutterMethod, FlutterOptions,
    FlutterSolution, FlutterStats,
};
use crate::solve::{Damping, StaticOptions};

/// Branches tracked when the plan does not say: `min(6, n_dofs)`.
pub const DEFAULT_MODES: usize = 6;

/// A flutter analysis. Build it with [`FlutterPlan::new`], set the fields, check it with
/// [`FlutterPlan::validate`].
#[derive(Debug, Clone)]
pub struct FlutterPlan {
    /// The full model (in vacuo).
    pub model: FullModel,
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// Root angle and gravity, at every speed (its speed is not used: the sweep gives them).
    pub flight: FlightCondition,
    /// The speeds of the V-g data (positive, increasing); required (`{aero}.sweep`).
    pub sweep: Option<SpeedSweep>,
    /// Other loads, at their full value at every speed.
    pub loads: Vec<Load>,
    /// Analyse the full model. Default `true`.
    pub full: bool,
    /// Reduced models on the first `r` wet modes, one per entry.
    pub reduced: Vec<usize>,
    /// Reduced models on listed wet modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// Number of branches tracked, from the lowest wet modes at `U = 0`; `None`:
    /// `min(`[`DEFAULT_MODES`]`, dofs)` for each model.
    pub modes: Option<usize>,
    /// Relative tolerance of the flutter and divergence speeds, in `(0, 1)`.
    pub tolerance: f64,
    /// Also run the p-k method with Theodorsen's function (needs an unsteady model).
    pub pk: bool,
    /// Options of the static solver for the equilibria.
    pub static_options: StaticOptions,
}

impl FlutterPlan {
    /// The full model in `aero` through `speeds`, `min(6, dofs)` branches, tolerance 1e-6, no
    /// root angle, gravity or loads.
    pub fn new(model: FullModel, aero: Aero, speeds: Vec<f64>) -> Self {
        Self {
            model,
            aero,
            flight: FlightCondition::at_speed(0.0),
            sweep: Some(SpeedSweep { speeds }),
            loads: Vec::new(),
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            modes: None,
            tolerance: 1e-6,
            pk: false,
            static_options: StaticOptions::default(),
        }
    }

    /// Check the plan under the caller's names.
    ///
    /// # Errors
    /// Invalid section data, air or aerodynamic model, root angle, gravity, speeds (missing, or
    /// not positive and increasing), loads, options; a number of branches outside `1 ..= dofs`
    /// of some model; the p-k check with steady aerodynamics; reduced models on modes the model
    /// does not have; nothing to run.
    pub fn validate(&self, fields: &Fields) -> Result<(), InputError> {
        let wing = self.aero.wing(&self.model, fields.aero)?;
        check_sweep(self.sweep.as_ref(), &self.flight, fields)?;
        self.model.apply(&self.loads, fields.loads)?;
        check_solver(
            &self.static_options,
            self.tolerance,
            self.pk,
            &self.aero,
            fields,
        )?;
        let n = wing.structure().n_dofs();
        let kinds = models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            n,
            fields.analysis,
        )?;
        if let Some(count) = self.modes {
            let smallest = kinds.iter().map(|k| dofs_of(k, n)).min().unwrap_or(n);
            if !(1..=smallest).contains(&count) {
                return Err(InputError::new(
                    fields.analysis("modes"),
                    format!(
                        "must be between 1 and {smallest} (the coordinates of the smallest \
                         model), got {count}"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The models analysed, in order: full (if asked), `reduced`, `reduced_modes`.
    ///
    /// # Errors
    /// As [`FlutterPlan::validate`] for the models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            self.model.n_dofs(),
            "",
        )
    }

    /// The speeds of the sweep (empty without one).
    pub fn speeds(&self) -> &[f64] {
        self.sweep.as_ref().map_or(&[], |s| &s.speeds)
    }

    /// Branches tracked on a model of `dofs` coordinates.
    pub fn branches_for(&self, dofs: usize) -> usize {
        self.modes.unwrap_or(DEFAULT_MODES.min(dofs))
    }
}

/// The checks of a flutter plan of either structure before its loads: the speed sweep (given,
/// positive and increasing) and the flight at its first speed; errors name `{aero}.sweep…` and
/// the flight's fields.
pub(crate) fn check_sweep(
    sweep: Option<&SpeedSweep>,
    flight: &FlightCondition,
    fields: &Fields,
) -> Result<(), InputError> {
    let speeds = format!("{}.sweep", fields.aero);
    let Some(sweep) = sweep else {
        return Err(InputError::new(
            speeds,
            "missing: a flutter analysis sweeps the free-stream speed; give the speeds of \
             its V-g data",
        ));
    };
    sweep.validate(&format!("{speeds}.speeds"), true)?;
    FlightCondition {
        speed: sweep.speeds[0],
        ..*flight
    }
    .validate(&fields.flight())
}

/// The checks of a flutter plan of either structure after its loads: the static options, the
/// crossing tolerance in (0, 1) and the p-k check only with unsteady aerodynamics.
pub(crate) fn check_solver(
    static_options: &StaticOptions,
    tolerance: f64,
    pk: bool,
    aero: &Aero,
    fields: &Fields,
) -> Result<(), InputError> {
    static_options.validate(fields.statics)?;
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(InputError::new(
            fields.analysis("tolerance"),
            format!("must be in (0, 1), got {}", crate::text::short(tolerance)),
        ));
    }
    if pk && !aero.aerodynamics.is_unsteady() {
        return Err(InputError::new(
            fields.analysis("pk"),
            "the p-k method replaces an unsteady model's lag by Theodorsen's function and \
             needs its apparent mass and rate terms: choose quasi-steady, wagner or peters \
             aerodynamics",
        ));
    }
    Ok(())
}

fn dofs_of(kind: &ModelKind, n: usize) -> usize {
    kind.modes().map_or(n, |m| m.len())
}

/// One tracked branch: `s = σ + iω` at every speed reached.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchData {
    /// The wet mode it starts from at `U = 0`, 1-based by frequency.
    pub mode: usize,
    /// Its wet natural frequency at `U = 0` (rad/s).
    pub wet_frequency: f64,
    /// `σ = Re s` at each speed (1/s); positive is unstable.
    pub real: Vec<f64>,
    /// `ω = Im s` at each speed (rad/s); 0 for a real (divergence-type) root.
    pub imag: Vec<f64>,
    /// Whether some step of its tracking was accepted without passing the shape check.
    pub uncertain: bool,
}

impl BranchData {
    fn of(b: &Branch) -> Self {
        Self {
            mode: b.mode + 1,
            wet_frequency: b.wet_frequency,
            real: b.eigenvalues.iter().map(|s| s.re).collect(),
            imag: b.eigenvalues.iter().map(|s| s.im).collect(),
            uncertain: b.uncertain,
        }
    }

    /// Damping ratios `ζ = −σ/|s|` at each speed.
    pub fn damping_ratios(&self) -> Vec<f64> {
        self.real
            .iter()
            .zip(&self.imag)
            .map(|(s, w)| -s / s.hypot(*w))
            .collect()
    }
}

/// The eigen-analysis of one model along the speeds (the model's own lag, or the p-k method).
#[derive(Debug, Clone, PartialEq)]
pub struct Stability {
    /// The speeds reached (m/s).
    pub speeds: Vec<f64>,
    /// The tracked branches.
    pub branches: Vec<BranchData>,
    /// Every crossing of the imaginary axis after the first speed, by speed, refined.
    pub crossings: Vec<Crossing>,
    /// The flutter (or dynamic divergence, at zero frequency) point: the lowest onset; `None`
    /// when no branch becomes unstable, or when one is unstable from the first speed.
    pub flutter: Option<Crossing>,
    /// Branches (indices into `branches`) already unstable at the first speed: no flutter speed
    /// exists within the sweep.
    pub unstable_at_start: Vec<usize>,
    /// Counters.
    pub stats: FlutterStats,
    /// Wall time (s).
    pub wall_time_s: f64,
}

impl Stability {
    /// No eigen-analysis (it was not run: the run was interrupted before it).
    fn none() -> Self {
        Self {
            speeds: Vec::new(),
            branches: Vec::new(),
            crossings: Vec::new(),
            flutter: None,
            unstable_at_start: Vec::new(),
            stats: FlutterStats::default(),
            wall_time_s: 0.0,
        }
    }

    fn of(out: FlutterSolution, wall_time_s: f64, points: usize) -> (Self, Option<Stop>) {
        let done = out.speeds.len();
        let stop = out.stopped.map(|s| Stop::of_flutter(s, done, points));
        let stability = Self {
            speeds: out.speeds,
            branches: out.branches.iter().map(BranchData::of).collect(),
            crossings: out.crossings,
            flutter: out.flutter,
            unstable_at_start: out.unstable_at_start,
            stats: out.stats,
            wall_time_s,
        };
        (stability, stop)
    }
}

/// The flutter analysis of one model.
#[derive(Debug, Clone)]
pub struct FlutterRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// The static equilibria along the speeds (the deformed shapes, lift, divergence pressure).
    pub equilibria: Vec<AeroPoint>,
    /// The static divergence speed found by the sweep of equilibria.
    pub divergence: Option<Divergence>,
    /// Whether the equilibria reached the last speed. Past the divergence speed the static
    /// solver finds no stable equilibrium and stops ([`Stop::SpeedPoint`]) while the
    /// eigen-analysis may go on about the unstable one (an undeformed wing): this is reported
    /// here, not in [`FlutterRun::status`].
    pub equilibria_status: Status,
    /// The eigenvalues of the model (its own aerodynamic lag).
    pub stability: Stability,
    /// The p-k check with Theodorsen's function, when asked.
    pub pk: Option<Stability>,
    /// Wall time of the whole analysis of this model: equilibria, eigen-analysis, p-k (s).
    pub wall_time_s: f64,
    /// Whether the eigen-analysis (and the p-k check) reached the last speed, or the first
    /// stop (the data up to it kept).
    pub status: Status,
    /// The p-k check's stop when the eigen-analysis stopped too.
    pub other_stops: Vec<Stop>,
    /// What its numbers mean that its status does not show: equilibria that stopped (expected
    /// past the divergence speed), branches unstable from the first speed.
    pub notes: Vec<Note>,
}

/// What a flutter analysis found.
#[derive(Debug, Clone)]
pub struct FlutterOutcome {
    /// One run per model, in the order of [`FlutterPlan::models`].
    pub runs: Vec<FlutterRun>,
}

impl FlutterOutcome {
    /// Whether the eigen-analysis (and the p-k check) of every model reached the last speed.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
    }

    /// The full model's run, if it was analysed.
    pub fn full(&self) -> Option<&FlutterRun> {
        self.runs.iter().find(|r| r.kind == ModelKind::Full)
    }
}

/// Run the flutter analysis of `plan`. `progress` hears each model's start and the fraction of
/// the speed range covered by each of its parts.
///
/// # Errors
/// An invalid plan (fields named relative to the plan, [`Fields::RELATIVE`]), or the wet modes
/// of a reduced model not found. Failures of the analysis are in each run's [`Status`].
///
/// ```
/// use flexwing::analysis::aero::{flutter, Aero};
/// use flexwing::analysis::NoProgress;
/// use flexwing::beam::Profile;
/// use flexwing::model::aero::{AeroSection, Aerodynamics};
/// let wing = flexwing::wings::patil_wing(8, Aerodynamics::Steady)?;
/// let aero = Aero {
///     section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
///     density: 0.0889,
///     aerodynamics: Aerodynamics::Wagner,
/// };
/// let speeds = (1..=10).map(|k| 4.0 * k as f64).collect();
/// let mut plan = flutter::FlutterPlan::new(wing.full().clone(), aero, speeds);
/// plan.modes = Some(4);
/// let outcome = flutter::run(&plan, &mut NoProgress)?;
/// let point = outcome.runs[0].stability.flutter.unwrap();
/// // Jones' approximation, n = 8 (the chain reference 32.586 m/s, 22.1 rad/s).
/// assert!((point.speed - 32.586).abs() < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(plan: &FlutterPlan, progress: &mut dyn Progress) -> Result<FlutterOutcome, Error> {
    let fields = Fields::RELATIVE;
    plan.validate(&fields)?;
    let full = plan.aero.wing(&plan.model, fields.aero)?;
    let kinds = plan.models()?;
    let speeds = plan.speeds().to_vec();
    let statics = AeroStaticOptions {
        speeds: speeds.clone(),
        root_angle: plan.flight.root_angle,
        gravity: plan.flight.gravity,
        loads: plan.loads.clone(),
        options: plan.static_options.clone(),
        divergence_tolerance: plan.tolerance,
    };
    let mut runs = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        let built = build(&full, kind)?;
        progress.start(k, kinds.len(), &kind.label());
        let run = match &built {
            Built::Full => analyse(kind, &full, plan, &statics, progress),
            Built::Reduced(rom) => analyse(kind, rom.as_ref(), plan, &statics, progress),
        }?;
        progress.finish();
        runs.push(run);
    }
    Ok(FlutterOutcome { runs })
}

/// The solver's plan for a model of `dofs` coordinates with `method`.
fn solver_plan(plan: &FlutterPlan, dofs: usize, method: FlutterMethod) -> FlutterOptions {
    FlutterOptions {
        speeds: plan.speeds().to_vec(),
        root_angle: plan.flight.root_angle,
        gravity: plan.flight.gravity,
        loads: plan.loads.clone(),
        damping: Damping::None,
        modes: plan.branches_for(dofs),
        tolerance: plan.tolerance,
        static_options: plan.static_options.clone(),
        method,
    }
}

/// Equilibria, eigen-analysis and (if asked) the p-k check of one model, in thirds of its
/// progress.
fn analyse<M: PlanarStructure>(
    kind: &ModelKind,
    aero: &Aeroelastic<M>,
    plan: &FlutterPlan,
    statics: &AeroStaticOptions,
    progress: &mut dyn Progress,
) -> Result<FlutterRun, InputError> {
    let start = Instant::now();
    // Ctrl-C (a cancelled progress) is honoured between the parts and inside the eigen-analysis
    // and the p-k check (polled at every trial speed of the branch tracking).
    let points = plan.speeds().len();
    let interrupted = |done: usize| Stop::SweepInterrupted { done, points };
    let dofs = aero.structure().n_dofs();
    if progress.cancelled() {
        return Ok(FlutterRun {
            kind: kind.clone(),
            dofs,
            equilibria: Vec::new(),
            divergence: None,
            equilibria_status: Status::Stopped(interrupted(0)),
            stability: Stability::none(),
            pk: None,
            wall_time_s: 0.0,
            status: Status::Stopped(interrupted(0)),
            other_stops: Vec::new(),
            notes: Vec::new(),
        });
    }
    let parts = if plan.pk { 3.0 } else { 2.0 };
    let part = |k: f64| move |f: f64| (k + f) / parts;
    let mut stops = Vec::new();
    let mut sub = Sub {
        progress: &mut *progress,
        map: part(0.0),
    };
    let equilibria = sweep_model(kind, aero, statics, &mut sub)?;
    let eig = |method: FlutterMethod, k: f64, progress: &mut dyn Progress| {
        let t = Instant::now();
        let map = part(k);
        let out = flutter_polled(aero, &solver_plan(plan, dofs, method), "", &mut |f| {
            progress.advance(map(f));
            !progress.cancelled()
        })?;
        Ok::<_, InputError>(Stability::of(out, t.elapsed().as_secs_f64(), points))
    };
    let (stability, stop) = if progress.cancelled() {
        let none = Stability::none();
        let stop = Some(interrupted(0));
        (none, stop)
    } else {
        eig(FlutterMethod::Eigenvalues, 1.0, progress)?
    };
    stops.extend(stop);
    let pk = if plan.pk && progress.cancelled() {
        if stops.is_empty() {
            stops.push(interrupted(stability.speeds.len()));
        }
        None
    } else if plan.pk {
        let (pk, stop) = eig(FlutterMethod::PkTheodorsen, 2.0, progress)?;
        stops.extend(stop);
        Some(pk)
    } else {
        None
    };
    let mut stops = stops.into_iter();
    let mut notes: Vec<Note> = equilibria
        .status
        .stop()
        .map(|stop| Note::EquilibriaStopped { stop: stop.clone() })
        .into_iter()
        .collect();
    let first = plan.speeds().first().copied().unwrap_or(0.0);
    for (pk, s) in std::iter::once((false, &stability)).chain(pk.as_ref().map(|p| (true, p))) {
        notes.extend(s.unstable_at_start.iter().map(|&b| Note::UnstableAtStart {
            pk,
            mode: s.branches[b].mode,
            wet_frequency: s.branches[b].wet_frequency,
            speed: first,
        }));
    }
    notes.extend(planar_deflection(
        &equilibria.points,
        stability.flutter.as_ref().map(|c| c.speed),
        aero.chain().length(),
    ));
    Ok(FlutterRun {
        kind: kind.clone(),
        dofs,
        divergence: equilibria.divergence,
        equilibria: equilibria.points,
        equilibria_status: equilibria.status,
        stability,
        pk,
        wall_time_s: start.elapsed().as_secs_f64(),
        status: stops.next().map_or(Status::Complete, Status::Stopped),
        other_stops: stops.collect(),
        notes,
    })
}

/// The note that the planar chain's flutter speed ignores the deflection
/// ([`Note::PlanarDeflection`]), if some equilibrium up to the flutter speed (every one, without
/// flutter) has its tip displaced by at least [`crate::analysis::PLANAR_DEFLECTION_NOTE`] of the
/// span `span`. Every model of a [`FlutterPlan`] is on the planar chain.
fn planar_deflection(points: &[AeroPoint], flutter: Option<f64>, span: f64) -> Option<Note> {
    let (speed, tip_deflection) = points
        .iter()
        .filter(|p| flutter.is_none_or(|u| p.speed <= u))
        .map(|p| {
            let (x, y, _) = p.tip();
            (p.speed, (x - span).hypot(y))
        })
        .filter(|(_, d)| d.is_finite())
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    (tip_deflection >= crate::analysis::PLANAR_DEFLECTION_NOTE * span).then_some(
        Note::PlanarDeflection {
            tip_deflection,
            span,
            speed,
        },
    )
}

/// A [`Progress`] that reports a part of the work through `map`.
struct Sub<'a, F: Fn(f64) -> f64> {
    progress: &'a mut dyn Progress,
    map: F,
}

impl<F: Fn(f64) -> f64> Progress for Sub<'_, F> {
    fn advance(&mut self, fraction: f64) {
        self.progress.advance((self.map)(fraction));
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::patil;
    use super::*;
    use crate::analysis::NoProgress;
    use crate::model::aero::Aerodynamics;
    use crate::solve::aeroelastic::flutter;

    fn speeds() -> Vec<f64> {
        (1..=10).map(|k| 4.0 * k as f64).collect()
    }

    /// The run's eigen-analysis is the solver's (a regression test of the wrapper); its
    /// equilibria stay undeformed (no root angle, symmetric section) and give the linear
    /// divergence speed of the chain (reference `chain_patil_points.csv`, steady, n = 8:
    /// 37.094216856 m/s; the frozen divergence pressure is exact to round-off at rest).
    #[test]
    fn runs_wrap_the_solver_and_find_divergence_and_flutter() {
        let (model, aero) = patil(8, Aerodynamics::Peters { states: 6 });
        let mut plan = FlutterPlan::new(model, aero.clone(), speeds());
        plan.reduced = vec![6];
        let out = run(&plan, &mut NoProgress).unwrap();
        assert!(out.is_complete());
        let full = out.full().unwrap();
        let direct = flutter(
            &aero.wing(&plan.model, "aero").unwrap(),
            &solver_plan(&plan, 16, FlutterMethod::Eigenvalues),
            "f",
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(full.stability.flutter, direct.flutter);
        assert_eq!(full.stability.branches.len(), 6);
        // The equilibria stay undeformed up to the divergence speed; past it (40 m/s) the
        // static solver finds no stable equilibrium and says so.
        assert_eq!(full.equilibria.len(), 9);
        assert!(full
            .equilibria
            .iter()
            .all(|p| p.q.iter().all(|&v| v == 0.0)));
        let Some(Stop::SpeedPoint { speed, error, .. }) = full.equilibria_status.stop() else {
            panic!("{:?}", full.equilibria_status)
        };
        assert_eq!(*speed, 40.0);
        assert!(
            matches!(error, crate::SolveError::StaticUnstable { .. }),
            "{error:?}"
        );
        let d = full.divergence.unwrap();
        assert!((d.speed - 37.094216856).abs() < 1e-6 * 37.1, "{d:?}");
        // Peters 6, n = 8: the chain reference 32.048756335 m/s (k-method, exact to 1e-13);
        // tolerance 1e-6 asked of the refinement.
        let f = full.stability.flutter.unwrap();
        assert!((f.speed - 32.048756335).abs() < 1e-5, "{f:?}");
        // The reduced model on 6 wet modes is close (the library's reduced-model tests give
        // its accuracy against r; here: within 1 %).
        let r = out.runs[1].stability.flutter.unwrap();
        assert!((r.speed / f.speed - 1.0).abs() < 0.01, "{r:?}");
    }

    /// The quasi-steady model on Patil's section (elastic axis at mid-chord) is unstable from
    /// the lowest speed (reference: `Re p = 1.28e-5 1/s` at 0.5 m/s, n = 8 … 32): no flutter
    /// speed, the branch listed instead.
    #[test]
    fn quasi_steady_on_a_mid_chord_axis_gives_no_flutter_speed() {
        let (model, aero) = patil(8, Aerodynamics::QuasiSteady);
        let plan = FlutterPlan::new(model, aero, vec![0.5, 5.0, 10.0, 20.0]);
        let out = run(&plan, &mut NoProgress).unwrap();
        let s = &out.runs[0].stability;
        assert_eq!(s.flutter, None);
        // The first torsion branch (wet frequency 30.66 rad/s at n = 8).
        let b = s
            .unstable_at_start
            .iter()
            .map(|&i| &s.branches[i])
            .find(|b| (30.0..31.0).contains(&b.wet_frequency))
            .expect("the torsion branch is unstable from the start");
        // Reference Re p = 1.290e-5 1/s at 0.5 m/s, n = 8 (chain_patil_points.csv); the tracked
        // root agrees to the refinement of the reference's printout (4 digits).
        assert!((b.real[0] - 1.290e-5).abs() < 0.005e-5, "{}", b.real[0]);
    }

    #[test]
    fn errors_name_the_callers_fields() {
        let fields = Fields {
            loads: "loads",
            aero: "aero",
            statics: "static",
            analysis: "flutter",
        };
        type Change = Box<dyn Fn(&mut FlutterPlan)>;
        let cases: Vec<(Change, &str)> = vec![
            (Box::new(|p| p.sweep = None), "aero.sweep: missing"),
            (
                Box::new(|p| p.sweep.as_mut().unwrap().speeds[0] = 0.0),
                "aero.sweep.speeds[0]: must be positive",
            ),
            (Box::new(|p| p.tolerance = 2.0), "flutter.tolerance:"),
            (Box::new(|p| p.modes = Some(0)), "flutter.modes: must be"),
            (
                Box::new(|p| {
                    p.reduced = vec![3];
                    p.modes = Some(4)
                }),
                "flutter.modes: must be between 1 and 3",
            ),
            (
                Box::new(|p| {
                    p.aero.aerodynamics = Aerodynamics::Steady;
                    p.pk = true
                }),
                "flutter.pk: the p-k method",
            ),
            (
                Box::new(|p| p.flight.gravity = Some(f64::NAN)),
                "aero.flight.gravity:",
            ),
            (
                Box::new(|p| p.static_options.max_iterations = 0),
                "static.max_iterations",
            ),
        ];
        for (change, expected) in cases {
            let (model, aero) = patil(4, Aerodynamics::Wagner);
            let mut p = FlutterPlan::new(model, aero, speeds());
            change(&mut p);
            let msg = p.validate(&fields).unwrap_err().to_string();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }

    /// The planar chain warns when it runs flutter about a deflected wing: Patil's wing under a
    /// 24 N dead tip force (the continuum rod's tip 1.6211 m up, README of
    /// `tests/data/chain3d_reference/`; the chain at n = 8 within 2 % of it, and the
    /// displacement's chordwise part, the shortening, is under 0.1 m) gets the note, the
    /// unloaded wing does not.
    #[test]
    fn the_planar_chain_notes_a_deflected_equilibrium() {
        let (model, aero) = patil(8, Aerodynamics::Peters { states: 6 });
        let mut plan = FlutterPlan::new(model, aero, speeds());
        let quiet = run(&plan, &mut NoProgress).unwrap();
        let planar = |n: &&Note| matches!(n, Note::PlanarDeflection { .. });
        assert!(!quiet.full().unwrap().notes.iter().any(|n| planar(&n)));
        plan.loads = vec![Load::PointForce {
            span: 16.0,
            force: crate::model::Force::Dead { fx: 0.0, fy: 24.0 },
        }];
        let out = run(&plan, &mut NoProgress).unwrap();
        let notes = &out.full().unwrap().notes;
        let Some(Note::PlanarDeflection {
            tip_deflection,
            span,
            ..
        }) = notes.iter().find(planar)
        else {
            panic!("{notes:?}")
        };
        assert!((tip_deflection / 1.6211 - 1.0).abs() < 0.02 + 0.1 / 1.6211);
        assert_eq!(*span, 16.0);
        let text = notes.iter().find(planar).unwrap().to_string();
        assert!(text.contains("cannot couple torsion with lag"), "{text}");
        assert!(text.contains("3-D chain"), "{text}");
    }
}
