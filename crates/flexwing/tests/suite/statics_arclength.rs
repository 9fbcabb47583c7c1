//! Arc-length continuation through limit points (issue 9, section 1), against the elastica
//! computed here (`common/elastica.rs`).
//!
//! The case: the Table 4 cantilever (L = 1 m, EI = 50 N·m²) under a dead compressive tip force
//! `P = 1.5 P_cr` (`P_cr = π² EI / 4L²`, Euler) and a tip moment `M`, the load factor. Above the
//! buckling load the moment–rotation curve is an S: the beam buckled downwards (held by a small
//! negative moment) stays on its stable branch as `M` grows until a limit point (`M_max`), where
//! it would snap through; the path then runs back through the straight state on an unstable
//! branch to a second limit point (`−M_max`), and rises again on the stable upward-buckled branch.
//! Why this case: it has two limit points and an unstable branch between them, and its exact path
//! is one pendulum equation — every root curvature `κ0` gives one equilibrium
//! (`θ'' = −(P/EI) sin θ`, `θ(0) = 0`, `θ'(0) = κ0`, `M = EI θ'(L)`), so the reference needs no
//! shooting and no branch choice. The stable branches are where `M` grows with `κ0`.

use crate::common::elastica::compressed_with_tip_moment;
use crate::common::*;
use flexwing::beam::{Calibration, Profile};
use flexwing::model::{AppliedLoads, Force, FullModel, Load};
use flexwing::solve::{
    arc_length_static, continue_static, solve_static, ArcLengthOptions, StaticOptions, StaticPath,
};
use flexwing::SolveError;
use std::f64::consts::PI;

const EI: f64 = 50.0;
/// Compressive tip force, 1.5 × Euler (N).
const P: f64 = 1.5 * PI * PI * EI / 4.0;
/// The path: M = −2 → 30 N·m.
const M_START: f64 = -2.0;
const M_END: f64 = 30.0;

fn setup(n: usize) -> (FullModel, AppliedLoads) {
    let full = model(
        1.0,
        &bending_only(Profile::Uniform(EI), Profile::Uniform(0.2)),
        n,
        Calibration::TipLoad,
    );
    let loads = full
        .apply(
            &[
                Load::PointForce {
                    span: 1.0,
                    force: Force::Dead { fx: -P, fy: 0.0 },
                },
                Load::Moment {
                    span: 1.0,
                    value: 1.0,
                },
            ],
            "loads",
        )
        .unwrap();
    (full, loads)
}

/// The reference: `(M, tip x, tip y, tip angle)` for the root curvature `κ0`.
fn exact(kappa0: f64) -> [f64; 4] {
    let r = compressed_with_tip_moment(P / EI, kappa0);
    [EI * r[0], r[1], r[2], r[3]]
}

/// The reference's `κ0` for a tip angle (the tip angle grows monotonically with `κ0` on this
/// path, checked below by sampling), by bisection.
fn kappa_for_tip_angle(theta: f64) -> f64 {
    // 40 halvings of 12: 1e-11.
    let (mut lo, mut hi) = (-6.0, 6.0);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if exact(mid)[3] < theta {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The reference's limit point on the downward branch: `(M_max, κ0)` at the maximum of `M(κ0)`,
/// by golden section on `κ0 ∈ [−3, −0.5]` (one maximum there: the sampled curve rises then
/// falls). By symmetry the other limit point is `(−M_max, −κ0)`.
fn exact_limit() -> (f64, f64) {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (-3.0, -0.5);
    for _ in 0..100 {
        let c = b - g * (b - a);
        let d = a + g * (b - a);
        if exact(c)[0] > exact(d)[0] {
            b = d;
        } else {
            a = c;
        }
    }
    let k = 0.5 * (a + b);
    (exact(k)[0], k)
}

/// Start (M = −2 N·m, buckled downwards, by load control from rest) and the path to M = 30 N·m.
fn path(n: usize, options: &ArcLengthOptions) -> (FullModel, StaticPath) {
    let (full, loads) = setup(n);
    let start = solve_static(&full, &loads, &[1.0, M_START], &StaticOptions::default()).unwrap();
    assert_eq!(start.stable, Some(true));
    let path = arc_length_static(
        &full,
        &loads,
        (&start.x, &start.scales),
        &[1.0, M_END],
        options,
    )
    .unwrap_or_else(|e| panic!("n = {n}: {e}"));
    (full, path)
}

fn moment(path: &StaticPath, i: usize) -> f64 {
    path.points[i].solution.scales[1]
}

fn tip_angle(full: &FullModel, path: &StaticPath, i: usize) -> f64 {
    full.kinematics(&path.points[i].solution.q).theta[full.n_elements() - 1]
}

/// The extremum of `M` at a limit point, from the parabola through the point and its two
/// neighbours (in arc length).
fn vertex(path: &StaticPath, i: usize) -> f64 {
    let (s0, s1, s2) = (
        path.points[i - 1].arc_length,
        path.points[i].arc_length,
        path.points[i + 1].arc_length,
    );
    let (m0, m1, m2) = (moment(path, i - 1), moment(path, i), moment(path, i + 1));
    let d01 = (m1 - m0) / (s1 - s0);
    let d12 = (m2 - m1) / (s2 - s1);
    let c = (d12 - d01) / (s2 - s0);
    let b = d01 - c * (s0 + s1);
    let s_star = -b / (2.0 * c);
    m1 + b * (s_star - s1) + c * (s_star * s_star - s1 * s1)
}

/// Distance of a point `(M, tip)` of the model from the reference curve, in `(M L/EI, x/L, y/L)`:
/// golden section on `κ0` around `guess` (the curve is smooth and the distance unimodal there).
fn distance_to_curve(m: f64, tip: [f64; 2], guess: f64) -> f64 {
    let d = |k: f64| {
        let r = exact(k);
        ((m - r[0]) / EI).hypot(tip[0] - r[1]).hypot(tip[1] - r[2])
    };
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (guess - 0.3, guess + 0.3);
    // 0.6 · 0.618⁵⁰ ≈ 2e-11.
    for _ in 0..50 {
        let c = b - g * (b - a);
        let e = a + g * (b - a);
        if d(c) < d(e) {
            b = e;
        } else {
            a = c;
        }
    }
    d(0.5 * (a + b))
}

fn tip(full: &FullModel, path: &StaticPath, i: usize) -> [f64; 2] {
    let p = full.node_positions(&full.kinematics(&path.points[i].solution.q))[full.n_elements()];
    [p[0], p[1]]
}

fn fine() -> ArcLengthOptions {
    // Steps of at most 0.02 rad (rms rotation): about 160 points, enough for the parabola through
    // the points at a limit point to locate it to ~1e-4 of M_max.
    ArcLengthOptions {
        max_arc: 0.02,
        ..ArcLengthOptions::default()
    }
}

#[test]
fn arc_length_follows_the_s_curve_through_both_limit_points() {
    let (m_max, _) = exact_limit();
    // The reference's own check: M_max ≈ 20.19 N·m, the path of the test passes it.
    assert!((20.0..20.4).contains(&m_max) && M_END > m_max);
    let mut limit_errors = Vec::new();
    let mut distances = Vec::new();
    for n in [20, 40, 80] {
        let (full, p) = path(n, &fine());
        // The path reaches the target: M = 30 N·m, on the upward-buckled stable branch.
        let end = p.points.last().unwrap();
        assert_eq!(end.load_factor, 1.0);
        assert_eq!(end.solution.scales, vec![1.0, M_END]);
        assert_eq!(end.solution.stable, Some(true));
        // Two limit points: M rises to M_max, falls to −M_max, rises again.
        let lp = p.limit_points();
        assert_eq!(lp.len(), 2, "n = {n}: limit points {lp:?}");
        assert!(moment(&p, lp[0]) > 0.0 && moment(&p, lp[1]) < 0.0);
        limit_errors.push([vertex(&p, lp[0]) - m_max, vertex(&p, lp[1]) + m_max]);
        // Every point (every fourth, for time) lies on the reference curve (M, tip): the
        // distance is the model's discretization error.
        let worst = (0..p.points.len())
            .step_by(4)
            .map(|i| {
                let guess = kappa_for_tip_angle(tip_angle(&full, &p, i));
                distance_to_curve(moment(&p, i), tip(&full, &p, i), guess)
            })
            .fold(0.0, f64::max);
        distances.push(worst);
    }
    // Distance to the curve, second order: measured 5.9e-4, 1.47e-4, 3.7e-5 at n = 20, 40, 80;
    // bound 0.3/n², and the ratio of successive errors in [3.5, 4.5].
    for (d, n) in distances.iter().zip([20.0, 40.0, 80.0]) {
        assert!(*d < 0.3 / (n * n), "n = {n}: distance {d:.3e}");
    }
    for w in distances.windows(2) {
        assert!((3.5..4.5).contains(&(w[0] / w[1])), "ratio {}", w[0] / w[1]);
    }
    // Limit moments, second order too: measured errors 1.27e-2, 3.2e-3, 8e-4 N·m (6e-4 … 4e-5
    // of M_max) at both limit points; bound 6/n² N·m, each error at least 3× the next.
    for (e, n) in limit_errors.iter().zip([20.0, 40.0, 80.0]) {
        for v in e {
            assert!(
                v.abs() < 6.0 / (n * n),
                "n = {n}: limit moment error {v:.3e}"
            );
        }
    }
    for w in limit_errors.windows(2) {
        for k in 0..2 {
            assert!(w[0][k].abs() > 3.0 * w[1][k].abs(), "{limit_errors:?}");
        }
    }
}

#[test]
fn the_branch_between_the_limit_points_is_marked_unstable() {
    let (full, p) = path(40, &fine());
    let lp = p.limit_points();
    // κ0 of the reference's limit points: ±κ*.
    let kappa_star = exact_limit().1.abs();
    let mut unstable = 0;
    for (i, point) in p.points.iter().enumerate() {
        let stable = point
            .solution
            .stable
            .expect("conservative loads are assessed");
        // Against the path's own limit points: the flag changes exactly there (the point at the
        // turn itself may fall on either side).
        if i < lp[0] || i > lp[1] {
            assert!(
                stable,
                "point {i} before/after the limit points is unstable"
            );
        } else if i > lp[0] && i < lp[1] {
            assert!(!stable, "point {i} between the limit points is stable");
        }
        // Against the reference: stable where M grows with κ0 (|κ0| > κ*), away from the folds
        // by more than the discretization error (0.02 in κ0).
        let k = kappa_for_tip_angle(tip_angle(&full, &p, i));
        if (k.abs() - kappa_star).abs() > 0.02 {
            assert_eq!(stable, k.abs() > kappa_star, "point {i}, κ0 = {k}");
        }
        unstable += usize::from(!stable);
    }
    assert_eq!(unstable, p.unstable_points());
    assert!(unstable > 50, "{unstable} unstable points");
}

#[test]
fn load_control_stops_at_the_limit_point_with_an_error() {
    // Load control from the same start cannot pass M_max: it must fail there, not snap to the
    // other branch and report it as the path.
    let (m_max, _) = exact_limit();
    let (full, loads) = setup(40);
    let start = solve_static(&full, &loads, &[1.0, M_START], &StaticOptions::default()).unwrap();
    let err = continue_static(
        &full,
        &loads,
        (&start.x, &start.scales),
        &[1.0, M_END],
        &StaticOptions::default(),
    )
    .unwrap_err();
    let reached = M_START + err.load_factor().expect("a static error") * (M_END - M_START);
    // It stops at the model's limit point (3.2e-3 N·m below the continuum's at n = 40) to within
    // the smallest load step: measured 20.1848 N·m; bound 0.01 N·m.
    assert!(
        (reached - m_max).abs() < 0.01,
        "stopped at M = {reached}: {err}"
    );
    assert!(matches!(
        err,
        SolveError::StaticDiverged { .. } | SolveError::StaticUnstable { .. }
    ));
}

#[test]
fn reduced_models_follow_the_same_path() {
    // Consistency with the full model: reduced models on their first r modes pass the same two
    // limit points, their limit moments above the full model's (a reduced basis stiffens) by a
    // truncation error that falls with r: measured 0.72 %, 0.29 %, 0.12 % at r = 3, 6, 10
    // (n = 40); bounds 1 %, 0.4 %, 0.15 %.
    let n = 40;
    let (full, loads) = setup(n);
    let modes = flexwing::solve::Modes::undeformed(&full).unwrap();
    let limits =
        |p: &StaticPath| -> Vec<f64> { p.limit_points().iter().map(|&i| vertex(p, i)).collect() };
    let (_, reference) = path(n, &fine());
    let full_limits = limits(&reference);
    for (r, bound) in [(3, 1e-2), (6, 4e-3), (10, 1.5e-3)] {
        let rom = flexwing::model::ReducedModel::first(&full, modes.shapes(), r).unwrap();
        let start = solve_static(&rom, &loads, &[1.0, M_START], &StaticOptions::default()).unwrap();
        let p = arc_length_static(
            &rom,
            &loads,
            (&start.x, &start.scales),
            &[1.0, M_END],
            &fine(),
        )
        .unwrap();
        let a = limits(&p);
        assert_eq!(a.len(), 2, "r = {r}");
        for (x, y) in a.iter().zip(&full_limits) {
            let e = (x - y) / y;
            assert!(e > 0.0 && e < bound, "r = {r}: reduced {x}, full {y}");
        }
        assert_eq!(p.points.last().unwrap().solution.stable, Some(true));
    }
}

#[test]
fn bad_options_name_the_field() {
    let (full, loads) = setup(10);
    let rest = vec![0.0; 10];
    let opts = ArcLengthOptions {
        max_arc: -1.0,
        ..ArcLengthOptions::default()
    };
    let err =
        arc_length_static(&full, &loads, (&rest, &[0.0, 0.0]), &[1.0, 0.0], &opts).unwrap_err();
    assert!(err.path.points.is_empty());
    assert!(
        err.to_string().starts_with("arc_length.max_arc: must be"),
        "{err}"
    );
}

#[test]
fn a_path_that_stops_keeps_its_points() {
    let (full, loads) = setup(20);
    let start = solve_static(&full, &loads, &[1.0, M_START], &StaticOptions::default()).unwrap();
    let from = (start.x.as_slice(), start.scales.as_slice());
    // Out of points: the ten points found, and where the path stood.
    let opts = ArcLengthOptions {
        max_points: 10,
        ..ArcLengthOptions::default()
    };
    let err = arc_length_static(&full, &loads, from, &[1.0, M_END], &opts).unwrap_err();
    assert_eq!(err.path.points.len(), 10);
    let last = err.path.points.last().unwrap().load_factor;
    assert!(matches!(
        err.error,
        SolveError::ArcLengthTooManyPoints { load_factor, points: 10 } if load_factor == last
    ));
    // Steps that must be long (min_arc = 3 rad) but may rotate an element by 0.1 rad at most:
    // the corrector is refused until the arc falls below min_arc; the start is kept.
    let opts = ArcLengthOptions {
        min_arc: 3.0,
        max_arc: 3.0,
        max_rotation_step: 0.1,
        ..ArcLengthOptions::default()
    };
    let err = arc_length_static(&full, &loads, from, &[1.0, M_END], &opts).unwrap_err();
    assert_eq!(err.path.points.len(), 1);
    assert!(
        matches!(err.error, SolveError::ArcLengthStalled { points: 1, .. }),
        "{}",
        err.error
    );
}
