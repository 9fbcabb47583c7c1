//! Benchmark of the reduced models against the full one at the setting of `flexwing
//! reproduce`'s Table 8: case (b) (tip force 10 sin(20 t) N, 1 s, output every 5 ms, Table 4
//! beam), Radau IIA rtol 1e-2, steps at most 6 ms, the energy audit on (the library's audited
//! integration, as every dynamic analysis), exact γ. The coordinate atol is `0.2/n` rad per joint
//! (Table 8's 1e-2 at n = 20, scaled by the joint's share of the span so that the tolerance on the
//! tip angle stays the same as n grows). For n = 20, 80 and 320 and r = 1, 2, 3, 4, 6: steps,
//! right-hand sides, Jacobians, LU factorizations, the CPU time of the thread (`common::cpu_time`,
//! the fastest of several batches: the machine is shared) and its ratio to the full model's
//! (beside the ratio measured before issue 22's change, `RATIO_BEFORE`), the slope of the time against n, and the breakdown of a reduced run into its right-hand sides,
//! Jacobians and the rest (the integrator's linear algebra), from the cost of one evaluation of
//! each times the counters.
//!
//! Run: `cargo bench -p flexwing --bench reduced` (add `-- --quick` for fewer batches, `--
//! --profile N R [RUNS]` to loop the reduced run of n elements and r modes for a profiler, for 10
//! s or RUNS times).

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{cpu_per_call, fmt_time};

use flexwing::analysis::dynamics::{integrate_audited, AuditSettings};
use flexwing::model::{AppliedLoads, FullModel, PlanarModel, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{IntegratorSettings, IntegratorStats, Method, OdeSystem};
use flexwing::solve::{
    chain_newton_min_dofs, Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction,
};
use nalgebra::DMatrix;

/// The modes of Table 8 (and r = 6, the largest of the goal).
const MODES: [usize; 5] = [1, 2, 3, 4, 6];

/// The reduced/full ratios of this bench's `--quick` run of `31a2e37` (before the reduced model's
/// one-reduction trigonometry, issue 22), at n = 20, 80, 320 and r as [`MODES`]: load average
/// 2.4, the run right before that of the change (docs/performance.md, "Reduced models at the
/// paper's size"). Printed beside the ratios measured, as the issue asks.
const RATIO_BEFORE: [(usize, [f64; 5]); 3] = [
    (20, [0.229, 0.286, 0.375, 0.442, 0.554]),
    (80, [0.138, 0.168, 0.217, 0.354, 0.491]),
    (320, [0.142, 0.183, 0.218, 0.270, 0.368]),
];

/// The ratio of [`RATIO_BEFORE`] for `n` elements and `r` modes, if measured.
fn ratio_before(n: usize, r: usize) -> Option<f64> {
    let k = MODES.iter().position(|&m| m == r)?;
    RATIO_BEFORE
        .iter()
        .find(|(m, _)| *m == n)
        .map(|(_, v)| v[k])
}

/// Case (b) with `n` elements: the model, its loads applied, their time functions, the output
/// times.
fn sine_case(n: usize) -> (FullModel, AppliedLoads, Vec<TimeFunction>, Vec<f64>) {
    let case = flexwing::paper::sine_case(n).expect("case (b)");
    let loads = case.model.apply(&case.loads, "loads").expect("loads");
    let time = case.time.iter().flatten().cloned().collect();
    (case.model, loads, time, case.output_times)
}

/// Table 8's integrator at `n` elements (module documentation).
fn table8_settings(n: usize) -> IntegratorSettings {
    IntegratorSettings {
        rtol: 1e-2,
        atol: 0.2 / n as f64,
        max_step: Some(6e-3),
        ..Default::default()
    }
}

/// Case (b)'s loads applied, their time functions and the output times.
type Case<'a> = (&'a AppliedLoads, &'a [TimeFunction], &'a [f64]);

/// The equations of motion of `model` in case (b): exact γ, no damping.
fn equations<'a, M: StructuralModel>(
    model: &'a M,
    (loads, time, _): Case<'a>,
) -> EquationsOfMotion<'a, M> {
    EquationsOfMotion::new(
        model,
        loads,
        time.to_vec(),
        Gyroscopic::Exact,
        &Damping::None,
    )
    .expect("eom")
}

/// One audited run of `model` from rest: its counters.
fn run<M: StructuralModel>(
    model: &M,
    case @ (_, _, t_out): Case,
    settings: &IntegratorSettings,
) -> IntegratorStats {
    let mut eom = equations(model, case);
    let rest = vec![0.0; model.n_dofs()];
    let audit = AuditSettings::default();
    let run = integrate_audited(
        &mut eom,
        &rest,
        &rest,
        t_out,
        Method::Radau,
        settings,
        &audit,
        None,
        &mut |_| {},
    );
    assert!(run.stop().is_none(), "case (b) stopped: {:?}", run.stop());
    run.stats
}

/// The fastest of `batches` CPU times per run (each batch at least `budget` of CPU time).
fn best(batches: usize, budget: Duration, mut f: impl FnMut()) -> f64 {
    (0..batches)
        .map(|_| cpu_per_call(budget, &mut f))
        .fold(f64::INFINITY, f64::min)
}

/// CPU time of one right-hand side and, if `with_jacobian`, of one dense Jacobian of `model`'s
/// equations, at two bent, moving states in turn under the case's load.
fn evaluation_costs<M: PlanarModel>(
    model: &M,
    case: Case,
    with_jacobian: bool,
    batches: usize,
    budget: Duration,
) -> (f64, Option<f64>) {
    let mut eom = equations(model, case);
    let nd = model.n_dofs();
    let x: Vec<f64> = (0..nd).map(|i| 0.05 / (1.0 + i as f64)).collect();
    // Two states in turn, so that no evaluation finds its configuration cached.
    let y = [
        eom.state(&x, &vec![0.3; nd]),
        eom.state(
            &x.iter().map(|v| 0.9 * v).collect::<Vec<_>>(),
            &vec![0.2; nd],
        ),
    ];
    let mut dy = vec![0.0; y[0].len()];
    let mut jac = DMatrix::zeros(dy.len(), dy.len());
    // Reading the thread's CPU time costs microseconds: time batches of evaluations.
    const CALLS: usize = 100;
    let rhs = best(batches, budget / 4, || {
        for k in 0..CALLS {
            eom.rhs(0.3, black_box(&y[k % 2]), &mut dy);
        }
    });
    let jacobian = with_jacobian.then(|| {
        best(batches, budget / 4, || {
            for k in 0..CALLS {
                eom.jacobian(0.3, black_box(&y[k % 2]), &mut jac);
            }
        }) / CALLS as f64
    });
    (rhs / CALLS as f64, jacobian)
}

/// One row of the table: a run's counters, its time `t` and the full model's `t_full`, the
/// slope against the previous row of the same model (`n`, time), and the run's time split by
/// the costs of one right-hand side and one dense Jacobian (none: the chain's Newton solves).
struct Row {
    n: usize,
    label: String,
    stats: IntegratorStats,
    t: f64,
    t_full: f64,
    previous: Option<(usize, f64)>,
    costs: (f64, Option<f64>),
    /// The ratio to full of `31a2e37` ([`RATIO_BEFORE`]; none for the full model).
    before: Option<f64>,
}

impl Row {
    fn print(&self) {
        let Self { n, stats, t, .. } = *self;
        let rhs = self.costs.0 * stats.rhs_evaluations as f64 / t;
        let jac = self
            .costs
            .1
            .map(|j| j * stats.jacobian_evaluations as f64 / t);
        let percent = |v: Option<f64>| v.map_or("–".into(), |v| format!("{:.0} %", 100.0 * v));
        println!(
            "| {n} | {} | {} | {} | {} | {} | {} | {} | {:.3} | {} | {} | {} | {} | {} | {} | {} |",
            self.label,
            stats.steps,
            stats.rhs_evaluations,
            stats.jacobian_evaluations,
            stats.factorizations,
            fmt_time(t),
            fmt_time(t / stats.steps as f64),
            t / self.t_full,
            self.before.map_or("–".into(), |b| format!("{b:.3}")),
            slope(self.previous, n, t),
            fmt_time(self.costs.0),
            self.costs.1.map_or("–".into(), fmt_time),
            percent(Some(rhs)),
            percent(jac),
            percent(jac.map(|j| 1.0 - rhs - j)),
        );
    }
}

fn slope(prev: Option<(usize, f64)>, n: usize, t: f64) -> String {
    prev.map_or("–".into(), |(n0, t0)| {
        format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln())
    })
}

/// Loop the reduced run of `n` elements and `r` modes for a profiler: `runs` times, or for 10 s.
fn profile(n: usize, r: usize, runs: Option<usize>) {
    let (full, loads, time, t_out) = sine_case(n);
    let case = (&loads, time.as_slice(), t_out.as_slice());
    let modes = Modes::undeformed(&full).expect("modes");
    let rom = ReducedModel::first(&full, modes.shapes(), r).expect("rom");
    let settings = table8_settings(n);
    let t = std::time::Instant::now();
    let mut done = 0;
    while runs.map_or(t.elapsed() < Duration::from_secs(10), |k| done < k) {
        black_box(run(&rom, case, &settings));
        done += 1;
    }
    println!(
        "{done} runs of n = {n}, r = {r} in {:.2} s",
        t.elapsed().as_secs_f64()
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(k) = args.iter().position(|a| a == "--profile") {
        let n = args.get(k + 1).and_then(|s| s.parse().ok()).unwrap_or(20);
        let r = args.get(k + 2).and_then(|s| s.parse().ok()).unwrap_or(2);
        profile(n, r, args.get(k + 3).and_then(|s| s.parse().ok()));
        return;
    }
    let quick = args.iter().any(|a| a == "--quick");
    let (batches, budget) = if quick {
        (3, Duration::from_millis(100))
    } else {
        (7, Duration::from_millis(300))
    };
    println!(
        "Case (b), Table 8's setting (Radau rtol 1e-2, steps ≤ 6 ms, atol 0.2/n rad, audit on), \
         CPU time of the thread, fastest of {batches} batches of ≥ {} ms\n",
        budget.as_millis()
    );
    println!(
        "| n | model | steps | RHS | Jacobians | LU | CPU time | per step | ratio to full \
         | ratio at 31a2e37 | slope | one RHS | one Jacobian | RHS share | Jacobian share | rest |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut previous: Vec<Option<(usize, f64)>> = vec![None; MODES.len() + 1];
    for n in [20, 80, 320] {
        let (full, loads, time, t_out) = sine_case(n);
        let case = (&loads, time.as_slice(), t_out.as_slice());
        let settings = table8_settings(n);
        let modes = Modes::undeformed(&full).expect("modes");
        let stats = run(&full, case, &settings);
        let t_full = best(batches, budget, || {
            black_box(run(&full, case, &settings));
        });
        // From `chain_newton_min_dofs` coordinates on the full model's Newton systems are the
        // chain's O(n) sweeps, and its dense Jacobian is never formed.
        let dense = full.n_dofs() < chain_newton_min_dofs(Method::Radau, &settings);
        let costs = evaluation_costs(&full, case, dense, batches, budget);
        let row = |label, previous, stats, t, costs, before| Row {
            n,
            label,
            stats,
            t,
            t_full,
            previous,
            costs,
            before,
        };
        row("full".to_string(), previous[0], stats, t_full, costs, None).print();
        previous[0] = Some((n, t_full));
        for (k, &r) in MODES.iter().enumerate() {
            let rom = ReducedModel::first(&full, modes.shapes(), r).expect("rom");
            let stats = run(&rom, case, &settings);
            let t = best(batches, budget, || {
                black_box(run(&rom, case, &settings));
            });
            let costs = evaluation_costs(&rom, case, true, batches, budget);
            let label = format!("reduced r = {r}");
            let before = ratio_before(n, r);
            row(label, previous[k + 1], stats, t, costs, before).print();
            previous[k + 1] = Some((n, t));
        }
    }
}
