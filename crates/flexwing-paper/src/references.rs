//! The independent references of the study (the "reference" columns), read through this one
//! place: the continuous coupled beam, the elastica and the independent Python implementation of
//! the dynamics, checked into the library's test data (`crates/flexwing/tests/data/`, each
//! folder with a README giving its provenance) and embedded at build time.

use anyhow::{anyhow, Context, Result};

const CONTINUOUS_TABLE1: &str =
    include_str!("../../flexwing/tests/data/continuous_beam/table1_coupled.csv");
const DYNAMICS_CASE_B: &str =
    include_str!("../../flexwing/tests/data/dynamics_reference/case_b_tip.csv");
const ELASTICA_DEAD_TIP: &str = include_str!("../../flexwing/tests/data/elastica/dead_tip.csv");
const ELASTICA_TWO_LOADS: &str =
    include_str!("../../flexwing/tests/data/elastica/paper_two_loads.csv");
const ELASTICA_TWO_LOADS_SHAPES: &str =
    include_str!("../../flexwing/tests/data/elastica/paper_two_loads_shapes.csv");

/// Where the references come from, for the report.
pub const REFERENCE_NOTE: &str = "Continuous coupled beam: exact frequency equation solved to 40 \
digits (crates/flexwing/tests/data/continuous_beam, mpmath). Elastica: the inextensible planar \
elastica by shooting (crates/flexwing/tests/data/elastica, SciPy). Dynamics: the full model \
written again in Python from docs/model.md and integrated by SciPy (crates/flexwing/tests/data/\
dynamics_reference). All were computed by scripts independent of flexwing; their READMEs give the \
equations and checks.";

fn records(name: &str, text: &str) -> Result<Vec<Vec<f64>>> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    reader
        .records()
        .map(|r| {
            let r = r.with_context(|| format!("reference {name}"))?;
            r.iter()
                .map(|v| {
                    v.parse::<f64>()
                        .map_err(|e| anyhow!("reference {name}: {v:?}: {e}"))
                })
                .collect()
        })
        .collect()
}

/// Continuous coupled-beam frequencies of the Table 1 beam (rad/s), modes 1, 2, ….
pub fn continuous_table1() -> Result<Vec<f64>> {
    Ok(records("table1_coupled.csv", CONTINUOUS_TABLE1)?
        .iter()
        .map(|r| r[1])
        .collect())
}

/// Tip history `(t, x, y)` of case (b) from the independent Python implementation of the full
/// model (SciPy Radau at rtol 1e-10, 6.4e-10 m from DOP853).
pub fn independent_case_b() -> Result<Vec<[f64; 3]>> {
    Ok(records("case_b_tip.csv", DYNAMICS_CASE_B)?
        .iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// Elastica tip position `(x, y)` under a dead vertical tip force `p` (N) on the Table 4 beam.
pub fn elastica_tip(p: f64) -> Result<(f64, f64)> {
    records("dead_tip.csv", ELASTICA_DEAD_TIP)?
        .iter()
        .find(|r| (r[1] - p).abs() < 1e-9)
        .map(|r| (r[2], r[3]))
        .ok_or_else(|| anyhow!("no elastica reference for a tip force of {p} N"))
}

/// One point of the two-force elastica: `F1` (N), tip `(x, y)`, mid-span `(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLoadsPoint {
    /// The tip force F1 (N).
    pub f1: f64,
    /// Tip position (m).
    pub tip: (f64, f64),
    /// Mid-span position (m).
    pub mid: (f64, f64),
}

/// The elastica under the paper's two forces, `F1 = 0, 10, …, 150` N.
pub fn elastica_two_loads() -> Result<Vec<TwoLoadsPoint>> {
    Ok(records("paper_two_loads.csv", ELASTICA_TWO_LOADS)?
        .iter()
        .map(|r| TwoLoadsPoint {
            f1: r[0],
            tip: (r[1], r[2]),
            mid: (r[3], r[4]),
        })
        .collect())
}

/// A deformed shape: `(F1, node positions (x, y))`.
pub type Shape = (f64, Vec<(f64, f64)>);

/// Elastica shapes under the two forces, for the tabulated `F1`.
pub fn elastica_two_loads_shapes() -> Result<Vec<Shape>> {
    let mut shapes: Vec<Shape> = Vec::new();
    for r in records("paper_two_loads_shapes.csv", ELASTICA_TWO_LOADS_SHAPES)? {
        match shapes.last_mut() {
            Some((f1, nodes)) if *f1 == r[0] => nodes.push((r[3], r[4])),
            _ => shapes.push((r[0], vec![(r[3], r[4])])),
        }
    }
    Ok(shapes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_parse() {
        let w = continuous_table1().unwrap();
        assert!(w.len() >= 9 && (w[0] - 2.2128).abs() < 1e-3);
        let (x, y) = elastica_tip(150.0).unwrap();
        assert!(x > 0.0 && y > 0.5, "{x} {y}");
        assert!(elastica_tip(151.0).is_err());
        assert_eq!(elastica_two_loads().unwrap().len(), 16);
        let shapes = elastica_two_loads_shapes().unwrap();
        assert_eq!(shapes.len(), 4);
        assert!(shapes.iter().all(|(_, nodes)| nodes.len() == 81));
        let b = independent_case_b().unwrap();
        assert_eq!(b.len(), 201);
        assert!((b[200][0] - 1.0).abs() < 1e-12);
    }
}
