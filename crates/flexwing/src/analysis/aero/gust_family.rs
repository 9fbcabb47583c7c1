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
//! wind frame: a user converts EAS with `√(ρ0/ρ)`.
//!
//! Not yet here: the root torque and shear (the response's samples carry the tip deflection and
//! twist, the root bending moment and the lift), the case-file keys, CLI and Python front ends.

use super::response::{run as response_run, AeroDynamicPlan, AeroSample};
use crate::analysis::{ModelKind, Progress, Status};
use crate::error::{Error, InputError};
use crate::solve::aeroelastic::{Gust, GustPenetration, GustShape};

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
                 {MAX_GRADIENT}] m (CS 25.341(a)(2)), got {gradient}"
            ),
        ));
    }
    if !(reference_velocity.is_finite() && reference_velocity > 0.0) {
        return Err(InputError::new(
            format!("{field}.reference_velocity"),
            format!("must be a positive velocity (m/s), got {reference_velocity}"),
        ));
    }
    if !(alleviation > 0.0 && alleviation <= 1.0) {
        return Err(InputError::new(
            format!("{field}.alleviation"),
            format!(
                "the flight profile alleviation factor F_g must be in (0, 1], got {alleviation}"
            ),
        ));
    }
    Ok(reference_velocity * alleviation * (gradient / MAX_GRADIENT).powf(1.0 / 6.0))
}

/// The gust gradient distances `H` of a family (m).
#[derive(Debug, Clone, PartialEq)]
pub enum GustLengths {
    /// `count` distances evenly spaced from `from` to `to` (both included; `count ≥ 2`, or 1 with
    /// `from = to`).
    Range {
        /// The first distance (m).
        from: f64,
        /// The last distance (m).
        to: f64,
        /// How many.
        count: usize,
    },
    /// The distances given (m), at least one.
    List(Vec<f64>),
}

impl GustLengths {
    /// The distances, in the order given; errors name `{field}.lengths`.
    pub fn values(&self, field: &str) -> Result<Vec<f64>, InputError> {
        let err = |reason: String| InputError::new(format!("{field}.lengths"), reason);
        match self {
            GustLengths::Range { from, to, count } => {
                if !(from.is_finite() && to.is_finite() && from <= to) {
                    return Err(err(format!("from ≤ to, both finite, got {from} and {to}")));
                }
                match *count {
                    0 => Err(err("count must be at least 1".into())),
                    1 if from == to => Ok(vec![*from]),
                    1 => Err(err("count = 1 needs from = to".into())),
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

/// A gust family: the response plan (structure, aerodynamics, flight and models; its own gust,
/// if any, gives only the penetration) and the family's gusts.
#[derive(Debug, Clone)]
pub struct GustFamilyPlan {
    /// The response of each member: its flight's gust is replaced by the member's.
    pub response: AeroDynamicPlan,
    /// The gust gradient distances `H` (m).
    pub lengths: GustLengths,
    /// `U_ref` (m/s, true air velocity).
    pub reference_velocity: f64,
    /// `F_g`, in (0, 1].
    pub alleviation: f64,
    /// When each gust front reaches the wing (s).
    pub start: f64,
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
}

/// The outputs of a family, in the order of [`MemberRun::peaks`].
pub const OUTPUTS: [&str; 4] = ["tip_y", "tip_twist", "root_bending_moment", "lift"];

fn output_values(s: &AeroSample) -> [f64; 4] {
    [s.tip_y, s.tip_twist, s.root_bending_moment, s.lift]
}

/// One model's response to one member of the family.
#[derive(Debug, Clone)]
pub struct MemberRun {
    /// Which model.
    pub kind: ModelKind,
    /// The run's status (a stopped run's peaks are over the times it reached).
    pub status: Status,
    /// The peaks of [`OUTPUTS`].
    pub peaks: [Peak; 4],
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
}

/// Run the family: for each gradient `H`, the response plan with the gust 1−cos of wavelength
/// `2H` and amplitude `U_ds(H)` from `start` on (penetration as the plan's own gust, uniform
/// without one). The plan's end time must let the longest gust pass the wing.
pub fn run(plan: &GustFamilyPlan, progress: &mut dyn Progress) -> Result<GustFamilyOutcome, Error> {
    let field = "gust_family";
    let gradients = plan.lengths.values(field)?;
    let velocities = gradients
        .iter()
        .map(|&h| design_gust_velocity(h, plan.reference_velocity, plan.alleviation, field))
        .collect::<Result<Vec<_>, _>>()?;
    if !(plan.start.is_finite() && plan.start >= 0.0) {
        return Err(InputError::new(
            format!("{field}.start"),
            format!("must be a time ≥ 0 (s), got {}", plan.start),
        )
        .into());
    }
    let u0 = plan.response.flight.initial.speed;
    let longest = gradients.iter().copied().fold(0.0, f64::max);
    let passed = plan.start + 2.0 * longest / u0;
    if !(u0 > 0.0) || plan.response.structure.end_time < passed {
        return Err(InputError::new(
            "dynamic.end_time",
            format!(
                "the longest gust (H = {longest} m) has passed the wing at {passed} s at \
                 {u0} m/s: the end time must be at least that, got {}",
                plan.response.structure.end_time
            ),
        )
        .into());
    }
    let penetration = plan
        .response
        .flight
        .gust
        .as_ref()
        .map_or(GustPenetration::Uniform, |g| g.penetration);
    let mut members = Vec::with_capacity(gradients.len());
    for (&h, &u_ds) in gradients.iter().zip(&velocities) {
        let mut p = plan.response.clone();
        p.flight.gust = Some(Gust {
            shape: GustShape::OneMinusCosine { length: 2.0 * h },
            amplitude: u_ds,
            start: plan.start,
            spanwise: crate::beam::Profile::Uniform(1.0),
            penetration,
        });
        let out = response_run(&p, progress)?;
        let runs = out
            .runs
            .iter()
            .map(|r| MemberRun {
                kind: r.kind.clone(),
                status: r.status.clone(),
                peaks: peaks(&r.samples, plan.start),
            })
            .collect();
        members.push(GustMember {
            gradient: h,
            design_velocity: u_ds,
            runs,
        });
    }
    Ok(GustFamilyOutcome { members })
}

/// The peaks of the changes from the first sample, over the samples from `start` on (before it
/// the wing is at its equilibrium: the changes are round-off); a change that never goes above
/// (below) zero has the peak 0 at `start`.
fn peaks(samples: &[AeroSample], start: f64) -> [Peak; 4] {
    let first = samples.first().map(output_values).unwrap_or([0.0; 4]);
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
