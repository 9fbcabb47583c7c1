//! Which models an analysis runs: the full model, the simplified one (dynamics), and reduced
//! models on the first `r` modes or on listed modes, in the order of the plan.

use crate::error::InputError;

/// Which modes a reduced model keeps.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReducedChoice {
    /// The first `r` modes.
    First(usize),
    /// These modes, 1-based, in the order given.
    Modes(Vec<usize>),
}

/// Which model a run is of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ModelKind {
    /// The full model.
    Full,
    /// The full model with the gyroscopic term neglected (dynamics).
    Simplified,
    /// A reduced model.
    Reduced(ReducedChoice),
}

impl ModelKind {
    /// `full`, `simplified`, `reduced-r2` (the first 2 modes), `reduced-modes-1-2-4`.
    pub fn label(&self) -> String {
        match self {
            ModelKind::Full => "full".into(),
            ModelKind::Simplified => "simplified".into(),
            ModelKind::Reduced(ReducedChoice::First(r)) => format!("reduced-r{r}"),
            ModelKind::Reduced(ReducedChoice::Modes(list)) => {
                let numbers: Vec<String> = list.iter().map(usize::to_string).collect();
                format!("reduced-modes-{}", numbers.join("-"))
            }
        }
    }

    /// The retained modes of a reduced model, 1-based; `None` for the full and simplified models.
    pub fn modes(&self) -> Option<Vec<usize>> {
        match self {
            ModelKind::Reduced(ReducedChoice::First(r)) => Some((1..=*r).collect()),
            ModelKind::Reduced(ReducedChoice::Modes(list)) => Some(list.clone()),
            _ => None,
        }
    }

    /// The retained modes of a reduced model, 0-based, for [`crate::model::ReducedModel::new`].
    pub(crate) fn mode_indices(&self) -> Option<Vec<usize>> {
        self.modes().map(|m| m.iter().map(|k| k - 1).collect())
    }
}

/// How many of the lowest modes the reduced models among `kinds` project on (the highest mode
/// index they use), `None` if there is no reduced model: only those are computed, by Lanczos
/// at large `n` (`Modes::lowest`).
pub(crate) fn modes_needed(kinds: &[ModelKind]) -> Option<usize> {
    kinds
        .iter()
        .filter_map(|k| k.modes().and_then(|m| m.iter().copied().max()))
        .max()
}

/// The reduced models of `reduced` (first `r` modes) and `reduced_modes` (1-based lists) for a
/// model with `n_modes` modes, in that order, after checking them; errors name
/// `{prefix}.reduced[i]` and `{prefix}.reduced_modes[i]`.
pub(crate) fn reduced_models(
    reduced: &[usize],
    reduced_modes: &[Vec<usize>],
    n_modes: usize,
    prefix: &str,
) -> Result<Vec<(ModelKind, String)>, InputError> {
    let mut models = Vec::new();
    for (i, &r) in reduced.iter().enumerate() {
        let field = crate::field(prefix, &format!("reduced[{i}]"));
        if !(1..=n_modes).contains(&r) {
            return Err(InputError::new(
                field,
                format!("must be between 1 and {n_modes} (the number of modes), got {r}"),
            ));
        }
        models.push((ModelKind::Reduced(ReducedChoice::First(r)), field));
    }
    for (i, list) in reduced_modes.iter().enumerate() {
        let field = crate::field(prefix, &format!("reduced_modes[{i}]"));
        let reason = if list.is_empty() {
            Some("needs at least one mode".to_string())
        } else if list.contains(&0) {
            Some("mode numbers start at 1, got 0".to_string())
        } else if let Some(k) = list.iter().find(|&&k| k > n_modes) {
            Some(format!(
                "mode {k} is out of range: the model has {n_modes} modes"
            ))
        } else {
            (1..list.len())
                .find(|&j| list[..j].contains(&list[j]))
                .map(|j| format!("mode {} is listed twice", list[j]))
        };
        if let Some(reason) = reason {
            return Err(InputError::new(field, reason));
        }
        models.push((
            ModelKind::Reduced(ReducedChoice::Modes(list.clone())),
            field,
        ));
    }
    for (i, (kind, field)) in models.iter().enumerate() {
        let label = kind.label();
        if let Some((_, first)) = models[..i].iter().find(|(k, _)| k.label() == label) {
            return Err(InputError::new(
                field,
                format!("the model {label} is already requested by {first}"),
            ));
        }
    }
    Ok(models)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_and_modes() {
        let m = reduced_models(&[2, 3], &[vec![1, 2, 4]], 10, "static").unwrap();
        let labels: Vec<String> = m.iter().map(|(k, _)| k.label()).collect();
        assert_eq!(labels, ["reduced-r2", "reduced-r3", "reduced-modes-1-2-4"]);
        assert_eq!(m[2].0.mode_indices(), Some(vec![0, 1, 3]));
        assert_eq!(m[0].0.modes(), Some(vec![1, 2]));
        assert_eq!(ModelKind::Full.modes(), None);
    }

    #[test]
    fn errors_name_the_callers_field() {
        type Case<'a> = (&'a [usize], &'a [Vec<usize>], &'a str);
        let cases: [Case; 6] = [
            (
                &[2, 2],
                &[],
                "s.reduced[1]: the model reduced-r2 is already requested by s.reduced[0]",
            ),
            (
                &[0],
                &[],
                "s.reduced[0]: must be between 1 and 4 (the number of modes), got 0",
            ),
            (
                &[5],
                &[],
                "s.reduced[0]: must be between 1 and 4 (the number of modes), got 5",
            ),
            (
                &[],
                &[vec![0, 1]],
                "s.reduced_modes[0]: mode numbers start at 1, got 0",
            ),
            (
                &[],
                &[vec![1, 1]],
                "s.reduced_modes[0]: mode 1 is listed twice",
            ),
            (
                &[],
                &[vec![2, 9]],
                "s.reduced_modes[0]: mode 9 is out of range: the model has 4 modes",
            ),
        ];
        for (reduced, lists, expected) in cases {
            let e = reduced_models(reduced, lists, 4, "s").unwrap_err();
            assert_eq!(e.to_string(), expected);
        }
    }
}
