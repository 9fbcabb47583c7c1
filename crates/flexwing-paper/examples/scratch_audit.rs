use flexwing::analysis::{dynamics, NoProgress};
use flexwing_case::Case;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let file = &args[1];
    let (mut runaway, mut tol, mut print) = (None, None, false);
    let mut case = Case::load(std::path::Path::new(file)).unwrap();
    let d = case.dynamic.as_mut().unwrap();
    for kv in &args[2..] {
        let (k, v) = kv.split_once('=').unwrap();
        match k {
            "rtol" => d.rtol = Some(v.parse().unwrap()),
            "atol" => d.atol = Some(v.parse().unwrap()),
            "max_step" => d.max_step = Some(v.parse().unwrap()),
            "end" => d.end_time = v.parse().unwrap(),
            "n" => case.beam.elements = Some(v.parse().unwrap()),
            "reduced" => d.reduced = v.split(',').map(|x| x.parse().unwrap()).collect(),
            "simplified" => d.simplified = v == "true",
            "full" => d.full = v == "true",
            "integrator" => d.integrator = flexwing_case::IntegratorSpec(Some(match v { "radau" => flexwing::solve::integrate::Method::Radau, "bdf" => flexwing::solve::integrate::Method::Bdf, "dopri5" => flexwing::solve::integrate::Method::Dopri5, "midpoint" => flexwing::solve::integrate::Method::Midpoint, _ => flexwing::solve::integrate::Method::GeneralizedAlpha })),
            "step" => d.step = Some(v.parse().unwrap()),
            "runaway" => runaway = Some(v.parse::<f64>().unwrap()),
            "tol" => tol = Some(v.parse::<f64>().unwrap()),
            "print" => print = true,
            _ => panic!("{k}"),
        }
    }
    let mut plan = case.dynamic_plan().unwrap();
    if let Some(r) = runaway { plan.audit.runaway = r; }
    plan.audit.tolerance = tol;
    let out = dynamics::run(&plan, &mut NoProgress).unwrap();
    for r in &out.runs {
        if print { for s in &r.samples { println!("{} {:.6e} {:.4e} {:.4e}", r.kind.label(), s.t, s.kinetic + s.strain, s.balance_error); } }
        let e = r.energy.unwrap();
        let last = r.samples.last().unwrap();
        let max_sample = r.samples.iter().map(|s| s.balance_error.abs()).fold(0.0, f64::max);
        let worst = r.samples.iter().max_by(|a, b| a.balance_error.abs().total_cmp(&b.balance_error.abs())).unwrap();
        println!(
            "{:>12} steps {:>6} wall {:>8.3} ms  H0 {:.4e} E {:.4e} floor {:.1e}  max_err {:.3e} at {:.4}  gain {:.3e}  exceeded {:?} runaway {:?}  samples max {:.3e} at t={:.3}  t_end {:.3} H_end {:.4e} W {:.3e} status {:?} tip ({:.6},{:.6})",
            r.kind.label(), r.stats.steps, 1e3 * r.wall_time_s, e.initial, e.reference, e.limits.floor, e.max_error, e.max_error_time, e.max_gain,
            e.exceeded_at, e.runaway_at, max_sample, worst.t, last.t, last.kinetic + last.strain, last.work, r.status.word(), last.tip_x, last.tip_y
        );
    }
}
