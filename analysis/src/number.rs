//! The one way numbers are written in words: evidence of a verdict and the report's tables.

/// A number in scientific notation with three significant digits (`1.23e-4`); `0.00e0` for
/// zero; `NaN`, `inf` and `-inf` as Rust writes them.
pub fn sci(v: f64) -> String {
    if v == 0.0 {
        "0.00e0".to_string()
    } else if v.is_finite() {
        format!("{v:.2e}")
    } else {
        v.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::sci;

    #[test]
    fn three_significant_digits_and_the_special_values() {
        assert_eq!(sci(0.0), "0.00e0");
        assert_eq!(sci(-0.000123456), "-1.23e-4");
        assert_eq!(sci(12345.0), "1.23e4");
        assert_eq!(sci(f64::NAN), "NaN");
        assert_eq!(sci(f64::NEG_INFINITY), "-inf");
    }
}
