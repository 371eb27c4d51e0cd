//! Properties of the `f32` kernels (`src/scalar/kernels/f32.rs`).
//!
//! Each property is a plain function of the kernel's input(s), returning a
//! [`Verdict`]; the engines that run it:
//!
//! * **Exhaustive** — `exhaustive_*_f32` below, every `f32` bit pattern of the
//!   kernel's domain (`atan2`: a 4096 × 4096 grid of codes). These are the
//!   proofs of the bounds stated on the kernels. Each prints one line
//!   `PROOF kernel=… backend=f32 domain=… bound=… max_err=… at=… checked=…
//!   engine=exhaustive` (the kernel table of docs/verification.md is built from them). Run:
//!   `cargo test --release --lib -- --ignored exhaustive_ --test-threads 1 --nocapture`
//!   (about 6–8 minutes for this file on two cores).
//! * **Random** — `proptest` over physically meaningful ranges (motor angles,
//!   force ratios, exponents of the friction and stiffness models), in plain
//!   `cargo test`.
//! * **Kani** — `kani_*_f32` entries wrapping the same bodies.
//!
//! The reference is the `f64` function of `std` in tests (glibc/LLVM, < 1 ulp
//! of `f64`, i.e. ~2^-29 `f32` ulp) and the `libm` crate under Kani (`no_std`).
//! Errors are measured by [`ulp_error_f32`]: in ulp of the `f32` binade of
//! the reference, subnormal results in `2^-149`.

use super::engine::{ulp_error_f32, Verdict};
use crate::scalar::kernels::f32 as k;

/// Proven bounds (ulp), as stated on the kernels.
pub const ATAN_BOUND: f64 = 2.0;
/// See [`ATAN_BOUND`].
pub const TAN_BOUND: f64 = 2.0;
/// See [`ATAN_BOUND`].
pub const EXP_BOUND: f64 = 2.0;
/// See [`ATAN_BOUND`].
pub const SIN_COS_BOUND: f64 = 2.0;
/// See [`ATAN_BOUND`].
pub const ATAN2_BOUND: f64 = 2.0;
/// See [`ATAN_BOUND`].
pub const ACOS_BOUND: f64 = 2.0;
/// Correct rounding.
pub const SQRT_BOUND: f64 = 0.5;

/// The `f64` reference functions: `std` in tests, `libm` under Kani.
mod reference {
    #[cfg(not(test))]
    pub use libm::{acos, atan, atan2, cos, exp, sin, sqrt, tan};

    macro_rules! std_reference {
        ($($name:ident),*) => {$(
            #[cfg(test)]
            pub fn $name(x: f64) -> f64 {
                x.$name()
            }
        )*};
    }
    std_reference!(acos, atan, cos, exp, sin, sqrt, tan);

    #[cfg(test)]
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
}

/// The next `f32` above `x` (for finite `x` or `-∞`; `-0.0` → smallest
/// positive subnormal).
pub fn next_up(x: f32) -> f32 {
    let b = x.to_bits();
    if b == 0x8000_0000 {
        f32::from_bits(1)
    } else if b >> 31 == 0 {
        f32::from_bits(b + 1)
    } else {
        f32::from_bits(b - 1)
    }
}

/// `f(next_up(x)) ≥ f(x)` for every non-NaN `x < +∞`: over all codes this
/// is monotonicity over every pair of adjacent `f32`s.
fn monotone_at(f: fn(f32) -> f32, x: f32) -> Verdict {
    if x.is_nan() || x == f32::INFINITY {
        return Verdict::logical(true);
    }
    Verdict::logical(f(next_up(x)) >= f(x))
}

/// `f(-x) = -f(x)` bit for bit (non-NaN `x`).
fn odd_at(f: fn(f32) -> f32, x: f32) -> Verdict {
    if x.is_nan() {
        return Verdict::logical(true);
    }
    Verdict::logical(f(-x).to_bits() == (-f(x)).to_bits())
}

fn within(got: f32, reference: f64, bound: f64) -> Verdict {
    Verdict::bounded(ulp_error_f32(got, reference), bound)
}

// ---------------------------------------------------------------- atan ----

/// `atan` is within [`ATAN_BOUND`] of `atan(x)` (NaN: exactly 0).
/// Engines: exhaustive (every `f32`), random, Kani.
pub fn atan_within_bound(x: f32) -> Verdict {
    if x.is_nan() {
        return Verdict::logical(k::atan(x) == 0.0 && k::atan(-x) == 0.0);
    }
    within(k::atan(x), reference::atan(x as f64), ATAN_BOUND)
}

/// `atan` is non-decreasing at `x`. Engines: exhaustive, Kani.
pub fn atan_monotone_at(x: f32) -> Verdict {
    monotone_at(k::atan, x)
}

/// The contract of `recip` (`1/t`) at `x`: non-increasing over the positive
/// `f32`s and `+∞` (checked between `x` and its successor), at least 1 on
/// `(0, 1]` (the arguments `tan` passes) and in `[0, 0.6]` above
/// `ATAN_HIGH` (the arguments `atan` passes). Vacuous at `x ≤ 0` and NaN.
pub fn recip_contract_at(x: f32) -> Verdict {
    if x.is_nan() || x <= 0.0 {
        return Verdict::logical(true);
    }
    let r = k::recip(x);
    let mut ok = (x > 1.0 || r >= 1.0) && (x <= k::ATAN_HIGH || (0.0..=0.6).contains(&r));
    if x < f32::INFINITY {
        ok &= k::recip(next_up(x)) <= r;
    }
    Verdict::logical(ok)
}

/// The contracts by which `kani_atan_monotone_f32` stubs `atan`'s
/// polynomial and middle-branch ratio, at the non-negative `x` (and its
/// negative, for the polynomial):
///
/// * `atan_poly` on `[−0.6, 0.6]`: non-decreasing (between `x` and its
///   successor, and between `−next_up(x)` and `−x`), with the sign of its
///   argument (`≥ 0` for `u ≥ 0`, `≤ 0` for `u ≤ 0`) and `|p| ≤ 0.6`;
/// * `atan_mid_ratio` on `(0.6, ATAN_HIGH]`: in `[−¼, ¼]`, non-decreasing;
/// * `recip` ([`recip_contract_at`]).
pub fn atan_contracts_at(x: f32) -> Verdict {
    if x.is_nan() || x < 0.0 {
        return Verdict::logical(true);
    }
    let mut ok = true;
    if x <= k::ATAN_LOW {
        let (p, q) = (k::atan_poly(x), k::atan_poly(-x));
        ok &= (0.0..=0.6).contains(&p) && (-0.6..=0.0).contains(&q);
        let xn = next_up(x);
        if xn <= k::ATAN_LOW {
            ok &= k::atan_poly(xn) >= p && k::atan_poly(-xn) <= q;
        }
    } else if x <= k::ATAN_HIGH {
        let v = k::atan_mid_ratio(x);
        ok &= (-0.25..=0.25).contains(&v);
        let xn = next_up(x);
        if xn <= k::ATAN_HIGH {
            ok &= k::atan_mid_ratio(xn) >= v;
        }
    }
    Verdict::logical(ok).and(recip_contract_at(x))
}

/// `atan(-x) = -atan(x)` exactly. Engines: exhaustive, Kani.
pub fn atan_odd_at(x: f32) -> Verdict {
    odd_at(k::atan, x)
}

// ----------------------------------------------------------------- tan ----

/// `tan` is within [`TAN_BOUND`] of `tan(x)` for `|x| ≤ TAN_DOMAIN_EDGE`, and
/// equals `±tan(TAN_DOMAIN_EDGE)` (sign of `x`) outside (NaN: exactly 0).
/// Engines: exhaustive (every `f32`), random, Kani.
pub fn tan_within_bound(x: f32) -> Verdict {
    if x.is_nan() {
        return Verdict::logical(k::tan(x) == 0.0 && k::tan(-x) == 0.0);
    }
    if x > k::TAN_DOMAIN_EDGE {
        return Verdict::logical(k::tan(x) == k::tan(k::TAN_DOMAIN_EDGE));
    }
    if x < -k::TAN_DOMAIN_EDGE {
        return Verdict::logical(k::tan(x) == -k::tan(k::TAN_DOMAIN_EDGE));
    }
    within(k::tan(x), reference::tan(x as f64), TAN_BOUND)
}

/// `tan` is non-decreasing at `x` (over every `f32`, saturation included).
/// Engines: exhaustive, Kani.
pub fn tan_monotone_at(x: f32) -> Verdict {
    monotone_at(k::tan, x)
}

/// The order of `tan_poly`'s arguments: `(d, d_lo)` lexicographically,
/// which is the order of the real values `d + d_lo` (each `d + d_lo` lies
/// in the rounding interval of `d`).
pub fn tan_poly_args_below(d1: f32, lo1: f32, d2: f32, lo2: f32) -> bool {
    d1 < d2 || (d1 == d2 && lo1 < lo2)
}

/// The range part of `tan_poly`'s contract at the arguments `tan` passes:
/// `t ∈ [0, 1]`, and `t > 0` when `d > 0`.
pub fn tan_poly_in_range(d: f32, t: f32) -> bool {
    (0.0..=1.0).contains(&t) && (d == 0.0 || t > 0.0)
}

/// The contracts by which `kani_tan_monotone_f32` stubs `tan`'s core, at
/// the non-negative `x`:
///
/// * `tan_poly` over its argument set `S` (`(d, 0)` for every
///   `0 ≤ d < π/4`, the direct branch, and `tan_reflect(ax)` for every
///   `π/4 < ax ≤ TAN_DOMAIN_EDGE`, the reflection): in range
///   ([`tan_poly_in_range`]) and non-decreasing along `S` in the order of
///   [`tan_poly_args_below`]. Checked as three chains that together order
///   every pair of `S`: the direct arguments `x`, `next_up(x)`; the
///   reflected ones at `ax`, `next_up(ax)` (strictly decreasing
///   arguments, so no two share a `d`); and each reflected `(d, d_lo)`
///   between the direct neighbours of `d` on the side of `d_lo`.
/// * `recip` ([`recip_contract_at`]).
pub fn tan_contracts_at(x: f32) -> Verdict {
    if x.is_nan() || x < 0.0 {
        return Verdict::logical(true);
    }
    let up = f32::from_bits(k::FRAC_PI_4_UP);
    let direct = |d: f32| k::tan_poly(d, 0.0);
    let mut ok = true;
    if x < up {
        let t = direct(x);
        ok &= tan_poly_in_range(x, t);
        let xn = next_up(x);
        if xn < up {
            ok &= direct(xn) >= t;
        }
    } else if x <= k::TAN_DOMAIN_EDGE {
        let (d, lo) = k::tan_reflect(x);
        let t = k::tan_poly(d, lo);
        ok &= d > 0.0 && d < up && tan_poly_in_range(d, t);
        ok &= if lo > 0.0 {
            direct(d) <= t && t <= direct(next_up(d))
        } else if lo < 0.0 {
            direct(f32::from_bits(d.to_bits() - 1)) <= t && t <= direct(d)
        } else {
            t == direct(d)
        };
        let xn = next_up(x);
        if xn <= k::TAN_DOMAIN_EDGE {
            let (dn, lon) = k::tan_reflect(xn);
            ok &= tan_poly_args_below(dn, lon, d, lo) && k::tan_poly(dn, lon) <= t;
        }
    }
    Verdict::logical(ok).and(recip_contract_at(x))
}

/// `tan(-x) = -tan(x)` exactly. Engines: exhaustive, Kani.
pub fn tan_odd_at(x: f32) -> Verdict {
    odd_at(k::tan, x)
}

/// `tan_bounded` is bit for bit `tan` for `|x| ≤ TAN_BOUNDED_MAX` and
/// `±tan(TAN_BOUNDED_MAX)` beyond (NaN included, with its sign bit), so it
/// inherits `tan`'s proven bound, monotonicity and oddness on its domain
/// and stays non-decreasing and odd beyond. Engines: exhaustive, random.
pub fn tan_bounded_is_tan_on_its_domain(x: f32) -> Verdict {
    let got = k::tan_bounded(x).to_bits();
    let sign = x.to_bits() & 0x8000_0000;
    let a = f32::from_bits(x.to_bits() & !0x8000_0000);
    let want = if a <= k::TAN_BOUNDED_MAX {
        k::tan(x).to_bits()
    } else {
        k::tan(k::TAN_BOUNDED_MAX).to_bits() | sign
    };
    Verdict::logical(got == want && k::tan_bounded(-x).to_bits() == got ^ 0x8000_0000)
}

// ----------------------------------------------------------------- exp ----

/// `exp` is within [`EXP_BOUND`] of `e^x` for `x ≤ EXP_MAX_ARG` (subnormal
/// and flushed results included); above, `e^x` overflows `f32` and the
/// result is `f32::MAX` (NaN: exactly 1). Engines: exhaustive, random, Kani.
pub fn exp_within_bound(x: f32) -> Verdict {
    if x.is_nan() {
        return Verdict::logical(k::exp(x) == 1.0);
    }
    let reference = reference::exp(x as f64);
    if x > k::EXP_MAX_ARG {
        // Saturation is only allowed where the rounded e^x is infinite.
        let overflows = reference >= f32::MAX as f64 * (1.0 + 1.0 / 16_777_216.0);
        return Verdict::logical(k::exp(x) == f32::MAX && overflows);
    }
    within(k::exp(x), reference, EXP_BOUND)
}

/// `exp` is non-decreasing at `x`. Engines: exhaustive, Kani.
pub fn exp_monotone_at(x: f32) -> Verdict {
    monotone_at(k::exp, x)
}

/// The range part of the contract of `exp`'s reduction `exp_reduced(x) =
/// (p, k)` (`e^x ≈ p·2^k`) on its domain `EXP_MIN_ARG ≤ x ≤ EXP_MAX_ARG`:
/// `k ∈ [−150, 128]`, `p ∈ [½, 2)`, and `p < 1` when `k = 128` (so that
/// `p·2^k` is finite). Checked at every argument by `exhaustive_exp_f32`.
pub fn exp_reduced_in_range(p: f32, k: i32) -> bool {
    (-150..=128).contains(&k) && (0.5..2.0).contains(&p) && (k < 128 || p < 1.0)
}

/// The order part of the contract of `exp_reduced`: for arguments
/// `x1 < x2` of its domain with `(p1, k1)`, `(p2, k2)` in range
/// ([`exp_reduced_in_range`]), `k1 ≤ k2`, `p1 ≤ p2` when `k1 = k2`, and
/// `p1 ≤ 2·p2` when `k2 = k1 + 1` (`2·p2` is exact). With the range this is
/// `p1·2^k1 ≤ p2·2^k2` as real numbers (for `k2 ≥ k1 + 2`,
/// `p1·2^k1 < 2^(k1+1) ≤ 2^(k2−1) ≤ p2·2^k2`), so it holds for every pair
/// as soon as it holds for every pair of adjacent arguments (the real
/// values are then in order along the whole domain, and each clause
/// follows from the order of the real values), which is what
/// [`exp_reduced_contract_at`] checks.
pub fn exp_reduced_order(p1: f32, k1: i32, p2: f32, k2: i32) -> bool {
    k1 <= k2 && (k1 != k2 || p1 <= p2) && (k2 != k1 + 1 || p1 <= 2.0 * p2)
}

/// `exp_reduced` meets its contract at `x` (range) and between `x` and
/// its successor (order), wherever both are in its domain. Engine:
/// exhaustive (every `f32`, in `exhaustive_exp_f32`'s pass); the Kani
/// harness `kani_exp_monotone_f32` assumes it.
pub fn exp_reduced_contract_at(x: f32) -> Verdict {
    let inside = |v: f32| (k::EXP_MIN_ARG..=k::EXP_MAX_ARG).contains(&v);
    if !inside(x) {
        return Verdict::logical(true);
    }
    let (p1, k1) = k::exp_reduced(x);
    let ok = exp_reduced_in_range(p1, k1);
    let xn = next_up(x);
    if !inside(xn) {
        return Verdict::logical(ok);
    }
    let (p2, k2) = k::exp_reduced(xn);
    Verdict::logical(ok && exp_reduced_order(p1, k1, p2, k2))
}

/// Upper bound of `e^{−|x|}` where `exp_neg_abs` flushes to 0, as stated on
/// the kernel (`e^{−EXP_NEG_ABS_MAX_ARG} = 1.169e-38`, below the smallest
/// normal `f32`).
pub const EXP_NEG_ABS_FLUSH_BOUND: f64 = 1.17e-38;

/// Proven ulp bound of `exp_neg_abs` on `|x| ≤ EXP_NEG_ABS_MAX_ARG`.
pub const EXP_NEG_ABS_BOUND: f64 = 2.0;

/// `exp_neg_abs(x)` for `|x| ≤ EXP_NEG_ABS_MAX_ARG` is within
/// [`EXP_NEG_ABS_BOUND`] of `e^{−|x|}`; above, it is exactly `+0.0` and
/// `e^{−|x|} < EXP_NEG_ABS_FLUSH_BOUND`; NaN gives exactly 1. Engines:
/// exhaustive (every magnitude), random.
pub fn exp_neg_abs_within_bound(x: f32) -> Verdict {
    let got = k::exp_neg_abs(x);
    if x.is_nan() {
        return Verdict::logical(got.to_bits() == 1.0f32.to_bits());
    }
    let a = f32::from_bits(x.to_bits() & 0x7fff_ffff);
    let reference = reference::exp(-(a as f64));
    if a > k::EXP_NEG_ABS_MAX_ARG {
        return Verdict::logical(got.to_bits() == 0 && reference < EXP_NEG_ABS_FLUSH_BOUND);
    }
    within(got, reference, EXP_NEG_ABS_BOUND)
}

/// `exp_neg_abs` does not increase from `|x|` to the next `f32` magnitude
/// (the table kernel's segments join in order). Engine: exhaustive (every
/// magnitude up to +∞).
pub fn exp_neg_abs_non_increasing_at(x: f32) -> Verdict {
    let a = f32::from_bits(x.to_bits() & 0x7fff_ffff);
    if !a.is_finite() {
        return Verdict::logical(true);
    }
    Verdict::logical(k::exp_neg_abs(next_up(a)) <= k::exp_neg_abs(a))
}

/// `exp_neg_abs(-x) = exp_neg_abs(x)` bit for bit (NaNs of both signs
/// included). Engines: exhaustive, Kani.
pub fn exp_neg_abs_even_at(x: f32) -> Verdict {
    Verdict::logical(k::exp_neg_abs(-x).to_bits() == k::exp_neg_abs(x).to_bits())
}

// ------------------------------------------------------------- sin/cos ----

/// `sin` is within [`SIN_COS_BOUND`] of `sin(x)` for finite `x`; `±∞` and
/// NaN give exactly 0. Engines: exhaustive, random, Kani.
pub fn sin_within_bound(x: f32) -> Verdict {
    if !x.is_finite() {
        return Verdict::logical(k::sin(x) == 0.0 && k::sin(-x) == 0.0);
    }
    within(k::sin(x), reference::sin(x as f64), SIN_COS_BOUND)
}

/// `cos` is within [`SIN_COS_BOUND`] of `cos(x)` for finite `x`; `±∞` and
/// NaN give exactly 1. Engines: exhaustive, random, Kani.
pub fn cos_within_bound(x: f32) -> Verdict {
    if !x.is_finite() {
        return Verdict::logical(k::cos(x) == 1.0 && k::cos(-x) == 1.0);
    }
    within(k::cos(x), reference::cos(x as f64), SIN_COS_BOUND)
}

/// `sin_cos(x)` equals `(sin x, cos x)` bit for bit, and for finite `x`
/// `sin` is exactly odd and `cos` exactly even (`±∞`, NaN: see
/// [`sin_within_bound`]). Engines: exhaustive, Kani.
pub fn sin_cos_consistent_and_symmetric_at(x: f32) -> Verdict {
    let (s, c) = k::sin_cos(x);
    let same = s.to_bits() == k::sin(x).to_bits() && c.to_bits() == k::cos(x).to_bits();
    let (sn, cn) = k::sin_cos(-x);
    let symmetric =
        !x.is_finite() || (sn.to_bits() == (-s).to_bits() && cn.to_bits() == c.to_bits());
    Verdict::logical(same && symmetric)
}

// --------------------------------------------------------------- atan2 ----

/// `atan2(y, x)` is within [`ATAN2_BOUND`] of the `f64` `atan2` (IEEE
/// signed-zero conventions), lies in `[-π, π]` (π rounded to `f32`), and
/// `atan2(±0, ±0) = 0`. NaN counts as 0. Engines: exhaustive grid, random,
/// Kani.
pub fn atan2_within_bound(y: f32, x: f32) -> Verdict {
    let got = k::atan2(y, x);
    let y = if y.is_nan() { 0.0 } else { y };
    let x = if x.is_nan() { 0.0 } else { x };
    if y == 0.0 && x == 0.0 {
        return Verdict::logical(got.to_bits() == 0);
    }
    let in_range = got.abs() <= core::f32::consts::PI;
    within(got, reference::atan2(y as f64, x as f64), ATAN2_BOUND).and(Verdict::logical(in_range))
}

// ---------------------------------------------------------------- acos ----

/// `acos` is within [`ACOS_BOUND`] of `acos(x)` on `[-1, 1]`; outside, equal to
/// `acos(±1)` (clamped; NaN: `acos(0)`). Engines: exhaustive, random, Kani.
pub fn acos_within_bound(x: f32) -> Verdict {
    if x.is_nan() {
        return Verdict::logical(k::acos(x) == k::acos(0.0));
    }
    if x > 1.0 {
        return Verdict::logical(k::acos(x) == k::acos(1.0));
    }
    if x < -1.0 {
        return Verdict::logical(k::acos(x) == k::acos(-1.0));
    }
    within(k::acos(x), reference::acos(x as f64), ACOS_BOUND)
}

// ---------------------------------------------------------------- sqrt ----

/// `sqrt` is correctly rounded: bit-equal to the `f64` square root rounded
/// to `f32` (innocuous double rounding: 53 ≥ 2·24 + 2), for `x ≥ 0`;
/// negatives and NaN give 0, `+∞` gives `f32::MAX`. Engines: exhaustive,
/// random, Kani.
pub fn sqrt_correctly_rounded(x: f32) -> Verdict {
    let got = k::sqrt(x);
    if x.is_nan() || x < 0.0 {
        return Verdict::logical(got.to_bits() == 0);
    }
    if x == f32::INFINITY {
        return Verdict::logical(got == f32::MAX);
    }
    let reference = reference::sqrt(x as f64);
    within(got, reference, SQRT_BOUND).and(Verdict::logical(got == reference as f32))
}

/// `sqrt` is non-decreasing at `x`. Engines: exhaustive, Kani.
pub fn sqrt_monotone_at(x: f32) -> Verdict {
    monotone_at(k::sqrt, x)
}

/// The scaled mantissas `sqrt` passes to its root: every `mm ∈ [2²³, 2²⁴)`
/// (even exponent) and the even `mm ∈ [2²⁴, 2²⁵)` (odd exponent, the
/// mantissa doubled). At odd `mm` above `2²⁴`, which never occur, the three
/// Newton steps can leave the candidate more than one off, and the root is
/// not always correctly rounded (at 90,549 of them).
pub fn sqrt_mantissa_domain(mm: u32) -> bool {
    (1 << 23..1 << 24).contains(&mm) || ((1 << 24..1 << 25).contains(&mm) && mm & 1 == 0)
}

/// The root of `sqrt` on a scaled mantissa `mm` of its domain
/// ([`sqrt_mantissa_domain`]) is `round(√(mm·2²³))`: `q² − q < M ≤ q² + q`
/// for `M = mm·2²³`, and `q ∈ [2²³, 2²⁴]`. Engine: exhaustive (every `mm`,
/// in `exhaustive_sqrt_f32`); as a Kani harness it timed out at 602 s.
pub fn sqrt_mantissa_rounded(mm: u32) -> bool {
    let q = k::sqrt_mantissa(mm) as u64;
    let m = (mm as u64) << 23;
    (1 << 23..=1 << 24).contains(&q) && q * q - q < m && m <= q * q + q
}

// ---------------------------------------------------------- Kani entries --

#[cfg(kani)]
mod kani_entries {
    use super::*;

    #[kani::proof]
    fn kani_atan_f32() {
        let x: f32 = kani::any();
        assert!(atan_within_bound(x).holds);
    }

    static ATAN_POLY_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static ATAN_MID_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static ATAN_RECIP_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `atan_poly` by its contract ([`atan_contracts_at`], checked at every
    /// `|u| ≤ 0.6` by `exhaustive_atan_f32`): the sign of `u`, `|p| ≤ 0.6`,
    /// non-decreasing. The precondition `|u| ≤ 0.6` is asserted.
    fn atan_poly_by_contract(u: f32) -> f32 {
        assert!(u.abs() <= k::ATAN_LOW, "atan_poly precondition");
        let p: f32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(p.abs() <= 0.6 && (u < 0.0 || p >= 0.0) && (u > 0.0 || p <= 0.0));
        ATAN_POLY_FIRST.assume_in_order_f32(u, p, true);
        p
    }

    /// `atan_mid_ratio` by its contract ([`atan_contracts_at`]): in
    /// `[−¼, ¼]`, non-decreasing. The precondition `0.6 < u ≤ ATAN_HIGH` is
    /// asserted.
    fn atan_mid_ratio_by_contract(u: f32) -> f32 {
        assert!(
            u > k::ATAN_LOW && u <= k::ATAN_HIGH,
            "atan_mid_ratio precondition"
        );
        let v: f32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume((-0.25..=0.25).contains(&v));
        ATAN_MID_FIRST.assume_in_order_f32(u, v, true);
        v
    }

    /// `recip` by its contract above `ATAN_HIGH` ([`recip_contract_at`]): in
    /// `[0, 0.6]`, non-increasing. The precondition `u > ATAN_HIGH` (`+∞`
    /// included) is asserted.
    fn recip_by_contract_above_atan_high(u: f32) -> f32 {
        assert!(u > k::ATAN_HIGH, "recip precondition (atan)");
        let r: f32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume((0.0..=0.6).contains(&r));
        ATAN_RECIP_FIRST.assume_in_order_f32(u, r, false);
        r
    }

    /// The four `x` whose successor is in another branch of `atan_nonneg`
    /// (`|x|` or `|next_up(x)|` at `0.6` and `ATAN_HIGH`).
    fn atan_branch_crossings() -> [f32; 4] {
        let (lo, hi) = (k::ATAN_LOW, k::ATAN_HIGH);
        [lo, hi, -next_up(lo), -next_up(hi)]
    }

    /// `atan` non-decreasing over every pair of adjacent `f32`s in one
    /// branch: NaN, the sign, `±∞`, and in each branch the composition of
    /// the reduction with the polynomial and the reconstruction
    /// `π/4 + (p + lo)`, `π/2 − (p − lo)` (the real float additions), with
    /// the polynomial, the middle ratio and the reciprocal by their
    /// contracts, which `exhaustive_atan_f32` checks at every argument.
    /// Split domain: the four pairs that cross a branch point are
    /// `kani_atan_monotone_crossings_f32`'s. With the real kernel (two
    /// copies of the polynomial and of a division) it timed out at 603 s.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::f32::atan_poly, atan_poly_by_contract)]
    #[kani::stub(
        crate::scalar::kernels::f32::atan_mid_ratio,
        atan_mid_ratio_by_contract
    )]
    #[kani::stub(crate::scalar::kernels::f32::recip, recip_by_contract_above_atan_high)]
    fn kani_atan_monotone_f32() {
        let x: f32 = kani::any();
        // Split domain (the complement is the next harness).
        kani::assume(!atan_branch_crossings().contains(&x));
        assert!(atan_monotone_at(x).holds);
    }

    /// `atan` non-decreasing at the four pairs of adjacent `f32`s that cross
    /// a branch point, with the real kernel (concrete arguments).
    #[kani::proof]
    fn kani_atan_monotone_crossings_f32() {
        for x in atan_branch_crossings() {
            assert!(atan_monotone_at(x).holds);
        }
    }

    static ATAN_CORE: crate::proofs::uninterpreted::Memo<2> =
        crate::proofs::uninterpreted::Memo::new();

    /// `atan_nonneg` (the kernel on `|x|`) as an uninterpreted function
    /// (`proofs/uninterpreted.rs`): any value, the same one for the same
    /// argument.
    fn atan_nonneg_uninterpreted(u: f32) -> f32 {
        f32::from_bits(ATAN_CORE.call(u64::from(u.to_bits())) as u32)
    }

    /// `atan` odd at every `f32`, bit for bit: the sign handling around the
    /// kernel on `|x|`, which is an uninterpreted function here (with both
    /// calls on the same `|x|` the solver had to prove two copies of the
    /// polynomial circuit equal, and did not in 603 s). The exhaustive
    /// engine checks oddness with the real kernel at every `f32`.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::f32::atan_nonneg, atan_nonneg_uninterpreted)]
    fn kani_atan_odd_f32() {
        let x: f32 = kani::any();
        assert!(atan_odd_at(x).holds);
    }

    #[kani::proof]
    fn kani_tan_f32() {
        let x: f32 = kani::any();
        assert!(tan_within_bound(x).holds);
    }

    static TAN_POLY_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();
    static RECIP_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `tan_poly` by its contract ([`tan_contracts_at`], checked at every
    /// argument `tan` passes by `exhaustive_tan_f32`): a value in range
    /// ([`tan_poly_in_range`]), and at a second call one in the order of the
    /// arguments ([`tan_poly_args_below`]; the same again for the same
    /// arguments). The precondition (`0 ≤ d < π/4`, `|d_lo|` below half an
    /// ulp of `d`) is asserted at each call.
    fn tan_poly_by_contract(d: f32, d_lo: f32) -> f32 {
        assert!(
            d >= 0.0 && d < f32::from_bits(k::FRAC_PI_4_UP) && d_lo.abs() <= d * f32::EPSILON,
            "tan_poly precondition"
        );
        let t: f32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(tan_poly_in_range(d, t));
        if let Some((d1, lo1, t1)) =
            TAN_POLY_FIRST.first_or_record(d.to_bits(), d_lo.to_bits(), t.to_bits())
        {
            let (d1, lo1, t1) = (f32::from_bits(d1), f32::from_bits(lo1), f32::from_bits(t1));
            // postcondition of the stubbed function: the order lemma
            kani::assume(if tan_poly_args_below(d1, lo1, d, d_lo) {
                t >= t1
            } else if tan_poly_args_below(d, d_lo, d1, lo1) {
                t <= t1
            } else {
                t.to_bits() == t1.to_bits()
            });
        }
        t
    }

    /// `recip` by its contract on `(0, 1]` ([`tan_contracts_at`]): at least
    /// 1, and at a second call one in the reverse order of the arguments.
    /// The precondition is asserted at each call.
    fn recip_by_contract(t: f32) -> f32 {
        assert!(t > 0.0 && t <= 1.0, "recip precondition");
        let r: f32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(r >= 1.0);
        RECIP_FIRST.assume_in_order_f32(t, r, false);
        r
    }

    /// `tan` non-decreasing over every pair of adjacent `f32`s: NaN, the
    /// clamp at the domain edge, the choice of the reflection, the pair
    /// `π/2 − |x| = d + d_lo` (Sterbenz and Fast2Sum, the real float
    /// operations), the join at π/4 (`t ≤ 1 ≤ 1/t'`) and the sign, with the
    /// polynomial and the reciprocal by their contracts, which
    /// `exhaustive_tan_f32` checks at every argument `tan` passes. With the
    /// real ones (two copies of the polynomial circuit and of the division)
    /// it timed out at 602 s.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::f32::tan_poly, tan_poly_by_contract)]
    #[kani::stub(crate::scalar::kernels::f32::recip, recip_by_contract)]
    fn kani_tan_monotone_f32() {
        let x: f32 = kani::any();
        assert!(tan_monotone_at(x).holds);
    }

    #[kani::proof]
    fn kani_exp_f32() {
        let x: f32 = kani::any();
        assert!(exp_within_bound(x).holds);
    }

    static EXP_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `exp_reduced` by its contract: any `(p, k)` in range
    /// ([`exp_reduced_in_range`]), and at a second call one in the order of
    /// the arguments ([`exp_reduced_order`]; the same value again for the
    /// same argument). Both are checked at every argument by
    /// `exhaustive_exp_f32`. The precondition (the argument in the
    /// reduction's domain) is asserted at each call.
    fn exp_reduced_by_contract(x: f32) -> (f32, i32) {
        assert!(
            (k::EXP_MIN_ARG..=k::EXP_MAX_ARG).contains(&x),
            "exp_reduced precondition"
        );
        let p: f32 = kani::any();
        let kk: i32 = kani::any();
        // postcondition of the stubbed function: the range
        kani::assume(exp_reduced_in_range(p, kk));
        if let Some((x1, k1, p1)) = EXP_FIRST.first_or_record(x.to_bits(), kk as u32, p.to_bits()) {
            let (x1, k1, p1) = (f32::from_bits(x1), k1 as i32, f32::from_bits(p1));
            // postcondition of the stubbed function: the order lemma
            kani::assume(if x > x1 {
                exp_reduced_order(p1, k1, p, kk)
            } else if x < x1 {
                exp_reduced_order(p, kk, p1, k1)
            } else {
                // the same value for the same argument bits (nothing
                // assumed between −0.0 and +0.0)
                x.to_bits() != x1.to_bits() || (p.to_bits() == p1.to_bits() && kk == k1)
            });
        }
        (p, kk)
    }

    /// `exp` non-decreasing over every pair of adjacent `f32`s: NaN, the
    /// saturation above `EXP_MAX_ARG`, the flush to 0 below `EXP_MIN_ARG`
    /// and the scaling `p·2^k1·2^k2` (exact, or one rounding into the
    /// subnormal range), with the reduction and polynomial by their
    /// contract, which `exhaustive_exp_f32` checks at every argument. With
    /// the real polynomial (two copies of its circuit on adjacent
    /// arguments) it timed out at 605 s.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::f32::exp_reduced, exp_reduced_by_contract)]
    fn kani_exp_monotone_f32() {
        let x: f32 = kani::any();
        assert!(exp_monotone_at(x).holds);
    }

    #[kani::proof]
    fn kani_exp_neg_abs_f32() {
        let x: f32 = kani::any();
        assert!(exp_neg_abs_within_bound(x).holds);
    }

    static EXP_NEG_CORE: crate::proofs::uninterpreted::Memo<2> =
        crate::proofs::uninterpreted::Memo::new();

    /// `exp_neg_of_magnitude` (the table kernel's `e^{−a}`) as an
    /// uninterpreted function: any value for a new argument, the same again
    /// for the same argument.
    fn exp_neg_of_magnitude_uninterpreted(a: f32) -> f32 {
        f32::from_bits(EXP_NEG_CORE.call(u64::from(a.to_bits())) as u32)
    }

    /// `exp_neg_abs` is even, bit for bit (the part of the former
    /// `kani_exp_neg_abs_f32` without the `f64` reference): the magnitude
    /// and range logic, with the table kernel's `e^{−a}` as an
    /// uninterpreted function (with the real one, two copies of its float
    /// circuit on arguments the solver must first prove equal: not
    /// finished after 440 s). The exhaustive engine checks evenness with
    /// the real kernel at every `f32`.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::f32::exp_neg_of_magnitude,
        exp_neg_of_magnitude_uninterpreted
    )]
    fn kani_exp_neg_abs_even_f32() {
        let x: f32 = kani::any();
        assert!(exp_neg_abs_even_at(x).holds);
    }

    #[kani::proof]
    fn kani_sin_f32() {
        let x: f32 = kani::any();
        // solver budget: the reduction is exercised up to 2^16 rad here; the
        // exhaustive engine covers every finite f32.
        kani::assume(x.abs() <= 65_536.0);
        assert!(sin_within_bound(x).holds);
    }

    #[kani::proof]
    fn kani_cos_f32() {
        let x: f32 = kani::any();
        // solver budget: as in kani_sin_f32.
        kani::assume(x.abs() <= 65_536.0);
        assert!(cos_within_bound(x).holds);
    }

    static REDUCE_QUADRANT: crate::proofs::uninterpreted::Memo<2> =
        crate::proofs::uninterpreted::Memo::new();
    static SIN_COS_POLY: crate::proofs::uninterpreted::Memo<2> =
        crate::proofs::uninterpreted::Memo::new();

    /// `reduce_quadrant` uninterpreted: any `(r, n)` for a new argument, the
    /// same again for the same argument. Postcondition of the stubbed
    /// function: `n < 4` (`kani_reduce_quadrant_n_in_range_f32`).
    fn reduce_quadrant_uninterpreted(abits: u32) -> (f32, u32) {
        let v = REDUCE_QUADRANT.call(u64::from(abits));
        (f32::from_bits(v as u32), (v >> 62) as u32)
    }

    /// `sin_cos_poly` uninterpreted: any `(sin r, cos r)` for a new `r`, the
    /// same pair again for the same `r` (bit pattern).
    fn sin_cos_poly_uninterpreted(r: f32) -> (f32, f32) {
        let v = SIN_COS_POLY.call(u64::from(r.to_bits()));
        (f32::from_bits(v as u32), f32::from_bits((v >> 32) as u32))
    }

    /// The postcondition `reduce_quadrant_uninterpreted` assumes: the
    /// quadrant is in `0..4` for every finite `|x| ≥ π/4`.
    #[kani::proof]
    fn kani_reduce_quadrant_n_in_range_f32() {
        let abits: u32 = kani::any();
        // precondition: sin_cos's reduced branch (finite, |x| ≥ π/4)
        kani::assume((0x3f49_0fdb..0x7f80_0000).contains(&abits));
        assert!(crate::scalar::kernels::f32::reduce_quadrant(abits).1 < 4);
    }

    /// `sin_cos(x)` equals `(sin x, cos x)` bit for bit, `sin` exactly odd
    /// and `cos` exactly even at every `f32`: the branch, quadrant and sign
    /// logic around the reduction and the two polynomials, which are
    /// uninterpreted functions here (`proofs/uninterpreted.rs`). With the
    /// real ones the solver had to prove four copies of the reduction's
    /// integer products and of the polynomial circuit equal, and did not in
    /// 607 s. The exhaustive engine checks the property with the real cores
    /// at every `f32`.
    #[kani::proof]
    #[kani::stub(
        crate::scalar::kernels::f32::reduce_quadrant,
        reduce_quadrant_uninterpreted
    )]
    #[kani::stub(crate::scalar::kernels::f32::sin_cos_poly, sin_cos_poly_uninterpreted)]
    fn kani_sin_cos_consistent_f32() {
        let x: f32 = kani::any();
        assert!(sin_cos_consistent_and_symmetric_at(x).holds);
    }

    #[kani::proof]
    fn kani_atan2_f32() {
        let y: f32 = kani::any();
        let x: f32 = kani::any();
        assert!(atan2_within_bound(y, x).holds);
    }

    #[kani::proof]
    fn kani_acos_f32() {
        let x: f32 = kani::any();
        assert!(acos_within_bound(x).holds);
    }

    #[kani::proof]
    fn kani_sqrt_f32() {
        let x: f32 = kani::any();
        assert!(sqrt_correctly_rounded(x).holds);
    }

    static SQRT_FIRST: crate::proofs::uninterpreted::FirstCall =
        crate::proofs::uninterpreted::FirstCall::new();

    /// `sqrt_mantissa` by what its contract ([`sqrt_mantissa_rounded`])
    /// implies: a root in `[2²³, 2²⁴]`, and at a
    /// second call one in the order of the arguments, because `round(√·)`
    /// is non-decreasing on the integers. The precondition is asserted at
    /// each call.
    fn sqrt_mantissa_by_contract(mm: u32) -> u32 {
        assert!(sqrt_mantissa_domain(mm), "sqrt_mantissa precondition");
        let q: u32 = kani::any();
        // postcondition of the stubbed function: the root's range
        kani::assume((1 << 23..=1 << 24).contains(&q));
        SQRT_FIRST.assume_in_order_u32(mm, q, true);
        q
    }

    /// `sqrt` non-decreasing over every pair of adjacent `f32`s: the
    /// special cases, the subnormal normalization, the even exponent and
    /// the carry of the root into the exponent field, with the mantissa
    /// root by its contract, which `exhaustive_sqrt_f32` checks at every
    /// mantissa `sqrt` passes. With the real root (three `f32` divisions on
    /// each side) it timed out at 602 s; the contract on the real root as a
    /// harness of its own timed out at 602 s as well.
    #[kani::proof]
    #[kani::stub(crate::scalar::kernels::f32::sqrt_mantissa, sqrt_mantissa_by_contract)]
    fn kani_sqrt_monotone_f32() {
        let x: f32 = kani::any();
        assert!(sqrt_monotone_at(x).holds);
    }
}

// ------------------------------------------------------ exhaustive engine --

#[cfg(test)]
mod exhaustive {
    extern crate std;
    use super::super::engine::{exhaustive_u32, Report};
    use super::*;
    use std::println;

    /// Run `property` over the codes `lo..=hi` (decoded by `decode`), print
    /// one summary line per entry of `claims` — `(domain, bound)`; the
    /// property checks all of them at once, sharing the kernel evaluations —
    /// and fail on any counterexample. Error bounds print the maximum error
    /// and its argument; logical claims (`monotone`, `odd`, `exact`) print 0.
    fn prove(
        kernel: &str,
        claims: &[(&str, &str)],
        lo: u32,
        hi: u32,
        describe: impl Fn(u32) -> std::string::String,
        property: impl Fn(u32) -> Verdict + Sync,
    ) -> Report {
        let start = std::time::Instant::now();
        let rep = exhaustive_u32(lo, hi, property);
        let secs = start.elapsed().as_secs_f64();
        if rep.failures != 0 {
            // One pass checks every claim, so a failure is reported once,
            // naming all of them.
            let first = rep.first_failure.unwrap_or(0);
            let mut names = std::string::String::new();
            for &(domain, bound) in claims {
                names.push_str(&std::format!("[domain={domain} bound={bound}]"));
            }
            println!(
                "FAILED kernel={kernel} backend=f32 claims={names} failures={} first_failure={} (code {first:#010x}) max_err={:.3} ulp at={} checked={} engine=exhaustive",
                rep.failures,
                describe(first),
                rep.max_error,
                describe(rep.argmax),
                rep.checked
            );
        }
        for &(domain, bound) in claims.iter().filter(|_| rep.failures == 0) {
            let logical = bound.parse::<f64>().is_err();
            let (max_err, at) = if logical {
                (
                    std::string::String::from("0"),
                    std::string::String::from("-"),
                )
            } else {
                (
                    std::format!("{:.3} ulp", rep.max_error),
                    describe(rep.argmax),
                )
            };
            let bound = if logical {
                std::string::String::from(bound)
            } else {
                std::format!("{bound} ulp")
            };
            println!(
                "PROOF kernel={kernel} backend=f32 domain={domain} bound={bound} max_err={max_err} at={at} checked={} engine=exhaustive",
                rep.checked
            );
        }
        println!("  ({kernel}: {} codes in {secs:.1} s)", rep.checked);
        assert_eq!(rep.failures, 0, "{kernel}: property fails");
        rep
    }

    fn bits(c: u32) -> f32 {
        f32::from_bits(c)
    }

    /// The input of code `c` as printed in the summary line.
    fn show(c: u32) -> std::string::String {
        std::format!("{:e}", f32::from_bits(c))
    }

    /// Codes `0..2n` → `+code` for `c < n`, `-(c - n)` above: both signs of
    /// the magnitudes `0..n`.
    fn both_signs(n: u32) -> impl Fn(u32) -> f32 + Copy {
        move |c| {
            if c < n {
                f32::from_bits(c)
            } else {
                f32::from_bits(0x8000_0000 | (c - n))
            }
        }
    }

    /// Odd kernels are checked on the codes of `x ≥ 0` (including +∞ and the
    /// NaNs): the bound and monotonicity there, plus exact oddness, give the
    /// bound and monotonicity over every `f32` (for `a < b ≤ 0`,
    /// `f(a) = −f(−a) ≤ −f(−b) = f(b)`).
    const POSITIVE_CODES: (u32, u32) = (0, 0x7fff_ffff);

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan_f32() {
        let (lo, hi) = POSITIVE_CODES;
        prove(
            "atan",
            &[
                ("all-f32", "2"),
                ("all-f32", "monotone"),
                ("all-f32", "odd"),
                ("x>=0", "atan_poly,atan_mid_ratio,recip-contracts"),
            ],
            lo,
            hi,
            show,
            |c| {
                let x = bits(c);
                atan_within_bound(x)
                    .and(atan_monotone_at(x))
                    .and(atan_odd_at(x))
                    .and(atan_contracts_at(x))
            },
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_f32() {
        let (lo, hi) = POSITIVE_CODES;
        prove(
            "tan",
            &[
                ("|x|<=1.5707962(all-f32;saturated-outside)", "2"),
                ("all-f32", "monotone"),
                ("all-f32", "odd"),
                ("x>=0", "tan_poly,recip-contracts"),
            ],
            lo,
            hi,
            show,
            |c| {
                let x = bits(c);
                tan_within_bound(x)
                    .and(tan_monotone_at(x))
                    .and(tan_odd_at(x))
                    .and(tan_contracts_at(x))
            },
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_tan_bounded_f32() {
        let (lo, hi) = POSITIVE_CODES;
        prove(
            "tan_bounded",
            &[
                ("|x|<=1.4464413(atan8;all-f32)", "bit-identical-to-tan"),
                ("|x|>1.4464413(all-f32;NaN)", "tan(1.4464413)-with-sign"),
                ("all-f32", "odd"),
            ],
            lo,
            hi,
            show,
            |c| tan_bounded_is_tan_on_its_domain(bits(c)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_f32() {
        prove(
            "exp",
            &[
                ("x<=88.72283(all-f32;MAX-above;0-below-103.97208)", "2"),
                ("all-f32", "monotone"),
                ("EXP_MIN_ARG..=EXP_MAX_ARG", "exp_reduced-contract"),
            ],
            0,
            u32::MAX,
            show,
            |c| {
                let x = bits(c);
                exp_within_bound(x)
                    .and(exp_monotone_at(x))
                    .and(exp_reduced_contract_at(x))
            },
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_exp_neg_abs_f32() {
        // Every magnitude code (+0 to +∞ and the positive NaNs); the negative
        // codes by the exact evenness checked in the same pass.
        let (lo, hi) = POSITIVE_CODES;
        prove(
            "exp_neg_abs",
            &[
                ("|x|<=87.34196(all-f32;0-above)", "2"),
                ("|x|>87.34196(all-f32)", "0(e^-|x|<1.17e-38)"),
                ("all-f32", "even"),
                ("all-f32", "non-increasing-in-|x|"),
            ],
            lo,
            hi,
            show,
            |c| {
                let x = bits(c);
                exp_neg_abs_within_bound(x)
                    .and(exp_neg_abs_even_at(x))
                    .and(exp_neg_abs_non_increasing_at(x))
            },
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sin_f32() {
        // x ≥ 0; x < 0 by the exact oddness checked in the same pass.
        prove(
            "sin",
            &[
                ("all-finite-f32", "2"),
                ("all-f32", "odd"),
                ("all-f32(sin_cos=(sin,cos))", "exact"),
            ],
            0,
            0x7fff_ffff,
            show,
            |c| {
                let x = bits(c);
                sin_within_bound(x).and(sin_cos_consistent_and_symmetric_at(x))
            },
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_cos_f32() {
        // x ≥ 0; x < 0 by the exact evenness checked in exhaustive_sin_f32.
        prove(
            "cos",
            &[("all-finite-f32", "2")],
            0,
            0x7fff_ffff,
            show,
            |c| cos_within_bound(bits(c)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_acos_f32() {
        let n = 1.0f32.to_bits() + 1;
        let dec = both_signs(n);
        let show_dec = move |c| std::format!("{:e}", dec(c));
        prove(
            "acos",
            &[("[-1,1]", "2")],
            0,
            2 * n - 1,
            show_dec,
            move |c| acos_within_bound(dec(c)),
        );
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_sqrt_f32() {
        prove(
            "sqrt",
            &[("x>=0", "0.5"), ("x>=0", "monotone")],
            0,
            0x7fff_ffff,
            show,
            |c| {
                let x = bits(c);
                sqrt_correctly_rounded(x).and(sqrt_monotone_at(x))
            },
        );
        // x < 0 (and negative NaNs) → 0: then monotone over every f32 too.
        prove(
            "sqrt",
            &[("x<0", "exact")],
            0x8000_0000,
            u32::MAX,
            show,
            |c| sqrt_correctly_rounded(bits(c)),
        );
        // The contract `kani_sqrt_monotone_f32` stubs the root by, at every
        // scaled mantissa.
        let bad = (1u32 << 23..1 << 25)
            .filter(|&mm| sqrt_mantissa_domain(mm) && !sqrt_mantissa_rounded(mm))
            .count();
        assert_eq!(
            bad, 0,
            "sqrt_mantissa is not round(√(mm·2²³)) at {bad} mantissas"
        );
    }

    /// The 4096 grid values per axis: 2048 magnitudes spread over every
    /// exponent (0, subnormals, normals from 2^-126 to MAX, ∞), both signs.
    fn atan2_axis(i: u32) -> f32 {
        let j = i & 2047;
        let mag = match j {
            0 => 0,
            2047 => 0x7f80_0000,
            // Spread j = 1..2046 over the finite positive codes, plus a
            // per-index offset so mantissas vary.
            _ => ((j as u64 * 0x7f7f_ffff / 2046) as u32 | 1).wrapping_sub(j & 0x3e),
        };
        if i < 2048 {
            f32::from_bits(mag)
        } else {
            f32::from_bits(mag | 0x8000_0000)
        }
    }

    #[test]
    #[ignore = "exhaustive: run in release by .ci/run"]
    fn exhaustive_atan2_f32() {
        let pair = |c: u32| std::format!("({:e},{:e})", atan2_axis(c >> 12), atan2_axis(c & 4095));
        prove(
            "atan2",
            &[("grid-4096x4096-all-exponents-signs-zeros-inf", "2")],
            0,
            (1 << 24) - 1,
            pair,
            |c| atan2_within_bound(atan2_axis(c >> 12), atan2_axis(c & 4095)),
        );
    }
}

// --------------------------------------------------------- random engine --

#[cfg(test)]
mod random {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Joint angles and motor angles (after the gear ratio) in ±10⁴ rad.
        #[test]
        fn sin_cos_within_bound_on_motor_angles(x in -1.0e4f32..1.0e4) {
            prop_assert!(sin_within_bound(x).holds);
            prop_assert!(cos_within_bound(x).holds);
            prop_assert!(sin_cos_consistent_and_symmetric_at(x).holds);
        }

        /// Small wrist angles, where the unreduced branch is used.
        #[test]
        fn sin_cos_within_bound_near_zero(x in -1.0f32..1.0) {
            prop_assert!(sin_within_bound(x).holds);
            prop_assert!(cos_within_bound(x).holds);
        }

        /// Compliance arguments `c_f·τ` (eq. 2.26): torques up to ±500 N·m
        /// times compliance up to 10 rad/(N·m).
        #[test]
        fn atan_within_bound_on_compliance_arguments(x in -5.0e3f32..5.0e3) {
            prop_assert!(atan_within_bound(x).holds);
            prop_assert!(atan_monotone_at(x).holds);
        }

        #[test]
        fn tan_within_bound_on_principal_branch(x in -1.570_796_2f32..1.570_796_2) {
            prop_assert!(tan_within_bound(x).holds);
            prop_assert!(tan_monotone_at(x).holds);
        }

        /// Arguments of eq. (3.10) in the estimator, and beyond.
        #[test]
        fn tan_bounded_is_tan_on_the_estimator_arguments(x in -3.0f32..3.0) {
            prop_assert!(tan_bounded_is_tan_on_its_domain(x).holds);
        }

        /// Exponents of the stiffness (eq. 2.29) and Stribeck (eq. 4.7) terms.
        #[test]
        fn exp_within_bound_on_model_exponents(x in -100.0f32..88.0) {
            prop_assert!(exp_within_bound(x).holds);
            prop_assert!(exp_monotone_at(x).holds);
        }

        /// Exponents `−c_w·|τ_w|` (eq. (2.29)) and `−f_lτ·q̇²` (eq. (4.7)), both
        /// signs of the argument, through the flush threshold.
        #[test]
        fn exp_neg_abs_within_bound_on_model_exponents(x in -120.0f32..120.0) {
            prop_assert!(exp_neg_abs_within_bound(x).holds);
            prop_assert!(exp_neg_abs_even_at(x).holds);
            prop_assert!(exp_neg_abs_non_increasing_at(x).holds);
            let a = x.abs();
            // Against the f64 exponential directly.
            let reference = (-(a as f64)).exp();
            if a <= k::EXP_NEG_ABS_MAX_ARG {
                prop_assert!(ulp_error_f32(k::exp_neg_abs(x), reference) <= EXP_NEG_ABS_BOUND);
            } else {
                prop_assert_eq!(k::exp_neg_abs(x).to_bits(), 0);
                prop_assert!(reference < EXP_NEG_ABS_FLUSH_BOUND);
            }
        }

        /// Any bit pattern (subnormals, huge magnitudes, infinities, NaNs).
        #[test]
        fn exp_neg_abs_within_bound_on_all_codes(c in any::<u32>()) {
            let x = f32::from_bits(c);
            prop_assert!(exp_neg_abs_within_bound(x).holds);
            prop_assert!(exp_neg_abs_even_at(x).holds);
        }

        /// Force components in ±10³ N (F/T sensor mapping, ch. 5).
        #[test]
        fn atan2_within_bound_on_forces(y in -1.0e3f32..1.0e3, x in -1.0e3f32..1.0e3) {
            prop_assert!(atan2_within_bound(y, x).holds);
        }

        /// Direction cosines of the wrist kinematics.
        #[test]
        fn acos_within_bound_on_direction_cosines(x in -1.0f32..=1.0) {
            prop_assert!(acos_within_bound(x).holds);
        }

        /// Sums of squares of forces and velocities.
        #[test]
        fn sqrt_correctly_rounded_on_norms(x in 0.0f32..1.0e7) {
            prop_assert!(sqrt_correctly_rounded(x).holds);
            prop_assert!(sqrt_monotone_at(x).holds);
        }
    }

    /// The edges of `exp_neg_abs`, each against a value computed without
    /// the kernel.
    #[test]
    fn exp_neg_abs_edges() {
        let t = k::EXP_NEG_ABS_MAX_ARG;
        // The threshold: k = round(a·64/ln 2) reaches 8065 = 126·64 + 1
        // (whose table value scaled by 2^-126 is not normal) just above T,
        // at 8064.5·ln 2/64, and e^{−T} is below the smallest normal f32.
        let edge = 8064.5 * core::f64::consts::LN_2 / 64.0;
        assert!((t as f64) <= edge && (next_up(t) as f64) - edge < 2e-5);
        assert!((-(t as f64)).exp() < EXP_NEG_ABS_FLUSH_BOUND);
        assert!((-(t as f64)).exp() < f32::MIN_POSITIVE as f64);
        assert!((-(t as f64)).exp() > 1.16e-38);
        // The table: 2^{−j/64} (its entry less j·2¹⁷) against the f64 power,
        // to the nearest f32 (no f64 value is within 1e-6 ulp of a midpoint
        // between two f32s, so rounding it once more gives the correctly
        // rounded f32).
        for (j, &entry) in k::EXP_NEG_ABS_TABLE.iter().enumerate() {
            let bits = entry - ((j as u32) << 17);
            let v = 2f64.powf(-(j as f64) / 64.0);
            let nearest = v as f32;
            let ulp = (next_up(nearest) - nearest) as f64;
            let off = (v - nearest as f64).abs() / ulp;
            assert!((0.5 - off).abs() > 1e-6, "{j}: near a midpoint");
            assert_eq!(bits, nearest.to_bits(), "{j}");
        }

        // 1 at both zeros and for NaNs of both signs (NaN counts as 0).
        for x in [
            0.0f32,
            -0.0,
            f32::NAN,
            -f32::NAN,
            f32::from_bits(0x7fc0_0001),
        ] {
            assert_eq!(k::exp_neg_abs(x).to_bits(), 1.0f32.to_bits(), "{x}");
        }
        // Subnormal and tiny inputs: e^{−a} ≈ 1 − a is nearer to 1 than to
        // the next f32 below, 1 − 2^-24, for a < 2^-25.
        for c in [1u32, 2, 0x007f_ffff, 0x0080_0000, 0x3000_0000] {
            for x in [f32::from_bits(c), -f32::from_bits(c)] {
                assert_eq!(k::exp_neg_abs(x), 1.0, "{x:e}");
            }
        }
        let a = 3.0 * 2f32.powi(-26); // e^{−a} ≈ 1 − 0.75·2^-24: nearest is 1 − 2^-24
        assert_eq!(k::exp_neg_abs(a), 1.0 - 2f32.powi(-24));
        // At T: a subnormal, within 2 ulp (2^-149) of e^{−T}.
        let at_t = k::exp_neg_abs(t);
        assert!(at_t > 0.0 && at_t < f32::MIN_POSITIVE);
        assert!(((at_t as f64) - (-(t as f64)).exp()).abs() <= 2.0 * 2f64.powi(-149));
        assert_eq!(k::exp_neg_abs(-t).to_bits(), at_t.to_bits());
        // Above T: +0, while exp(−a) is still a positive subnormal there.
        for x in [next_up(t), 100.0, f32::MAX, f32::INFINITY] {
            assert_eq!(k::exp_neg_abs(x).to_bits(), 0, "{x}");
            assert_eq!(k::exp_neg_abs(-x).to_bits(), 0, "{x}");
        }
        assert!(k::exp(-next_up(t)) > 0.0);
        // Mid-range against the f64 exponential.
        for a in [0.5f32, 1.0, 10.0, 50.0, 87.0] {
            let got = k::exp_neg_abs(-a);
            assert!(
                ulp_error_f32(got, (-(a as f64)).exp()) <= EXP_NEG_ABS_BOUND,
                "{a}"
            );
        }
    }

    #[test]
    fn special_values() {
        assert_eq!(k::atan(f32::INFINITY), core::f32::consts::FRAC_PI_2);
        assert_eq!(k::atan(f32::NAN), 0.0);
        assert_eq!(k::tan(f32::NAN), 0.0);
        assert_eq!(k::tan(f32::INFINITY), k::tan(k::TAN_DOMAIN_EDGE));
        assert_eq!(k::exp(f32::NAN), 1.0);
        assert_eq!(k::exp(f32::INFINITY), f32::MAX);
        assert_eq!(k::exp(f32::NEG_INFINITY), 0.0);
        assert_eq!(k::exp(0.0), 1.0);
        assert_eq!(k::sin_cos(f32::INFINITY), (0.0, 1.0));
        assert_eq!(k::sin_cos(f32::NAN), (0.0, 1.0));
        assert_eq!(k::atan2(0.0, 0.0), 0.0);
        assert_eq!(k::atan2(-0.0, -0.0), 0.0);
        assert_eq!(k::atan2(0.0, -1.0), core::f32::consts::PI);
        assert_eq!(k::atan2(1.0, 0.0), core::f32::consts::FRAC_PI_2);
        assert_eq!(k::acos(2.0), 0.0);
        assert_eq!(k::acos(-1.0), core::f32::consts::PI);
        assert_eq!(k::sqrt(-4.0), 0.0);
        assert_eq!(k::sqrt(4.0), 2.0);
        assert_eq!(k::sqrt(f32::INFINITY), f32::MAX);
        for x in [
            0.0f32,
            1e-30,
            0.5,
            1.0,
            3.0,
            1e10,
            f32::MAX,
            f32::MIN_POSITIVE,
        ] {
            assert!(atan_within_bound(x).holds, "atan {x}");
            assert!(exp_within_bound(-x).holds, "exp {x}");
            assert!(sin_within_bound(x).holds, "sin {x}");
            assert!(cos_within_bound(x).holds, "cos {x}");
            assert!(sqrt_correctly_rounded(x).holds, "sqrt {x}");
        }
    }
}
