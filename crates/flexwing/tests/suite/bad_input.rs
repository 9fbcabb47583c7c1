//! Bad input gives an `InputError` naming the field, never a panic.

use crate::common::*;
use flexwing::beam::{Beam, Calibration, Discretization, InertiaAxis, Profile, TorsionProperties};
use flexwing::model::{Force, FullModel, Load};

fn stations_of(x: &[f64]) -> Discretization {
    Discretization::Stations(x.to_vec())
}

fn field_of(r: Result<Beam, flexwing::InputError>) -> String {
    r.expect_err("must be rejected").field
}

#[test]
fn beam_errors_name_the_field() {
    let good = table1_section();
    let d = Discretization::Uniform(4);
    let cal = Calibration::TipLoad;
    assert_eq!(
        field_of(Beam::new(16.0, &good, &Discretization::Uniform(0), cal)),
        "beam.elements"
    );
    assert_eq!(field_of(Beam::new(-1.0, &good, &d, cal)), "beam.length");
    assert_eq!(
        field_of(Beam::new(
            16.0,
            &good,
            &Discretization::Uniform(1_000_000),
            cal
        )),
        "beam.elements"
    );
    assert_eq!(field_of(Beam::new(f64::NAN, &good, &d, cal)), "beam.length");
    // Under the caller's own name for the beam.
    assert_eq!(
        field_of(Beam::named("wing", -1.0, &good, &d, cal)),
        "wing.length"
    );
    let mut negative = good.clone();
    negative.ei = Profile::Uniform(-1.0);
    assert_eq!(
        field_of(Beam::named("wing", 16.0, &negative, &d, cal)),
        "wing.section.EI"
    );
    assert_eq!(
        field_of(Beam::named("", 16.0, &good, &stations_of(&[0.0, 8.0]), cal)),
        "stations"
    );
    let stations = |x: Vec<f64>| Discretization::Stations(x);
    assert_eq!(
        field_of(Beam::new(
            16.0,
            &good,
            &stations(vec![0.0, 9.0, 8.0, 16.0]),
            cal
        )),
        "beam.stations"
    );
    assert_eq!(
        field_of(Beam::new(16.0, &good, &stations(vec![0.0, 8.0, 15.0]), cal)),
        "beam.stations"
    );
    assert_eq!(
        field_of(Beam::new(16.0, &good, &stations(vec![1.0, 8.0, 16.0]), cal)),
        "beam.stations"
    );

    let mut s = good.clone();
    s.ei = Profile::Uniform(-2e4);
    assert_eq!(field_of(Beam::new(16.0, &s, &d, cal)), "beam.section.EI");
    s.ei = Profile::Uniform(0.0);
    assert_eq!(field_of(Beam::new(16.0, &s, &d, cal)), "beam.section.EI");
    s = good.clone();
    s.mass_per_length = Profile::Uniform(f64::NAN);
    assert_eq!(
        field_of(Beam::new(16.0, &s, &d, cal)),
        "beam.section.mass_per_length"
    );
    s = good.clone();
    s.mass_per_length = linear(8.0, 1.0, 1.0); // covers only half the span
    let e = Beam::new(16.0, &s, &d, cal).unwrap_err();
    assert_eq!(e.field, "beam.section.mass_per_length");
    assert!(e.reason.contains("covers"), "{e}");
    let t = |f: &dyn Fn(&mut TorsionProperties)| {
        let mut s = good.clone();
        f(s.torsion.as_mut().unwrap());
        field_of(Beam::new(16.0, &s, &d, cal))
    };
    assert_eq!(t(&|t| t.gj = Profile::Uniform(-1.0)), "beam.section.GJ");
    assert_eq!(
        t(&|t| t.polar_inertia = Profile::Uniform(-0.1)),
        "beam.section.polar_inertia"
    );
    assert_eq!(
        t(&|t| t.offset = Profile::Uniform(f64::INFINITY)),
        "beam.section.d0"
    );
    // About the elastic axis, I_ea = 0.05 < m d0² = 0.0535: negative inertia about the mass centre.
    assert_eq!(
        t(&|t| {
            t.inertia_axis = InertiaAxis::ElasticAxis;
            t.polar_inertia = Profile::Uniform(0.05);
        }),
        "beam.section.polar_inertia"
    );
    // No torsional inertia at all.
    assert_eq!(
        t(&|t| {
            t.polar_inertia = Profile::Uniform(0.0);
            t.offset = Profile::Uniform(0.0);
        }),
        "beam.section.polar_inertia"
    );
}

#[test]
fn load_errors_name_the_load() {
    let m = FullModel::new(
        Beam::new(
            1.0,
            &bending_only(Profile::Uniform(1.0), Profile::Uniform(1.0)),
            &Discretization::Uniform(4),
            Calibration::TipLoad,
        )
        .unwrap(),
    );
    let dead = |span: f64, fy: f64| Load::PointForce {
        span,
        force: Force::Dead { fx: 0.0, fy },
    };
    assert_eq!(
        m.apply(&[dead(1.0, 1.0), dead(1.5, 1.0)], "loads")
            .unwrap_err()
            .field,
        "loads[1].span"
    );
    assert_eq!(
        m.apply(&[dead(-0.1, 1.0)], "loads").unwrap_err().field,
        "loads[0].span"
    );
    assert_eq!(
        m.apply(&[dead(0.5, f64::NAN)], "loads").unwrap_err().field,
        "loads[0].fy"
    );
    assert_eq!(
        m.apply(
            &[Load::Torque {
                span: 1.0,
                value: 1.0
            }],
            "loads"
        )
        .unwrap_err()
        .field,
        // The load itself cannot act on this beam (it was `loads[0].torque`, a name no caller
        // uses; the value of a moment or torque is `value`, as in `Load::Torque { value }`).
        "loads[0]"
    );
    assert_eq!(
        m.apply(
            &[Load::Moment {
                span: 1.0,
                value: f64::NAN
            }],
            "loads"
        )
        .unwrap_err()
        .field,
        "loads[0].value"
    );
    assert!(m
        .apply(
            &[
                dead(1.0, 1.0),
                Load::Moment {
                    span: 0.3,
                    value: 2.0
                }
            ],
            "loads"
        )
        .is_ok());
}
