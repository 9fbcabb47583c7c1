//! `[dynamic]` and the time histories of `[[loads]]` into a [`DynamicPlan`]. The library checks
//! the values ([`DynamicPlan::validate`]: times, tolerances, damping, time histories over the
//! simulated time, the initial state's size); this module checks what it cannot see: which keys
//! were given together, load names, and how the output times are spelled.

use flexwing::analysis::dynamics::{AuditSettings, DynamicPlan, Initial, MAX_OUTPUT_TIMES};
use flexwing::model::FullModel;
use flexwing::solve::integrate::{IntegratorSettings, Method};
use flexwing::solve::{Damping, Gyroscopic, TimeFunction};
use flexwing::text::short;
use flexwing::InputError;

use super::spec::{
    Case, DampingKindSpec, DynamicSpec, EquationsSpec, GyroscopicSpec, InitialKindSpec,
    InitialSpec, IntegrationSpec, TimeKindSpec, TimeSpec,
};
use crate::CaseError;

impl Case {
    /// The dynamic analysis of `[[loads]]` and `[dynamic]`, validated.
    ///
    /// # Errors
    /// No `[dynamic]` table, keys that do not belong together, unknown load names, and every
    /// error of [`DynamicPlan::validate`], named as in the case file.
    pub fn dynamic_plan(&self) -> Result<DynamicPlan, CaseError> {
        self.not_aeroelastic("aero_dynamic_plan")
            .and_then(|()| self.checked_dynamic_plan())
            .map_err(|e| self.error(e))
    }

    pub(crate) fn checked_dynamic_plan(&self) -> Result<DynamicPlan, InputError> {
        let model = FullModel::new(self.to_beam()?);
        let loads = self.to_loads(model.beam())?;
        let p = self.dynamic_parts(model.n_dofs())?;
        let mut plan = DynamicPlan::new(model, loads, p.end_time, Vec::new());
        set_dynamic_parts!(plan, p);
        plan.validate("loads", "dynamic")?;
        Ok(plan)
    }

    /// What `[dynamic]` and the loads' time histories say, for a model of `n_dofs`
    /// coordinates: the planar plan's and the 3-D chain's ([`crate::chain3d`]) alike.
    pub(crate) fn dynamic_parts(&self, n_dofs: usize) -> Result<DynamicParts, InputError> {
        let d = self.dynamic.as_ref().ok_or_else(|| {
            InputError::new(
                "dynamic",
                "missing: flexwing dynamic needs a [dynamic] table (at least end_time, and \
                 output_step or output_times)",
            )
        })?;
        let output_times = output_times(d)?;
        let equations = d.equations();
        let (integrator, settings) = d.integration().to_settings("dynamic")?;
        let mut audit = AuditSettings {
            tolerance: d.energy_tolerance,
            ..AuditSettings::default()
        };
        if let Some(r) = d.energy_runaway {
            audit.runaway = r;
        }
        Ok(DynamicParts {
            end_time: d.end_time,
            // The node histories of `[output] node_times` (every front end writes these).
            snapshots: crate::thinned_indices(output_times.len(), self.output.max_node_times()),
            output_times,
            time: self.time_histories()?,
            full: d.full,
            simplified: d.simplified,
            reduced: d.reduced.clone(),
            reduced_modes: d.reduced_modes.clone(),
            gyroscopic: equations.to_gyroscopic("dynamic")?,
            integrator,
            settings,
            audit,
            damping: equations.to_damping("dynamic")?,
            initial: self.initial(d.initial.as_ref(), n_dofs)?,
            load_names: self.load_names(),
        })
    }

    /// The time history of each load during the motion (`None` for an inactive load).
    fn time_histories(&self) -> Result<Vec<Option<TimeFunction>>, InputError> {
        self.loads
            .iter()
            .enumerate()
            .map(|(i, load)| {
                let field = format!("loads[{i}].time");
                match (load.active, &load.time) {
                    (Some(false), Some(_)) => Err(InputError::new(
                        field,
                        "the load is inactive (active = false) and takes no time history; \
                         remove time, or set active = true",
                    )),
                    (Some(false), None) => Ok(None),
                    (_, None) => Ok(Some(TimeFunction::Constant)),
                    (_, Some(spec)) => time_function(&field, spec).map(Some),
                }
            })
            .collect()
    }

    fn initial(&self, spec: Option<&InitialSpec>, n_dofs: usize) -> Result<Initial, InputError> {
        let Some(s) = spec else {
            return Ok(Initial::Rest);
        };
        let field = |key: &str| format!("dynamic.initial.{key}");
        let (name, allowed, takes): (&str, &[&str], &str) = match s.kind {
            InitialKindSpec::Rest => ("rest", &[], "no other key"),
            InitialKindSpec::Static => ("static", &["loads"], "loads"),
            InitialKindSpec::Given => ("given", &["q", "qdot"], "q and qdot"),
        };
        let given = [
            ("loads", s.loads.is_some()),
            ("q", s.q.is_some()),
            ("qdot", s.qdot.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|(k, g)| *g && !allowed.contains(k)) {
            return Err(InputError::new(
                field(key),
                format!("is not a key of a {name:?} initial state, which takes {takes}"),
            ));
        }
        match s.kind {
            InitialKindSpec::Rest => Ok(Initial::Rest),
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
                Ok(Initial::Static { loads })
            }
            InitialKindSpec::Given => {
                if s.q.is_none() && s.qdot.is_none() {
                    return Err(InputError::new(
                        field("q"),
                        "missing: a \"given\" initial state needs q (joint rotations, rad) \
                         and/or qdot (rates, rad/s)",
                    ));
                }
                let zero = || vec![0.0; n_dofs];
                Ok(Initial::Given {
                    q: s.q.clone().unwrap_or_else(zero),
                    qdot: s.qdot.clone().unwrap_or_else(zero),
                })
            }
        }
    }

    /// Each load's name for messages: its `name`, or `loads[i]`.
    pub(crate) fn load_names(&self) -> Vec<String> {
        self.loads
            .iter()
            .enumerate()
            .map(|(i, l)| l.name.clone().unwrap_or_else(|| format!("loads[{i}]")))
            .collect()
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

/// Set the fields of a dynamic plan (the planar `DynamicPlan`, the 3-D chain's `Dynamic3d`: the
/// same names) from [`DynamicParts`].
macro_rules! set_dynamic_parts {
    ($plan:ident, $p:ident) => {
        $plan.output_times = $p.output_times;
        $plan.time = $p.time;
        $plan.full = $p.full;
        $plan.simplified = $p.simplified;
        $plan.reduced = $p.reduced;
        $plan.reduced_modes = $p.reduced_modes;
        $plan.gyroscopic = $p.gyroscopic;
        ($plan.integrator, $plan.settings) = ($p.integrator, $p.settings);
        $plan.audit = $p.audit;
        $plan.damping = $p.damping;
        $plan.initial = $p.initial;
        $plan.load_names = $p.load_names;
        $plan.snapshots = $p.snapshots;
    };
}
pub(crate) use set_dynamic_parts;

/// The values of `[dynamic]` and of the loads' time histories, as the library's dynamic plans
/// take them (the fields of [`DynamicPlan`] but the model and the loads).
pub(crate) struct DynamicParts {
    pub end_time: f64,
    pub output_times: Vec<f64>,
    pub time: Vec<Option<TimeFunction>>,
    pub full: bool,
    pub simplified: bool,
    pub reduced: Vec<usize>,
    pub reduced_modes: Vec<Vec<usize>>,
    pub gyroscopic: Gyroscopic,
    pub integrator: Method,
    pub settings: IntegratorSettings,
    pub audit: AuditSettings,
    pub damping: Damping,
    pub initial: Initial,
    pub load_names: Vec<String>,
    pub snapshots: Vec<usize>,
}

/// `prefix.key`, or `key` alone with an empty prefix.
fn field(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// The output times of `output_step` or `output_times`. Outputs at `k · output_step` (not
/// accumulated), and `end_time` itself if it is not a multiple. The library checks the times and
/// `end_time`; with an invalid `end_time` no times are made, so that its error comes first.
fn output_times(d: &DynamicSpec) -> Result<Vec<f64>, InputError> {
    let end = d.end_time;
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
        (None, Some(times)) => Ok(times.clone()),
        (Some(_), None) if !(end > 0.0 && end.is_finite()) => Ok(Vec::new()),
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
            let intervals = (end / dt * (1.0 + 1e-12)).floor();
            if intervals + 2.0 > MAX_OUTPUT_TIMES as f64 {
                return Err(InputError::new(
                    field,
                    format!(
                        "gives {} output times; at most {MAX_OUTPUT_TIMES} are allowed",
                        short(intervals + 1.0)
                    ),
                ));
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
    }
}

impl IntegrationSpec {
    /// The integrator and its settings (the library's defaults where a key is not given), after
    /// checking that the options that belong to one integrator have it; errors name
    /// `{prefix}.max_order`, … (`prefix` empty: the keys alone).
    pub fn to_settings(&self, prefix: &str) -> Result<(Method, IntegratorSettings), InputError> {
        let d = self;
        let field = |k: &str| field(prefix, k);
        let method = d.integrator.method();
        if d.max_order.is_some() && method != Method::Bdf {
            return Err(InputError::new(
                field("max_order"),
                "is an option of the BDF integrator; it needs integrator = \"bdf\"",
            ));
        }
        if d.step.is_some() && !matches!(method, Method::Midpoint | Method::GeneralizedAlpha) {
            return Err(InputError::new(
                field("step"),
                "is the fixed step of the implicit midpoint rule and generalized-α; it needs \
             integrator = \"midpoint\" or \"generalized-alpha\" (the other integrators choose \
             their steps)",
            ));
        }
        if d.spectral_radius.is_some() && method != Method::GeneralizedAlpha {
            return Err(InputError::new(
                field("spectral_radius"),
                "is an option of the generalized-α integrator; it needs \
             integrator = \"generalized-alpha\"",
            ));
        }
        if d.max_step.is_some() && d.step.is_some() {
            return Err(InputError::new(
                field("max_step"),
                "caps the steps of the adaptive integrators; it cannot be given with the fixed \
             step `step`",
            ));
        }
        let mut s = IntegratorSettings::default();
        s.rtol = d.rtol.unwrap_or(s.rtol);
        s.atol = d.atol.unwrap_or(s.atol);
        s.max_order = d.max_order.unwrap_or(s.max_order);
        s.spectral_radius = d.spectral_radius.unwrap_or(s.spectral_radius);
        s.step = d.step;
        s.max_steps = d.max_steps.unwrap_or(s.max_steps);
        s.max_step = d.max_step;
        Ok((method, s))
    }
}

impl EquationsSpec {
    /// The gyroscopic option; errors name `{prefix}.gyroscopic_step`.
    pub fn to_gyroscopic(&self, prefix: &str) -> Result<Gyroscopic, InputError> {
        let d = self;
        Ok(match (d.gyroscopic, d.gyroscopic_step) {
            (GyroscopicSpec::FiniteDifference, step) => Gyroscopic::FiniteDifference {
                step: step.unwrap_or(Gyroscopic::DEFAULT_STEP),
            },
            (_, Some(_)) => {
                return Err(InputError::new(
                    field(prefix, "gyroscopic_step"),
                    "is the step of the finite-difference gyroscopic term; it needs \
                 gyroscopic = \"finite-difference\"",
                ))
            }
            (GyroscopicSpec::Exact, None) => Gyroscopic::Exact,
            (GyroscopicSpec::Neglected, None) => Gyroscopic::Neglected,
        })
    }

    /// The structural damping (none without `damping`); errors name `{prefix}.damping.alpha`,
    /// ….
    pub fn to_damping(&self, prefix: &str) -> Result<Damping, InputError> {
        let Some(s) = &self.damping else {
            return Ok(Damping::None);
        };
        let damping = field(prefix, "damping");
        let field = |key: &str| format!("{damping}.{key}");
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
                    alpha: s.alpha.unwrap_or(0.0),
                    beta: s.beta.unwrap_or(0.0),
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
                Ok(Damping::Modal { ratios })
            }
        }
    }
}

/// The library's time function of `loads[i].time`, after checking which keys were given.
pub(crate) fn time_function(field: &str, s: &TimeSpec) -> Result<TimeFunction, InputError> {
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
mod tests;
