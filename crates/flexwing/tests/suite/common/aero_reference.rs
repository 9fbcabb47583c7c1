//! Readers of the independent aeroelastic references in `tests/data/aero_reference/` (see its
//! README: typical section, Patil and Goland wings as continuous beams, flexwing's lumped chain
//! built from docs/model.md with strip aerodynamics per element; no flexwing code was used).

use std::path::PathBuf;

/// The rows of `tests/data/aero_reference/{file}` (header dropped), split on commas (no field
/// holds a comma, README).
pub fn rows(file: &str) -> Vec<Vec<String>> {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "tests/data/aero_reference",
        file,
    ]
    .iter()
    .collect();
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

fn num(s: &str) -> f64 {
    s.parse()
        .unwrap_or_else(|e| panic!("not a number: {s:?} ({e})"))
}

/// A point `(U, ω)` of `chain_{case}_points.csv`: `quantity` (`flutter`, `divergence`), `model`
/// (`theodorsen`, `jones_k`, `peters6_k`, `quasi_steady`, …), `n` elements.
pub fn chain_point(case: &str, quantity: &str, model: &str, n: usize) -> (f64, f64) {
    rows(&format!("chain_{case}_points.csv"))
        .into_iter()
        .find(|r| r[0] == quantity && r[1] == model && r[2] == n.to_string())
        .map(|r| (num(&r[3]), num(&r[4])))
        .unwrap_or_else(|| panic!("chain_{case}_points.csv: no {quantity} {model} n = {n}"))
}

/// The note of a row of `chain_{case}_points.csv` (e.g. "unstable from U -> 0+ …").
pub fn chain_note(case: &str, quantity: &str, model: &str, n: usize) -> String {
    rows(&format!("chain_{case}_points.csv"))
        .into_iter()
        .find(|r| r[0] == quantity && r[1] == model && r[2] == n.to_string())
        .map(|r| r[6].clone())
        .unwrap_or_else(|| panic!("chain_{case}_points.csv: no {quantity} {model} n = {n}"))
}

/// A 30-digit refined chain flutter point `(U, ω)` of `chain_{case}_mp.csv` (`model`:
/// `theodorsen`, `jones`, `peters2` … `peters10`; `n` = 8, 16, 32).
pub fn chain_mp_point(case: &str, model: &str, n: usize) -> (f64, f64) {
    rows(&format!("chain_{case}_mp.csv"))
        .into_iter()
        .find(|r| r[0] == model && r[1] == n.to_string())
        .map(|r| (num(&r[2]), num(&r[3])))
        .unwrap_or_else(|| panic!("chain_{case}_mp.csv: no {model} n = {n}"))
}

/// A point `(U, ω)` of `beam_{case}_points.csv` (continuous wing): `quantity`, `model`,
/// `discretization` (`closed_form`, `galerkin`, `galerkin_pk`, `galerkin_k`, `fe`, …), `n`.
pub fn beam_point(
    case: &str,
    quantity: &str,
    model: &str,
    discretization: &str,
    n: usize,
) -> (f64, f64) {
    rows(&format!("beam_{case}_points.csv"))
        .into_iter()
        .find(|r| {
            r[0] == quantity && r[1] == model && r[2] == discretization && r[3] == n.to_string()
        })
        .map(|r| (num(&r[4]), num(&r[5])))
        .unwrap_or_else(|| {
            panic!("beam_{case}_points.csv: no {quantity} {model} {discretization} n = {n}")
        })
}

/// Parse a number of a reference row.
pub fn parse(s: &str) -> f64 {
    num(s)
}
