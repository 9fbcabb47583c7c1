//! Benchmark of the model's building blocks: mass-matrix assembly and modal analysis for
//! n = 10 … 320 elements (coupled model, 2n coordinates). Prints a Markdown table that can be
//! pasted into docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench model` (add `-- --quick` for a short run).
//!
//! Each figure is the median over several batches of the mean time per call within a batch; the
//! spread is the (max − min) / median of the batch means. `slope` is the local exponent
//! `log(t₂/t₁) / log(n₂/n₁)` against the previous row: 2 means O(n²), 3 means O(n³).

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{fmt_time, measure};

use flexwing::model::{FullModel, Kinematics};
use flexwing::solve::Modes;
use nalgebra::DMatrix;

fn table1(n: usize) -> FullModel {
    flexwing::paper::table1_beam(n).expect("valid beam")
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(20), 3)
    } else {
        (Duration::from_millis(200), 7)
    };
    println!("| n | dofs | mass matrix | spread | slope | modal analysis | spread | slope |");
    println!("|---|---|---|---|---|---|---|---|");
    let mut prev: Option<(usize, f64, f64)> = None;
    for n in [10, 20, 40, 80, 160, 320] {
        let model = table1(n);
        let nd = model.n_dofs();
        let q: Vec<f64> = (0..nd).map(|i| 0.01 * (i as f64).sin()).collect();
        let mut kin = Kinematics::new(n);
        let mut m = DMatrix::zeros(nd, nd);
        let (t_mass, s_mass) = measure(budget, batches, || {
            kin.update(black_box(&q));
            model.mass_matrix_kin_into(&kin, &mut m);
            black_box(&m);
        });
        let modal_budget = if n >= 160 { budget * 3 } else { budget };
        let (t_modes, s_modes) = measure(modal_budget, batches.min(5), || {
            black_box(Modes::undeformed(&model).expect("modes"));
        });
        let slope = |t: f64, t0: f64, n0: usize| (t / t0).ln() / (n as f64 / n0 as f64).ln();
        let (sm, se) = match prev {
            Some((n0, tm0, te0)) => (
                format!("{:.2}", slope(t_mass, tm0, n0)),
                format!("{:.2}", slope(t_modes, te0, n0)),
            ),
            None => ("–".into(), "–".into()),
        };
        println!(
            "| {n} | {nd} | {} | {:.0} % | {sm} | {} | {:.0} % | {se} |",
            fmt_time(t_mass),
            100.0 * s_mass,
            fmt_time(t_modes),
            100.0 * s_modes
        );
        prev = Some((n, t_mass, t_modes));
    }
}
