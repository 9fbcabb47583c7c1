//! Prints the statics tables of `docs/validation.md`: tip displacement errors of the lumped model
//! (full and reduced) against the elastica of `tests/data/elastica/` (see its README).
//!
//! Run: `cargo run --release -p flexwing --example statics_convergence`

use flexwing::beam::Profile;
use flexwing::model::{DistributedForce, Force, FullModel, Load, PlanarModel, ReducedModel};
use flexwing::solve::{sweep_static, Modes, StaticOptions, StaticSolution};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/elastica/");

fn read(file: &str) -> Vec<Vec<f64>> {
    csv::Reader::from_path(format!("{DATA}{file}"))
        .expect("reference file")
        .records()
        .map(|r| {
            r.expect("record")
                .iter()
                .map(|v| v.parse().expect("number"))
                .collect()
        })
        .collect()
}

fn table4(n: usize) -> FullModel {
    flexwing::paper::table4_beam(n).expect("valid beam")
}

fn tip(full: &FullModel, sol: &StaticSolution) -> [f64; 2] {
    let p = full.node_positions(&full.kinematics(&sol.q));
    let t = p[full.n_elements()];
    [t[0], t[1]]
}

/// Max over the reference rows of the tip position error (m), for a sweep of the first load.
fn max_error<M: PlanarModel>(
    model: &M,
    loads: &[Load],
    rows: &[Vec<f64>],
    scale_col: usize,
    tip_cols: (usize, usize),
) -> f64 {
    let full = model.full_model();
    let applied = full.apply(loads, "loads").unwrap();
    let points: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            let mut s = vec![1.0; loads.len()];
            s[0] = r[scale_col];
            s
        })
        .collect();
    let sols = sweep_static(model, &applied, &points, &StaticOptions::default()).unwrap();
    sols.iter()
        .zip(rows)
        .map(|(s, r)| {
            let t = tip(full, s);
            (t[0] - r[tip_cols.0]).hypot(t[1] - r[tip_cols.1])
        })
        .fold(0.0, f64::max)
}

fn main() {
    let dead = read("dead_tip.csv");
    let follower = read("follower_tip.csv");
    let two = read("paper_two_loads.csv");
    let dist = read("distributed.csv");
    let unit_dead = vec![Load::PointForce {
        span: 1.0,
        force: Force::Dead { fx: 0.0, fy: 1.0 },
    }];
    let unit_follower = vec![Load::PointForce {
        span: 1.0,
        force: Force::Follower {
            tangential: 0.0,
            normal: 1.0,
        },
    }];
    let two_loads = vec![
        Load::PointForce {
            span: 1.0,
            force: Force::Dead { fx: 0.0, fy: 1.0 },
        },
        Load::PointForce {
            span: 0.5,
            force: Force::Dead {
                fx: 0.0,
                fy: -150.0,
            },
        },
    ];
    let distributed = vec![Load::Distributed(DistributedForce::Dead {
        fx: Profile::Uniform(0.0),
        fy: Profile::Uniform(-1.0),
    })];
    println!("\nFull model: max over the load range of the tip position error |Δtip| / L\n");
    println!("| n | dead tip, α = 0…10 | follower tip, α = 0…10 | two loads, F1 = 0…150 N | distributed, β = 0.5…10 |");
    println!("|---|---|---|---|---|");
    for n in [10, 20, 40, 80] {
        let full = table4(n);
        println!(
            "| {n} | {:.2e} | {:.2e} | {:.2e} | {:.2e} |",
            max_error(&full, &unit_dead, &dead, 1, (2, 3)),
            max_error(&full, &unit_follower, &follower, 1, (2, 3)),
            max_error(&full, &two_loads, &two, 0, (1, 2)),
            max_error(&full, &distributed, &dist, 1, (2, 3)),
        );
    }
    println!("\nReduced models (first r modes) against the elastica: max |Δtip| / L over the load range\n");
    println!("| n | r | dead tip | follower tip | two loads | distributed |");
    println!("|---|---|---|---|---|---|");
    for n in [10, 20] {
        let full = table4(n);
        let modes = Modes::undeformed(&full).unwrap();
        for r in [1, 2, 3, 4, 6] {
            let rom = ReducedModel::first(&full, modes.shapes(), r).unwrap();
            let e = |loads: &[Load], rows: &[Vec<f64>], c: usize, t: (usize, usize)| {
                // A reduced model may fail to converge where its basis cannot carry the load.
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    max_error(&rom, loads, rows, c, t)
                }))
                .map(|v| format!("{v:.2e}"))
                .unwrap_or_else(|_| "no convergence".into())
            };
            println!(
                "| {n} | {r} | {} | {} | {} | {} |",
                e(&unit_dead, &dead, 1, (2, 3)),
                e(&unit_follower, &follower, 1, (2, 3)),
                e(&two_loads, &two, 0, (1, 2)),
                e(&distributed, &dist, 1, (2, 3)),
            );
        }
    }
}
