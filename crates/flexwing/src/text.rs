//! Numbers in messages: the shortest readable form, so that an error or a stop reason reads
//! `got 1e-300` rather than three hundred zeros (`f64`'s `Display` never uses an exponent).

/// `v` with `digits` significant digits, without exponent for ordinary magnitudes.
///
/// ```
/// assert_eq!(flexwing::text::significant(55.596, 4), "55.60");
/// assert_eq!(flexwing::text::significant(1.5e-7, 3), "1.50e-7");
/// ```
pub fn significant(v: f64, digits: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs().log10().floor() as i32;
    if !(-4..=6).contains(&magnitude) {
        return format!("{:.*e}", digits.saturating_sub(1), v);
    }
    let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
    format!("{v:.decimals$}")
}

/// `v` with up to 6 significant digits and no trailing zeros: `150`, `0.0666667`, `1.5e-7`; the
/// sign of a zero is dropped.
///
/// ```
/// assert_eq!(flexwing::text::short(1.0 / 15.0), "0.0666667");
/// assert_eq!(flexwing::text::short(1e-300), "1e-300");
/// ```
pub fn short(v: f64) -> String {
    let s = significant(v + 0.0, 6);
    let (mantissa, exponent) = s.split_at(s.find('e').unwrap_or(s.len()));
    if !mantissa.contains('.') {
        return s;
    }
    format!(
        "{}{exponent}",
        mantissa.trim_end_matches('0').trim_end_matches('.')
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.35221, 4), "0.3522");
        assert_eq!(significant(55.596, 4), "55.60");
        assert_eq!(significant(12345.6, 4), "12346");
        assert_eq!(significant(1.5e-7, 3), "1.50e-7");
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short(150.0), "150");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(-0.0), "0");
        assert_eq!(short(1.0 / 15.0), "0.0666667");
        assert_eq!(short(2.5), "2.5");
        assert_eq!(short(1.5e-7), "1.5e-7");
        assert_eq!(short(2e7), "2e7");
    }
}
