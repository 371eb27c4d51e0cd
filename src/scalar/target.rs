//! What differs per core, in one place.
//!
//! Armv6-M (the `armv6m` configuration, set by the build script) has no
//! divide instruction, no 32×32 → 64 multiply (`/` and 64-bit `*` are
//! library loops there) and eight low registers. The helpers below give
//! the same value on every target; only the instructions differ.

/// The core divides in hardware (every target but Armv6-M, whose `/` is a
/// library loop).
pub(crate) const HAS_DIVIDE: bool = cfg!(not(armv6m));

/// `a·b` exactly, for `0 ≤ b < 2⁴⁸` (callers: products below 2⁶³; a
/// larger product wraps, the value modulo 2⁶⁴ on every target). On
/// Armv6-M the split form [`mul_wide_split`] (no `__aeabi_lmul`, no
/// branch); elsewhere the plain product.
#[inline(always)]
pub(crate) fn mul_wide(a: u32, b: i64) -> i64 {
    // Cores with a long multiply (`umull`, x86) take the plain product.
    if cfg!(not(armv6m)) {
        return (a as i64).wrapping_mul(b);
    }
    mul_wide_split(a, b)
}

/// [`mul_wide`] from one 32×32 → 64 product ([`crate::scalar::fixed`]'s
/// split form on Armv6-M) of the low word of `b` and one 32-bit product
/// of its high word: `a·b = a·b_lo + a·b_hi·2³²`, and `a·b < 2⁶³` makes
/// `a·b_hi < 2³¹`, so that product and the high-word sum are exact in 32
/// bits. Built on every target so the host tests check it.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_wide_split(a: u32, b: i64) -> i64 {
    let (hi, lo) = crate::scalar::fixed::wide_mul(a, b as u32);
    let hi = hi.wrapping_add(a.wrapping_mul((b >> 32) as u32));
    ((hi as u64) << 32 | lo as u64) as i64
}

/// `a·b` modulo 2⁶⁴ for every `a` and `b` (the wrapping `i64`
/// product of a sign-extended `a`). On Armv6-M one unsigned 32×32 → 64
/// product of the low words ([`crate::scalar::fixed`]'s split form) and
/// two corrections of its high word ([`mul_wide_signed_split`]);
/// elsewhere the plain product.
#[inline(always)]
pub(crate) fn mul_wide_signed(a: i32, b: i64) -> i64 {
    if cfg!(not(armv6m)) {
        return (a as i64).wrapping_mul(b);
    }
    mul_wide_signed_split(a, b)
}

/// [`mul_wide_signed`] without a sign test: with `a_u = a mod 2³²`,
/// `a = a_u − 2³²·[a < 0]`, and with `b = b_h·2³² + b_l`,
/// `a·b ≡ a_u·b_l + 2³²·(a_u·b_h − [a < 0]·b_l)` modulo 2⁶⁴ (the other
/// terms are multiples of 2⁶⁴). The high word takes `a_u·b_h` and
/// `b_l & (a >> 31)` (all ones when `a < 0`), both modulo 2³². Built on
/// every target so the host tests check it.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_wide_signed_split(a: i32, b: i64) -> i64 {
    let (au, bl) = (a as u32, b as u32);
    let (hi, lo) = crate::scalar::fixed::wide_mul(au, bl);
    let hi = hi
        .wrapping_add(au.wrapping_mul((b >> 32) as u32))
        .wrapping_sub(bl & (a >> 31) as u32);
    ((hi as u64) << 32 | lo as u64) as i64
}

/// `a·b + c` exactly, for `a·b + c < bound ≤ 2⁶³` and `b < 2⁴⁸`. On
/// Armv6-M (no long multiply) with `bound ≤ 2³²` one 32-bit multiply,
/// which cannot wrap; otherwise [`mul_wide`].
#[inline(always)]
pub(crate) fn mul_add_below(a: u32, b: u32, c: u32, bound: i64) -> i64 {
    if cfg!(armv6m) && bound >> 32 == 0 {
        a.wrapping_mul(b).wrapping_add(c) as i64
    } else {
        mul_wide(a, b as i64) + c as i64
    }
}

/// A function compiled as a function of its own on Armv6-M and inlined
/// elsewhere: `own_function_on_armv6m! { fn ... }` (attributes and doc
/// comments inside). A large step inlined whole on a core with eight low
/// registers spills the addresses of many prepared fields; a part of it
/// called as a function starts from a fresh register allocation. On cores
/// with more registers the call and its argument passing are the larger
/// cost.
macro_rules! own_function_on_armv6m {
    ($(#[$m:meta])* $v:vis fn $($t:tt)*) => {
        $(#[$m])*
        #[cfg_attr(armv6m, inline(never))]
        #[cfg_attr(not(armv6m), inline(always))]
        $v fn $($t)*
    };
}
pub(crate) use own_function_on_armv6m;

/// A function always inlined except on Armv6-M, where the compiler
/// decides: `inlined_except_on_armv6m! { fn ... }`. On the Cortex-M4F the
/// joint step is then one function, without call and argument-struct
/// overhead; on Armv6-M forcing it whole spills more than the calls cost.
macro_rules! inlined_except_on_armv6m {
    ($(#[$m:meta])* $v:vis fn $($t:tt)*) => {
        $(#[$m])*
        #[cfg_attr(not(armv6m), inline(always))]
        #[cfg_attr(armv6m, inline)]
        $v fn $($t)*
    };
}
pub(crate) use inlined_except_on_armv6m;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The reference: the product in 128 bits, reduced modulo 2⁶⁴.
    fn reference(a: i32, b: i64) -> i64 {
        (a as i128 * b as i128) as i64
    }

    /// The edges: both signs, zero, the extreme turns and the extreme
    /// `M·N` (2³² validated) and words with every high bit set.
    #[test]
    fn mul_wide_signed_edges() {
        let aa = [
            0,
            1,
            -1,
            2,
            -2,
            7,
            -7,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            0x1_0000,
            -0x1_0000,
        ];
        let bb = [
            0,
            1,
            2,
            200_000,
            (1 << 32) - 1,
            1 << 32,
            (1 << 33) + 5,
            0xFFFF_FFFF_FFFF,
            i64::MAX,
            i64::MIN,
            -1,
            -(1 << 32),
        ];
        for a in aa {
            for b in bb {
                assert_eq!(mul_wide_signed_split(a, b), reference(a, b), "{a} {b}");
                assert_eq!(mul_wide_signed(a, b), reference(a, b), "{a} {b}");
            }
        }
    }

    proptest! {
        /// Both forms are the product modulo 2⁶⁴ for every `a` and `b`,
        /// and exact for the frame origins (`|turns| ≤ 2³¹`, `M·N ≤ 2³²`).
        #[test]
        fn mul_wide_signed_is_the_wrapping_product(a in any::<i32>(), b in any::<i64>(), mn in 1i64..=1 << 32) {
            prop_assert_eq!(mul_wide_signed_split(a, b), reference(a, b));
            prop_assert_eq!(mul_wide_signed(a, b), reference(a, b));
            prop_assert_eq!(mul_wide_signed_split(a, mn) as i128, a as i128 * mn as i128);
        }
    }
}
