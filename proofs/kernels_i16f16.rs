//! I16F16 kernel properties (`src/scalar/kernels/i16f16.rs`).
//!
//! Each property is a plain function of raw inputs, run by:
//!
//! * **Exhaustive** (`exhaustive_*_i16f16`, `#[ignore]`d, run in release):
//!   every one of the 2³² `I16F16` bit patterns (for `atan2`, every pair of
//!   a 16-bit lattice packed into the `u32` code). A complete proof for the
//!   type. Each test prints one `PROOF …` line.
//!   `cargo test --release --lib -- --ignored exhaustive_ --test-threads 1 --nocapture`
//! * **Kani** (`kani_*`): the same bodies with `kani::any()` inputs, plus
//!   cheap integer properties of the building blocks (exact `mulhi`,
//!   `div_ratio`, `sqrt_q16`), output ranges and monotone pairs, which Kani
//!   decides bit-precisely.
//! * **Random** (proptest, plain `cargo test`): bounded physical ranges.
//!
//! Reference: `f64` functions (std's in tests, `libm` elsewhere), exact
//! `f64` conversion of the input; error in LSB (2⁻¹⁶) by
//! [`lsb_error`](super::engine::lsb_error).

use super::engine::{lsb_error, Verdict};
use crate::scalar::kernels::i16f16 as k;
use crate::scalar::{Scalar, I16F16};

/// One LSB of `I16F16`.
pub const LSB: f64 = 1.0 / 65536.0;
/// `I16F16::MAX` as `f64`.
const MAX_F: f64 = 32768.0 - LSB;

/// f64 reference functions: std in tests (glibc), `libm` otherwise (no_std
/// Kani builds). Both are within 1 ulp of `f64`, i.e. 2⁻³⁶ LSB here.
mod reference {
    pub use imp::*;
    #[cfg(not(test))]
    mod imp {
        pub use libm::{acos, atan, atan2, cos, exp, sin, sqrt, tan};
    }
    #[cfg(test)]
    mod imp {
        pub fn atan(x: f64) -> f64 {
            x.atan()
        }
        pub fn tan(x: f64) -> f64 {
            x.tan()
        }
        pub fn exp(x: f64) -> f64 {
            x.exp()
        }
        pub fn sin(x: f64) -> f64 {
            x.sin()
        }
        pub fn cos(x: f64) -> f64 {
            x.cos()
        }
        pub fn atan2(y: f64, x: f64) -> f64 {
            y.atan2(x)
        }
        pub fn acos(x: f64) -> f64 {
            x.acos()
        }
        pub fn sqrt(x: f64) -> f64 {
            x.sqrt()
        }
    }
}

/// Raw bit pattern → value.
pub fn from_code(code: u32) -> I16F16 {
    I16F16::from_bits(code as i32)
}

/// Code whose value order is the code order: `MIN` at 0, `MAX` at `u32::MAX`.
pub fn ordered(code: u32) -> I16F16 {
    I16F16::from_bits((code ^ 0x8000_0000) as i32)
}

/// The next representable value (`x < MAX`).
fn next_up(x: I16F16) -> I16F16 {
    I16F16::from_bits(x.to_bits() + 1)
}

/// `f(x) ≤ f(x + 2⁻¹⁶)` (vacuous at `MAX`).
pub fn monotone_at(f: fn(I16F16) -> I16F16, x: I16F16) -> Verdict {
    Verdict::logical(x == I16F16::MAX || f(x) <= f(next_up(x)))
}

/// `f(−x) = −f(x)`, checked from the non-negative side: at `x ≥ 0` it
/// compares `f(−x)` with `−f(x)`; vacuous at `x < 0` (each pair is checked
/// once, at its non-negative member; `MIN` has no pair).
pub fn odd_at(f: fn(I16F16) -> I16F16, x: I16F16, fx: I16F16) -> Verdict {
    Verdict::logical(x < I16F16::ZERO || f(-x) == -fx)
}

/// `atan`, given its result `got` at `x`: `≤ 1 LSB`, odd.
pub fn atan_check(x: I16F16, got: I16F16) -> Verdict {
    let err = lsb_error(got.to_f64(), reference::atan(x.to_f64()), LSB);
    Verdict::bounded(err, 1.0).and(odd_at(k::atan, x, got))
}

/// `atan`: `≤ 1 LSB`, odd.
pub fn atan_within_bound(x: I16F16) -> Verdict {
    atan_check(x, k::atan(x))
}

/// `atan_small`: `≤ 1 LSB` against the exact arctangent of the input
/// clamped to `|x| ≤ 2 − 2⁻¹⁶` (its documented domain), odd. (The unit
/// test `atan_small_is_within_one_lsb` checks every input below 2.)
pub fn atan_small_within_bound(x: I16F16) -> Verdict {
    let top = 2.0 - LSB;
    let got = k::atan_small(x);
    let err = lsb_error(
        got.to_f64(),
        reference::atan(x.to_f64().clamp(-top, top)),
        LSB,
    );
    Verdict::bounded(err, 1.0).and(odd_at(k::atan_small, x, got))
}

/// The inputs of `hypot_unit` and `unit_vector` clamped to their
/// documented domain, `[−(1 − 2⁻¹⁶), 1 − 2⁻¹⁶]`.
fn clamp_unit(a: I16F16) -> f64 {
    let top = 1.0 - LSB;
    a.to_f64().clamp(-top, top)
}

/// `hypot_unit`: `≤ 1 LSB` against the exact `√(a² + b²)` of the inputs
/// clamped to `±(1 − 2⁻¹⁶)` (its documented domain).
pub fn hypot_unit_within_bound(a: I16F16, b: I16F16) -> Verdict {
    let (ca, cb) = (clamp_unit(a), clamp_unit(b));
    let got = k::hypot_unit(a, b);
    Verdict::bounded(
        lsb_error(got.to_f64(), reference::sqrt(ca * ca + cb * cb), LSB),
        1.0,
    )
}

/// `unit_vector`: each component `≤ 1 LSB` from the exact direction of
/// the clamped inputs, `None` exactly for the zero vector.
pub fn unit_vector_within_bound(a: I16F16, b: I16F16) -> Verdict {
    let (ca, cb) = (clamp_unit(a), clamp_unit(b));
    let h = reference::sqrt(ca * ca + cb * cb);
    match k::unit_vector(a, b) {
        None => Verdict::logical(h == 0.0),
        Some((u, v)) => Verdict::bounded(
            lsb_error(u.to_f64(), ca / h, LSB).max(lsb_error(v.to_f64(), cb / h, LSB)),
            1.0,
        ),
    }
}

/// `rsqrt_quarter`: `≤ 1 LSB` against the exact `1/√x` of the input
/// clamped to `[¼, 1]`.
pub fn rsqrt_quarter_within_bound(x: I16F16) -> Verdict {
    let c = x.to_f64().clamp(0.25, 1.0);
    Verdict::bounded(
        lsb_error(k::rsqrt_quarter(x).to_f64(), 1.0 / reference::sqrt(c), LSB),
        1.0,
    )
}

/// The `tan` reference: `tan x` on `|x| < π/2`, `±MAX` outside, saturated
/// at `±MAX` (the kernel's documented value beyond the range).
pub fn tan_reference(x: I16F16) -> f64 {
    let v = x.to_f64();
    if v.abs() >= core::f64::consts::FRAC_PI_2 {
        if v > 0.0 {
            MAX_F
        } else {
            -MAX_F
        }
    } else {
        reference::tan(v).clamp(-MAX_F, MAX_F)
    }
}

/// `tan`, given `got`: `≤ 1 LSB` against the saturated reference
/// ([`tan_reference`]), hence exactly `±MAX` outside the branch; odd.
pub fn tan_check(x: I16F16, got: I16F16) -> Verdict {
    let err = lsb_error(got.to_f64(), tan_reference(x), LSB);
    Verdict::bounded(err, 1.0).and(odd_at(k::tan, x, got))
}

/// `tan`: see [`tan_check`].
pub fn tan_within_bound(x: I16F16) -> Verdict {
    tan_check(x, k::tan(x))
}

/// `exp`, given `got`: `≤ 2 LSB` everywhere and `≤ 1 LSB` where
/// `e^x ≤ 4096` (the internal relative error is `≤ 2⁻²⁸`, which only
/// exceeds half an LSB above 2¹¹); the reference saturates at `MAX` like
/// the kernel.
pub fn exp_check(x: I16F16, got: I16F16) -> Verdict {
    let r = reference::exp(x.to_f64()).min(MAX_F);
    let err = lsb_error(got.to_f64(), r, LSB);
    Verdict::bounded(err, if r <= 4096.0 { 1.0 } else { 2.0 })
}

/// `exp`: see [`exp_check`].
pub fn exp_within_bound(x: I16F16) -> Verdict {
    exp_check(x, k::exp(x))
}

/// `exp_neg_abs`, given `got`: `≤ 1 LSB` against `e^{−|x|}` and in
/// `[0, 1]` (the contract by which the joint-step harnesses stub it); at
/// `x ≥ 0` also even (`f(−x) = f(x)`) and non-increasing (`f(x + δ) ≤
/// f(x)`), so every pair of adjacent magnitudes is checked once.
pub fn exp_neg_abs_check(x: I16F16, got: I16F16) -> Verdict {
    let r = reference::exp(-x.to_f64().abs());
    let err = lsb_error(got.to_f64(), r, LSB);
    let in_range = got >= I16F16::ZERO && got <= I16F16::ONE;
    let shape = x < I16F16::ZERO
        || (k::exp_neg_abs(-x) == got && (x == I16F16::MAX || k::exp_neg_abs(next_up(x)) <= got));
    let shape = in_range && shape;
    Verdict::bounded(err, 1.0).and(Verdict::logical(shape))
}

/// `exp_neg_abs`: see [`exp_neg_abs_check`].
pub fn exp_neg_abs_within_bound(x: I16F16) -> Verdict {
    exp_neg_abs_check(x, k::exp_neg_abs(x))
}

/// Errors (LSB) of `sin_cos(x) = (s, c)`, and whether `s = sin x`,
/// `c = cos x` bit for bit, `sin` is odd and `cos` even (from `x ≥ 0`).
pub fn sin_cos_check(x: I16F16, (s, c): (I16F16, I16F16)) -> (f64, f64, bool) {
    let v = x.to_f64();
    let es = lsb_error(s.to_f64(), reference::sin(v), LSB);
    let ec = lsb_error(c.to_f64(), reference::cos(v), LSB);
    let same = k::sin(x) == s && k::cos(x) == c;
    let sym = x < I16F16::ZERO || {
        let (sn, cn) = k::sin_cos(-x);
        sn == -s && cn == c
    };
    (es, ec, same && sym)
}

/// `sin`: `≤ 1 LSB`, odd, equal to `sin_cos(x).0`.
pub fn sin_within_bound(x: I16F16) -> Verdict {
    let (es, _, ok) = sin_cos_check(x, k::sin_cos(x));
    Verdict::bounded(es, 1.0).and(Verdict::logical(ok))
}

/// `cos`: `≤ 1 LSB`, even, equal to `sin_cos(x).1`.
pub fn cos_within_bound(x: I16F16) -> Verdict {
    let (_, ec, ok) = sin_cos_check(x, k::sin_cos(x));
    Verdict::bounded(ec, 1.0).and(Verdict::logical(ok))
}

/// `atan2(y, x)`: `≤ 1 LSB`, `atan2(0, 0) = 0`.
pub fn atan2_within_bound(y: I16F16, x: I16F16) -> Verdict {
    let got = k::atan2(y, x);
    if y == I16F16::ZERO && x == I16F16::ZERO {
        return Verdict::logical(got == I16F16::ZERO);
    }
    let err = lsb_error(got.to_f64(), reference::atan2(y.to_f64(), x.to_f64()), LSB);
    Verdict::bounded(err, 1.0)
}

/// The 16-bit lattice of the `atan2` proof: `code = (y_k << 16) | x_k`,
/// value `k·2⁻⁸` (every pair of `I8F8` values, embedded in `I16F16`).
pub fn lattice_pair(code: u32) -> (I16F16, I16F16) {
    let y = ((code >> 16) as u16 as i16 as i32) << 8;
    let x = (code as u16 as i16 as i32) << 8;
    (I16F16::from_bits(y), I16F16::from_bits(x))
}

/// `acos`, given `got`: `≤ 1 LSB` against `acos(clamp(x, −1, 1))`.
pub fn acos_check(x: I16F16, got: I16F16) -> Verdict {
    let r = reference::acos(x.to_f64().clamp(-1.0, 1.0));
    Verdict::bounded(lsb_error(got.to_f64(), r, LSB), 1.0)
}

/// `acos`: see [`acos_check`].
pub fn acos_within_bound(x: I16F16) -> Verdict {
    acos_check(x, k::acos(x))
}

/// `sqrt`, given `got`: correctly rounded (`≤ 0.5 LSB`), 0 for negatives.
pub fn sqrt_check(x: I16F16, got: I16F16) -> Verdict {
    let r = reference::sqrt(x.to_f64().max(0.0));
    Verdict::bounded(lsb_error(got.to_f64(), r, LSB), 0.5)
}

/// `sqrt`: see [`sqrt_check`].
pub fn sqrt_within_bound(x: I16F16) -> Verdict {
    sqrt_check(x, k::sqrt(x))
}

/// `sin_cos(x) == (sin x, cos x)` bit for bit.
pub fn sin_cos_is_sin_and_cos(x: I16F16) -> Verdict {
    Verdict::logical(k::sin_cos(x) == (k::sin(x), k::cos(x)))
}

/// Output ranges that need no reference: `|atan| ≤ π/2`, `|sin|, |cos| ≤ 1`,
/// `acos ∈ [0, π]`, `sqrt ≥ 0`, `exp ≥ 0` (all as rounded `I16F16`).
pub fn outputs_in_range(x: I16F16) -> Verdict {
    let one = I16F16::ONE;
    let (s, c) = k::sin_cos(x);
    let a = k::atan(x);
    let ac = k::acos(x);
    Verdict::logical(
        a.abs() <= I16F16::FRAC_PI_2
            && s.abs() <= one
            && c.abs() <= one
            && ac >= I16F16::ZERO
            && ac <= I16F16::PI
            && k::sqrt(x) >= I16F16::ZERO
            && k::exp(x) >= I16F16::ZERO,
    )
}

/// `mulhi(a, b) = ⌊a·b/2³²⌋` exactly.
pub fn mulhi_is_exact(a: u32, b: u32) -> bool {
    k::mulhi(a, b) as u64 == (a as u64 * b as u64) >> 32
}

/// `div_ratio(n, d) = ⌊n·2³²/d⌋` for `n < d ≤ 2³¹` (the `atan2` use).
pub fn div_ratio_is_exact(n: u32, d: u32) -> bool {
    k::div_ratio(n, d) as u64 == ((n as u64) << 32) / d as u64
}

/// `sqrt_q16(n) = (⌊√(n·2¹⁶)⌋, remainder)`.
pub fn sqrt_q16_is_exact(n: u32) -> bool {
    let (root, rem) = k::sqrt_q16(n);
    let v = (n as u64) << 16;
    let r = root as u64;
    r * r + rem as u64 == v && v < (r + 1) * (r + 1)
}

// ---- Kani ------------------------------------------------------------------

#[cfg(kani)]
mod kani_proofs {
    use super::*;

    fn any_fixed() -> I16F16 {
        I16F16::from_bits(kani::any())
    }

    #[kani::proof]
    fn kani_mulhi_exact() {
        assert!(mulhi_is_exact(kani::any(), kani::any()));
    }

    #[kani::proof]
    fn kani_div_ratio_exact() {
        let n: u32 = kani::any();
        let d: u32 = kani::any();
        kani::assume(n < d && d <= 1 << 31); // the operands of atan2_mag
        assert!(div_ratio_is_exact(n, d));
    }

    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_q16_exact() {
        assert!(sqrt_q16_is_exact(kani::any()));
    }

    // `outputs_in_range` (all six kernels on one input: TIMEOUT at 600 s)
    // split by kernel; together the same property.

    /// `|sin x|, |cos x| ≤ 1` (the `sin_cos` part of [`outputs_in_range`]).
    #[kani::proof]
    fn kani_sin_cos_in_range_i16f16() {
        let (s, c) = k::sin_cos(any_fixed());
        assert!(s.abs() <= I16F16::ONE && c.abs() <= I16F16::ONE);
    }

    /// `|atan x| ≤ π/2` for `|x| ≤ 1` (part of [`outputs_in_range`]; with
    /// `kani_atan_in_range_large_i16f16`, every input).
    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan_in_range_i16f16() {
        let x = any_fixed();
        // Split domain: |x| ≤ 1 (the rest: the next harness).
        kani::assume(x.to_bits().unsigned_abs() <= 1 << 16);
        assert!(k::atan(x).abs() <= I16F16::FRAC_PI_2);
    }

    /// Any quotient: the stub of `div_ratio` for range properties, which
    /// hold whatever ratio the division returns. Every `u32` is allowed, so
    /// the real quotient is among the behaviours checked and nothing about
    /// the division is assumed (an over-approximation, not a contract).
    fn any_div_ratio(_n: u32, _d: u32) -> u32 {
        kani::any()
    }

    /// Any root and remainder: the stub of `sqrt_q16` for range properties
    /// (as [`any_div_ratio`]).
    fn any_sqrt_q16(_n: u32) -> (u32, u32) {
        (kani::any(), kani::any())
    }

    /// Any quotient at least the numerator: the stub of `div_ratio` for
    /// the `|x| > 1` range of `atan` (`n = 2¹⁶`, `d = |x|` bits). The
    /// contract `⌊2⁴⁸/d⌋ ≥ 2¹⁶` (`d ≤ 2³¹ < 2³²`) is checked for the real
    /// `div_ratio` at every such `d` by the exhaustive engine
    /// (`exhaustive_atan_bit_identity_i16f16`); as a harness it timed out,
    /// over every `(n, d)` at 604 s and for `n = 2¹⁶` at 602 s. The
    /// precondition is asserted at every call.
    fn div_ratio_atan_contract(n: u32, d: u32) -> u32 {
        assert!(
            n == 1 << 16 && d > 1 << 16 && d <= 1 << 31,
            "div_ratio outside atan's |x| > 1 calls"
        );
        let q: u32 = kani::any();
        kani::assume(q >= n);
        q
    }

    /// `|atan x| ≤ π/2` for `|x| > 1`. There `atan` is `π/2 − atan_unit(t)`
    /// of the ratio `t = ⌊2⁴⁸/|x|⌋`. The range needs a lower bound on `t`
    /// (with any quotient the harness FAILS in 5.4 s), so the division
    /// is its contract `q ≥ n` ([`div_ratio_atan_contract`]; 604 s
    /// TIMEOUT with the real division, whose exactness is a separate
    /// property).
    #[kani::proof]
    #[kani::unwind(40)]
    #[kani::stub(crate::scalar::kernels::i16f16::div_ratio, div_ratio_atan_contract)]
    fn kani_atan_in_range_large_i16f16() {
        let x = any_fixed();
        // Split domain: the complement of the previous harness's.
        kani::assume(x.to_bits().unsigned_abs() > 1 << 16);
        assert!(k::atan(x).abs() <= I16F16::FRAC_PI_2);
    }

    /// `acos x ∈ [0, π]` (part of [`outputs_in_range`]), for every root and
    /// ratio its square root and division may return ([`any_sqrt_q16`],
    /// [`any_div_ratio`]; 603 s TIMEOUT with the real ones): the range is
    /// the branch and sign logic around `atan_unit`, not their values.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::div_ratio, any_div_ratio)]
    #[kani::stub(crate::scalar::kernels::i16f16::sqrt_q16, any_sqrt_q16)]
    #[kani::unwind(40)]
    fn kani_acos_in_range_i16f16() {
        let a = k::acos(any_fixed());
        assert!(a >= I16F16::ZERO && a <= I16F16::PI);
    }

    /// `sqrt x ≥ 0` and `exp x ≥ 0` (part of [`outputs_in_range`]).
    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_exp_in_range_i16f16() {
        let x = any_fixed();
        assert!(k::sqrt(x) >= I16F16::ZERO && k::exp(x) >= I16F16::ZERO);
    }

    static SQRT_Q16_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `sqrt_q16` by what its contract implies ([`sqrt_q16_is_exact`]:
    /// `root = ⌊√(n·2¹⁶)⌋`, `rem = n·2¹⁶ − root²`): `root < 2²⁴` and
    /// `rem ≤ 2·root`; at a second call with a larger `n` either a larger
    /// root or the same root with a larger remainder (`n·2¹⁶` grew), and
    /// the reverse for a smaller `n`. The precondition (`0 < n < 2³¹`, the
    /// arguments `sqrt` passes) is asserted at each call.
    fn sqrt_q16_by_contract(n: u32) -> (u32, u32) {
        assert!(n > 0 && n < 1 << 31, "sqrt_q16 precondition");
        let root: u32 = kani::any();
        let rem: u32 = kani::any();
        // postcondition of the stubbed function: the ranges
        kani::assume(root < 1 << 24 && rem <= 2 * root);
        if let Some((n1, root1, rem1)) = SQRT_Q16_FIRST.first_or_record(n, root, rem) {
            // postcondition of the stubbed function: the order lemma
            kani::assume(if n > n1 {
                root > root1 || (root == root1 && rem > rem1)
            } else if n < n1 {
                root < root1 || (root == root1 && rem < rem1)
            } else {
                root == root1 && rem == rem1
            });
        }
        (root, rem)
    }

    /// `sqrt` non-decreasing over every pair of adjacent inputs: the sign
    /// test and the final rounding (`root + (rem > root)`), with the
    /// integer root by its contract, which `exhaustive_sqrt_q16_exact`
    /// checks at every argument `sqrt` passes (with the real root, two
    /// copies of its sixteen squared trials: TIMEOUT at 605 s; its Kani
    /// harness `kani_sqrt_q16_exact` times out as well).
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::sqrt_q16, sqrt_q16_by_contract)]
    fn kani_sqrt_monotone_pair_i16f16() {
        assert!(monotone_at(k::sqrt, any_fixed()).holds);
    }

    static ATAN_LOW_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static ATAN_HIGH_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static ATAN_RATIO_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `atan_rounded` by its contract (`atan_contract_violations`, checked
    /// at every argument `atan` passes by `exhaustive_atan_contracts_i16f16`:
    /// `t = a·2¹⁶` below 1, `t = ⌊2⁴⁸/a⌋` above): a value in `[0, 2¹⁹]`,
    /// and at a second call on the same side of 1 one non-decreasing in `t`
    /// below 1 and non-increasing above (the same value again for the same
    /// arguments). The precondition below 1 (`t` a multiple of `2¹⁶`) is
    /// asserted at each call.
    fn atan_rounded_by_contract(t: u32, above: bool) -> i32 {
        assert!(above || t & 0xFFFF == 0, "atan_rounded precondition");
        let v: u32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(v <= 1 << 19);
        let first = if above {
            &ATAN_HIGH_FIRST
        } else {
            &ATAN_LOW_FIRST
        };
        first.assume_in_order_u32(t, v, !above);
        v as i32
    }

    /// `div_ratio(2¹⁶, d)` by its order contract: any quotient,
    /// non-increasing in `d` (as `⌊2⁴⁸/d⌋` is; checked at every divisor
    /// `2¹⁶ < d ≤ 2³¹` by `exhaustive_atan_contracts_i16f16`). The
    /// precondition (`n = 2¹⁶ < d`, `atan`'s calls) is asserted at each
    /// call.
    fn div_ratio_by_order_contract(n: u32, d: u32) -> u32 {
        assert!(n == 1 << 16 && d > 1 << 16, "div_ratio precondition (atan)");
        let t: u32 = kani::any();
        ATAN_RATIO_FIRST.assume_in_order_u32(d, t, false);
        t
    }

    /// The inputs `x` whose successor `x + 1 LSB` has its magnitude in
    /// another branch of `atan` (below 1, at 1, above 1).
    const ATAN_BRANCH_CROSSINGS: [i32; 4] = [(1 << 16) - 1, 1 << 16, -(1 << 16) - 1, -(1 << 16)];

    /// `atan` non-decreasing over every pair of adjacent inputs in one
    /// branch of the magnitude: the branch choice, the division-free ratio
    /// `a·2¹⁶` below 1 and the sign, with the two rounded cores and the
    /// quotient `⌊2⁴⁸/a⌋` by their order contracts, which the exhaustive
    /// engine checks at every argument `atan` passes. Split domain: the
    /// four pairs that cross a branch are
    /// `kani_atan_monotone_crossings_i16f16`'s. The core `atan_unit` alone
    /// is not monotone (it decreases at 1,390,503 of the 2³² steps
    /// `t → t + 1`), but each rounded core is over the arguments `atan`
    /// passes it. With the real kernel it timed out at 604 s.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::atan_rounded, atan_rounded_by_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::div_ratio, div_ratio_by_order_contract)]
    fn kani_atan_monotone_pair_i16f16() {
        let x = any_fixed();
        // Split domain (the complement is the next harness).
        kani::assume(!ATAN_BRANCH_CROSSINGS.contains(&x.to_bits()));
        assert!(monotone_at(k::atan, x).holds);
    }

    /// `atan` non-decreasing at the four pairs of adjacent inputs that
    /// cross a branch of the magnitude, with the real kernel (concrete
    /// arguments).
    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan_monotone_crossings_i16f16() {
        for b in ATAN_BRANCH_CROSSINGS {
            assert!(monotone_at(k::atan, I16F16::from_bits(b)).holds);
        }
    }

    static TAN_Q_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `tan_quotient` by its order contract (`tan_quotient_is_monotone`,
    /// checked at every magnitude of the domain by
    /// `exhaustive_tan_quotient_monotone_i16f16`): any quotient, and at a
    /// second call one in the order of the magnitudes (the same again for
    /// the same magnitude). The precondition `a < TAN_SAT_BITS` is asserted
    /// at each call.
    fn tan_quotient_by_contract(a: u32) -> u32 {
        assert!(a < k::TAN_SAT_BITS, "tan_quotient precondition");
        let q: u32 = kani::any();
        TAN_Q_FIRST.assume_in_order_u32(a, q, true);
        q
    }

    /// `tan` non-decreasing over every pair of adjacent inputs: the
    /// saturation at `TAN_SAT_BITS`, the final rounding of the quotient, its
    /// cap at `MAX` and the sign, with the quotient of the magnitude (the
    /// table polynomials and, beyond π/4, the division) by its order contract,
    /// which the exhaustive engine checks at each of the 102,942 magnitudes.
    /// With the real quotient (two copies of the polynomials and of the
    /// division) it timed out at 643 s.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::tan_quotient, tan_quotient_by_contract)]
    fn kani_tan_monotone_pair_i16f16() {
        assert!(monotone_at(k::tan, any_fixed()).holds);
    }

    static EXP2_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `exp2_frac` by its contract (`exp_contract_violations`,
    /// checked over every fraction `exp` passes by
    /// `exhaustive_exp_contracts_i16f16`): a value `m ≥ 2³¹`, and at a
    /// second call one in the order of the fractions (the same again for
    /// the same fraction). The precondition (a 47-bit fraction) is asserted
    /// at each call.
    fn exp2_frac_by_contract(f: u64) -> u32 {
        assert!(f < 1 << 47, "exp2_frac precondition");
        let m: u32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(m >= 1 << 31);
        if let Some((hi1, lo1, m1)) = EXP2_FIRST.first_or_record((f >> 32) as u32, f as u32, m) {
            let f1 = (hi1 as u64) << 32 | lo1 as u64;
            // postcondition of the stubbed function: the order lemma
            kani::assume(if f > f1 {
                m >= m1
            } else if f < f1 {
                m <= m1
            } else {
                m == m1
            });
        }
        m
    }

    static EXP_REDUCE_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static EXP_REDUCE_FIRST_LOW: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `exp_reduce` by its contract (`exp_contract_violations`, checked at
    /// every argument of its domain by
    /// `exhaustive_exp_contracts_i16f16`): `k ∈ [−18, 14]`,
    /// `f < 2⁴⁷`, and at a second call a `(k, f)` in the order of the
    /// arguments (lexicographic: `y = k + f·2⁻⁴⁷` is non-decreasing in `x`).
    /// The precondition (`EXP_ZERO_BITS ≤ bits < EXP_SAT_BITS`) is asserted
    /// at each call.
    fn exp_reduce_by_contract(bits: i32) -> (i32, u64) {
        assert!(
            (k::EXP_ZERO_BITS..k::EXP_SAT_BITS).contains(&bits),
            "exp_reduce precondition"
        );
        let kk: i32 = kani::any();
        let f: u64 = kani::any();
        // postcondition of the stubbed function: the ranges
        kani::assume((-18..=14).contains(&kk) && f < 1 << 47);
        let first = EXP_REDUCE_FIRST.first_or_record(bits as u32, kk as u32, (f >> 32) as u32);
        let low = EXP_REDUCE_FIRST_LOW.first_or_record(0, 0, f as u32);
        if let (Some((b1, k1, fh1)), Some((_, _, fl1))) = (first, low) {
            let (b1, k1) = (b1 as i32, k1 as i32);
            let f1 = (fh1 as u64) << 32 | fl1 as u64;
            // postcondition of the stubbed function: the order lemma
            kani::assume(if bits > b1 {
                kk > k1 || (kk == k1 && f >= f1)
            } else if bits < b1 {
                kk < k1 || (kk == k1 && f <= f1)
            } else {
                kk == k1 && f == f1
            });
        }
        (kk, f)
    }

    /// `exp` non-decreasing over every pair of adjacent inputs: the
    /// saturation and zero tests, the shift by `15 − k` across every change
    /// of `k` and the final rounding, with the reduction `y = x·log₂e =
    /// k + f` and the table-and-cubic core `2^f` by their contracts. With
    /// the real core (two copies of its six products) it timed out at
    /// 604 s, and with the real reduction (two copies of the product by
    /// `log₂e`) it did not finish in 600 s either.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::i16f16::exp_reduce, exp_reduce_by_contract)]
    #[kani::stub(crate::scalar::kernels::i16f16::exp2_frac, exp2_frac_by_contract)]
    fn kani_exp_monotone_pair_i16f16() {
        assert!(monotone_at(k::exp, any_fixed()).holds);
    }

    use crate::proofs::uninterpreted::Memo;
    static REDUCE: Memo<2> = Memo::new();
    static MULHI: Memo<2> = Memo::new();
    static SIN_POLY: Memo<2> = Memo::new();
    static ONE_MINUS_COS: Memo<2> = Memo::new();

    /// `reduce_half_pi` uninterpreted: any `(quadrant, ρ, sign)` for a new
    /// argument, the same again for the same argument. Postcondition of
    /// the stubbed function: the quadrant is `q & 3`, in `0..=3`.
    fn reduce_half_pi_uninterpreted(a: u32) -> (u32, u32, bool) {
        let v = REDUCE.call(u64::from(a));
        ((v >> 62) as u32, v as u32, (v >> 32) & 1 == 1)
    }

    fn mulhi_uninterpreted(a: u32, b: u32) -> u32 {
        MULHI.call(u64::from(a) << 32 | u64::from(b)) as u32
    }

    fn sin_poly_uninterpreted(rho: u32, z: u32) -> u32 {
        SIN_POLY.call(u64::from(rho) << 32 | u64::from(z)) as u32
    }

    fn one_minus_cos_poly_uninterpreted(z: u32) -> u32 {
        ONE_MINUS_COS.call(u64::from(z)) as u32
    }

    /// `sin_cos(x) == (sin x, cos x)` bit for bit at every input: the
    /// quadrant and sign selection and the rounding to `I16F16`, with the
    /// shared cores (the reduction, `mulhi` and the two polynomials) as
    /// uninterpreted functions (`proofs/uninterpreted.rs`). With the real
    /// cores the solver had to prove three copies of the same integer
    /// multipliers equal, and did not in 602 s. The exhaustive engine
    /// checks the property with the real cores at all 2³² inputs.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::i16f16::reduce_half_pi,
        reduce_half_pi_uninterpreted
    )]
    #[kani::stub(crate::scalar::kernels::i16f16::mulhi, mulhi_uninterpreted)]
    #[kani::stub(crate::scalar::kernels::i16f16::sin_poly, sin_poly_uninterpreted)]
    #[kani::stub(
        crate::scalar::kernels::i16f16::one_minus_cos_poly,
        one_minus_cos_poly_uninterpreted
    )]
    fn kani_sin_cos_is_sin_and_cos_i16f16() {
        assert!(sin_cos_is_sin_and_cos(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan_i16f16() {
        assert!(atan_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_tan_i16f16() {
        assert!(tan_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_exp_i16f16() {
        let x = any_fixed();
        // solver budget: the float reference is costly; restrict to the
        // non-saturated, non-flushed range (the rest is constant-valued).
        kani::assume(x.to_bits() > -12 << 16 && x.to_bits() < 681392);
        assert!(exp_within_bound(x).holds);
    }

    #[kani::proof]
    fn kani_sin_i16f16() {
        assert!(sin_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    fn kani_cos_i16f16() {
        assert!(cos_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_atan2_i16f16() {
        assert!(atan2_within_bound(any_fixed(), any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(40)]
    fn kani_acos_i16f16() {
        assert!(acos_within_bound(any_fixed()).holds);
    }

    #[kani::proof]
    #[kani::unwind(30)]
    fn kani_sqrt_i16f16() {
        assert!(sqrt_within_bound(any_fixed()).holds);
    }
}

// ---- exhaustive and random ---------------------------------------------------

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::engine::exhaustive_u32;
    use super::*;
    use core::cell::Cell;
    use proptest::prelude::*;
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::sync::Mutex;
    use std::time::Instant;
    use std::{eprintln, println};

    /// Largest error seen by any worker, and where (the shared word is read
    /// on every input but written only when the maximum grows).
    struct MaxTracker {
        bits: AtomicU64,
        at: Mutex<(f64, u32)>,
    }

    impl MaxTracker {
        fn new() -> Self {
            MaxTracker {
                bits: AtomicU64::new(0),
                at: Mutex::new((0.0, 0)),
            }
        }
        fn note(&self, err: f64, code: u32) {
            if err.to_bits() > self.bits.load(Ordering::Relaxed) {
                let mut g = self.at.lock().unwrap();
                if err > g.0 {
                    *g = (err, code);
                    self.bits.fetch_max(err.to_bits(), Ordering::Relaxed);
                }
            }
        }
        fn get(&self) -> (f64, u32) {
            *self.at.lock().unwrap()
        }
    }

    fn line(kernel: &str, domain: &str, bound: &str, err: f64, at: &str, checked: u64) {
        println!(
            "PROOF kernel={kernel} backend=I16F16 domain={domain} bound={bound} max_err={err:.6} LSB at={at} checked={checked} engine=exhaustive"
        );
    }

    fn show(code: u32) -> std::string::String {
        std::format!("{}", from_code(code))
    }

    fn show_ordered(code: u32) -> std::string::String {
        std::format!("{}", ordered(code))
    }

    fn show_pair(code: u32) -> std::string::String {
        let (y, x) = lattice_pair(code);
        std::format!("(y={y},x={x})")
    }

    std::thread_local! {
        /// The previous code of this worker and its kernel result, so the
        /// monotonicity check `f(x−δ) ≤ f(x)` costs no extra evaluation.
        static PREV: Cell<(u32, i32)> = const { Cell::new((u32::MAX, 0)) };
    }

    /// One pass over every input in value order ([`ordered`]): the error
    /// bound (and symmetry) of `check`, and, if `monotone`, `f(x−δ) ≤ f(x)`.
    /// Prints the bound line and the monotonicity line; fails on any
    /// counter-example, naming the first one and what broke.
    fn run(
        kernel: &str,
        domain: &str,
        bound: &str,
        f: fn(I16F16) -> I16F16,
        check: fn(I16F16, I16F16) -> Verdict,
        monotone: bool,
    ) {
        let t = Instant::now();
        let mono_ok = |c: u32, got: I16F16| -> bool {
            if !monotone || c == 0 {
                return true;
            }
            let prev = PREV.with(|p| {
                let (pc, pv) = p.get();
                if pc == c - 1 {
                    pv
                } else {
                    f(ordered(c - 1)).to_bits()
                }
            });
            prev <= got.to_bits()
        };
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let x = ordered(c);
            let got = f(x);
            let v = check(x, got).and(Verdict::logical(mono_ok(c, got)));
            PREV.with(|p| p.set((c, got.to_bits())));
            v
        });
        eprintln!("({kernel}: {:.1} s)", t.elapsed().as_secs_f64());
        if let Some(c) = r.first_failure {
            let x = ordered(c);
            let prev = if c > 0 { f(ordered(c - 1)) } else { f(x) };
            panic!(
                "{kernel}: {} failures; first at x={x} (bits {}): got {}, check {:?}, monotone {} (f(x-δ)={prev}); max_err={} LSB at {}",
                r.failures,
                x.to_bits(),
                f(x),
                check(x, f(x)),
                prev <= f(x),
                r.max_error,
                show_ordered(r.argmax),
            );
        }
        line(
            kernel,
            domain,
            bound,
            r.max_error,
            &show_ordered(r.argmax),
            r.checked,
        );
        if monotone {
            line(kernel, "all", "monotone", 0.0, "-", r.checked);
        }
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_i16f16() {
        run("atan", "all", "1 LSB", k::atan, atan_check, true);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_i16f16() {
        run(
            "tan",
            "|x|<pi/2,outside=+-MAX",
            "1 LSB",
            k::tan,
            tan_check,
            true,
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_i16f16() {
        run(
            "exp",
            "all,sat=MAX",
            "2 LSB(1 LSB for e^x<=4096)",
            k::exp,
            exp_check,
            true,
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_neg_abs_i16f16() {
        run(
            "exp_neg_abs",
            "all,zero-from-17ln2",
            "1 LSB,even,non-increasing-in-|x|",
            k::exp_neg_abs,
            exp_neg_abs_check,
            false,
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_i16f16() {
        run("sqrt", "x>=0,neg=0", "0.5 LSB", k::sqrt, sqrt_check, true);
    }

    /// The contracts of `exp`'s reduction and core, by which
    /// `kani_exp_monotone_pair_i16f16` stubs them. `exp_reduce(bits) = (k, f)`
    /// at every `bits` of its domain `[EXP_ZERO_BITS, EXP_SAT_BITS)`:
    /// `k ∈ [−18, 14]`, `f < 2⁴⁷`, and `(k, f)` non-decreasing
    /// (lexicographically) from each argument to the next, hence over every
    /// pair. `exp2_frac(f) = m` over the fractions that reduction produces
    /// (the only arguments `exp` passes): every `m` is at least `2³¹` (so
    /// `2^(k+1)` at the smallest fraction is at least `2^k` at the largest),
    /// and `m` is non-decreasing in `f` over those fractions (sorted by `f`,
    /// each adjacent pair once). Returns the number of fractions checked and
    /// the number of violations of either contract.
    pub fn exp_contract_violations() -> (usize, usize) {
        let mut pairs: std::vec::Vec<(u64, u32)> = (k::EXP_ZERO_BITS..k::EXP_SAT_BITS)
            .map(|bits| {
                let f = k::exp_reduce(bits).1;
                (f, k::exp2_frac(f))
            })
            .collect();
        // exp_reduce's contract: ranges, and (k, f) non-decreasing
        // (lexicographic) from each argument to the next.
        let reduce_bad = (k::EXP_ZERO_BITS..k::EXP_SAT_BITS)
            .filter(|&bits| {
                let (kk, f) = k::exp_reduce(bits);
                let in_range = (-18..=14).contains(&kk) && f < 1 << 47;
                let ordered = bits + 1 == k::EXP_SAT_BITS || (kk, f) <= k::exp_reduce(bits + 1);
                !(in_range && ordered)
            })
            .count();
        pairs.sort_unstable();
        let low = pairs.iter().filter(|&&(_, m)| m < 1 << 31).count();
        let order = pairs.windows(2).filter(|w| w[1].1 < w[0].1).count();
        (pairs.len(), low + order + reduce_bad)
    }

    /// The contracts by which `kani_atan_monotone_pair_i16f16` stubs
    /// `atan`'s parts, and the identity of `atan`'s branches with the
    /// two-argument form `round_q30(atan2_mag(a, 2¹⁶))`, at every magnitude
    /// `a ≤ 2³¹`: `atan_rounded(·, false)` non-decreasing and in `[0, 2¹⁹]` over
    /// `t = a·2¹⁶` (`a < 2¹⁶`); `div_ratio(2¹⁶, a)` non-increasing in `a`
    /// and `atan_rounded(·, true)` non-increasing in `t` along it, in `[0, 2¹⁹]`
    /// (`2¹⁶ < a ≤ 2³¹`; consecutive magnitudes, so every pair of
    /// arguments). Returns the number of violations. Two threads.
    pub fn atan_contract_violations() -> u64 {
        const ONE: u32 = 1 << 16;
        let one = ONE;
        let same = |a: u32| {
            let one = ONE;
            let branch = if a < one {
                k::atan_rounded(a << 16, false)
            } else if a == one {
                k::round_q30(k::PIO4_Q30)
            } else {
                k::atan_rounded(k::div_ratio(one, a), true)
            };
            branch == k::round_q30(k::atan2_mag(a, one))
        };
        let mut bad = 0u64;
        for a in 0..one {
            let v = k::atan_rounded(a << 16, false);
            bad += u64::from(!(0..=1 << 19).contains(&v) || !same(a));
            if a + 1 < one {
                bad += u64::from(k::atan_rounded((a + 1) << 16, false) < v);
            }
        }
        bad += u64::from(!same(one));
        let high = move |lo: u32, hi: u32| {
            move || {
                let one = ONE;
                let mut bad = 0u64;
                let mut prev: Option<(u32, i32)> = None;
                for a in lo..=hi {
                    let t = k::div_ratio(one, a);
                    let v = k::atan_rounded(t, true);
                    bad += u64::from(!(0..=1 << 19).contains(&v) || !same(a));
                    if let Some((pt, pv)) = prev {
                        bad += u64::from(t > pt || (t < pt && v < pv) || (t == pt && v != pv));
                    }
                    prev = Some((t, v));
                }
                bad
            }
        };
        let mid = 1u32 << 30;
        let first = std::thread::spawn(high(one + 1, mid));
        // The second half starts at `mid` so the pair (mid, mid + 1) is checked.
        let second = std::thread::spawn(high(mid, 1 << 31));
        bad + first.join().unwrap() + second.join().unwrap()
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_contracts_i16f16() {
        let bad = atan_contract_violations();
        assert_eq!(
            bad, 0,
            "atan's branch contracts violated at {bad} magnitudes"
        );
        std::println!("PROOF kernel=atan_rounded,div_ratio(2^16,a) backend=I16F16 domain=every-magnitude bound=order-contracts,atan2_mag-identity checked=2147483649 engine=exhaustive");
    }

    /// The magnitudes `a < TAN_SAT_BITS − 1` at which `tan_quotient(a + 1) <
    /// tan_quotient(a)`: none, which is the contract
    /// `kani_tan_monotone_pair_i16f16` stubs `tan`'s quotient by.
    pub fn tan_quotient_is_monotone() -> usize {
        (0..k::TAN_SAT_BITS - 1)
            .filter(|&a| k::tan_quotient(a + 1) < k::tan_quotient(a))
            .count()
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_quotient_monotone_i16f16() {
        let bad = tan_quotient_is_monotone();
        assert_eq!(bad, 0, "tan_quotient decreases at {bad} magnitudes");
        std::println!("PROOF kernel=tan_quotient backend=I16F16 domain=0..TAN_SAT_BITS bound=non-decreasing checked={} engine=exhaustive", k::TAN_SAT_BITS);
    }

    /// `exp_contract_violations`: the contracts
    /// `kani_exp_monotone_pair_i16f16` stubs `exp`'s reduction and core by,
    /// at every argument `exp` passes to them.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_contracts_i16f16() {
        let (n, bad) = exp_contract_violations();
        assert!(n > 1_400_000, "{n}");
        assert_eq!(
            bad, 0,
            "exp_reduce / exp2_frac contracts violated at {bad} arguments"
        );
        std::println!("PROOF kernel=exp_reduce,exp2_frac backend=I16F16 domain=every-argument-exp-passes bound=contracts checked={n} engine=exhaustive");
    }

    /// [`sqrt_q16_is_exact`] at every argument `sqrt` passes (`0 < n <
    /// 2³¹`): the contract `kani_sqrt_monotone_pair_i16f16` stubs the root
    /// by. Two threads, one per half.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_q16_exact() {
        let half = |lo: u32, hi: u32| move || (lo..hi).filter(|&n| !sqrt_q16_is_exact(n)).count();
        let a = std::thread::spawn(half(1, 1 << 30));
        let b = std::thread::spawn(half(1 << 30, 1 << 31));
        let bad = a.join().unwrap() + b.join().unwrap();
        assert_eq!(bad, 0, "sqrt_q16 not exact at {bad} arguments");
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_acos_i16f16() {
        run(
            "acos",
            "[-1,1],clamped",
            "1 LSB",
            k::acos,
            acos_check,
            false,
        );
    }

    /// `sin`, `cos` and `sin_cos` in one pass (one reference evaluation of
    /// each): bounds, `sin_cos ≡ (sin, cos)`, `sin` odd and `cos` even.
    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_cos_i16f16() {
        let t = Instant::now();
        let (ms, mc) = (MaxTracker::new(), MaxTracker::new());
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let x = from_code(c);
            let (es, ec, ok) = sin_cos_check(x, k::sin_cos(x));
            ms.note(es, c);
            mc.note(ec, c);
            Verdict::bounded(es, 1.0)
                .and(Verdict::bounded(ec, 1.0))
                .and(Verdict::logical(ok))
        });
        eprintln!("(sin_cos: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(
            r.failures,
            0,
            "first failure at {:?}",
            r.first_failure.map(show)
        );
        let (es, cs) = ms.get();
        let (ec, cc) = mc.get();
        line("sin", "all", "1 LSB", es, &show(cs), r.checked);
        line("cos", "all", "1 LSB", ec, &show(cc), r.checked);
        line("sin_cos", "all", "exact=(sin,cos)", 0.0, "-", r.checked);
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan2_i16f16() {
        let t = Instant::now();
        let r = exhaustive_u32(0, u32::MAX, |c| {
            let (y, x) = lattice_pair(c);
            atan2_within_bound(y, x)
        });
        eprintln!("(atan2: {:.1} s)", t.elapsed().as_secs_f64());
        assert_eq!(
            r.failures,
            0,
            "first failure at {:?}",
            r.first_failure.map(show_pair)
        );
        line(
            "atan2",
            "all-I8F8-pairs",
            "1 LSB",
            r.max_error,
            &show_pair(r.argmax),
            r.checked,
        );
    }

    // -- fast, non-ignored checks ------------------------------------------

    fn fx(v: f64) -> I16F16 {
        <I16F16 as Scalar>::from_f64(v)
    }

    #[test]
    fn hand_values() {
        assert_eq!(k::atan(I16F16::ZERO), I16F16::ZERO);
        assert_eq!(k::atan(I16F16::ONE), fx(core::f64::consts::FRAC_PI_4));
        assert_eq!(k::sqrt(fx(2.25)), fx(1.5));
        assert_eq!(k::sqrt(fx(-1.0)), I16F16::ZERO);
        assert_eq!(k::exp(I16F16::ZERO), I16F16::ONE);
        assert_eq!(k::exp(I16F16::MAX), I16F16::MAX);
        assert_eq!(k::exp(I16F16::MIN), I16F16::ZERO);
        assert_eq!(k::tan(fx(2.0)), I16F16::MAX);
        assert_eq!(k::tan(fx(-2.0)), -I16F16::MAX);
        assert_eq!(k::tan(I16F16::MIN), -I16F16::MAX);
        assert_eq!(k::acos(fx(1.0)), I16F16::ZERO);
        assert_eq!(k::acos(fx(5.0)), I16F16::ZERO);
        assert_eq!(k::acos(fx(-5.0)), fx(core::f64::consts::PI));
        assert_eq!(k::atan2(I16F16::ZERO, I16F16::ZERO), I16F16::ZERO);
        assert_eq!(
            k::atan2(I16F16::ZERO, -I16F16::ONE),
            fx(core::f64::consts::PI)
        );
        assert_eq!(k::sin_cos(I16F16::ZERO), (I16F16::ZERO, I16F16::ONE));
    }

    #[test]
    fn building_blocks_on_edges() {
        for &a in &[0u32, 1, 0xFFFF, 0x1_0000, 0x8000_0000, u32::MAX] {
            for &b in &[0u32, 1, 0xFFFF, 0x1_0000, 0x8000_0000, u32::MAX] {
                assert!(mulhi_is_exact(a, b));
            }
        }
        assert!(div_ratio_is_exact(0x7FFF_FFFF, 0x8000_0000));
        assert!(div_ratio_is_exact(1, 0x8000_0000));
        assert!(div_ratio_is_exact(0, 1));
        assert!(div_ratio_is_exact(0xFFFF, 0x1_0000));
        assert!(sqrt_q16_is_exact(u32::MAX));
        assert!(sqrt_q16_is_exact(0));
    }

    /// Dense grid at the axes and at tiny magnitudes, where a known I16F16
    /// `atan2` is off by up to 2.3 rad: `y, x ∈ {±0..64 LSB}` and one
    /// coordinate tiny while the other spans large values.
    #[test]
    fn atan2_dense_near_axes_and_tiny() {
        let mut worst = 0.0f64;
        for yb in -64..=64 {
            for xb in -64..=64 {
                let v = atan2_within_bound(I16F16::from_bits(yb), I16F16::from_bits(xb));
                assert!(v.holds, "atan2({yb}, {xb}) LSB err {}", v.error);
                worst = worst.max(v.error);
            }
        }
        let big = [
            1i32,
            3,
            255,
            65535,
            65536,
            1 << 20,
            1 << 24,
            i32::MAX,
            i32::MIN,
            -(1 << 24),
        ];
        for tiny in -16..=16 {
            for &b in &big {
                for (y, x) in [(tiny, b), (b, tiny)] {
                    let v = atan2_within_bound(I16F16::from_bits(y), I16F16::from_bits(x));
                    assert!(v.holds, "atan2 bits ({y}, {x}) LSB err {}", v.error);
                    worst = worst.max(v.error);
                }
            }
        }
        assert!(worst <= 1.0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Full-range I16F16 pairs (every bit pattern equally likely).
        #[test]
        fn atan2_full_range(y in any::<i32>(), x in any::<i32>()) {
            let v = atan2_within_bound(I16F16::from_bits(y), I16F16::from_bits(x));
            prop_assert!(v.holds, "err {}", v.error);
        }

        /// `atan_small` and `hypot_unit` on every bit pattern (clamped
        /// beyond their domains).
        #[test]
        fn atan_small_and_hypot_unit_full_range(a in any::<i32>(), b in any::<i32>()) {
            let (x, y) = (I16F16::from_bits(a), I16F16::from_bits(b));
            let v = atan_small_within_bound(x);
            prop_assert!(v.holds, "atan_small err {}", v.error);
            let v = hypot_unit_within_bound(x, y);
            prop_assert!(v.holds, "hypot_unit err {}", v.error);
            // Unit-range pairs, where it is used.
            let v = hypot_unit_within_bound(I16F16::from_bits(a >> 15), I16F16::from_bits(b >> 15));
            prop_assert!(v.holds, "hypot_unit err {}", v.error);
        }

        /// `unit_vector` and `rsqrt_quarter` on every bit pattern, and on
        /// unit-range pairs (where the wrist uses them).
        #[test]
        fn unit_vector_and_rsqrt_quarter_full_range(a in any::<i32>(), b in any::<i32>()) {
            let (x, y) = (I16F16::from_bits(a), I16F16::from_bits(b));
            let v = unit_vector_within_bound(x, y);
            prop_assert!(v.holds, "unit_vector err {}", v.error);
            let v = unit_vector_within_bound(I16F16::from_bits(a >> 15), I16F16::from_bits(b >> 15));
            prop_assert!(v.holds, "unit_vector err {}", v.error);
            let v = rsqrt_quarter_within_bound(x);
            prop_assert!(v.holds, "rsqrt_quarter err {}", v.error);
            let v = rsqrt_quarter_within_bound(I16F16::from_bits(a >> 15));
            prop_assert!(v.holds, "rsqrt_quarter err {}", v.error);
        }

        /// Joint angles within ±4 turns.
        #[test]
        fn sin_cos_joint_angles(a in -25.0f64..25.0) {
            let x = fx(a);
            prop_assert!(sin_within_bound(x).holds);
            prop_assert!(cos_within_bound(x).holds);
        }

        /// Slopes and ratios met by the kinematics.
        #[test]
        fn atan_ratios(a in -200.0f64..200.0) {
            let x = fx(a);
            prop_assert!(atan_within_bound(x).holds);
            prop_assert!(atan_within_bound(-x).holds);
            prop_assert!(monotone_at(k::atan, x).holds);
        }

        /// Angles inside the principal branch.
        #[test]
        fn tan_branch(a in -1.57f64..1.57) {
            let x = fx(a);
            prop_assert!(tan_within_bound(x).holds);
            prop_assert!(monotone_at(k::tan, x).holds);
        }

        /// Stribeck / exponential-decay exponents.
        #[test]
        fn exp_exponents(a in -13.0f64..10.5) {
            let x = fx(a);
            prop_assert!(exp_within_bound(x).holds);
            prop_assert!(monotone_at(k::exp, x).holds);
        }

        /// Exponents of the decaying exponentials, up to where they vanish.
        #[test]
        fn exp_neg_abs_exponents(a in -12.5f64..12.5) {
            prop_assert!(exp_neg_abs_within_bound(fx(a)).holds);
        }

        /// Cosines of joint angles and a margin outside [-1, 1].
        #[test]
        fn acos_cosines(a in -1.2f64..1.2) {
            prop_assert!(acos_within_bound(fx(a)).holds);
        }

        /// Squared norms of forces/velocities.
        #[test]
        fn sqrt_norms(a in -10.0f64..30000.0) {
            let x = fx(a);
            prop_assert!(sqrt_within_bound(x).holds);
            prop_assert!(monotone_at(k::sqrt, x).holds);
        }

        #[test]
        fn building_blocks_exact(a in any::<u32>(), b in any::<u32>(), d in 1u32..=(1 << 31)) {
            prop_assert!(mulhi_is_exact(a, b));
            prop_assert!(div_ratio_is_exact(a % d, d));
            prop_assert!(sqrt_q16_is_exact(a));
        }
    }
}
