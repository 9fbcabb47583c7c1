//! The range of magnitudes an input value may have (issue 9: "never a silent wrong answer").
//!
//! A value far outside any physical range (`length = 1e300`, `d0 = 1e160`) overflows the
//! products the model forms (the mass matrix holds `m L³`, the torsional inertia `m d0²`, the
//! modal problem the ratio of stiffness to inertia) and used to surface as a misleading downstream
//! error (a modal failure) or a hang. Two rules, both derived in docs/model-choices.md
//! ("Magnitudes accepted"), reject such input with an error naming the field:
//!
//! 1. Every dimensional input value is zero (where zero is allowed) or between [`SMALLEST`] and
//!    [`LARGEST`] in magnitude, in whatever consistent units the user works in. Sixty decades
//!    hold any physical quantity in SI or nondimensional units (a 1e-6 m MEMS beam has
//!    `EI ≈ 1e-14`, `m ≈ 1e-9`, a polar inertia per length `≈ 1e-21`), and the products the model
//!    forms from them (`m L³`, `m d0² ℓ`, `F L`, `q̇ᵀ M q̇`) stay finite doubles.
//! 2. The beam's element frequencies squared, `K/(inertia)` of each joint spring against its own
//!    element ([`Beam`](crate::beam::Beam) checks them), lie within [`FREQUENCY_SQUARED`]: the
//!    stiffness and mass matrices are then within 120 decades of each other, so the modal and
//!    time-stepping problems (which form `K − ω² M`, `M + h² K`, and their squares in norms)
//!    cannot overflow, for any stiffness ratio along the span a structure can have.

use crate::error::InputError;

/// Largest magnitude of a dimensional input value.
pub const LARGEST: f64 = 1e30;

/// Smallest non-zero magnitude of a dimensional input value.
pub const SMALLEST: f64 = 1e-30;

/// Accepted range of an element's frequency squared `K/J` (in the user's time unit, s⁻² in SI):
/// periods from 1e-30 to 1e30 time units.
pub const FREQUENCY_SQUARED: (f64, f64) = (1e-60, 1e60);

/// The words that end a magnitude error: the range, and where the rule is written.
pub(crate) fn range_words() -> String {
    format!(
        "must have a magnitude between {SMALLEST:e} and {LARGEST:e}, or be 0 where 0 is \
         allowed (the range accepted in any consistent units, docs/model-choices.md)"
    )
}

/// Check that `v` (finite) is zero or within [`SMALLEST`, `LARGEST`] in magnitude. `what` is
/// the part of the field the value is (e.g. `value[3]`), or empty.
pub(crate) fn check(field: &str, what: &str, v: f64) -> Result<f64, InputError> {
    let a = v.abs();
    if a == 0.0 || (SMALLEST..=LARGEST).contains(&a) {
        return Ok(v);
    }
    let what = if what.is_empty() {
        String::new()
    } else {
        format!("{what} ")
    };
    Err(InputError::new(
        field,
        format!("{what}{}, got {}", range_words(), crate::text::short(v)),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bounds_are_inclusive_and_zero_is_accepted() {
        for v in [0.0, -0.0, 1e30, -1e30, 1e-30, -1e-30, 1.0, -3.5e12] {
            assert_eq!(check("f", "", v), Ok(v));
        }
        for v in [1.1e30, -1e31, 9e-31, -1e-300, 1e300] {
            let e = check("beam.length", "", v).unwrap_err();
            assert_eq!(e.field, "beam.length");
            assert!(e.reason.contains("between 1e-30 and 1e30"), "{e}");
        }
        let e = check("beam.section.EI", "value[2]", 1e300).unwrap_err();
        assert!(
            e.reason.starts_with("value[2] must have a magnitude"),
            "{e}"
        );
        assert!(e.reason.ends_with("got 1e300"), "{e}");
    }
}
