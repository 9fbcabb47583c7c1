//! Prints the convergence tables of `docs/validation.md`: natural frequencies of the lumped model
//! against the continuous references, for several `n` and both calibration rules.
//!
//! Run: `cargo run --release -p flexwing --example convergence`

use flexwing::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use flexwing::model::FullModel;
use flexwing::solve::Modes;

fn omega(length: f64, section: &SectionProperties, n: usize, cal: Calibration) -> Vec<f64> {
    let beam = Beam::new(length, section, &Discretization::Uniform(n), cal).expect("valid beam");
    Modes::undeformed(&FullModel::new(beam))
        .expect("modes")
        .omega()
        .to_vec()
}

fn main() {
    // Euler–Bernoulli cantilever, β_k L from 1 + cos x cosh x = 0.
    let bl = [
        1.875_104_068_7,
        4.694_091_133_0,
        7.854_757_438_2,
        10.995_540_734_9,
    ];
    let (l, ei, m) = (1.0, 50.0, 0.2);
    let section = SectionProperties {
        ei: Profile::Uniform(ei),
        mass_per_length: Profile::Uniform(m),
        torsion: None,
    };
    for cal in [Calibration::TipLoad, Calibration::Uniform] {
        println!("\nBending only, {cal:?} calibration: error of ω_k against Euler–Bernoulli (%)\n");
        println!("| n | mode 1 | mode 2 | mode 3 | mode 4 |\n|---|---|---|---|---|");
        for n in [8, 16, 32, 64, 128] {
            let w = omega(l, &section, n, cal);
            let e: Vec<String> = (0..4)
                .map(|k| {
                    let exact = bl[k] * bl[k] * (ei / (m * l.powi(4))).sqrt();
                    format!("{:+.4}", 100.0 * (w[k] / exact - 1.0))
                })
                .collect();
            println!("| {n} | {} |", e.join(" | "));
        }
    }

    // Table 1 beam (model.md item 6), coupled bending–torsion.
    // Continuous coupled beam, tests/data/continuous_beam/table1_coupled.csv (see its README).
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/continuous_beam/table1_coupled.csv"
    );
    let reference: Vec<f64> = csv::Reader::from_path(path)
        .expect("reference file")
        .records()
        .map(|r| r.expect("record")[1].parse().expect("number"))
        .collect();
    let paper_n16 = [2.21, 9.55, 13.78, 27.39, 36.38, 46.69, 63.14, 65.05, 80.53];
    let paper_n32 = [2.21, 9.55, 13.79, 27.40, 36.59, 46.88, 63.79, 65.96, 83.08];
    let table1 = SectionProperties {
        ei: Profile::Uniform(2e4),
        mass_per_length: Profile::Uniform(0.75),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(1e3),
            polar_inertia: Profile::Uniform(0.1),
            inertia_axis: InertiaAxis::MassCentre,
            offset: Profile::Uniform(0.267),
        }),
    };
    for (n, paper) in [(16, paper_n16), (32, paper_n32)] {
        let w = omega(16.0, &table1, n, Calibration::TipLoad);
        println!("\nTable 2, n = {n} (rad/s)\n");
        println!("| mode | flexwing | paper (lumped) | continuous reference | error vs reference (%) | paper's error (%) |");
        println!("|---|---|---|---|---|---|");
        for k in 0..9 {
            println!(
                "| {} | {:.3} | {:.2} | {:.3} | {:+.3} | {:+.3} |",
                k + 1,
                w[k],
                paper[k],
                reference[k],
                100.0 * (w[k] / reference[k] - 1.0),
                100.0 * (paper[k] / reference[k] - 1.0),
            );
        }
    }
    println!("\nTable 1 beam: error (%) of the first 9 modes against the continuous reference\n");
    println!(
        "| n | {} |",
        (1..=9)
            .map(|k| format!("mode {k}"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|{}", "---|".repeat(9));
    for n in [8, 16, 32, 64, 128] {
        let w = omega(16.0, &table1, n, Calibration::TipLoad);
        let e: Vec<String> = (0..9)
            .map(|k| format!("{:+.3}", 100.0 * (w[k] / reference[k] - 1.0)))
            .collect();
        println!("| {n} | {} |", e.join(" | "));
    }

    // Large n: the lowest ten modes by Lanczos (tests/suite/modes_large_n.rs).
    let bl10 = euler_bernoulli_roots(10);
    let eb: Vec<f64> = bl10
        .iter()
        .map(|b| b * b * (ei / (m * l.powi(4))).sqrt())
        .collect();
    for (name, length, section, exact) in [
        ("Table 4 beam against Euler–Bernoulli", l, &section, &eb[..]),
        (
            "Table 1 beam against the continuous coupled beam",
            16.0,
            &table1,
            &reference[..10],
        ),
    ] {
        println!("\n{name}: error of ω_k, and observed order against the previous row\n");
        println!(
            "| n | {} |",
            [1, 2, 3, 4, 10]
                .map(|k| format!("mode {k} | order"))
                .join(" | ")
        );
        println!("|---|{}", "---|---|".repeat(5));
        let mut prev: Option<(usize, Vec<f64>)> = None;
        for n in [100, 300, 1000, 3000, 10_000] {
            let beam = Beam::new(
                length,
                section,
                &Discretization::Uniform(n),
                Calibration::TipLoad,
            )
            .expect("valid beam");
            let modes = Modes::lowest(&FullModel::new(beam), 10).expect("modes");
            let e: Vec<f64> = (0..10).map(|k| modes.omega()[k] / exact[k] - 1.0).collect();
            let cells: Vec<String> = [0, 1, 2, 3, 9]
                .iter()
                .map(|&k| {
                    let order = prev.as_ref().map_or("–".to_string(), |(n0, e0)| {
                        format!("{:.4}", (e0[k] / e[k]).ln() / (n as f64 / *n0 as f64).ln())
                    });
                    format!("{:+.3e} | {order}", e[k])
                })
                .collect();
            println!("| {n} | {} |", cells.join(" | "));
            prev = Some((n, e));
        }
    }
}

/// Roots of `1 + cos x cosh x = 0` by bisection in `[(k − 1)π, kπ]`.
fn euler_bernoulli_roots(count: usize) -> Vec<f64> {
    let f = |x: f64| 1.0 + x.cos() * x.cosh();
    (1..=count)
        .map(|k| {
            let pi = std::f64::consts::PI;
            let (mut a, mut b) = ((k as f64 - 1.0) * pi, k as f64 * pi);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if f(a) * f(mid) <= 0.0 {
                    b = mid;
                } else {
                    a = mid;
                }
            }
            0.5 * (a + b)
        })
        .collect()
}
