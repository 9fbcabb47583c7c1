//! The non-linear modal ROM on the 3-D chain (`ReducedChain3d`, `model/chain3d/reduced.rs`):
//! exact where the projection is (every mode: the full chain in other coordinates; the linear
//! limit: the retained modes' frequencies), and its accuracy against the full chain on a swept,
//! pretwisted, bend–twist coupled wing (flap, lag and twist coupled), statics and dynamics, tip
//! error against the number of modes.

use crate::common::chain3d::coupled_chain;
use flexwing::model::chain3d::{Chain3d, ReducedChain3d, SpatialLoad, SpatialVector};
use flexwing::model::{AppliedLoads, StructuralModel};
use flexwing::solve::integrate::{Radau, RadauOptions, Tolerances};
use flexwing::solve::{
    solve_static, Damping, EquationsOfMotion, Gyroscopic, Modes, StaticOptions, TimeFunction,
};

fn tip_load() -> Vec<SpatialLoad> {
    vec![SpatialLoad::PointForce {
        span: 1.0,
        force: SpatialVector::Dead([0.0, 6.0, -3.0]),
    }]
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn modes(model: &Chain3d, count: usize) -> Modes {
    let nd = model.n_dofs();
    Modes::of_model(model, &vec![0.0; nd], &AppliedLoads::none(), &[], count).unwrap()
}

/// The tip of `model` (coordinates mapped to the joints' rotations by `full_coordinates`) over
/// a release from rest under `10 sin(12 t)` times the tip load, 0.3 s, Radau at rtol 1e-9.
fn tip_history<M: StructuralModel>(
    model: &M,
    chain: &Chain3d,
    applied: &AppliedLoads,
) -> Vec<[f64; 3]> {
    let tf = vec![TimeFunction::Sine {
        omega: 12.0,
        phase: 0.0,
    }];
    let mut eom =
        EquationsOfMotion::new(model, applied, tf, Gyroscopic::Exact, &Damping::None).unwrap();
    let r = model.n_dofs();
    let y0 = eom.state(&vec![0.0; r], &vec![0.0; r]);
    let t: Vec<f64> = (0..=30).map(|k| k as f64 * 0.01).collect();
    let atol = eom.state_atol(1e-10);
    let (traj, _) = Radau {
        options: RadauOptions {
            tolerances: Tolerances { rtol: 1e-9, atol },
            ..Default::default()
        },
    }
    .integrate(&mut eom, 0.0, &y0, &t, &mut |_| {})
    .expect("integrates");
    let n = chain.n_elements();
    traj.y
        .iter()
        .map(|y| chain.node_positions(&model.full_coordinates(&y[..r]))[n])
        .collect()
}

/// With every mode the ROM is the full chain in other (modal) coordinates: the same static
/// equilibrium and the same motion, to the solvers' tolerances (a regression test: the model
/// against itself). Statics: Newton to ~1e-12 on both (bound 1e-10 m); dynamics: Radau at rtol
/// 1e-9 on both (bound 1e-7 m on a motion of ~0.1 m).
#[test]
fn regression_reduced_chain3d_with_every_mode_is_the_full_chain() {
    let n = 5;
    let full = coupled_chain(n);
    let nd = full.n_dofs();
    let shapes = modes(&full, nd);
    let rom = ReducedChain3d::first(&full, shapes.shapes(), nd).unwrap();
    let applied = full.apply(&tip_load(), "loads").unwrap();
    let opts = StaticOptions::default();
    let xf = solve_static(&full, &applied, &[1.0], &opts).unwrap().x;
    let xr = solve_static(&rom, &applied, &[1.0], &opts).unwrap().x;
    let (tf, tr) = (
        full.node_positions(&xf)[n],
        full.node_positions(&rom.full_coordinates(&xr))[n],
    );
    let start = full.node_positions(&vec![0.0; nd])[n];
    let stat = distance(tf, tr);
    eprintln!(
        "every mode, statics: tips {stat:.2e} m apart (deflection {:.3} m)",
        distance(tf, start)
    );
    assert!(stat < 1e-10, "{stat:e}");
    let a = tip_history(&full, &full, &applied);
    let b = tip_history(&rom, &full, &applied);
    let worst = a
        .iter()
        .zip(&b)
        .map(|(p, q)| distance(*p, *q))
        .fold(0.0, f64::max);
    let travel = a.iter().map(|p| distance(*p, start)).fold(0.0, f64::max);
    eprintln!("every mode, dynamics: tips {worst:.2e} m apart (travel {travel:.3} m)");
    assert!(travel > 0.05, "{travel}");
    assert!(worst < 1e-7, "{worst:e}");
}

/// In the linear limit the ROM's natural frequencies are exactly those of the retained modes
/// of the full chain (the Rayleigh–Ritz projection on eigenvectors: `Φᵀ K Φ = Ω²`,
/// `Φᵀ M(0) Φ = I`), whichever modes are kept: to round-off of the eigen-solvers (1e-10).
#[test]
fn reduced_chain3d_is_exact_in_the_linear_limit() {
    let full = coupled_chain(8);
    let all = modes(&full, 12);
    let kept = [0, 2, 3, 7];
    let rom = ReducedChain3d::new(&full, all.shapes(), &kept).unwrap();
    let reduced = modes_of(&rom);
    for (j, &k) in kept.iter().enumerate() {
        let (w, want) = (reduced[j], all.omega()[k]);
        eprintln!("mode {}: ω = {w:.9} rad/s, full chain {want:.9}", k + 1);
        assert!((w - want).abs() < 1e-10 * want, "{w} {want}");
    }
    // The mass-orthogonal projection recovers the modal amplitudes of a shape in the span.
    let x: Vec<f64> = (0..full.n_dofs())
        .map(|i| 0.3 * all.shapes()[(i, 2)] - 0.7 * all.shapes()[(i, 7)])
        .collect();
    let eta = rom.reduce_coordinates(&x);
    let want = [0.0, 0.3, 0.0, -0.7];
    for (e, w) in eta.iter().zip(want) {
        assert!((e - w).abs() < 1e-10, "{eta:?}");
    }
}

fn modes_of(rom: &ReducedChain3d) -> Vec<f64> {
    let r = rom.n_dofs();
    Modes::of_model(rom, &vec![0.0; r], &AppliedLoads::none(), &[], r)
        .unwrap()
        .omega()
        .to_vec()
}

/// Accuracy against the full chain per number of modes on the coupled wing (n = 16, 48
/// coordinates): the static tip under a dead tip force out of every symmetry plane (tip
/// deflection 0.2 m of the 1 m span: geometrically non-linear) and the largest tip error over a
/// forced motion (`10 sin(12 t)` times that force). The figures are reported
/// (docs/chain3d-model.md, "Reduced-order model"); the assertions: the error falls by at least
/// 10× from 1 mode to 12, and vanishes (≤ 1e-7 m, the solvers' tolerance) with all 48.
#[test]
fn reduced_chain3d_accuracy_against_the_number_of_modes() {
    let n = 16;
    let full = coupled_chain(n);
    let nd = full.n_dofs();
    let all = modes(&full, nd);
    let applied = full.apply(&tip_load(), "loads").unwrap();
    let opts = StaticOptions::default();
    let xf = solve_static(&full, &applied, &[1.0], &opts).unwrap().x;
    let start = full.node_positions(&vec![0.0; nd])[n];
    let tip_full = full.node_positions(&xf)[n];
    let reference = tip_history(&full, &full, &applied);
    let travel = reference
        .iter()
        .map(|p| distance(*p, start))
        .fold(0.0, f64::max);
    eprintln!(
        "coupled wing, n = {n}: static tip deflection {:.4} m, dynamic travel {travel:.4} m",
        distance(tip_full, start)
    );
    eprintln!("| modes | static tip error (m) | relative | dynamic tip error (m) | relative |");
    eprintln!("|---|---|---|---|---|");
    let mut errors = Vec::new();
    for r in [1, 2, 3, 4, 6, 8, 12, nd] {
        let rom = ReducedChain3d::first(&full, all.shapes(), r).unwrap();
        let xr = solve_static(&rom, &applied, &[1.0], &opts).unwrap().x;
        let tip = full.node_positions(&rom.full_coordinates(&xr))[n];
        let stat = distance(tip, tip_full);
        let hist = tip_history(&rom, &full, &applied);
        let dynamic = hist
            .iter()
            .zip(&reference)
            .map(|(p, q)| distance(*p, *q))
            .fold(0.0, f64::max);
        eprintln!(
            "| {r} | {stat:.2e} | {:.2e} | {dynamic:.2e} | {:.2e} |",
            stat / distance(tip_full, start),
            dynamic / travel
        );
        errors.push((r, stat, dynamic));
    }
    let first = errors[0];
    let twelve = errors.iter().find(|e| e.0 == 12).copied().unwrap();
    let last = *errors.last().unwrap();
    assert!(twelve.1 < first.1 / 10.0, "{errors:?}");
    assert!(twelve.2 < first.2 / 10.0, "{errors:?}");
    assert!(last.1 < 1e-7 && last.2 < 1e-7, "{errors:?}");
}
