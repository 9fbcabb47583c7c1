//! Section properties that vary along the span, and exact integration over them.
//!
//! A tabulated property is piecewise linear, so every integral the beam needs is an integral of a
//! polynomial (or of a polynomial over a linear function) on the pieces between consecutive
//! stations. [`for_each_piece`] walks the pieces of a set of intervals and a set of profiles in
//! one left-to-right sweep, O(intervals + stations), with the profiles' values at the ends of
//! each piece; the integrals on a piece are then closed forms (here and in `calibration.rs`).

use crate::error::InputError;

/// A section property as a function of the span coordinate `x` (m): uniform, or piecewise linear
/// through a table of points.
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    /// The same value everywhere.
    Uniform(f64),
    /// Piecewise-linear interpolation of `value` over the strictly increasing stations `x` (m).
    /// The table must cover the whole span `[0, L]`.
    Table {
        /// Stations along the span (m), strictly increasing.
        x: Vec<f64>,
        /// Values at the stations, in the unit of the property.
        value: Vec<f64>,
    },
}

/// What a property is allowed to be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sign {
    /// Strictly positive (stiffness, mass).
    Positive,
    /// Zero or positive (inertia).
    NonNegative,
    /// Any finite value (offset).
    Any,
}

impl Profile {
    /// Check the profile over the span `[0, length]`; `field` names it in the error.
    pub(crate) fn validate(&self, field: &str, length: f64, sign: Sign) -> Result<(), InputError> {
        let check = |v: f64, what: &str| -> Result<(), InputError> {
            let ok = v.is_finite()
                && match sign {
                    Sign::Positive => v > 0.0,
                    Sign::NonNegative => v >= 0.0,
                    Sign::Any => true,
                };
            if ok {
                crate::magnitude::check(field, what, v).map(|_| ())
            } else {
                let need = match sign {
                    Sign::Positive => "a finite positive number",
                    Sign::NonNegative => "a finite non-negative number",
                    Sign::Any => "a finite number",
                };
                Err(InputError::new(
                    field,
                    format!("{what} must be {need}, got {}", crate::text::short(v)),
                ))
            }
        };
        match self {
            Profile::Uniform(v) => check(*v, "value"),
            Profile::Table { x, value } => {
                if x.len() != value.len() {
                    return Err(InputError::new(
                        field,
                        format!("table has {} stations but {} values", x.len(), value.len()),
                    ));
                }
                if x.len() < 2 {
                    return Err(InputError::new(field, "table needs at least two points"));
                }
                for (k, &xk) in x.iter().enumerate() {
                    if !xk.is_finite() {
                        return Err(InputError::new(field, format!("station x[{k}] is {xk}")));
                    }
                    crate::magnitude::check(field, &format!("station x[{k}]"), xk)?;
                    if k > 0 && xk <= x[k - 1] {
                        return Err(InputError::new(
                            field,
                            format!(
                                "stations must be strictly increasing, but x[{k}] = {} <= x[{}] = {}",
                                crate::text::short(xk),
                                k - 1,
                                crate::text::short(x[k - 1])
                            ),
                        ));
                    }
                }
                for (k, &v) in value.iter().enumerate() {
                    check(v, &format!("value[{k}]"))?;
                }
                let tol = 1e-9 * length;
                if x[0] > tol || x[x.len() - 1] < length - tol {
                    return Err(InputError::new(
                        field,
                        format!(
                            "table covers [{}, {}] m but the span is [0, {}] m",
                            crate::text::short(x[0]),
                            crate::text::short(x[x.len() - 1]),
                            crate::text::short(length)
                        ),
                    ));
                }
                Ok(())
            }
        }
    }

    /// Value at span position `x` (clamped to the table's range).
    pub fn at(&self, x: f64) -> f64 {
        match self {
            Profile::Uniform(v) => *v,
            Profile::Table { x: xs, value } => {
                let last = xs.len() - 1;
                if x <= xs[0] {
                    return value[0];
                }
                if x >= xs[last] {
                    return value[last];
                }
                // First station strictly greater than x.
                let k = xs.partition_point(|&s| s <= x);
                let t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
                value[k - 1] + t * (value[k] - value[k - 1])
            }
        }
    }

    /// Whether the profile is uniform.
    pub fn is_uniform(&self) -> bool {
        matches!(self, Profile::Uniform(_))
    }

    /// A cursor for a left-to-right sweep over the profile.
    fn cursor(&self) -> Cursor<'_> {
        match self {
            Profile::Uniform(v) => Cursor {
                x: &[],
                value: std::slice::from_ref(v),
                k: 0,
            },
            Profile::Table { x, value } => Cursor { x, value, k: 0 },
        }
    }

    /// Stations where the profile has a kink, strictly inside `(a, b)`.
    fn kinks_in(&self, a: f64, b: f64) -> impl Iterator<Item = f64> + '_ {
        let xs: &[f64] = match self {
            Profile::Uniform(_) => &[],
            Profile::Table { x, .. } => x,
        };
        xs.iter().copied().filter(move |&s| s > a && s < b)
    }
}

/// A position in a profile during a left-to-right sweep: `k` is the index of the first station
/// strictly after the current position (`x.len()` past the last; `x` empty for a uniform profile).
struct Cursor<'a> {
    x: &'a [f64],
    value: &'a [f64],
    k: usize,
}

impl Cursor<'_> {
    /// Move to `a` (never backwards) and return the first station strictly after it (∞ if none).
    fn seek(&mut self, a: f64) -> f64 {
        while self.k < self.x.len() && self.x[self.k] <= a {
            self.k += 1;
        }
        self.x.get(self.k).copied().unwrap_or(f64::INFINITY)
    }

    /// Value at `x`, which must lie between the station before the current position and the
    /// next one. The same arithmetic as [`Profile::at`], so the same value to the last bit.
    fn at(&self, x: f64) -> f64 {
        let (xs, vs, k) = (self.x, self.value, self.k);
        let last = vs.len() - 1;
        if xs.is_empty() || x <= xs[0] {
            vs[0]
        } else if k > last || x >= xs[last] {
            vs[last]
        } else if x == xs[k] {
            vs[k]
        } else {
            let t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
            vs[k - 1] + t * (vs[k] - vs[k - 1])
        }
    }
}

/// One piece `[a, b]` of an interval on which every profile of the sweep is linear, with the
/// profiles' values at both ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece<const N: usize> {
    /// Start of the piece.
    pub(crate) a: f64,
    /// End of the piece.
    pub(crate) b: f64,
    /// Values of the profiles at `a`.
    pub(crate) at_a: [f64; N],
    /// Values of the profiles at `b`.
    pub(crate) at_b: [f64; N],
}

impl<const N: usize> Piece<N> {
    /// `∫_a^b f dx` for `f` a polynomial of degree ≤ 3 in `x` given through the values of the
    /// profiles (Simpson's rule, exact to that degree; the midpoint values of linear profiles
    /// are the means of the end values).
    pub(crate) fn simpson(&self, f: impl Fn(&[f64; N]) -> f64) -> f64 {
        let mid: [f64; N] = std::array::from_fn(|k| 0.5 * (self.at_a[k] + self.at_b[k]));
        (self.b - self.a) / 6.0 * (f(&self.at_a) + 4.0 * f(&mid) + f(&self.at_b))
    }
}

/// Call `f(i, piece)` for every piece of every interval `[bounds[i], bounds[i + 1]]`, in order,
/// the intervals being split at every station of `profiles` inside them. One sweep: O(intervals +
/// stations), no search. `bounds` must be strictly increasing.
pub(crate) fn for_each_piece<const N: usize>(
    bounds: &[f64],
    profiles: [&Profile; N],
    mut f: impl FnMut(usize, Piece<N>),
) {
    let mut cursors = profiles.map(Profile::cursor);
    for (i, w) in bounds.windows(2).enumerate() {
        let (mut a, end) = (w[0], w[1]);
        loop {
            let mut b = end;
            for c in cursors.iter_mut() {
                b = b.min(c.seek(a));
            }
            let piece = Piece {
                a,
                b,
                at_a: std::array::from_fn(|k| cursors[k].at(a)),
                at_b: std::array::from_fn(|k| cursors[k].at(b)),
            };
            f(i, piece);
            if b >= end {
                break;
            }
            a = b;
        }
    }
}

/// `∫_a^b f(x) dx` for an integrand built from piecewise-linear profiles: the interval is split at
/// every kink of `profiles` and each smooth piece is integrated by adaptive Gauss–Legendre
/// quadrature to about 1e-14 relative.
pub(crate) fn integrate(profiles: &[&Profile], a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    if b <= a {
        return 0.0;
    }
    let mut cuts: Vec<f64> = vec![a, b];
    for p in profiles {
        cuts.extend(p.kinks_in(a, b));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts.windows(2)
        .map(|w| adaptive_gauss(&f, w[0], w[1], 0))
        .sum()
}

/// 8-point Gauss–Legendre nodes and weights on `[-1, 1]`.
const GL_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GL_W: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

fn gauss8(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut s = 0.0;
    for k in 0..4 {
        s += GL_W[k] * (f(c - h * GL_X[k]) + f(c + h * GL_X[k]));
    }
    s * h
}

fn adaptive_gauss(f: &impl Fn(f64) -> f64, a: f64, b: f64, depth: u32) -> f64 {
    let whole = gauss8(f, a, b);
    let m = 0.5 * (a + b);
    let halves = gauss8(f, a, m) + gauss8(f, m, b);
    if depth >= 40 || (whole - halves).abs() <= 1e-14 * halves.abs().max(f64::MIN_POSITIVE) {
        halves
    } else {
        adaptive_gauss(f, a, m, depth + 1) + adaptive_gauss(f, m, b, depth + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_interpolates_linearly() {
        let p = Profile::Table {
            x: vec![0.0, 1.0, 3.0],
            value: vec![1.0, 3.0, 2.0],
        };
        assert!((p.at(0.5) - 2.0).abs() < 1e-15);
        assert!((p.at(2.0) - 2.5).abs() < 1e-15);
        assert!((p.at(3.0) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn quadrature_is_exact_for_rational_integrand() {
        // ∫_0^1 dx / (1 + x) = ln 2, with a kink-free profile.
        let p = Profile::Uniform(1.0);
        let v = integrate(&[&p], 0.0, 1.0, |x| 1.0 / (1.0 + x));
        assert!((v - 2f64.ln()).abs() < 1e-14);
    }

    #[test]
    fn table_must_cover_the_span() {
        let p = Profile::Table {
            x: vec![0.0, 0.5],
            value: vec![1.0, 1.0],
        };
        let e = p.validate("EI", 1.0, Sign::Positive).unwrap_err();
        assert!(e.to_string().contains("covers"), "{e}");
    }

    #[test]
    fn rejects_nan_and_negative() {
        for v in [f64::NAN, -1.0, 0.0] {
            assert!(Profile::Uniform(v)
                .validate("EI", 1.0, Sign::Positive)
                .is_err());
        }
        assert!(Profile::Uniform(0.0)
            .validate("I", 1.0, Sign::NonNegative)
            .is_ok());
    }
}
