//! Discrete gust families as in certification practice (issue 24, item 2): 1−cos gusts over a
//! range of gust gradient distances `H`, each at its design velocity, run through the
//! aeroelastic response ([`super::response`]) on every model of the plan, with the peaks of each
//! output per gradient and the critical gradient of each output.
//!
//! Source: EASA CS-25 Amendment 27, CS 25.341(a) (the same text as FAR 25.341(a), amendment
//! 25-86): the gust `U = (U_ds/2)(1 − cos(π s/H))` for `0 ≤ s ≤ 2H` (`s` the distance penetrated,
//! so the 1−cos wavelength is `2H`), `H` from 30 ft to 350 ft, and the design gust velocity
//! `U_ds = U_ref F_g (H/350 ft)^(1/6)`, `U_ref` the reference gust velocity (EAS, 56 ft/s at sea
//! level down to 44 ft/s at 15 000 ft for the design cruise speed) and `F_g` the flight profile
//! alleviation factor, both given by the user. The velocities here are true air velocities of the
//! wind frame: a user converts EAS with `√(ρ0/ρ)`. The reference velocities were checked against
//! the text of 14 CFR 25.341(a)(5)(i): 56.0 ft/s EAS at sea level, linearly to 44.0 ft/s at
//! 15 000 ft, then linearly to 20.86 ft/s at 60 000 ft (half these at the dive speed, (a)(5)(ii)).
//!
//! The outputs are those a response's samples carry ([`OUTPUTS`]); the root shear, which needs
//! the wing's accelerations, is an output of the linear model only (`linearize`), as of the
//! stepper. Peaks are over the plan's output times: their spacing bounds how well a peak's
//! value and time are resolved.

use super::response::{AeroDynamicPlan, AeroSample, Prepared, Samples};
use super::Fields;
use crate::analysis::{ModelKind, Progress, Status};
use crate::beam::Profile;
use crate::error::{Error, InputError};
use crate::model::aero::Aerodynamics;
use crate::solve::aeroelastic::{Gust, GustPenetration, GustShape};
use crate::text::short;

/// One foot (m).
pub const FOOT: f64 = 0.3048;
/// The shortest gust gradient distance of CS 25.341(a)(2), 30 ft (m).
pub const MIN_GRADIENT: f64 = 30.0 * FOOT;
/// The longest gust gradient distance of CS 25.341(a)(2), and the reference of the design
/// velocity's scaling, 350 ft (m).
pub const MAX_GRADIENT: f64 = 350.0 * FOOT;

/// The design gust velocity `U_ds = U_ref F_g (H/350 ft)^(1/6)` (m/s) of the gradient distance
/// `gradient` (m, within [30 ft, 350 ft]), for the reference velocity `reference_velocity`
/// (m/s, positive) and the alleviation factor `alleviation` (in (0, 1]). Errors name `{field}.lengths`,
/// `{field}.reference_velocity` or `{field}.alleviation`.
pub fn design_gust_velocity(
    gradient: f64,
    reference_velocity: f64,
    alleviation: f64,
    field: &str,
) -> Result<f64, InputError> {
    // A gradient a rounding away from a bound (feet converted to metres) is accepted.
    let slack = 1e-9 * MAX_GRADIENT;
    if !(gradient >= MIN_GRADIENT - slack && gradient <= MAX_GRADIENT + slack) {
        return Err(InputError::new(
            format!("{field}.lengths"),
            format!(
                "a gust gradient distance H must be within [30 ft, 350 ft] = [{MIN_GRADIENT}, \
                 {MAX_GRADIENT}] m (CS 25.341(a)(2)), got {}",
                short(gradient)
            ),
        ));
    }
    if !(reference_velocity.is_finite() && reference_velocity > 0.0) {
        return Err(InputError::new(
            format!("{field}.reference_velocity"),
            format!(
                "must be a positive velocity (m/s), got {}",
                short(reference_velocity)
            ),
        ));
    }
    if !(alleviation > 0.0 && alleviation <= 1.0) {
        return Err(InputError::new(
            format!("{field}.alleviation"),
            format!(
                "the flight profile alleviation factor F_g must be in (0, 1], got {}",
                short(alleviation)
            ),
        ));
    }
    Ok(reference_velocity * alleviation * (gradient / MAX_GRADIENT).powf(1.0 / 6.0))
}

/// The gust gradient distances `H` of a family (m).
#[derive(Debug, Clone, PartialEq)]
pub enum GustLengths {
    /// `steps` distances evenly spaced from `from` to `to` (both included; `steps ≥ 2`, or 1 with
    /// `from = to`).
    Range {
        /// The first distance (m).
        from: f64,
        /// The last distance (m).
        to: f64,
        /// How many.
        steps: usize,
    },
    /// The distances given (m), at least one.
    List(Vec<f64>),
}

impl GustLengths {
    /// The distances, in the order given; errors name `{field}.lengths` (a list) or
    /// `{field}.from`, `{field}.steps` (a range).
    pub fn values(&self, field: &str) -> Result<Vec<f64>, InputError> {
        let key = |k: &str| crate::field(field, k);
        let err = |reason: String| InputError::new(key("lengths"), reason);
        match self {
            GustLengths::Range { from, to, steps } => {
                if !(from.is_finite() && to.is_finite() && from <= to) {
                    return Err(InputError::new(
                        key("from"),
                        format!(
                            "from ≤ to, both finite, got {} and {}",
                            short(*from),
                            short(*to)
                        ),
                    ));
                }
                let steps_error = |r: &str| InputError::new(key("steps"), r);
                match *steps {
                    0 => Err(steps_error("must be at least 1")),
                    1 if from == to => Ok(vec![*from]),
                    1 => Err(steps_error("steps = 1 needs from = to")),
                    n => Ok((0..n)
                        .map(|k| from + (to - from) * k as f64 / (n - 1) as f64)
                        .collect()),
                }
            }
            GustLengths::List(v) if v.is_empty() => Err(err("at least one length".into())),
            GustLengths::List(v) => Ok(v.clone()),
        }
    }
}

/// A gust family: the response plan (structure, aerodynamics, flight and models; without a gust
/// of its own: each member's replaces it) and the family's gusts.
#[derive(Debug, Clone)]
pub struct GustFamilyPlan {
    /// The response of each member, its flight without gust.
    pub response: AeroDynamicPlan,
    /// The gust gradient distances `H` (m).
    pub lengths: GustLengths,
    /// `U_ref` (m/s, true air velocity).
    pub reference_velocity: f64,
    /// `F_g`, in (0, 1].
    pub alleviation: f64,
    /// When each gust front reaches the wing (s).
    pub start: f64,
    /// How each gust front meets the sections.
    pub penetration: GustPenetration,
}

impl GustFamilyPlan {
    /// Check the family under the caller's names: the family's own values as `{family}.key`, the
    /// end time as `{analysis}.end_time` and the speed as `{aero}.flight.speed` of `fields` (the
    /// response plan is checked by its own `validate`). Returns the gradients and their design
    /// velocities.
    ///
    /// # Errors
    /// Invalid lengths, velocities or start; a flight with its own gust; an end time before
    /// the longest gust has passed the wing.
    pub fn validate(&self, family: &str, fields: &Fields) -> Result<Vec<(f64, f64)>, InputError> {
        let gradients = self.lengths.values(family)?;
        let members = gradients
            .iter()
            .map(|&h| {
                design_gust_velocity(h, self.reference_velocity, self.alleviation, family)
                    .map(|u| (h, u))
            })
            .collect::<Result<Vec<_>, _>>()?;
        if !(self.start.is_finite() && self.start >= 0.0) {
            return Err(InputError::new(
                crate::field(family, "start"),
                format!("must be a time ≥ 0 (s), got {}", short(self.start)),
            ));
        }
        let aerodynamics = self.response.aero.aerodynamics;
        if self.penetration == GustPenetration::Kussner
            && !matches!(
                aerodynamics,
                Aerodynamics::Wagner | Aerodynamics::Peters { .. }
            )
        {
            return Err(InputError::new(
                crate::field(family, "penetration"),
                format!(
                    "\"kussner\" is the gust's circulation lag: it needs the wagner or peters \
                     model, not {}",
                    aerodynamics.name()
                ),
            ));
        }
        if self.response.flight.gust.is_some() {
            return Err(InputError::new(
                crate::field(family, "response"),
                "the response's flight has a gust of its own: each member's gust replaces it",
            ));
        }
        let u0 = self.response.flight.initial.speed;
        if !(u0 > 0.0) {
            return Err(InputError::new(
                crate::field(&fields.flight(), "speed"),
                format!(
                    "a gust family needs a positive flight speed (the gusts are lengths \
                     flown through), got {}",
                    short(u0)
                ),
            ));
        }
        let longest = gradients.iter().copied().fold(0.0, f64::max);
        let passed = self.start + 2.0 * longest / u0;
        let end_time = self.response.structure.end_time;
        if end_time < passed {
            return Err(InputError::new(
                fields.analysis("end_time"),
                format!(
                    "the longest gust (H = {} m) has passed the wing at {} s at {} m/s: the \
                     end time must be at least that, got {}",
                    short(longest),
                    short(passed),
                    short(u0),
                    short(end_time)
                ),
            ));
        }
        Ok(members)
    }
}

/// The largest and smallest change of one output from its value at `t = 0` (the equilibrium the
/// response starts from) from the gust's start on, and their times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// Largest change.
    pub max: f64,
    /// Its time (s).
    pub max_time: f64,
    /// Smallest (most negative) change.
    pub min: f64,
    /// Its time (s).
    pub min_time: f64,
}

impl Peak {
    /// The larger of `|max|` and `|min|`.
    pub fn magnitude(&self) -> f64 {
        self.max.abs().max(self.min.abs())
    }

    /// The change of the larger magnitude, signed, and its time: `(max, max_time)` or
    /// `(min, min_time)`.
    pub fn extreme(&self) -> (f64, f64) {
        if self.max.abs() >= self.min.abs() {
            (self.max, self.max_time)
        } else {
            (self.min, self.min_time)
        }
    }
}

/// The outputs of a family, in the order of [`MemberRun::peaks`]: the names of the response's
/// samples ([`AeroSample`]) and of the linear model's outputs.
pub const OUTPUTS: [&str; 5] = [
    "tip_y",
    "tip_twist",
    "root_bending_moment",
    "root_torque",
    "lift",
];

/// The SI units of [`OUTPUTS`].
pub const OUTPUT_UNITS: [&str; 5] = ["m", "rad", "N·m", "N·m", "N"];

fn output_values(s: &AeroSample) -> [f64; 5] {
    [
        s.tip_y,
        s.tip_twist,
        s.root_bending_moment,
        s.root_torque,
        s.lift,
    ]
}

/// One model's response to one member of the family.
#[derive(Debug, Clone)]
pub struct MemberRun {
    /// Which model.
    pub kind: ModelKind,
    /// The run's status (a stopped run's peaks are over the times it reached).
    pub status: Status,
    /// The peaks of [`OUTPUTS`].
    pub peaks: [Peak; 5],
    /// Accepted integrator steps.
    pub steps: usize,
    /// Wall time of the integration (s).
    pub wall_time_s: f64,
}

/// One gust of the family.
#[derive(Debug, Clone)]
pub struct GustMember {
    /// `H` (m); the 1−cos wavelength is `2H`.
    pub gradient: f64,
    /// `U_ds` (m/s).
    pub design_velocity: f64,
    /// One run per model of the plan.
    pub runs: Vec<MemberRun>,
}

/// What a gust family produced.
#[derive(Debug, Clone)]
pub struct GustFamilyOutcome {
    /// One member per gradient, in the order given.
    pub members: Vec<GustMember>,
}

impl GustFamilyOutcome {
    /// For model `model` (index into each member's runs) and output `output` (index into
    /// [`OUTPUTS`]): the member whose peak magnitude is the largest, over members whose run is
    /// complete; `None` if none is.
    pub fn critical(&self, model: usize, output: usize) -> Option<&GustMember> {
        self.members
            .iter()
            .filter(|m| m.runs[model].status.is_complete())
            .max_by(|a, b| {
                let pa = a.runs[model].peaks[output].magnitude();
                let pb = b.runs[model].peaks[output].magnitude();
                pa.total_cmp(&pb)
            })
    }

    /// Whether every run of every member is complete.
    pub fn is_complete(&self) -> bool {
        self.members
            .iter()
            .all(|m| m.runs.iter().all(|r| r.status.is_complete()))
    }

    /// Per model (in the plan's order): its kind and how its runs ended, the first run that
    /// stopped, else the first that is not complete, else complete.
    pub fn statuses(&self) -> Vec<(&ModelKind, &Status)> {
        let Some(first) = self.members.first() else {
            return Vec::new();
        };
        (0..first.runs.len())
            .map(|k| {
                let runs = || self.members.iter().map(move |m| &m.runs[k]);
                let worst = runs()
                    .find(|r| matches!(r.status, Status::Stopped(_)))
                    .or_else(|| runs().find(|r| !r.status.is_complete()))
                    .unwrap_or(&first.runs[k]);
                (&first.runs[k].kind, &worst.status)
            })
            .collect()
    }

    /// Wall time of model `model`'s runs over all members (s).
    pub fn wall_time_s(&self, model: usize) -> f64 {
        self.members.iter().map(|m| m.runs[model].wall_time_s).sum()
    }
}

/// The caller's progress seen through one member: model `k` of member `m` is model
/// `m · count + k` of the whole family, labelled with the member's `H`.
struct MemberProgress<'a> {
    inner: &'a mut dyn Progress,
    member: usize,
    members: usize,
    gradient: f64,
}

impl Progress for MemberProgress<'_> {
    fn start(&mut self, index: usize, count: usize, label: &str) {
        let label = format!("{label}, H = {:.2} m", self.gradient);
        let (i, n) = (self.member * count + index, self.members * count);
        self.inner.start(i, n, &label);
    }
    fn advance(&mut self, fraction: f64) {
        self.inner.advance(fraction)
    }
    fn finish(&mut self) {
        self.inner.finish()
    }
    fn cancelled(&mut self) -> bool {
        self.inner.cancelled()
    }
}

/// Run the family: for each gradient `H`, the response plan with the gust 1−cos of wavelength
/// `2H` and amplitude `U_ds(H)` from `start` on, uniform over the span. The plan's end time must
/// let the longest gust pass the wing. An interrupted member ends the family there.
///
/// # Errors
/// An invalid plan (named as in a case file: the family's fields `gust_family.key`, the end time
/// `dynamic.end_time`), or those of [`super::response::run`].
pub fn run(plan: &GustFamilyPlan, progress: &mut dyn Progress) -> Result<GustFamilyOutcome, Error> {
    let fields = Fields {
        loads: "loads",
        aero: "aero",
        statics: "static",
        analysis: "dynamic",
    };
    let gusts = plan.validate("gust_family", &fields)?;
    // The models and their initial equilibrium are the same for every member (the gusts start
    // from the one initial flight condition): built and solved once.
    let prepared = Prepared::new(&plan.response)?;
    let mut members = Vec::with_capacity(gusts.len());
    for (m, &(h, u_ds)) in gusts.iter().enumerate() {
        let mut flight = plan.response.flight.clone();
        flight.gust = Some(Gust {
            shape: GustShape::OneMinusCosine { length: 2.0 * h },
            amplitude: u_ds,
            start: plan.start,
            spanwise: Profile::Uniform(1.0),
            penetration: plan.penetration,
        });
        let mut member_progress = MemberProgress {
            inner: &mut *progress,
            member: m,
            members: gusts.len(),
            gradient: h,
        };
        let out = prepared.run(&flight, Samples::Outputs, &mut member_progress);
        let runs: Vec<MemberRun> = out
            .runs
            .iter()
            .map(|r| MemberRun {
                kind: r.kind.clone(),
                status: r.status.clone(),
                peaks: peaks(&r.samples, plan.start),
                steps: r.stats.steps,
                wall_time_s: r.wall_time_s,
            })
            .collect();
        let interrupted = runs.iter().any(|r| r.status.word() == "interrupted");
        members.push(GustMember {
            gradient: h,
            design_velocity: u_ds,
            runs,
        });
        if interrupted {
            break;
        }
    }
    Ok(GustFamilyOutcome { members })
}

/// The peaks of the changes from the first sample, over the samples from `start` on (before it
/// the wing is at its equilibrium: the changes are round-off); a change that never goes above
/// (below) zero has the peak 0 at `start`.
fn peaks(samples: &[AeroSample], start: f64) -> [Peak; 5] {
    let first = samples.first().map(output_values).unwrap_or([0.0; 5]);
    std::array::from_fn(|r| {
        let mut p = Peak {
            max: 0.0,
            max_time: start,
            min: 0.0,
            min_time: start,
        };
        for s in samples.iter().filter(|s| s.t >= start) {
            let d = output_values(s)[r] - first[r];
            if d > p.max {
                (p.max, p.max_time) = (d, s.t);
            }
            if d < p.min {
                (p.min, p.min_time) = (d, s.t);
            }
        }
        p
    })
}
