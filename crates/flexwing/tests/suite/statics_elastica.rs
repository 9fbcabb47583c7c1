//! Non-linear statics against the inextensible elastica (independent reference:
//! `tests/data/elastica/`, shooting with 24th-order Taylor series at 30 digits, cross-checked
//! against elliptic integrals; see the README there). Table 4 beam: L = 1 m, EI = 50 N·m².

use crate::common::elastica::two_followers;
use crate::common::*;
use flexwing::beam::Profile;
use flexwing::model::{DistributedForce, Force, FullModel, Load, PlanarModel, ReducedModel};
use flexwing::solve::{sweep_static, Modes, StaticOptions, StaticSolution};

fn read(file: &str) -> Vec<Vec<f64>> {
    let path = format!("{}/tests/data/elastica/{file}", env!("CARGO_MANIFEST_DIR"));
    csv::Reader::from_path(path)
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

/// Sweep the first load's scale over `column` of `rows` (other loads at scale 1).
fn sweep<M: PlanarModel>(
    model: &M,
    loads: &[Load],
    rows: &[Vec<f64>],
    column: usize,
) -> Vec<StaticSolution> {
    let applied = model.full_model().apply(loads, "loads").unwrap();
    let points: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            let mut s = vec![1.0; loads.len()];
            s[0] = r[column];
            s
        })
        .collect();
    sweep_static(model, &applied, &points, &StaticOptions::default()).expect("converges")
}

fn tip(full: &FullModel, sol: &StaticSolution) -> [f64; 2] {
    let p = full.node_positions(&full.kinematics(&sol.q))[full.n_elements()];
    [p[0], p[1]]
}

/// Max over the sweep of the tip position error (m) against columns `cols` of `rows`.
fn max_tip_error<M: PlanarModel>(
    model: &M,
    loads: &[Load],
    rows: &[Vec<f64>],
    scale: usize,
    cols: (usize, usize),
) -> f64 {
    let sols = sweep(model, loads, rows, scale);
    sols.iter()
        .zip(rows)
        .map(|(s, r)| {
            let t = tip(model.full_model(), s);
            (t[0] - r[cols.0]).hypot(t[1] - r[cols.1])
        })
        .fold(0.0, f64::max)
}

fn unit_tip(force: Force) -> Vec<Load> {
    vec![Load::PointForce { span: 1.0, force }]
}

#[test]
fn reference_reproduces_bisshopp_and_drucker() {
    // Provenance check of the data itself: tip deflection / L at α = 1, 3, 10 (B&D 1945, 4 digits).
    let dead = read("dead_tip.csv");
    for (alpha, published) in [(1.0, 0.3017), (3.0, 0.6033), (10.0, 0.8106)] {
        let row = dead.iter().find(|r| r[0] == alpha).unwrap();
        assert!(
            (row[3] - published).abs() <= 5e-5,
            "α = {alpha}: {}",
            row[3]
        );
    }
}

#[test]
fn dead_and_follower_tip_loads_within_a_thousandth_of_l_at_40_elements() {
    let (dead, follower) = (read("dead_tip.csv"), read("follower_tip.csv"));
    // Column 1 is P in N: the unit load is scaled by P. α = PL²/EI runs 0…10.
    let cases = [
        (unit_tip(Force::Dead { fx: 0.0, fy: 1.0 }), &dead),
        (
            unit_tip(Force::Follower {
                tangential: 0.0,
                normal: 1.0,
            }),
            &follower,
        ),
    ];
    for (loads, rows) in cases {
        let e: Vec<f64> = [20, 40, 80]
            .iter()
            .map(|&n| max_tip_error(&table4(n), &loads, rows, 1, (2, 3)))
            .collect();
        // The bound: 0.1 % of L at n = 40 (measured 1.8e-4 dead, 4.1e-4 follower).
        assert!(e[1] < 1e-3, "n = 40: {:.2e}", e[1]);
        // Second order in 1/n: the error quarters with each doubling.
        for w in e.windows(2) {
            assert!((3.5..4.5).contains(&(w[0] / w[1])), "ratio {}", w[0] / w[1]);
        }
    }
}

#[test]
fn deformed_shapes_match_the_elastica_at_every_node() {
    let n = 40;
    let full = table4(n);
    for (file, force) in [
        ("dead_tip_shapes.csv", Force::Dead { fx: 0.0, fy: 1.0 }),
        (
            "follower_tip_shapes.csv",
            Force::Follower {
                tangential: 0.0,
                normal: 1.0,
            },
        ),
    ] {
        let rows = read(file);
        for alpha in [1.0, 3.0, 10.0] {
            let shape: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] == alpha).collect();
            let sol = &sweep(&full, &unit_tip(force), &[vec![50.0 * alpha]], 0)[0];
            let nodes = full.node_positions(&full.kinematics(&sol.q));
            for (k, p) in nodes.iter().enumerate() {
                // Reference nodes at s = j/80: lumped node k is reference node 2k.
                let r = shape[2 * k];
                let e = (p[0] - r[3]).hypot(p[1] - r[4]);
                assert!(e < 1e-3, "{file} α = {alpha} node {k}: {e:.2e}");
            }
        }
    }
}

#[test]
fn paper_two_load_case_full_and_reduced() {
    // Section 5.2.1: dead tip F1 = 0…150 N (+y), dead F2 = −150 N at mid-span.
    let rows = read("paper_two_loads.csv");
    let loads = vec![
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
    // Full model: measured 4.6e-4 (n = 10) and 1.2e-4 (n = 20); bounds with 30 % margin.
    assert!(max_tip_error(&table4(10), &loads, &rows, 0, (1, 2)) < 6e-4);
    assert!(max_tip_error(&table4(20), &loads, &rows, 0, (1, 2)) < 1.5e-4);
    // Reduced models, n = 20: their truncation error against the full model shrinks with r.
    let full = table4(20);
    let modes = Modes::undeformed(&full).unwrap();
    let full_sols = sweep(&full, &loads, &rows, 0);
    let truncation = |r: usize| -> f64 {
        let rom = ReducedModel::first(&full, modes.shapes(), r).unwrap();
        sweep(&rom, &loads, &rows, 0)
            .iter()
            .zip(&full_sols)
            .map(|(a, b)| {
                let (ta, tb) = (tip(&full, a), tip(&full, b));
                (ta[0] - tb[0]).hypot(ta[1] - tb[1])
            })
            .fold(0.0, f64::max)
    };
    let (e2, e3, e4) = (truncation(2), truncation(3), truncation(4));
    assert!(e4 < e2, "r = 4: {e4:.2e}, r = 2: {e2:.2e}");
    // Two modes already carry the two-load case within 0.2 % of L, three within 0.05 %.
    assert!(e2 < 2e-3 && e3 < 5e-4, "r = 2: {e2:.2e}, r = 3: {e3:.2e}");
}

#[test]
fn distributed_load_converges_to_the_elastica() {
    let rows = read("distributed.csv");
    let loads = vec![Load::Distributed(DistributedForce::Dead {
        fx: Profile::Uniform(0.0),
        fy: Profile::Uniform(-1.0),
    })];
    // Column 1 is w0 (N/m). Midpoint lumping is second order too: measured 7.0e-4, 1.75e-4 at
    // n = 20, 40.
    let e20 = max_tip_error(&table4(20), &loads, &rows, 1, (2, 3));
    let e40 = max_tip_error(&table4(40), &loads, &rows, 1, (2, 3));
    assert!(
        e40 < 1e-3 && (3.5..4.5).contains(&(e20 / e40)),
        "{e20:.2e} {e40:.2e}"
    );
}

#[test]
fn the_shooting_reference_of_follower_forces_matches_the_checked_in_one() {
    // The two-follower shooting of common/elastica.rs with the mid-span force off is the
    // follower tip case of tests/data/elastica (30 digits): RK4 on 4000 steps, agreement 1e-10.
    let rows = read("follower_tip.csv");
    let mut guess = 0.0;
    for row in rows.iter().skip(1) {
        let r = two_followers(50.0, row[1], 0.0, guess);
        guess = r[2];
        for (k, col) in [(0, 2), (1, 3), (2, 4)] {
            assert!((r[k] - row[col]).abs() < 1e-10, "α = {}: {r:?}", row[0]);
        }
    }
}

#[test]
fn follower_forces_at_mid_span_converge_at_second_order() {
    // The paper's two-load case with both forces as followers normal to the beam: F1 at the tip,
    // swept 0 … ±150 N (up and down), F2 = −150 N at mid-span (a node for even n), against the
    // elastica of two follower forces shot in common/elastica.rs (each force along the normal of
    // the beam's tangent at its point). Before the follower force turned with the beam's tangent
    // at its point (it turned with the inboard element), the error fell at first order only:
    // 4.7e-3, 2.5e-3, 1.3e-3, 6.6e-4 L at n = 10 … 80 (F1 up).
    let f1: Vec<f64> = (0..=15).map(|k| 10.0 * k as f64).collect();
    for sign in [1.0, -1.0] {
        let mut guess = 0.0;
        let reference: Vec<Vec<f64>> = f1
            .iter()
            .map(|&f| {
                let r = two_followers(50.0, sign * f, -150.0, guess);
                guess = r[2];
                vec![f, r[0], r[1]]
            })
            .collect();
        let loads = vec![
            Load::PointForce {
                span: 1.0,
                force: Force::Follower {
                    tangential: 0.0,
                    normal: sign,
                },
            },
            Load::PointForce {
                span: 0.5,
                force: Force::Follower {
                    tangential: 0.0,
                    normal: -150.0,
                },
            },
        ];
        let e: Vec<f64> = [10, 20, 40, 80]
            .iter()
            .map(|&n| max_tip_error(&table4(n), &loads, &reference, 0, (1, 2)))
            .collect();
        // Measured (F1 up) 3.8e-4, 9.5e-5, 2.4e-5, 5.9e-6 and (F1 down, the beam curls to a tip
        // angle of −1.7 rad) 1.4e-3, 3.5e-4, 8.6e-5, 2.2e-5 at n = 10, 20, 40, 80: bound 0.2 L/n²,
        // and each doubling of n divides the error by 3.5 to 4.5.
        for (err, n) in e.iter().zip([10.0, 20.0, 40.0, 80.0]) {
            assert!(*err < 0.2 / (n * n), "F1 sign {sign}, n = {n}: {err:.3e}");
        }
        for w in e.windows(2) {
            assert!(
                (3.5..4.5).contains(&(w[0] / w[1])),
                "F1 sign {sign}: errors {e:?}"
            );
        }
    }
}

#[test]
fn tip_loads_converge_at_second_order_up_to_ten_thousand_elements() {
    // The full model's Newton tangent is factored by the O(n) chain sweep (solve/tangent.rs),
    // so the solve at n = 10 000 costs milliseconds (most of this test's second or so is the
    // beam's set-up, the spring calibration). Dead and follower tip forces of 150 N (α = 3)
    // against the elastica: the error falls as 1/n² (measured ratios between n = 1000 and
    // 10 000: 100.0 dead, 100.1 follower) down to 1e-9 m (measured 7.8e-10 m dead, 5.3e-10 m
    // follower at n = 10 000). Bounds: ratio in [80, 125] (second order), error below 5e-9 m.
    for (file, force) in [
        ("dead_tip.csv", Force::Dead { fx: 0.0, fy: 150.0 }),
        (
            "follower_tip.csv",
            Force::Follower {
                tangential: 0.0,
                normal: 150.0,
            },
        ),
    ] {
        let row = read(file)
            .into_iter()
            .find(|r| r[1] == 150.0)
            .expect("α = 3 row");
        let error = |n: usize| {
            let full = table4(n);
            let loads = full.apply(&unit_tip(force), "loads").unwrap();
            let sol =
                flexwing::solve::solve_static(&full, &loads, &[1.0], &StaticOptions::default())
                    .expect("converges");
            let t = tip(&full, &sol);
            (t[0] - row[2]).hypot(t[1] - row[3])
        };
        let (e1, e2) = (error(1000), error(10_000));
        eprintln!(
            "{file}: n = 1000 {e1:.2e} m, n = 10 000 {e2:.2e} m, ratio {:.1}",
            e1 / e2
        );
        assert!(
            (80.0..125.0).contains(&(e1 / e2)),
            "{file}: {e1:.2e} {e2:.2e}"
        );
        assert!(e2 < 5e-9, "{file}: {e2:.2e}");
    }
}
