//! Properties of the [`Q15`] arithmetic and kernels
//! ([`crate::scalar::q15`]).
//!
//! Error bounds are in LSB of the result: `2⁻¹⁵` for [`Q15`] results, one
//! angle code (`2π/2¹⁶ rad`) for [`BinaryAngle`] results, measured modulo
//! the turn (a result of `-π` for a reference of `+π` is at distance 0). The
//! reference is the `f64` function of `libm` on the exact input value.
//!
//! | property | engines |
//! |---|---|
//! | `mul_within_bound` (≤ 0.5 LSB; 1 for `(-1)(-1)`), `mul_correctly_rounded` | exhaustive (all 2³² pairs); Kani (integer form) |
//! | `sgn_exact` | exhaustive (all 2¹⁶); Kani |
//! | `sat_within_bound` (≤ 1 LSB), `sat_correctly_rounded` | exhaustive (all 2³² pairs `(x, y)`); Kani (integer form) |
//! | `sat_in_range`, `sat_odd`, `sat_monotone_step`, `sat_continuous_at_layer`, `sat_zero` | exhaustive (all 2³² pairs); Kani |
//! | `sin_within_bound`, `cos_within_bound` (≤ 1 LSB) | exhaustive (all 2¹⁶ angles); random |
//! | `sin_cos_matches` (bit-exact), `sin_odd`, `cos_is_shifted_even_sin` | exhaustive; Kani |
//! | `pythagorean_within_bound` (`|sin² + cos² - 1| ≤ 2` LSB) | exhaustive; random |
//! | `atan_within_bound` (≤ 1 LSB) | exhaustive (all 2¹⁶); random |
//! | `atan_monotone`, `atan_odd` | exhaustive; Kani |
//! | `atan2_within_bound` (≤ 1 code mod 2π, `atan2(0,0) = 0`) | exhaustive (all 2³² pairs `(y, x)`); random |
//! | `sqrt_within_bound` (≤ 0.5 LSB), `sqrt_correctly_rounded` | exhaustive (all 2¹⁶); Kani (integer form) |
//! | `sqrt_monotone` | exhaustive; Kani |
//! | `exp_neg_within_bound` (≤ 1 LSB on `[-1, 0]`, `MAX` above) | exhaustive (all 2¹⁶); random |
//! | `exp_neg_monotone` | exhaustive; Kani |
//!
//! The error-bound properties whose reference is a transcendental `libm`
//! function (`sin`, `cos`, `atan`, `atan2`, `exp`) have no Kani entry: a
//! bit-precise solver cannot reach through the `libm` implementations, and
//! the exhaustive engine already checks every input of the 16-bit type.
//! Where a bound has an integer formulation (`mul`, `sat`, `sqrt`), that form
//! has a Kani entry.
//!
//! Every property is total: inputs outside its precondition (stated in its
//! doc) make it hold vacuously, so the exhaustive engine can enumerate the
//! whole type; the Kani entries `assume` the precondition instead.

use super::engine::{lsb_error, Verdict};
use crate::scalar::q15::{self, BinaryAngle, Q15};

/// One Q15 LSB, `2⁻¹⁵`.
const LSB: f64 = 1.0 / 32768.0;

/// Proven bound of [`q15::mul`], LSB.
pub const MUL_BOUND: f64 = 1.0;
/// Proven bound of [`q15::sat`], LSB.
pub const SAT_BOUND: f64 = 1.0;
/// Proven bound of [`q15::sin`] and [`q15::cos`], LSB.
pub const SIN_COS_BOUND: f64 = 1.0;
/// Proven bound on `|sin² + cos² - 1|`, LSB.
pub const PYTHAGOREAN_BOUND: f64 = 2.0;
/// Proven bound of [`q15::atan`], LSB.
pub const ATAN_BOUND: f64 = 1.0;
/// Proven bound of [`q15::atan2`], angle codes.
pub const ATAN2_BOUND: f64 = 1.0;
/// Proven bound of [`q15::sqrt`], LSB.
pub const SQRT_BOUND: f64 = 0.5;
/// Proven bound of [`q15::exp_neg`] on `[-1, 0]`, LSB.
pub const EXP_NEG_BOUND: f64 = 1.0;

#[inline]
fn q(bits: i16) -> Q15 {
    Q15::from_bits(bits)
}

// ---------------------------------------------------------------------------
// mul, sgn, sat
// ---------------------------------------------------------------------------

/// `mul(a, b)` is within [`MUL_BOUND`] of the exact product; ≤ 0.5 LSB
/// except for the saturated `(-1)·(-1)`.
pub fn mul_within_bound(a: i16, b: i16) -> Verdict {
    let got = q15::to_f64(q15::mul(q(a), q(b)));
    let exact = q15::to_f64(q(a)) * q15::to_f64(q(b));
    let e = lsb_error(got, exact, LSB);
    let bound = if a == i16::MIN && b == i16::MIN {
        MUL_BOUND
    } else {
        0.5
    };
    Verdict::bounded(e, bound)
}

/// Integer form of [`mul_within_bound`]: with `p = a·b` and `r` the result
/// bits, `|2¹⁶·r - 2p| ≤ 2¹⁵` (round to nearest), except `(-1)·(-1) = MAX`.
pub fn mul_correctly_rounded(a: i16, b: i16) -> Verdict {
    let r = q15::mul(q(a), q(b)).to_bits() as i64;
    if a == i16::MIN && b == i16::MIN {
        return Verdict::logical(r == i16::MAX as i64);
    }
    let p = a as i64 * b as i64;
    Verdict::logical(((r << 16) - 2 * p).abs() <= 1 << 15)
}

/// `sgn` of eq. (2.17) is exactly `MAX`, `0` or `-MAX` by the sign of `x`.
pub fn sgn_exact(x: i16) -> Verdict {
    let expected = match x {
        1.. => i16::MAX,
        0 => 0,
        _ => -i16::MAX,
    };
    Verdict::logical(q15::sgn(q(x)).to_bits() == expected)
}

/// Exact eq. (4.18) on the values of `x`, `y` (with `0/0 = 0`).
fn sat_reference(x: i16, y: i16) -> f64 {
    let (xv, yv) = (x as f64, y as f64);
    if x == 0 {
        0.0
    } else if xv.abs() > yv {
        xv.signum()
    } else {
        // 0 < |x| ≤ y, so y > 0.
        xv / yv
    }
}

/// `sat(x, y)` is within [`SAT_BOUND`] LSB of eq. (4.18) (≤ 0.5 LSB where
/// the exact value is not `±1`).
pub fn sat_within_bound(x: i16, y: i16) -> Verdict {
    let got = q15::to_f64(q15::sat(q(x), q(y)));
    let exact = sat_reference(x, y);
    let e = lsb_error(got, exact, LSB);
    let bound = if exact.abs() == 1.0 { SAT_BOUND } else { 0.5 };
    Verdict::bounded(e, bound)
}

/// Integer form of [`sat_within_bound`]: inside the layer (`0 < |x| < y`)
/// the result bits `r` satisfy `|2·r·y - 2¹⁶·x| ≤ y`; outside (`|x| ≥ y`,
/// or `y ≤ 0`) `r = sgn(x)`.
pub fn sat_correctly_rounded(x: i16, y: i16) -> Verdict {
    let r = q15::sat(q(x), q(y)).to_bits() as i64;
    let (x, y) = (x as i64, y as i64);
    if y > 0 && x.abs() < y {
        Verdict::logical((2 * r * y - (x << 16)).abs() <= y)
    } else {
        Verdict::logical(r == q15::sgn(q(x as i16)).to_bits() as i64)
    }
}

/// `sat(x, y) ∈ [-MAX, MAX]` (never `MIN`).
pub fn sat_in_range(x: i16, y: i16) -> Verdict {
    let r = q15::sat(q(x), q(y)).to_bits();
    Verdict::logical(r != i16::MIN)
}

/// `sat(-x, y) = -sat(x, y)`. Precondition: `x ≠ MIN` (`-MIN` is not a
/// Q15 value).
pub fn sat_odd(x: i16, y: i16) -> Verdict {
    if x == i16::MIN {
        return Verdict::logical(true);
    }
    let a = q15::sat(q(x), q(y)).to_bits();
    let b = q15::sat(q(-x), q(y)).to_bits();
    Verdict::logical(b == -a)
}

/// Monotone and (for `y > 0`) Lipschitz in `x`: with `x' = x + 1 LSB`,
/// `0 ≤ sat(x', y) - sat(x, y) ≤ ⌊2¹⁵ / y⌋ + 1` LSB, the exact slope
/// `1/y` plus rounding. Precondition: `x < MAX`.
pub fn sat_monotone_step(x: i16, y: i16) -> Verdict {
    if x == i16::MAX {
        return Verdict::logical(true);
    }
    let a = q15::sat(q(x), q(y)).to_bits() as i32;
    let b = q15::sat(q(x + 1), q(y)).to_bits() as i32;
    let step = b - a;
    let lipschitz = y <= 0 || step <= (1 << 15) / y as i32 + 1;
    Verdict::logical(step >= 0 && lipschitz)
}

/// Continuity at the layer boundary `|x| = y` (`0 < y < MAX`): the value
/// at `x = ±y` equals the value just outside, `±MAX`. Holds vacuously for
/// other inputs.
pub fn sat_continuous_at_layer(x: i16, y: i16) -> Verdict {
    if !(y > 0 && y < i16::MAX && (x == y || x == -y)) {
        return Verdict::logical(true);
    }
    let outside = if x > 0 { x + 1 } else { x - 1 };
    let at = q15::sat(q(x), q(y));
    let out = q15::sat(q(outside), q(y));
    Verdict::logical(at == out && out == q15::sgn(q(x)))
}

/// `sat(0, y) = 0` for every `y`.
pub fn sat_zero(y: i16) -> Verdict {
    Verdict::logical(q15::sat(q15::ZERO, q(y)) == q15::ZERO)
}

/// Every `sat` property at one pair (what the exhaustive engine runs).
pub fn sat_all(x: i16, y: i16) -> Verdict {
    let mut v = sat_within_bound(x, y)
        .and(sat_correctly_rounded(x, y))
        .and(sat_in_range(x, y))
        .and(sat_odd(x, y))
        .and(sat_monotone_step(x, y))
        .and(sat_continuous_at_layer(x, y));
    if x == 0 {
        v = v.and(sat_zero(y));
    }
    v
}

// ---------------------------------------------------------------------------
// sin, cos
// ---------------------------------------------------------------------------

/// `sin(a)` is within [`SIN_COS_BOUND`] LSB of `sin(a·2π/2¹⁶)`.
pub fn sin_within_bound(a: i16) -> Verdict {
    let a = BinaryAngle::from_bits(a);
    let got = q15::to_f64(q15::sin(a));
    Verdict::bounded(
        lsb_error(got, libm::sin(a.to_radians()), LSB),
        SIN_COS_BOUND,
    )
}

/// `cos(a)` is within [`SIN_COS_BOUND`] LSB of `cos(a·2π/2¹⁶)`.
pub fn cos_within_bound(a: i16) -> Verdict {
    let a = BinaryAngle::from_bits(a);
    let got = q15::to_f64(q15::cos(a));
    Verdict::bounded(
        lsb_error(got, libm::cos(a.to_radians()), LSB),
        SIN_COS_BOUND,
    )
}

/// `cos(a) == sin(a + π/2)` and `cos(-a) == cos(a)`, bit for bit.
pub fn cos_is_shifted_even_sin(a: i16) -> Verdict {
    let c = q15::cos(BinaryAngle::from_bits(a));
    let shifted = q15::sin(BinaryAngle::from_bits(a) + BinaryAngle::FRAC_PI_2);
    let mirrored = q15::cos(BinaryAngle::from_bits(a).wrapping_neg());
    Verdict::logical(c == shifted && c == mirrored)
}

/// `sin_cos(a) == (sin(a), cos(a))` bit for bit.
pub fn sin_cos_matches(a: i16) -> Verdict {
    let a = BinaryAngle::from_bits(a);
    Verdict::logical(q15::sin_cos(a) == (q15::sin(a), q15::cos(a)))
}

/// `sin(-a) = -sin(a)` bit for bit. Precondition: `a ≠ -π` (where
/// `-a = a` and `sin = 0`; it holds there too, checked separately by the
/// hand values).
pub fn sin_odd(a: i16) -> Verdict {
    if a == i16::MIN {
        return Verdict::logical(true);
    }
    let s = q15::sin(BinaryAngle::from_bits(a)).to_bits();
    let t = q15::sin(BinaryAngle::from_bits(-a)).to_bits();
    Verdict::logical(t == -s)
}

/// `|sin²(a) + cos²(a) - 1| ≤` [`PYTHAGOREAN_BOUND`] LSB.
pub fn pythagorean_within_bound(a: i16) -> Verdict {
    let (s, c) = q15::sin_cos(BinaryAngle::from_bits(a));
    let (s, c) = (q15::to_f64(s), q15::to_f64(c));
    // s² + c² is exact in f64 (30-bit products).
    Verdict::bounded(lsb_error(s * s + c * c, 1.0, LSB), PYTHAGOREAN_BOUND)
}

// ---------------------------------------------------------------------------
// atan, atan2
// ---------------------------------------------------------------------------

/// `atan(x)` is within [`ATAN_BOUND`] LSB of `atan(x)` (radians).
pub fn atan_within_bound(x: i16) -> Verdict {
    let got = q15::to_f64(q15::atan(q(x)));
    Verdict::bounded(
        lsb_error(got, libm::atan(q15::to_f64(q(x))), LSB),
        ATAN_BOUND,
    )
}

/// `atan(x) ≤ atan(x + 1 LSB)`. Precondition: `x < MAX`.
pub fn atan_monotone(x: i16) -> Verdict {
    if x == i16::MAX {
        return Verdict::logical(true);
    }
    Verdict::logical(q15::atan(q(x)) <= q15::atan(q(x + 1)))
}

/// `atan(-x) = -atan(x)`. Precondition: `x ≠ MIN`.
pub fn atan_odd(x: i16) -> Verdict {
    if x == i16::MIN {
        return Verdict::logical(true);
    }
    Verdict::logical(q15::atan(q(-x)) == -q15::atan(q(x)))
}

/// `atan2(y, x)` is within [`ATAN2_BOUND`] angle codes of
/// `atan2(y, x)` modulo `2π`, and `atan2(0, 0) = 0` exactly.
pub fn atan2_within_bound(y: i16, x: i16) -> Verdict {
    let got = q15::atan2(q(y), q(x));
    if x == 0 && y == 0 {
        return Verdict::logical(got == BinaryAngle::ZERO);
    }
    // The scale 2⁻¹⁵ cancels in the ratio.
    let reference = libm::atan2(y as f64, x as f64) / BinaryAngle::RADIANS_PER_CODE;
    let mut d = got.to_bits() as f64 - reference;
    // Distance modulo the turn (65536 codes).
    d -= 65536.0 * libm::round(d / 65536.0);
    Verdict::bounded(libm::fabs(d), ATAN2_BOUND)
}

// ---------------------------------------------------------------------------
// sqrt, exp_neg
// ---------------------------------------------------------------------------

/// `sqrt(x)` is within [`SQRT_BOUND`] LSB of `√x` (`0` for `x < 0`).
pub fn sqrt_within_bound(x: i16) -> Verdict {
    let got = q15::to_f64(q15::sqrt(q(x)));
    let xv = q15::to_f64(q(x));
    let reference = if xv < 0.0 { 0.0 } else { libm::sqrt(xv) };
    Verdict::bounded(lsb_error(got, reference, LSB), SQRT_BOUND)
}

/// Integer form: with `n = x·2¹⁵` and result bits `r`,
/// `(2r - 1)² ≤ 4n ≤ (2r + 1)²` (correct rounding); `r = 0` for `x ≤ 0`.
pub fn sqrt_correctly_rounded(x: i16) -> Verdict {
    let r = q15::sqrt(q(x)).to_bits() as i64;
    if x <= 0 {
        return Verdict::logical(r == 0);
    }
    let n4 = (x as i64) << 17;
    Verdict::logical((2 * r - 1) * (2 * r - 1) <= n4 && n4 <= (2 * r + 1) * (2 * r + 1))
}

/// `sqrt(x) ≤ sqrt(x + 1 LSB)`. Precondition: `x < MAX`.
pub fn sqrt_monotone(x: i16) -> Verdict {
    if x == i16::MAX {
        return Verdict::logical(true);
    }
    Verdict::logical(q15::sqrt(q(x)) <= q15::sqrt(q(x + 1)))
}

/// `exp_neg(x)` is within [`EXP_NEG_BOUND`] LSB of `e^x` for
/// `x ∈ [-1, 0]`, and is exactly `MAX` for `x > 0`.
pub fn exp_neg_within_bound(x: i16) -> Verdict {
    let got = q15::exp_neg(q(x));
    if x > 0 {
        return Verdict::logical(got == q15::MAX);
    }
    Verdict::bounded(
        lsb_error(q15::to_f64(got), libm::exp(q15::to_f64(q(x))), LSB),
        EXP_NEG_BOUND,
    )
}

/// `exp_neg(x) ≤ exp_neg(x + 1 LSB)`. Precondition: `x < MAX`.
pub fn exp_neg_monotone(x: i16) -> Verdict {
    if x == i16::MAX {
        return Verdict::logical(true);
    }
    Verdict::logical(q15::exp_neg(q(x)) <= q15::exp_neg(q(x + 1)))
}

// ---------------------------------------------------------------------------
// Kani entries (integer-logic properties; run with `cargo kani`)
// ---------------------------------------------------------------------------

#[cfg(kani)]
mod kani_entries {
    use super::*;

    #[kani::proof]
    fn kani_mul_correctly_rounded_q15() {
        assert!(mul_correctly_rounded(kani::any(), kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sgn_exact_q15() {
        assert!(sgn_exact(kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sat_correctly_rounded_q15() {
        assert!(sat_correctly_rounded(kani::any(), kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sat_in_range_q15() {
        assert!(sat_in_range(kani::any(), kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sat_odd_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MIN); // precondition: -MIN is not a Q15 value
        assert!(sat_odd(x, kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sat_monotone_step_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MAX); // precondition: x + 1 LSB must exist
        assert!(sat_monotone_step(x, kani::any()).holds);
    }

    /// The operands and value of the first stubbed `ratio` call.
    static RATIO_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `ratio` (the shift-and-subtract `num/den`) as comparisons only, at
    /// `sat`'s calls (`num < den < 2¹⁵`, asserted): any value up to
    /// `2^BITS`, and a second call by the same divisor in the order of the
    /// dividends. Both hold for the real `ratio` (a correctly rounded
    /// quotient below one); `exhaustive_sat_q15` checks the order of `sat`
    /// itself at every pair.
    fn ratio_as_order_lemma<const BITS: u32>(num: u32, den: u32) -> u32 {
        assert!(num < den && den < 1 << 15, "ratio outside sat's calls");
        let r: u32 = kani::any();
        kani::assume(r <= 1 << BITS);
        if let Some((num0, den0, r0)) = RATIO_FIRST.first_or_record(num, den, r) {
            if den0 == den {
                kani::assume((num0 > num || r0 <= r) && (num > num0 || r <= r0));
            }
        }
        r
    }

    /// The order part of `sat_monotone_step`: `sat(x, y) ≤ sat(x + 1 LSB,
    /// y)` at every pair, the division by its order lemma
    /// ([`ratio_as_order_lemma`]). The step bound is
    /// `kani_sat_monotone_step_q15`'s, which needs the quotient's value.
    #[kani::proof]
    #[kani::stub(crate::scalar::q15::ratio, ratio_as_order_lemma)]
    fn kani_sat_order_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MAX); // precondition: x + 1 LSB must exist
        let y = q(kani::any());
        assert!(q15::sat(q(x), y) <= q15::sat(q(x + 1), y));
    }

    #[kani::proof]
    fn kani_sat_continuous_at_layer_q15() {
        let y: i16 = kani::any();
        kani::assume(y > 0 && y < i16::MAX); // precondition: a layer with an outside
        let x = if kani::any() { y } else { -y };
        assert!(sat_continuous_at_layer(x, y).holds);
    }

    #[kani::proof]
    fn kani_sat_zero_q15() {
        assert!(sat_zero(kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sin_cos_matches_q15() {
        assert!(sin_cos_matches(kani::any()).holds);
    }

    #[kani::proof]
    fn kani_cos_is_shifted_even_sin_q15() {
        assert!(cos_is_shifted_even_sin(kani::any()).holds);
    }

    #[kani::proof]
    fn kani_sin_odd_q15() {
        let a: i16 = kani::any();
        kani::assume(a != i16::MIN); // precondition: -(-π) wraps to -π
        assert!(sin_odd(a).holds);
    }

    #[kani::proof]
    fn kani_atan_monotone_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MAX); // precondition: x + 1 LSB must exist
        assert!(atan_monotone(x).holds);
    }

    #[kani::proof]
    fn kani_atan_odd_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MIN); // precondition: -MIN is not a Q15 value
        assert!(atan_odd(x).holds);
    }

    #[kani::proof]
    #[kani::unwind(16)]
    fn kani_sqrt_correctly_rounded_q15() {
        assert!(sqrt_correctly_rounded(kani::any()).holds);
    }

    #[kani::proof]
    #[kani::unwind(16)]
    fn kani_sqrt_monotone_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MAX); // precondition: x + 1 LSB must exist
        assert!(sqrt_monotone(x).holds);
    }

    #[kani::proof]
    fn kani_exp_neg_monotone_q15() {
        let x: i16 = kani::any();
        kani::assume(x != i16::MAX); // precondition: x + 1 LSB must exist
        assert!(exp_neg_monotone(x).holds);
    }
}

// ---------------------------------------------------------------------------
// Exhaustive and random engines
// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::{exhaustive_u32, Report};
    use super::*;
    use proptest::prelude::*;
    use std::{format, println, string::String};

    /// The low 16 bits of an engine code as an `i16`.
    fn lo(code: u32) -> i16 {
        code as u16 as i16
    }

    /// The high 16 bits of an engine code as an `i16`.
    fn hi(code: u32) -> i16 {
        (code >> 16) as u16 as i16
    }

    fn report(kernel: &str, domain: &str, bound: f64, rep: &Report, at: String) {
        println!(
            "PROOF kernel={kernel} backend=Q15 domain={domain} bound={bound} LSB \
             max_err={:.4} LSB at={at} checked={} engine=exhaustive",
            rep.max_error, rep.checked
        );
        assert_eq!(
            rep.failures,
            0,
            "{kernel}: {} failures, first at code {:#010x}",
            rep.failures,
            rep.first_failure.unwrap_or(0)
        );
    }

    fn unary(
        kernel: &str,
        domain: &str,
        bound: f64,
        unit: &str,
        property: impl Fn(i16) -> Verdict + Sync,
    ) {
        let rep = exhaustive_u32(0, u16::MAX as u32, |c| property(lo(c)));
        let at = format!("{}={}", unit, lo(rep.argmax));
        report(kernel, domain, bound, &rep, at);
    }

    fn pairs(
        kernel: &str,
        domain: &str,
        bound: f64,
        names: (&str, &str),
        property: impl Fn(i16, i16) -> Verdict + Sync,
    ) {
        let rep = exhaustive_u32(0, u32::MAX, |c| property(hi(c), lo(c)));
        let at = format!(
            "{}={},{}={}",
            names.0,
            hi(rep.argmax),
            names.1,
            lo(rep.argmax)
        );
        report(kernel, domain, bound, &rep, at);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_mul_q15() {
        pairs(
            "mul",
            "all-2^32-(a,b)-bit-pairs;rounded",
            MUL_BOUND,
            ("a", "b"),
            |a, b| mul_within_bound(a, b).and(mul_correctly_rounded(a, b)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sgn_q15() {
        unary("sgn", "all-2^16-x;exact", 0.0, "x", sgn_exact);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sat_q15() {
        pairs(
            "sat",
            "all-2^32-(x,y)-bit-pairs;bound+rounding+range+odd+monotone+lipschitz+continuity+zero",
            SAT_BOUND,
            ("y", "x"),
            // code = y << 16 | x
            |y, x| sat_all(x, y),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_q15() {
        unary("sin", "all-2^16-angle-codes;odd", SIN_COS_BOUND, "a", |a| {
            sin_within_bound(a).and(sin_odd(a))
        });
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_q15() {
        unary(
            "cos",
            "all-2^16-angle-codes;even;=sin(a+pi/2)",
            SIN_COS_BOUND,
            "a",
            |a| cos_within_bound(a).and(cos_is_shifted_even_sin(a)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_cos_q15() {
        unary(
            "sin_cos",
            "all-2^16-angle-codes;bit-equal-to-(sin,cos);err=|sin^2+cos^2-1|",
            PYTHAGOREAN_BOUND,
            "a",
            |a| pythagorean_within_bound(a).and(sin_cos_matches(a)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_q15() {
        unary("atan", "all-2^16-x;monotone+odd", ATAN_BOUND, "x", |x| {
            atan_within_bound(x).and(atan_monotone(x)).and(atan_odd(x))
        });
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan2_q15() {
        pairs(
            "atan2",
            "all-2^32-(y,x)-bit-pairs;codes-mod-2pi",
            ATAN2_BOUND,
            ("y", "x"),
            atan2_within_bound,
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_q15() {
        unary("sqrt", "all-2^16-x;monotone;x<0->0", SQRT_BOUND, "x", |x| {
            sqrt_within_bound(x)
                .and(sqrt_correctly_rounded(x))
                .and(sqrt_monotone(x))
        });
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_neg_q15() {
        unary(
            "exp_neg",
            "all-2^16-x;bound-on-[-1,0];x>0->MAX;monotone",
            EXP_NEG_BOUND,
            "x",
            |x| exp_neg_within_bound(x).and(exp_neg_monotone(x)),
        );
    }

    /// Any Q15 bit pattern: the whole normalized range `[-1, 1)`.
    fn normalized() -> impl Strategy<Value = i16> {
        i16::MIN..=i16::MAX
    }

    proptest! {
        #[test]
        fn random_mul_q15(a in normalized(), b in normalized()) {
            prop_assert!(mul_within_bound(a, b).holds);
            prop_assert!(mul_correctly_rounded(a, b).holds);
        }

        #[test]
        fn random_sat_inside_layer_q15(y in 1i16..=i16::MAX, t in -1.0f64..=1.0) {
            // x inside the boundary layer |x| ≤ y.
            let x = (t * y as f64) as i16;
            prop_assert!(sat_all(x, y).holds);
        }

        #[test]
        fn random_sat_q15(x in normalized(), y in normalized()) {
            prop_assert!(sat_all(x, y).holds);
        }

        #[test]
        fn random_sin_cos_q15(a in normalized()) {
            prop_assert!(sin_within_bound(a).holds);
            prop_assert!(cos_within_bound(a).holds);
            prop_assert!(sin_cos_matches(a).holds);
            prop_assert!(cos_is_shifted_even_sin(a).holds);
            prop_assert!(pythagorean_within_bound(a).holds);
        }

        #[test]
        fn random_atan_q15(x in normalized()) {
            prop_assert!(atan_within_bound(x).holds);
            prop_assert!(atan_monotone(x).holds);
        }

        #[test]
        fn random_atan2_q15(y in normalized(), x in normalized()) {
            prop_assert!(atan2_within_bound(y, x).holds);
        }

        #[test]
        fn random_atan2_small_q15(y in -64i16..=64, x in -64i16..=64) {
            // Tiny vectors: the ratio, not the magnitude, sets the angle.
            prop_assert!(atan2_within_bound(y, x).holds);
        }

        #[test]
        fn random_sqrt_q15(x in normalized()) {
            prop_assert!(sqrt_within_bound(x).holds);
            prop_assert!(sqrt_correctly_rounded(x).holds);
        }

        #[test]
        fn random_exp_neg_q15(x in i16::MIN..=0i16) {
            prop_assert!(exp_neg_within_bound(x).holds);
            prop_assert!(exp_neg_monotone(x).holds);
        }
    }
}
