//! Time histories `f(t)` that scale the loads of a dynamic run, `Q(t) = f(t) Q₀`, and their
//! validation against the simulated time span.

use crate::error::InputError;

/// Time history `f(t)` that scales a load: `Q(t) = f(t) Q₀`.
#[derive(Debug, Clone, PartialEq)]
pub enum TimeFunction {
    /// `f = 1`.
    Constant,
    /// `f = sin(ω t + φ)`.
    Sine {
        /// Circular frequency `ω` (rad/s).
        omega: f64,
        /// Phase `φ` (rad).
        phase: f64,
    },
    /// `f = 0` before `time`, 1 after.
    Step {
        /// Switch time (s).
        time: f64,
    },
    /// `f = 0` before `start`, rising linearly to 1 at `end`, then 1.
    Ramp {
        /// Start of the ramp (s).
        start: f64,
        /// End of the ramp (s), after `start`.
        end: f64,
    },
    /// Piecewise-linear table `(t, value)`; must cover the simulated time.
    Table {
        /// Times (s), strictly increasing.
        t: Vec<f64>,
        /// Values (dimensionless factors).
        value: Vec<f64>,
    },
}

impl TimeFunction {
    /// Value at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            TimeFunction::Constant => 1.0,
            TimeFunction::Sine { omega, phase } => (omega * t + phase).sin(),
            TimeFunction::Step { time } => {
                if t >= *time {
                    1.0
                } else {
                    0.0
                }
            }
            TimeFunction::Ramp { start, end } => ((t - start) / (end - start)).clamp(0.0, 1.0),
            TimeFunction::Table { t: ts, value } => {
                let last = ts.len() - 1;
                if t <= ts[0] {
                    return value[0];
                }
                if t >= ts[last] {
                    return value[last];
                }
                let k = ts.partition_point(|&s| s <= t);
                let w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
                value[k - 1] + w * (value[k] - value[k - 1])
            }
        }
    }

    /// Check the function for a simulation over `[t0, t1]`; `field` names it in errors.
    pub fn validate(&self, field: &str, t0: f64, t1: f64) -> Result<(), InputError> {
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
        match self {
            TimeFunction::Constant => Ok(()),
            TimeFunction::Sine { omega, phase } => {
                finite("omega", *omega)?;
                finite("phase", *phase)
            }
            TimeFunction::Step { time } => finite("time", *time),
            TimeFunction::Ramp { start, end } => {
                finite("start", *start)?;
                finite("end", *end)?;
                if end > start {
                    Ok(())
                } else {
                    Err(InputError::new(
                        format!("{field}.end"),
                        format!("must be after start ({start} s), got {end} s"),
                    ))
                }
            }
            TimeFunction::Table { t, value } => {
                if t.len() != value.len() || t.len() < 2 {
                    return Err(InputError::new(
                        field,
                        format!("table needs at least two (t, value) pairs of equal length, got {} and {}", t.len(), value.len()),
                    ));
                }
                for k in 0..t.len() {
                    finite(&format!("t[{k}]"), t[k])?;
                    finite(&format!("value[{k}]"), value[k])?;
                    if k > 0 && t[k] <= t[k - 1] {
                        return Err(InputError::new(
                            format!("{field}.t"),
                            format!(
                                "must be strictly increasing, but t[{k}] = {} <= t[{}] = {}",
                                t[k],
                                k - 1,
                                t[k - 1]
                            ),
                        ));
                    }
                }
                if t[0] > t0 || t[t.len() - 1] < t1 {
                    return Err(InputError::new(
                        format!("{field}.t"),
                        format!(
                            "table covers [{}, {}] s but the simulation runs over [{t0}, {t1}] s",
                            t[0],
                            t[t.len() - 1]
                        ),
                    ));
                }
                Ok(())
            }
        }
    }
}
