//! The `I16F16` fixed-point backend (Q16.16: 16 integer bits including the
//! sign, 16 fractional bits).
//!
//! Range `[-32768, 32768 - 2⁻¹⁶]`, resolution `2⁻¹⁶ ≈ 1.53e-5`. Every
//! operation saturates; nothing wraps or panics. Products are rounded to
//! nearest (ties up), quotients to nearest (ties away from zero).
//!
//! The kernels are those of [`kernels::i16f16`].

use super::{kernels, Scalar, I16F16};

/// Saturate a 64-bit intermediate to the `i32` bit range.
#[inline]
pub(crate) const fn sat_i64(v: i64) -> i32 {
    if v > i32::MAX as i64 {
        i32::MAX
    } else if v < i32::MIN as i64 {
        i32::MIN
    } else {
        v as i32
    }
}

/// Rounded, saturating Q16.16 product of two raw bit patterns:
/// `sat(⌊(a·b + 2¹⁵) / 2¹⁶⌋)`.
///
/// Computed by [`mul_bits_long`] without a 64-bit multiply or shift (so
/// Armv6-M calls neither `__aeabi_lmul` nor a 64-bit shift); equal to the
/// 64-bit formula [`mul_bits_reference`] for every pair of operands
/// (checked at random on the host and exhaustively over edge classes in
/// the tests below).
///
/// When either operand lies in `[−2¹⁵, 2¹⁵)` (a value below 0.5 in
/// magnitude — small errors, speeds and boundary-layer quantities, the
/// common case in a control law) the product takes [`mul_bits_short`]: two
/// 32-bit multiplies and no saturation check. Not on Armv6-M: there the
/// two operand tests cost six instructions on top of the long form on
/// every worst-case path (the one a servo tick's budget is signed on),
/// which then is [`mul_bits_long_split`] alone; the value is the same.
#[inline]
pub(crate) fn mul_bits(a: i32, b: i32) -> i32 {
    if cfg!(armv6m) {
        mul_bits_long(a, b)
    } else if b as i16 as i32 == b {
        mul_bits_short(a, b)
    } else if a as i16 as i32 == a {
        mul_bits_short(b, a)
    } else {
        mul_bits_long(a, b)
    }
}

/// [`mul_bits`] for any operands. On Armv6-M [`mul_bits_long_split`];
/// elsewhere [`signed_wide_mul`], then [`round_shift_sat`] by 16.
#[inline(always)]
fn mul_bits_long(a: i32, b: i32) -> i32 {
    #[cfg(armv6m)]
    {
        mul_bits_long_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        let (hi, lo) = signed_wide_mul(a, b);
        round_shift_sat(hi, lo, 1 << 15, 15)
    }
}

/// [`mul_bits`] for any operands, formed directly at the Q16.16 scale
/// (the Armv6-M path; built on every target so the host tests check it).
/// With `a = a_h·2¹⁶ + a_l`, `b = b_h·2¹⁶ + b_l` (`a_h = a >> 16`
/// arithmetic, `a_l ∈ [0, 2¹⁶)`):
///
/// ```text
/// ⌊(a·b + 2¹⁵)/2¹⁶⌋ = a_h b_h·2¹⁶ + a_h b_l + a_l b_h + ⌊(a_l b_l + 2¹⁵)/2¹⁶⌋
/// ```
///
/// exactly, because every other term is a multiple of 2¹⁶. Each partial
/// product is exact in 32 bits (`|a_h b_h| ≤ 2³⁰`, the middle ones in
/// `(−2³¹, 2³¹)`, `a_l b_l + 2¹⁵ < 2³²`). Splitting each middle product
/// `m = m_h·2¹⁶ + m_l` the same way, the sum is `t·2¹⁶ + f` with
/// `t = a_h b_h + m1_h + m2_h + ⌊s/2¹⁶⌋`, `s = m1_l + m2_l + ⌊(a_l b_l +
/// 2¹⁵)/2¹⁶⌋ < 3·2¹⁶` and `f = s mod 2¹⁶`; `|t| < 2³¹`, and the result
/// fits `i32` exactly when `t ∈ [−2¹⁵, 2¹⁵)`, else it saturates with the
/// sign of `t`. All in 32-bit words: four multiplies, no 64-bit addition
/// or shift.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_bits_long_split(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let (m1, m2) = (ah * bl, al * bh);
    let low = ((al as u32) * (bl as u32) + (1 << 15)) >> 16;
    let s = (m1 & 0xFFFF) as u32 + (m2 & 0xFFFF) as u32 + low;
    let t = ah * bh + (m1 >> 16) + (m2 >> 16) + (s >> 16) as i32;
    // `t ∈ [−2¹⁵, 2¹⁵)` exactly when `t·2¹⁶` shifted back is `t` (the
    // shifted word is the result's high half); else the sign of `t` picks
    // the bound, without a branch.
    let high = t << 16;
    if high >> 16 != t {
        return (t >> 31) ^ i32::MAX;
    }
    high | (s & 0xFFFF) as i32
}

/// The signed 64-bit product `V = a·b` as `(high word, low word)`, in
/// two's complement: the unsigned product of the bit patterns ([`wide_mul`])
/// with its high word corrected by `−b` for `a < 0` and by `−a` for `b < 0`.
/// `|V| ≤ 2⁶²`, so `|high| ≤ 2³⁰`.
#[inline(always)]
#[cfg_attr(armv6m, allow(dead_code))]
pub(crate) fn signed_wide_mul(a: i32, b: i32) -> (i32, u32) {
    #[cfg(armv6m)]
    {
        signed_wide_mul_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        let p = a as i64 * b as i64;
        ((p >> 32) as i32, p as u32)
    }
}

/// [`signed_wide_mul`] from four 16×16 partial products of the signed
/// high halves and unsigned low halves (`a = a_h·2¹⁶ + a_l`, `a_h = a >> 16`
/// arithmetic, `a_l ∈ [0, 2¹⁶)`):
/// `a·b = a_h b_h·2³² + (a_h b_l + a_l b_h)·2¹⁶ + a_l b_l`, where `|a_h b_h| ≤ 2³⁰`, each middle product is in
/// `(−2³¹, 2³¹)` and `a_l b_l < 2³²`, so every partial product is exact in
/// 32 bits; each middle product enters the low word shifted up (with its
/// carry) and the high word shifted down arithmetically. No sign fix-up
/// (the Armv6-M path; built on every target so the host tests check it).
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn signed_wide_mul_split(a: i32, b: i32) -> (i32, u32) {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let ll = (al as u32).wrapping_mul(bl as u32);
    let m1 = ah * bl;
    let m2 = al * bh;
    let (lo, c1) = ll.overflowing_add((m1 as u32) << 16);
    let (lo, c2) = lo.overflowing_add((m2 as u32) << 16);
    let hi = (ah * bh) + (m1 >> 16) + (m2 >> 16) + c1 as i32 + c2 as i32;
    (hi, lo)
}

/// `sat(⌊(V + round) / 2^sh⌋)` for `V = hi·2³² + lo` with `|hi| ≤ 2³⁰`,
/// `sh = rs + 1 ∈ [1, 32]` and `round = 2^rs` (the rounding constant
/// `2^(sh−1)`; every caller passes it). After the carry of `lo + round` into
/// `hi`, the shifted value fits `i32` exactly when `hi >> (sh − 1)`
/// (arithmetic) is `0` or `−1`;
/// otherwise it saturates with the sign of `hi`. `lo >> sh` and
/// `hi << (32 − sh)` are written with `rs` so that `sh = 32` needs no
/// special case.
#[inline(always)]
#[cfg_attr(armv6m, allow(dead_code))]
pub(crate) fn round_shift_sat(hi: i32, lo: u32, round: u32, rs: u32) -> i32 {
    let (lo, carry) = lo.overflowing_add(round);
    let hi = hi + carry as i32;
    // `hi >> rs ∈ {−1, 0}` ⟺ `hi + 2^rs ∈ [0, 2^(rs+1))` ⟺ `⌊((hi + round)
    // mod 2³²) / 2⌋ < round` (`round = 2^rs`; for `rs = 31` always true,
    // as it must be): no shift by the variable amount in the test.
    if ((hi as u32).wrapping_add(round) >> 1) >= round {
        return if hi < 0 { i32::MIN } else { i32::MAX };
    }
    (hi << (31 - rs)) | ((lo >> rs) >> 1) as i32
}

/// `V + r` for the signed product `V = x·m` as `(high word, low word)`,
/// from 16-bit halves with *signed* low parts: `x = x_h·2¹⁶ + x_l` and
/// `m = m_h·2¹⁶ + m_l` with `x_l = x as i16`, `x_h = (x − x_l)/2¹⁶`
/// (so `x_l, m_l ∈ [−2¹⁵, 2¹⁵)`, `x_h, m_h ∈ [−2¹⁵, 2¹⁵]`); the
/// coefficient's halves are prepared (`m_h = (m + 2¹⁵) >> 16`,
/// `m_l = m as i16`).
///
/// `V = x_h m_h·2³² + M·2¹⁶ + x_l m_l` with `M = x_h m_l + x_l m_h`: each
/// middle product is at most `2³⁰` in magnitude, and both reach `±2³⁰`
/// only for operands outside the `i32` range, so `M ∈ [−2³¹, 2³¹)` is
/// exact in an `i32` (one multiply-add instead of two carried ones), and
/// `|x_l m_l| ≤ 2³⁰`. The low word is `x_l m_l + M·2¹⁶` (one carry into the
/// high word, which also takes the sign of `x_l m_l`), then `+ r` (one more
/// carry): on Armv6-M two `ADDS`/`ADCS` pairs. Requires `|m| < 2³¹` and
/// `r < 2³²` (then `|V + r| < 2⁶³`).
#[inline(always)]
#[cfg(any(test, armv6m))]
pub(crate) fn signed_wide_mul_add_split(x: i32, mh: i32, ml: i32, r: u32) -> (i32, u32) {
    let xl = x as i16 as i32;
    // (x − x_l)/2¹⁶ = ⌊(x + 2¹⁵)/2¹⁶⌋, without the overflow of either sum.
    let xh = ((x >> 15) + 1) >> 1;
    let mid = xh * ml + xl * mh;
    let ll = xl * ml;
    let (lo, c1) = (ll as u32).overflowing_add((mid as u32) << 16);
    let hi = xh * mh + (ll >> 31) + (mid >> 16) + c1 as i32;
    let (lo, c2) = lo.overflowing_add(r);
    (hi + c2 as i32, lo)
}

/// [`round_shift_sat`] of a value whose rounding constant `round = 2^rs`
/// is already added: `sat(⌊W / 2^(rs+1)⌋)` for `W = hi·2³² + lo`,
/// `|hi| ≤ 2³⁰ + 1`, `rs ≤ 31`.
#[inline(always)]
#[cfg(any(test, armv6m))]
pub(crate) fn shift_sat(hi: i32, lo: u32, round: u32, rs: u32) -> i32 {
    if ((hi as u32).wrapping_add(round) >> 1) >= round {
        return if hi < 0 { i32::MIN } else { i32::MAX };
    }
    (hi << (31 - rs)) | ((lo >> rs) >> 1) as i32
}

/// [`mul_bits`] for `b ∈ [−2¹⁵, 2¹⁵)`, in 32-bit words. With
/// `a = h·2¹⁶ + l` (`h = a >> 16` signed, `l ∈ [0, 2¹⁶)`):
/// `⌊(a·b + 2¹⁵)/2¹⁶⌋ = h·b + ⌊(l·b + 2¹⁵)/2¹⁶⌋`, because `h·b·2¹⁶` is a
/// multiple of 2¹⁶. `|h·b| ≤ 2³⁰` and `l·b + 2¹⁵ ∈ (−2³¹, 2³¹)`, so nothing
/// overflows, and `|a·b|/2¹⁶ ≤ 2³⁰` never saturates.
#[inline(always)]
fn mul_bits_short(a: i32, b: i32) -> i32 {
    let (h, l) = (a >> 16, a & 0xFFFF);
    h * b + ((l * b + (1 << 15)) >> 16)
}

/// [`mul_bits`] for `u ∈ [−2¹⁶, 2¹⁶]` (a factor of magnitude at most 1;
/// `u` is clamped to that range), from one [`mul_bits_short`]-style product
/// by `t ≤ 2¹⁵`. With `x·u = x·2¹⁶ − x·t` (`t = 2¹⁶ − u`, `u ≥ 2¹⁵`):
/// `⌊(x·u + 2¹⁵)/2¹⁶⌋ = x − ⌊(x·t + 2¹⁵ − 1)/2¹⁶⌋`; with `x·u = −x·2¹⁶ +
/// x·t` (`t = 2¹⁶ + u`, `u < −2¹⁵`): `−x + ⌊(x·t + 2¹⁵)/2¹⁶⌋`. `|x·u| ≤
/// |x|`, so only `x = MIN, u = −2¹⁶` leaves the range (saturated); every
/// other sum is exact in wrapping 32-bit arithmetic.
#[inline(always)]
pub(crate) fn mul_bits_unit(a: i32, u: i32) -> i32 {
    // The clamp of `u` is `t ≥ 0` in the two outer cases.
    if u >= 1 << 15 {
        let t = ((1 << 16) - u).max(0);
        a.wrapping_sub(mul_bits_short_with(a, t, (1 << 15) - 1))
    } else if u >= -(1 << 15) {
        mul_bits_short(a, u)
    } else {
        let t = ((1 << 16) + u).max(0);
        if a == i32::MIN && t == 0 {
            i32::MAX
        } else {
            a.wrapping_neg()
                .wrapping_add(mul_bits_short_with(a, t, 1 << 15))
        }
    }
}

/// `⌊(a·b + c)/2¹⁶⌋` for `b ∈ [0, 2¹⁵]` and `c < 2¹⁶`, as in
/// [`mul_bits_short`] (`l·b + c < 2³¹`).
#[inline(always)]
fn mul_bits_short_with(a: i32, b: i32, c: i32) -> i32 {
    let (h, l) = (a >> 16, a & 0xFFFF);
    h * b + ((l * b + c) >> 16)
}

/// The straightforward 64-bit form of [`mul_bits`], the reference of its
/// tests.
#[cfg(test)]
pub(crate) const fn mul_bits_reference(a: i32, b: i32) -> i32 {
    sat_i64(((a as i64) * (b as i64) + (1 << 15)) >> 16)
}

/// The 64-bit product `a·b` as `(high, low)` words.
///
/// On Armv6-M (no `umull`; recognised by its missing 32-bit atomics, since
/// stable Rust exposes no Thumb-2 feature flag) it is formed from four
/// 16×16 partial products
/// and two add-with-carry steps ([`wide_mul_split`]); elsewhere the native
/// widening multiply. Both are exact.
#[inline(always)]
pub(crate) fn wide_mul(a: u32, b: u32) -> (u32, u32) {
    #[cfg(armv6m)]
    {
        wide_mul_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        let p = a as u64 * b as u64;
        ((p >> 32) as u32, p as u32)
    }
}

/// [`wide_mul`] from four 16×16 partial products (the Armv6-M path; built
/// on every target so the host tests check it).
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn wide_mul_split(a: u32, b: u32) -> (u32, u32) {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let ll = al * bl;
    let hh = ah * bh;
    // a·b = hh·2³² + (lh + hl)·2¹⁶ + ll. The middle sum may carry out of
    // 32 bits (a carry worth 2⁴⁸ = 2¹⁶ in the high word), and its low half
    // shifted up may carry out of the low word: two add-with-carry steps
    // instead of masking each partial product. LLVM does not recognize
    // this form as a widening multiply, so no optimization barrier is
    // needed to keep it off `__aeabi_lmul` (a masked form needs one,
    // `core::hint::black_box`, which costs a stack store and load per
    // product); the embedded counter shows it if that ever changes.
    let (mid, c1) = (al * bh).overflowing_add(ah * bl);
    let (lo, c2) = ll.overflowing_add(mid << 16);
    let hi = hh + (mid >> 16) + ((c1 as u32) << 16) + c2 as u32;
    (hi, lo)
}

/// `sat(⌊(s·a·b + 2^(sh−1)) / 2^sh⌋)` for `sh > 0` (rounded to nearest,
/// ties up) and `sat(s·a·b · 2^−sh)` for `sh ≤ 0`, with `s = −1` when `neg`,
/// for magnitudes `a, b ≤ 2³¹` (so `a·b ≤ 2⁶²`). Saturates to the `i32`
/// range. Uses only 32-bit operations and shifts by amounts below 32.
///
/// For the sign-magnitude form: with `P = a·b` and `h = 2^(sh−1)`,
/// `⌊(−P + h)/2^sh⌋ = −⌈(P − h)/2^sh⌉ = −⌊(P + h − 1)/2^sh⌋` (because
/// `2^sh − h = h`), so a negative product rounds its magnitude with
/// `h − 1` instead of `h`. `P + h < 2⁶³` for every `sh < 63`.
#[inline(always)]
pub(crate) fn scaled_product(neg: bool, a: u32, b: u32, sh: i32) -> i32 {
    let (hi, lo) = wide_mul(a, b);
    scaled_magnitude(neg, hi, lo, sh)
}

/// [`scaled_product`] of a magnitude given as two words:
/// `sat(⌊(s·P + 2^(sh−1)) / 2^sh⌋)` for `sh > 0` (`sh ≥ 63`: 0) and
/// `sat(s·P·2^−sh)` for `sh ≤ 0`, `P = hi·2³² + lo`, `s = −1` when `neg`.
/// Exact for `P < 2⁶³` and `sh ≤ 62` (then `P + 2^(sh−1) < 2⁶⁴`; the
/// shortcut for `sh ≥ 63` assumes `P ≤ 2⁶²`).
#[inline(always)]
pub(crate) fn scaled_magnitude(neg: bool, hi: u32, lo: u32, sh: i32) -> i32 {
    let mag: u32; // the magnitude, or > 2³¹ when it saturates
    if sh > 0 {
        if sh >= 63 {
            return 0;
        }
        // (hi, lo) += h or h − 1.
        let (hi, lo) = if sh <= 32 {
            let h = 1u32 << (sh - 1);
            let add = if neg { h - 1 } else { h };
            let (l, c) = lo.overflowing_add(add);
            (hi + c as u32, l)
        } else {
            let h = 1u32 << (sh - 33);
            if neg {
                // h − 1 = (h − 1)·2³² + (2³² − 1): add h to the high
                // word after adding 2³² − 1 = −1 (mod 2³²) to the low one.
                let (l, c) = lo.overflowing_add(u32::MAX);
                (hi + (h - 1) + c as u32, l)
            } else {
                (hi + h, lo)
            }
        };
        if sh >= 32 {
            mag = hi >> (sh - 32);
        } else if hi >> sh != 0 {
            mag = u32::MAX;
        } else {
            mag = (lo >> sh) | (hi << (32 - sh));
        }
    } else {
        let s = -sh;
        if hi == 0 && lo == 0 {
            return 0;
        }
        if hi != 0 || s >= 32 || (s > 0 && lo >> (32 - s) != 0) {
            mag = u32::MAX;
        } else {
            mag = lo << s;
        }
    }
    if neg {
        if mag >= 1 << 31 {
            i32::MIN
        } else {
            (mag as i32).wrapping_neg()
        }
    } else if mag > i32::MAX as u32 {
        i32::MAX
    } else {
        mag as i32
    }
}

/// Rounded (to nearest, ties away from zero), saturating Q16.16 quotient of
/// two raw bit patterns; `x/0` saturates with the sign of `x`, `0/0 = 0`.
///
/// Equal to the 64-bit formula [`div_bits_reference`] for every pair of
/// operands (checked at random and over edge classes in the tests below),
/// without its 64-bit division (on Armv6-M a call of `__aeabi_ldivmod`,
/// thousands of instructions): on the magnitudes `A = |a|`, `B = |b|`,
///
/// 1. `A ≥ B·2¹⁵` (`⌊A/2¹⁵⌋ ≥ B`, which includes `B = 0`): the quotient
///    `A·2¹⁶/B` is at least `2³¹`, so the result saturates (to 0 for
///    `A = 0`, which with `B = 0` is `0/0`);
/// 2. otherwise `Q = ⌊A·2¹⁶/B⌋ < 2³¹` by the exact normalized reciprocal
///    division of the kernels (`div_norm_steps`, loop-free: a table seed,
///    one Newton step, one correction): the divisor is shifted to
///    `D = B·2ˢ ∈ [2³¹, 2³²)` and the 48-bit dividend by the same `s` into
///    two words `u₁·2³² + u₀` with `u₁ < D` (because `Q < 2³¹`);
/// 3. the remainder `R = A·2¹⁶ − Q·B < B ≤ 2³¹` is exact in wrapping 32-bit
///    arithmetic, and `Q + 1` when `2R ≥ B` (`R ≥ B − R`) is the rounding,
///    applied to the magnitude, so ties go away from zero;
/// 4. the sign, then saturation (`Q + 1 ≤ 2³¹`: only `+2³¹` saturates).
#[inline(always)]
pub(crate) fn div_bits(a: i32, b: i32) -> i32 {
    let neg = (a < 0) != (b < 0);
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    if ua >> 15 >= ub {
        return if ua == 0 {
            0
        } else if neg {
            i32::MIN
        } else {
            i32::MAX
        };
    }
    let q = div_magnitude(ua, ub);
    if neg {
        // q ≤ 2³¹: 2³¹ reads as i32::MIN, whose negation wraps to itself.
        (q as i32).wrapping_neg()
    } else if q > i32::MAX as u32 {
        i32::MAX
    } else {
        q as i32
    }
}

/// Steps 2–3 of [`div_bits`]: the rounded magnitude quotient
/// `⌊A·2¹⁶/B⌉` (ties up) for `1 ≤ B ≤ 2³¹` and `A < B·2¹⁵`, below or at
/// `2³¹`.
#[inline(always)]
pub(crate) fn div_magnitude(ua: u32, ub: u32) -> u32 {
    let s = kernels::i16f16::leading_zeros_32(ub);
    let (u1, u0) = if s < 16 {
        (ua >> (16 - s), ua << (16 + s))
    } else {
        (ua << (s - 16), 0)
    };
    let q = kernels::i16f16::div_norm_steps(u1, u0, ub << s).0;
    let r = (ua << 16).wrapping_sub(q.wrapping_mul(ub));
    q + (r >= ub - r) as u32
}

/// [`div_bits`] for a ratio `|a| ≤ |b|` (the quotient in `[−1, 1]`, i.e.
/// `[−2¹⁶, 2¹⁶]` bits): the same value for every such pair, with its range
/// and sign by construction rather than by the division's exactness:
/// `0` for `a = 0`, `±2¹⁶` for `|a| ≥ |b|` (so outside the precondition the
/// quotient is clamped to `[−1, 1]`), otherwise the magnitude quotient
/// capped at `2¹⁶` and signed. The cap never acts on a pair of the
/// precondition (`div_magnitude` is exact, so `A < B` gives at most
/// `2¹⁶`); it is what makes the range a property of the code's structure,
/// which the Kani harness `kani_div_unit_range_contract` checks for any
/// magnitude quotient.
#[inline]
pub(crate) fn div_bits_unit(a: i32, b: i32) -> i32 {
    const ONE: u32 = 1 << 16;
    let neg = (a < 0) != (b < 0);
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let q = if ua == 0 {
        0
    } else if ua >= ub {
        ONE
    } else {
        // 1 ≤ A < B ≤ 2³¹: within `div_magnitude`'s precondition.
        div_magnitude(ua, ub).min(ONE)
    };
    // q ≤ 2¹⁶: the negation is exact.
    if neg {
        -(q as i32)
    } else {
        q as i32
    }
}

/// [`div_bits`] by its definition in 64-bit arithmetic (the reference of
/// the tests).
#[cfg(test)]
pub(crate) const fn div_bits_reference(a: i32, b: i32) -> i32 {
    if b == 0 {
        return if a > 0 {
            i32::MAX
        } else if a < 0 {
            i32::MIN
        } else {
            0
        };
    }
    let n = (a as i64) << 16;
    let d = b as i64;
    let mut q = n / d;
    let r = n % d;
    if 2 * r.unsigned_abs() >= d.unsigned_abs() {
        q += if (n < 0) == (d < 0) { 1 } else { -1 };
    }
    sat_i64(q)
}

impl Scalar for I16F16 {
    const NAME: &'static str = "I16F16";
    const ZERO: Self = I16F16::ZERO;
    const ONE: Self = I16F16::ONE;
    const MIN: Self = I16F16::MIN;
    const MAX: Self = I16F16::MAX;
    const RESOLUTION: Self = I16F16::DELTA;
    const PI: Self = I16F16::PI;
    const FRAC_PI_2: Self = I16F16::FRAC_PI_2;
    const UNITS: super::units::Units = super::units::FIXED;

    /// No NaN or infinity in fixed point.
    #[inline(always)]
    fn all_finite<const N: usize>(_: &[Self; N]) -> bool {
        true
    }

    #[inline]
    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            I16F16::ZERO
        } else {
            // Rounds to nearest (ties to even) and saturates.
            I16F16::saturating_from_num(x)
        }
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.to_bits() as f64 / 65536.0
    }
    #[inline]
    fn from_i32(x: i32) -> Self {
        I16F16::from_bits(sat_i64((x as i64) << 16))
    }
    #[inline(always)]
    fn from_counts(counts: i64, scale: &super::Coef) -> Self {
        I16F16::from_bits(scale.scale_int(counts, 16))
    }
    #[inline(always)]
    fn mul_coef(self, c: &super::Coef) -> Self {
        I16F16::from_bits(c.scale_i32(self.to_bits()))
    }
    #[inline(always)]
    fn dot_coef<const N: usize>(x: &[Self; N], row: &super::CoefRow<N>) -> Self {
        // x = xh·2¹⁶ + xl and M = h·2¹⁶ + l (|xh| ≤ 2¹⁵, |h| ≤ 2¹², xl, l <
        // 2¹⁶): x·M = xh·h·2³² + (xh·l + xl·h)·2¹⁶ + xl·l, each partial
        // product a 32-bit multiply. Over N ≤ 6 terms: |Σ xh·h| ≤ 1.5·2²⁹
        // and |Σ xl·h| < 1.5·2³⁰ (i32), |Σ xh·l| < 6·2³¹ (i64),
        // Σ xl·l < 6·2³² (u64); the total is below 2⁶³.
        let mut hh = 0i32;
        let mut hl = 0i64;
        let mut lh = 0i32;
        let mut ll = 0u64;
        for (x, &(h, l)) in x.iter().zip(row.split().iter()) {
            let b = x.to_bits();
            let (xh, xl) = (b >> 16, b & 0xFFFF);
            hh += xh * h;
            hl += (xh * l) as i64;
            lh += xl * h;
            ll += (xl as u32 * l as u32) as u64;
        }
        let acc = ((hh as i64) << 32) + ((hl + lh as i64) << 16) + ll as i64;
        let p = acc.unsigned_abs();
        I16F16::from_bits(scaled_magnitude(
            acc < 0,
            (p >> 32) as u32,
            p as u32,
            row.fixed().1,
        ))
    }
    type Residual = i32;
    #[inline(always)]
    fn integrate(self, residual: i32, x: Self, c: &super::Coef, lo: Self, hi: Self) -> (Self, i32) {
        // The Q16.48 sum `self·2³² + residual + step`, exactly: the low
        // words with their carry, the high words (and the residual's
        // sign) in i64, so nothing saturates but the step itself.
        let step = c.scale_wide(x.to_bits(), 32);
        let (low, carry) = (residual as u32).overflowing_add(step as u32);
        let high = self.to_bits() as i64 + (step >> 32) + (residual >> 31) as i64 + carry as i64;
        // Outside the box exactly when the sum is above `hi·2³²` or below
        // `lo·2³²`: the end, residual 0.
        let (h, l) = (hi.to_bits() as i64, lo.to_bits() as i64);
        // Above `hi·2³²` exactly when `high > h`, or `high = h` with a
        // non-zero low word: `high − h − [low = 0] ≥ 0` (one comparison of
        // the 64-bit high words instead of two).
        if high - h - (low == 0) as i64 >= 0 {
            (hi, 0)
        } else if high < l {
            (lo, 0)
        } else {
            // Round to nearest (ties up): the high word, plus one when the
            // low word is at least ½ LSB (then `high < h`, so it fits); the
            // residual is the low word read as signed (`low − 2³²` in the
            // second case).
            let v = high as i32 + (low >> 31) as i32;
            (I16F16::from_bits(v), low as i32)
        }
    }
    #[inline]
    fn add(self, rhs: Self) -> Self {
        self.saturating_add(rhs)
    }
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self.saturating_sub(rhs)
    }
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        I16F16::from_bits(mul_bits(self.to_bits(), rhs.to_bits()))
    }
    #[inline]
    fn mul_int(self, n: &super::IntFactor) -> Self {
        // Equal to `mul_coef(&n.coef)` for an integer `n < 2³¹` (its
        // coefficient is exact and the product rounds nothing); `new`
        // rounds any other value, which the callers' validation excludes.
        // `low ≤ x ≤ high` as one unsigned compare (`low ≤ 0 ≤ high`);
        // outside it the product saturates to the side of `x`'s sign.
        let x = self.to_bits();
        I16F16::from_bits(
            if (x.wrapping_sub(n.low) as u32) <= n.high.wrapping_sub(n.low) as u32 {
                x.wrapping_mul(n.n)
            } else {
                i32::MAX ^ (x >> 31)
            },
        )
    }
    #[inline]
    fn mul_unit_range(self, u: Self) -> Self {
        I16F16::from_bits(mul_bits_unit(self.to_bits(), u.to_bits()))
    }
    #[inline(always)]
    fn dot_direction_positive(self, u: Self, c: Self, v: Self) -> bool {
        // Products of 2⁻³² units over 4: |self|, |c| ≤ 2¹⁶ and |u >> 2|,
        // |v >> 2| ≤ 2¹⁴, so each is within 2³⁰ and, by Cauchy–Schwarz
        // (|self·u + c·v| ≤ √2·√(u² + v²)), their sum within 1.52·2³⁰ <
        // 2³¹. Flooring `u`, `v` errs by less than 4 units each: at most
        // 3·(|self| + |c|) in the sum, i.e. 3·2⁻¹⁶(|self| + |c|).
        let p = self.to_bits().wrapping_mul(u.to_bits() >> 2);
        let q = c.to_bits().wrapping_mul(v.to_bits() >> 2);
        p.wrapping_add(q) > 0
    }
    #[inline(always)]
    fn div(self, rhs: Self) -> Self {
        I16F16::from_bits(div_bits(self.to_bits(), rhs.to_bits()))
    }
    #[inline]
    fn neg(self) -> Self {
        self.saturating_neg()
    }
    #[inline]
    fn abs(self) -> Self {
        self.saturating_abs()
    }
    #[inline]
    fn atan(self) -> Self {
        kernels::i16f16::atan(self)
    }
    #[inline]
    fn tan(self) -> Self {
        kernels::i16f16::tan(self)
    }
    #[inline]
    fn exp(self) -> Self {
        kernels::i16f16::exp(self)
    }
    #[inline]
    fn exp_neg_abs(self) -> Self {
        kernels::i16f16::exp_neg_abs(self)
    }
    #[inline]
    fn sin(self) -> Self {
        kernels::i16f16::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        kernels::i16f16::cos(self)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        kernels::i16f16::sin_cos(self)
    }
    #[inline]
    fn cos_turn(turn: u32) -> Self {
        kernels::i16f16::cos_turn(turn)
    }
    #[inline]
    fn to_turn(self) -> u32 {
        kernels::i16f16::turn_of_radians(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        kernels::i16f16::atan2(self, x)
    }
    #[inline]
    fn acos(self) -> Self {
        kernels::i16f16::acos(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        kernels::i16f16::sqrt(self)
    }
    #[inline]
    fn unit_vector(self, b: Self) -> Option<(Self, Self)> {
        kernels::i16f16::unit_vector(self, b)
    }
}

impl super::sealed::Sealed for I16F16 {
    const FLOAT: bool = false;

    #[inline(always)]
    fn mul_whole(self, n: i32) -> Self {
        // `|n·bits| ≤ i32::MAX` by the precondition: the exact product.
        I16F16::from_bits(self.to_bits().wrapping_mul(n))
    }

    #[inline(always)]
    fn from_counts_i32(counts: i32, scale: &super::CountCoef) -> Self {
        // `scale_i32(x)` equals `scale_int(x, 0)` for every coefficient
        // and `i32`, and the factor moved up 16 bits with the same
        // mantissa makes that `scale_int(x, 16)` of the factor: the value
        // of `from_counts`.
        I16F16::from_bits(scale.bits().scale_i32(counts))
    }
    #[inline]
    fn hypot_unit(self, b: Self) -> Self {
        kernels::i16f16::hypot_unit(self, b)
    }
    #[inline]
    fn rsqrt_quarter(self) -> Self {
        kernels::i16f16::rsqrt_quarter(self)
    }
    #[inline]
    fn atan_small(self) -> Self {
        kernels::i16f16::atan_small(self)
    }
    #[inline]
    fn sqrt_small(self) -> Self {
        kernels::i16f16::sqrt_small(self)
    }
    #[inline(always)]
    fn from_counts_prepared(counts: i64, scale: &super::CountCoef) -> Self {
        // `from_counts` clamps the count to [−2³¹, 2³¹]: below 2³¹ the
        // clamped count fits `i32`; above, the clamp's value is prepared.
        if counts > i32::MAX as i64 {
            I16F16::from_bits(scale.top())
        } else {
            Self::from_counts_i32(counts.max(i32::MIN as i64) as i32, scale)
        }
    }
    #[inline]
    fn div_unit_range(self, rhs: Self) -> Self {
        I16F16::from_bits(div_bits_unit(self.to_bits(), rhs.to_bits()))
    }
    #[inline]
    fn tan_bounded(self) -> Self {
        kernels::i16f16::tan_bounded(self)
    }
}

#[cfg(test)]
mod tests;
