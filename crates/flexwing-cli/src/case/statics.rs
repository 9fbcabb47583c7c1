//! `[static]` into a plan: which models to solve, the solver options, the sweep points and the
//! loaded modes. Reduced-model mode lists are validated by the library when the models are built
//! ([`ReducedPlan::build`]); this module checks the rest.

use flexwing::model::{DistributedForce, Force, FullModel, Load, ReducedModel};
use flexwing::solve::{Modes, StaticOptions};
use flexwing::InputError;

use super::spec::{Case, StaticSpec, SweepSpec};

/// What `flexwing static` solves.
#[derive(Debug, Clone)]
pub struct StaticPlan {
    /// Solve the full model.
    pub full: bool,
    /// Reduced models, in the order of `reduced`, then `reduced_modes`.
    pub reduced: Vec<ReducedPlan>,
    /// Solver options.
    pub options: StaticOptions,
    /// Number of loaded modes to report.
    pub modes: Option<usize>,
    /// The load sweep.
    pub sweep: Option<Sweep>,
}

/// One reduced model to build.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedPlan {
    /// `reduced-r2`, `reduced-modes-1-2-4`.
    pub label: String,
    /// The case key it comes from, e.g. `static.reduced[1]`.
    pub field: String,
    /// Which modes.
    pub modes: ReducedModes,
}

/// The modes of a reduced model.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReducedModes {
    /// The first `r`.
    First(usize),
    /// These, 0-based.
    Indices(Vec<usize>),
}

impl ReducedPlan {
    /// Project `full` on its modes about the undeformed state, `modes`.
    ///
    /// # Errors
    /// The library's checks of the mode list (`r = 0`, beyond the number of modes, a mode listed
    /// twice), reported under the case key.
    pub fn build(&self, full: &FullModel, modes: &Modes) -> Result<ReducedModel, InputError> {
        let shapes = modes.shapes();
        match &self.modes {
            ReducedModes::First(r) => ReducedModel::first(full, shapes, *r),
            ReducedModes::Indices(k) => ReducedModel::new(full, shapes, k),
        }
        .map_err(|e| InputError::new(&self.field, e.reason))
    }
}

/// A sweep of one load's scale.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// Index of the swept load.
    pub load: usize,
    /// Its name.
    pub name: String,
    /// The scale of the swept load at each point.
    pub scales: Vec<f64>,
}

impl StaticPlan {
    /// The scale of the swept load at each point; `[1]` without a sweep.
    pub fn point_scales(&self) -> Vec<f64> {
        self.sweep.as_ref().map_or(vec![1.0], |s| s.scales.clone())
    }

    /// The scales of all `n_loads` loads at each point: 1, except the swept load.
    pub fn points(&self, n_loads: usize) -> Vec<Vec<f64>> {
        match &self.sweep {
            None => vec![vec![1.0; n_loads]],
            Some(s) => s
                .scales
                .iter()
                .map(|&v| {
                    let mut p = vec![1.0; n_loads];
                    p[s.load] = v;
                    p
                })
                .collect(),
        }
    }
}

impl Case {
    /// The plan of `[static]` (defaults without it) for a model of `n_dofs` coordinates under
    /// `loads` (from [`Case::to_loads`]).
    ///
    /// # Errors
    /// No loads, nothing to solve, options out of range, a sweep of an unknown load, a malformed
    /// sweep, loaded modes without the full model or with follower loads.
    pub fn static_plan(&self, n_dofs: usize, loads: &[Load]) -> Result<StaticPlan, InputError> {
        let s = &self.statics;
        if loads.is_empty() {
            return Err(InputError::new(
                "loads",
                "flexwing static needs at least one [[loads]] table",
            ));
        }
        let reduced = reduced_plans("static", &s.reduced, &s.reduced_modes)?;
        if !s.full && reduced.is_empty() {
            return Err(InputError::new(
                "static.full",
                "nothing to solve: full = false and no reduced models \
                 (give static.reduced or static.reduced_modes)",
            ));
        }
        let modes = loaded_modes(s, n_dofs, loads)?;
        let sweep = match &s.sweep {
            None => None,
            Some(spec) => Some(sweep(self, spec)?),
        };
        Ok(StaticPlan {
            full: s.full,
            reduced,
            options: options(s)?,
            modes,
            sweep,
        })
    }
}

/// The reduced models of `reduced` and `reduced_modes` of the table `table` (`static`,
/// `dynamic`), labelled, with the same model asked at most once.
pub(super) fn reduced_plans(
    table: &str,
    reduced: &[usize],
    reduced_modes: &[Vec<usize>],
) -> Result<Vec<ReducedPlan>, InputError> {
    let mut plans: Vec<ReducedPlan> = Vec::new();
    for (i, &r) in reduced.iter().enumerate() {
        plans.push(ReducedPlan {
            label: format!("reduced-r{r}"),
            field: format!("{table}.reduced[{i}]"),
            modes: ReducedModes::First(r),
        });
    }
    for (i, list) in reduced_modes.iter().enumerate() {
        let field = format!("{table}.reduced_modes[{i}]");
        if list.contains(&0) {
            return Err(InputError::new(field, "mode numbers start at 1, got 0"));
        }
        let numbers: Vec<String> = list.iter().map(usize::to_string).collect();
        plans.push(ReducedPlan {
            label: format!("reduced-modes-{}", numbers.join("-")),
            field,
            modes: ReducedModes::Indices(list.iter().map(|k| k - 1).collect()),
        });
    }
    for (i, p) in plans.iter().enumerate() {
        if let Some(first) = plans[..i].iter().find(|o| o.label == p.label) {
            return Err(InputError::new(
                &p.field,
                format!(
                    "the model {} is already requested by {}",
                    p.label, first.field
                ),
            ));
        }
    }
    Ok(plans)
}

fn options(s: &StaticSpec) -> Result<StaticOptions, InputError> {
    let mut o = StaticOptions::default();
    if let Some(t) = s.tolerance {
        if !(t > 0.0 && t.is_finite()) {
            return Err(InputError::new(
                "static.tolerance",
                format!("must be a finite positive number, got {t}"),
            ));
        }
        o.tolerance = t;
    }
    if let Some(m) = s.max_iterations {
        if m == 0 {
            return Err(InputError::new(
                "static.max_iterations",
                "must be at least 1, got 0",
            ));
        }
        o.max_iterations = m;
    }
    if let Some(m) = s.min_step {
        if !(m > 0.0 && m <= 1.0) {
            return Err(InputError::new(
                "static.min_step",
                format!("must be in (0, 1] (a fraction of the load change), got {m}"),
            ));
        }
        o.min_step = m;
    }
    if let Some(l) = s.line_search {
        o.line_search = l;
    }
    Ok(o)
}

fn loaded_modes(
    s: &StaticSpec,
    n_dofs: usize,
    loads: &[Load],
) -> Result<Option<usize>, InputError> {
    let Some(count) = s.modes else {
        return Ok(None);
    };
    let field = "static.modes";
    if !(1..=n_dofs).contains(&count) {
        return Err(InputError::new(
            field,
            format!(
                "must be between 1 and the number of degrees of freedom ({n_dofs}), got {count}"
            ),
        ));
    }
    if !s.full {
        return Err(InputError::new(
            field,
            "loaded modes are computed about the full model's equilibrium, which needs full = true",
        ));
    }
    let follower = loads.iter().position(|l| {
        matches!(
            l,
            Load::PointForce {
                force: Force::Follower { .. },
                ..
            } | Load::Distributed(DistributedForce::Follower { .. })
        )
    });
    if let Some(i) = follower {
        return Err(InputError::new(
            field,
            format!(
                "loaded modes need conservative loads, but loads[{i}] is a follower force \
                 (its tangent stiffness is not symmetric)"
            ),
        ));
    }
    Ok(Some(count))
}

fn sweep(case: &Case, spec: &SweepSpec) -> Result<Sweep, InputError> {
    let load = case
        .load_index(&spec.load)
        .ok_or_else(|| InputError::new("static.sweep.load", case.unknown_load(&spec.load)))?;
    let range = (spec.from, spec.to, spec.steps);
    let scales = match (&spec.scales, range) {
        (Some(_), (None, None, None)) | (None, (Some(_), Some(_), Some(_))) => sweep_scales(spec)?,
        (Some(_), _) => {
            return Err(InputError::new(
                "static.sweep",
                "give either scales or from/to/steps, not both",
            ))
        }
        (None, (None, None, None)) => {
            return Err(InputError::new(
                "static.sweep.scales",
                "missing: give scales = [...] or from, to and steps",
            ))
        }
        (None, (from, to, _)) => {
            let missing = if from.is_none() {
                "from"
            } else if to.is_none() {
                "to"
            } else {
                "steps"
            };
            return Err(InputError::new(
                format!("static.sweep.{missing}"),
                "missing: from, to and steps go together",
            ));
        }
    };
    Ok(Sweep {
        load,
        name: spec.load.clone(),
        scales,
    })
}

/// The scales of a well-formed sweep spec (either `scales`, or all of `from`, `to`, `steps`).
fn sweep_scales(spec: &SweepSpec) -> Result<Vec<f64>, InputError> {
    let finite = |field: String, v: f64| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(InputError::new(field, format!("must be finite, got {v}")))
        }
    };
    if let Some(scales) = &spec.scales {
        if scales.is_empty() {
            return Err(InputError::new("static.sweep.scales", "must not be empty"));
        }
        return scales
            .iter()
            .enumerate()
            .map(|(i, &v)| finite(format!("static.sweep.scales[{i}]"), v))
            .collect();
    }
    let (Some(from), Some(to), Some(steps)) = (spec.from, spec.to, spec.steps) else {
        unreachable!("sweep_scales is called with scales or a complete range")
    };
    let from = finite("static.sweep.from".into(), from)?;
    let to = finite("static.sweep.to".into(), to)?;
    if steps < 2 {
        return Err(InputError::new(
            "static.sweep.steps",
            format!("must be at least 2 (both ends are points), got {steps}"),
        ));
    }
    let last = (steps - 1) as f64;
    Ok((0..steps)
        .map(|k| {
            if k + 1 == steps {
                to
            } else {
                // Multiplying before dividing keeps round steps exact (150 · 11 / 15 = 110).
                from + (to - from) * k as f64 / last
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    const BEAM: &str = "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\n\
         mass_per_length = 0.2\n\n[[loads]]\nname = \"F1\"\ntype = \"point-force\"\nspan = 1\n\
         direction = \"dead\"\nfy = 1\n\n[[loads]]\ntype = \"gravity\"\n";

    fn plan(extra: &str) -> Result<StaticPlan, String> {
        let case = Case::parse(&format!("{BEAM}{extra}"), "x.toml")?;
        let beam = case.to_beam().map_err(|e| e.to_string())?;
        let loads = case.to_loads(&beam).map_err(|e| e.to_string())?;
        case.static_plan(4, &loads).map_err(|e| e.to_string())
    }

    #[test]
    fn defaults_solve_the_full_model_at_scale_one() {
        let p = plan("").unwrap();
        assert!(p.full);
        assert!(p.reduced.is_empty());
        assert_eq!(p.options, StaticOptions::default());
        assert_eq!(p.points(2), [vec![1.0, 1.0]]);
        assert_eq!(p.point_scales(), [1.0]);
    }

    #[test]
    fn sweep_from_to_steps_ends_exactly() {
        let p = plan("[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 0.3\nsteps = 4\n").unwrap();
        let s = p.point_scales();
        assert_eq!(s.len(), 4);
        assert_eq!(s[0], 0.0);
        assert_eq!(s[3], 0.3);
        assert!((s[1] - 0.1).abs() < 1e-15);
        assert_eq!(p.points(2)[3], [0.3, 1.0]);
        let round =
            plan("[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 150\nsteps = 16\n").unwrap();
        let expected: Vec<f64> = (0..16).map(|k| 10.0 * k as f64).collect();
        assert_eq!(round.point_scales(), expected);
    }

    #[test]
    fn labels() {
        let p = plan("[static]\nreduced = [2, 3]\nreduced_modes = [[1, 2, 4]]\n").unwrap();
        let labels: Vec<_> = p.reduced.iter().map(|r| r.label.as_str()).collect();
        assert_eq!(labels, ["reduced-r2", "reduced-r3", "reduced-modes-1-2-4"]);
        assert_eq!(p.reduced[2].modes, ReducedModes::Indices(vec![0, 1, 3]));
    }

    #[test]
    fn errors_name_the_field() {
        let cases = [
            (
                "[static.sweep]\nload = \"F3\"\nscales = [1]\n",
                "static.sweep.load: no load named \"F3\" (the named loads are \"F1\")",
            ),
            (
                "[static.sweep]\nload = \"F1\"\nscales = [1]\nsteps = 3\n",
                "static.sweep: give either",
            ),
            (
                "[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 1\n",
                "static.sweep.steps: missing",
            ),
            (
                "[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 1\nsteps = 1\n",
                "static.sweep.steps: must be at least 2",
            ),
            (
                "[static.sweep]\nload = \"F1\"\nscales = [0, nan]\n",
                "static.sweep.scales[1]: must be finite",
            ),
            (
                "[static]\nreduced = [2, 2]\n",
                "static.reduced[1]: the model reduced-r2 is already",
            ),
            (
                "[static]\nreduced_modes = [[0, 1]]\n",
                "static.reduced_modes[0]: mode numbers start at 1",
            ),
            ("[static]\nfull = false\n", "static.full: nothing to solve"),
            (
                "[static]\nmodes = 5\n",
                "static.modes: must be between 1 and the number of degrees of freedom (4), got 5",
            ),
            (
                "[static]\nfull = false\nreduced = [2]\nmodes = 2\n",
                "static.modes: loaded modes are computed about the full",
            ),
            ("[static]\ntolerance = -1\n", "static.tolerance:"),
            ("[static]\nmin_step = 2\n", "static.min_step:"),
            ("[static]\nmax_iterations = 0\n", "static.max_iterations:"),
        ];
        for (extra, expected) in cases {
            let msg = plan(extra).unwrap_err();
            assert!(msg.starts_with(expected), "{extra}: {msg}");
        }
    }
}
