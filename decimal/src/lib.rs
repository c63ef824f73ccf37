//! The decimal text of an `f64` exactly as Rust's `Display` writes it (`format!("{v}")`), made
//! from Ryu's shortest digits ([`ryu`]) instead of the standard library's formatting machinery:
//! the traces of every run are written this way, about 7,600 numbers a run.
//!
//! # Why the text is the same
//!
//! Both Rust's `Display` (Grisu with a Dragon4 fallback) and Ryu write the shortest digit
//! string d_1 ... d_k that reads back as the same `f64`, and of those the one closest to the
//! number's exact binary value. They differ only where that value lies exactly halfway between
//! the two closest candidates, as a dyadic number with one digit more than the shortest does
//! (2^-25 = 2.98023223876953125e-8 needs 17 digits: 2.9802322387695312e-8 or ...313e-8): Ryu
//! rounds half to even, `Display` half up. [`push`] tells such a tie exactly (`ties_below`, in
//! integers) and takes the candidate above. The rest is layout: Ryu writes `1e-7`, `1.5e16` or
//! `123.0`, `Display` never an exponent and no `.0`. [`push`] reads the digits and the decimal
//! exponent back from Ryu's text and lays them out as `Display` does:
//!
//! - value = 0.d_1 ... d_k x 10^p (d_1 != 0, d_k != 0);
//! - p <= 0: `0.` then -p zeros then the digits (`0.0000001`);
//! - 0 < p < k: the first p digits, `.`, the rest (`1.5`);
//! - p >= k: the digits then p - k zeros (`100`, `150000000000000000`);
//! - zero: `0`, negative zero `-0`; a minus sign before any other negative number;
//! - NaN and the infinities by `Display` itself (`NaN`, `inf`, `-inf`).
//!
//! The tests compare [`push`] with `Display` on a million random bit patterns, on the
//! boundaries (subnormals, powers of ten and two, the largest and smallest numbers) and on
//! 726,000 dyadic numbers (+-k 2^-j and k 2^j, odd k < 4000, j <= 120), where the ties are.

/// Appends `v` to `out` as the bytes of `format!("{v}")` (ASCII).
pub fn push(out: &mut Vec<u8>, v: f64) {
    if !v.is_finite() {
        // NaN, inf, -inf: rare; Display's own words.
        out.extend_from_slice(v.to_string().as_bytes());
        return;
    }
    let mut buffer = ryu::Buffer::new();
    let text = buffer.format_finite(v).as_bytes();
    let (negative, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
        None => (text, 0),
    };
    // The mantissa's digits without its point, and where the point stood.
    let mut digits = [0u8; 24];
    let mut len = 0;
    let mut point = None;
    for &c in mantissa {
        if c == b'.' {
            point = Some(len);
        } else {
            digits[len] = c;
            len += 1;
        }
    }
    let mut point = point.unwrap_or(len) as i32 + exponent;
    // value = 0.digits x 10^point; drop the leading zeros (each moves the point) and the
    // trailing zeros.
    let mut start = 0;
    while start < len && digits[start] == b'0' {
        start += 1;
        point -= 1;
    }
    while len > start && digits[len - 1] == b'0' {
        len -= 1;
    }
    if negative {
        out.push(b'-');
    }
    let digits = &mut digits[start..len];
    let q = point - digits.len() as i32;
    if digits.last().is_some_and(|&c| c % 2 == 0) && ties_below(v, digits_value(digits), q) {
        // An even last digit chosen in a tie (Ryu rounds half to even): Display rounds half
        // up, to the candidate above, whose last digit is odd (no carry).
        if let Some(last) = digits.last_mut() {
            *last += 1;
        }
    }
    let digits = &*digits;
    if digits.is_empty() {
        out.push(b'0');
        return;
    }
    let k = digits.len() as i32;
    if point <= 0 {
        out.extend_from_slice(b"0.");
        out.resize(out.len() + (-point) as usize, b'0');
        out.extend_from_slice(digits);
    } else if point < k {
        let (whole, fraction) = digits.split_at(point as usize);
        out.extend_from_slice(whole);
        out.push(b'.');
        out.extend_from_slice(fraction);
    } else {
        out.extend_from_slice(digits);
        out.resize(out.len() + (point - k) as usize, b'0');
    }
}

/// The integer the ASCII digits stand for (at most 17 of them: it fits).
fn digits_value(digits: &[u8]) -> u64 {
    digits
        .iter()
        .fold(0u64, |d, &c| d * 10 + u64::from(c - b'0'))
}

/// Whether |v| lies exactly halfway between d x 10^q and (d + 1) x 10^q: 2 |v| = (2 d + 1) 10^q.
/// With |v| = m 2^e, m odd, and 2 d + 1 odd, that is e + 1 = q (the powers of two) and
/// m = (2 d + 1) 5^q for q >= 0, m 5^-q = 2 d + 1 for q < 0 (the odd parts), in exact integers.
fn ties_below(v: f64, d: u64, q: i32) -> bool {
    let bits = v.to_bits() & !(1u64 << 63);
    let (fraction, biased) = (bits & ((1u64 << 52) - 1), (bits >> 52) as i32);
    let (m, e) = match biased {
        0 => (fraction, -1074),
        _ => (fraction | (1u64 << 52), biased - 1075),
    };
    // |v| = (m >> zeros) 2^(e + zeros) with an odd m >> zeros.
    let zeros = m.trailing_zeros();
    if m == 0 || e + zeros as i32 + 1 != q {
        // Zero, or the powers of two differ.
        return false;
    }
    let m = m >> zeros;
    let odd = u128::from(2 * d + 1);
    let five = |k: u32| 5u128.checked_pow(k);
    if q >= 0 {
        five(q as u32).and_then(|p| odd.checked_mul(p)) == Some(u128::from(m))
    } else {
        five((-q) as u32).and_then(|p| u128::from(m).checked_mul(p)) == Some(odd)
    }
}

/// The exponent after Ryu's `e`: an optional minus sign and at most three digits.
fn parse_exponent(text: &[u8]) -> i32 {
    let (sign, digits) = match text.split_first() {
        Some((b'-', rest)) => (-1, rest),
        _ => (1, text),
    };
    sign * digits
        .iter()
        .fold(0i32, |e, &d| e * 10 + i32::from(d - b'0'))
}

#[cfg(test)]
mod tests {
    use super::push;

    fn check(v: f64) {
        let mut ours = Vec::new();
        push(&mut ours, v);
        assert_eq!(
            String::from_utf8(ours).unwrap(),
            format!("{v}"),
            "bits {:#018x}",
            v.to_bits()
        );
    }

    #[test]
    fn the_boundaries_read_as_display_writes_them() {
        let mut cases = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.5,
            1.5,
            100.0,
            123.456,
            1e-7,
            -2.5e-5,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e23,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            5e-324,
            -5e-324,
            // The largest subnormal number.
            f64::from_bits(0x000f_ffff_ffff_ffff),
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            9007199254740993.0,
            0.30000000000000004,
        ];
        for e in -330..=310 {
            let p = 10f64.powi(e);
            cases.extend([p, -p, p * 1.5, p * 9.999999999999999, p / 3.0]);
        }
        for e in -1074..=1023 {
            let p = 2f64.powi(e);
            cases.extend([
                p,
                p * 3.0,
                f64::from_bits(p.to_bits().saturating_sub(1)),
                f64::from_bits(p.to_bits().saturating_add(1)),
            ]);
        }
        for v in cases {
            check(v);
        }
    }

    #[test]
    fn dyadic_numbers_halfway_between_two_candidates_round_up_as_display_does() {
        // k 2^j and k 2^-j for odd k: the numbers whose exact value can end in a 5 one digit
        // past the shortest (2^-25 and 1658206780088562.25 are two).
        check(2f64.powi(-25));
        check(f64::from_bits(0x4317_9085_685d_83c9)); // 1658206780088562.25
        for j in 0..=120 {
            for k in (1..4000u32).step_by(2) {
                let k = f64::from(k);
                check(k * 2f64.powi(j));
                check(k * 2f64.powi(-j));
                check(-k * 2f64.powi(-j));
            }
        }
    }

    #[test]
    fn a_million_random_numbers_read_as_display_writes_them() {
        // Random bit patterns (every exponent, subnormals, NaNs), then numbers of the size a
        // trace holds (random in [-10, 10] and their small multiples).
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..1_000_000 {
            check(f64::from_bits(next()));
        }
        for _ in 0..200_000 {
            let unit = (next() >> 11) as f64 / (1u64 << 53) as f64;
            check(20.0 * unit - 10.0);
            check((20.0 * unit - 10.0) * 1e-6);
        }
    }
}
