//! Load control follows the equilibrium path from the unloaded beam (issue 9, section 1): a large
//! load applied at once reaches the equilibrium a fine sweep reaches, the primary branch of the
//! elastica (computed here by shooting, `common/elastica.rs`), never a distant unstable branch.
//! Table 4 beam: L = 1 m, EI = 50 N·m², m = 0.2 kg/m.

use crate::common::elastica::dead_tip_primary;
use crate::common::*;
use flexwing::model::{Force, FullModel, Load};
use flexwing::solve::{solve_static, sweep_static, StaticOptions, StaticSolution};
use flexwing::SolveError;
use std::f64::consts::PI;

const EI: f64 = 50.0;

fn tip_load(full: &FullModel, fx: f64, fy: f64) -> flexwing::model::AppliedLoads {
    full.apply(
        &[Load::PointForce {
            span: 1.0,
            force: Force::Dead { fx, fy },
        }],
        "loads",
    )
    .unwrap()
}

fn tip(full: &FullModel, sol: &StaticSolution) -> [f64; 2] {
    let p = full.node_positions(&full.kinematics(&sol.q))[full.n_elements()];
    [p[0], p[1]]
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The dead tip load `α EI/L²` applied in one call, from rest, with the default options.
fn at_once(n: usize, alpha: f64) -> (FullModel, StaticSolution) {
    let full = table4(n);
    let loads = tip_load(&full, 0.0, alpha * EI);
    let sol = solve_static(&full, &loads, &[1.0], &StaticOptions::default())
        .unwrap_or_else(|e| panic!("n = {n}, α = {alpha}: {e}"));
    (full, sol)
}

#[test]
fn the_shooting_elastica_matches_the_checked_in_reference() {
    // The in-test elastica against the 30-digit reference of tests/data/elastica (elliptic
    // integrals and Taylor shooting): RK4 on 800 √α steps is good to ~1e-12; allow 1e-10.
    let path = format!(
        "{}/tests/data/elastica/dead_tip.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let rows: Vec<Vec<f64>> = csv::Reader::from_path(path)
        .unwrap()
        .records()
        .map(|r| r.unwrap().iter().map(|v| v.parse().unwrap()).collect())
        .collect();
    for alpha in [1.0, 3.0, 10.0] {
        let row = rows.iter().find(|r| r[0] == alpha).unwrap();
        let e = dead_tip_primary(alpha);
        for (k, col) in [(0, 2), (1, 3), (2, 4)] {
            assert!(
                (e[k] - row[col]).abs() < 1e-10,
                "α = {alpha}, column {col}: {} vs {}",
                e[k],
                row[col]
            );
        }
    }
}

#[test]
fn a_large_tip_load_applied_at_once_lands_on_the_elastica() {
    // The case: fy = 750 N (α = 15) at once. Before path following, Newton from rest went
    // to an unstable C-shape below the clamp at n = 40 and a looped shape at n = 20.
    let alpha = 15.0;
    let exact = dead_tip_primary(alpha);
    // The elastica tip the issue quotes.
    assert!(distance([exact[0], exact[1]], [0.365, 0.848]) < 1e-3);
    let errors: Vec<f64> = [20, 40, 80]
        .iter()
        .map(|&n| {
            let (full, sol) = at_once(n, alpha);
            distance(tip(&full, &sol), [exact[0], exact[1]])
        })
        .collect();
    // Discretization error of the primary branch, second order: measured 9.7e-4, 2.4e-4, 6.0e-5
    // at n = 20, 40, 80 (0.39 L/n²); bound 0.5 L/n² (the wrong branches were 0.4–1 L away).
    for (e, n) in errors.iter().zip([20.0, 40.0, 80.0]) {
        assert!(*e < 0.5 / (n * n), "n = {n}: tip error {e:.3e}");
    }
    for w in errors.windows(2) {
        assert!((3.5..4.5).contains(&(w[0] / w[1])), "ratio {}", w[0] / w[1]);
    }
}

#[test]
fn dead_tip_loads_up_to_alpha_50_at_once() {
    let n = 40;
    for alpha in [5.0, 10.0, 12.0, 20.0, 30.0, 40.0, 50.0] {
        let exact = dead_tip_primary(alpha);
        let (full, sol) = at_once(n, alpha);
        let e = distance(tip(&full, &sol), [exact[0], exact[1]]);
        // The discretization error grows with the load (the curvature concentrates at the root):
        // measured 9.0e-5 (α = 5), 1.75e-4 (10), 3.0e-4 (20), 5.5e-4 (50) at n = 40, about
        // 1.1e-5 α; bound 1.5e-5 α + 1e-4, far below the distance to any other branch (> 0.3 L).
        assert!(e < 1.5e-5 * alpha + 1e-4, "α = {alpha}: tip error {e:.3e}");
        // A path-following solve from rest reports a stable equilibrium.
        assert_eq!(sol.stable, Some(true), "α = {alpha}");
    }
}

#[test]
fn a_load_at_once_reaches_the_equilibrium_of_a_fine_sweep() {
    // Regression test of path following against itself: one call against 60 sweep points.
    let n = 40;
    let full = table4(n);
    let loads = tip_load(&full, 0.0, 1.0);
    let opts = StaticOptions::default();
    let once = solve_static(&full, &loads, &[750.0], &opts).unwrap();
    let points: Vec<Vec<f64>> = (1..=60).map(|k| vec![12.5 * k as f64]).collect();
    let sweep = sweep_static(&full, &loads, &points, &opts).unwrap();
    let last = sweep.last().unwrap();
    // Both converge to 1e-10 of the residual scale, so they may differ by that times the
    // tangent's condition number: bound 1e-8 rad (measured 6e-15: the same converged digits).
    let diff = once
        .q
        .iter()
        .zip(&last.q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(diff < 1e-8, "max |Δq| = {diff:.2e}");
}

#[test]
fn load_control_stops_where_the_straight_beam_buckles() {
    // A perfectly straight beam under a compressive dead tip load of 1.5 × Euler: the straight
    // state is an equilibrium at every load but unstable past buckling, and no other branch is
    // connected to it without a bifurcation. Load control must stop at the model's buckling load
    // (8e-5 above Euler's at n = 40, statics_closed_form.rs) with an error — before path
    // following it returned the unstable straight beam as a solution.
    let n = 40;
    let full = table4(n);
    let p_euler = PI * PI * EI / 4.0;
    let loads = tip_load(&full, -1.5 * p_euler, 0.0);
    let err = solve_static(&full, &loads, &[1.0], &StaticOptions::default()).unwrap_err();
    let SolveError::StaticUnstable {
        load_factor,
        attempted,
    } = err
    else {
        panic!("expected StaticUnstable, got {err}");
    };
    // The last stable load is within the smallest load step (1e-6) of the buckling load:
    // measured |1.5 λ − 1| = 7.9e-5; bound 2e-4.
    assert!((1.5 * load_factor - 1.0).abs() < 2e-4, "λ = {load_factor}");
    assert!(attempted > load_factor && attempted - load_factor < 1e-5);
    assert!(err.to_string().contains("arc-length"), "{err}");
    // With a small lateral imperfection the path bends away smoothly and stays stable: the
    // buckled beam is found, stable, well past the Euler load.
    let imperfect = tip_load(&full, -1.5 * p_euler, 1e-3 * p_euler);
    let sol = solve_static(&full, &imperfect, &[1.0], &StaticOptions::default()).unwrap();
    assert_eq!(sol.stable, Some(true));
    let y = tip(&full, &sol)[1];
    assert!(y > 0.5, "tip y = {y}");
}

#[test]
fn follower_loads_are_not_assessed() {
    // A follower tip force (non-conservative): the tangent is not symmetric, statics cannot
    // prove stability; the point is reported as not assessed, not as stable.
    let full = table4(20);
    let loads = full
        .apply(
            &[Load::PointForce {
                span: 1.0,
                force: Force::Follower {
                    tangential: 0.0,
                    normal: 500.0,
                },
            }],
            "loads",
        )
        .unwrap();
    let sol = solve_static(&full, &loads, &[1.0], &StaticOptions::default()).unwrap();
    assert_eq!(sol.stable, None);
}

#[test]
fn the_stability_check_alone_refuses_the_unstable_c_shape() {
    // With the rotation limit off, Newton's first step from rest goes where it went before path
    // following (the C-shape below the clamp at n = 40); the stability check refuses it, the step
    // is cut, and the path is followed to the elastica anyway.
    let n = 40;
    let full = table4(n);
    let loads = tip_load(&full, 0.0, 750.0);
    let opts = StaticOptions {
        max_rotation_step: 1e6,
        ..StaticOptions::default()
    };
    let sol = solve_static(&full, &loads, &[1.0], &opts).unwrap();
    assert!(sol.stats.unstable_steps >= 1, "{:?}", sol.stats);
    let exact = dead_tip_primary(15.0);
    // As in a_large_tip_load_applied_at_once_lands_on_the_elastica: 2.4e-4 at n = 40.
    assert!(distance(tip(&full, &sol), [exact[0], exact[1]]) < 0.5 / (n * n) as f64);
}

#[test]
fn an_extreme_tip_load_at_once_gives_the_primary_branch() {
    // fy = 5e7 N (α = 1e6) at once at n = 20, which gave a zig-zag reported complete. The
    // primary branch of the elastica has θ rising monotonically from 0 to θ_L < π/2 (first
    // integral θ'² = 2α(sin θ_L − sin θ)); at this load the whole beam stands almost vertical.
    let n = 20;
    let full = table4(n);
    let loads = tip_load(&full, 0.0, 5e7);
    let sol = solve_static(&full, &loads, &[1.0], &StaticOptions::default()).unwrap();
    assert_eq!(sol.stable, Some(true));
    let theta = full.kinematics(&sol.q).theta;
    assert!(theta[0] > 0.0, "θ_0 = {}", theta[0]);
    // (to round-off: the outer elements are vertical to 1 ulp)
    for w in theta.windows(2) {
        assert!(
            w[1] >= w[0] - 1e-12 && w[1] <= PI / 2.0 + 1e-12,
            "θ = {theta:?}"
        );
    }
    // The tip is within the root element's rotation of the vertical: (ℓ cos θ_0, ≈ L).
    let t = tip(&full, &sol);
    assert!(t[0] > 0.0 && t[0] < 1e-3 && t[1] > 0.999, "tip {t:?}");
}
