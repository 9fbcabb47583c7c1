//! `[static]` into a [`StaticPlan`]: which models to solve, the solver options, the sweep points
//! and the loaded modes. The library checks the values ([`StaticPlan::validate`]); this module
//! checks what it cannot see: load names and how the sweep is spelled.

use flexwing::analysis::statics::{StaticPlan, Sweep};
use flexwing::model::FullModel;
use flexwing::InputError;

use super::spec::{Case, SweepSpec};
use crate::CaseError;

impl Case {
    /// The static analysis of `[[loads]]` and `[static]` (defaults without it), validated.
    ///
    /// # Errors
    /// A bad beam or load, a sweep of an unknown load or spelled wrongly, and every error of
    /// [`StaticPlan::validate`], named as in the case file.
    pub fn static_plan(&self) -> Result<StaticPlan, CaseError> {
        self.not_aeroelastic("aero_static_plan")
            .and_then(|()| self.checked_static_plan())
            .map_err(|e| self.error(e))
    }

    fn checked_static_plan(&self) -> Result<StaticPlan, InputError> {
        let model = FullModel::new(self.to_beam()?);
        let loads = self.to_loads(model.beam())?;
        let s = &self.statics;
        let mut plan = StaticPlan::new(model, loads);
        plan.full = s.full;
        plan.reduced.clone_from(&s.reduced);
        plan.reduced_modes.clone_from(&s.reduced_modes);
        let o = &mut plan.options;
        o.tolerance = s.tolerance.unwrap_or(o.tolerance);
        o.max_iterations = s.max_iterations.unwrap_or(o.max_iterations);
        o.min_step = s.min_step.unwrap_or(o.min_step);
        o.line_search = s.line_search.unwrap_or(o.line_search);
        plan.modes = s.modes;
        plan.load_names = self.load_names();
        plan.sweep = s.sweep.as_ref().map(|spec| self.sweep(spec)).transpose()?;
        plan.validate("loads", "static")?;
        Ok(plan)
    }

    pub(crate) fn sweep(&self, spec: &SweepSpec) -> Result<Sweep, InputError> {
        let load = self
            .load_index(&spec.load)
            .ok_or_else(|| InputError::new("static.sweep.load", self.unknown_load(&spec.load)))?;
        let scales = match (&spec.scales, spec.from, spec.to, spec.steps) {
            (Some(scales), None, None, None) => scales.clone(),
            (None, Some(from), Some(to), Some(steps)) => {
                evenly_spaced("static.sweep", from, to, steps)?
            }
            (Some(_), ..) => {
                return Err(InputError::new(
                    "static.sweep",
                    "give either scales or from/to/steps, not both",
                ))
            }
            (None, None, None, None) => {
                return Err(InputError::new(
                    "static.sweep.scales",
                    "missing: give scales = [...] or from, to and steps",
                ))
            }
            (None, from, to, _) => {
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
        Ok(Sweep { load, scales })
    }
}

/// Most points of a sweep given by `from`, `to` and `steps`: every point is an equilibrium
/// (statics) or a speed with its eigen-analysis (flutter) written to the outputs; 1e5 points
/// already take hours. (`steps = 2^62` aborted on allocation: issue 9.)
pub const MAX_SWEEP_POINTS: usize = 100_000;

/// `steps` values from `from` to `to`, both ends included; errors name `{prefix}.from`, ….
pub(crate) fn evenly_spaced(
    prefix: &str,
    from: f64,
    to: f64,
    steps: usize,
) -> Result<Vec<f64>, InputError> {
    for (key, v) in [("from", from), ("to", to)] {
        if !v.is_finite() {
            return Err(InputError::new(
                format!("{prefix}.{key}"),
                format!("must be finite, got {v}"),
            ));
        }
    }
    if steps < 2 {
        return Err(InputError::new(
            format!("{prefix}.steps"),
            format!("must be at least 2 (both ends are points), got {steps}"),
        ));
    }
    if steps > MAX_SWEEP_POINTS {
        return Err(InputError::new(
            format!("{prefix}.steps"),
            format!("at most {MAX_SWEEP_POINTS} points, got {steps}"),
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
    use flexwing::solve::StaticOptions;

    const BEAM: &str = "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\n\
         mass_per_length = 0.2\n\n[[loads]]\nname = \"F1\"\ntype = \"point-force\"\nspan = 1\n\
         direction = \"dead\"\nfy = 1\n\n[[loads]]\ntype = \"gravity\"\n";

    fn plan(extra: &str) -> Result<StaticPlan, String> {
        let case = Case::from_toml_str(&format!("{BEAM}{extra}")).map_err(|e| e.to_string())?;
        case.static_plan().map_err(|e| e.to_string())
    }

    #[test]
    fn a_sweep_of_too_many_points_is_refused() {
        // Regression (issue 9): steps = 2^62 aborted on allocation, 1e9 ran out of memory.
        for steps in ["4611686018427387904", "1000000000", "100001"] {
            let e = plan(&format!(
                "[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 1\nsteps = {steps}\n"
            ))
            .unwrap_err();
            assert!(
                e.contains("static.sweep.steps: at most 100000 points"),
                "{e}"
            );
        }
        assert!(plan("[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 1\nsteps = 100000\n").is_ok());
    }

    #[test]
    fn defaults_solve_the_full_model_at_scale_one() {
        let p = plan("").unwrap();
        assert!(p.full);
        assert!(p.reduced.is_empty());
        assert_eq!(p.options, StaticOptions::default());
        assert_eq!(p.points(), [vec![1.0, 1.0]]);
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
        assert_eq!(p.points()[3], [0.3, 1.0]);
        let round =
            plan("[static.sweep]\nload = \"F1\"\nfrom = 0\nto = 150\nsteps = 16\n").unwrap();
        let expected: Vec<f64> = (0..16).map(|k| 10.0 * k as f64).collect();
        assert_eq!(round.point_scales(), expected);
    }

    #[test]
    fn labels() {
        let p = plan("[static]\nreduced = [2, 3]\nreduced_modes = [[1, 2, 4]]\n").unwrap();
        let labels: Vec<_> = p.models().unwrap().iter().map(|m| m.label()).collect();
        assert_eq!(
            labels,
            ["full", "reduced-r2", "reduced-r3", "reduced-modes-1-2-4"]
        );
        assert_eq!(p.reduced_modes, [vec![1, 2, 4]]);
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
