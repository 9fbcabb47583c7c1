use super::response::{run, AeroDynamicPlan};
use super::tests::patil;
use crate::analysis::dynamics::DynamicPlan;
use crate::analysis::NoProgress;
use crate::beam::Profile;
use crate::model::aero::{Aerodynamics, FlightCondition};
use crate::solve::aeroelastic::{FlightHistory, Gust, GustShape};
use crate::solve::integrate::Method;
use crate::solve::{Damping, TimeFunction};

fn gust_flight() -> FlightHistory {
    FlightHistory {
        initial: FlightCondition {
            speed: 25.0,
            root_angle: 0.0349,
            gravity: Some(9.80665),
        },
        speed_change: Some((3.0, TimeFunction::Ramp { start: 0.2, end: 0.8 })),
        root_angle_change: Some((0.02, TimeFunction::Ramp { start: 0.1, end: 0.5 })),
        gust: Some(Gust {
            shape: GustShape::OneMinusCosine { length: 10.0 },
            amplitude: 1.0,
            start: 0.1,
            spanwise: Profile::Uniform(1.0),
        }),
    }
}

fn plan(n: usize, aerodynamics: Aerodynamics, method: Method, rtol: f64) -> AeroDynamicPlan {
    let (model, aero) = patil(n, aerodynamics);
    let times: Vec<f64> = (0..=20).map(|k| 0.05 * k as f64).collect();
    let mut s = DynamicPlan::new(model, vec![], 1.0, times);
    s.integrator = method;
    s.settings.rtol = rtol;
    s.settings.atol = rtol;
    s.damping = Damping::Rayleigh { alpha: 0.05, beta: 1e-4 };
    AeroDynamicPlan::new(s, aero, gust_flight())
}

#[test]
fn explore() {
    for method in [Method::Radau, Method::Bdf, Method::Dopri5] {
        for rtol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
            let p = plan(8, Aerodynamics::Peters { states: 6 }, method, rtol);
            let out = run(&p, &mut NoProgress).unwrap();
            let r = &out.runs[0];
            let e = r.energy.as_ref().unwrap();
            let last = r.samples.last().unwrap();
            eprintln!("{method:?} rtol {rtol:e}: steps {} err {:.3e} at {} ref {:.3e} W {:.3e} D {:.3e} {:?} wall {:.3}",
                r.stats.steps, e.max_error, e.max_error_time, e.reference, last.work, last.dissipated, r.status, r.wall_time_s);
        }
    }
    for method in [Method::Midpoint, Method::GeneralizedAlpha] {
        for h in [4e-3, 2e-3, 1e-3, 5e-4] {
            let mut p = plan(8, Aerodynamics::Peters { states: 6 }, method, 1e-8);
            p.structure.settings.step = Some(h);
            let out = run(&p, &mut NoProgress).unwrap();
            let r = &out.runs[0];
            let e = r.energy.as_ref().unwrap();
            eprintln!("{method:?} h {h:e}: steps {} err {:.3e} at {} {:?}",
                r.stats.steps, e.max_error, e.max_error_time, r.status);
        }
    }
}
