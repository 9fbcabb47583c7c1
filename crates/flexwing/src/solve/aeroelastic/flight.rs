//! Time histories of the flight condition: free-stream speed, root angle and a vertical gust
//! (docs/aeroelastic-model.md §1), and the gust's penetration of the chord (§3a): uniform over the
//! chord with its apparent mass, or Küssner's function by a three-term exponential fit (fitted by
//! least squares to the exact function, the inverse Fourier transform of Sears' function;
//! Sears, J. Aero. Sci. 8(3), 1941; Bisplinghoff, Ashley & Halfman §5-7), whose states are solved
//! in closed form for the gust's known history.

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
    /// A seeded realization of continuous turbulence (m/s; the gust's `amplitude` scales it,
    /// 1 for the realization as drawn), from `start` on, periodic
    /// ([`super::turbulence::Realization`]).
    Turbulence(Box<super::turbulence::Realization>),
}

/// How a gust front meets a section (docs/aeroelastic-model.md §3a).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum GustPenetration {
    /// The whole chord meets the gust at once, and every strip at the same time: the gust's
    /// upwash enters the three-quarter-chord upwash (through the circulation lag, if any) and its
    /// apparent mass `πρb² v̇_g` acts at mid-chord (the section's own non-circulatory term for a
    /// section moving with `−v_g`). A sharp-edged gust's apparent mass is an impulse at the
    /// front's arrival, which is not applied (use `Kussner` for a sharp-edged gust).
    #[default]
    Uniform,
    /// The gust front is convected over the chord at the initial speed `U₀`: the gust's lift is
    /// `2πρU b v_g,LE ∗ ψ` (Küssner's function, with its non-circulatory part) at the quarter
    /// chord, `v_g,LE` the gust at the strip's leading edge, which the front reaches when it has
    /// travelled from the wing's most upstream leading-edge point (a swept wing's outboard strips
    /// later). Needs a model with a circulation lag (Wagner or Peters).
    Kussner,
}

impl GustPenetration {
    /// The case file's word.
    pub fn name(&self) -> &'static str {
        match self {
            GustPenetration::Uniform => "uniform",
            GustPenetration::Kussner => "kussner",
        }
    }
}

/// Küssner's function `ψ(s) = 1 − Σ_k A_k e^{−β_k s}` (`s` in half-chords travelled by the front
/// past the leading edge): a three-term fit with `Σ A_k = 1` (`ψ(0) = 0`), least squares over
/// `s ∈ [0, 40]` against the exact function. Max error 0.045 (in the first half-chord, where the
/// exact function grows like `√s`), 0.0097 for `s ≥ 1`; frequency response within 0.013 of
/// Sears' function for `k ≤ 1` (`tests/suite/aero_gust.rs` measures both).
pub const KUSSNER_A: [f64; 3] = [0.1915, 0.5213, 0.2872];
/// Exponents of [`KUSSNER_A`] (per half-chord).
pub const KUSSNER_BETA: [f64; 3] = [0.0497, 0.3082, 3.542];

/// The fit's `ψ(s)`.
pub fn kussner_fit(s: f64) -> f64 {
    if s <= 0.0 {
        return 0.0;
    }
    1.0 - KUSSNER_A
        .iter()
        .zip(KUSSNER_BETA)
        .map(|(a, b)| a * (-b * s).exp())
        .sum::<f64>()
}

/// A vertical gust `v_g(s, t) = amplitude · spanwise(s) · shape(t)` (up positive, ground frame);
/// how its front meets each section is `penetration`.
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
    /// How the front meets each section: at once over the chord, or Küssner's penetration.
    pub penetration: GustPenetration,
}

impl Gust {
    /// The time derivative of [`Self::factor`] (1/s), away from jumps (a sharp-edged front, a
    /// step: their impulses are not represented).
    pub fn rate(&self, t: f64, u0: f64) -> f64 {
        let tau = t - self.start;
        if tau < 0.0 {
            return 0.0;
        }
        match &self.shape {
            GustShape::SharpEdged => 0.0,
            GustShape::History(f) => time_function_rate(f, t),
            GustShape::Turbulence(r) => r.value_and_rate(tau).1,
            GustShape::OneMinusCosine { length } => {
                let x = tau * u0 / length;
                if (0.0..=1.0).contains(&x) {
                    let w = 2.0 * std::f64::consts::PI * u0 / length;
                    0.5 * w * (w * tau).sin()
                } else {
                    0.0
                }
            }
        }
    }

    /// The time factor seen through Küssner's function: the response at `t` of the fit
    /// [`KUSSNER_A`], [`KUSSNER_BETA`] (in the reduced time `u0 (t − delay)/b`) to the time factor
    /// at a leading edge the front reaches `delay` s late, i.e. the exact solution of the fit's
    /// states `ż_k = (u0/b)(f − β_k z_k)`, output `Σ A_k β_k z_k`, for the shapes' closed forms:
    /// `Σ_k A_k (f − λ_k ∫ e^{−λ_k(t−σ)} f dσ)` with `λ_k = β_k u0/b`, by parts
    /// `f(t) − Σ_k A_k ∫ e^{−λ_k (t−σ)} df(σ)`.
    pub fn kussner_factor(&self, t: f64, u0: f64, b: f64, delay: f64) -> f64 {
        let tau = t - delay - self.start;
        if tau <= 0.0 || u0 <= 0.0 {
            return 0.0;
        }
        let lambdas = KUSSNER_BETA.map(|beta| beta * u0 / b);
        match &self.shape {
            // ∫ e^{−λ(τ−σ)} dH(σ) = e^{−λτ}.
            GustShape::SharpEdged => kussner_fit(u0 * tau / b),
            GustShape::OneMinusCosine { length } => {
                let period = length / u0;
                let w = 2.0 * std::f64::consts::PI / period;
                let end = tau.min(period);
                let f = if tau <= period {
                    0.5 * (1.0 - (w * tau).cos())
                } else {
                    0.0
                };
                // df = (w/2) sin(wσ) dσ on [0, period]:
                // ∫_0^end e^{−λ(τ−σ)} (w/2) sin wσ dσ
                //   = (w/2)/(λ² + w²) [e^{−λ(τ−end)} (λ sin w end − w cos w end) + w e^{−λτ}].
                let (se, ce) = (w * end).sin_cos();
                f - KUSSNER_A
                    .iter()
                    .zip(lambdas)
                    .map(|(a, l)| {
                        a * 0.5 * w / (l * l + w * w)
                            * ((-l * (tau - end)).exp() * (l * se - w * ce) + w * (-l * tau).exp())
                    })
                    .sum::<f64>()
            }
            GustShape::History(TimeFunction::Sine { omega, phase }) => {
                // f = sin(w σ' + φ) from the front's arrival σ' = start on (σ' the time at the
                // leading edge): a jump f(start) there, then df = w cos(wσ' + φ) dσ'.
                let (w, p) = (*omega, *phase);
                let t_le = t - delay;
                let f = (w * t_le + p).sin();
                let f0 = (w * self.start + p).sin();
                let (s1, c1) = (w * t_le + p).sin_cos();
                let (s0, c0) = (w * self.start + p).sin_cos();
                f - KUSSNER_A
                    .iter()
                    .zip(lambdas)
                    .map(|(a, l)| {
                        let decay = (-l * tau).exp();
                        a * (f0 * decay
                            + w / (l * l + w * w) * (l * c1 + w * s1 - decay * (l * c0 + w * s0)))
                    })
                    .sum::<f64>()
            }
            GustShape::History(TimeFunction::Constant) => kussner_fit(u0 * tau / b),
            // Refused by `FlightHistory::validate`.
            GustShape::History(_) | GustShape::Turbulence(_) => f64::NAN,
        }
    }

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
            GustShape::Turbulence(r) => {
                if tau >= 0.0 {
                    r.value_and_rate(tau).0
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

/// The flight condition over time: `U(t) = U₀ + ΔU f_U(t)`, `α_r(t) = α_r0 + Δα f_α(t)`, a
/// gust, and the control surfaces' deflections `δ_k(t) = δ_k0 + Δδ_k f_k(t)`.
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
    /// Per control surface (in the order of the surfaces, possibly fewer), the change of its
    /// deflection `Δδ` (rad, trailing edge down) and its time function, or `None` (held at its
    /// equilibrium deflection). The rates follow the function: `δ̇ = Δδ f'(t)`, `δ̈ = Δδ f''(t)`
    /// (a sine's exact derivatives; a ramp or table is piecewise linear, its rate the slope of
    /// each piece and no acceleration; a step's jump carries no rate).
    pub deflection_changes: Vec<Option<(f64, TimeFunction)>>,
}

impl FlightHistory {
    /// Steady flight in the condition `initial`.
    pub fn steady(initial: FlightCondition) -> Self {
        Self {
            initial,
            speed_change: None,
            root_angle_change: None,
            gust: None,
            deflection_changes: Vec::new(),
        }
    }

    /// The deflections `(δ, δ̇, δ̈)` (rad, rad/s, rad/s²) of the surfaces at `t` into `out`, which
    /// holds their equilibrium values `(δ_0, 0, 0)` on entry.
    pub(crate) fn add_deflection_changes(&self, t: f64, out: &mut [[f64; 3]]) {
        for (o, change) in out.iter_mut().zip(&self.deflection_changes) {
            if let Some((d, f)) = change {
                o[0] += d * f.at(t);
                o[1] += d * time_function_rate(f, t);
                o[2] += d * time_function_acceleration(f, t);
            }
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

    /// Check the surfaces' deflection changes for a run over `[t0, t1]` against the surfaces'
    /// equilibrium deflections `rest`: finite, valid time functions, `|δ(t)| < 90°` (sampled at
    /// 201 times and the table's); errors name `{surfaces}[k].deflection_change` and
    /// `{surfaces}[k].deflection_function` (`surfaces`: the surfaces' key, `aero.surfaces`).
    ///
    /// # Errors
    /// As above, and more changes than surfaces.
    pub fn validate_deflection_changes(
        &self,
        surfaces: &str,
        rest: &[f64],
        t0: f64,
        t1: f64,
    ) -> Result<(), InputError> {
        if self.deflection_changes.len() > rest.len() {
            return Err(InputError::new(
                surfaces,
                format!(
                    "{} deflection changes for {} surfaces",
                    self.deflection_changes.len(),
                    rest.len()
                ),
            ));
        }
        for (k, change) in self.deflection_changes.iter().enumerate() {
            let Some((d, f)) = change else { continue };
            let key = |name: &str| format!("{surfaces}[{k}].{name}");
            if !d.is_finite() {
                return Err(InputError::new(
                    key("deflection_change"),
                    format!("must be finite, got {d}"),
                ));
            }
            crate::magnitude::check(&key("deflection_change"), "", *d)?;
            f.validate(&key("deflection_function"), t0, t1)?;
            let mut times: Vec<f64> = (0..=200)
                .map(|i| t0 + (t1 - t0) * i as f64 / 200.0)
                .collect();
            if let TimeFunction::Table { t, .. } = f {
                times.extend(t.iter().copied().filter(|s| (t0..=t1).contains(s)));
            }
            if let Some(t) = times
                .into_iter()
                .find(|&t| (rest[k] + d * f.at(t)).abs() >= 0.5 * std::f64::consts::PI)
            {
                return Err(InputError::new(
                    key("deflection_change"),
                    format!(
                        "makes the deflection {} rad at t = {} s: thin-airfoil flap theory needs \
                         |δ| well below 90° (π/2 rad)",
                        crate::text::short(rest[k] + d * f.at(t)),
                        crate::text::short(t)
                    ),
                ));
            }
        }
        Ok(())
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
            if g.penetration == GustPenetration::Kussner {
                let closed_form = match &g.shape {
                    GustShape::SharpEdged | GustShape::OneMinusCosine { .. } => true,
                    GustShape::History(f) => {
                        matches!(f, TimeFunction::Sine { .. } | TimeFunction::Constant)
                    }
                    GustShape::Turbulence(_) => false,
                };
                if !closed_form {
                    return Err(InputError::new(
                        format!("{field}.gust.penetration"),
                        "\"kussner\" takes a sharp-edged, 1−cos, sine or constant gust, not a \
                         turbulence realization",
                    ));
                }
                if !(self.initial.speed > 0.0) {
                    return Err(InputError::new(
                        format!("{field}.speed"),
                        "Küssner's penetration convects the gust front with the free stream: \
                         the speed must be positive",
                    ));
                }
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

/// `f'(t)` of a time function, away from its jumps; at a kink the left limit (the rate over the
/// interval ending at `t`, as an integration or a stepper's interval reaching `t` used it: the
/// outputs at a table's times are then those at the end of each interval).
fn time_function_rate(f: &TimeFunction, t: f64) -> f64 {
    match f {
        TimeFunction::Constant | TimeFunction::Step { .. } => 0.0,
        TimeFunction::Sine { omega, phase } => omega * (omega * t + phase).cos(),
        TimeFunction::Ramp { start, end } => {
            if t > *start && t <= *end {
                1.0 / (end - start)
            } else {
                0.0
            }
        }
        TimeFunction::Table { t: ts, value } => {
            let last = ts.len() - 1;
            if t <= ts[0] || t > ts[last] {
                return 0.0;
            }
            let k = ts.partition_point(|&s| s < t);
            (value[k] - value[k - 1]) / (ts[k] - ts[k - 1])
        }
    }
}

/// `f''(t)` of a time function: a sine's `−ω² sin(ωt + φ)`; zero for the piecewise-linear ones
/// (their kinks' impulses are not represented) and the constant and step.
fn time_function_acceleration(f: &TimeFunction, t: f64) -> f64 {
    match f {
        TimeFunction::Sine { omega, phase } => -omega * omega * (omega * t + phase).sin(),
        _ => 0.0,
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

    /// The rate at `t`: the slope over `[t0, t1]` (both ends: the interval a stepper integrates,
    /// its last stage at `t1`), zero outside it and for a held value.
    pub fn rate(&self, t: f64) -> f64 {
        if self.t1 > self.t0 && t >= self.t0 && t <= self.t1 {
            (self.v1 - self.v0) / (self.t1 - self.t0)
        } else {
            0.0
        }
    }
}

/// Increments of the flight condition set from outside between integrations (a stepper's or an
/// FMU's inputs, `analysis::aero::stepper`), added to the flight history's root angle, speed,
/// uniform gust and surface deflections; zero by default.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct FlightOffsets {
    /// Root angle (rad).
    pub root_angle: Segment,
    /// Free-stream speed (m/s).
    pub speed: Segment,
    /// Uniform vertical gust velocity (m/s, up).
    pub gust: Segment,
    /// Deflection of each control surface (rad; fewer than the surfaces: the others none):
    /// the segment's value and rate are `δ` and `δ̇` (no `δ̈`: a hold is piecewise linear).
    pub deflections: Vec<Segment>,
}

impl FlightOffsets {
    /// The deflections' increments `(δ, δ̇, 0)` at `t` added to `out`.
    pub(crate) fn add_deflections(&self, t: f64, out: &mut [[f64; 3]]) {
        for (o, s) in out.iter_mut().zip(&self.deflections) {
            o[0] += s.at(t);
            o[1] += s.rate(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gust(shape: GustShape) -> Gust {
        Gust {
            shape,
            amplitude: 1.0,
            start: 0.1,
            spanwise: Profile::Uniform(1.0),
            penetration: GustPenetration::Kussner,
        }
    }

    /// The closed forms of the Küssner states against a direct integration of the fit's state
    /// equations `ż_k = (u0/b)(f − β_k z_k)` (RK4, 20 000 steps: error ~1e-12, and the jumps
    /// fall on steps), for every shape; the rates against central differences of the factor
    /// (step 1e-6 s: error ~1e-9 of the peak rate).
    #[test]
    fn closed_forms_agree_with_the_state_equations() {
        let (u0, b, delay) = (20.0, 0.5, 0.05);
        let shapes = [
            GustShape::SharpEdged,
            GustShape::OneMinusCosine { length: 3.0 },
            GustShape::History(TimeFunction::Sine {
                omega: 9.0,
                phase: 0.4,
            }),
        ];
        for shape in shapes {
            let g = gust(shape);
            let (t0, t1, steps) = (g.start + delay, 0.6, 20_000);
            let h = (t1 - t0) / steps as f64;
            let f = |t: f64| g.factor(t - delay, u0);
            let mut z = [0.0; 3];
            // The jump at the arrival is in f(t0⁺); integrate from just after it.
            let rate = |t: f64, z: &[f64; 3]| -> [f64; 3] {
                std::array::from_fn(|k| u0 / b * (f(t) - KUSSNER_BETA[k] * z[k]))
            };
            let mut worst: f64 = 0.0;
            for i in 0..steps {
                let t = t0 + i as f64 * h + 1e-15;
                let k1 = rate(t, &z);
                let zk = |k: &[f64; 3], c: f64| std::array::from_fn(|j| z[j] + c * h * k[j]);
                let k2 = rate(t + 0.5 * h, &zk(&k1, 0.5));
                let k3 = rate(t + 0.5 * h, &zk(&k2, 0.5));
                let k4 = rate(t + h, &zk(&k3, 1.0));
                for j in 0..3 {
                    z[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
                }
                let out: f64 = (0..3).map(|k| KUSSNER_A[k] * KUSSNER_BETA[k] * z[k]).sum();
                let exact = g.kussner_factor(t + h, u0, b, delay);
                worst = worst.max((out - exact).abs());
            }
            assert!(worst < 1e-9, "{:?}: {worst:.2e}", g.shape);
            let g = Gust {
                penetration: GustPenetration::Uniform,
                ..g
            };
            for t in [0.13, 0.2, 0.24, 0.4] {
                let fd = (g.factor(t + 1e-6, u0) - g.factor(t - 1e-6, u0)) / 2e-6;
                assert!(
                    (fd - g.rate(t, u0)).abs() < 1e-6 * 10.0,
                    "{:?} {t}",
                    g.shape
                );
            }
        }
    }
}
