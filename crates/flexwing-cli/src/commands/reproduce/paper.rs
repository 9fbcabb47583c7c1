//! The paper's beams, the numbers it prints (for the "paper" columns, clearly labelled as such),
//! and the independent references checked into the library's test data (for the "reference"
//! columns). Every other number of the report is computed by the run.

use anyhow::{anyhow, Context, Result};
use flexwing::model::FullModel;

/// Table 1 beam (coupled, L = 16 m) with `n` elements: the library's preset
/// ([`flexwing::paper::table1_section`] documents its polar inertia).
pub fn table1_beam(n: usize) -> Result<FullModel> {
    Ok(flexwing::paper::table1_beam(n)?)
}

/// Table 4 beam (bending only, L = 1 m) with `n` elements: the library's preset.
pub fn table4_beam(n: usize) -> Result<FullModel> {
    Ok(flexwing::paper::table4_beam(n)?)
}

/// Table 2 as printed: per mode, (lumped n = 16, semi-analytical, error %) and the same at n = 32.
pub const TABLE2: [[f64; 6]; 9] = [
    [2.21, 2.21, 0.02, 2.21, 2.21, 0.01],
    [9.55, 9.55, 0.01, 9.55, 9.55, 0.00],
    [13.78, 13.80, 0.10, 13.79, 13.80, 0.03],
    [27.39, 27.40, 0.02, 27.40, 27.40, 0.01],
    [36.38, 36.66, 0.76, 36.59, 36.66, 0.19],
    [46.69, 46.95, 0.56, 46.88, 46.95, 0.16],
    [63.14, 64.02, 1.38, 63.79, 64.02, 0.37],
    [65.05, 66.52, 2.21, 65.96, 66.52, 0.84],
    [80.53, 86.71, 7.14, 83.08, 86.71, 4.19],
];

/// Table 3 (tip force, n = 20): CPU time of the reduced models relative to the full one.
pub const TABLE3_RATIOS: [(usize, f64); 2] = [(2, 0.32), (3, 0.36)];
/// Table 5 (two forces, n = 10): CPU time of the reduced models relative to the full one.
pub const TABLE5_RATIOS: [(usize, f64); 2] = [(2, 0.34), (3, 0.32)];
/// Table 6: mean absolute and relative error of the finite-difference gradient, its CPU ratio.
pub const TABLE6: (f64, f64, f64) = (8.99e-10, 1.26e-8, 0.084);
/// Table 7: CPU time of the simplified model relative to the full one (n = 10).
pub const TABLE7_RATIO: f64 = 0.197;
/// Table 8: CPU time of the reduced model (r = 2) relative to the full one (n = 20).
pub const TABLE8_RATIO: f64 = 0.146;
/// Figure 5: the largest relative error of the simplified model the paper reports.
pub const FIGURE5_MAX_ERROR: f64 = 0.04;

const CONTINUOUS_TABLE1: &str =
    include_str!("../../../../flexwing/tests/data/continuous_beam/table1_coupled.csv");
const DYNAMICS_CASE_B: &str =
    include_str!("../../../../flexwing/tests/data/dynamics_reference/case_b_tip.csv");
const ELASTICA_DEAD_TIP: &str =
    include_str!("../../../../flexwing/tests/data/elastica/dead_tip.csv");
const ELASTICA_TWO_LOADS: &str =
    include_str!("../../../../flexwing/tests/data/elastica/paper_two_loads.csv");
const ELASTICA_TWO_LOADS_SHAPES: &str =
    include_str!("../../../../flexwing/tests/data/elastica/paper_two_loads_shapes.csv");

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
pub struct TwoLoadsPoint {
    pub f1: f64,
    pub tip: (f64, f64),
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
