//! `[dynamic]` and the time histories of `[[loads]]` into a plan: which models to simulate, the
//! output times, the integrator settings, the damping, the initial state and one time function
//! per active load. Values the library checks again (time functions, damping coefficients) are
//! checked here first, so that bad input is reported before anything runs.

use flexwing::solve::{Damping, Gyroscopic, TimeFunction};
use flexwing::InputError;

use super::spec::{
    Case, DampingKindSpec, DampingSpec, DynamicSpec, GyroscopicSpec, InitialKindSpec, InitialSpec,
    IntegratorSpec, TimeKindSpec, TimeSpec,
};
use super::statics::{reduced_plans, ReducedPlan};
use crate::output::short;

/// Most output times of a run: every output time keeps the whole state in memory.
pub const MAX_OUTPUT_TIMES: usize = 100_000;

/// Default relative tolerance.
pub const DEFAULT_RTOL: f64 = 1e-6;
/// Default absolute tolerance on the coordinates (rad).
pub const DEFAULT_ATOL: f64 = 1e-8;
/// Default largest BDF order.
pub const DEFAULT_MAX_ORDER: usize = 2;
/// Default budget of integrator steps per model (accepted and rejected): the library's default.
pub const DEFAULT_MAX_STEPS: usize = 1_000_000;
/// Default step of the finite-difference gyroscopic term (rad), as the paper's eq. 17.
pub const DEFAULT_GYROSCOPIC_STEP: f64 = 1e-6;
/// Smallest accepted relative tolerance: below it round-off dominates the error estimates.
const MIN_RTOL: f64 = 1e-13;

/// What `flexwing dynamic` simulates.
#[derive(Debug, Clone)]
pub struct DynamicPlan {
    /// End of the simulated time (s); the run starts at 0.
    pub end_time: f64,
    /// Output times (s), strictly increasing, within `[0, end_time]`.
    pub output_times: Vec<f64>,
    /// The models, in the order full, simplified, `reduced`, `reduced_modes`.
    pub models: Vec<ModelPlan>,
    /// Integrator settings shared by the models.
    pub settings: IntegratorSettings,
    /// Structural damping of the full model (reduced models get its projection).
    pub damping: Damping,
    /// The state at `t = 0`.
    pub initial: InitialPlan,
    /// Indices (in `[[loads]]`) of the loads that act during the motion.
    pub active: Vec<usize>,
    /// The time function of each active load, in the order of `active`.
    pub time_functions: Vec<TimeFunction>,
}

/// One model to simulate.
#[derive(Debug, Clone)]
pub struct ModelPlan {
    /// `full`, `simplified`, `reduced-r2`, `reduced-modes-1-3`.
    pub label: String,
    /// Which model.
    pub kind: ModelKind,
    /// How its gyroscopic term is obtained.
    pub gyroscopic: Gyroscopic,
    /// Its integrator.
    pub integrator: Integrator,
}

/// The kind of a simulated model.
#[derive(Debug, Clone)]
pub enum ModelKind {
    /// The full model.
    Full,
    /// The full model with the gyroscopic term neglected.
    Simplified,
    /// A reduced model.
    Reduced(ReducedPlan),
}

/// A time integrator of the library.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Variable-order BDF/NDF.
    Bdf,
    /// Dormand–Prince 5(4).
    Dopri5,
    /// Implicit midpoint rule.
    Midpoint,
    /// Radau IIA of order 5.
    Radau,
}

impl Integrator {
    /// The case-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Bdf => "bdf",
            Integrator::Dopri5 => "dopri5",
            Integrator::Midpoint => "midpoint",
            Integrator::Radau => "radau",
        }
    }
}

/// Tolerances and options of the integrators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegratorSettings {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on the coordinates (rad).
    pub atol: f64,
    /// Largest BDF order.
    pub max_order: usize,
    /// Fixed step of the implicit midpoint rule (s); adaptive without it.
    pub step: Option<f64>,
    /// Budget of integrator steps per model.
    pub max_steps: usize,
    /// Largest step of the adaptive integrators (s); unlimited without it.
    pub max_step: Option<f64>,
}

/// The state at `t = 0`.
#[derive(Debug, Clone, PartialEq)]
pub enum InitialPlan {
    /// Undeformed, at rest.
    Rest,
    /// Each model's static equilibrium under these loads at their full value, at rest.
    Static {
        /// Indices of the loads in `[[loads]]`.
        loads: Vec<usize>,
        /// Their names.
        names: Vec<String>,
    },
    /// Given joint rotations and rates of the full model.
    Given {
        /// Joint rotations (rad).
        q: Vec<f64>,
        /// Joint rotation rates (rad/s).
        qdot: Vec<f64>,
    },
}

impl Case {
    /// The plan of `[dynamic]` for a full model of `n_dofs` coordinates.
    ///
    /// # Errors
    /// No `[dynamic]` table, a value out of range, keys that do not belong together, unknown
    /// load names, nothing to simulate; each names its key.
    pub fn dynamic_plan(&self, n_dofs: usize) -> Result<DynamicPlan, InputError> {
        let d = self.dynamic.as_ref().ok_or_else(|| {
            InputError::new(
                "dynamic",
                "missing: flexwing dynamic needs a [dynamic] table (at least end_time, and \
                 output_step or output_times)",
            )
        })?;
        let end_time = d.end_time;
        if !(end_time > 0.0 && end_time.is_finite()) {
            return Err(InputError::new(
                "dynamic.end_time",
                format!("must be a finite positive number, got {}", short(end_time)),
            ));
        }
        let output_times = output_times(d)?;
        let settings = settings(d)?;
        let models = models(d)?;
        let (active, time_functions) = self.time_functions(end_time)?;
        Ok(DynamicPlan {
            end_time,
            output_times,
            models,
            settings,
            damping: damping(d.damping.as_ref(), n_dofs)?,
            initial: self.initial(d.initial.as_ref(), n_dofs)?,
            active,
            time_functions,
        })
    }

    /// The active loads and their time functions, checked over `[0, end_time]`.
    fn time_functions(&self, end_time: f64) -> Result<(Vec<usize>, Vec<TimeFunction>), InputError> {
        let mut active = Vec::new();
        let mut functions = Vec::new();
        for (i, load) in self.loads.iter().enumerate() {
            let field = format!("loads[{i}].time");
            if load.active == Some(false) {
                if load.time.is_some() {
                    return Err(InputError::new(
                        field,
                        "the load is inactive (active = false) and takes no time history; \
                         remove time, or set active = true",
                    ));
                }
                continue;
            }
            let f = match &load.time {
                None => TimeFunction::Constant,
                Some(spec) => time_function(&field, spec)?,
            };
            f.validate(&field, 0.0, end_time)?;
            active.push(i);
            functions.push(f);
        }
        Ok((active, functions))
    }

    fn initial(
        &self,
        spec: Option<&InitialSpec>,
        n_dofs: usize,
    ) -> Result<InitialPlan, InputError> {
        let Some(s) = spec else {
            return Ok(InitialPlan::Rest);
        };
        let field = |key: &str| format!("dynamic.initial.{key}");
        let (name, allowed): (&str, &[&str]) = match s.kind {
            InitialKindSpec::Rest => ("rest", &[]),
            InitialKindSpec::Static => ("static", &["loads"]),
            InitialKindSpec::Given => ("given", &["q", "qdot"]),
        };
        let given = [
            ("loads", s.loads.is_some()),
            ("q", s.q.is_some()),
            ("qdot", s.qdot.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|(k, g)| *g && !allowed.contains(k)) {
            let takes = match s.kind {
                InitialKindSpec::Rest => "no other key",
                InitialKindSpec::Static => "loads",
                InitialKindSpec::Given => "q and qdot",
            };
            return Err(InputError::new(
                field(key),
                format!("is not a key of a {name:?} initial state, which takes {takes}"),
            ));
        }
        match s.kind {
            InitialKindSpec::Rest => Ok(InitialPlan::Rest),
            InitialKindSpec::Static => {
                let names = s.loads.clone().unwrap_or_default();
                if names.is_empty() {
                    return Err(InputError::new(
                        field("loads"),
                        "missing: a \"static\" initial state needs the names of the [[loads]] \
                         it is the equilibrium under, e.g. loads = [\"F0\"]",
                    ));
                }
                let mut loads = Vec::new();
                for (k, n) in names.iter().enumerate() {
                    let f = format!("dynamic.initial.loads[{k}]");
                    let i = self
                        .load_index(n)
                        .ok_or_else(|| InputError::new(&f, self.unknown_load(n)))?;
                    if loads.contains(&i) {
                        return Err(InputError::new(f, format!("{n:?} is listed twice")));
                    }
                    loads.push(i);
                }
                Ok(InitialPlan::Static { loads, names })
            }
            InitialKindSpec::Given => {
                if s.q.is_none() && s.qdot.is_none() {
                    return Err(InputError::new(
                        field("q"),
                        "missing: a \"given\" initial state needs q (joint rotations, rad) \
                         and/or qdot (rates, rad/s)",
                    ));
                }
                let vector = |key: &str, v: &Option<Vec<f64>>| -> Result<Vec<f64>, InputError> {
                    let Some(v) = v else {
                        return Ok(vec![0.0; n_dofs]);
                    };
                    if v.len() != n_dofs {
                        return Err(InputError::new(
                            field(key),
                            format!(
                                "needs {n_dofs} values (one per coordinate of the full model), \
                                 got {}",
                                v.len()
                            ),
                        ));
                    }
                    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
                        return Err(InputError::new(
                            format!("dynamic.initial.{key}[{k}]"),
                            format!("must be finite, got {}", short(v[k])),
                        ));
                    }
                    Ok(v.clone())
                };
                Ok(InitialPlan::Given {
                    q: vector("q", &s.q)?,
                    qdot: vector("qdot", &s.qdot)?,
                })
            }
        }
    }

    /// The reason for an unknown load name, listing the known ones.
    pub(super) fn unknown_load(&self, name: &str) -> String {
        let names: Vec<String> = self
            .loads
            .iter()
            .filter_map(|l| l.name.as_ref().map(|n| format!("{n:?}")))
            .collect();
        let known = if names.is_empty() {
            "no load has a name; give one with name = \"...\" in its [[loads]] table".to_string()
        } else {
            format!("the named loads are {}", names.join(", "))
        };
        format!("no load named {name:?} ({known})")
    }
}

fn output_times(d: &DynamicSpec) -> Result<Vec<f64>, InputError> {
    let end = d.end_time;
    let too_many = |field: &str, n: f64| {
        InputError::new(
            field,
            format!("gives {n} output times; at most {MAX_OUTPUT_TIMES} are allowed"),
        )
    };
    match (d.output_step, &d.output_times) {
        (Some(_), Some(_)) => Err(InputError::new(
            "dynamic.output_step",
            "give either output_step or output_times, not both",
        )),
        (None, None) => Err(InputError::new(
            "dynamic.output_step",
            "missing: give output_step (s, outputs at 0, step, 2 step, … end_time) or \
             output_times = [...]",
        )),
        (Some(dt), None) => {
            let field = "dynamic.output_step";
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(InputError::new(
                    field,
                    format!("must be a finite positive number, got {}", short(dt)),
                ));
            }
            if dt > end {
                return Err(InputError::new(
                    field,
                    format!("{} is longer than end_time {}", short(dt), short(end)),
                ));
            }
            // Outputs at k·dt (not accumulated), and end_time itself if it is not a multiple.
            let intervals = (end / dt * (1.0 + 1e-12)).floor();
            if intervals + 2.0 > MAX_OUTPUT_TIMES as f64 {
                return Err(too_many(field, intervals + 1.0));
            }
            let mut t: Vec<f64> = (0..=intervals as usize)
                .map(|k| (k as f64 * dt).min(end))
                .collect();
            let last = t[t.len() - 1];
            if end - last > 1e-9 * end {
                t.push(end);
            } else if let Some(l) = t.last_mut() {
                *l = end;
            }
            Ok(t)
        }
        (None, Some(times)) => {
            if times.is_empty() {
                return Err(InputError::new("dynamic.output_times", "must not be empty"));
            }
            if times.len() > MAX_OUTPUT_TIMES {
                return Err(too_many("dynamic.output_times", times.len() as f64));
            }
            for (i, &t) in times.iter().enumerate() {
                let field = format!("dynamic.output_times[{i}]");
                if !t.is_finite() {
                    return Err(InputError::new(
                        field,
                        format!("must be finite, got {}", short(t)),
                    ));
                }
                if t < 0.0 {
                    return Err(InputError::new(
                        field,
                        format!("{} is before the start time 0", short(t)),
                    ));
                }
                if t > end {
                    return Err(InputError::new(
                        field,
                        format!("{} is after end_time {}", short(t), short(end)),
                    ));
                }
                if i > 0 && t <= times[i - 1] {
                    return Err(InputError::new(
                        field,
                        format!(
                            "{} is not after output_times[{}] = {}; output times must increase",
                            short(t),
                            i - 1,
                            short(times[i - 1])
                        ),
                    ));
                }
            }
            Ok(times.clone())
        }
    }
}

fn settings(d: &DynamicSpec) -> Result<IntegratorSettings, InputError> {
    let rtol = d.rtol.unwrap_or(DEFAULT_RTOL);
    if !(MIN_RTOL..1.0).contains(&rtol) {
        return Err(InputError::new(
            "dynamic.rtol",
            format!(
                "must be a number in [{}, 1), got {}",
                short(MIN_RTOL),
                short(rtol)
            ),
        ));
    }
    let atol = d.atol.unwrap_or(DEFAULT_ATOL);
    if !(atol > 0.0 && atol.is_finite()) {
        return Err(InputError::new(
            "dynamic.atol",
            format!("must be a finite positive number, got {}", short(atol)),
        ));
    }
    if let Some(m) = d.max_order {
        if d.integrator != IntegratorSpec::Bdf {
            return Err(InputError::new(
                "dynamic.max_order",
                "is an option of the BDF integrator; it needs integrator = \"bdf\"",
            ));
        }
        if !(1..=5).contains(&m) {
            return Err(InputError::new(
                "dynamic.max_order",
                format!("must be between 1 and 5, got {m}"),
            ));
        }
    }
    if let Some(h) = d.step {
        if d.integrator != IntegratorSpec::Midpoint {
            return Err(InputError::new(
                "dynamic.step",
                "is the fixed step of the implicit midpoint rule; it needs \
                 integrator = \"midpoint\" (the other integrators choose their steps)",
            ));
        }
        if !(h > 0.0 && h.is_finite()) {
            return Err(InputError::new(
                "dynamic.step",
                format!("must be a finite positive number, got {}", short(h)),
            ));
        }
    }
    if let Some(h) = d.max_step {
        if !(h > 0.0 && h.is_finite()) {
            return Err(InputError::new(
                "dynamic.max_step",
                format!("must be a finite positive number, got {}", short(h)),
            ));
        }
        if d.step.is_some() {
            return Err(InputError::new(
                "dynamic.max_step",
                "caps the steps of the adaptive integrators; it cannot be given with the fixed \
                 step `step`",
            ));
        }
    }
    if d.max_steps == Some(0) {
        return Err(InputError::new(
            "dynamic.max_steps",
            "must be at least 1, got 0",
        ));
    }
    Ok(IntegratorSettings {
        rtol,
        atol,
        max_order: d.max_order.unwrap_or(DEFAULT_MAX_ORDER),
        step: d.step,
        max_steps: d.max_steps.unwrap_or(DEFAULT_MAX_STEPS),
        max_step: d.max_step,
    })
}

fn models(d: &DynamicSpec) -> Result<Vec<ModelPlan>, InputError> {
    let gyroscopic = match (d.gyroscopic, d.gyroscopic_step) {
        (GyroscopicSpec::FiniteDifference, step) => {
            let step = step.unwrap_or(DEFAULT_GYROSCOPIC_STEP);
            if !(step > 0.0 && step.is_finite()) {
                return Err(InputError::new(
                    "dynamic.gyroscopic_step",
                    format!("must be a finite positive number, got {}", short(step)),
                ));
            }
            Gyroscopic::FiniteDifference { step }
        }
        (_, Some(_)) => {
            return Err(InputError::new(
                "dynamic.gyroscopic_step",
                "is the step of the finite-difference gyroscopic term; it needs \
                 gyroscopic = \"finite-difference\"",
            ))
        }
        (GyroscopicSpec::Exact, None) => Gyroscopic::Exact,
        (GyroscopicSpec::Neglected, None) => Gyroscopic::Neglected,
    };
    let integrator = match d.integrator {
        // Radau for every model: on the paper's cases it needs fewer right-hand sides than BDF2
        // on the full model (10–20 times) and than Dormand–Prince on reduced models (from r = 2
        // on), docs/performance.md.
        IntegratorSpec::Auto | IntegratorSpec::Radau => Integrator::Radau,
        IntegratorSpec::Bdf => Integrator::Bdf,
        IntegratorSpec::Dopri5 => Integrator::Dopri5,
        IntegratorSpec::Midpoint => Integrator::Midpoint,
    };
    let mut models = Vec::new();
    if d.full {
        models.push(ModelPlan {
            label: "full".into(),
            kind: ModelKind::Full,
            gyroscopic,
            integrator,
        });
    }
    if d.simplified {
        models.push(ModelPlan {
            label: "simplified".into(),
            kind: ModelKind::Simplified,
            gyroscopic: Gyroscopic::Neglected,
            integrator,
        });
    }
    for r in reduced_plans("dynamic", &d.reduced, &d.reduced_modes)? {
        models.push(ModelPlan {
            label: r.label.clone(),
            kind: ModelKind::Reduced(r),
            gyroscopic,
            integrator,
        });
    }
    if models.is_empty() {
        return Err(InputError::new(
            "dynamic.full",
            "nothing to simulate: full = false, simplified = false and no reduced models \
             (give dynamic.reduced or dynamic.reduced_modes)",
        ));
    }
    Ok(models)
}

fn damping(spec: Option<&DampingSpec>, n_dofs: usize) -> Result<Damping, InputError> {
    let Some(s) = spec else {
        return Ok(Damping::None);
    };
    let field = |key: &str| format!("dynamic.damping.{key}");
    let (name, allowed, takes): (&str, &[&str], &str) = match s.kind {
        DampingKindSpec::None => ("none", &[], "no other key"),
        DampingKindSpec::Rayleigh => ("rayleigh", &["alpha", "beta"], "alpha and beta"),
        DampingKindSpec::Modal => ("modal", &["ratios"], "ratios"),
    };
    let given = [
        ("alpha", s.alpha.is_some()),
        ("beta", s.beta.is_some()),
        ("ratios", s.ratios.is_some()),
    ];
    if let Some((key, _)) = given.iter().find(|(k, g)| *g && !allowed.contains(k)) {
        return Err(InputError::new(
            field(key),
            format!("is not a key of {name:?} damping, which takes {takes}"),
        ));
    }
    let non_negative = |f: String, v: f64| {
        if v >= 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(InputError::new(
                f,
                format!("must be a finite non-negative number, got {}", short(v)),
            ))
        }
    };
    match s.kind {
        DampingKindSpec::None => Ok(Damping::None),
        DampingKindSpec::Rayleigh => {
            if s.alpha.is_none() && s.beta.is_none() {
                return Err(InputError::new(
                    field("alpha"),
                    "missing: Rayleigh damping C = alpha M(0) + beta K needs alpha (1/s) \
                     and/or beta (s)",
                ));
            }
            Ok(Damping::Rayleigh {
                alpha: non_negative(field("alpha"), s.alpha.unwrap_or(0.0))?,
                beta: non_negative(field("beta"), s.beta.unwrap_or(0.0))?,
            })
        }
        DampingKindSpec::Modal => {
            let ratios = s.ratios.clone().unwrap_or_default();
            if ratios.is_empty() {
                return Err(InputError::new(
                    field("ratios"),
                    "missing: modal damping needs the damping ratios of modes 1, 2, … \
                     (e.g. ratios = [0.02, 0.02])",
                ));
            }
            if ratios.len() > n_dofs {
                return Err(InputError::new(
                    field("ratios"),
                    format!(
                        "{} ratios given but the model has {n_dofs} modes",
                        ratios.len()
                    ),
                ));
            }
            for (k, &z) in ratios.iter().enumerate() {
                non_negative(format!("dynamic.damping.ratios[{k}]"), z)?;
            }
            Ok(Damping::Modal { ratios })
        }
    }
}

/// The library's time function of `loads[i].time`, after checking which keys were given.
fn time_function(field: &str, s: &TimeSpec) -> Result<TimeFunction, InputError> {
    let key = |k: &str| format!("{field}.{k}");
    let (name, allowed, takes): (&str, &[&str], &str) = match s.kind {
        TimeKindSpec::Constant => ("constant", &[], "no other key"),
        TimeKindSpec::Sine => ("sine", &["omega", "phase"], "omega and phase"),
        TimeKindSpec::Step => ("step", &["time"], "time"),
        TimeKindSpec::Ramp => ("ramp", &["start", "end"], "start and end"),
        TimeKindSpec::Table => ("table", &["t", "value"], "t and value"),
    };
    let given = [
        ("omega", s.omega.is_some()),
        ("phase", s.phase.is_some()),
        ("time", s.time.is_some()),
        ("start", s.start.is_some()),
        ("end", s.end.is_some()),
        ("t", s.t.is_some()),
        ("value", s.value.is_some()),
    ];
    if let Some((k, _)) = given.iter().find(|(k, g)| *g && !allowed.contains(k)) {
        return Err(InputError::new(
            key(k),
            format!("is not a key of a {name:?} time history, which takes {takes}"),
        ));
    }
    let required = |k: &str, v: Option<f64>, what: &str| {
        v.ok_or_else(|| {
            InputError::new(
                key(k),
                format!("missing: a {name:?} time history needs {k} ({what})"),
            )
        })
    };
    Ok(match s.kind {
        TimeKindSpec::Constant => TimeFunction::Constant,
        TimeKindSpec::Sine => TimeFunction::Sine {
            omega: required("omega", s.omega, "circular frequency, rad/s")?,
            phase: s.phase.unwrap_or(0.0),
        },
        TimeKindSpec::Step => TimeFunction::Step {
            time: required("time", s.time, "the switch time, s")?,
        },
        TimeKindSpec::Ramp => TimeFunction::Ramp {
            start: s.start.unwrap_or(0.0),
            end: required("end", s.end, "the time the ramp reaches 1, s")?,
        },
        TimeKindSpec::Table => {
            let list = |k: &str, v: &Option<Vec<f64>>, what: &str| {
                v.clone().ok_or_else(|| {
                    InputError::new(
                        key(k),
                        format!("missing: a \"table\" time history needs {k} ({what})"),
                    )
                })
            };
            TimeFunction::Table {
                t: list("t", &s.t, "times, s")?,
                value: list("value", &s.value, "the factor at each time")?,
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const BEAM: &str = "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\n\
         mass_per_length = 0.2\n\n[[loads]]\nname = \"F0\"\ntype = \"point-force\"\nnode = 4\n\
         direction = \"dead\"\nfy = 1\n";

    fn plan_of(loads: &str, dynamic: &str) -> Result<DynamicPlan, String> {
        let case = Case::parse(&format!("{BEAM}{loads}\n[dynamic]\n{dynamic}"), "x.toml")?;
        case.dynamic_plan(4).map_err(|e| e.to_string())
    }

    fn plan(dynamic: &str) -> Result<DynamicPlan, String> {
        plan_of("", dynamic)
    }

    #[test]
    fn defaults() {
        let p = plan("end_time = 1\noutput_step = 0.25\n").unwrap();
        assert_eq!(p.output_times, [0.0, 0.25, 0.5, 0.75, 1.0]);
        let labels: Vec<_> = p.models.iter().map(|m| m.label.as_str()).collect();
        assert_eq!(labels, ["full"]);
        assert_eq!(p.models[0].integrator, Integrator::Radau);
        assert_eq!(p.models[0].gyroscopic, Gyroscopic::Exact);
        assert_eq!(p.settings.rtol, DEFAULT_RTOL);
        assert_eq!(p.settings.atol, DEFAULT_ATOL);
        assert_eq!(p.settings.max_order, 2);
        assert_eq!(p.damping, Damping::None);
        assert_eq!(p.initial, InitialPlan::Rest);
        assert_eq!(p.active, [0]);
        assert_eq!(p.time_functions, [TimeFunction::Constant]);
    }

    #[test]
    fn output_step_ends_at_end_time() {
        let p = plan("end_time = 1\noutput_step = 0.3\n").unwrap();
        assert_eq!(p.output_times.len(), 5);
        assert_eq!(p.output_times[4], 1.0);
        let p = plan("end_time = 1\noutput_step = 0.005\n").unwrap();
        assert_eq!(p.output_times.len(), 201);
        assert_eq!(p.output_times[200], 1.0);
        assert!((p.output_times[77] - 0.385).abs() < 1e-15);
    }

    #[test]
    fn models_and_integrators() {
        let p = plan(
            "end_time = 1\noutput_step = 0.5\nsimplified = true\nreduced = [2]\n\
             reduced_modes = [[1, 3]]\n",
        )
        .unwrap();
        let got: Vec<_> = p
            .models
            .iter()
            .map(|m| (m.label.as_str(), m.integrator, m.gyroscopic))
            .collect();
        assert_eq!(
            got,
            [
                ("full", Integrator::Radau, Gyroscopic::Exact),
                ("simplified", Integrator::Radau, Gyroscopic::Neglected),
                ("reduced-r2", Integrator::Radau, Gyroscopic::Exact),
                ("reduced-modes-1-3", Integrator::Radau, Gyroscopic::Exact),
            ]
        );
        let p = plan(
            "end_time = 1\noutput_step = 0.5\nreduced = [2]\nintegrator = \"midpoint\"\n\
             step = 1e-3\ngyroscopic = \"finite-difference\"\n",
        )
        .unwrap();
        assert_eq!(p.models[1].integrator, Integrator::Midpoint);
        assert_eq!(
            p.models[1].gyroscopic,
            Gyroscopic::FiniteDifference { step: 1e-6 }
        );
        assert_eq!(p.settings.step, Some(1e-3));
    }

    #[test]
    fn time_histories_and_inactive_loads() {
        let loads = "time = { type = \"sine\", omega = 20 }\n\n[[loads]]\nname = \"G\"\n\
                     type = \"gravity\"\nactive = false\n";
        let p = plan_of(
            loads,
            "end_time = 1\noutput_step = 0.5\n\n[dynamic.initial]\ntype = \"static\"\n\
             loads = [\"G\"]\n",
        )
        .unwrap();
        assert_eq!(p.active, [0]);
        assert_eq!(
            p.time_functions,
            [TimeFunction::Sine {
                omega: 20.0,
                phase: 0.0
            }]
        );
        assert_eq!(
            p.initial,
            InitialPlan::Static {
                loads: vec![1],
                names: vec!["G".into()]
            }
        );
    }

    #[test]
    fn errors_name_the_field() {
        let d = "end_time = 1\noutput_step = 0.5\n";
        let cases: Vec<(&str, String, &str)> = vec![
            (
                "",
                "end_time = -1\noutput_step = 0.5\n".into(),
                "dynamic.end_time: must be a finite positive number, got -1",
            ),
            (
                "",
                "end_time = 1\noutput_times = [0, 0.5, 0.7, 2.0]\n".into(),
                "dynamic.output_times[3]: 2 is after end_time 1",
            ),
            (
                "",
                "end_time = 1\noutput_times = [0, 0.5, 0.5]\n".into(),
                "dynamic.output_times[2]: 0.5 is not after",
            ),
            ("", "end_time = 1\n".into(), "dynamic.output_step: missing"),
            (
                "",
                "end_time = 1\noutput_step = 0.1\noutput_times = [0]\n".into(),
                "dynamic.output_step: give either",
            ),
            (
                "",
                "end_time = 1\noutput_step = 1e-9\n".into(),
                "dynamic.output_step: gives",
            ),
            (
                "time = { type = \"table\", t = [0, 0.5], value = [0, 1] }\n",
                d.into(),
                "loads[0].time.t: table covers [0, 0.5] s but the simulation runs over [0, 1] s",
            ),
            (
                "time = { type = \"sine\" }\n",
                d.into(),
                "loads[0].time.omega: missing",
            ),
            (
                "time = { type = \"step\", omega = 3 }\n",
                d.into(),
                "loads[0].time.omega: is not a key of a \"step\" time history",
            ),
            (
                "time = { type = \"ramp\", start = 0.5, end = 0.2 }\n",
                d.into(),
                "loads[0].time.end: must be after start",
            ),
            (
                "active = false\ntime = { type = \"step\", time = 0.1 }\n",
                d.into(),
                "loads[0].time: the load is inactive",
            ),
            ("", format!("{d}rtol = 1e-300\n"), "dynamic.rtol: must be"),
            ("", format!("{d}rtol = 0\n"), "dynamic.rtol: must be"),
            ("", format!("{d}atol = -1\n"), "dynamic.atol: must be"),
            (
                "",
                format!("{d}integrator = \"bdf\"\nmax_order = 6\n"),
                "dynamic.max_order: must be",
            ),
            (
                "",
                format!("{d}integrator = \"dopri5\"\nmax_order = 3\n"),
                "dynamic.max_order: is an option of the BDF",
            ),
            (
                "",
                format!("{d}step = 1e-3\n"),
                "dynamic.step: is the fixed step",
            ),
            (
                "",
                format!("{d}max_step = -1\n"),
                "dynamic.max_step: must be a finite positive number",
            ),
            (
                "",
                format!("{d}integrator = \"midpoint\"\nstep = 1e-3\nmax_step = 1e-2\n"),
                "dynamic.max_step: caps the steps",
            ),
            (
                "",
                format!("{d}integrator = \"midpoint\"\nstep = 0\n"),
                "dynamic.step: must be",
            ),
            (
                "",
                format!("{d}gyroscopic_step = 1e-5\n"),
                "dynamic.gyroscopic_step: is the step",
            ),
            (
                "",
                format!("{d}gyroscopic = \"finite-difference\"\ngyroscopic_step = -1\n"),
                "dynamic.gyroscopic_step: must be",
            ),
            (
                "",
                format!("{d}full = false\n"),
                "dynamic.full: nothing to simulate",
            ),
            (
                "",
                format!("{d}reduced = [2, 2]\n"),
                "dynamic.reduced[1]: the model reduced-r2 is already",
            ),
            (
                "",
                format!("{d}damping = {{ type = \"rayleigh\", ratios = [0.1] }}\n"),
                "dynamic.damping.ratios: is not a key of \"rayleigh\" damping",
            ),
            (
                "",
                format!("{d}damping = {{ type = \"rayleigh\", beta = -1 }}\n"),
                "dynamic.damping.beta: must be a finite non-negative number",
            ),
            (
                "",
                format!(
                    "{d}damping = {{ type = \"modal\", ratios = [0.1, 0.1, 0.1, 0.1, 0.1] }}\n"
                ),
                "dynamic.damping.ratios: 5 ratios given but the model has 4 modes",
            ),
            (
                "",
                format!("{d}damping = {{ type = \"modal\", ratios = [0.1, nan] }}\n"),
                "dynamic.damping.ratios[1]: must be",
            ),
            (
                "",
                format!("{d}\n[dynamic.initial]\ntype = \"static\"\nloads = [\"F9\"]\n"),
                "dynamic.initial.loads[0]: no load named \"F9\" (the named loads are \"F0\")",
            ),
            (
                "",
                format!("{d}\n[dynamic.initial]\ntype = \"static\"\n"),
                "dynamic.initial.loads: missing",
            ),
            (
                "",
                format!("{d}\n[dynamic.initial]\ntype = \"rest\"\nq = [0, 0, 0, 0]\n"),
                "dynamic.initial.q: is not a key of a \"rest\" initial state",
            ),
            (
                "",
                format!("{d}\n[dynamic.initial]\ntype = \"given\"\nq = [0, 0]\n"),
                "dynamic.initial.q: needs 4 values",
            ),
            (
                "",
                format!("{d}\n[dynamic.initial]\ntype = \"given\"\nqdot = [0, 0, inf, 0]\n"),
                "dynamic.initial.qdot[2]: must be finite",
            ),
        ];
        for (loads, dynamic, expected) in cases {
            let msg = plan_of(loads, &dynamic).unwrap_err();
            assert!(msg.starts_with(expected), "{loads}{dynamic}: {msg}");
        }
        let case = Case::parse(BEAM, "x.toml").unwrap();
        let msg = case.dynamic_plan(4).unwrap_err().to_string();
        assert!(msg.starts_with("dynamic: missing"), "{msg}");
    }
}
