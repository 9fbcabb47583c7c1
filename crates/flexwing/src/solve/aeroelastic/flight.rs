//! Time histories of the flight condition: free-stream speed, root angle and a vertical gust
//! (docs/aeroelastic-model.md §1).

use crate::beam::profile::Sign;
use crate::beam::Profile;
use crate::error::InputError;
use crate::model::aero::FlightCondition;
use crate::solve::TimeFunction;

/// The shape in time of a gust.
#[derive(Debug, Clone, PartialEq)]
pub enum GustShape {
    /// Sharp-edged: the full amplitude from `start` on.
    SharpEdged,
    /// `½ (1 − cos(2π U₀ (t − start)/length))` for `0 ≤ t − start ≤ length/U₀`, zero otherwise:
    /// a gust of wavelength `length` (m) convected at the initial free-stream speed `U₀`.
    OneMinusCosine {
        /// Gust length `L_g` (m), positive.
        length: f64,
    },
    /// The time factor `f(t)` of a time function (a sine, a step, a ramp, a table), whatever the
    /// speed: harmonic gusts for frequency responses, the histories a stepper or an FMU sets.
    History(TimeFunction),
}

/// A vertical gust `v_g(s, t) = amplitude · spanwise(s) · shape(t)` (up positive, ground frame),
/// uniform over the chord; every strip meets it at the same time (unswept wing).
#[derive(Debug, Clone, PartialEq)]
pub struct Gust {
    /// Shape in time.
    pub shape: GustShape,
    /// Peak vertical velocity (m/s).
    pub amplitude: f64,
    /// Time the gust front reaches the wing (s).
    pub start: f64,
    /// Spanwise distribution (dimensionless factor over the span), `Profile::Uniform(1.0)` for a
    /// uniform gust.
    pub spanwise: Profile,
}

impl Gust {
    /// The time factor at `t` for initial speed `u0`.
    pub fn factor(&self, t: f64, u0: f64) -> f64 {
        let tau = t - self.start;
        match &self.shape {
            GustShape::SharpEdged => {
                if tau >= 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
            GustShape::History(f) => {
                if tau >= 0.0 {
                    f.at(t)
                } else {
                    0.0
                }
            }
            GustShape::OneMinusCosine { length } => {
                let x = tau * u0 / length;
                if (0.0..=1.0).contains(&x) {
                    0.5 * (1.0 - (2.0 * std::f64::consts::PI * x).cos())
                } else {
                    0.0
                }
            }
        }
    }
}

/// The flight condition over time: `U(t) = U₀ + ΔU f_U(t)`, `α_r(t) = α_r0 + Δα f_α(t)`, and a
/// gust.
#[derive(Debug, Clone, PartialEq)]
pub struct FlightHistory {
    /// The initial condition (speed, root angle, gravity).
    pub initial: FlightCondition,
    /// Change of speed `ΔU` (m/s) and its time function.
    pub speed_change: Option<(f64, TimeFunction)>,
    /// Change of root angle `Δα` (rad) and its time function.
    pub root_angle_change: Option<(f64, TimeFunction)>,
    /// A gust, or none.
    pub gust: Option<Gust>,
}

impl FlightHistory {
    /// Steady flight in the condition `initial`.
    pub fn steady(initial: FlightCondition) -> Self {
        Self {
            initial,
            speed_change: None,
            root_angle_change: None,
            gust: None,
        }
    }

    /// Free-stream speed at `t`.
    pub fn speed(&self, t: f64) -> f64 {
        self.initial.speed + self.speed_change.as_ref().map_or(0.0, |(d, f)| d * f.at(t))
    }

    /// Root angle at `t`.
    pub fn root_angle(&self, t: f64) -> f64 {
        self.initial.root_angle
            + self
                .root_angle_change
                .as_ref()
                .map_or(0.0, |(d, f)| d * f.at(t))
    }

    /// Gust velocity at span station `s` and time `t`.
    pub fn gust(&self, s: f64, t: f64) -> f64 {
        self.gust.as_ref().map_or(0.0, |g| {
            g.amplitude * g.spanwise.at(s) * g.factor(t, self.initial.speed)
        })
    }

    /// Check the history for a run over `[t0, t1]` on a wing of span `length`; `field` prefixes
    /// the error fields.
    pub fn validate(&self, field: &str, length: f64, t0: f64, t1: f64) -> Result<(), InputError> {
        self.initial.validate(field)?;
        let finite = |name: &str, v: f64| {
            if v.is_finite() {
                crate::magnitude::check(&format!("{field}.{name}"), "", v).map(|_| ())
            } else {
                Err(InputError::new(
                    format!("{field}.{name}"),
                    format!("must be finite, got {v}"),
                ))
            }
        };
        if let Some((d, f)) = &self.speed_change {
            finite("speed_change", *d)?;
            f.validate(&format!("{field}.speed_function"), t0, t1)?;
            // The speed must stay non-negative: check the end points and the table values.
            let lo = self.initial.speed - d.abs();
            if lo < 0.0 && (0..=100).any(|k| self.speed(t0 + (t1 - t0) * k as f64 / 100.0) < 0.0) {
                return Err(InputError::new(
                    format!("{field}.speed_change"),
                    "makes the speed negative during the run",
                ));
            }
        }
        if let Some((d, f)) = &self.root_angle_change {
            finite("root_angle_change", *d)?;
            f.validate(&format!("{field}.root_angle_function"), t0, t1)?;
        }
        if let Some(g) = &self.gust {
            finite("gust.amplitude", g.amplitude)?;
            finite("gust.start", g.start)?;
            g.spanwise
                .validate(&format!("{field}.gust.spanwise"), length, Sign::Any)?;
            if let GustShape::History(f) = &g.shape {
                f.validate(&format!("{field}.gust.function"), t0, t1)?;
            }
            if let GustShape::OneMinusCosine { length } = g.shape {
                if !(length.is_finite() && length > 0.0) {
                    return Err(InputError::new(
                        format!("{field}.gust.length"),
                        format!(
                            "must be a finite positive length (m), got {}",
                            crate::text::short(length)
                        ),
                    ));
                }
                if !(self.initial.speed > 0.0) {
                    return Err(InputError::new(
                        format!("{field}.speed"),
                        "a 1−cos gust is convected by the free stream: the speed must be positive",
                    ));
                }
            }
        }
        Ok(())
    }
}

/// A value linear in time over `[t0, t1]` and held outside it: an input of a stepper over one
/// communication interval (first-order hold), or held (`t0 = t1`: zero-order hold).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Segment {
    pub t0: f64,
    pub t1: f64,
    pub v0: f64,
    pub v1: f64,
}

impl Segment {
    /// `value` at every time.
    pub fn held(value: f64) -> Self {
        Self {
            t0: 0.0,
            t1: 0.0,
            v0: value,
            v1: value,
        }
    }

    /// The value at `t`.
    pub fn at(&self, t: f64) -> f64 {
        if self.t1 > self.t0 {
            let s = ((t - self.t0) / (self.t1 - self.t0)).clamp(0.0, 1.0);
            self.v0 + (self.v1 - self.v0) * s
        } else {
            self.v1
        }
    }
}

/// Increments of the flight condition set from outside between integrations (a stepper's or an
/// FMU's inputs, `analysis::aero::stepper`), added to the flight history's root angle, speed and
/// uniform gust; zero by default.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct FlightOffsets {
    /// Root angle (rad).
    pub root_angle: Segment,
    /// Free-stream speed (m/s).
    pub speed: Segment,
    /// Uniform vertical gust velocity (m/s, up).
    pub gust: Segment,
}
